// waam_twin.plan, check and simulate: the steps of `waam plan`, `waam check` and `waam simulate` in memory, their
// arrays as numpy views owned by the result objects.
#include <chrono>

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "analysis/cell_files.h"
#include "analysis/check_command.h"
#include "analysis/import_command.h"
#include "analysis/scenario_plan.h"
#include "analysis/plan_command.h"
#include "analysis/plan_timeline.h"
#include "analysis/simulate_command.h"
#include "python/bindings.h"
#include "python/steps.h"
#include "twin/cell/cell_check.h"
#include "twin/cell/mujoco_cell.h"
#include "twin/simulation.h"

namespace waam::python {
namespace fs = std::filesystem;

namespace {

// The columns of plan.h5 (docs/OUTPUTS.md), one row per path point.
constexpr int kPlanColumns = 11;
const char* const kPlanColumnNames[kPlanColumns] = {"x_mm",          "y_mm",           "z_mm",
                                                    "tool_x",        "tool_y",         "tool_z",
                                                    "bead_width_mm", "bead_height_mm", "travel_speed_mm_min",
                                                    "weld",          "layer"};

}  // namespace

void FillTable(PlanHolder* h) {
  h->offsets.assign(1, 0);
  for (const planner::LayerPath& layer : h->result.plan.layers) {
    for (const planner::PathPoint& p : layer.points) {
      const double row[kPlanColumns] = {p.p_P.x(), p.p_P.y(), p.p_P.z(), p.tool_dir_P.x(), p.tool_dir_P.y(),
                                        p.tool_dir_P.z(), p.bead_width_mm, p.bead_height_mm, p.speed_mm_s * 60.0,
                                        p.weld ? 1.0 : 0.0, static_cast<double>(layer.index)};
      h->table.insert(h->table.end(), row, row + kPlanColumns);
    }
    h->offsets.push_back(h->table.size() / kPlanColumns);
  }
}

std::shared_ptr<PlanHolder> PlanOf(const std::shared_ptr<const ScenarioHolder>& scn) {
  auto h = std::make_shared<PlanHolder>();
  h->scenario = scn;
  Progress progress("plan", 0, "layers", /*quiet=*/true);
  h->result = analysis::PlanScenarioOrProgram(scn->scenario, &progress, &h->import);
  // As `waam plan`: a planned part's timeline on the cell (a program's import builds its own).
  if (!scn->scenario.program.present) analysis::AddCellTimeline(scn->scenario, &h->result);
  FillTable(h.get());
  return h;
}

nlohmann::json PlanDocument(const PlanHolder& plan) {
  if (plan.imported) return analysis::ImportedPlanToJson(plan.scenario->scenario, plan.result, plan.import, *plan.imported);
  return analysis::PlanDocument(plan.scenario->scenario, plan.result, plan.import);
}

void SavePlan(const PlanHolder& plan, const fs::path& dir, bool images) {
  py::gil_scoped_release release;
  analysis::WritePlanOutputs(plan.result.plan, PlanDocument(plan), dir, images, /*quiet=*/true);
}

void SaveCheck(const CheckHolder& check, const fs::path& dir, bool images) {
  py::gil_scoped_release release;
  analysis::CheckOptions options;
  options.out_dir = dir;
  options.quiet = true;
  options.images = images;
  options.target = &check.plan->result.mesh;
  const twin::CellModel cell = waam::analysis::LoadCell(check.scenario->scenario.cell);
  analysis::WriteCheckOutputs(check.scenario->scenario, check.plan->result.plan, cell, check.report, options);
}

void SaveSimulate(const SimulateHolder& part, const fs::path& dir, bool images) {
  py::gil_scoped_release release;
  analysis::WriteSimulateOutputs(part.scenario->scenario, part.plan->result, *part.result, dir, images);
}

namespace {

std::shared_ptr<PlanHolder> Plan(const std::shared_ptr<const ScenarioHolder>& scn, const py::object& progress) {
  return RunLong(progress, [&] { return PlanOf(scn); });
}

std::shared_ptr<CheckHolder> Check(const std::shared_ptr<const ScenarioHolder>& scn,
                                   std::shared_ptr<const PlanHolder> plan, const py::object& progress) {
  return RunLong(progress, [&] {
    if (!plan) plan = PlanOf(scn);
    auto h = std::make_shared<CheckHolder>();
    h->scenario = scn;
    h->plan = plan;
    const analysis::Scenario& s = scn->scenario;
    const twin::CellModel cell = waam::analysis::LoadCell(s.cell);
    Progress bar("check", 0, "samples", /*quiet=*/true);
    h->report = twin::CheckPlan(cell, plan->result.plan, s.cell, s.process.rapid_speed_mm_min / 60.0, &bar);
    h->document = analysis::CheckPlanToJson(s, cell, plan->result.plan, h->report);
    return h;
  });
}

std::shared_ptr<SimulateHolder> Simulate(const std::shared_ptr<const ScenarioHolder>& scn,
                                         std::shared_ptr<const PlanHolder> plan, const py::object& progress) {
  return RunLong(progress, [&] {
    if (!plan) plan = PlanOf(scn);
    auto h = std::make_shared<SimulateHolder>();
    h->scenario = scn;
    h->plan = plan;
    const analysis::Scenario& s = scn->scenario;
    const planner::PlanResult& planned = plan->result;
    analysis::CheckVoxelBudget(s, planned.plan);
    Progress bar("deposit", 0, "passes", /*quiet=*/true);
    twin::Depositor depositor = twin::DepositPlan(planned.plan, s.simulation, s.process.rapid_speed_mm_min / 60.0, &bar);
    h->result.emplace(twin::MeasureBuild(planned.plan, std::move(depositor),
                                         planned.mesh.facets.empty() ? nullptr : &planned.mesh, s.path.bead_width_mm));
    h->document = analysis::SimulationToJson(s, planned, *h->result);
    const twin::VoxelGrid& grid = h->result->depositor.grid();
    h->voxel_mm = grid.voxel_mm();
    grid.ForEach([&](const twin::VoxelIndex& v, const twin::VoxelData&) {
      h->ijk.insert(h->ijk.end(), {v.x(), v.y(), v.z()});
    });
    return h;
  });
}

// The seconds of each of `repeat` runs of a step's C++ computation alone, called directly as `waam plan -q` and
// `waam check -q` call it (with a quiet Progress), with no result object, no numpy table and no Python callback:
// the plan and its cell timeline, or the cell, the check and check.json's document. python/benchmarks/overhead.py sets it against wt.plan and
// wt.check in the same process.
std::vector<double> NativeStepSeconds(const std::string& step, const std::shared_ptr<const ScenarioHolder>& scn,
                                      const std::shared_ptr<const PlanHolder>& plan, int repeat) {
  WAAM_THROW_UNLESS(step == "plan" || (step == "check" && plan), "step '" << step << "': plan, or check with a plan");
  const analysis::Scenario& s = scn->scenario;
  py::gil_scoped_release release;
  std::vector<double> seconds;
  for (int i = 0; i < repeat; ++i) {
    const auto start = std::chrono::steady_clock::now();
    if (step == "plan") {
      analysis::ImportReport import;
      Progress progress("plan", 0, "layers", /*quiet=*/true);
      planner::PlanResult result = analysis::PlanScenarioOrProgram(s, &progress, &import);
      if (!s.program.present) analysis::AddCellTimeline(s, &result);
    } else {
      const twin::CellModel cell = waam::analysis::LoadCell(s.cell);
      Progress progress("check", 0, "samples", /*quiet=*/true);
      const twin::CheckReport report =
          twin::CheckPlan(cell, plan->result.plan, s.cell, s.process.rapid_speed_mm_min / 60.0, &progress);
      const nlohmann::json document = analysis::CheckPlanToJson(s, cell, plan->result.plan, report);
      WAAM_DEMAND(document.is_object());
    }
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return seconds;
}

}  // namespace

void BindSteps(py::module_& m) {
  py::class_<PlanHolder, std::shared_ptr<PlanHolder>>(m, "PlanResult", "A planned part (or an imported program).")
      .def_property_readonly(
          "points",
          [](py::object self) {
            const auto& h = self.cast<const PlanHolder&>();
            return View(h.table.data(), h.table.size() / kPlanColumns, kPlanColumns, self);
          },
          "Every path point, (points x 11) float64 read-only view, the columns of plan.h5 (PlanResult.columns).")
      .def(
          "layer_points",
          [](py::object self, int i) {
            const auto& h = self.cast<const PlanHolder&>();
            const int layers = static_cast<int>(h.offsets.size()) - 1;
            WAAM_THROW_UNLESS(i >= 0 && i < layers, "layer " << i << ": the plan has layers 0.." << layers - 1);
            const std::size_t a = h.offsets[i], b = h.offsets[i + 1];
            return View(h.table.data() + a * kPlanColumns, b - a, kPlanColumns, self);
          },
          py::arg("i"), "The points of layer i, a view into points. Raises InputError for a layer not in the plan.")
      .def_property_readonly(
          "timeline", [](const PlanHolder& h) { return ToPython(analysis::TimelineToJson(h.result.timeline)); },
          "The build's timeline as plan.json has it: total_s, arc_on_s, travel_s, wait_s, layers.")
      .def_property_readonly("layer_count", [](const PlanHolder& h) { return h.offsets.size() - 1; },
                             "The number of layers.")
      .def_property_readonly_static(
          "columns",
          [](py::object) { return std::vector<std::string>(kPlanColumnNames, kPlanColumnNames + kPlanColumns); },
          "The names of the columns of points (units in the names; weld is 1 for a move that lays a bead).")
      .def("to_dict", [](const PlanHolder& h) { return ToPython(PlanDocument(h)); }, "The content of plan.json.")
      .def("save", &SavePlan, py::arg("dir"), py::arg("images") = true,
           "Writes what `waam plan` writes into dir (plan.json, plan.h5, layers/*.png with images), by the same\n"
           "writers. Raises OSError-like InputError/OutputError when the folder cannot be written.");
  m.def("plan", &Plan, py::arg("scenario"), py::arg("progress") = py::none(),
        "Plans the scenario (or reads its program:), as `waam plan` does; returns a PlanResult.\n\n"
        "progress: None or a callable progress(label, done, total), called at most every 50 ms.");

  py::class_<CheckHolder, std::shared_ptr<CheckHolder>>(m, "CheckResult", "The check of a plan on the robot cell.")
      .def_property_readonly("ok", [](const CheckHolder& h) { return h.report.ok; },
                             "True when the path passes every check.")
      .def_property_readonly(
          "joints",
          [](py::object self) {
            const auto& h = self.cast<const CheckHolder&>();
            // The samples' joint vectors in place: row i is report.motion[i].q (8 contiguous doubles).
            static const double kNone[8] = {};
            const std::vector<planner::CellSample>& motion = h.report.motion;
            if (motion.empty()) return View(kNone, 0, std::size_t{8}, self);
            return StridedView(motion.front().q.data(), motion.size(), std::size_t{8}, sizeof(planner::CellSample),
                               self);
          },
          "The eight axes at every checked sample, (samples x 8) float64 view, rad: the arm's six axes, then the\n"
          "positioner's tilt and rotation.")
      .def("to_dict", [](const CheckHolder& h) { return ToPython(h.document); }, "The content of check.json.")
      .def("save", &SaveCheck, py::arg("dir"), py::arg("images") = true,
           "Writes what `waam check` writes into dir (check.json, the pictures and viewer.html with images, the\n"
           "program files), by the same writers.");
  m.def("_check", &Check, py::arg("scenario"), py::arg("plan") = nullptr, py::arg("progress") = py::none());

  py::class_<SimulateHolder, std::shared_ptr<SimulateHolder>>(m, "SimulateResult",
                                                              "The part built in the voxel twin.")
      .def_property_readonly(
          "voxels",
          [](py::object self) {
            const auto& h = self.cast<const SimulateHolder&>();
            return View(h.ijk.data(), h.ijk.size() / 3, std::size_t{3}, self);
          },
          "Occupied voxel indices, (voxels x 3) int32 view, as part.h5 /voxels/ijk.")
      .def_property_readonly("voxel_mm", [](const SimulateHolder& h) { return h.voxel_mm; },
                             "The voxel edge, mm: voxel (i, j, k) covers [i, i + 1) x voxel_mm along x, ...")
      .def("to_dict", [](const SimulateHolder& h) { return ToPython(h.document); },
           "The content of simulate.json.")
      .def("save", &SaveSimulate, py::arg("dir"), py::arg("images") = true,
           "Writes what `waam simulate` writes into dir (simulate.json, part.stl, part.h5, the pictures with\n"
           "images), by the same writers.");
  m.def("_native_step_seconds", &NativeStepSeconds, py::arg("step"), py::arg("scenario"), py::arg("plan") = nullptr,
        py::arg("repeat") = 1,
        "Benchmark aid: the seconds of each of `repeat` runs of the step's C++ computation alone ('plan' or\n"
        "'check' with a plan), without the Python result object. python/benchmarks/overhead.py uses it.");
  m.def("_simulate", &Simulate, py::arg("scenario"), py::arg("plan") = nullptr, py::arg("progress") = py::none());
}

}  // namespace waam::python
