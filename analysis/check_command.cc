// `waam check`: the cell check of a planned path and its outputs.
#include "analysis/check_command.h"

#include <cmath>

#include "analysis/cell_files.h"
#include "analysis/scenario.h"
#include "analysis/viewer.h"
#include "models/core/error.h"
#include "models/core/files.h"
#include "models/core/json_text.h"
#include "models/core/output_lock.h"
#include "models/core/numbers.h"
#include "models/core/progress.h"
#include "models/core/run_outputs.h"
#include "planner/program/fanuc_ls.h"
#include "planner/program/robot_program.h"
#include "twin/cell/mujoco_cell.h"

namespace waam::analysis {
namespace fs = std::filesystem;

namespace {

// JSON numbers must be finite.
double Finite(double v) { return std::isfinite(v) ? v : 0.0; }

constexpr std::size_t kMaxViolationsListed = 1000;

// The first kMaxViolationsListed violations of the check, as check.json lists them.
nlohmann::json ViolationsJson(const twin::CheckReport& report) {
  nlohmann::json violations = nlohmann::json::array();
  for (std::size_t i = 0; i < report.violations.size() && i < kMaxViolationsListed; ++i) {
    const twin::CheckViolation& v = report.violations[i];
    nlohmann::json j = {{"kind", v.kind},          {"point", v.point},           {"layer", v.layer},
                        {"first_point", v.first_point}, {"last_point", v.last_point}, {"samples", v.samples},
                        {v.unit, Finite(v.value)}};
    if (v.kind == twin::ViolationKind::kCollision) {
      j["bodies"] = {v.body1, v.body2};
    } else if (!v.joint.empty()) {
      j["joint"] = v.joint;
    }
    if (v.t_s >= 0.0) {
      j["t_s"] = v.t_s;
      j["between_samples"] = v.between_samples;
    }
    violations.push_back(j);
  }
  return violations;
}

// Positioner angles and torch tilt where each layer's welding starts.
nlohmann::json LayerStartsJson(const twin::CheckReport& report) {
  nlohmann::json layers = nlohmann::json::array();
  int last_layer = -1;
  for (const planner::CellSample& s : report.motion) {
    if (!s.weld || s.layer == last_layer) continue;
    last_layer = s.layer;
    layers.push_back({{"layer", s.layer},
                      {"tilt_deg", s.q[6] * 180.0 / kPi},
                      {"rotation_deg", s.q[7] * 180.0 / kPi},
                      {"positioner_at_limit", s.positioner_at_limit},
                      {"torch_tilt_deg", s.torch_tilt_rad * 180.0 / kPi}});
  }
  return layers;
}

// How the positioner's redundancy was resolved: the mode and, when optimised, the margins before and after.
nlohmann::json ResolveJson(const twin::CheckReport& report, const twin::CellSettings& c) {
  const auto margins_json = [&](const twin::CheckMargins& m) {
    return nlohmann::json{{"violation_count", m.violations},
                          {"violating_samples", m.violating_samples},
                          {"min_arm_margin_deg", Finite(m.min_arm_margin_deg)},
                          {"min_j5_deg", Finite(m.min_j5_deg)},
                          {"min_clearance_mm", Finite(m.min_clearance_mm)},
                          {"max_joint_speed_ratio", Finite(m.max_joint_speed_ratio)},
                          {"margin", Finite(twin::CheckMargin(m, c))}};
  };
  nlohmann::json resolve = {{"mode", report.resolve.mode}};
  if (report.resolve.mode == twin::CellResolve::kOptimise) {
    double lo = 0.0, hi = 0.0;
    int turned = 0;
    for (double spin : report.resolve.layer_spin_deg) {
      lo = std::min(lo, spin);
      hi = std::max(hi, spin);
      turned += spin != 0.0;
    }
    resolve["kept"] = report.resolve.kept_fixed ? "fixed" : "optimise";
    resolve["before"] = margins_json(report.resolve.before);
    resolve["after"] = margins_json(report.resolve.after);
    resolve["spin_deg"] = {{"min", lo}, {"max", hi}, {"layers_turned", turned}};
    resolve["layer_spin_deg"] = report.resolve.layer_spin_deg;
  }
  return resolve;
}

// What the mode covered: the sweep's figures in continuous mode, null otherwise (mode_fallback says why).
nlohmann::json ContinuousJson(const twin::CheckReport& report) {
  nlohmann::json sweep = nullptr;
  if (report.mode == twin::CheckMode::kContinuous) {
    sweep = {{"certified_clearance_mm", Finite(report.certified_clearance_mm)},
             {"min_distance_mm", Finite(report.sweep_min_distance_mm)},
             {"closest_bodies", {report.closest_body1, report.closest_body2}},
             {"closest_t_s", Finite(report.closest_t_s)},
             {"first_contact_s", report.first_contact_s >= 0.0 ? nlohmann::json(report.first_contact_s) : nullptr},
             {"gjk_queries", report.gjk_queries},
             {"poses", report.poses},
             {"refinements", report.refinements},
             {"part_clearance_mm", std::isfinite(report.part_clearance_mm) ? nlohmann::json(report.part_clearance_mm) : nullptr},
             {"part_queries", report.part_queries}};
  }
  return sweep;
}

// The cell the check ran in.
nlohmann::json CellJson(const twin::CellSettings& c, const fs::path& mjcf, const twin::CheckReport& report) {
  return {{"mjcf", mjcf.string()},
          {"robot_base_mm", c.robot_base_mm},
          {"robot_yaw_deg", c.robot_yaw_deg},
          {"positioner_base_mm", c.positioner_base_mm},
          {"positioner_yaw_deg", c.positioner_yaw_deg},
          {"positioner_type", report.positioner_type},
          {"positioner_follow", c.positioner_follow},
          {"positioner_tilt_tolerance_deg", c.positioner_tilt_tolerance_deg},
          {"part_offset_mm", c.part_offset_mm},
          {"part_yaw_deg", c.part_yaw_deg},
          {"joint_margin_deg", c.joint_margin_deg},
          {"singularity_deg", c.singularity_deg},
          {"collision_tolerance_mm", c.collision_tolerance_mm}};
}

}  // namespace

nlohmann::json CheckToJson(const Scenario& scenario, const fs::path& mjcf, const twin::CheckReport& report) {
  const nlohmann::json violations = ViolationsJson(report);
  nlohmann::json accel = nlohmann::json::object();
  for (int a = 0; a < 8; ++a) accel[twin::AxisName(a)] = Finite(report.max_accel_deg_s2[a]);
  const twin::CellSettings& c = scenario.cell;
  const int worst_point = report.motion.empty() ? 0 : report.motion[report.worst_sample].point;
  return {
      {"mode", report.mode},
      {"mode_fallback", report.mode_fallback},
      {"distance_queries", report.distance_queries},
      {"continuous", ContinuousJson(report)},
      {"scenario", scenario.name},
      {"ok", report.ok},
      {"ik", report.ik},
      {"robot", {{"name", report.robot.name}, {"source", report.robot.source}, {"ik", report.ik},
                 {"joints", report.robot.joints}}},
      {"points", report.points},
      {"samples", report.samples},
      {"step_mm", c.step_mm},
      {"violations", violations},
      {"violation_count", report.violations.size()},
      {"min_joint_margin_deg", Finite(report.min_joint_margin_deg)},
      {"min_margin_joint", report.min_margin_joint},
      {"min_arm_margin_deg", Finite(report.min_arm_margin_deg)},
      {"max_joint_speed_ratio", Finite(report.max_joint_speed_ratio)},
      {"max_speed_joint", report.max_speed_joint},
      {"min_j5_deg", Finite(report.min_j5_deg)},
      {"min_clearance_mm", Finite(report.min_clearance_mm)},
      {"max_joint_accel_deg_s2", accel},
      {"duration_s", Finite(report.duration_s)},
      {"positioner_limit_layers", report.positioner_limit_layers},
      {"max_torch_tilt_deg", Finite(report.max_torch_tilt_deg)},
      {"worst_point", worst_point},
      {"resolve", ResolveJson(report, c)},
      {"layers", LayerStartsJson(report)},
      {"cell", CellJson(c, mjcf, report)},
  };
}

twin::CheckReport RunCheckOnPlan(const Scenario& scenario, const planner::Plan& plan,
                                 const CheckOptions& options) {
  ClaimOutputDirectory(options.out_dir);
  RemoveEarlierSummary(options.out_dir / "check.json");
  const twin::CellModel cell = LoadCell(scenario.cell);
  twin::CheckReport report;
  {
    Progress progress("check", 0, "samples", options.quiet);
    report = twin::CheckPlan(cell, plan, scenario.cell, scenario.process.rapid_speed_mm_min / 60.0, &progress);
    progress.Finish();
  }
  WriteCheckOutputs(scenario, plan, cell, report, options);
  return report;
}

nlohmann::json CheckPlanToJson(const Scenario& scenario, const twin::CellModel& cell, const planner::Plan& plan,
                               const twin::CheckReport& report) {
  nlohmann::json document = CheckToJson(scenario, cell.file(), report);
  if (plan.X_FT) {
    // The program's own tool moved instead of the cell's torch: how far apart the two TCPs are.
    const planner::CellKinematics kin = twin::PartKinematics(cell, scenario.cell);
    const Eigen::Isometry3d X_TT = kin.X_FT.inverse() * *plan.X_FT;
    const double offset_mm = X_TT.translation().norm();
    const double angle_deg = Eigen::AngleAxisd(X_TT.linear()).angle() * kDeg;
    document["tool"] = {{"source", "program"},
                        {"name", plan.tool_name},
                        {"offset_from_torch_mm", offset_mm},
                        {"angle_from_torch_deg", angle_deg},
                        {"differs_from_torch", offset_mm > 0.01 || angle_deg > 0.01}};
  }
  return document;
}

nlohmann::json WriteCheckOutputs(const Scenario& scenario, const planner::Plan& plan, const twin::CellModel& cell,
                                 const twin::CheckReport& report, const CheckOptions& options) {
  ClaimOutputDirectory(options.out_dir);
  RunOutputs outputs(options.out_dir / "check.json");
  const planner::CellKinematics kin = twin::PartKinematics(cell, scenario.cell);
  if (options.program) {
    const planner::RobotProgram program = planner::BuildProgram(kin, report.motion, scenario.name);
    WriteFileAtomic(outputs.Add(options.out_dir / "program.csv"), planner::ProgramToCsv(program));
    WriteFileAtomic(outputs.Add(options.out_dir / "program.ls"),
                    planner::ProgramToFanucLs(program, planner::FanucLsOptions{}));
  }
  if (options.images && !report.motion.empty()) {
    WriteCellPng(cell, kin, plan, report, scenario.name, outputs.Add(options.out_dir / "cell_worst.png"));
    WriteJointPlots(kin, report, scenario.name, outputs.Add(options.out_dir / "joints.png"));
  }
  nlohmann::json document = CheckPlanToJson(scenario, cell, plan, report);
  if (options.images && options.viewer) {
    const ViewerSummary viewer = WriteViewer(scenario.name, cell, kin, plan, options.target, report,
                                             outputs.Add(options.out_dir / "viewer.html"));
    document["viewer"] = {{"file", "viewer.html"},       {"frames", viewer.frames},
                          {"bodies", viewer.bodies},     {"violations", viewer.violations},
                          {"path_points", viewer.path_points}, {"beads", viewer.beads},
                          {"bytes", viewer.bytes}};
  }
  CheckInterrupt();  // a Ctrl-C while the outputs were written still ends the run as interrupted (exit 130)
  WriteFileAtomic(options.out_dir / "check.json", JsonText(document) + "\n");
  outputs.Complete();
  return document;
}

}  // namespace waam::analysis
