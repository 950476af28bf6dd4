// Tests of the scan readers (PLY ascii/binary, XYZ), the ovality of eq. 6.5 and the central axis of a point cloud.
#include "models/core/numbers.h"
#include "analysis/point_cloud_file.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <Eigen/Geometry>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/error.h"
#include "twin/scanner/scan_deviation.h"

namespace waam::twin {
namespace {

using ::testing::HasSubstr;
using analysis::ReadPointCloud;
using analysis::WritePlyWithDeviation;

std::filesystem::path Write(const std::string& name, const std::string& text) {
  const std::filesystem::path p = std::filesystem::path(::waam_test_env::TempDir()) / ("waam_scan_io_" + name);
  std::ofstream(p, std::ios::binary) << text;
  return p;
}

TEST(PointCloud, ReadsAsciiPlyWithExtraPropertiesAndFaces) {
  const auto p = Write("a.ply",
                       "ply\nformat ascii 1.0\ncomment x\nelement vertex 3\nproperty float x\nproperty float y\n"
                       "property float z\nproperty uchar red\nelement face 1\nproperty list uchar int vertex_indices\n"
                       "end_header\n1 2 3 255\n4 5 6 0\n7 8 9 1\n3 0 1 2\n");
  const auto pts = ReadPointCloud(p);
  ASSERT_EQ(pts.size(), 3u);
  EXPECT_EQ(pts[2], Eigen::Vector3d(7, 8, 9));
}

TEST(PointCloud, BinaryPlyRoundTripsTheWriter) {
  const auto p = std::filesystem::path(::waam_test_env::TempDir()) / "waam_scan_io_b.ply";
  WritePlyWithDeviation(p, {{1, 2, 3}, {-4, 5.5, 6}}, {0.5, -0.25});
  const auto pts = ReadPointCloud(p);
  ASSERT_EQ(pts.size(), 2u);
  EXPECT_EQ(pts[1], Eigen::Vector3d(-4, 5.5, 6));
}

TEST(PointCloud, BadInputsNameFileAndLine) {
  EXPECT_THAT([&] { ReadPointCloud(Write("bad.xyz", "1 2 3\n# c\n4 five 6\n")); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("bad.xyz:3: expected three numbers")));
  EXPECT_THAT([&] { ReadPointCloud(Write("nan.xyz", "1 2 nan\n")); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("nan.xyz:1:")));
  EXPECT_THAT([&] { ReadPointCloud(Write("big.ply", "ply\nformat binary_big_endian 1.0\nend_header\n")); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("big.ply:2: PLY format 'binary_big_endian'")));
  EXPECT_THAT([&] {
    ReadPointCloud(Write("short.ply", "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
                                      "property float z\nend_header\n1 2 3\n4 5\n"));
  }, ::testing::ThrowsMessage<InputError>(HasSubstr("short.ply:9: expected 3 values")));
  EXPECT_THAT([&] {
    ReadPointCloud(Write("trunc.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 2\nproperty float x\n"
                                      "property float y\nproperty float z\nend_header\nabcd"));
  }, ::testing::ThrowsMessage<InputError>(HasSubstr("binary PLY truncated")));
  EXPECT_THAT([&] { ReadPointCloud(Write("scan.obj", "v 1 2 3\n")); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("unknown scan format '.obj'")));
}

// Points on an elliptic tube (semi-axes a, b) along the unit direction `dir` from the origin, height h.
std::vector<Eigen::Vector3d> EllipticTube(double a, double b, double h, const Eigen::Vector3d& dir) {
  const Eigen::Vector3d t1 = dir.unitOrthogonal(), t2 = dir.cross(t1);
  std::vector<Eigen::Vector3d> pts;
  for (double s = 0.0; s <= h; s += 0.25) {
    for (int k = 0; k < 360; ++k) {
      const double q = k * kPi / 180.0;
      pts.push_back(s * dir + a * std::cos(q) * t1 + b * std::sin(q) * t2);
    }
  }
  return pts;
}

TEST(ScanDeviation, OvalityOfEquation6_5) {
  EXPECT_NEAR(Ovality(55.0, 45.0), 20.0, 1e-12) << "OV = 200 (55 - 45) / (55 + 45)";
  const auto tube = EllipticTube(27.5, 22.5, 20.0, Eigen::Vector3d::UnitZ());
  AxisStation st;
  st.center = Eigen::Vector3d(0, 0, 10);
  const SectionMeasure m = MeasureSection(tube, st, 1.0, 100.0);
  EXPECT_NEAR(m.d_max_mm, 55.0, 0.1);
  EXPECT_NEAR(m.d_min_mm, 45.0, 0.5);
  EXPECT_NEAR(m.ovality_pct, 20.0, 1.0);
  EXPECT_NEAR(MeasureSection(EllipticTube(25, 25, 20, Eigen::Vector3d::UnitZ()), st, 1.0, 100.0).ovality_pct, 0.0,
              0.2) << "a circle has no ovality";
}

TEST(ScanDeviation, CentralAxisFollowsALeaningTubeAndSeesAShift) {
  // A tube built on a flat substrate that leans along x: horizontal circles of radius 20 centred at (0.3 z, 0, z).
  const Eigen::Vector3d dir = Eigen::Vector3d(0.3, 0.0, 1.0).normalized();
  std::vector<Eigen::Vector3d> tube;
  for (double z = 0.0; z <= 60.0; z += 0.25) {
    for (int k = 0; k < 360; ++k) {
      const double q = k * kPi / 180.0;
      tube.emplace_back(0.3 * z + 20.0 * std::cos(q), 20.0 * std::sin(q), z);
    }
  }
  const auto axis = CentralAxis(tube, 2.0, 1.0);
  ASSERT_GT(axis.size(), 10u);
  EXPECT_GT(axis[axis.size() / 2].normal.dot(dir), 0.99) << "the slicing plane turns normal to the tube axis";
  std::vector<Eigen::Vector3d> shifted = tube;
  for (Eigen::Vector3d& p : shifted) p += Eigen::Vector3d(0, 1.5, 0);
  const AxisComparison c = CompareAxis(tube, shifted, 2.0, 1.0);
  EXPECT_NEAR(c.max_axis_deviation_mm, 1.5, 0.2) << "a tube moved 1.5 mm sideways has its axis 1.5 mm off";
}

}  // namespace
}  // namespace waam::twin
