// waam_twin.Scenario: load_scenario (a file), scenario_from_dict (a document), overrides, pickling by reloading.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "analysis/scenario_keys.h"
#include "models/core/json_text.h"
#include "python/bindings.h"

namespace waam::python {
namespace fs = std::filesystem;

namespace {

std::shared_ptr<ScenarioHolder> LoadScenario(const fs::path& path, const py::object& overrides) {
  return LoadHolder(path, nullptr, {}, OverridesOf(overrides));
}

std::shared_ptr<ScenarioHolder> ScenarioFromDict(const py::object& document, const fs::path& base_dir,
                                                 const py::object& overrides) {
  WAAM_THROW_UNLESS(py::isinstance<py::dict>(document), "scenario_from_dict: expected a dict with the YAML's "
                                                            "structure, got "
                                                                << std::string(py::str(document.get_type().attr("__name__"))));
  return LoadHolder({}, ToJson(document, ""), base_dir, OverridesOf(overrides));
}

// The same scenario with more overrides (applied after its own).
std::shared_ptr<ScenarioHolder> WithOverrides(const ScenarioHolder& s, const py::object& overrides) {
  std::vector<std::string> all = s.overrides;
  for (std::string& o : OverridesOf(overrides)) all.push_back(std::move(o));
  return LoadHolder(s.file, s.document, s.base_dir, all);
}

}  // namespace

void BindScenario(py::module_& m) {
  py::class_<ScenarioHolder, std::shared_ptr<ScenarioHolder>>(
      m, "Scenario",
      "A loaded and validated scenario (load_scenario, scenario_from_dict). Picklable: it is loaded again from its\n"
      "file or document and overrides, so it can go to another process (sweep on an executor).")
      .def_property_readonly("name", [](const ScenarioHolder& s) { return s.scenario.name; }, "The scenario's name.")
      .def_property_readonly(
          "file", [](const ScenarioHolder& s) -> py::object {
            return s.file.empty() ? py::none() : py::cast(s.file);
          },
          "The scenario file (None for a scenario from a dict).")
      .def_property_readonly("overrides", [](const ScenarioHolder& s) { return s.overrides; },
                             "The overrides applied, as --set strings 'key.path=value'.")
      .def_property_readonly("has_thermal", [](const ScenarioHolder& s) { return s.scenario.thermal.given; },
                             "True when the scenario has a thermal: section (wt.thermal needs one).")
      .def_property_readonly("has_program", [](const ScenarioHolder& s) { return s.scenario.program.present; },
                             "True when the scenario reads a program (program:) instead of planning a part.")
      .def("document", [](const ScenarioHolder& s) -> py::object {
            return s.document.is_null() ? py::none() : ToPython(s.document);
          },
           "The dict a scenario_from_dict scenario was built from (None for a file).")
      .def("with_overrides", &WithOverrides, py::arg("overrides"),
           "The same scenario with more overrides (a dict of key paths to values, applied after its own).")
      .def("__repr__", [](const ScenarioHolder& s) { return "<waam_twin.Scenario '" + s.scenario.name + "'>"; })
      .def(py::pickle(
          [](const ScenarioHolder& s) {
            return py::make_tuple(s.file.string(), s.document.is_null() ? std::string() : JsonText(s.document, -1),
                                  s.base_dir.string(), s.overrides);
          },
          [](const py::tuple& t) {
            WAAM_DEMAND(t.size() == 4);
            const std::string document = t[1].cast<std::string>();
            return LoadHolder(t[0].cast<std::string>(),
                              document.empty() ? nlohmann::json() : nlohmann::json::parse(document),
                              t[2].cast<std::string>(), t[3].cast<std::vector<std::string>>());
          }));
  m.def(
      "_check_override_keys", [](const py::object& overrides) { analysis::CheckOverrideKeys(OverridesOf(overrides)); },
      py::arg("overrides"));
  m.def("load_scenario", &LoadScenario, py::arg("path"), py::arg("overrides") = py::none(),
        "Loads and validates a scenario file, as the command line does (same checks, same one-line errors).\n\n"
        "overrides maps key paths to values, as --set does: {'path.pattern': 'hybrid', 'path.bead_width_mm': 5}\n"
        "(strings as written, other values as JSON). Raises InputError naming the file, line and key.");
  m.def("scenario_from_dict", &ScenarioFromDict, py::arg("d"), py::arg("base_dir") = ".",
        py::arg("overrides") = py::none(),
        "Builds a scenario from a dict with the YAML file's structure, with the same checks as load_scenario.\n\n"
        "Relative paths in it (meshes, programs, materials) are taken from base_dir. Errors name\n"
        "'<base_dir>/<dict>' and the key path: InputError('./<dict>: path.bead_width_mm = -1: must be in [...]').");
}

}  // namespace waam::python
