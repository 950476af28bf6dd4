// `waam inspect`: reads an STL mesh and prints its health report (MeshReport) as JSON.
#include <iostream>
#include <memory>
#include <string>

#include "app/commands.h"
#include "analysis/stl_file.h"
#include "planner/mesh/stl_io.h"

namespace waam::app {

void AddInspectCommand(CLI::App& app, CommandRunner* runner) {
  struct Options {
    std::string mesh;
    double weld_tol_mm = 1e-4;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand(
      "inspect",
      "Read an STL part (binary or ASCII, coordinates in mm), weld vertices closer than --weld-tol-mm and print the\n"
      "mesh report as JSON on stdout: facets read and kept, degenerate facets dropped, welded vertices, boundary,\n"
      "non-manifold and misoriented edges, watertightness, enclosed volume (mm^3) and bounding box (mm).\n"
      "Exit code 2 with a one-line message on stderr for a file that cannot be read, and also for a mesh that\n"
      "reads but cannot be sliced (open or non-manifold): its report is still printed, with \"sliceable\": false.");
  command->add_option("mesh", options->mesh, "STL file to inspect")->required();
  command->add_option("--weld-tol-mm", options->weld_tol_mm,
                      "merge vertices closer than this distance (mm, 0..10; 0 merges identical points only)")
      ->capture_default_str();
  command->callback([runner, options] {
    *runner = [options] {
      planner::MeshReport report;
      analysis::ReadStl(options->mesh, options->weld_tol_mm, &report);
      std::cout << planner::MeshReportJson(report) << std::endl;
      planner::CheckSliceable(report);  // exit 2 with the reason on stderr
      return kExitOk;
    };
  });
}

}  // namespace waam::app
