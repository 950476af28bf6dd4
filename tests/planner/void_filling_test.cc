// Junction detection and void filling (003 sec. 4.4.1, eq. 4.3-4.6): corner geometry, junction classes, bad input.
#include "models/core/numbers.h"
#include "planner/path/void_filling.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/error.h"
#include "planner/mesh/generators.h"
#include "planner/planar_planner.h"
#include "planner/scenario/scenario.h"
#include "tests/planner/pattern_checks.h"
#include "tests/planner/test_shapes.h"

namespace waam::planner {
namespace {

using ::testing::HasSubstr;
using Vec = Eigen::Vector2d;

PolygonWithHoles Grid2x2() {
  PolygonWithHoles region{testing::Rect(-4.5, -4.5, 124.5, 124.5), {}};
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) {
      region.holes.push_back(testing::Rect(i * 60 + 4.5, j * 60 + 4.5, (i + 1) * 60 - 4.5, (j + 1) * 60 - 4.5, true));
    }
  }
  return region;
}

TEST(VoidFilling, CornerGeometryFollowsEq43To45) {
  const double l = 3.7;
  for (double theta_deg : {30.0, 60.0, 90.0, 120.0, 150.0}) {
    for (double lambda : {0.0, 1.0, 2.5}) {
      const double theta = theta_deg * kPi / 180.0;
      // A-P-B with the angle APB = theta, P at (5, 7); the junction lies opposite the angle's bisector.
      const Vec p(5, 7);
      const Vec a = p + 30.0 * Vec(1, 0);
      const Vec b = p + 30.0 * Vec(std::cos(theta), std::sin(theta));
      const Vec into = -((a - p).normalized() + (b - p).normalized()).normalized();
      const CornerCorrection c = CorrectCorner(a, p, b, into, lambda, l, "test");
      const double s = std::sin(theta / 2);
      EXPECT_NEAR((c.p_n - p).norm(), lambda * l * (1 / s - 1), 1e-9) << "eq. 4.5 at theta " << theta_deg;
      EXPECT_NEAR(c.shift_mm, lambda * l * (1 / s - 1), 1e-9);
      EXPECT_NEAR((c.e - p).norm(), l / (2 * s), 1e-9) << "eq. 4.4: |PE|";
      EXPECT_NEAR((c.f - p).norm(), l / (2 * s), 1e-9) << "eq. 4.4: |PF|";
      EXPECT_NEAR((c.e - p).normalized().dot((a - p).normalized()), 1.0, 1e-12) << "E lies on PA";
      EXPECT_NEAR((c.f - p).normalized().dot((b - p).normalized()), 1.0, 1e-12) << "F lies on PB";
      if (lambda == 1.0) {
        // eq. 4.1-4.2: P_o, the corner of the curve l away, is l / sin(theta/2) from P and l from P_N.
        const Vec p_o = p + l / s * into;
        EXPECT_NEAR((p_o - c.p_n).norm(), l, 1e-9) << "geometric correction keeps l to P_o";
      }
      if (lambda > 0.0) {
        EXPECT_GT((c.p_n - p).dot(into), 0.0) << "P moves into the junction";
      }
    }
  }
}

TEST(VoidFilling, Eq46LambdaMakesTheShiftTheVoidLength) {
  const double l = 3.7, theta = 90.0 * kPi / 180.0, void_length = 28.3;
  const double lambda = LambdaForVoidLength(void_length, theta, l);
  EXPECT_NEAR(lambda * l * (1 / std::sin(theta / 2) - 1), void_length, 1e-9);
}

TEST(VoidFilling, TooSharpOrShortCornersAreRefused) {
  const Vec p(0, 0), a(20, 0);
  const double theta = 10.0 * kPi / 180.0;
  const Vec b = 20.0 * Vec(std::cos(theta), std::sin(theta));
  try {
    CorrectCorner(a, p, b, Vec(-1, 0), 1.0, 3.0, "s.yaml:9: path.void_filling");
    FAIL() << "expected InputError for a 10 degree corner";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("s.yaml:9: path.void_filling: turning point at (0.0, 0.0) mm has theta = 10"));
    EXPECT_THAT(e.what(), HasSubstr("too small to correct"));
  }
  try {
    CorrectCorner(Vec(1, 0), p, Vec(0, 1), Vec(-1, -1).normalized(), 1.0, 3.0, "where");
    FAIL() << "expected InputError for 1 mm legs";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("too sharp to correct: E and F lie 2.12"));
  }
}

TEST(Junctions, GridJunctionClasses) {
  PatternOptions options;
  options.pattern = Pattern::kEulerian;
  const PolygonWithHoles grid = Grid2x2();
  const std::vector<Move2D> moves = PlanLayerPattern({grid}, options);
  std::map<std::string, int> classes;
  for (const Junction& j : FindJunctions({grid}, moves, 6.0, 2)) {
    ++classes[j.ClassName()];
    double sum = 0.0;
    for (double a : j.angles_deg) sum += a;
    EXPECT_NEAR(sum, 360.0, 1e-6) << j.ClassName() << ": angles go once round the junction";
  }
  EXPECT_EQ(classes["4 ribs 90/90/90/90"], 1) << "the centre cross";
  EXPECT_EQ(classes["3 ribs 180/90/90"], 4) << "T junctions on the outer wall (Appendix A1 B1)";
  EXPECT_EQ(classes["2 ribs 270/90"], 4) << "corners of the outer wall";
  EXPECT_EQ(classes.size(), 3u);
  EXPECT_EQ(FindJunctions({grid}, moves, 6.0, 3).size(), 5u) << "min_ribs 3 leaves the corners out";
}

TEST(VoidFilling, FixedLambdaCorrectsOneCornerPerJunctionAndKeepsOnePass) {
  PatternOptions options;
  options.pattern = Pattern::kEulerian;
  const PolygonWithHoles grid = Grid2x2();
  VoidFillingSettings settings;
  settings.mode = VoidFillingMode::kFixed;
  settings.lambda = 1.0;
  const VoidFiller filler(settings, 6.0, 3.0);
  for (int layer = 0; layer < 4; ++layer) {
    options.layer_index = layer;
    const std::vector<Move2D> moves = PlanLayerPattern({grid}, options);
    std::vector<CornerCorrection> corrections;
    const std::vector<Move2D> filled = filler.Apply({grid}, moves, layer, &corrections);
    EXPECT_EQ(corrections.size(), 5u) << "one corner per junction of three or four ribs";
    EXPECT_EQ(filled.size(), moves.size() + 2 * corrections.size()) << "each P becomes E, P_N, F";
    EXPECT_EQ(testing::CountPasses(filled), 1);
    for (const CornerCorrection& c : corrections) {
      EXPECT_NEAR(c.shift_mm, 3.0 * (std::sqrt(2.0) - 1.0), 1e-6) << "90 degree cell corners, l = 3 mm";
      EXPECT_NEAR(c.theta_deg, 90.0, 1e-6);
    }
  }
}

TEST(Junctions, GeneratorRefusesArmsTooClose) {
  try {
    GeneratePart("junction", {{"arm_angles_deg", {0, 10, 180}}}, "s.yaml:3: part.generator");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("s.yaml:3: part.generator: junction.arm_angles_deg: arms at 0 and 10 deg"));
  }
}

}  // namespace
}  // namespace waam::planner
