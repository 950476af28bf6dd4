// The Python module waam_twin._core: scenarios, plan, check and simulate in memory over the C++ libraries, arrays as
// numpy views that keep their owner alive, long calls without the GIL, InputError as a Python ValueError subclass.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "analysis/check_command.h"
#include "analysis/import_command.h"
#include "analysis/scenario_plan.h"
#include "analysis/plan_command.h"
#include "analysis/plan_timeline.h"
#include "analysis/scenario.h"
#include "analysis/simulate_command.h"
#include "models/core/error.h"
#include "models/core/parallel.h"
#include "models/core/progress.h"
#include "twin/cell/cell_check.h"
#include "twin/cell/mujoco_cell.h"
#include "twin/simulation.h"

namespace py = pybind11;
namespace fs = std::filesystem;

namespace waam::python {
namespace {

// A JSON document as Python objects (through the json module, which keeps the JSON's types).
py::object ToPython(const nlohmann::json& document) {
  return py::module_::import("json").attr("loads")(document.dump());
}

// The columns of plan.h5 (docs/OUTPUTS.md), one row per path point.
constexpr int kPlanColumns = 11;
const char* const kPlanColumnNames[kPlanColumns] = {"x_mm",          "y_mm",           "z_mm",
                                                    "tool_x",        "tool_y",         "tool_z",
                                                    "bead_width_mm", "bead_height_mm", "travel_speed_mm_min",
                                                    "weld",          "layer"};

struct ScenarioHolder {
  analysis::Scenario scenario;
};

// A plan and its points as one row-major (points x 11) table; layer i is rows [offsets[i], offsets[i + 1]).
struct PlanHolder {
  std::shared_ptr<const ScenarioHolder> scenario;
  planner::PlanResult result;
  analysis::ImportReport import;
  std::vector<double> table;
  std::vector<std::size_t> offsets;
};

struct CheckHolder {
  twin::CheckReport report;
  nlohmann::json document;
  std::vector<double> joints;  // samples x 8, rad
};

struct SimulateHolder {
  nlohmann::json document;
  std::vector<std::int32_t> ijk;  // voxels x 3, as part.h5 /voxels/ijk
  double voxel_mm = 0.0;  // voxel (i, j, k) covers [i, i + 1) x voxel_mm along x from the part frame's origin
};

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

// A read-only (rows x cols) numpy view of `data`, owned by `owner` (kept alive by the array's base).
template <typename T>
py::array View(const T* data, std::size_t rows, std::size_t cols, py::handle owner) {
  py::array a(py::dtype::of<T>(), {rows, cols}, {cols * sizeof(T), sizeof(T)}, data, owner);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

std::vector<std::string> OverridesOf(const py::object& overrides) {
  std::vector<std::string> out;
  if (overrides.is_none()) return out;
  WAAM_THROW_UNLESS(py::isinstance<py::dict>(overrides),
                    "overrides: expected a dict of key paths to values, got " << std::string(py::str(overrides.get_type())));
  py::object dumps = py::module_::import("json").attr("dumps");
  for (auto item : overrides.cast<py::dict>()) {
    WAAM_THROW_UNLESS(py::isinstance<py::str>(item.first), "overrides: keys must be strings such as 'path.pattern'");
    const std::string key = item.first.cast<std::string>();
    // A string stays as written (YAML reads `hybrid`); other values go as JSON, which YAML reads as flow values.
    const std::string value = py::isinstance<py::str>(item.second) ? item.second.cast<std::string>()
                                                                     : dumps(item.second).cast<std::string>();
    out.push_back(key + "=" + value);
  }
  return out;
}

std::shared_ptr<ScenarioHolder> LoadScenario(const fs::path& path, const py::object& overrides) {
  const std::vector<std::string> sets = OverridesOf(overrides);
  auto holder = std::make_shared<ScenarioHolder>();
  py::gil_scoped_release release;
  holder->scenario = analysis::LoadScenario(path, sets);
  return holder;
}

std::shared_ptr<PlanHolder> Plan(const std::shared_ptr<const ScenarioHolder>& scn) {
  auto h = std::make_shared<PlanHolder>();
  h->scenario = scn;
  py::gil_scoped_release release;
  Progress progress("plan", 0, "layers", /*quiet=*/true);
  h->result = analysis::PlanScenarioOrProgram(scn->scenario, &progress, &h->import);
  // As `waam plan`: a planned part's timeline on the cell (a program's import builds its own).
  if (!scn->scenario.program.present) analysis::AddCellTimeline(scn->scenario, &h->result);
  FillTable(h.get());
  return h;
}

std::shared_ptr<CheckHolder> Check(const std::shared_ptr<const ScenarioHolder>& scn,
                                   std::shared_ptr<const PlanHolder> plan) {
  if (!plan) plan = Plan(scn);
  auto h = std::make_shared<CheckHolder>();
  py::gil_scoped_release release;
  const analysis::Scenario& s = scn->scenario;
  const twin::CellModel cell = twin::LoadCell(s.cell);
  Progress progress("check", 0, "samples", /*quiet=*/true);
  h->report = twin::CheckPlan(cell, plan->result.plan, s.cell, s.process.rapid_speed_mm_min / 60.0, &progress);
  h->document = analysis::CheckToJson(s, cell.file(), h->report);
  for (const planner::CellSample& sample : h->report.motion) {
    for (int k = 0; k < 8; ++k) h->joints.push_back(sample.q[k]);
  }
  return h;
}

std::shared_ptr<SimulateHolder> Simulate(const std::shared_ptr<const ScenarioHolder>& scn,
                                         std::shared_ptr<const PlanHolder> plan) {
  if (!plan) plan = Plan(scn);
  auto h = std::make_shared<SimulateHolder>();
  py::gil_scoped_release release;
  const analysis::Scenario& s = scn->scenario;
  const planner::PlanResult& planned = plan->result;
  const twin::TwinResult result = twin::SimulateBuild(
      planned.plan, planned.mesh.facets.empty() ? nullptr : &planned.mesh, s.simulation,
      s.process.rapid_speed_mm_min / 60.0, s.path.bead_width_mm, {});
  h->document = analysis::SimulationToJson(s, planned, result);
  const twin::VoxelGrid& grid = result.depositor.grid();
  h->voxel_mm = grid.voxel_mm();
  grid.ForEach([&](const twin::VoxelIndex& v, const twin::VoxelData&) {
    h->ijk.insert(h->ijk.end(), {v.x(), v.y(), v.z()});
  });
  return h;
}

}  // namespace
}  // namespace waam::python

PYBIND11_MODULE(_core, m) {
  using namespace waam;
  using namespace waam::python;
  m.doc() = "waam-twin's C++ core: scenarios, plan, check and simulate in memory (use the waam_twin package).";
  static py::exception<InputError> input_error(m, "InputError", PyExc_ValueError);
  static py::exception<InternalError> internal_error(m, "InternalError", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      input_error(e.what());
    } catch (const InternalError& e) {
      internal_error(e.what());
    } catch (const Interrupted&) {
      PyErr_SetNone(PyExc_KeyboardInterrupt);
    }
  });

  m.def("set_threads", &SetThreadCount, py::arg("n"),
        "Threads for the parallel steps (0 = all hardware threads); results are the same on any count.");
  m.def("threads", &ThreadCount, "The threads the parallel steps use.");

  py::class_<ScenarioHolder, std::shared_ptr<ScenarioHolder>>(m, "Scenario", "A loaded and validated scenario.")
      .def_property_readonly("name", [](const ScenarioHolder& s) { return s.scenario.name; })
      .def_property_readonly("file", [](const ScenarioHolder& s) { return s.scenario.file; })
      .def("__repr__", [](const ScenarioHolder& s) { return "<waam_twin.Scenario '" + s.scenario.name + "'>"; });
  m.def("load_scenario", &LoadScenario, py::arg("path"), py::arg("overrides") = py::none(),
        "Loads and validates a scenario file; overrides maps key paths to values, as --set does.");

  py::class_<PlanHolder, std::shared_ptr<PlanHolder>>(m, "PlanResult", "A planned part (or an imported program).")
      .def_property_readonly("points",
                             [](py::object self) {
                               const auto& h = self.cast<const PlanHolder&>();
                               return View(h.table.data(), h.table.size() / kPlanColumns, kPlanColumns, self);
                             },
                             "Every path point, (points x 11) float64, the columns of plan.h5 (columns).")
      .def("layer_points",
           [](py::object self, int i) {
             const auto& h = self.cast<const PlanHolder&>();
             const int layers = static_cast<int>(h.offsets.size()) - 1;
             WAAM_THROW_UNLESS(i >= 0 && i < layers, "layer " << i << ": the plan has layers 0.." << layers - 1);
             const std::size_t a = h.offsets[i], b = h.offsets[i + 1];
             return View(h.table.data() + a * kPlanColumns, b - a, kPlanColumns, self);
           },
           py::arg("i"), "The points of layer i, a view into points.")
      .def_property_readonly("timeline",
                             [](const PlanHolder& h) { return ToPython(analysis::TimelineToJson(h.result.timeline)); },
                             "The build's timeline as plan.json has it: total_s, arc_on_s, travel_s, wait_s, layers.")
      .def_property_readonly("layer_count", [](const PlanHolder& h) { return h.offsets.size() - 1; })
      .def_property_readonly_static("columns", [](py::object) {
        return std::vector<std::string>(kPlanColumnNames, kPlanColumnNames + kPlanColumns);
      })
      .def("to_dict",
           [](const PlanHolder& h) {
             nlohmann::json document = analysis::PlanToJson(h.scenario->scenario, h.result);
             if (h.scenario->scenario.program.present) document["import"] = analysis::ImportToJson(h.import);
             return ToPython(document);
           },
           "The content of plan.json.");
  m.def("plan", &Plan, py::arg("scenario"), "Plans the scenario (or reads its program:), as `waam plan` does.");

  py::class_<CheckHolder, std::shared_ptr<CheckHolder>>(m, "CheckResult", "The check of a plan on the robot cell.")
      .def_property_readonly("ok", [](const CheckHolder& h) { return h.report.ok; })
      .def_property_readonly("joints",
                             [](py::object self) {
                               const auto& h = self.cast<const CheckHolder&>();
                               return View(h.joints.data(), h.joints.size() / 8, std::size_t{8}, self);
                             },
                             "The eight axes at every checked sample, (samples x 8) float64, rad.")
      .def("to_dict", [](const CheckHolder& h) { return ToPython(h.document); }, "The content of check.json.");
  m.def("check", &Check, py::arg("scenario"), py::arg("plan") = nullptr,
        "Checks the plan (planned here when None) on the scenario's cell, as `waam check` does.");

  py::class_<SimulateHolder, std::shared_ptr<SimulateHolder>>(m, "SimulateResult", "The part built in the voxel twin.")
      .def_property_readonly("voxels",
                             [](py::object self) {
                               const auto& h = self.cast<const SimulateHolder&>();
                               return View(h.ijk.data(), h.ijk.size() / 3, std::size_t{3}, self);
                             },
                             "Occupied voxel indices, (voxels x 3) int32, as part.h5 /voxels/ijk.")
      .def_property_readonly("voxel_mm", [](const SimulateHolder& h) { return h.voxel_mm; })
      .def("to_dict", [](const SimulateHolder& h) { return ToPython(h.document); }, "The content of simulate.json.");
  m.def("simulate", &Simulate, py::arg("scenario"), py::arg("plan") = nullptr,
        "Deposits the plan (planned here when None) in the voxel twin and measures it, as `waam simulate` does.");
}
