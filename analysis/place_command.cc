// `waam place`: a grid search over the cell layout, coarse pass first, the whole path for the finalists.
#include "analysis/place_command.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <map>
#include <mutex>
#include <numeric>
#include <optional>
#include <sstream>

#include <yaml-cpp/yaml.h>

#include "analysis/cell_files.h"
#include "analysis/import_command.h"
#include "analysis/scenario_keys.h"
#include "analysis/scenario_plan.h"
#include "models/core/error.h"
#include "models/core/files.h"
#include "models/core/json_text.h"
#include "models/core/output_lock.h"
#include "models/core/parallel.h"
#include "models/core/progress.h"
#include "models/core/run_outputs.h"
#include "planner/scenario/scenario_document.h"
#include "twin/cell/mujoco_cell.h"

namespace waam::analysis {
namespace fs = std::filesystem;

namespace {

std::vector<double> RangeValues(const std::optional<PlaceRange>& range, double current) {
  if (!range) return {current};
  if (range->step <= 0.0) return {range->min};
  std::vector<double> values;
  const auto n = static_cast<std::size_t>(std::floor((range->max - range->min) / range->step + 1e-9)) + 1;
  for (std::size_t i = 0; i < n; ++i) values.push_back(range->min + static_cast<double>(i) * range->step);
  return values;
}

// The plan with `keep` layers spread evenly over it (first and last included), each entered by an arc-off move:
// the coarse pass's path. Its samples are a subset of the whole path's, its violations a subset of the whole path's
// apart from the part collisions of the layers left out.
planner::Plan CoarsePlan(const planner::Plan& plan, int keep) {
  const std::size_t n = plan.layers.size();
  if (n <= static_cast<std::size_t>(keep)) return plan;
  planner::Plan coarse;
  coarse.name = plan.name;
  std::size_t last = n;
  for (int i = 0; i < keep; ++i) {
    const auto index = static_cast<std::size_t>(std::llround(static_cast<double>(i) * (n - 1) / (keep - 1)));
    if (index == last) continue;
    last = index;
    coarse.layers.push_back(plan.layers[index]);
    if (!coarse.layers.back().points.empty()) coarse.layers.back().points.front().weld = false;
  }
  return coarse;
}

std::string FormatValue(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// The key of the cell model a layout needs: the arm base and the positioner's yaw move bodies of the model.
std::array<double, 3> ModelKey(const Layout& layout) {
  return {layout[kPositionerYaw], layout[kRobotX], layout[kRobotY]};
}

nlohmann::json LayoutJson(const Layout& layout) {
  nlohmann::json j = nlohmann::json::object();
  for (int v = 0; v < kPlaceVars; ++v) j[PlaceVariableName(v)] = layout[v];
  return j;
}

nlohmann::json ScoreJson(const LayoutScore& s) {
  nlohmann::json j = {{"pass", s.full ? "full" : "coarse"},
                      {"violation_count", s.violations},
                      {"violating_samples", s.violating_samples},
                      {"margin", s.margin},
                      {"min_joint_margin_deg", s.min_joint_margin_deg},
                      {"min_j5_deg", s.min_j5_deg},
                      {"min_clearance_mm", s.min_clearance_mm}};
  if (s.bounded) j["bounded"] = true;
  if (!s.worst.empty()) {
    j["worst_violation"] = {{"what", s.worst}, {s.worst_unit, s.worst_value}, {"layer", s.worst_layer}};
  }
  return j;
}

}  // namespace

const char* PlaceVariableName(int variable) {
  static const char* const kNames[kPlaceVars] = {"part_x_mm",          "part_y_mm",          "part_z_mm",
                                                 "part_yaw_deg",       "table_rotation_deg", "positioner_yaw_deg",
                                                 "robot_x_mm",         "robot_y_mm"};
  return (variable >= 0 && variable < kPlaceVars) ? kNames[variable] : "?";
}

twin::CellSettings ApplyLayout(const twin::CellSettings& cell, const Layout& layout) {
  twin::CellSettings out = cell;
  out.part_offset_mm = {layout[kPartX], layout[kPartY], layout[kPartZ]};
  out.part_yaw_deg = layout[kPartYaw];
  out.positioner_rotation_deg = layout[kTableRotation];
  out.positioner_yaw_deg = layout[kPositionerYaw];
  out.robot_base_mm[0] = layout[kRobotX];
  out.robot_base_mm[1] = layout[kRobotY];
  twin::ValidateCellSettings(out);
  return out;
}

std::vector<std::string> LayoutOverrides(const Layout& layout, const Layout& current, double robot_z_mm) {
  std::vector<std::string> out;
  const auto differs = [&](std::initializer_list<int> vars) {
    for (int v : vars) {
      if (layout[v] != current[v]) return true;
    }
    return false;
  };
  if (differs({kPartX, kPartY, kPartZ})) {
    out.push_back("cell.part.offset_mm=[" + FormatValue(layout[kPartX]) + ", " + FormatValue(layout[kPartY]) + ", " +
                  FormatValue(layout[kPartZ]) + "]");
  }
  if (differs({kPartYaw})) out.push_back("cell.part.yaw_deg=" + FormatValue(layout[kPartYaw]));
  if (differs({kTableRotation})) out.push_back("cell.positioner.rotation_deg=" + FormatValue(layout[kTableRotation]));
  if (differs({kPositionerYaw})) out.push_back("cell.positioner.yaw_deg=" + FormatValue(layout[kPositionerYaw]));
  if (differs({kRobotX, kRobotY})) {
    out.push_back("cell.robot.base_mm=[" + FormatValue(layout[kRobotX]) + ", " + FormatValue(layout[kRobotY]) + ", " +
                  FormatValue(robot_z_mm) + "]");
  }
  return out;
}

LayoutScore ScoreLayout(const twin::CheckReport& report, const twin::CellSettings& cell, bool full) {
  const twin::CheckMargins m = twin::MarginsOf(report);
  LayoutScore s;
  s.full = full;
  s.violations = m.violations;
  s.violating_samples = m.violating_samples;
  for (const twin::CheckViolation& v : report.violations) {
    if (v.sample != report.worst_sample) continue;
    s.worst = std::string(NameOf(v.kind)) + " " + v.joint + v.body1 + (v.body2.empty() ? "" : "/") + v.body2;
    while (!s.worst.empty() && s.worst.back() == ' ') s.worst.pop_back();
    s.worst_unit = v.unit;
    s.worst_value = v.value;
    s.worst_layer = v.layer;
    break;
  }
  s.min_joint_margin_deg = m.min_arm_margin_deg;
  s.min_j5_deg = m.min_j5_deg;
  s.min_clearance_mm = m.min_clearance_mm;
  s.margin = twin::CheckMargin(m, cell);
  s.abandoned = report.resolve.abandoned;
  s.bounded = report.bounded;
  return s;
}

bool BetterLayout(const LayoutScore& a, const LayoutScore& b) {
  if (a.violating_samples != b.violating_samples) return a.violating_samples < b.violating_samples;
  return a.margin > b.margin;
}

void WritePlaceMarginPng(const PlaceResult& result, const fs::path& path);  // place_picture.cc

namespace {

using CellModels = std::map<std::array<double, 3>, twin::CellModel>;

// CPU time of the process (every thread) since `start`, s.
double CpuSince(std::clock_t start) { return static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC; }

// Every layout of the grid over `values` (per variable the values searched), the last variable varying fastest.
std::vector<Layout> LayoutGrid(const std::vector<std::vector<double>>& values) {
  std::size_t count = 1;
  for (const std::vector<double>& v : values) count *= v.size();
  std::vector<Layout> layouts(count);
  for (std::size_t i = 0; i < count; ++i) {
    std::size_t rest = i;
    for (int v = kPlaceVars - 1; v >= 0; --v) {
      const std::size_t n = values[v].size();
      layouts[i][v] = values[v][rest % n];
      rest /= n;
    }
  }
  return layouts;
}

// The bar a layout's coarse check must beat to reach the whole path: the `keep`-th best of the coarse checks done
// whole among `scores` (none while fewer than `keep` are). A check proven worse has `keep` layouts better than it
// and is never among the `keep` the whole path may take (CheckFinalists).
std::optional<twin::CheckBar> CoarseBar(const std::vector<LayoutScore>& scores, std::size_t keep) {
  std::vector<const LayoutScore*> whole;
  for (const LayoutScore& s : scores) {
    if (!s.bounded) whole.push_back(&s);
  }
  if (keep == 0 || whole.size() < keep) return std::nullopt;
  std::nth_element(whole.begin(), whole.begin() + static_cast<std::ptrdiff_t>(keep - 1), whole.end(),
                   [](const LayoutScore* a, const LayoutScore* b) { return BetterLayout(*a, *b); });
  const LayoutScore& bar = *whole[keep - 1];
  return twin::CheckBar{bar.violating_samples, bar.margin};
}

// Coarse pass: `coarse_plan` at a step of at least `coarse_step_mm` with cell.resolve fixed, every layout of
// `result`, `keep` layouts at a time (in parallel over a batch); with cell.prune, each batch's checks stop once
// proven worse than CoarseBar of the batches before (a bar that does not depend on the threads). Fills
// result->coarse, coarse_bounded and coarse_s.
void CheckCoarse(const planner::Plan& coarse_plan, const twin::CellSettings& cell, double coarse_step_mm,
                 double rapid_mm_s, const CellModels& models, std::size_t keep, bool quiet, PlaceResult* result) {
  const std::size_t count = result->layouts.size();
  result->coarse.resize(count);
  const auto start = std::chrono::steady_clock::now();
  const std::clock_t cpu_start = std::clock();
  Progress progress("place", count, "layouts", quiet);
  std::mutex mutex;
  std::size_t done = 0;
  for (std::size_t first = 0; first < count; first += keep) {
    const std::size_t batch = std::min(keep, count - first);
    std::optional<twin::CheckBar> bar;
    if (cell.prune) bar = CoarseBar({result->coarse.begin(), result->coarse.begin() + first}, keep);
    ParallelFor(batch, [&](std::size_t k) {
      const std::size_t i = first + k;
      twin::CellSettings settings = ApplyLayout(cell, result->layouts[i]);
      settings.step_mm = std::max(settings.step_mm, coarse_step_mm);
      settings.resolve = twin::CellResolve::kFixed;  // the ranking needs the layout's effect, not the resolution's
      const twin::CellModel& model = models.at(ModelKey(result->layouts[i]));
      const twin::CheckReport report = bar ? twin::CheckPlanBounded(model, coarse_plan, settings, rapid_mm_s, *bar)
                                           : twin::CheckPlan(model, coarse_plan, settings, rapid_mm_s, nullptr);
      result->coarse[i] = ScoreLayout(report, settings, false);
      const std::lock_guard<std::mutex> lock(mutex);
      progress.Update(++done);
    });
  }
  progress.Finish();
  for (const LayoutScore& s : result->coarse) result->coarse_bounded += s.bounded ? 1 : 0;
  result->coarse_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result->coarse_cpu_s = CpuSince(cpu_start);
}

// Full checks of `plan`: the best of the coarse pass, `finalists` at a time, until one passes or the coarse pass's
// passing layouts are used up (at most 4 batches); fills result->full, full_index, best, best_score, feasible and
// full_s.
void CheckFinalists(const planner::Plan& plan, const twin::CellSettings& cell, int finalists, double rapid_mm_s,
                    const CellModels& models, bool quiet, PlaceResult* result) {
  const std::size_t count = result->layouts.size();
  std::vector<int> order(count);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return BetterLayout(result->coarse[a], result->coarse[b]); });
  const auto start = std::chrono::steady_clock::now();
  const std::clock_t cpu_start = std::clock();
  const std::size_t cap = std::min<std::size_t>(count, 4 * static_cast<std::size_t>(finalists));
  Progress progress("full", 0, "layouts", quiet);
  for (std::size_t next = 0; next < cap && !result->feasible;) {
    const std::size_t batch = std::min<std::size_t>(finalists, cap - next);
    // Past the first batch only layouts that passed the coarse pass are worth the whole path.
    if (next > 0 && result->coarse[order[next]].violating_samples > 0) break;
    std::vector<LayoutScore> scores(batch);
    ParallelFor(batch, [&](std::size_t k) {
      const Layout& layout = result->layouts[order[next + k]];
      const twin::CellSettings settings = ApplyLayout(cell, layout);
      const twin::CheckReport report = twin::CheckPlan(models.at(ModelKey(layout)), plan, settings, rapid_mm_s, nullptr);
      scores[k] = ScoreLayout(report, settings, true);
    });
    for (std::size_t k = 0; k < batch; ++k) {
      result->full_index.push_back(order[next + k]);
      result->full.push_back(scores[k]);
      if (result->best < 0 || BetterLayout(scores[k], result->best_score)) {
        result->best = order[next + k];
        result->best_score = scores[k];
      }
      result->feasible = result->feasible || scores[k].violating_samples == 0;
    }
    next += batch;
    progress.SetTotal(cap);
    progress.Update(next);
  }
  progress.Finish();
  result->full_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result->full_cpu_s = CpuSince(cpu_start);
}

// The text of scenario.yaml: the scenario with `overrides` (the best layout's among them) and `base_dir` pointing back
// at its files, under a comment saying whether it passes.
std::string PlacedScenarioYaml(const PlaceOptions& options, const Scenario& scenario,
                               const std::vector<std::string>& overrides, bool feasible) {
  YAML::Node document = LoadScenarioTop(options.scenario, overrides).node();
  std::error_code ec;
  const fs::path out_abs = fs::absolute(options.out_dir, ec).lexically_normal();
  const fs::path base_dir = scenario.dir.lexically_relative(out_abs);
  document["base_dir"] = base_dir.empty() ? scenario.dir.string() : base_dir.string();
  YAML::Emitter emitter;
  emitter << document;
  std::ostringstream text;
  text << "# " << (feasible ? "The layout waam place found" : "The nearest miss waam place found (it does not pass)")
       << " for " << options.scenario.string() << "; place.json has every layout tried.\n"
       << "# base_dir: relative paths below are resolved against the original scenario's folder.\n"
       << emitter.c_str() << "\n";
  return text.str();
}

// place.json: every layout tried with its coarse (and full) score, the best one as `best_json`.
nlohmann::json PlaceJson(const PlaceResult& result, const std::string& scenario_name, const nlohmann::json& best_json,
                         std::size_t coarse_layers, double coarse_step_mm, bool exhaustive) {
  const std::size_t count = result.layouts.size();
  std::size_t abandoned = 0;
  for (const LayoutScore& s : result.full) abandoned += s.abandoned ? 1 : 0;
  nlohmann::json variables = nlohmann::json::array();
  for (int v = 0; v < kPlaceVars; ++v) variables.push_back({{"name", PlaceVariableName(v)}, {"values", result.values[v]}});
  nlohmann::json tried = nlohmann::json::array();
  std::vector<int> full_of(count, -1);
  for (std::size_t k = 0; k < result.full_index.size(); ++k) full_of[result.full_index[k]] = static_cast<int>(k);
  for (std::size_t i = 0; i < count; ++i) {
    nlohmann::json entry = {{"layout", LayoutJson(result.layouts[i])}, {"coarse", ScoreJson(result.coarse[i])}};
    if (full_of[i] >= 0) entry["full"] = ScoreJson(result.full[full_of[i]]);
    tried.push_back(entry);
  }
  return {
      {"scenario", scenario_name},
      {"feasible", result.feasible},
      {"best", best_json},
      {"scenario_file", "scenario.yaml"},
      {"variables", variables},
      {"layouts", count},
      {"coarse_layers", coarse_layers},
      {"coarse_step_mm", coarse_step_mm},
      {"full_checks", result.full.size()},
      {"pruning", {{"enabled", !exhaustive},
                   {"coarse_bounded", result.coarse_bounded},
                   {"resolved_checks_abandoned", abandoned}}},
      {"tried", tried},
      {"timing", {{"coarse_s", result.coarse_s},
                  {"full_s", result.full_s},
                  {"coarse_cpu_s", result.coarse_cpu_s},
                  {"full_cpu_s", result.full_cpu_s},
                  {"coarse_layouts_per_s", result.coarse_s > 0.0 ? count / result.coarse_s : 0.0}}},
  };
}

}  // namespace

PlaceResult RunPlace(const PlaceOptions& options) {
  const Scenario scenario = LoadScenario(options.scenario, options.overrides);
  ClaimOutputDirectory(options.out_dir);
  planner::PlanResult planned = PlanForCommand(scenario, options.quiet);
  const planner::Plan& plan = planned.plan;
  const PlaceSettings& place = scenario.place;
  twin::CellSettings cell = scenario.cell;
  cell.prune = !options.exhaustive;
  const double rapid_mm_s = scenario.process.rapid_speed_mm_min / 60.0;

  PlaceResult result;
  const Layout current = {cell.part_offset_mm[0], cell.part_offset_mm[1], cell.part_offset_mm[2], cell.part_yaw_deg,
                          cell.positioner_rotation_deg, cell.positioner_yaw_deg, cell.robot_base_mm[0],
                          cell.robot_base_mm[1]};
  const std::optional<PlaceRange>* ranges[kPlaceVars] = {
      &place.part_x_mm,          &place.part_y_mm,          &place.part_z_mm,  &place.part_yaw_deg,
      &place.table_rotation_deg, &place.positioner_yaw_deg, &place.robot_x_mm, &place.robot_y_mm};
  for (int v = 0; v < kPlaceVars; ++v) result.values.push_back(RangeValues(*ranges[v], current[v]));
  result.layouts = LayoutGrid(result.values);

  // One cell model per arm base and positioner yaw (MuJoCo compiles a model per placement), loaded in order.
  CellModels models;
  for (const Layout& layout : result.layouts) {
    if (!models.count(ModelKey(layout))) models.emplace(ModelKey(layout), LoadCell(ApplyLayout(cell, layout)));
  }

  // Coarse pass: a subset of the layers at a coarser step, every layout, in parallel over layouts.
  const planner::Plan coarse_plan = CoarsePlan(plan, place.coarse_layers);
  const std::size_t keep = 4 * static_cast<std::size_t>(place.finalists);  // the most the whole path may take
  CheckCoarse(coarse_plan, cell, place.coarse_step_mm, rapid_mm_s, models, keep, options.quiet, &result);

  CheckFinalists(plan, cell, place.finalists, rapid_mm_s, models, options.quiet, &result);

  // Outputs: the scenario with the best layout, the picture, place.json last.
  RunOutputs outputs(options.out_dir / "place.json");
  const Layout& best = result.layouts[result.best];
  std::vector<std::string> overrides = options.overrides;
  const std::vector<std::string> best_overrides = LayoutOverrides(best, current, cell.robot_base_mm[2]);
  overrides.insert(overrides.end(), best_overrides.begin(), best_overrides.end());
  if (result.feasible) overrides.push_back("run.expected_exit_code=0");
  // The placed scenario meets every key's limits (the cell's included) before it is written.
  Scenario placed = scenario;
  placed.cell = ApplyLayout(scenario.cell, best);
  ValidateScenario(placed);
  const std::string text = PlacedScenarioYaml(options, scenario, overrides, result.feasible);
  WriteFileAtomic(outputs.Add(options.out_dir / "scenario.yaml"), text);
  if (options.images) WritePlaceMarginPng(result, outputs.Add(options.out_dir / "place_margin.png"));

  nlohmann::json best_json = ScoreJson(result.best_score);
  best_json["layout"] = LayoutJson(best);
  best_json["overrides"] = best_overrides;
  const nlohmann::json document_json = PlaceJson(result, scenario.name, best_json, coarse_plan.layers.size(),
                                                 std::max(cell.step_mm, place.coarse_step_mm), options.exhaustive);
  CheckInterrupt();
  WriteFileAtomic(options.out_dir / "place.json", JsonText(document_json) + "\n");
  outputs.Complete();
  return result;
}

}  // namespace waam::analysis
