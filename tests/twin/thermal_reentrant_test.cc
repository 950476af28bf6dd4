// The thermal model at re-entrant edges (a wall standing on a plate): the face factor's derivation from the edge's
// singular solution, and the observed grid order of a wall on a plate.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "tests/twin/thermal_test_util.h"
#include "twin/thermal/thermal_state.h"

namespace waam::twin {
namespace {

using testing::ConstantMaterial;
using testing::InsulatedSettings;

// The leading singular solution at a re-entrant (270 degree) edge with insulated faces, the air in the quadrant
// y > 0, z > 0: u = r^(2/3) cos(2 (theta - pi/2) / 3), theta in [pi/2, 2 pi] (Grisvard 1985, Elliptic Problems in
// Nonsmooth Domains, ch. 4 and 5: u ~ r^(pi/omega) at a corner of angle omega).
double EdgeSingular(double y, double z) {
  double theta = std::atan2(z, y);
  if (theta < 0.5 * std::numbers::pi) theta += 2.0 * std::numbers::pi;
  return std::pow(std::hypot(y, z), 2.0 / 3.0) * std::cos(2.0 / 3.0 * (theta - 0.5 * std::numbers::pi));
}

// Mean of EdgeSingular over the unit square [y0, y0 + 1] x [z0, z0 + 1] (midpoint rule, n^2 points).
double UnitSquareMean(double y0, double z0) {
  constexpr int n = 1000;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) sum += EdgeSingular(y0 + (i + 0.5) / n, z0 + (j + 0.5) / n);
  }
  return sum / (n * n);
}

// The factor makes the two-point flux between the means of the unit cells above (wall) and below (plate) the face
// y in [-1, 0], z = 0 exact: there du/dz = (2/3) sin(pi/3) r^(-1/3), so the face passes sin(pi/3) = sqrt(3)/2.
TEST(ThermalReentrant, FaceFactorMakesTheTwoPointFluxExactForTheSingularSolution) {
  const double wall = UnitSquareMean(-1.0, 0.0), plate = UnitSquareMean(-1.0, -1.0);
  const double factor = 0.5 * std::sqrt(3.0) / (wall - plate);
  EXPECT_NEAR(factor, internal::kReentrantFaceFactor, 1e-5);
  // The other face at the edge (y = 0, z in [-1, 0], between the plate cell under the wall and the one beside it)
  // has the same factor by the solution's symmetry about theta = 5 pi / 4.
  const double beside = UnitSquareMean(0.0, -1.0);
  EXPECT_NEAR(0.5 * std::sqrt(3.0) / (plate - beside), internal::kReentrantFaceFactor, 1e-5);
}

// Mean temperature of the cells whose centres lie in `box` (degC): a whole number of cells at every grid here.
double BoxMean(const TemperatureField& field, const Eigen::AlignedBox3d& box) {
  double sum = 0.0;
  int count = 0;
  for (int k = 0; k < field.size.z(); ++k) {
    for (int j = 0; j < field.size.y(); ++j) {
      for (int i = 0; i < field.size.x(); ++i) {
        const Eigen::Vector3d c = field.origin_mm + field.cell_mm * Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5);
        const float t = field.temperature_c[(static_cast<std::size_t>(k) * field.size.y() + j) * field.size.x() + i];
        if (!box.contains(c) || std::isnan(t)) continue;
        sum += t;
        ++count;
      }
    }
  }
  return sum / count;
}

// A 4 mm wall 8 mm tall on a 24 x 8 mm plate, 4 mm long with insulated faces (a 2-D section): 400 W into the wall's
// top 4 mm for 4 s (one micro step of 0.25 s per Weld over the whole length, so every grid heats the same volume at
// the same times), then 4 s of cooling. Returns the means over the wall's bottom 2 mm and over the plate's 2 x 2 mm
// beside the edge, degC.
Eigen::Vector2d WallOnPlate(double cell_mm) {
  ThermalSettings st = InsulatedSettings(ConstantMaterial(40.0, 7850.0, 600.0),
                                         Eigen::AlignedBox3d(Eigen::Vector3d(-2, -12, -8), Eigen::Vector3d(2, 12, 0)),
                                         Eigen::AlignedBox3d(Eigen::Vector3d(-2, -2, 0), Eigen::Vector3d(2, 2, 8)), cell_mm);
  st.initial_c = st.ambient_c = 20.0;
  st.far_step_s = 0.0;
  st.arc_step_cells = 4.0 / cell_mm;
  ThermalSimulation sim(st);
  for (double top = 2.0; top <= 8.0; top += 2.0) sim.Weld({-2, 0, top}, {2, 0, top}, 4.0, 2.0, 0.0, 1e-9);
  // The bead rule heats the bead's section and one cell under it: 4 mm deep on every grid.
  for (int step = 0; step < 16; ++step) sim.Weld({-2, 0, 8}, {2, 0, 8}, 4.0, 4.0 - cell_mm, 400.0, 0.25);
  for (int step = 0; step < 16; ++step) sim.Cool(0.25);
  const TemperatureField field = sim.Field();
  return {BoxMean(field, Eigen::AlignedBox3d(Eigen::Vector3d(-2, -2, 0), Eigen::Vector3d(2, 2, 2))),
          BoxMean(field, Eigen::AlignedBox3d(Eigen::Vector3d(-2, 2, -2), Eigen::Vector3d(2, 4, 0)))};
}

// Cell-centred finite volumes lose order at the re-entrant edges where the wall meets the plate (the solution
// grows as r^(2/3) there): without the face factor the means below converge at order 1.3 (4/3, the singular
// exponent's 2 x 2/3), with it at order 2. Observed order log2((e(2) - e(1)) / (e(1) - e(0.5))) from the three
// grids' differences; it must exceed 1.7.
TEST(ThermalReentrant, WallOnPlateConvergesAtSecondOrder) {
  const Eigen::Vector2d coarse = WallOnPlate(2.0), medium = WallOnPlate(1.0), fine = WallOnPlate(0.5);
  for (int q = 0; q < 2; ++q) {
    const double order = std::log2((coarse[q] - medium[q]) / (medium[q] - fine[q]));
    EXPECT_GT(order, 1.7) << (q == 0 ? "wall bottom" : "plate beside the edge") << ": " << coarse[q] << ", "
                          << medium[q] << ", " << fine[q] << " degC";
  }
}

}  // namespace
}  // namespace waam::twin
