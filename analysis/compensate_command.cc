// `waam compensate`: plan the scenario, run the compensation loop in the twin, write the corrected path and program.
#include <iostream>

#include "analysis/check_command.h"
#include "analysis/compensate_heat.h"
#include "analysis/distortion_command.h"
#include "analysis/plan_command.h"
#include "analysis/scenario.h"
#include "models/core/error.h"
#include "models/core/files.h"
#include "models/core/json_text.h"
#include "models/core/output_lock.h"
#include "models/core/progress.h"
#include "models/fit/model_file.h"
#include "planner/plan_scenario.h"
#include "planner/scenario/scenario.h"
#include "analysis/point_cloud_file.h"

namespace waam::analysis {
namespace {

nlohmann::json IterationJson(const twin::CompensationIteration& it) {
  return {{"max_abs_deviation_mm", it.max_abs_deviation_mm},
          {"rms_deviation_mm", it.rms_deviation_mm},
          {"p99_abs_deviation_mm", it.p99_abs_deviation_mm},
          {"min_deviation_mm", it.min_deviation_mm},
          {"max_deviation_mm", it.max_deviation_mm},
          {"axis_deviation_mm", it.axis_deviation_mm},
          {"ovality_pct", it.ovality_pct},
          {"max_abs_vs_target_mm", it.max_abs_vs_target_mm},
          {"rms_vs_target_mm", it.rms_vs_target_mm},
          {"max_correction_mm", it.max_correction_mm},
          {"top_band_mm", it.top_band_mm},
          {"real_scan", it.real_scan},
          {"twin_correction_error_mm", it.twin_correction_error_mm},
          {"distortion",
           {{"elements", it.distortion.elements},
            {"dofs", it.distortion.dofs},
            {"nonzeros", it.distortion.nonzeros},
            {"solves", it.distortion.solves},
            {"dropped_elements", it.distortion.dropped_elements},
            {"solve_s", it.distortion.solve_s},
            {"max_displacement_mm", it.distortion.max_displacement_mm}}}};
}

// The loop's options from the command's and the scenario's: the distortion model at `model_path`, its mode, the
// correction method and the real first scan when one is given. Throws InputError for a bad value or file.
twin::CompensationOptions LoopOptions(const CompensateOptions& options, const Scenario& scenario,
                                      const std::filesystem::path& model_path) {
  twin::CompensationOptions loop;
  loop.params = models::ReadDistortionParams(model_path);
  loop.max_iterations = options.max_iterations;
  loop.tolerance_mm = options.tolerance_mm;
  loop.rapid_speed_mm_s = scenario.process.rapid_speed_mm_min / 60.0;
  loop.wire_feed_mm_s = scenario.process.wire_feed_mm_min / 60.0;
  loop.bead_width_mm = scenario.path.bead_width_mm;
  loop.distortion.mode =
      options.mode.empty() ? loop.params.mode : models::ParseDistortionMode(options.mode, "distortion.mode");
  loop.distortion.element_mm = options.element_mm;
  loop.distortion.groups = options.groups;
  const std::optional<twin::CorrectionMethod> correction = ParseEnum<twin::CorrectionMethod>(options.correction);
  WAAM_THROW_UNLESS(correction.has_value(), "--correction = '" << options.correction << "': must be one of "
                                                               << EnumNameList<twin::CorrectionMethod>());
  loop.correction = *correction;
  loop.debug_level = options.debug_level;
  twin::ValidateDistortionOptions(loop.distortion);
  if (!options.first_scan.empty()) {
    ScanCloud cloud = ReadScan(options.first_scan, 0.5, /*skip_bottom=*/true);
    loop.first_scan = std::move(cloud.points);
    loop.first_scan_weight = std::move(cloud.weight);
  }
  return loop;
}

// The scans before and after compensation (PLY with their deviations, and their pictures unless turned off).
void WriteScans(const twin::CompensationResult& result, const CompensateOptions& options) {
  WritePlyWithDeviation(options.out_dir / "scan_before.ply", result.first_scan.points,
                              result.first_scan.deviation_mm);
  WritePlyWithDeviation(options.out_dir / "scan_after.ply", result.last_scan.points,
                              result.last_scan.deviation_mm);
  if (options.images) {
    const double range = std::max(result.first_scan.max_abs_mm, result.last_scan.max_abs_mm);
    WriteScanDeviationPng(result.first_scan, "before compensation", range, options.out_dir / "deviation_before.png");
    WriteScanDeviationPng(result.last_scan,
                          "after " + std::to_string(result.iterations.size() - 1) + " compensation(s)", range,
                          options.out_dir / "deviation_after.png");
  }
}

// The compensated path through the cell check, which writes program.ls / program.csv for the robot, when asked for;
// returns compensate.json's "program".
nlohmann::json WriteProgram(const Scenario& scenario, const twin::CompensationResult& result,
                            const CompensateOptions& options) {
  if (!options.program) return {{"written", false}};
  CheckOptions check;
  check.out_dir = options.out_dir / "program";
  check.quiet = true;
  check.images = false;
  check.program = true;
  RunCheckOnPlan(scenario, result.plan, check);
  return {{"written", true}, {"dir", "program"}, {"check", "program/check.json"}};
}

nlohmann::json CompensateJson(const Scenario& scenario, const std::filesystem::path& model_path,
                              const twin::CompensationOptions& loop, const twin::CompensationResult& result,
                              const CompensateOptions& options, const nlohmann::json& heat,
                              const nlohmann::json& program) {
  nlohmann::json iterations = nlohmann::json::array();
  for (const twin::CompensationIteration& it : result.iterations) iterations.push_back(IterationJson(it));
  return {
      {"scenario", scenario.name},
      {"model", model_path.string()},
      {"mode", loop.distortion.mode},
      {"element_mm", loop.distortion.element_mm},
      {"groups", loop.distortion.groups},
      {"reference", result.reference},
      {"correction", loop.correction},
      {"tolerance_mm", result.tolerance_mm},
      {"waviness_mm", result.waviness_mm},
      {"waviness_median_mm", result.waviness_median_mm},
      {"top_band_mm", result.top_band_mm},
      {"converged", result.converged},
      {"status", result.status},
      {"message", result.message},
      {"first_scan", options.first_scan.empty() ? "" : options.first_scan.string()},
      {"iterations", iterations},
      {"heat", heat},
      {"program", program},
  };
}

}  // namespace

twin::CompensationResult RunCompensate(const CompensateOptions& options) {
  const Scenario scenario = LoadScenario(options.scenario, options.overrides);
  const std::filesystem::path model_path =
      options.model.empty() ? models::DefaultModelPath("distortion") : options.model;
  twin::CompensationOptions loop = LoopOptions(options, scenario, model_path);
  planner::PlanResult planned;
  {
    Progress progress("plan", 0, "layers", options.quiet);
    planned = planner::PlanScenario(scenario, &progress);
  }
  WAAM_THROW_UNLESS(!planned.mesh.facets.empty(), options.scenario.string() << ": compensate needs a target part mesh");
  ClaimOutputDirectory(options.out_dir);
  const nlohmann::json heat = PrepareHeatShape(scenario, planned.plan, options.quiet, &loop);
  Progress progress("compensate", static_cast<std::size_t>(options.max_iterations) + 1, "builds", options.quiet);
  const twin::CompensationResult result =
      twin::Compensate(planned.plan, planned.mesh, scenario.simulation, loop,
                       [&](int i, const twin::CompensationIteration&) { progress.Update(i + 1); });
  progress.Finish();

  WritePlanH5(result.plan, options.out_dir / "compensated_path.h5");
  WriteScans(result, options);
  const nlohmann::json program = WriteProgram(scenario, result, options);
  const nlohmann::json json = CompensateJson(scenario, model_path, loop, result, options, heat, program);
  WriteFileAtomic(options.out_dir / "compensate.json", JsonText(json) + "\n");
  if (!options.quiet) std::cerr << "compensate: " << result.message << "\n";
  return result;
}

}  // namespace waam::analysis
