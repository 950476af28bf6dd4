// `waam check <scenario.yaml> -o <dir>`: command-line options of the cell check.
#include <iostream>
#include <memory>

#include "analysis/check_command.h"
#include "app/commands.h"

namespace waam::app {

void AddCheckCommand(CLI::App& app, CommandRunner* runner) {
  auto options = std::make_shared<analysis::CheckOptions>();
  CLI::App* command = app.add_subcommand(
      "check",
      "Check before a build that the robot cell can follow every point of the planned path.\n"
      "Plans the scenario's part, then moves the MuJoCo cell (FANUC ARC Mate 100iC/12 arm with torch, two-axis\n"
      "tilt/rotate positioner, substrate plate, clamps, floor; or the scenario's cell.mjcf) along the path at the\n"
      "planned travel speed, sampling every cell.checks.step_mm (default 1 mm), and checks at every sample:\n"
      "  unreachable   no inverse-kinematics solution (the pose lies outside the arm's reach)\n"
      "  joint_limit   an axis closer than cell.checks.joint_margin_deg (default 2 deg) to its limit\n"
      "  joint_speed   an axis faster than its maximum speed while welding\n"
      "  singularity   |J5| below cell.checks.singularity_deg (default 5 deg)\n"
      "  collision     two cell bodies in contact, or the torch nozzle in the layers already deposited\n"
      "The positioner turns each layer's build direction up (neutral welding position); a turntable or no\n"
      "positioner (cell.positioner.type) cannot, and the torch follows the path's tool direction; arm and positioner\n"
      "placement come from the scenario's cell: section (see docs/CELL.md). Writes to the output directory:\n"
      "  check.json      ok, points, violations (kind, point, layer, joint or bodies, margin_deg | speed_ratio |\n"
      "                  j5_deg | penetration_mm | reach_excess_mm), min_joint_margin_deg, max_joint_speed_ratio\n"
      "  cell_worst.png  the cell at the worst point (side and top views)\n"
      "  joints.png      the eight axis angles (deg) against time (s) with their limits\n"
      "  viewer.html     the 3D viewer: the cell moving along the path, the beads laid down, the violations\n"
      "  program.csv     the eight-axis program table (TCP mm, torch Euler angles deg, positioner deg, speed)\n"
      "  program.ls      FANUC LS program, positioner as motion group 2\n"
      "check.json is written last. Exit code 0 when the path passes, 3 when there are violations.");
  command->add_option("scenario", options->scenario, "Scenario YAML file")->required();
  command->add_option("-o,--out", options->out_dir, "Output directory (created if missing)")->required();
  command->add_option("--set", options->overrides,
                      "Override a scenario setting, key.path=value (repeatable), e.g. --set cell.robot.yaw_deg=30");
  command->add_flag("-q,--quiet", options->quiet, "No progress bar on stderr");
  command->add_flag("!--no-images", options->images, "Do not draw cell_worst.png, joints.png and viewer.html");
  command->add_flag("!--no-program", options->program, "Do not write program.csv and program.ls");
  command->callback([options, runner] {
    *runner = [options] {
      const twin::CheckReport report = analysis::RunCheck(*options);
      std::cout << (report.ok ? "ok" : "VIOLATIONS") << ": " << report.points << " path points, " << report.samples
                << " samples checked, " << report.violations.size() << " violations, min joint margin "
                << report.min_joint_margin_deg << " deg (" << report.min_margin_joint << "), max joint speed "
                << 100.0 * report.max_joint_speed_ratio << " % of limit -> "
                << (options->out_dir / "check.json").string() << "\n";
      for (std::size_t i = 0; i < report.violations.size() && i < 10; ++i) {
        const twin::CheckViolation& v = report.violations[i];
        std::cout << "  " << NameOf(v.kind) << " " << v.joint << v.body1 << (v.body2.empty() ? "" : "/") << v.body2
                  << " at point " << v.point << " (layer " << v.layer << "): " << v.unit << " = " << v.value << "\n";
      }
      return report.ok ? kExitOk : kExitViolations;
    };
  });
}

}  // namespace waam::app
