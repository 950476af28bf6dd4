// `waam import`: a program read into the twin's plan.
#include "analysis/import_command.h"

#include <cmath>
#include <iostream>

#include "analysis/cell_files.h"
#include "analysis/plan_command.h"
#include "analysis/program_file.h"
#include "analysis/plan_timeline.h"
#include "models/bead/parabolic_bead.h"
#include "models/core/error.h"
#include "models/core/files.h"
#include "models/core/output_lock.h"
#include "models/core/numbers.h"
#include "models/core/progress.h"
#include "models/core/run_outputs.h"
#include "planner/program/program_motion.h"
#include "twin/cell/cell_check.h"
#include "twin/cell/mujoco_cell.h"

namespace waam::analysis {
namespace fs = std::filesystem;

planner::PlanResult PlanFromProgram(const Scenario& scenario, const planner::ParsedProgram& program,
                                    ImportReport* report) {
  const twin::CellModel cell = LoadCell(scenario.cell);
  const planner::CellKinematics kin = twin::PartKinematics(cell, scenario.cell);
  const planner::ProcessSettings& process = scenario.process;
  planner::ImportSettings settings;
  if (scenario.program.user_frame_mm) {
    const std::array<double, 6>& f = *scenario.program.user_frame_mm;
    Eigen::Isometry3d X_WU = Eigen::Isometry3d::Identity();
    X_WU.translation() = Eigen::Vector3d(f[0], f[1], f[2]);
    // W P R in degrees about fixed x, y, z: R = Rz(r) Ry(p) Rx(w).
    X_WU.linear() = (Eigen::AngleAxisd(f[5] * kPi / 180.0, Eigen::Vector3d::UnitZ()) *
                     Eigen::AngleAxisd(f[4] * kPi / 180.0, Eigen::Vector3d::UnitY()) *
                     Eigen::AngleAxisd(f[3] * kPi / 180.0, Eigen::Vector3d::UnitX()))
                        .toRotationMatrix();
    settings.X_WU = X_WU;
  }
  settings.bead_width_mm = scenario.path.bead_width_mm;
  const double area = models::BeadAreaFromWireFeed(process.wire_diameter_mm, process.wire_feed_mm_min,
                                                   process.travel_speed_mm_min, process.deposition_efficiency);
  settings.bead_height_mm = 1.5 * area / settings.bead_width_mm;  // eq. 3.3: A = 2 w h / 3
  settings.weld_speed_mm_s = process.travel_speed_mm_min / 60.0;
  settings.rapid_speed_mm_s = process.rapid_speed_mm_min / 60.0;
  settings.arc_step_mm = scenario.cell.step_mm;
  settings.layer_tolerance_mm = scenario.program.layer_tolerance_mm;
  planner::ImportedPlan imported = planner::ProgramToPlan(program, kin, settings);

  // The bead of each weld point from the wire feed and its own travel speed (eq. 3.4, then eq. 3.3).
  for (planner::LayerPath& layer : imported.plan.layers) {
    for (planner::PathPoint& p : layer.points) {
      if (!p.weld || p.speed_mm_s <= 0.0) continue;
      const double a = models::BeadAreaFromWireFeed(process.wire_diameter_mm, process.wire_feed_mm_min,
                                                    p.speed_mm_s * 60.0, process.deposition_efficiency);
      p.bead_height_mm = 1.5 * a / p.bead_width_mm;
    }
  }
  planner::PlanResult result;
  result.plan = std::move(imported.plan);
  if (result.plan.name.empty()) result.plan.name = scenario.name;
  result.stats = planner::ComputeStats(result.plan);
  result.timeline = CellTimeline(scenario, cell, result.plan);
  result.stats.estimated_time_s = result.timeline.total_s;
  result.bead_width_mm = settings.bead_width_mm;
  result.bead_area_mm2 = area;
  result.bead_height_mm = settings.bead_height_mm;
  result.layer_growth_mm = settings.bead_height_mm;
  result.travel_speed_mm_min = process.travel_speed_mm_min;
  double lo = 0.0, hi = 0.0, h_lo = 0.0, h_hi = 0.0;
  bool any = false;
  for (const planner::LayerPath& layer : result.plan.layers) {
    for (const planner::PathPoint& p : layer.points) {
      if (!p.weld) continue;
      const double v = p.speed_mm_s * 60.0;
      lo = any ? std::min(lo, v) : v, hi = any ? std::max(hi, v) : v;
      h_lo = any ? std::min(h_lo, p.bead_height_mm) : p.bead_height_mm;
      h_hi = any ? std::max(h_hi, p.bead_height_mm) : p.bead_height_mm;
      any = true;
    }
  }
  result.speed_min_mm_min = lo, result.speed_max_mm_min = hi;
  result.layer_height_min_mm = h_lo, result.layer_height_max_mm = h_hi;
  // Mean layer step along the build direction.
  const auto& layers = result.plan.layers;
  result.layer_height_mm =
      layers.size() > 1 ? (layers.back().z_mm - layers.front().z_mm) / static_cast<double>(layers.size() - 1)
                        : settings.bead_height_mm;
  for (const planner::ProgramWarning& w : imported.warnings) {
    result.warnings.push_back(w.what + " (" + std::to_string(w.count) + "x, first at line " +
                              std::to_string(w.first_line) + "): the check follows the program without it");
  }
  if (report != nullptr) {
    report->format = program.format;
    report->motions = program.motions.size();
    report->motions_by_kind = program.MotionsByKind();
    report->points = imported.points;
    report->warnings = imported.warnings;
  }
  return result;
}

planner::JbiReadOptions JbiOptionsOf(const Scenario& scenario, const std::vector<double>& robot,
                                     const std::vector<double>& station) {
  planner::JbiReadOptions jbi;
  // Absent from the scenario: zeros, which the reader and the JBI writer refuse naming the key and the option.
  jbi.robot_pulses_per_deg = scenario.program.yaskawa_pulses_per_deg.value_or(std::array<double, 6>{});
  jbi.station_pulses_per_deg = scenario.program.yaskawa_station_pulses_per_deg.value_or(std::array<double, 2>{});
  auto check = [](const std::vector<double>& v, std::size_t n, const char* flag) {
    WAAM_THROW_UNLESS(v.size() == n, flag << ": needs " << n << " values separated by commas, " << v.size()
                                          << " given");
    for (double x : v) WAAM_THROW_UNLESS(std::isfinite(x) && x > 0.0, flag << " = " << x << ": must be > 0");
  };
  if (!robot.empty()) {
    check(robot, 6, "--pulses-per-deg");
    for (int j = 0; j < 6; ++j) jbi.robot_pulses_per_deg[j] = robot[j];
  }
  if (!station.empty()) {
    check(station, 2, "--station-pulses-per-deg");
    jbi.station_pulses_per_deg = {station[0], station[1]};
  }
  return jbi;
}

nlohmann::json ImportToJson(const ImportReport& report) {
  nlohmann::json warnings = nlohmann::json::array();
  for (const planner::ProgramWarning& w : report.warnings) {
    warnings.push_back({{"what", w.what}, {"count", w.count}, {"first_line", w.first_line}});
  }
  return {{"format", report.format},
          {"motions", report.motions},
          {"motions_by_kind", report.motions_by_kind},
          {"points", report.points},
          {"warnings", warnings}};
}

planner::PlanResult ImportProgramInto(const ImportOptions& options, Scenario* scenario, ImportReport* report) {
  if (scenario->name.empty()) scenario->name = options.program.stem().string();
  const planner::GcodeReadOptions gcode = planner::GcodeOptionsOf(scenario->program);
  const planner::ParsedProgram program =
      ReadProgramFile(options.program, options.format, gcode,
                               JbiOptionsOf(*scenario, options.pulses_per_deg, options.station_pulses_per_deg),
                               scenario->program.frames);
  return PlanFromProgram(*scenario, program, report);
}

nlohmann::json ImportedPlanToJson(const Scenario& scenario, const planner::PlanResult& result,
                                  const ImportReport& report, const fs::path& program) {
  nlohmann::json summary = PlanToJson(scenario, result);
  summary["slicing"] = "program";
  summary["pattern"] = "program";
  summary["import"] = ImportToJson(report);
  summary["import"]["file"] = program.string();
  return summary;
}

nlohmann::json RunImport(const ImportOptions& options) {
  Scenario scenario;
  if (!options.scenario.empty()) {
    scenario = LoadScenario(options.scenario, options.overrides);
  } else {
    WAAM_THROW_UNLESS(options.overrides.empty(), "--set needs --scenario");
  }
  ImportReport report;
  const planner::PlanResult result = ImportProgramInto(options, &scenario, &report);

  const nlohmann::json summary = ImportedPlanToJson(scenario, result, report, options.program);
  WritePlanOutputs(result.plan, summary, options.out_dir, options.layer_images, options.quiet);
  for (const std::string& warning : result.warnings) std::cerr << "waam: warning: " << warning << "\n";
  return summary;
}

}  // namespace waam::analysis
