// Tests of the STL reader/writers: round trips, welding, the mesh report and every bad-input message.
#include "planner/mesh/stl_io.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <random>
#include <algorithm>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "analysis/stl_file.h"
#include "models/core/error.h"
#include "models/core/files.h"
#include "planner/mesh/generators.h"
#include "planner/mesh/mesh_ops.h"
#include "planner/slicing/planar_slicer.h"
#include "tests/planner/mesh_test_util.h"

namespace waam::planner {
namespace {

using ::testing::HasSubstr;
using testing::TestDir;
using testing::WriteBytes;
using testing::ReadStl;

// A binary STL image: `header` (up to 80 bytes), a facet count and the facets (9 floats each).
std::string BinaryStl(const std::vector<std::array<float, 9>>& facets, std::uint32_t count, const std::string& header) {
  std::string bytes(80, ' ');
  std::memcpy(bytes.data(), header.data(), std::min<std::size_t>(header.size(), 80));
  bytes.append(reinterpret_cast<const char*>(&count), 4);
  for (const auto& f : facets) {
    const float normal[3] = {0, 0, 0};
    bytes.append(reinterpret_cast<const char*>(normal), 12);
    bytes.append(reinterpret_cast<const char*>(f.data()), 36);
    bytes.append(2, '\0');
  }
  return bytes;
}

const std::array<float, 9> kFacet = {0, 0, 0, 1, 0, 0, 0, 1, 0};

std::string StlErrorOf(const std::filesystem::path& path, double weld_tol_mm = 1e-4) {
  try {
    ReadStl(path, weld_tol_mm, nullptr);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(StlIo, BinaryRoundTripKeepsTopologyAndVolume) {
  const std::filesystem::path file = TestDir() / "ding_b.stl";
  const TriangleMesh mesh = GeneratePart("ding_b", {}, "test");
  analysis::WriteStlBinary(mesh, file);
  EXPECT_EQ(std::filesystem::file_size(file), 84 + 50 * mesh.facets.size());
  MeshReport report;
  const TriangleMesh back = ReadStl(file, 1e-4, &report);
  EXPECT_TRUE(report.binary);
  EXPECT_EQ(report.facets_read, mesh.facets.size());
  EXPECT_EQ(back.facets.size(), mesh.facets.size());
  EXPECT_EQ(back.vertices.size(), mesh.vertices.size()) << "welding must recover the shared vertices";
  EXPECT_TRUE(report.watertight);
  EXPECT_EQ(report.misoriented_edges, 0u);
  EXPECT_NEAR(report.volume_mm3, EnclosedVolume(mesh), 1e-5 * EnclosedVolume(mesh));
  EXPECT_NEAR(report.bbox_max.z(), 30.0, 1e-5);
  CheckSliceable(report);
}

TEST(StlIo, AsciiRoundTripKeepsTopologyAndVolume) {
  const std::filesystem::path file = TestDir() / "torus.stl";
  const TriangleMesh mesh = GeneratePart("torus", {{"major_segments", {24}}, {"minor_segments", {12}}}, "test");
  analysis::WriteStlAscii(mesh, file, "torus");
  MeshReport report;
  const TriangleMesh back = ReadStl(file, 1e-4, &report);
  EXPECT_FALSE(report.binary);
  EXPECT_EQ(back.facets.size(), mesh.facets.size());
  EXPECT_EQ(back.vertices.size(), mesh.vertices.size());
  EXPECT_TRUE(report.watertight);
  EXPECT_NEAR(report.volume_mm3, EnclosedVolume(mesh), 1e-6 * EnclosedVolume(mesh));
}

TEST(StlIo, BinaryFileWhoseHeaderStartsWithSolidIsReadAsBinary) {
  const std::filesystem::path file = TestDir() / "solid_header.stl";
  WriteBytes(file, BinaryStl({kFacet}, 1, "solid this is really binary"));
  MeshReport report;
  ReadStl(file, 0.0, &report);
  EXPECT_TRUE(report.binary);
  EXPECT_EQ(report.facets, 1u);
  EXPECT_EQ(report.boundary_edges, 3u);
  EXPECT_FALSE(report.watertight);
}

TEST(StlIo, WeldsWithinToleranceOnlyAndDropsDegenerateFacets) {
  const std::filesystem::path file = TestDir() / "weld.stl";
  // Two triangles sharing an edge whose copies differ by 1e-5 mm, plus a facet with a repeated vertex.
  WriteBytes(file,
             "solid w\n"
             "facet normal 0 0 1\n outer loop\n  vertex 0 0 0\n  vertex 1 0 0\n  vertex 0 1 0\n endloop\nendfacet\n"
             "facet normal 0 0 1\n outer loop\n  vertex 1.00001 0 0\n  vertex 1 1 0\n  vertex 0 1.00001 0\n endloop\n"
             "endfacet\n"
             "facet normal 0 0 1\n outer loop\n  vertex 5 5 5\n  vertex 5 5 5\n  vertex 6 5 5\n endloop\nendfacet\n"
             "endsolid w\n");
  MeshReport welded;
  const TriangleMesh a = ReadStl(file, 1e-4, &welded);
  EXPECT_EQ(a.vertices.size(), 4u) << "the square's 4 corners; the degenerate facet's vertices are removed";
  EXPECT_EQ(welded.facets_read, 3u);
  EXPECT_EQ(welded.degenerate_facets, 1u);
  EXPECT_EQ(welded.facets, 2u);
  EXPECT_EQ(welded.boundary_edges, 4u) << "the shared diagonal is welded";
  MeshReport exact;
  ReadStl(file, 0.0, &exact);
  EXPECT_EQ(exact.boundary_edges, 6u) << "with tolerance 0 the 1e-5 mm gap stays open";
}

// WeldTriangles against the rule its header states, applied corner by corner with a search over every earlier
// vertex: each corner joins the lowest-numbered vertex within the tolerance, else becomes a new one. A seeded soup
// with bit-identical repeats, -0 and +0, points just inside and just outside the tolerance, in shuffled order.
TEST(StlIo, WeldMatchesTheCornerByCornerRule) {
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> pick(0, 59);
  std::uniform_real_distribution<double> jitter(-0.8, 0.8);
  std::vector<Eigen::Vector3d> base;
  for (int i = 0; i < 60; ++i) base.emplace_back(i % 4, (i / 4) % 5, i / 20);
  base[0] = Eigen::Vector3d(-0.0, 0.0, -0.0);  // and base[59] the same point with +0
  base[59] = Eigen::Vector3d(0.0, 0.0, 0.0);
  const double tol = 0.01;
  std::vector<Eigen::Vector3d> corners;
  for (int f = 0; f < 400; ++f) {
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector3d p = base[pick(rng)];
      if (f % 3 == 1) p += Eigen::Vector3d(jitter(rng), jitter(rng), jitter(rng)) * tol;  // within tol or not
      corners.push_back(p);
    }
  }
  // The rule, corner by corner.
  std::vector<Eigen::Vector3d> vertices;
  std::vector<int> id_of(corners.size());
  for (std::size_t c = 0; c < corners.size(); ++c) {
    int id = -1;
    for (std::size_t v = 0; v < vertices.size() && id < 0; ++v) {
      if ((vertices[v] - corners[c]).squaredNorm() <= tol * tol) id = static_cast<int>(v);
    }
    if (id < 0) {
      id = static_cast<int>(vertices.size());
      vertices.push_back(corners[c]);
    }
    id_of[c] = id;
  }
  std::size_t degenerate = 0;
  const TriangleMesh mesh = WeldTriangles(corners, tol, &degenerate);
  std::size_t kept = 0;
  for (std::size_t f = 0; f < corners.size() / 3; ++f) {
    const std::array<int, 3> ids = {id_of[3 * f], id_of[3 * f + 1], id_of[3 * f + 2]};
    if (ids[0] == ids[1] || ids[1] == ids[2] || ids[0] == ids[2] ||
        IsDegenerateFacet(vertices[ids[0]], vertices[ids[1]], vertices[ids[2]])) {
      continue;
    }
    ASSERT_LT(kept, mesh.facets.size());
    for (int k = 0; k < 3; ++k) {
      ASSERT_EQ(mesh.vertices[mesh.facets[kept][k]], vertices[ids[k]]) << "facet " << f << " corner " << k;
    }
    ++kept;
  }
  EXPECT_EQ(kept, mesh.facets.size());
  EXPECT_EQ(degenerate, corners.size() / 3 - kept);
  EXPECT_GT(kept, 100u);
  EXPECT_LT(vertices.size(), corners.size() / 2) << "the soup must repeat points";
}

TEST(StlIo, ReportsMisorientedFacetsButStaysSliceable) {
  TriangleMesh box = GeneratePart("box", {}, "test");
  std::swap(box.facets[0][1], box.facets[0][2]);
  const MeshReport report = InspectMesh(box, 0.0, "flipped box");
  EXPECT_EQ(report.misoriented_edges, 3u);
  EXPECT_TRUE(report.watertight);
  CheckSliceable(report);
}

TEST(StlIo, CheckSliceableRefusesOpenNonManifoldAndEmptyMeshes) {
  TriangleMesh open = GeneratePart("box", {}, "test");
  open.facets.pop_back();
  try {
    CheckSliceable(InspectMesh(open, 1e-4, "open.stl"));
    FAIL() << "expected an open-mesh error";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("open.stl"));
    EXPECT_THAT(e.what(), HasSubstr("open: 3 boundary edges"));
  }
  TriangleMesh fin = GeneratePart("box", {}, "test");
  fin.vertices.emplace_back(0.0, 0.0, 100.0);
  fin.facets.push_back({fin.facets[0][0], fin.facets[0][1], static_cast<int>(fin.vertices.size()) - 1});
  try {
    CheckSliceable(InspectMesh(fin, 1e-4, "fin.stl"));
    FAIL() << "expected a non-manifold error";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("fin.stl"));
    EXPECT_THAT(e.what(), HasSubstr("non-manifold"));
  }
  MeshReport empty;
  empty.source = "empty.stl";
  try {
    CheckSliceable(empty);
    FAIL() << "expected an empty-mesh error";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("empty.stl: the mesh has no facets"));
  }
}

TEST(StlIoErrors, EmptyFile) {
  const std::filesystem::path file = TestDir() / "empty.stl";
  WriteBytes(file, "");
  EXPECT_THAT(StlErrorOf(file), HasSubstr("empty.stl: the file is empty"));
}

TEST(StlIoErrors, TooShortForBinaryAndNotAscii) {
  const std::filesystem::path file = TestDir() / "short.stl";
  WriteBytes(file, "hello");
  EXPECT_THAT(StlErrorOf(file), HasSubstr("shorter than the 84-byte binary STL header"));
}

TEST(StlIoErrors, TruncatedBinaryNamesTheFacet) {
  const std::filesystem::path file = TestDir() / "truncated.stl";
  std::string bytes = BinaryStl({kFacet, kFacet, kFacet}, 3, "binary");
  bytes.resize(84 + 50 + 20);  // ends 20 bytes into facet 2
  WriteBytes(file, bytes);
  const std::string message = StlErrorOf(file);
  EXPECT_THAT(message, HasSubstr("truncated.stl: truncated binary STL"));
  EXPECT_THAT(message, HasSubstr("ends inside facet 2"));
}

TEST(StlIoErrors, TruncatedBinaryAtAFacetBoundary) {
  const std::filesystem::path file = TestDir() / "short_count.stl";
  std::string bytes = BinaryStl({kFacet, kFacet}, 5, "binary");
  WriteBytes(file, bytes);
  EXPECT_THAT(StlErrorOf(file), HasSubstr("header says 5 facets (334 bytes) but the file has 184 bytes; it ends after "
                                       "facet 2"));
}

TEST(StlIoErrors, HeaderCountDisagreesWithFileSize) {
  const std::filesystem::path file = TestDir() / "long.stl";
  std::string bytes = BinaryStl({kFacet, kFacet}, 1, "binary");  // 2 facets present, header says 1
  WriteBytes(file, bytes);
  EXPECT_THAT(StlErrorOf(file), HasSubstr("header facet count 1 disagrees with the file size 184 bytes"));
}

TEST(StlIoErrors, AbsurdHeaderCountIsRefusedWithoutAllocating) {
  const std::filesystem::path file = TestDir() / "huge.stl";
  WriteBytes(file, BinaryStl({kFacet}, 2'000'000'000u, "binary"));
  EXPECT_THAT(StlErrorOf(file), HasSubstr("header claims 2000000000 facets, more than the limit of 20000000"));
}

TEST(StlIoErrors, NonFiniteBinaryCoordinateNamesTheFacet) {
  const std::filesystem::path file = TestDir() / "nan.stl";
  std::array<float, 9> bad = kFacet;
  bad[4] = std::numeric_limits<float>::quiet_NaN();
  WriteBytes(file, BinaryStl({kFacet, bad}, 2, "binary"));
  const std::string message = StlErrorOf(file);
  EXPECT_THAT(message, HasSubstr("nan.stl: binary STL facet 2 of 2: vertex 2 has a non-finite coordinate"));
  std::array<float, 9> inf = kFacet;
  inf[0] = std::numeric_limits<float>::infinity();
  WriteBytes(file, BinaryStl({inf}, 1, "binary"));
  EXPECT_THAT(StlErrorOf(file), HasSubstr("facet 1 of 1: vertex 1 has a non-finite coordinate"));
}

TEST(StlIoErrors, AbsurdCoordinatesAreRefused) {
  const std::filesystem::path file = TestDir() / "far.stl";
  std::array<float, 9> far = kFacet;
  far[8] = 3e20f;
  WriteBytes(file, BinaryStl({far}, 1, "binary"));
  EXPECT_THAT(StlErrorOf(file), HasSubstr("far.stl: binary STL facet 1 of 1: vertex 3 coordinate 3e+20 mm is beyond"));
  WriteBytes(file, "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 -2e7\n");
  EXPECT_THAT(StlErrorOf(file), HasSubstr("far.stl: ASCII STL line 6: vertex z -2e+07 mm is beyond"));
}

TEST(StlIoErrors, NonFiniteAsciiCoordinateNamesTheLine) {
  const std::filesystem::path file = TestDir() / "nan_ascii.stl";
  WriteBytes(file, "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 nan 0\nvertex 0 1 0\nendloop\n"
                   "endfacet\nendsolid s\n");
  EXPECT_THAT(StlErrorOf(file), HasSubstr("nan_ascii.stl: ASCII STL line 5: vertex y 'nan' is not finite"));
}

TEST(StlIoErrors, AsciiSyntaxErrorsNameTheLine) {
  const std::filesystem::path file = TestDir() / "syntax.stl";
  WriteBytes(file, "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\n");
  EXPECT_THAT(StlErrorOf(file), HasSubstr("syntax.stl: ASCII STL line 6: expected 'vertex'"));
  WriteBytes(file, "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 zero 0\n");
  EXPECT_THAT(StlErrorOf(file), HasSubstr("line 5: expected a number for vertex y, found 'zero'"));
  WriteBytes(file, "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\n");
  EXPECT_THAT(StlErrorOf(file), HasSubstr("expected 'endfacet' after 'endloop', found the end of file"));
  WriteBytes(file, "solid s\n  facett normal 0 0 1\n");
  EXPECT_THAT(StlErrorOf(file), HasSubstr("line 2: expected 'facet' or 'endsolid', found 'facett'"));
}

TEST(StlIoErrors, NoUsableFacet) {
  const std::filesystem::path file = TestDir() / "degenerate.stl";
  const std::array<float, 9> line = {0, 0, 0, 1, 1, 1, 2, 2, 2};
  WriteBytes(file, BinaryStl({line, line}, 2, "binary"));
  EXPECT_THAT(StlErrorOf(file), HasSubstr("degenerate.stl: no usable facet: 2 facets read, 2 degenerate"));
}

TEST(StlIoErrors, WeldToleranceOutOfRange) {
  const std::filesystem::path file = TestDir() / "any.stl";
  WriteBytes(file, BinaryStl({kFacet}, 1, "binary"));
  EXPECT_THAT(StlErrorOf(file, -1.0), HasSubstr("weld tolerance -1 mm: must be between 0 and 10 mm"));
}

TEST(StlIoErrors, MissingFile) {
  EXPECT_THAT(StlErrorOf(TestDir() / "missing.stl"), HasSubstr("missing.stl"));
}

TEST(StlIoErrors, CorruptedFilesGiveAMeshOrAnInputErrorNeverACrash) {
  // Seeded random byte damage and truncation of a binary and an ASCII file; every outcome must be a usable mesh
  // (then sliceable or refused by CheckSliceable) or an InputError naming the file.
  const std::filesystem::path dir = TestDir();
  const TriangleMesh mesh = GeneratePart("ding_b", {{"segments", {8}}}, "test");
  analysis::WriteStlBinary(mesh, dir / "b.stl");
  analysis::WriteStlAscii(mesh, dir / "a.stl", "a");
  std::mt19937_64 rng(42);
  for (const char* name : {"b.stl", "a.stl"}) {
    const std::string original = ReadFile(dir / name);
    for (int trial = 0; trial < 150; ++trial) {
      std::string bytes = original;
      std::uniform_int_distribution<std::size_t> at(0, bytes.size() - 1);
      const int damage = trial % 3;
      if (damage == 0) bytes.resize(at(rng));
      for (int k = 0; k < 1 + trial % 5 && damage > 0; ++k) {
        bytes[at(rng)] = damage == 1 ? static_cast<char>(rng() & 0xff) : "0123456789.-e nan"[rng() % 17];
      }
      const std::filesystem::path file = dir / "damaged.stl";
      WriteBytes(file, bytes);
      try {
        MeshReport report;
        const TriangleMesh back = ReadStl(file, 1e-4, &report);
        ASSERT_FALSE(back.facets.empty());
        try {
          CheckSliceable(report);
          SliceReport slice_report;
          SlicePlanar(back, {1.0, 15.0}, &slice_report);
        } catch (const InputError& e) {
          EXPECT_THAT(e.what(), HasSubstr("damaged.stl"));
        }
      } catch (const InputError& e) {
        EXPECT_THAT(e.what(), HasSubstr("damaged.stl")) << "trial " << trial << " of " << name;
      }
    }
  }
}

}  // namespace
}  // namespace waam::planner
