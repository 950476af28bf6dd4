// Tests of the cell's file reader: a cell.mjcf's meshes and included MJCF reach MuJoCo through its virtual file
// system (the twin opens no file), found under the compiler's meshdir; a URDF arm's meshes likewise.
#include "analysis/cell_files.h"

#include <algorithm>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "analysis/stl_file.h"
#include "models/core/error.h"
#include "models/core/files.h"
#include "planner/mesh/generators.h"
#include "tests/analysis/cli_test_util.h"

namespace waam::analysis {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;

// The built-in cell with a 20 mm cube (binary STL in mm, scaled to metres) on the flange, declared in an included
// file and found under the compiler's meshdir.
fs::path CellWithIncludedMesh(const fs::path& dir) {
  WriteStlBinary(planner::GeneratePart("box", {{"size_mm", {20, 20, 20}}}, "cube"), dir / "meshes" / "cube.stl");
  WriteFileAtomic(dir / "parts.xml",
                  "<mujoco>\n  <asset>\n    <mesh name=\"cube\" file=\"cube.stl\" scale=\"0.001 0.001 0.001\"/>\n"
                  "  </asset>\n</mujoco>\n");
  std::string xml = ReadFile(BuiltinCellPath());
  const std::size_t compiler = xml.find("<compiler");
  EXPECT_NE(compiler, std::string::npos);
  xml.insert(compiler + std::string("<compiler").size(), " meshdir=\"meshes\"");
  xml.insert(compiler, "<include file=\"parts.xml\"/>\n  ");
  const std::size_t link6 = xml.find("<body name=\"link6\"");
  EXPECT_NE(link6, std::string::npos);
  xml.insert(xml.find('>', link6) + 1, "<geom name=\"cube_geom\" type=\"mesh\" mesh=\"cube\" contype=\"0\" "
                                       "conaffinity=\"0\"/>");
  WriteFileAtomic(dir / "cell.xml", xml);
  return dir / "cell.xml";
}

TEST(CellFiles, MjcfMeshesAndIncludesAreReadForMujoco) {
  const fs::path dir = cli_test::TempDir("cell_files_mesh");
  const twin::MjcfSource source = ReadMjcf(CellWithIncludedMesh(dir));
  ASSERT_EQ(source.assets.size(), 2u) << "the included file and the mesh it names";
  EXPECT_EQ(source.assets[0].first, "parts.xml");
  EXPECT_EQ(source.assets[1].first, "cube.stl");
  EXPECT_EQ(source.assets[1].second, ReadFile(dir / "meshes" / "cube.stl"));

  const twin::CellModel cell(source);
  int meshes = 0;
  for (const twin::CellBody& body : cell.Bodies()) {
    for (std::size_t g = 0; g < body.geoms.size(); ++g) {
      if (body.geoms[g].type != twin::CellShape::Type::kMesh) continue;
      ++meshes;
      // MuJoCo centres the cube on its centre of mass: every corner half a diagonal, 10 sqrt(3) mm, away.
      const std::vector<Eigen::Vector3f>& v = body.mesh_vertices_mm[g];
      ASSERT_EQ(v.size(), 8u);
      for (const Eigen::Vector3f& p : v) EXPECT_NEAR(p.norm(), 10.0 * std::sqrt(3.0), 1e-3);
    }
  }
  EXPECT_EQ(meshes, 1);
}

TEST(CellFiles, MjcfFileMissingIsNamed) {
  const fs::path dir = cli_test::TempDir("cell_files_missing");
  EXPECT_THAT([&] { ReadMjcf(dir / "nothere.xml"); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("nothere.xml: MJCF cell model not found")));
}

}  // namespace
}  // namespace waam::analysis
