// Tests of the distortion twin: FE invariants (linearity, symmetry, free shrinkage), heat-input scaling, the reduced
// mode's bending direction, and the Ceres fit recovering known parameters from a twin-generated scan.
#include "twin/distortion/distortion.h"

#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/error.h"
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

struct Build {
  planner::SimulationSettings settings;
  planner::Plan plan;
  Depositor depositor;
  DepositHistory history;
  Build(planner::Plan p, double voxel)
      : settings([&] {
          planner::SimulationSettings s;
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
  for (const Eigen::Vector3d p : {Eigen::Vector3d(14, 0, 10), Eigen::Vector3d(-10, 1, 5), Eigen::Vector3d(0, 0, 11)}) {
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
  for (const std::string mode : {"fe", "reduced"}) {
    DistortionOptions o = Fe(1.0);
    o.mode = mode;
    const DistortionField f = ComputeDistortion(b.depositor.grid(), b.history, Params(0.004, 1.0), o);
    const Eigen::Vector3d top = f.Displacement({0.0, 0.0, 7.0});
    const Eigen::Vector3d bottom = f.Displacement({0.0, 0.0, 1.0});
    EXPECT_GT(top.x() - bottom.x(), 0.0) << mode << ": the top of the wall must lean towards the hot side";
    EXPECT_LT(f.Displacement({10.0, 0.0, 7.0}).z(), f.Displacement({-10.0, 0.0, 7.0}).z())
        << mode << ": the hot end of the top must sink more";
  }
}

TEST(Distortion, BadOptionsNameTheField) {
  const Build b(StraightWall(2, 10.0, 8.0, 8.0), 1.0);
  DistortionOptions o;
  o.mode = "magic";
  EXPECT_THAT([&] { ComputeDistortion(b.depositor.grid(), b.history, Params(0.004, 0.0), o); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("distortion.mode = 'magic'")));
  o = Fe();
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

TEST(DistortionFit, RefusesUnknownFreeParameter) {
  const Build b(StraightWall(2, 10.0, 8.0, 8.0), 1.0);
  DistortionFitOptions fit;
  fit.free = {"colour"};
  const std::vector<Eigen::Vector3d> scan(20, Eigen::Vector3d::Zero());
  EXPECT_THAT([&] { FitDistortion(b.depositor.grid(), b.history, scan, Params(0.004, 0.0), Fe(), fit); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("free parameter 'colour'")));
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
