// waam_twin's file-based commands (place, compensate, run, fit, the thermal replay: each writes its outputs into a
// folder the package reads back) and the programs (import_program, export_program: in memory).
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cmath>
#include <sstream>

#include "analysis/distortion_command.h"
#include "analysis/export_command.h"
#include "analysis/fit_command.h"
#include "analysis/import_command.h"
#include "analysis/place_command.h"
#include "analysis/plan_command.h"
#include "analysis/replay_command.h"
#include "analysis/run_command.h"
#include "models/core/enum_names.h"
#include "python/bindings.h"
#include "python/steps.h"

namespace waam::python {
namespace fs = std::filesystem;

namespace {

// Runs `waam place` on the scenario into out_dir (place.json, scenario.yaml, place_margin.png with images).
void Place(const ScenarioHolder& scn, const fs::path& out_dir, bool images, const py::object& progress) {
  analysis::PlaceOptions options;
  options.scenario = ScenarioFileFor(scn, out_dir / ".input", &options.overrides);
  options.out_dir = out_dir;
  options.quiet = true;
  options.images = images;
  RunLong(progress, [&] { return analysis::RunPlace(options); });
}

// Runs `waam compensate` on the scenario into out_dir; returns {converged, status, message}.
py::dict Compensate(const ScenarioHolder& scn, const fs::path& out_dir, int max_iterations, double tolerance_mm,
                    const std::string& correction, const fs::path& model, bool images, const py::object& progress) {
  analysis::CompensateOptions options;
  options.scenario = ScenarioFileFor(scn, out_dir / ".input", &options.overrides);
  options.out_dir = out_dir;
  options.max_iterations = max_iterations;
  options.tolerance_mm = tolerance_mm;
  options.correction = correction;
  options.model = model;
  options.program = images;  // the compensated program with the pictures
  options.quiet = true;
  options.images = images;
  const twin::CompensationResult r = RunLong(progress, [&] { return analysis::RunCompensate(options); });
  py::dict out;
  out["converged"] = r.converged;
  out["status"] = r.status;
  out["message"] = r.message;
  return out;
}

// Runs `waam run` on the scenario into out_dir (<step>/..., summary.json); returns summary.json's content.
py::object Run(const ScenarioHolder& scn, const fs::path& out_dir, const std::vector<std::string>& steps, bool images,
               const py::object& progress) {
  analysis::RunOptions options;
  options.scenario = ScenarioFileFor(scn, out_dir / ".input", &options.overrides);
  options.out_dir = out_dir;
  options.steps = steps;
  options.quiet = true;
  options.images = images;
  const analysis::RunSummary summary = RunLong(progress, [&] { return analysis::RunScenario(options); });
  return ToPython(analysis::RunSummaryToJson(summary));
}

// Runs `waam fit model data -o output` with "role=column" columns; returns (ok, message, model, printed summary).
py::tuple Fit(const std::string& model, const fs::path& data, const fs::path& output,
              const std::vector<std::string>& columns, const py::dict& options_dict, const py::object& progress) {
  analysis::FitOptions options;
  options.model = analysis::ParseFitModel(model);
  options.data = data;
  options.output = output;
  options.columns = columns;
  options.quiet = true;
  for (auto item : options_dict) {
    const std::string key = py::str(item.first);
    if (key == "degree") options.degree = item.second.cast<int>();
    else if (key == "space") {
      const std::string name = item.second.cast<std::string>();
      const std::optional<models::PowerLawSpace> space = ParseEnum<models::PowerLawSpace>(name);
      WAAM_THROW_UNLESS(space, "fit: space '" << name << "': must be linear or log");
      options.space = *space;
    }
    else if (key == "speed_range") options.speed_range = item.second.cast<std::pair<double, double>>();
    else if (key == "seed") options.seed = item.second.cast<unsigned long long>();
    else if (key == "scenario") options.scenario = item.second.cast<fs::path>();
    else if (key == "overrides") options.overrides = item.second.cast<std::vector<std::string>>();
    else if (key == "max_points") options.max_points = item.second.cast<std::size_t>();
    else if (key == "max_iterations") options.max_iterations = item.second.cast<int>();
    else if (key == "mode") options.mode = item.second.cast<std::string>();
    else if (key == "start") options.start = item.second.cast<fs::path>();
    else if (key == "free") options.free = item.second.cast<std::vector<std::string>>();
    else if (key == "window") options.window = item.second.cast<std::string>();
    else if (key == "coarse_cell") options.coarse_cell_mm = item.second.cast<double>();
    else if (key == "jacobian_cell") {
      const bool is_auto = py::isinstance<py::str>(item.second) && item.second.cast<std::string>() == "auto";
      WAAM_THROW_UNLESS(is_auto || !py::isinstance<py::str>(item.second),
                        "fit: jacobian_cell '" << item.second.cast<std::string>() << "': must be \"auto\", 0 or mm");
      options.jacobian_cell_mm = is_auto ? analysis::kAutoJacobianCell : item.second.cast<double>();
      WAAM_THROW_UNLESS(is_auto || (std::isfinite(options.jacobian_cell_mm) && options.jacobian_cell_mm >= 0.0),
                        "fit: jacobian_cell " << options.jacobian_cell_mm << ": must be \"auto\", 0 or mm");
    }
    else if (key == "prior") options.prior_weight = item.second.cast<double>();
    else WAAM_THROW("fit: unknown option '" << key << "' (degree, space, speed_range, seed, max_points, "
                                               "max_iterations, mode, start, free, window, coarse_cell, "
                                               "jacobian_cell, prior)");
  }
  std::ostringstream printed;
  const analysis::FitOutcome outcome = RunLong(progress, [&] { return analysis::RunFit(options, printed); });
  return py::make_tuple(outcome.ok, outcome.message, ToPython(outcome.model), printed.str());
}

// Runs `waam thermal replay` on the scenario into out_dir (replay.json, replay.h5, probes_replay.png with images);
// returns {time_s, measured {NAME: degC}, simulated {NAME: degC}} (NaN where there is no reading or no metal).
py::dict ReplayThermal(const ScenarioHolder& scn, const fs::path& out_dir, const std::string& windows,
                       const fs::path& parameters, bool images, const py::object& progress) {
  analysis::ReplayOptions options;
  options.scenario = ScenarioFileFor(scn, out_dir / ".input", &options.overrides);
  options.out_dir = out_dir;
  options.windows = windows;
  options.parameters = parameters;
  options.quiet = true;
  options.images = images;
  std::ostringstream issues;  // listed in replay.json's log_issues
  const analysis::ReplayRunResult r = RunLong(progress, [&] { return analysis::RunThermalReplay(options, issues); });
  py::dict measured, simulated;
  for (std::size_t p = 0; p < r.model.probes.size(); ++p) {
    measured[py::str(r.model.probes[p].name)] = r.model.log.probe_c[p];
    simulated[py::str(r.model.probes[p].name)] = r.simulation.probe_c[p];
  }
  py::dict out;
  out["time_s"] = r.model.log.time_s;
  out["measured"] = measured;
  out["simulated"] = simulated;
  return out;
}

std::optional<planner::ProgramFormat> FormatOf(const std::string& name) {
  if (name.empty()) return std::nullopt;
  const std::optional<planner::ProgramFormat> format = ParseEnum<planner::ProgramFormat>(name);
  WAAM_THROW_UNLESS(format, "format = '" << name << "': unknown program format, expected one of "
                                         << EnumNameList<planner::ProgramFormat>());
  return format;
}

// Reads a program file with the scenario's cell, process and program settings; a PlanResult as `waam import` plans.
std::shared_ptr<PlanHolder> ImportProgram(const fs::path& path, const std::shared_ptr<const ScenarioHolder>& scn,
                                          const std::string& format, const py::object& progress) {
  analysis::ImportOptions options;
  options.program = path;
  options.format = FormatOf(format);
  return RunLong(progress, [&] {
    auto copy = std::make_shared<ScenarioHolder>(*scn);
    copy->scenario.name.clear();  // as `waam import`: the plan is named after the program file
    auto h = std::make_shared<PlanHolder>();
    h->result = analysis::ImportProgramInto(options, &copy->scenario, &h->import);
    h->imported = path;
    h->scenario = copy;
    FillTable(h.get());
    return h;
  });
}

// The program of `plan` (planned here when None) in `format` ("" = the cell preset's dialect, else fanuc_ls).
py::dict ExportProgram(const std::shared_ptr<const ScenarioHolder>& scn, std::shared_ptr<const PlanHolder> plan,
                       const std::string& format, const py::object& progress) {
  const std::optional<planner::ProgramFormat> wanted = FormatOf(format);
  const analysis::ProgramFiles program = RunLong(progress, [&] {
    if (!plan) plan = PlanOf(scn);
    return analysis::ExportPlan(scn->scenario, plan->result.plan, wanted, {}, /*quiet=*/true);
  });
  py::dict files;
  for (const auto& [extension, text] : program.files) files[py::str(extension)] = text;
  py::dict out;
  out["format"] = std::string(NameOf(program.format));
  out["files"] = files;
  out["points"] = program.points;
  out["violations"] = program.violations;
  return out;
}

}  // namespace

void BindCommands(py::module_& m) {
  m.def("_place", &Place, py::arg("scenario"), py::arg("out_dir"), py::arg("images"), py::arg("progress"));
  m.def("_compensate", &Compensate, py::arg("scenario"), py::arg("out_dir"), py::arg("max_iterations"),
        py::arg("tolerance_mm"), py::arg("correction"), py::arg("model"), py::arg("images"), py::arg("progress"));
  m.def("_run", &Run, py::arg("scenario"), py::arg("out_dir"), py::arg("steps"), py::arg("images"),
        py::arg("progress"));
  m.def("_fit", &Fit, py::arg("model"), py::arg("data"), py::arg("output"), py::arg("columns"), py::arg("options"),
        py::arg("progress"));
  m.def("_replay_thermal", &ReplayThermal, py::arg("scenario"), py::arg("out_dir"), py::arg("windows"),
        py::arg("parameters"), py::arg("images"), py::arg("progress"));
  m.def(
      "_fit_columns", [](const std::string& model) { return analysis::DefaultFitColumns(analysis::ParseFitModel(model)); },
      py::arg("model"));
  m.def(
      "_scenario_file",
      [](const ScenarioHolder& scn, const fs::path& tmp_dir) {
        std::vector<std::string> overrides;
        const fs::path file = ScenarioFileFor(scn, tmp_dir, &overrides);
        return py::make_tuple(file, overrides);
      },
      py::arg("scenario"), py::arg("tmp_dir"));
  m.def("import_program", &ImportProgram, py::arg("path"), py::arg("scenario"), py::arg("format") = "",
        py::arg("progress") = py::none(),
        "Reads a robot program or G-code made elsewhere (format: fanuc_ls, abb_rapid, kuka_krl, yaskawa_jbi,\n"
        "gcode, csv; '' = from the extension and first lines) and plans it with the scenario's cell, process and\n"
        "program settings, as `waam import` does; returns a PlanResult (to_dict() is plan.json with its import\n"
        "section). Raises InputError naming the program file and line.");
  m.def("export_program", &ExportProgram, py::arg("scenario"), py::arg("plan") = nullptr, py::arg("format") = "",
        py::arg("progress") = py::none(),
        "The program of plan (planned here when None) in one controller dialect, as `waam export` writes it: a\n"
        "dict with format, files {extension: text} ('' for the single file of most dialects, '.src' and '.dat'\n"
        "for kuka_krl), points and violations (what the cell check found on the way).");
}

}  // namespace waam::python
