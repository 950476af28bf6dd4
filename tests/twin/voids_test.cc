// Voids: a known cavity, and the junction voids of double-bead X junctions against 003 Appendix A1.
#include "tests/twin/twin_settings.h"
#include "models/core/numbers.h"
#include "twin/scanner/voids.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/error.h"
#include "tests/twin/test_paths.h"
#include "twin/deposition/bead_deposition.h"

namespace waam::twin {
namespace {

using ::testing::HasSubstr;

// A 10^3 cube of metal with a 2^3 cavity inside: one void of 8 voxels; with the metal above it removed, a valley.
TEST(Voids, FindsAKnownCavityAndTellsItFromAValley) {
  VoxelGrid grid(1.0, 100000);
  TargetVolume target(1.0, VoxelIndex(0, 0, 0), VoxelIndex(9, 9, 9));
  for (int k = 0; k < 10; ++k) {
    for (int j = 0; j < 10; ++j) {
      for (int i = 0; i < 10; ++i) {
        target.SetInside(VoxelIndex(i, j, k), true);
        const bool cavity = i >= 4 && i < 6 && j >= 4 && j < 6 && k >= 3 && k < 5;
        if (!cavity) grid.Set(VoxelIndex(i, j, k), VoxelData{});
      }
    }
  }
  VoidReport report = FindVoids(grid, target);
  ASSERT_EQ(report.voids.size(), 1u) << "expected the one enclosed cavity";
  EXPECT_EQ(report.voids[0].voxels, 8u);
  EXPECT_NEAR(report.void_volume_mm3, 8.0, 1e-9);
  EXPECT_TRUE(report.valleys.empty());
  const VoidReport filtered = FindVoids(grid, target, 8.5);  // a 2^3 mm cavity is below 8.5 mm3
  EXPECT_TRUE(filtered.voids.empty()) << "a region below the minimum volume is not listed";
  EXPECT_EQ(filtered.small_regions, 1u);
  EXPECT_NEAR(filtered.small_volume_mm3, 8.0, 1e-9);
  EXPECT_EQ(FindVoids(grid, target, 8.0).voids.size(), 1u) << "a region of exactly the minimum volume is kept";
  const std::vector<EmptyRegion> cut = SectionVoids(grid, target, 3.5);
  ASSERT_EQ(cut.size(), 1u) << "a cut through the cavity shows one hole";
  EXPECT_EQ(cut[0].voxels, 4u);
  EXPECT_NEAR(cut[0].length_mm, 2.0, 1e-9);
  EXPECT_TRUE(SectionVoids(grid, target, 7.5).empty()) << "a cut above the cavity shows none";

  VoxelGrid open(1.0, 100000);
  grid.ForEach([&](const VoxelIndex& v, const VoxelData& d) {
    if (!(v.x() >= 4 && v.x() < 6 && v.y() >= 4 && v.y() < 6 && v.z() >= 5)) open.Set(v, d);
  });
  report = FindVoids(open, target);
  EXPECT_TRUE(report.voids.empty()) << "a pit open to the top is a valley, not a void";
  ASSERT_EQ(report.valleys.size(), 1u);
  EXPECT_EQ(report.valleys[0].voxels, 8u + 20u);
}

TEST(Voids, VoxelSizesMustAgree) {
  VoxelGrid grid(0.5, 10);
  TargetVolume target(1.0, VoxelIndex(0, 0, 0), VoxelIndex(1, 1, 1));
  try {
    FindVoids(grid, target);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("differs"));
  }
}

// Measured void lengths of the symmetric X junctions (two walls crossing, angles theta, 180 - theta): D1 and F1-F8.
std::map<int, double> MeasuredXJunctionVoids() {
  std::ifstream in(std::string(WAAM_SOURCE_DIR) + "/models/data/nguyen2022_appendixA1_junction_voids.csv");
  std::map<int, double> by_angle;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line[0] == 'n') continue;
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) f.push_back(cell);
    if (f.size() < 8) continue;
    const double t1 = std::stod(f[3]), t2 = std::stod(f[4]), t3 = std::stod(f[5]), t4 = std::stod(f[6]);
    // Alternating pairs (theta1 = theta3, theta2 = theta4) are two straight walls crossing.
    if (t4 > 0 && t1 == t3 && t2 == t4 && std::abs(t1 + t2 - 180.0) < 1e-9) by_angle[static_cast<int>(t2)] = std::stod(f[7]);
  }
  return by_angle;
}

// Largest length of the enclosed empty regions (voids or valleys) near the junction centre.
double JunctionVoidLength(double theta_deg) {
  const double w = 5.2;           // double-bead ribs 9 mm wide (003 sec. 4.5): w + l = 9 with l = 0.738 w
  const double l = 0.738 * w;
  const double h = 3.0 * kPi * 5200.0 * 1.0 / (8.0 * w * 400.0);  // eq. 3.4, Appendix A1 parameters
  const double dz = 2.0 / 3.0 * w * h / l;
  const planner::Plan plan = testing::CrossJunction(theta_deg * kPi / 180.0, 40.0, 5, w, h, l, dz, 400.0 / 60.0);
  twin::SimulationSettings s = twin::TestSimulationSettings();
  s.voxel_mm = 0.5;
  const Depositor d = DepositPlan(plan, s, 100.0, nullptr);
  EXPECT_NEAR(d.grid().OccupiedVolume(), d.expected_volume_mm3(), 0.02 * d.expected_volume_mm3());
  // Milled sections (003 sec. 4.4.2) through the middle of the body, from 30 % to 70 % of the height of the first
  // four layers: the longest enclosed region near the junction centre.
  const TargetVolume target = TargetVolume::FromLayers(plan, s.voxel_mm, s.max_voxels);
  // Near the junction: within 2 w beyond the reflex corners of the sharp gaps, which lie l / (2 sin(theta/2)) out.
  const double reach = l / (2.0 * std::sin(theta_deg * kPi / 360.0)) + 2.0 * w;
  double longest = 0.0;
  for (double f = 0.3; f <= 0.7 + 1e-9; f += 0.1) {
    for (const EmptyRegion& r : SectionVoids(d.grid(), target, f * 4.0 * dz)) {
      if (r.centroid_mm.head<2>().norm() < reach) longest = std::max(longest, r.length_mm);
    }
  }
  return longest;
}

TEST(Voids, XJunctionVoidGrowsAsTheAngleSharpens) {
  const std::map<int, double> measured = MeasuredXJunctionVoids();
  ASSERT_GE(measured.size(), 9u) << "expected the D1 and F1-F8 rows of Appendix A1";
  std::map<int, double> simulated;
  for (const auto& [theta, length] : measured) {
    simulated[theta] = JunctionVoidLength(theta);
    std::printf("X junction %d/%d deg, 5 layers: simulated void length %.1f mm, measured %.1f mm (Appendix A1)\n",
                theta, 180 - theta, simulated[theta], length);
  }
  // Pearson correlation of simulated and measured lengths over the nine junctions.
  double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
  for (const auto& [theta, length] : measured) {
    const double x = simulated[theta];
    sx += x, sy += length, sxx += x * x, syy += length * length, sxy += x * length;
  }
  const double m = static_cast<double>(measured.size());
  const double r = (sxy - sx * sy / m) / std::sqrt((sxx - sx * sx / m) * (syy - sy * sy / m));
  std::printf("X junctions: correlation of simulated and measured void length r = %.2f\n", r);
  EXPECT_GT(r, 0.7) << "the simulated void length must follow the measured trend";
  EXPECT_LT(simulated[90], simulated[45]) << "sharper junction, longer void";
  EXPECT_LT(simulated[45], simulated[30]);
  EXPECT_LT(simulated[30], simulated[18]);
}

}  // namespace
}  // namespace waam::twin
