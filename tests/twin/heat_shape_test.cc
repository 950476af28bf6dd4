// Tests of heat into shape in the twin: beads and inherent strains at the reference temperature are today's bit for
// bit, and the thermal strain law's factor acts as a plain scaling of the fitted strain (closed form).
#include <cmath>
#include <limits>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/error.h"
#include "tests/twin/test_plans.h"
#include "tests/twin/twin_settings.h"
#include "twin/deposition/bead_deposition.h"
#include "twin/deposition/heat_bead.h"
#include "twin/distortion/distortion.h"

namespace waam::twin {
namespace {

using ::testing::HasSubstr;

twin::SimulationSettings Settings() {
  twin::SimulationSettings s = twin::TestSimulationSettings();
  s.voxel_mm = 0.5;
  s.start_length_mm = 0.0;
  s.stop_length_mm = 0.0;
  return s;
}

// Every voxel of `a` in `b` with the same bead and time, and as many voxels.
bool SameGrid(const VoxelGrid& a, const VoxelGrid& b) {
  if (a.occupied() != b.occupied()) return false;
  bool same = true;
  a.ForEach([&](const VoxelIndex& v, const VoxelData& d) {
    const VoxelData* e = b.Get(v);
    same = same && e != nullptr && e->bead == d.bead && e->time_s == d.time_s;
  });
  return same;
}

models::BeadTemperatureModel DemoBeadModel() {
  models::BeadTemperatureParams p;
  p.reference_c = 150.0;
  p.height_per_k = -4e-4;
  p.width_per_k = 3e-4;
  p.min_c = 20.0;
  p.max_c = 600.0;
  return models::BeadTemperatureModel(p);
}

TEST(HeatShape, BeadsAtTheReferenceTemperatureDepositExactlyTodaysPart) {
  const planner::Plan plan = testing::RectangleWall(3, 30.0, 20.0, 1.5, 8.0);
  const BeadHeatFactors f = BeadFactorsAt(DemoBeadModel(), std::vector<double>(plan.layers.size(), 150.0));
  const planner::Plan shaped = ShapeBeadsByHeat(plan, f);
  for (std::size_t l = 0; l < plan.layers.size(); ++l) {
    for (std::size_t i = 0; i < plan.layers[l].points.size(); ++i) {
      ASSERT_EQ(shaped.layers[l].points[i].bead_height_mm, plan.layers[l].points[i].bead_height_mm);
      ASSERT_EQ(shaped.layers[l].points[i].bead_width_mm, plan.layers[l].points[i].bead_width_mm);
    }
  }
  const Depositor today = DepositPlan(plan, Settings(), 100.0, nullptr);
  const Depositor heat = DepositPlan(shaped, Settings(), 100.0, nullptr);
  EXPECT_TRUE(SameGrid(today.grid(), heat.grid())) << "the deposit at T_ref must be today's voxel for voxel";
}

TEST(HeatShape, HotterLayersLayLowerWiderBeads) {
  const planner::Plan plan = testing::RectangleWall(2, 30.0, 20.0, 1.5, 8.0);
  const BeadHeatFactors f = BeadFactorsAt(DemoBeadModel(), {150.0, 400.0});
  const planner::Plan shaped = ShapeBeadsByHeat(plan, f);
  const planner::PathPoint& hot = shaped.layers[1].points[1];
  EXPECT_NEAR(hot.bead_height_mm, 1.5 * (1.0 - 4e-4 * 250.0), 1e-12);
  EXPECT_NEAR(hot.bead_width_mm, plan.layers[1].points[1].bead_width_mm * (1.0 + 3e-4 * 250.0), 1e-12);
  EXPECT_THROW(ShapeBeadsByHeat(plan, BeadFactorsAt(DemoBeadModel(), {150.0})), InputError)
      << "one factor per layer is needed";
  EXPECT_THROW(BeadFactorsAt(DemoBeadModel(), {std::nan("")}), InputError);
}

struct WallBuild {
  planner::Plan plan = testing::RectangleWall(4, 30.0, 20.0, 1.5, 8.0);
  Depositor depositor = DepositPlan(plan, Settings(), 100.0, nullptr);
  DepositHistory history{plan, depositor, Settings(), 100.0, 53.3};
};

models::DistortionParams Params() {
  models::DistortionParams p;
  p.strain = 0.004;
  p.heat_exponent = 0.0;
  p.substrate_stiffness_n_mm3 = 1e5;
  p.mechanical_melting_c = 800.0;
  p.reference_interpass_c = 200.0;
  return p;
}

TEST(HeatShape, StrainsAtTheFittedThermalHistoryAreTodays) {
  const WallBuild b;
  for (models::DistortionMode mode : {models::DistortionMode::kReduced, models::DistortionMode::kFe}) {
    DistortionOptions today;
    today.mode = mode;
    DistortionOptions heat = today;
    // Every layer laid on metal at the reference temperature and heated past mechanical melting: factor exactly 1.
    heat.layer_heat.assign(b.history.layers(), LayerHeat{200.0, 1600.0});
    const DistortionField a = ComputeDistortion(b.depositor.grid(), b.history, Params(), today);
    const DistortionField c = ComputeDistortion(b.depositor.grid(), b.history, Params(), heat);
    for (const Eigen::Vector3d& p :
         {Eigen::Vector3d(14, 9, 5), Eigen::Vector3d(-14, -9, 2), Eigen::Vector3d(0, 10, 6)}) {
      const Eigen::Vector3d ua = a.Displacement(p), uc = c.Displacement(p);
      EXPECT_EQ(ua.x(), uc.x()) << NameOf(mode);
      EXPECT_EQ(ua.y(), uc.y()) << NameOf(mode);
      EXPECT_EQ(ua.z(), uc.z()) << NameOf(mode);
    }
  }
}

TEST(HeatShape, ThermalLawScalesTheStrainInClosedForm) {
  // eps = eps_fit (min(T_peak, T_mm) - T_ip) / (T_mm - T_ref): T_mm 800, T_ref 200.
  models::DistortionParams p = Params();
  EXPECT_DOUBLE_EQ(p.ThermalFactor(1600.0, 500.0), 0.5) << "(800 - 500) / (800 - 200)";
  EXPECT_DOUBLE_EQ(p.ThermalFactor(650.0, 200.0), 0.75) << "peak below T_mm: (650 - 200) / 600";
  EXPECT_EQ(p.ThermalFactor(1600.0, 900.0), 0.0) << "laid on metal above T_mm: no strain left";
  EXPECT_EQ(p.ThermalFactor(1600.0, 200.0), 1.0);
  // The whole part at factor 0.5 distorts exactly as the fitted strain halved (the reduced model is linear in it).
  const WallBuild b;
  DistortionOptions heat;
  heat.mode = models::DistortionMode::kReduced;
  heat.layer_heat.assign(b.history.layers(), LayerHeat{500.0, 1600.0});
  DistortionOptions today;
  today.mode = models::DistortionMode::kReduced;
  models::DistortionParams half = p;
  half.strain = 0.5 * p.strain;
  const DistortionField a = ComputeDistortion(b.depositor.grid(), b.history, p, heat);
  const DistortionField c = ComputeDistortion(b.depositor.grid(), b.history, half, today);
  const Eigen::Vector3d q(14, 9, 5);
  EXPECT_GT(c.Displacement(q).norm(), 1e-3);
  EXPECT_NEAR((a.Displacement(q) - c.Displacement(q)).norm(), 0.0, 1e-12 * c.Displacement(q).norm() + 1e-15);
}

TEST(HeatShape, ThermalHistoryNeedsAReferenceAndEveryLayer) {
  const WallBuild b;
  DistortionOptions heat;
  heat.layer_heat.assign(b.history.layers(), LayerHeat{200.0, 1600.0});
  models::DistortionParams p = Params();
  p.reference_interpass_c = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT([&] { ComputeDistortion(b.depositor.grid(), b.history, p, heat); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("reference_interpass_c")));
  heat.layer_heat.pop_back();
  EXPECT_THAT([&] { ComputeDistortion(b.depositor.grid(), b.history, Params(), heat); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("one entry per layer")));
}

}  // namespace
}  // namespace waam::twin
