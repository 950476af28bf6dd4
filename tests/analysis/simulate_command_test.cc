// `waam simulate` outputs on a hand-made plan: the JSON contract, the STL and HDF5 files, the pictures, and the
// voxel-limit error.
#include "analysis/simulate_command.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <gmock/gmock.h>
#include <hdf5.h>
#include <gtest/gtest.h>

#include "models/core/error.h"
#include "analysis/distortion_command.h"
#include "analysis/scenario.h"
#include "analysis/stl_file.h"
#include "twin/scanner/mesh_distance.h"
#include "twin/scanner/surface_sample.h"
#include "models/core/files.h"
#include "tests/analysis/cli_test_util.h"
#include "tests/twin/test_paths.h"

namespace waam::analysis {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using cli_test::RunWaam;

struct Fixture {
  Scenario scenario;
  planner::PlanResult planned;
};

Fixture SmallBlock() {
  Fixture f;
  const double w = 6.0, h = 2.0, l = 0.738 * w;
  f.scenario.name = "small block";
  f.scenario.path.bead_width_mm = w;
  LoadScenarioFiles(&f.scenario);  // the default models, as LoadScenario loads them
  f.planned.plan = twin::testing::ParallelBlock(twin::testing::BlockPositions(0.5 * w, 0.47 * w, l, 3), 30.0, 3,
                                                2.0 / 3.0 * w * h / l, w, h, 8.0);
  const auto& ring = f.planned.plan.layers.back().slice.front().outer;
  f.planned.mesh = twin::testing::BoxMesh({ring[0].x(), 0, 0}, {ring[1].x(), 30.0, f.planned.plan.layers.back().z_mm});
  return f;
}

// The deviation measured on the written part.stl agrees with the deviation simulate.json reports (every exposed voxel
// face of the grid, each of the same area): the merged surface is the voxels' boundary. The file's surface is sampled
// as `waam deviation` samples an STL (the centres of n^2 sub-triangles of each facet, n = longest edge / 0.5 mm),
// each point weighted by its sub-triangle's area, since the merged facets are long slivers that this sampling
// crowds. The facets closing the part at z = 0 are left out, as simulate.json leaves the faces on the substrate out.
// Tolerance: 0.05 mm (a tenth of the 0.5 mm voxel) on rms and mean, one voxel on the extremes, which `waam
// deviation` on the file also gives.
TEST(SimulateCommand, DeviationOfTheWrittenPartStlMatchesSimulateJson) {
  const Fixture f = SmallBlock();
  SimulateOptions options;
  options.out_dir = fs::path(::waam_test_env::TempDir()) / "simulate_stl_deviation";
  options.quiet = true;
  options.images = false;
  SimulatePlanned(f.scenario, f.planned, options);
  const nlohmann::json sim = nlohmann::json::parse(ReadFile(options.out_dir / "simulate.json"));
  const double voxel = sim["voxel_mm"].get<double>();
  ASSERT_EQ(sim["stl_voxel_mm"].get<double>(), voxel) << "part.stl at the simulation's own voxel size";
  DeviationOptions deviation;
  deviation.target = options.out_dir / "target.stl";
  WriteStlBinary(f.planned.mesh, deviation.target);
  deviation.scan = options.out_dir / "part.stl";
  deviation.out_dir = options.out_dir / "deviation";
  deviation.images = false;
  const nlohmann::json command = RunDeviation(deviation);  // the command as a user runs it, on the two files
  const planner::TriangleMesh target = ReadStl(deviation.target, 0.0, nullptr);
  const planner::TriangleMesh part = ReadStl(deviation.scan, 0.0, nullptr);
  const twin::MeshDistance distance(target);
  double area = 0.0, sum = 0.0, sum2 = 0.0;
  for (const auto& t : part.facets) {
    planner::TriangleMesh facet;
    for (const int c : t) facet.vertices.push_back(part.vertices[static_cast<std::size_t>(c)]);
    if (std::max({facet.vertices[0].z(), facet.vertices[1].z(), facet.vertices[2].z()}) < 1e-6) continue;
    facet.facets.push_back({0, 1, 2});
    const std::vector<Eigen::Vector3d> points = twin::SampleSurface(facet, 0.5);
    const double a = 0.5 * (facet.vertices[1] - facet.vertices[0]).cross(facet.vertices[2] - facet.vertices[0]).norm();
    for (const Eigen::Vector3d& p : points) {
      const double d = distance.SignedDistance(p);
      sum += a / static_cast<double>(points.size()) * d;
      sum2 += a / static_cast<double>(points.size()) * d * d;
    }
    area += a;
  }
  const nlohmann::json& grid = sim["deviation"];
  std::printf("part.stl above z = 0, area-weighted: rms %.3f mean %.3f mm; waam deviation on the file: rms %.3f, "
              "min %.3f, max %.3f mm; simulate.json: rms %.3f mean %.3f min %.3f max %.3f mm\n",
              std::sqrt(sum2 / area), sum / area, command["rms_mm"].get<double>(), command["min_mm"].get<double>(),
              command["max_mm"].get<double>(), grid["rms_mm"].get<double>(), grid["mean_mm"].get<double>(),
              grid["min_mm"].get<double>(), grid["max_mm"].get<double>());
  EXPECT_NEAR(std::sqrt(sum2 / area), grid["rms_mm"].get<double>(), 0.1 * voxel);
  EXPECT_NEAR(sum / area, grid["mean_mm"].get<double>(), 0.1 * voxel);
  // The command itself: area-weighted, without the face the part stands on.
  EXPECT_EQ(command["weighting"], "area");
  EXPECT_GT(command["bottom_excluded"]["facets"].get<int>(), 0);
  EXPECT_NEAR(command["rms_mm"].get<double>(), grid["rms_mm"].get<double>(), 0.1 * voxel);
  EXPECT_NEAR(command["mean_mm"].get<double>(), grid["mean_mm"].get<double>(), 0.1 * voxel);
  EXPECT_NEAR(command["max_mm"].get<double>(), grid["max_mm"].get<double>(), voxel);
  EXPECT_NEAR(command["min_mm"].get<double>(), grid["min_mm"].get<double>(), voxel);
}

TEST(SimulateCommand, WritesTheContract) {
  const Fixture f = SmallBlock();
  SimulateOptions options;
  options.out_dir = fs::path(::waam_test_env::TempDir()) / "simulate_contract";
  options.quiet = true;
  const twin::TwinResult result = SimulatePlanned(f.scenario, f.planned, options);
  for (const char* name : {"simulate.json", "part.stl", "part.h5", "top_height.png", "section_xz.png",
                           "section_yz.png", "deviation_map.png"}) {
    EXPECT_TRUE(fs::exists(options.out_dir / name)) << "expected output " << name;
  }
  const nlohmann::json j = nlohmann::json::parse(ReadFile(options.out_dir / "simulate.json"));
  for (const char* key : {"voxel_mm", "deposited_volume_mm3", "expected_volume_mm3", "deviation", "voids",
                          "waviness_mm", "ra_mm", "boundary_lag_mm", "layers"}) {
    EXPECT_TRUE(j.contains(key)) << "simulate.json must contain " << key;
  }
  for (const char* key : {"min_mm", "max_mm", "rms_mm"}) EXPECT_TRUE(j["deviation"].contains(key)) << key;
  for (const char* key : {"count", "volume_mm3", "max_length_mm"}) EXPECT_TRUE(j["voids"].contains(key)) << key;
  for (const char* key : {"mean_mm", "min_mm", "max_mm"}) EXPECT_TRUE(j["top_height"].contains(key)) << key;
  EXPECT_LE(j["top_height"]["min_mm"].get<double>(), j["top_height"]["mean_mm"].get<double>());
  EXPECT_EQ(j["layers"].get<int>(), 3);
  const double deposited = j["deposited_volume_mm3"].get<double>();
  const double expected = j["expected_volume_mm3"].get<double>();
  EXPECT_NEAR(deposited, expected, 0.02 * expected);
  // Binary STL: 84 bytes of header and count, 50 per facet.
  const std::string stl = ReadFile(options.out_dir / "part.stl");
  ASSERT_GE(stl.size(), 84u);
  std::uint32_t facets = 0;
  std::memcpy(&facets, stl.data() + 80, 4);
  EXPECT_GT(facets, 0u);
  EXPECT_EQ(stl.size(), 84u + 50u * facets);
  const std::string h5 = ReadFile(options.out_dir / "part.h5");
  EXPECT_EQ(h5.substr(0, 8), std::string("\x89HDF\r\n\x1a\n", 8)) << "part.h5 must be an HDF5 file";
  // Every dataset chunked and deflated (the file is mailed and archived).
  const hid_t file = H5Fopen((options.out_dir / "part.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  for (const char* name : {"/voxels/ijk", "/voxels/bead", "/voxels/layer", "/voxels/time_s", "/top_height_mm", "/beads"}) {
    const hid_t dataset = H5Dopen2(file, name, H5P_DEFAULT);
    ASSERT_GE(dataset, 0) << name;
    const hid_t create = H5Dget_create_plist(dataset);
    EXPECT_EQ(H5Pget_layout(create), H5D_CHUNKED) << name;
    bool deflate = false;
    for (int i = 0; i < H5Pget_nfilters(create); ++i) {
      unsigned flags = 0;
      std::size_t n = 0;
      deflate |= H5Pget_filter2(create, static_cast<unsigned>(i), &flags, &n, nullptr, 0, nullptr, nullptr) ==
                 H5Z_FILTER_DEFLATE;
    }
    EXPECT_TRUE(deflate) << name << " is not deflated";
    H5Pclose(create);
    H5Dclose(dataset);
  }
  H5Fclose(file);
  EXPECT_EQ(result.measures.voxels, result.depositor.grid().occupied());
}

// Top-surface measures only where they apply: the planar block keeps its numbers; the same block with its top layer
// grown along +x (a multi-directional part) has them null, each with the reason in not_applicable.
TEST(SimulateCommand, TopSurfaceMeasuresAreNullWithAReasonOnAMultiDirectionalPart) {
  Fixture f = SmallBlock();
  SimulateOptions options;
  options.quiet = true;
  options.images = false;
  options.out_dir = fs::path(::waam_test_env::TempDir()) / "simulate_planar";
  SimulatePlanned(f.scenario, f.planned, options);
  const nlohmann::json planar = nlohmann::json::parse(ReadFile(options.out_dir / "simulate.json"));
  EXPECT_TRUE(planar["ra_mm"].is_number()) << planar["ra_mm"];
  EXPECT_TRUE(planar["waviness_mm"].is_number());
  EXPECT_TRUE(planar["not_applicable"].is_object() && planar["not_applicable"].empty()) << planar["not_applicable"];

  f.planned.plan.layers.back().build_dir_P = Eigen::Vector3d::UnitX();
  options.out_dir = fs::path(::waam_test_env::TempDir()) / "simulate_multidir";
  SimulatePlanned(f.scenario, f.planned, options);
  const nlohmann::json multi = nlohmann::json::parse(ReadFile(options.out_dir / "simulate.json"));
  for (const char* key : {"ra_mm", "waviness_mm", "boundary_lag_mm"}) {
    EXPECT_TRUE(multi[key].is_null()) << key << " must be null on a multi-directional part: " << multi[key];
    ASSERT_TRUE(multi["not_applicable"].contains(key)) << key;
    EXPECT_THAT(multi["not_applicable"][key].get<std::string>(), HasSubstr("multi-directional"));
  }
  EXPECT_TRUE(multi["top_height"]["mean_mm"].is_null());
  EXPECT_EQ(multi["deviation"]["rms_mm"], planar["deviation"]["rms_mm"]) << "the deviation applies to any part";
}

// The notes name a layer height the beads do not grow by and a wall thinner than the bead, and nothing otherwise.
TEST(SimulateCommand, NotesNameLayerHeightAndBeadWidthMismatches) {
  Fixture f = SmallBlock();
  f.planned.bead_width_mm = 6.0;
  f.planned.layer_height_mm = 2.0;
  f.planned.layer_growth_mm = 2.05;
  EXPECT_THAT(SimulationNotes(f.planned), ::testing::IsEmpty()) << "a 2.5 % mismatch is no note";
  f.planned.layer_height_mm = 1.8;
  f.planned.layer_growth_mm = 2.6;
  const std::vector<std::string> notes = SimulationNotes(f.planned);
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_THAT(notes[0], HasSubstr("slicing.layer_height_mm"));
  EXPECT_THAT(notes[0], HasSubstr("taller"));
  // A 3 mm wide, 30 mm long wall under the 6 mm bead.
  f.planned.layer_growth_mm = 1.8;
  f.planned.plan.layers.back().slice = {planner::PolygonWithHoles{{{0, 0}, {3, 0}, {3, 30}, {0, 30}}, {}}};
  const std::vector<std::string> wall = SimulationNotes(f.planned);
  ASSERT_EQ(wall.size(), 1u);
  EXPECT_THAT(wall[0], HasSubstr("path.bead_width_mm"));
}

// Identical inputs, identical outputs: the STL bytes and every measure except the timings.
TEST(SimulateCommand, IsDeterministic) {
  const Fixture f = SmallBlock();
  std::string stl[2];
  nlohmann::json json[2];
  for (int run = 0; run < 2; ++run) {
    SimulateOptions options;
    options.out_dir = fs::path(::waam_test_env::TempDir()) / ("simulate_determinism_" + std::to_string(run));
    options.quiet = true;
    options.images = false;
    SimulatePlanned(f.scenario, f.planned, options);
    stl[run] = ReadFile(options.out_dir / "part.stl");
    json[run] = nlohmann::json::parse(ReadFile(options.out_dir / "simulate.json"));
    json[run].erase("performance");
  }
  EXPECT_TRUE(stl[0] == stl[1]) << "part.stl must be byte-identical across runs";
  EXPECT_EQ(json[0], json[1]) << "simulate.json measures must not change between runs";
}

// A plan without weld moves deposits nothing and still writes a complete, zero result.
TEST(SimulateCommand, EmptyPlanGivesAnEmptyPart) {
  Fixture f = SmallBlock();
  for (auto& layer : f.planned.plan.layers) {
    for (auto& p : layer.points) p.weld = false;
  }
  SimulateOptions options;
  options.out_dir = fs::path(::waam_test_env::TempDir()) / "simulate_empty";
  options.quiet = true;
  const twin::TwinResult r = SimulatePlanned(f.scenario, f.planned, options);
  EXPECT_EQ(r.measures.voxels, 0u);
  EXPECT_EQ(r.measures.beads, 0u);
  EXPECT_TRUE(fs::exists(options.out_dir / "simulate.json"));
}

TEST(SimulateCommand, VoxelLimitIsCheckedUpFront) {
  Fixture f = SmallBlock();
  f.scenario.simulation.max_voxels = 5000;
  SimulateOptions options;
  options.scenario = "block.yaml";
  options.out_dir = fs::path(::waam_test_env::TempDir()) / "simulate_limit";
  options.quiet = true;
  try {
    SimulatePlanned(f.scenario, f.planned, options);
    FAIL() << "expected InputError past the voxel limit";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("simulation.max_voxels = 5000"));
  }
  EXPECT_FALSE(fs::exists(options.out_dir / "simulate.json")) << "no partial result";
}

fs::path ScenarioFile(const std::string& name, const std::string& simulation) {
  const fs::path dir = fs::path(::waam_test_env::TempDir()) / ("waam_simulate_" + std::to_string(::getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "scenario.yaml") << "name: " << name << "\n"
                                          "part:\n  generator: {type: box, size_mm: [40, 30, 4]}\n"
                                          "slicing:\n  type: planar\n  layer_height_mm: 2.0\n"
                                          "path:\n  pattern: continuous\n  bead_width_mm: 6\n"
                                          "process:\n  travel_speed_mm_min: 400\n  wire_feed_mm_min: 3200\n"
                                       << simulation;
  return dir / "scenario.yaml";
}

// The whole pipeline through the real planner: the plan's layers are deposited and the volume balances.
TEST(SimulateCommand, RunsAScenarioEndToEnd) {
  SimulateOptions options;
  options.scenario = ScenarioFile("box", "simulation: {voxel_mm: 0.5, blend: fixed, blend_radius_mm: 1.5}\n");
  options.out_dir = options.scenario.parent_path() / "out";
  options.quiet = true;
  options.images = false;
  const twin::TwinMeasures m = RunSimulate(options);
  EXPECT_EQ(m.layers, 2u);
  EXPECT_GT(m.beads, 0u);
  EXPECT_NEAR(m.deposited_volume_mm3, m.expected_volume_mm3, 0.02 * m.expected_volume_mm3);
  const nlohmann::json j = nlohmann::json::parse(ReadFile(options.out_dir / "simulate.json"));
  EXPECT_EQ(j["settings"]["blend"], "fixed") << "the scenario's simulation section must reach the twin";
  EXPECT_GT(j["deviation"]["samples"].get<int>(), 0) << "the box mesh is the target of the deviation";
  EXPECT_FALSE(fs::exists(options.out_dir / "top_height.png")) << "--no-images";

  // --set reaches the simulation section.
  options.overrides = {"simulation.voxel_mm=1.0"};
  EXPECT_DOUBLE_EQ(RunSimulate(options).voxel_mm, 1.0);
}

TEST(SimulateCommand, CliExitCodes) {
  std::string err;
  const fs::path good = ScenarioFile("cli_good", "");
  EXPECT_EQ(RunWaam("simulate " + good.string() + " -o " + (good.parent_path() / "out").string() + " -q", &err), 0)
      << err;
  const fs::path bad = ScenarioFile("cli_bad", "simulation: {voxel_mm: 5}\n");
  EXPECT_EQ(RunWaam("simulate " + bad.string() + " -o " + (bad.parent_path() / "out").string() + " -q", &err), 2);
  EXPECT_THAT(err, HasSubstr("simulation.voxel_mm"));
  EXPECT_EQ(RunWaam("simulate /nonexistent/scenario.yaml -o /tmp/never -q", &err), 2);
  EXPECT_THAT(err, HasSubstr("waam: error"));
}

}  // namespace
}  // namespace waam::analysis
