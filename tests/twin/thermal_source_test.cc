// The arc's heat source: Goldak's double ellipsoid integrated over cells holds exactly the power and the
// distribution's first moments, and a standing arc spread over its pool stays at pool temperatures.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "tests/twin/thermal_test_util.h"
#include "twin/thermal/heat_source.h"
#include "twin/thermal/thermal_simulation.h"

namespace waam::twin {
namespace {

struct Moments {
  double sum = 0.0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();  // mm, in the grid frame
};

// The cells' shares of a source at `arc` (travelling along `travel`) on a grid of `cell` mm cubes covering 2.5
// semi-axes around it (erfc(2.5 sqrt 3) = 1e-9 left outside), summed, with their first moments about the arc point.
Moments CellMoments(const DoubleEllipsoid& s, const Eigen::Vector3d& arc, const Eigen::Vector2d& travel, double cell) {
  Moments m;
  const int n = static_cast<int>(std::ceil(2.5 * std::max({s.half_width_mm, s.front_mm, s.rear_mm}) / cell));
  const int depth = static_cast<int>(std::ceil(2.5 * s.depth_mm / cell));
  for (int k = -depth; k < 1; ++k) {
    for (int j = -n; j < n; ++j) {
      for (int i = -n; i < n; ++i) {
        // Cells aligned so that the surface z = arc.z is a cell face.
        const Eigen::Vector3d lo = arc + cell * Eigen::Vector3d(i + 0.25, j + 0.5, k - 1);
        const Eigen::AlignedBox3d box(lo, lo + Eigen::Vector3d::Constant(cell));
        const double share = DoubleEllipsoidCellShare(s, arc, travel, box);
        m.sum += share;
        m.first += share * (box.center() - arc);
      }
    }
  }
  return m;
}

// The closed-form mean of each lobe: a half-Gaussian exp(-3 u^2 / c^2) on u >= 0 has mean c / sqrt(3 pi), so along the
// travel the mean is (f_f c_f - f_r c_r) / (2 sqrt(3 pi)) with f = 2 c / (c_f + c_r), and the mean depth b / sqrt(3 pi).
Eigen::Vector3d ExpectedMean(const DoubleEllipsoid& s) {
  const double root = std::sqrt(3.0 * std::numbers::pi);
  const double sum = s.front_mm + s.rear_mm;
  const double along = (s.front_mm * s.front_mm - s.rear_mm * s.rear_mm) / (sum * root);
  return {along, 0.0, -s.depth_mm / root};
}

TEST(ThermalSource, DoubleEllipsoidHoldsThePowerAndItsFirstMomentsOnAxisAlignedTravel) {
  const DoubleEllipsoid s{3.0, 4.0, 3.0, 12.0};
  EXPECT_NEAR(DoubleEllipsoidShare(s, Eigen::Vector3d::Constant(-1e3), Eigen::Vector3d::Constant(1e3)), 1.0, 1e-12);
  // The front lobe holds f_f / 2 = c_f / (c_f + c_r) of the power.
  EXPECT_NEAR(DoubleEllipsoidShare(s, Eigen::Vector3d(0, -1e3, -1e3), Eigen::Vector3d::Constant(1e3)), 0.2, 1e-12);
  const Eigen::Vector3d arc(0.3, -0.7, 5.0);
  const Eigen::Vector3d mean = ExpectedMean(s);
  // Along +x, -x, +y, -y: the moments rotate with the travel. Cell-centre moments of exact cell integrals are exact
  // for a density linear over a cell; 0.5 mm cells on 3-12 mm semi-axes leave < 1 % of the mean.
  struct Case {
    Eigen::Vector2d travel;
    Eigen::Vector3d mean;
  };
  for (const Case& c : {Case{{1, 0}, mean}, Case{{-2, 0}, {-mean.x(), 0, mean.z()}},
                        Case{{0, 1}, {0, mean.x(), mean.z()}}, Case{{0, -0.5}, {0, -mean.x(), mean.z()}}}) {
    const Moments m = CellMoments(s, arc, c.travel, 0.5);
    EXPECT_NEAR(m.sum, 1.0, 1e-8) << "travel " << c.travel.transpose();
    const Eigen::Vector3d got = m.first / m.sum;
    EXPECT_NEAR((got - c.mean).norm(), 0.0, 0.01 * c.mean.norm())
        << "travel " << c.travel.transpose() << ": mean " << got.transpose() << ", expected " << c.mean.transpose();
  }
}

TEST(ThermalSource, DoubleEllipsoidOnAnObliqueTravelKeepsItsMoments) {
  const DoubleEllipsoid s{3.0, 2.0, 3.0, 12.0};
  const Eigen::Vector2d d = Eigen::Vector2d(3, 4).normalized();
  const Eigen::Vector3d mean = ExpectedMean(s);
  const Moments m = CellMoments(s, Eigen::Vector3d(1, 2, 0), Eigen::Vector2d(3, 4), 0.5);
  // Columns of 0.125 mm: the midpoint rule's error on Gaussians of 3 mm semi-axes is ~1e-4.
  EXPECT_NEAR(m.sum, 1.0, 1e-3);
  const Eigen::Vector3d expected(mean.x() * d.x(), mean.x() * d.y(), mean.z());
  EXPECT_NEAR((m.first / m.sum - expected).norm(), 0.0, 0.01 * expected.norm())
      << "mean " << (m.first / m.sum).transpose() << ", expected " << expected.transpose();
}

// A 1500 W arc standing 2 s at the end of a 6 mm bead on a steel-like plate (latent heat, conductivity 35 W/(m K) in
// the liquid), 2 mm cells. The uniform bead rule with pure conduction (the model before the double ellipsoid) puts
// the heat into the handful of cells of the bead's disc and those under it and drives them past 3000 degC (measured:
// 3670), far above any measured steel pool (Kraus 1987, Welding Journal 66(12) 353s: 2000-2800 K on GTA pools of 304
// steel); the double ellipsoid with the default liquid conductivity factor spreads it over the pool and stays under
// 2500 degC (measured: 2056; 2520 with pure conduction, 2295 for the bead rule with the factor). The input is
// exactly the power in both.
TEST(ThermalSource, StandingArcSpreadOverItsPoolStaysAtPoolTemperatures) {
  const Eigen::AlignedBox3d plate(Eigen::Vector3d(-30, -30, -10), Eigen::Vector3d(30, 30, 0));
  const Eigen::AlignedBox3d deposit(Eigen::Vector3d(-10, -10, 0), Eigen::Vector3d(10, 10, 4));
  double peak[2] = {0.0, 0.0};
  for (int shape = 0; shape < 2; ++shape) {
    ThermalSettings st = testing::InsulatedSettings(testing::VaryingMaterial(), plate, deposit, 2.0);
    st.heat_source = shape == 0 ? HeatSourceShape::kUniformBead : HeatSourceShape::kDoubleEllipsoid;
    if (shape == 0) st.liquid_conductivity_factor = 1.0;  // the model before the pool's shape and stirring
    ThermalSimulation sim(st);
    // A short bead first, so the arc stands at the end of a pass (its pool oriented along it).
    sim.Weld({-6, 0, 2}, {0, 0, 2}, 6.0, 2.0, 1500.0, 1.0);
    for (int i = 0; i < 8; ++i) {
      sim.Weld({0, 0, 2}, {0, 0, 2}, 6.0, 2.0, 1500.0, 0.25, {1, 0, 0});
      peak[shape] = std::max(peak[shape], sim.MaxTemperatureIn(deposit.merged(plate)));
    }
    EXPECT_NEAR(sim.Energy().input_j, 1500.0 * 3.0, 1e-9 * 4500.0);
    EXPECT_LT(sim.Energy().RelativeError(), 1e-9);
  }
  EXPECT_GT(peak[0], 3000.0) << "the uniform bead rule no longer overheats a standing arc: revisit this bound";
  EXPECT_LT(peak[1], 2500.0) << "a standing arc of 2 s on its pool";
}

}  // namespace
}  // namespace waam::twin
