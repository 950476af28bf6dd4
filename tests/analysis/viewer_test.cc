// viewer.html: the cell's bodies match its shapes, the page's counts match the run, and Debian's chromium (headless,
// software WebGL) loads the page of a scenario with violations and of a multi-axis scenario without errors.
#include "analysis/viewer.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "analysis/bench_command.h"
#include "analysis/cell_files.h"
#include "analysis/check_command.h"
#include "analysis/png_file.h"
#include "analysis/scenario.h"
#include "analysis/thermal_run.h"
#include "planner/plan_scenario.h"
#include "planner/planar_planner.h"
#include "tests/analysis/cli_test_util.h"
#include "twin/cell/mujoco_cell.h"
#include "twin/deposition/bead_deposition.h"

namespace waam::analysis {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

const std::string kScenarios = std::string(WAAM_SOURCE_DIR) + "/scenarios/";

TEST(ViewerTest, Base64MatchesTheStandardAlphabetAndPadding) {
  EXPECT_EQ(internal::Base64(""), "");
  EXPECT_EQ(internal::Base64("M"), "TQ==");
  EXPECT_EQ(internal::Base64("Ma"), "TWE=");
  EXPECT_EQ(internal::Base64("Man"), "TWFu");
  EXPECT_EQ(internal::Base64(std::string("\xff\xfe\x00", 3)), "//4A");
}

// Each geom placed by its body's pose lands where the world-frame shapes put it.
void ExpectBodiesMatchShapes(const twin::CellModel& cell, const planner::Joints8& q) {
  twin::CellState state(cell);
  state.SetJoints(q);
  const std::vector<twin::CellBody> bodies = cell.Bodies();
  const std::vector<Eigen::Isometry3d> poses = state.BodyPoses();
  const std::vector<twin::CellShape> shapes = state.Shapes();
  ASSERT_EQ(bodies.size(), poses.size());
  std::size_t g = 0;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    for (const twin::CellShape& geom : bodies[b].geoms) {
      ASSERT_LT(g, shapes.size());
      EXPECT_EQ(geom.body, shapes[g].body);
      const Eigen::Isometry3d X_WG = poses[b] * geom.X_WG;
      EXPECT_LT((X_WG.translation() - shapes[g].X_WG.translation()).norm(), 1e-6) << geom.body << " geom " << g;
      EXPECT_LT((X_WG.linear() - shapes[g].X_WG.linear()).norm(), 1e-9) << geom.body << " geom " << g;
      ++g;
    }
  }
  EXPECT_EQ(g, shapes.size()) << "every geom belongs to one body";
}

TEST(ViewerTest, BodiesPlacedByTheirPosesMatchTheWorldShapes) {
  const twin::CellModel cell = LoadCellModel(fs::path{});
  planner::Joints8 q;
  q << 0.3, -0.2, 0.4, 0.5, -0.7, 1.1, 0.4, 2.0;
  ExpectBodiesMatchShapes(cell, q);
  ExpectBodiesMatchShapes(cell, planner::Joints8::Zero());
}

TEST(ViewerTest, MeshGeomsCarryTheirVertices) {
  // The built-in cell with a tetrahedron mesh on the flange.
  std::string xml = ReadFile(analysis::BuiltinCellPath());
  const std::size_t compiler = xml.find("<compiler");
  ASSERT_NE(compiler, std::string::npos);
  xml.insert(compiler, "<asset><mesh name=\"tetra\" vertex=\"0 0 0  0.05 0 0  0 0.05 0  0 0 0.05\"/></asset>\n  ");
  const std::size_t link6 = xml.find("<body name=\"link6\"");
  ASSERT_NE(link6, std::string::npos);
  const std::size_t open_end = xml.find('>', link6);
  xml.insert(open_end + 1, "<geom name=\"tetra_geom\" type=\"mesh\" mesh=\"tetra\" pos=\"0 0.02 0\" contype=\"0\" "
                           "conaffinity=\"0\" rgba=\"0 1 0 1\"/>");
  const fs::path dir = cli_test::TempDir("viewer_mesh");
  WriteFileAtomic(dir / "cell.xml", xml);
  const twin::CellModel cell = LoadCellModel(dir / "cell.xml");
  int meshes = 0;
  for (const twin::CellBody& body : cell.Bodies()) {
    ASSERT_EQ(body.geoms.size(), body.mesh_vertices_mm.size());
    for (std::size_t g = 0; g < body.geoms.size(); ++g) {
      if (body.geoms[g].type != twin::CellShape::Type::kMesh) continue;
      ++meshes;
      EXPECT_EQ(body.name, "link6");
      EXPECT_EQ(body.joint, "j6");
      EXPECT_EQ(body.mesh_vertices_mm[g].size(), 4u);
      EXPECT_EQ(body.mesh_triangles[g].size(), 4u) << "the convex hull of four points has four faces";
      // MuJoCo moved the vertices to the mesh's inertial frame; their distances stay: three edges of 50 mm from
      // the corner, three of 50 sqrt(2) mm between the others.
      const std::vector<Eigen::Vector3f>& v = body.mesh_vertices_mm[g];
      std::vector<float> edges;
      for (std::size_t i = 0; i < v.size(); ++i) {
        for (std::size_t j = i + 1; j < v.size(); ++j) edges.push_back((v[i] - v[j]).norm());
      }
      std::sort(edges.begin(), edges.end());
      ASSERT_EQ(edges.size(), 6u);
      for (int e = 0; e < 3; ++e) EXPECT_NEAR(edges[e], 50.0f, 1e-3f);
      for (int e = 3; e < 6; ++e) EXPECT_NEAR(edges[e], 50.0f * std::sqrt(2.0f), 1e-3f);
    }
  }
  EXPECT_EQ(meshes, 1);
  ExpectBodiesMatchShapes(cell, planner::Joints8::Zero());
}

// A checked scenario, in memory.
struct Checked {
  Scenario scenario;
  planner::PlanResult planned;
  twin::CheckReport report;
};

Checked CheckScenario(const std::string& file, const fs::path& out_dir) {
  Checked c{LoadScenario(kScenarios + file, {}), {}, {}};
  c.planned = planner::PlanScenario(c.scenario, nullptr);
  CheckOptions options;
  options.out_dir = out_dir;
  options.quiet = true;
  options.program = false;
  options.target = &c.planned.mesh;
  c.report = RunCheckOnPlan(c.scenario, c.planned.plan, options);
  return c;
}

TEST(ViewerTest, PageCountsMatchTheRunAndTheBudget) {
  const fs::path dir = cli_test::TempDir("viewer_counts");
  const Checked c = CheckScenario("cell/cell_joint_limit.yaml", dir);
  const nlohmann::json check = cli_test::ReadJson(dir / "check.json");
  ASSERT_TRUE(check.contains("viewer")) << check.dump(2);
  const nlohmann::json& v = check["viewer"];
  const twin::CellModel cell = LoadCell(c.scenario.cell);
  EXPECT_EQ(v["bodies"].get<std::size_t>(), cell.Bodies().size());
  EXPECT_EQ(v["violations"].get<std::size_t>(), check["violation_count"].get<std::size_t>());
  EXPECT_GT(v["violations"].get<std::size_t>(), 0u) << "the scenario plants joint-limit violations";
  EXPECT_EQ(v["path_points"].get<std::size_t>(), check["points"].get<std::size_t>()) << "under the path budget";
  const std::size_t samples = check["samples"].get<std::size_t>();
  const std::size_t frames = v["frames"].get<std::size_t>();
  EXPECT_LE(frames, ViewerBudget{}.max_frames + 1 + c.report.violations.size());
  EXPECT_GE(frames, std::min(samples, ViewerBudget{}.max_frames / 2));
  EXPECT_EQ(v["bytes"].get<std::size_t>(), fs::file_size(dir / "viewer.html"));

  // Self-contained: no external script, style or fetch of the data; three.js inlined.
  const std::string page = cli_test::Slurp(dir / "viewer.html");
  EXPECT_THAT(page, Not(HasSubstr("<script src")));
  EXPECT_THAT(page, Not(HasSubstr("<link")));
  EXPECT_THAT(page, HasSubstr("REVISION=\"111\""));
  EXPECT_THAT(page, HasSubstr("OrbitControls"));

  // A smaller budget thins the frames and the path but keeps each violation's frame.
  ViewerBudget small;
  small.max_frames = 100;
  small.max_path_points = 50;
  ViewerSummary summary;
  const nlohmann::json data = ViewerData(c.scenario.name, cell, twin::PartKinematics(cell, c.scenario.cell),
                                         c.planned.plan, &c.planned.mesh, c.report, small, &summary);
  EXPECT_LE(summary.frames, 100u + 1 + c.report.violations.size());
  EXPECT_GE(summary.frames, 50u);
  EXPECT_LE(summary.path_points, 50u + 2 * c.planned.plan.layers.size());
  EXPECT_LE(summary.beads, summary.path_points);
  EXPECT_EQ(data["violations"].size(), c.report.violations.size());
  for (const nlohmann::json& violation : data["violations"]) {
    EXPECT_LT(violation["frame"].get<std::size_t>(), summary.frames);
    EXPECT_FALSE(violation["highlight"].empty()) << "a joint-limit violation highlights the joint's body";
  }
  EXPECT_THAT(data["sampling"].get<std::string>(), HasSubstr(std::to_string(summary.frames) + " frames of"));
}

TEST(ViewerTest, DepositIsCoarsenedToItsBudgetAndAddedOnce) {
  const fs::path dir = cli_test::TempDir("viewer_deposit");
  const Checked c = CheckScenario("cell/cell_joint_limit.yaml", dir);
  const twin::Depositor depositor = twin::DepositPlan(c.planned.plan, c.scenario.simulation,
                                                      c.scenario.process.rapid_speed_mm_min / 60.0, nullptr);
  ASSERT_GT(depositor.grid().occupied(), 1000u);
  // Every voxel its own cell when the budget allows.
  fs::copy_file(dir / "viewer.html", dir / "full.html");
  EXPECT_EQ(AddDepositToViewer(dir / "full.html", depositor, nullptr, depositor.grid().occupied()),
            depositor.grid().occupied());
  // A budget of a tenth of the voxels: merged cubes, within the budget.
  const std::size_t budget = depositor.grid().occupied() / 10;
  const std::size_t cells = AddDepositToViewer(dir / "viewer.html", depositor, nullptr, budget);
  EXPECT_LE(cells, budget);
  EXPECT_GT(cells, 0u);
  const std::string page = cli_test::Slurp(dir / "viewer.html");
  EXPECT_THAT(page, HasSubstr("id=\"waam-deposit\""));
  EXPECT_EQ(page.find(std::string(kViewerDepositMarker)), std::string::npos) << "the room for the deposit is used";
  try {
    AddDepositToViewer(dir / "viewer.html", depositor);
    FAIL() << "a second deposit must be refused";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("viewer.html: not a viewer.html of this waam, or its deposit was added already"));
  }
}

// A thermal run of a 3 x 3 x 3 cell block whose top row of cells is laid by the second layer: the page takes the 26
// cells with a face outside (not the centre), each layer's temperatures on one scale, once.
TEST(ViewerTest, ThermalIsAddedOnceWithItsSurfaceCells) {
  const fs::path dir = cli_test::TempDir("viewer_thermal");
  CheckScenario("cell/cell_joint_limit.yaml", dir);
  ThermalRunResult result;
  result.settings.ambient_c = 20.0;
  for (int layer = 0; layer < 2; ++layer) {
    twin::TemperatureField f;
    f.origin_mm = Eigen::Vector3d(-3, -3, -4);
    f.cell_mm = 2.0;
    f.size = Eigen::Vector3i(3, 3, 3);
    f.temperature_c.assign(27, 100.0f + 500.0f * layer);
    if (layer == 0) std::fill(f.temperature_c.begin() + 18, f.temperature_c.end(), NAN);
    result.fields.push_back({layer, 10.0 * (layer + 1), f});
    result.layers.push_back({layer, 10.0 * layer, 10.0 * (layer + 1), 20.0, 600.0, 0.0, true});
  }
  EXPECT_EQ(AddThermalToViewer(dir / "viewer.html", result), 26u);
  const std::string page = cli_test::Slurp(dir / "viewer.html");
  const std::size_t at = page.find("<script type=\"application/json\" id=\"waam-thermal\">");
  ASSERT_NE(at, std::string::npos);
  const std::size_t from = page.find('>', at) + 1;
  const nlohmann::json thermal = nlohmann::json::parse(page.substr(from, page.find("</script>", from) - from));
  EXPECT_EQ(thermal["count"], 26);
  EXPECT_EQ(thermal["snapshots"], 2);
  EXPECT_DOUBLE_EQ(thermal["low_c"].get<double>(), 20.0);
  EXPECT_DOUBLE_EQ(thermal["high_c"].get<double>(), 600.0);
  EXPECT_EQ(page.find(std::string(kViewerThermalMarker)), std::string::npos) << "the room for them is used";
  try {
    AddThermalToViewer(dir / "viewer.html", result);
    FAIL() << "a second add must be refused";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("its temperatures were added already"));
  }
}

TEST(ViewerTest, BenchReportLinksEachScenarioViewer) {
  const fs::path dir = cli_test::TempDir("viewer_bench");
  fs::create_directories(dir / "scenarios");
  std::ofstream(dir / "scenarios" / "small.yaml") << R"(name: small_block
part:
  generator: {type: box, size_mm: [30, 20, 3]}
slicing:
  type: planar
  layer_height_mm: 1.5
path:
  pattern: continuous
  bead_width_mm: 6
process:
  travel_speed_mm_min: 400
  wire_feed_mm_min: 3200
run:
  steps: [plan, check]
)";
  BenchOptions options;
  options.scenarios = {dir / "scenarios"};
  options.out_dir = dir / "bench";
  options.waam_binary = WAAM_BINARY;
  options.quiet = true;
  RunBench(options);
  EXPECT_TRUE(fs::is_regular_file(dir / "bench" / "small" / "check" / "viewer.html")) << "waam run writes the viewer";
  const std::string report = ReadFile(dir / "bench" / "report.html");
  EXPECT_NE(report.find("<a href=\"small/check/viewer.html\">"), std::string::npos) << "the report links the viewer";
}

// --- In the browser ---

bool HaveChromium() { return std::system("command -v chromium >/dev/null 2>&1") == 0; }

// Runs headless chromium on `page` with `what` ("--dump-dom" or "--screenshot=<png>"); returns its stdout.
std::string Chromium(const fs::path& page, const std::string& what, const std::string& hash = "") {
  const fs::path dir = cli_test::TempDir("chromium_" + std::to_string(std::hash<std::string>{}(what + hash)));
  const std::string command =
      "timeout 120 chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run "
      "--disable-background-networking --disable-component-update --disable-sync --use-angle=swiftshader "
      "--enable-unsafe-swiftshader --user-data-dir=" + (dir / "profile").string() +
      " --virtual-time-budget=10000 --window-size=1200,800 " + what + " 'file://" + fs::absolute(page).string() +
      hash + "' >" + (dir / "out.html").string() + " 2>" + (dir / "err.txt").string();
  EXPECT_EQ(std::system(command.c_str()), 0) << command << "\n" << cli_test::Slurp(dir / "err.txt");
  return cli_test::Slurp(dir / "out.html");
}

// The attribute `name` of the page's <body> after loading ("" when missing).
std::string BodyAttribute(const std::string& dom, const std::string& name) {
  const std::size_t open = dom.find("<body");
  const std::size_t close = dom.find('>', open);
  if (open == std::string::npos || close == std::string::npos) return "";
  const std::string body = dom.substr(open, close - open);
  std::smatch value;
  return std::regex_search(body, value, std::regex(name + "=\"([^\"]*)\"")) ? value[1].str() : "";
}

// Loads the page, checks its counts against check.json, and that a screenshot of it is a drawn scene.
void ExpectPageLoads(const fs::path& check_dir, const std::string& screenshot_copy = "") {
  const nlohmann::json v = cli_test::ReadJson(check_dir / "check.json").at("viewer");
  const std::string dom = Chromium(check_dir / "viewer.html", "--dump-dom");
  EXPECT_EQ(BodyAttribute(dom, "data-viewer-ready"), "1") << "the page did not finish loading";
  EXPECT_EQ(BodyAttribute(dom, "data-errors"), "0") << "errors while loading";
  EXPECT_EQ(BodyAttribute(dom, "data-frames"), std::to_string(v["frames"].get<std::size_t>()));
  EXPECT_EQ(BodyAttribute(dom, "data-bodies"), std::to_string(v["bodies"].get<std::size_t>()));
  EXPECT_EQ(BodyAttribute(dom, "data-violations"), std::to_string(v["violations"].get<std::size_t>()));

  const fs::path png = check_dir / "viewer.png";
  Chromium(check_dir / "viewer.html", "--screenshot=" + png.string(), "#t=0.6&view=part");
  const cv::Mat image = internal::ReadPng(png, 3);
  ASSERT_FALSE(image.empty()) << "no screenshot at " << png;
  // The 3D view (left of the 320 px panel): many colours, and most pixels not the background.
  const cv::Mat view = image(cv::Rect(0, 0, image.cols - 340, image.rows));
  std::set<int> colours;
  int drawn = 0;
  for (int r = 0; r < view.rows; ++r) {
    for (int col = 0; col < view.cols; ++col) {
      const cv::Vec3b p = view.at<cv::Vec3b>(r, col);
      colours.insert(p[0] << 16 | p[1] << 8 | p[2]);
      drawn += (p[0] != 0xf2 || p[1] != 0xf4 || p[2] != 0xf4) ? 1 : 0;
    }
  }
  EXPECT_GT(colours.size(), 200u) << "the 3D view looks blank";
  EXPECT_GT(drawn, view.rows * view.cols / 4) << "the 3D view is mostly background";
  const char* keep = std::getenv(screenshot_copy.c_str());
  if (!screenshot_copy.empty() && keep && *keep) fs::copy_file(png, keep, fs::copy_options::overwrite_existing);
}

TEST(ViewerBrowserTest, PageOfAScenarioWithViolationsLoads) {
  if (!HaveChromium()) GTEST_SKIP() << "chromium is not installed (tools/install_deps.sh installs it)";
  const fs::path dir = cli_test::TempDir("viewer_browser_violations");
  CheckScenario("cell/cell_joint_limit.yaml", dir);
  ExpectPageLoads(dir);
  // Played (viewer.html#play), the build clock moves on from 0.
  const std::string dom = Chromium(dir / "viewer.html", "--dump-dom", "#play&speed=100");
  const std::size_t at = dom.find("id=\"clock\"");
  ASSERT_NE(at, std::string::npos) << "no clock in the page";
  const std::string text = dom.substr(at, 200);
  std::smatch clock;
  ASSERT_TRUE(std::regex_search(text, clock, std::regex("t = ([0-9.]+) s")))
      << "no clock in the page";
  EXPECT_GT(std::stod(clock[1].str()), 0.0) << "playing did not advance the time";

  // Opened at the first violation (as a click on it does): its body is lit, its row is the active one.
  const nlohmann::json check = cli_test::ReadJson(dir / "check.json");
  const std::string at_violation = Chromium(dir / "viewer.html", "--dump-dom", "#violation=0");
  EXPECT_EQ(BodyAttribute(at_violation, "data-errors"), "0");
  const std::string joint = check["violations"][0].value("joint", "");
  ASSERT_EQ(joint, "j1") << "the scenario plants a J1 limit violation";
  EXPECT_EQ(BodyAttribute(at_violation, "data-highlighted"), "link1") << "J1 turns link1";
  EXPECT_NE(at_violation.find("<li class=\"active\">joint_limit j1, layer " +
                              std::to_string(check["violations"][0]["layer"].get<int>())),
            std::string::npos);
}

// `waam run` without the simulate step: the page has the planned path and beads only. With
// WAAM_VIEWER_SCREENSHOT=<png> the screenshot is kept there (docs/images/viewer_multiaxis.png).
TEST(ViewerBrowserTest, PageOfAMultiAxisRunWithoutSimulateLoads) {
  if (!HaveChromium()) GTEST_SKIP() << "chromium is not installed (tools/install_deps.sh installs it)";
  const fs::path dir = cli_test::TempDir("viewer_browser_multiaxis");
  std::string err;
  const int code = cli_test::RunWaam("run " + kScenarios + "multiaxis/vanes_wide_cone.yaml -o " +
                                         (dir / "out").string() + " -q --steps plan check",
                                     &err);
  ASSERT_EQ(code, 0) << err;
  ASSERT_FALSE(fs::exists(dir / "out" / "simulate"));
  ExpectPageLoads(dir / "out" / "check", "WAAM_VIEWER_SCREENSHOT");
}

// With the simulate step after check, the page grows the deposited part.
TEST(ViewerBrowserTest, PageOfARunWithSimulateShowsTheDeposit) {
  const fs::path dir = cli_test::TempDir("viewer_browser_simulate");
  std::string err;
  ASSERT_EQ(cli_test::RunWaam("run " + kScenarios + "cell/cell_ok.yaml -o " + (dir / "out").string() +
                                  " -q --steps plan check simulate",
                              &err),
            0)
      << err;
  const std::string page = cli_test::Slurp(dir / "out" / "check" / "viewer.html");
  EXPECT_NE(page.find("id=\"waam-deposit\""), std::string::npos) << "the simulate step adds the deposit";
  EXPECT_NE(page.find("\"deviation_mm\""), std::string::npos) << "and its deviation from the target";
  if (!HaveChromium()) GTEST_SKIP() << "chromium is not installed (tools/install_deps.sh installs it)";
  const std::string dom = Chromium(dir / "out" / "check" / "viewer.html", "--dump-dom", "#t=0.5&deviation");
  EXPECT_EQ(BodyAttribute(dom, "data-viewer-ready"), "1");
  EXPECT_EQ(BodyAttribute(dom, "data-errors"), "0");
  EXPECT_NE(dom.find("deposited part:"), std::string::npos) << "the page says what it holds of the deposit";
  EXPECT_NE(dom.find("(rms "), std::string::npos) << "the deviation colour scale is shown";
}

// With the thermal step after check, the page colours the part by temperature at the slider's time: a small wall of
// the thermal scenario (30 x 8 x 4 mm on a 60 x 40 x 6 mm plate), opened at the middle and at the end of the build.
TEST(ViewerBrowserTest, PageOfARunWithThermalColoursThePartByTemperature) {
  const fs::path dir = cli_test::TempDir("viewer_browser_thermal");
  std::string err;
  ASSERT_EQ(cli_test::RunWaam("run " + kScenarios + "thermal/wall_interpass.yaml -o " + (dir / "out").string() +
                                  " -q --steps plan check thermal --set 'part.generator.size_mm=[30, 8, 4]' "
                                  "--set 'thermal.substrate.size_mm=[60, 40, 6]'",
                              &err),
            0)
      << err;
  const fs::path viewer = dir / "out" / "check" / "viewer.html";
  const std::string page = cli_test::Slurp(viewer);
  ASSERT_NE(page.find("id=\"waam-thermal\""), std::string::npos) << "the thermal step adds the temperatures";
  const double peak = cli_test::ReadJson(dir / "out" / "thermal" / "thermal.json")["peak_c"].get<double>();
  if (!HaveChromium()) GTEST_SKIP() << "chromium is not installed (tools/install_deps.sh installs it)";
  double hottest[2] = {0.0, 0.0};
  for (int end = 0; end < 2; ++end) {
    const std::string dom = Chromium(viewer, "--dump-dom", end ? "#t=1&view=part" : "#t=0.5&view=part");
    EXPECT_EQ(BodyAttribute(dom, "data-viewer-ready"), "1");
    EXPECT_EQ(BodyAttribute(dom, "data-errors"), "0");
    const int cells = std::stoi(BodyAttribute(dom, "data-thermal-cells"));
    const int shown = std::stoi(BodyAttribute(dom, "data-thermal-shown"));
    EXPECT_GT(shown, 0);
    EXPECT_LE(shown, cells);
    if (end) {
      EXPECT_EQ(shown, cells) << "at the end every cell is there";
    }
    const std::size_t at = dom.find("id=\"clock\"");
    ASSERT_NE(at, std::string::npos);
    std::smatch m;
    const std::string clock = dom.substr(at, 200);
    ASSERT_TRUE(std::regex_search(clock, m, std::regex("hottest ([0-9.]+) degC"))) << clock;
    hottest[end] = std::stod(m[1].str());
    // Layer ends are colder than the run's sampled peak (taken while the arc burns), hotter than the air.
    EXPECT_GT(hottest[end], 20.0);
    EXPECT_LE(hottest[end], peak + 1.0);
    EXPECT_THAT(dom, HasSubstr("id=\"thermal-high\">")) << "a colour bar with its scale";
    EXPECT_THAT(dom, HasSubstr(" degC</span>"));
  }
}

TEST(ViewerBrowserTest, EmptyMotionGivesAPageThatSaysSo) {
  const fs::path dir = cli_test::TempDir("viewer_empty");
  const twin::CellModel cell = LoadCellModel(fs::path{});
  const twin::CheckReport empty;
  const ViewerSummary summary =
      WriteViewer("nothing", cell, cell.kinematics(), planner::Plan{}, nullptr, empty, dir / "viewer.html");
  EXPECT_EQ(summary.frames, 0u);
  if (!HaveChromium()) GTEST_SKIP() << "chromium is not installed (tools/install_deps.sh installs it)";
  const std::string dom = Chromium(dir / "viewer.html", "--dump-dom");
  EXPECT_EQ(BodyAttribute(dom, "data-viewer-ready"), "1");
  EXPECT_EQ(BodyAttribute(dom, "data-errors"), "0");
  EXPECT_EQ(BodyAttribute(dom, "data-frames"), "0");
  EXPECT_THAT(dom, HasSubstr("is empty"));
}

}  // namespace
}  // namespace waam::analysis
