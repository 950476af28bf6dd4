// End-to-end tests of `waam generate` and `waam inspect` through the built executable: exit codes and output.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <sys/wait.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/files.h"
#include "planner/mesh/generators.h"
#include "analysis/stl_file.h"
#include "tests/planner/mesh_test_util.h"

namespace waam::planner {
namespace {

using ::testing::HasSubstr;
using testing::TestDir;
using testing::WriteBytes;

// The CLI exit codes and output, through the built executable.
int RunWaam(const std::string& args, const std::filesystem::path& out, const std::filesystem::path& err) {
  const std::string command = std::string(WAAM_BINARY) + " " + args + " >" + out.string() + " 2>" + err.string();
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(StlIoCli, GenerateThenInspectPrintsAWatertightReport) {
  const std::filesystem::path dir = TestDir();
  const std::filesystem::path stl = dir / "plate.stl";
  ASSERT_EQ(RunWaam("generate plate_with_holes --param size_mm=100,80,10 --param hole_diameters_mm=20 "
                "--param hole_centers_mm=0,0 -o " + stl.string(), dir / "out1", dir / "err1"), 0)
      << ReadFile(dir / "err1");
  ASSERT_EQ(RunWaam("inspect " + stl.string(), dir / "out2", dir / "err2"), 0) << ReadFile(dir / "err2");
  const std::string json = ReadFile(dir / "out2");
  EXPECT_THAT(json, HasSubstr("\"watertight\": true"));
  EXPECT_THAT(json, HasSubstr("\"sliceable\": true"));
}

TEST(StlIoCli, OpenMeshIsReportedThenRefusedWithCodeTwo) {
  const std::filesystem::path dir = TestDir();
  TriangleMesh box = GeneratePart("box", {}, "test");
  box.facets.pop_back();
  analysis::WriteStlBinary(box, dir / "open.stl");
  EXPECT_EQ(RunWaam("inspect " + (dir / "open.stl").string(), dir / "out", dir / "err"), 2);
  EXPECT_THAT(ReadFile(dir / "out"), HasSubstr("\"watertight\": false"));
  EXPECT_THAT(ReadFile(dir / "out"), HasSubstr("\"boundary_edges\": 3"));
  EXPECT_THAT(ReadFile(dir / "err"), HasSubstr("open.stl: the mesh is open: 3 boundary edges"));
}

TEST(StlIoCli, BadMeshExitsWithCodeTwoAndOneLine) {
  const std::filesystem::path dir = TestDir();
  WriteBytes(dir / "empty.stl", "");
  EXPECT_EQ(RunWaam("inspect " + (dir / "empty.stl").string(), dir / "out", dir / "err"), 2);
  const std::string err = ReadFile(dir / "err");
  EXPECT_THAT(err, HasSubstr("waam: error: "));
  EXPECT_THAT(err, HasSubstr("empty.stl: the file is empty"));
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << "expected one line, got: " << err;
  EXPECT_EQ(RunWaam("generate --help", dir / "out", dir / "err"), 0);
  EXPECT_THAT(ReadFile(dir / "out"), HasSubstr("ding_a"));
  EXPECT_EQ(RunWaam("generate box --param size_mm -o " + (dir / "x.stl").string(), dir / "out", dir / "err"), 2);
  EXPECT_THAT(ReadFile(dir / "err"), HasSubstr("--param 'size_mm': expected key=v1[,v2,...]"));
  EXPECT_EQ(RunWaam("generate box --param size=1 -o " + (dir / "x.stl").string(), dir / "out", dir / "err"), 2);
  EXPECT_THAT(ReadFile(dir / "err"), HasSubstr("unknown parameter 'size' for generator box"));
  EXPECT_FALSE(std::filesystem::exists(dir / "x.stl"));
}

// --param's values, like every list option's, are comma or space separated; an empty value between two commas is not.
TEST(StlIoCli, GenerateParamValuesCommaOrSpaceSeparated) {
  const std::filesystem::path dir = TestDir();
  const std::string comma = (dir / "comma.stl").string();
  ASSERT_EQ(RunWaam("generate box --param size_mm=30,20,4 -o " + comma, dir / "out", dir / "err"), 0)
      << ReadFile(dir / "err");
  for (const std::string values : {"'size_mm=30 20 4'", "'size_mm=30, 20,4 '", "'size_mm=30  20 , 4'"}) {
    const std::string spaced = (dir / "spaced.stl").string();
    ASSERT_EQ(RunWaam("generate box --param " + values + " -o " + spaced, dir / "out", dir / "err"), 0)
        << values << ": " << ReadFile(dir / "err");
    EXPECT_EQ(ReadFile(spaced), ReadFile(comma)) << values << " builds the same box as size_mm=30,20,4";
  }
  EXPECT_EQ(RunWaam("generate box --param size_mm=30,,4 -o " + (dir / "x.stl").string(), dir / "out", dir / "err"), 2);
  EXPECT_THAT(ReadFile(dir / "err"), HasSubstr("--param 'size_mm=30,,4': '' is not a number"));
}

}  // namespace
}  // namespace waam::planner
