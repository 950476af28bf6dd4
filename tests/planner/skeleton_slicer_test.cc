// Tests of the bent-tube generator, the skeleton slicing (Fig. 56 limits, planes perpendicular to the axis), the
// positioner turning every layer normal up, the eq. 6.4 design rule and the one-pass spiral.
#include "models/core/numbers.h"
#include "planner/slicing/skeleton_slicer.h"

#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/error.h"
#include "models/fit/model_file.h"
#include "planner/kinematics/positioner.h"
#include "planner/mesh/mesh_ops.h"
#include "planner/mesh/tube_generators.h"
#include "planner/scenario/scenario.h"
#include "planner/skeleton_planner.h"

namespace waam::planner {
namespace {

using ::testing::HasSubstr;

// A torus segment with a straight foot: 60 mm section on a 200 mm bend, coarse so the tests stay fast.
BentTubeSpec TorusSegment(double bend_deg) {
  BentTubeSpec spec;
  spec.diameter_start_mm = spec.diameter_end_mm = 60.0;
  spec.wall_mm = 4.0;
  spec.bend_radius_mm = 200.0;
  spec.bend_angle_rad = bend_deg * kPi / 180.0;
  spec.straight_start_mm = 10.0;
  spec.straight_end_mm = 0.0;
  spec.section_points = 48;
  spec.axis_step_mm = 1.0;
  return spec;
}

// Tangent of the spec's analytic axis at the point of the axis nearest `p` (straight foot, then the arc).
Eigen::Vector3d AxisTangentNear(const BentTubeSpec& spec, const Eigen::Vector3d& p) {
  if (p.z() <= spec.straight_start_mm) return Eigen::Vector3d::UnitZ();
  const double theta = std::clamp(std::atan2(p.z() - spec.straight_start_mm, spec.bend_radius_mm - p.x()), 0.0,
                                  spec.bend_angle_rad);
  return Eigen::Vector3d(std::sin(theta), 0.0, std::cos(theta));
}

SkeletonSliceOptions Limits(double h_min, double h_max) {
  SkeletonSliceOptions options;
  options.h_min_mm = h_min;
  options.h_max_mm = h_max;
  return options;
}

TEST(BentTube, ClosedOutwardAndVolumeOfTheWall) {
  const BentTubeSpec spec = TorusSegment(60.0);
  const TubePart tube = BuildBentTube(spec, "test");
  const MeshReport report = InspectMesh(tube.mesh, 1e-6, "tube");
  EXPECT_TRUE(report.watertight) << "the wall mesh must be closed";
  EXPECT_EQ(report.misoriented_edges, 0u);
  // Pappus: wall section area (pi d t for a circle, here a 48-gon) times the axis length.
  const double m = spec.section_points;
  const double polygon = 0.5 * m * std::sin(2.0 * kPi / m);  // area of the unit-circumradius m-gon
  const double r = 0.5 * spec.diameter_start_mm;
  const double ring = polygon * (std::pow(r + 2.0, 2) - std::pow(r - 2.0, 2));
  const double length = spec.straight_start_mm + spec.bend_radius_mm * spec.bend_angle_rad;
  EXPECT_NEAR(report.volume_mm3, ring * length, 0.002 * ring * length) << "outward normals give a positive volume";
  EXPECT_NEAR(tube.extent_in_bend_plane_mm, 60.0, 1e-9);
}

TEST(SkeletonSlicer, TorusSegmentLayersWithinLimitsAndPerpendicularToTheAxis) {
  const BentTubeSpec spec = TorusSegment(60.0);
  const TubePart tube = BuildBentTube(spec, "test");
  const SkeletonSlicing slicing = SliceAlongSkeleton(tube.mesh, Limits(1.0, 2.0), nullptr);
  ASSERT_GT(slicing.layers.size(), 50u);
  EXPECT_EQ(slicing.out_of_range_layers, 0);
  EXPECT_NEAR(slicing.wall_mm, 4.0, 0.05) << "wall measured on the base cut";
  for (std::size_t i = 0; i + 1 < slicing.layers.size(); ++i) {  // the last layer may end thinner at the top face
    const SkeletonLayer& layer = slicing.layers[i];
    EXPECT_GE(layer.min_height_mm, 1.0 * 0.99) << "layer " << i << " thinner than h_min";
    EXPECT_LE(layer.max_height_mm, 2.0 * 1.01) << "layer " << i << " thicker than h_max";
    const double angle = std::acos(std::clamp(layer.normal_P.dot(AxisTangentNear(spec, layer.centroid_P)), -1.0, 1.0));
    EXPECT_LT(angle, 0.5 * kPi / 180.0) << "layer " << i << " plane not perpendicular to the axis within 0.5 deg";
  }
  // The inner wall (towards the bend centre) is thinner than the outer one by (R - d/2) / (R + d/2) in the bend.
  const SkeletonLayer& mid = slicing.layers[slicing.layers.size() / 2];
  EXPECT_NEAR(mid.min_height_mm / mid.max_height_mm, (200.0 - 30.0) / (200.0 + 30.0), 0.02);
  // The last normal is the end tangent.
  EXPECT_GT(slicing.layers.back().normal_P.dot(AxisTangentNear(spec, Eigen::Vector3d(1e3, 0, 1e3))), std::cos(0.01));
}

TEST(SkeletonSlicer, TightestBendMeasuredOnTheCentroidChain) {
  const BentTubeSpec spec = TorusSegment(60.0);
  const SkeletonSlicing slicing = SliceAlongSkeleton(BuildBentTube(spec, "test").mesh, Limits(1.0, 2.0), nullptr);
  const BendEstimate bend = EstimateTightestBend(slicing, 3);
  EXPECT_NEAR(bend.radius_mm, 200.0, 4.0) << "the axis extracted from the mesh bends like the generator's";
  EXPECT_NEAR(bend.extent_mm, 60.0, 1.0) << "mid-wall section extent in the bend plane";
}

TEST(SkeletonSlicer, PositionerTurnsEveryLayerNormalUp) {
  const SkeletonSlicing slicing =
      SliceAlongSkeleton(BuildBentTube(TorusSegment(60.0), "test").mesh, Limits(1.0, 2.0), nullptr);
  const Positioner positioner;
  PositionerAngles angles;
  for (std::size_t i = 0; i < slicing.layers.size(); ++i) {
    const Eigen::Vector3d& n = slicing.layers[i].normal_P;
    angles = SolvePositionerAngles(positioner, n, angles);
    const Eigen::Vector3d up = PartPose(positioner, angles.tilt, angles.rotation).linear() * n;
    EXPECT_FALSE(angles.at_limit) << "layer " << i;
    EXPECT_NEAR(up.z(), 1.0, 1e-9) << "layer " << i << ": the normal must point up after the positioner turns";
  }
}

TEST(SkeletonSlicer, PastTheTiltRangeTheTorchTakesTheRest) {
  // A 90 deg bend leans the last normals past the 70 deg tilt limit: the positioner stops there and the rest is
  // left as torch tilt (residual).
  const SkeletonSlicing slicing =
      SliceAlongSkeleton(BuildBentTube(TorusSegment(90.0), "test").mesh, Limits(1.0, 2.0), nullptr);
  const Positioner positioner;
  PositionerAngles angles;
  int at_limit = 0;
  for (const SkeletonLayer& layer : slicing.layers) {
    angles = SolvePositionerAngles(positioner, layer.normal_P, angles);
    const double lean = std::acos(std::clamp(layer.normal_P.z(), -1.0, 1.0));
    const double expected = std::max(0.0, lean - positioner.tilt_upper);
    EXPECT_NEAR(angles.residual_rad, expected, 1e-6);
    at_limit += angles.at_limit ? 1 : 0;
  }
  EXPECT_GT(at_limit, 0) << "layers beyond 70 deg lean must be flagged at the tilt limit";
}

TEST(SkeletonPlanner, SpiralIsOnePassAndLayersArePerLayerPasses) {
  const SkeletonSlicing slicing =
      SliceAlongSkeleton(BuildBentTube(TorusSegment(45.0), "test").mesh, Limits(1.0, 2.0), nullptr);
  const auto speed_height = models::SpeedHeightModel::Load(models::DefaultModelPath("speed_height"));
  const auto width_height = models::WidthHeightModel::Load(models::DefaultModelPath("width_height"));
  SkeletonPathOptions options;
  options.spiral = true;
  const Plan spiral = BuildSkeletonPlan(slicing, speed_height, width_height, options, "spiral");
  const PathStats s = ComputeStats(spiral);
  EXPECT_EQ(s.passes, 1u) << "the spiral welds the whole part in one pass";
  EXPECT_EQ(spiral.layers.size(), slicing.layers.size() + 1) << "rise loop, blended loops, closing loop";
  EXPECT_DOUBLE_EQ(s.travel_length_mm, 0.0);
  // Continuous: no jump longer than about two point spacings anywhere, also across loops.
  const PathPoint* prev = nullptr;
  for (const LayerPath& layer : spiral.layers) {
    for (const PathPoint& p : layer.points) {
      if (prev) {
        EXPECT_LT((p.p_P - prev->p_P).norm(), 4.0) << "loop " << layer.index;
      }
      prev = &p;
    }
  }
  options.spiral = false;
  const Plan layers = BuildSkeletonPlan(slicing, speed_height, width_height, options, "layers");
  const PathStats d = ComputeStats(layers);
  EXPECT_EQ(d.passes, slicing.layers.size()) << "one closed pass per layer";
  // Per point: slower where the layer is thicker (eq. 6.6), wider with it (eq. 6.7), points about 2 mm apart.
  const LayerPath& mid = layers.layers[layers.layers.size() / 2];
  const PathPoint* thick = &mid.points[1];
  const PathPoint* thin = &mid.points[1];
  for (std::size_t i = 1; i < mid.points.size(); ++i) {
    const PathPoint& p = mid.points[i];
    EXPECT_NEAR((p.p_P - mid.points[i - 1].p_P).norm(), 2.0, 0.2);
    if (p.bead_height_mm > thick->bead_height_mm) thick = &p;
    if (p.bead_height_mm < thin->bead_height_mm) thin = &p;
  }
  EXPECT_LT(thick->speed_mm_s, thin->speed_mm_s);
  EXPECT_GT(thick->bead_width_mm, thin->bead_width_mm);
  // The walls of Fig. 64 are the mid curve shifted by -+ w/2: their area is about length x mean width.
  ASSERT_EQ(mid.slice.size(), 1u);
  EXPECT_EQ(mid.slice[0].holes.size(), 1u);
}

TEST(SkeletonPlanner, BendRuleRejectsATooTightBend) {
  // eq. 6.4: with layers of 1-2 mm a 100 mm section needs R >= 150 mm.
  EXPECT_NEAR(MinimumBendRadius(100.0, 1.0, 2.0), 150.0, 1e-9);
  EXPECT_NO_THROW(CheckBendRule(150.0, 100.0, 1.0, 2.0, "part"));
  try {
    CheckBendRule(120.0, 100.0, 1.0, 2.0, "part");
    FAIL() << "a 120 mm bend of a 100 mm tube must be rejected";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("bend radius 120 mm is tighter than R_min = 150 mm"));
    EXPECT_THAT(e.what(), HasSubstr("eq. 6.4"));
  }
}

}  // namespace
}  // namespace waam::planner
