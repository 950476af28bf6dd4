// report.html of a bench and of a sweep: inline SVG plots of time and memory per scenario, the published figures
// against ours, and each sweep metric against each swept value; no network, loads in headless chromium cleanly.
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "analysis/bench_command.h"
#include "models/core/files.h"
#include "tests/analysis/cli_test_util.h"

namespace waam::analysis {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

std::size_t Count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// A bench of a three-run sweep over path.bead_width_mm with hand-made timings and metrics, and two reference rows.
nlohmann::json SweepBench() {
  nlohmann::json scenarios = nlohmann::json::array(), runs = nlohmann::json::array();
  for (int i = 0; i < 3; ++i) {
    const std::string id = "run" + std::to_string(i);
    const double width = 5.0 + i;
    scenarios.push_back({{"id", id},
                         {"outcome", "pass"},
                         {"exit_code", 0},
                         {"expected_exit_code", 0},
                         {"timing", {{"wall_s", 2.0 + i}, {"peak_rss_mb", 100.0 + 50 * i}}},
                         {"steps", {{{"name", "plan"}, {"status", "ok"}, {"metrics", {{"weld_length_mm", 1000.0 / width}}}}}}});
    runs.push_back({{"id", id}, {"values", {{"path.bead_width_mm", width}}}});
  }
  nlohmann::json reference = nlohmann::json::array();
  reference.push_back({{"source", "Ding 2014"}, {"quantity", "Ra"}, {"published", "0.5"}, {"published_value", 0.5},
                       {"ours", 0.55}, {"unit", "mm"}, {"scenario", "run0"}});
  reference.push_back({{"source", "Nguyen 2022"}, {"quantity", "void length"}, {"published", "2"},
                       {"published_value", 2.0}, {"ours", nullptr}, {"unit", "mm"}, {"scenario", "run1"}});
  return {{"scenarios", scenarios},
          {"counts", {{"total", 3}, {"pass", 3}, {"expected_fail", 0}, {"fail", 0}}},
          {"timing", {{"total_s", 9.0}, {"scenarios_wall_s", 9.0}, {"reused_results", 0}}},
          {"reference", reference},
          {"sweep", {{"name", "width"}, {"file", "width.yaml"}, {"base", "box.yaml"}, {"set", nlohmann::json::array()},
                     {"keys", {"path.bead_width_mm"}}, {"metrics", {"plan.weld_length_mm"}}, {"runs", runs}}}};
}

TEST(BenchReportPlots, TimeMemoryReferenceAndSweepPlotsAreInlineSvg) {
  const fs::path dir = cli_test::TempDir("bench_report_plots");
  WriteBenchReport(SweepBench(), dir);
  const std::string html = ReadFile(dir / "report.html");
  EXPECT_THAT(html, HasSubstr("Wall time per scenario"));
  EXPECT_THAT(html, HasSubstr("Peak memory per scenario"));
  EXPECT_THAT(html, HasSubstr("Ours / published"));
  EXPECT_THAT(html, HasSubstr("plan.weld_length_mm against path.bead_width_mm"));
  // Three bars in each of the time and memory charts, one ratio bar (1.1) and an n/a for the missing figure.
  EXPECT_THAT(html, HasSubstr(">1.1</text>"));
  EXPECT_THAT(html, HasSubstr(">n/a</text>"));
  std::string offline = html;
  const std::string svg_namespace = "http://www.w3.org/2000/svg";
  for (std::size_t at = offline.find(svg_namespace); at != std::string::npos; at = offline.find(svg_namespace)) {
    offline.erase(at, svg_namespace.size());
  }
  EXPECT_EQ(offline.find("http://"), std::string::npos) << "no resource from the network (only the SVG namespace)";
  EXPECT_EQ(offline.find("https://"), std::string::npos);
  EXPECT_EQ(html.find("<script src"), std::string::npos);
}

TEST(BenchReportPlots, LoadsInHeadlessChromiumWithoutConsoleErrors) {
  if (std::system("command -v chromium >/dev/null 2>&1") != 0) {
    GTEST_SKIP() << "chromium is not installed (tools/install_deps.sh installs it)";
  }
  const fs::path dir = cli_test::TempDir("bench_report_browser");
  WriteBenchReport(SweepBench(), dir);
  const std::string command =
      "timeout 120 chromium --headless --no-sandbox --disable-gpu --no-first-run --disable-background-networking "
      "--disable-component-update --disable-sync --enable-logging=stderr --v=0 --user-data-dir=" +
      (dir / "profile").string() + " --virtual-time-budget=5000 --dump-dom 'file://" +
      fs::absolute(dir / "report.html").string() + "' >" + (dir / "dom.html").string() + " 2>" +
      (dir / "err.txt").string();
  ASSERT_EQ(std::system(command.c_str()), 0) << command << "\n" << cli_test::Slurp(dir / "err.txt");
  const std::string dom = cli_test::Slurp(dir / "dom.html");
  const std::string err = cli_test::Slurp(dir / "err.txt");
  EXPECT_GE(Count(dom, "<svg"), 4u) << "time, memory, reference and sweep plots in the parsed page";
  EXPECT_THAT(dom, HasSubstr("Wall time per scenario"));
  EXPECT_EQ(err.find(":CONSOLE("), std::string::npos) << "console messages: " << err;
}

}  // namespace
}  // namespace waam::analysis
