// Tests of the distortion twin: FE invariants (linearity, symmetry, free shrinkage), heat-input scaling, the reduced
// mode's bending direction, and the Ceres fit recovering known parameters from a twin-generated scan.
#include "tests/twin/twin_settings.h"
#include "twin/distortion/distortion.h"

#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/error.h"
#include "models/core/parallel.h"
#include "tests/twin/test_plans.h"
#include "twin/compensation/compensation.h"
#include "twin/distortion/distortion_fit.h"


namespace waam::twin {
namespace {

using ::testing::HasSubstr;

// A straight wall along x, `layers` x 1.5 mm, one pass per layer; points with x > 0 welded at `hot_speed`.
planner::Plan StraightWall(int layers, double length, double speed, double hot_speed) {
  planner::Plan plan;
  for (int l = 0; l < layers; ++l) {
    planner::LayerPath layer;
    layer.index = l;
    layer.z_mm = 1.5 * (l + 1);
    for (int i = 0; i <= 8; ++i) {
      planner::PathPoint p;
      const double x = -0.5 * length + length * i / 8.0;
      p.p_P = Eigen::Vector3d(x, 0.0, layer.z_mm);
      p.bead_width_mm = 5.0;
      p.bead_height_mm = 1.5;
      p.speed_mm_s = x > 0.0 ? hot_speed : speed;
      p.weld = i > 0;
      layer.points.push_back(p);
    }
    plan.layers.push_back(layer);
  }
  return plan;
}

// A square tube of `layers` loops (30 x 20 mm, 1.5 mm apart) welded as one continuous spiral pass; the loops on the
// +x side are welded at `hot_speed` (the rest at 8 mm/s), so the tube bends towards +x.
planner::Plan SpiralTube(int layers, double hot_speed) {
  planner::Plan plan;
  const double corners[5][2] = {{-15, -10}, {15, -10}, {15, 10}, {-15, 10}, {-15, -10}};
  for (int l = 0; l < layers; ++l) {
    planner::LayerPath layer;
    layer.index = l;
    layer.z_mm = 1.5 * (l + 1);
    for (int k = 0; k < 5; ++k) {
      planner::PathPoint p;
      p.p_P = Eigen::Vector3d(corners[k][0], corners[k][1], layer.z_mm);
      p.bead_width_mm = 4.0;
      p.bead_height_mm = 1.5;
      p.speed_mm_s = k == 2 ? hot_speed : 8.0;  // the segment along x = +15 ends at corner 2
      p.weld = k > 0 || l > 0;
      layer.points.push_back(p);
    }
    plan.layers.push_back(layer);
  }
  return plan;
}

struct Build {
  twin::SimulationSettings settings = twin::TestSimulationSettings();
  planner::Plan plan;
  Depositor depositor;
  DepositHistory history;
  Build(planner::Plan p, double voxel)
      : settings([&] {
          twin::SimulationSettings s = twin::TestSimulationSettings();
          s.voxel_mm = voxel;
          s.start_length_mm = 0.0;
          s.stop_length_mm = 0.0;
          return s;
        }()),
        plan(std::move(p)),
        depositor(DepositPlan(plan, settings, 100.0, nullptr)),
        history(plan, depositor, settings, 100.0, 53.3) {}
};

models::DistortionParams Params(double strain, double exponent) {
  models::DistortionParams p;
  p.strain = strain;
  p.heat_exponent = exponent;
  p.substrate_stiffness_n_mm3 = 1e5;
  return p;
}

DistortionOptions Fe(double element_mm = 2.0, int groups = 2) {
  DistortionOptions o;
  o.element_mm = element_mm;
  o.groups = groups;
  return o;
}

TEST(Distortion, DisplacementIsLinearInTheStrain) {
  const Build b(StraightWall(8, 30.0, 8.0, 8.0), 0.5);
  const DistortionField one = ComputeDistortion(b.depositor.grid(), b.history, Params(0.002, 0.0), Fe());
  const DistortionField two = ComputeDistortion(b.depositor.grid(), b.history, Params(0.004, 0.0), Fe());
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(14, 0, 10), Eigen::Vector3d(-10, 1, 5), Eigen::Vector3d(0, 0, 11)}) {
    EXPECT_LT((two.Displacement(p) - 2.0 * one.Displacement(p)).norm(), 1e-6 + 1e-3 * two.Displacement(p).norm())
        << "linear elasticity: twice the inherent strain, twice the displacement at " << p.transpose();
  }
}

TEST(Distortion, UniformStrainShrinksAWallSymmetricallyTowardsItsMiddle) {
  const Build b(StraightWall(8, 30.0, 8.0, 8.0), 0.5);
  DistortionStats stats;
  const DistortionField f = ComputeDistortion(b.depositor.grid(), b.history, Params(0.004, 0.0), Fe(1.0), &stats);
  EXPECT_GT(stats.dofs, 0u);
  EXPECT_EQ(stats.solves, 2) << "two activation groups, two solves";
  const Eigen::Vector3d right = f.Displacement({12.0, 0.0, 5.0});
  const Eigen::Vector3d left = f.Displacement({-12.0, 0.0, 5.0});
  EXPECT_LT(right.x(), 0.0) << "the right end of the top must move inwards (-x)";
  // Not exactly mirrored: the single pass runs from -x to +x, so the deposit itself is slightly asymmetric.
  EXPECT_NEAR(right.x(), -left.x(), 0.15 * std::abs(right.x())) << "mirror symmetry about x = 0 within 15 %";
  // The top of a wall held at its base shrinks in height at most as much as free metal would: ratio eps H.
  const double top_z = f.Displacement({0.0, 0.0, 6.0}).z();
  EXPECT_LT(top_z, 0.0);
  EXPECT_GT(top_z, -1.2 * 0.5 * 0.004 * 6.0) << "vertical shrinkage bounded by the free value ratio x eps x H";
}

TEST(Distortion, SlowerSegmentsShrinkMore) {
  // Heat input per length q = e_w v_w / v: half the speed, twice q; with exponent 1 the strain doubles.
  models::DistortionParams p = Params(0.004, 1.0);
  EXPECT_NEAR(p.StrainAt(p.HeatInput(53.3, 4.0)) / p.StrainAt(p.HeatInput(53.3, 8.0)), 2.0, 1e-9);
  const Build slow(StraightWall(8, 30.0, 4.0, 4.0), 0.5);
  const Build fast(StraightWall(8, 30.0, 8.0, 8.0), 0.5);
  const double u_slow = ComputeDistortion(slow.depositor.grid(), slow.history, p, Fe(1.0)).Displacement({12, 0, 5}).x();
  const double u_fast = ComputeDistortion(fast.depositor.grid(), fast.history, p, Fe(1.0)).Displacement({12, 0, 5}).x();
  EXPECT_NEAR(u_slow / u_fast, 2.0, 0.05) << "the slow wall's end must move twice as far";
}

TEST(Distortion, HotSideBendsTheWallTowardsItInBothModes) {
  // The right half is welded at half the speed: it shrinks more along z, so the wall leans to the right (+x).
  const Build b(StraightWall(12, 30.0, 8.0, 4.0), 0.5);
  for (const models::DistortionMode mode : {models::DistortionMode::kFe, models::DistortionMode::kReduced}) {
    DistortionOptions o = Fe(1.0);
    o.mode = mode;
    const DistortionField f = ComputeDistortion(b.depositor.grid(), b.history, Params(0.004, 1.0), o);
    const Eigen::Vector3d top = f.Displacement({0.0, 0.0, 7.0});
    const Eigen::Vector3d bottom = f.Displacement({0.0, 0.0, 1.0});
    EXPECT_GT(top.x() - bottom.x(), 0.0) << NameOf(mode) << ": the top of the wall must lean towards the hot side";
    EXPECT_LT(f.Displacement({10.0, 0.0, 7.0}).z(), f.Displacement({-10.0, 0.0, 7.0}).z())
        << NameOf(mode) << ": the hot end of the top must sink more";
  }
}

TEST(Distortion, EachLoopOfASpiralPassIsItsOwnLayer) {
  const Build b(SpiralTube(6, 4.0), 0.5);
  ASSERT_EQ(b.depositor.beads().size(), 1u) << "the spiral must be one pass";
  std::vector<double> z_sum(6, 0.0);
  std::vector<int> count(6, 0);
  b.depositor.grid().ForEach([&](const VoxelIndex& v, const VoxelData& d) {
    const int layer = b.history.At(d.bead, d.time_s, b.depositor.grid().Center(v)).layer;
    ASSERT_GE(layer, 0);
    ASSERT_LT(layer, 6);
    z_sum[layer] += b.depositor.grid().Center(v).z();
    ++count[layer];
  });
  for (int l = 0; l < 6; ++l) {
    ASSERT_GT(count[l], 0) << "loop " << l << " must own voxels";
    EXPECT_NEAR(count[l], count[0], 0.2 * count[0]) << "every loop lays the same metal; loop " << l;
    if (l > 0) {
      EXPECT_GT(z_sum[l] / count[l] - z_sum[l - 1] / count[l - 1], 0.4)
          << "the metal of loop " << l << " lies above that of loop " << l - 1;
    }
  }
  // The reduced model bends a spiral tube only through the layers below each point: the build-direction strain
  // (vertical_ratio) must change the displacement of the top.
  DistortionOptions o = Fe(1.0);
  o.mode = models::DistortionMode::kReduced;
  models::DistortionParams p = Params(0.004, 1.0);
  const Eigen::Vector3d top(15.0, 0.0, 4.5);  // near the top of the +x wall (the tube is about 5 mm tall)
  const Eigen::Vector3d u1 = ComputeDistortion(b.depositor.grid(), b.history, p, o).Displacement(top);
  ASSERT_GT(u1.norm(), 0.0) << "the top of the hot wall must move";
  p.vertical_ratio *= 2.0;
  const Eigen::Vector3d u2 = ComputeDistortion(b.depositor.grid(), b.history, p, o).Displacement(top);
  EXPECT_GT((u2 - u1).norm(), 0.2 * u1.norm()) << "vertical_ratio must matter on a spiral: " << u1.transpose()
                                                << " vs " << u2.transpose();
}

// The FE assembly gathers each node's columns in parallel: the same displacements, bit for bit, on 1 and 4 threads,
// and the same stiffness pattern (stats) as well.
TEST(Distortion, SameFieldOnOneAndFourThreads) {
  const Build b(SpiralTube(6, 4.0), 0.5);
  const models::DistortionParams p = Params(0.004, 1.0);
  DistortionStats one_stats, four_stats;
  SetThreadCount(1);
  const DistortionField one = ComputeDistortion(b.depositor.grid(), b.history, p, Fe(1.0, 3), &one_stats);
  SetThreadCount(4);
  const DistortionField four = ComputeDistortion(b.depositor.grid(), b.history, p, Fe(1.0, 3), &four_stats);
  SetThreadCount(0);
  ASSERT_GT(one.nodes(), 500u) << "several nodes a thread";
  EXPECT_EQ(one.nodes(), four.nodes());
  EXPECT_EQ(one_stats.dofs, four_stats.dofs);
  EXPECT_EQ(one_stats.nonzeros, four_stats.nonzeros);
  EXPECT_EQ(one_stats.solves, four_stats.solves);
  int moved = 0;
  for (double x = -16.0; x <= 16.0; x += 0.75) {
    for (double y = -11.0; y <= 11.0; y += 0.75) {
      for (double z = 0.25; z <= 9.0; z += 0.75) {
        const Eigen::Vector3d u1 = one.Displacement({x, y, z}), u4 = four.Displacement({x, y, z});
        ASSERT_EQ(u1, u4) << "at " << x << " " << y << " " << z;
        moved += u1.squaredNorm() > 0.0;
      }
    }
  }
  EXPECT_GT(moved, 100) << "the comparison must cover displaced points";
}

TEST(Distortion, BadOptionsNameTheField) {
  const Build b(StraightWall(2, 10.0, 8.0, 8.0), 1.0);
  DistortionOptions o = Fe();
  o.groups = 0;
  EXPECT_THAT([&] { ComputeDistortion(b.depositor.grid(), b.history, Params(0.004, 0.0), o); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("distortion.groups")));
  models::DistortionParams p = Params(-0.1, 0.0);
  EXPECT_THAT([&] { ComputeDistortion(b.depositor.grid(), b.history, p, Fe()); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("strain = -0.1")));
}

TEST(DistortionFit, RecoversKnownParametersFromATwinScan) {
  const Build b(StraightWall(8, 24.0, 8.0, 4.0), 1.0);
  const models::DistortionParams truth = Params(0.01, 0.8);
  const DistortionOptions o = Fe(2.0, 2);
  const std::vector<Eigen::Vector3d> scan =
      ScanDistortedPart(b.depositor.grid(), ComputeDistortion(b.depositor.grid(), b.history, truth, o));
  DistortionFitOptions fit;
  fit.max_points = 800;
  const DistortionFitResult r = FitDistortion(b.depositor.grid(), b.history, scan, Params(0.005, 0.3), o, fit);
  ASSERT_TRUE(r.solver.usable) << r.solver.message;
  EXPECT_NEAR(r.params.strain, truth.strain, 0.03 * truth.strain) << "strain within 3 %";
  EXPECT_NEAR(r.params.heat_exponent, truth.heat_exponent, 0.03 * truth.heat_exponent) << "exponent within 3 %";
  EXPECT_LT(r.rms_mm, 0.05) << "the fitted surface must pass through the scan";
}

// Weights decide what the fit follows: the twin scan at known parameters (weight 1 per point) and as many points 2 mm
// above it (weight 1e-6, like the slivers' points of an STL that stand for almost no area). Per unit weight the fit
// recovers the parameters and its rms is that of the true points; counted alike (no weights), the raised half pulls
// the strain to 0 and leaves an rms of 0.49 mm.
TEST(DistortionFit, FollowsThePointsByTheirWeights) {
  const Build b(StraightWall(8, 24.0, 8.0, 4.0), 1.0);
  const models::DistortionParams truth = Params(0.01, 0.8);
  const DistortionOptions o = Fe(2.0, 2);
  std::vector<Eigen::Vector3d> scan =
      ScanDistortedPart(b.depositor.grid(), ComputeDistortion(b.depositor.grid(), b.history, truth, o));
  const std::size_t n = scan.size();
  std::vector<double> weight(n, 1.0);
  for (std::size_t i = 0; i < n; ++i) {
    scan.push_back(scan[i] + Eigen::Vector3d(0.0, 0.0, 2.0));
    weight.push_back(1e-6);
  }
  DistortionFitOptions fit;
  fit.max_points = 800;  // every k-th point: half from the true scan, half from the raised copy
  const DistortionFitResult r =
      FitDistortion(b.depositor.grid(), b.history, scan, Params(0.005, 0.3), o, fit, {}, weight);
  ASSERT_TRUE(r.solver.usable) << r.solver.message;
  EXPECT_NEAR(r.params.strain, truth.strain, 0.03 * truth.strain) << "strain within 3 %";
  EXPECT_NEAR(r.params.heat_exponent, truth.heat_exponent, 0.03 * truth.heat_exponent) << "exponent within 3 %";
  EXPECT_LT(r.rms_mm, 0.05) << "the rms per unit weight is the true points'";
  weight.pop_back();
  EXPECT_THAT([&] { FitDistortion(b.depositor.grid(), b.history, scan, truth, o, fit, {}, weight); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("weights for")));
}

TEST(DistortionFit, RefusesRepeatedFreeParameter) {
  const Build b(StraightWall(2, 10.0, 8.0, 8.0), 1.0);
  DistortionFitOptions fit;
  fit.free = {models::DistortionParam::kStrain, models::DistortionParam::kStrain};
  const std::vector<Eigen::Vector3d> scan(20, Eigen::Vector3d::Zero());
  EXPECT_THAT([&] { FitDistortion(b.depositor.grid(), b.history, scan, Params(0.004, 0.0), Fe(), fit); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("free parameter 'strain' is given twice")));
}

TEST(Compensation, ResamplingKeepsThePathAndSpacing) {
  const planner::Plan plan = testing::RectangleWall(2, 40.0, 20.0, 1.5, 8.0);
  const planner::Plan r = ResamplePlan(plan, 2.0);
  for (std::size_t l = 0; l < plan.layers.size(); ++l) {
    double length = 0.0, resampled = 0.0;
    for (std::size_t i = 1; i < plan.layers[l].points.size(); ++i) {
      length += (plan.layers[l].points[i].p_P - plan.layers[l].points[i - 1].p_P).norm();
    }
    for (std::size_t i = 1; i < r.layers[l].points.size(); ++i) {
      const double step = (r.layers[l].points[i].p_P - r.layers[l].points[i - 1].p_P).norm();
      EXPECT_LE(step, 2.0 + 1e-9) << "reference points at most 2 mm apart (003 sec. 6.5.2)";
      resampled += step;
    }
    EXPECT_NEAR(resampled, length, 1e-9) << "resampling must not change the path";
  }
}

}  // namespace
}  // namespace waam::twin
