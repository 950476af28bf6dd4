// Tests of the CSW curvature widening along executed passes: the radius estimate, the model's ratio, its limits.
#include "tests/twin/twin_settings.h"
#include "twin/deposition/curvature_width.h"

#include <cmath>
#include <limits>
#include <numbers>

#include <gtest/gtest.h>

#include "models/fit/model_file.h"
#include "twin/simulation_settings.h"

namespace waam::twin {
namespace {

constexpr double kW = 6.0;           // planned bead width, mm
constexpr double kH = 1.5;           // planned bead height, mm
constexpr double kSpeed = 400.0 / 60.0;  // mm/s

// A pass around a full circle of radius `r` (mm) in 1-degree chords, with arc lengths filled in.
ExecutedPass Circle(double r) {
  ExecutedPass pass;
  double s = 0.0;
  for (int k = 0; k <= 360; ++k) {
    const double a = k * std::numbers::pi / 180.0;
    ExecutedPoint p;
    p.p_P = Eigen::Vector3d(r * std::cos(a), r * std::sin(a), 0.0);
    if (k > 0) s += (p.p_P - pass.points.back().p_P).norm();
    p.s_mm = s;
    p.bead_width_mm = kW;
    p.bead_height_mm = kH;
    p.speed_mm_s = kSpeed;
    pass.points.push_back(p);
  }
  return pass;
}

models::CswModel DefaultCsw() { return models::CswModel::Load(models::DefaultModelPath("csw")); }

TEST(PathRadius, CircleAndStraightLine) {
  const ExecutedPass circle = Circle(40.0);
  EXPECT_NEAR(PathRadiusAt(circle, 0.5 * circle.length_mm(), kW), 40.0, 0.2);
  ExecutedPass line;
  for (int k = 0; k <= 10; ++k) {
    ExecutedPoint p;
    p.p_P = Eigen::Vector3d(5.0 * k, 0.0, 0.0);
    p.s_mm = 5.0 * k;
    line.points.push_back(p);
  }
  EXPECT_TRUE(std::isinf(PathRadiusAt(line, 20.0, kW)));
}

TEST(CurvatureWidth, CircleWidensByTheModelsRatioAndKeepsTheArea) {
  const models::CswModel csw = DefaultCsw();
  const double inf = std::numeric_limits<double>::infinity();
  ExecutedPass pass = Circle(50.0);
  ApplyCurvatureWidth(csw, 30.0, &pass);
  const double expected = csw.Width(400.0, 50.0) / csw.Width(400.0, inf);
  ASSERT_GT(expected, 1.01) << "the default CSW model should widen beads on a 50 mm radius";
  const std::size_t mid = pass.points.size() / 2;
  EXPECT_NEAR(pass.points[mid].width_factor, expected, 0.01 * expected);
  twin::SimulationSettings settings = twin::TestSimulationSettings();
  settings.start_length_mm = 0.0;
  settings.stop_length_mm = 0.0;
  const BeadSection section = SectionAt(pass, mid, pass.points[mid].s_mm, settings);
  EXPECT_NEAR(section.width_mm, kW * pass.points[mid].width_factor, 1e-9);
  EXPECT_NEAR(section.width_mm * section.height_mm, kW * kH, 1e-9) << "the bead's area must not change";
}

TEST(CurvatureWidth, RadiiBelowTheFittedRangeAreClampedAndCornersAreLeftToTheSweep) {
  const models::CswModel csw = DefaultCsw();
  const double inf = std::numeric_limits<double>::infinity();
  ExecutedPass tight = Circle(12.0);  // a curve (r > w) tighter than the model's 30 mm data
  ApplyCurvatureWidth(csw, 30.0, &tight);
  EXPECT_NEAR(tight.points[180].width_factor, csw.Width(400.0, 30.0) / csw.Width(400.0, inf), 1e-3);
  ExecutedPass corner = Circle(4.0);  // r < w: a corner, no widening
  ApplyCurvatureWidth(csw, 30.0, &corner);
  EXPECT_DOUBLE_EQ(corner.points[180].width_factor, 1.0);
}

}  // namespace
}  // namespace waam::twin
