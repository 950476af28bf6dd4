// JSON <-> Python values, --set overrides from a dict, and the scenario's source for the file-based commands.
#include <pybind11/stl.h>

#include <cmath>

#include "models/core/files.h"
#include "models/core/json_text.h"
#include "python/bindings.h"

namespace waam::python {
namespace fs = std::filesystem;

namespace {
constexpr int kMaxDepth = 64;
}  // namespace

py::object ToPython(const nlohmann::json& document) {
  return py::module_::import("json").attr("loads")(JsonText(document, -1));
}

nlohmann::json ToJson(py::handle value, const std::string& where, int depth) {
  WAAM_THROW_UNLESS(depth < kMaxDepth, where << ": nested deeper than " << kMaxDepth << " levels");
  if (value.is_none()) return nullptr;
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>();
  if (py::isinstance<py::int_>(value)) {
    try {
      return value.cast<long long>();
    } catch (const py::cast_error&) {
      WAAM_THROW(where << " = " << std::string(py::str(value)) << ": integer out of range");
    }
  }
  if (py::isinstance<py::float_>(value)) return value.cast<double>();
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::isinstance<py::dict>(value)) {
    nlohmann::json object = nlohmann::json::object();
    for (auto item : value.cast<py::dict>()) {
      WAAM_THROW_UNLESS(py::isinstance<py::str>(item.first), where << ": key " << std::string(py::repr(item.first))
                                                                   << " is not a string");
      const std::string key = item.first.cast<std::string>();
      object[key] = ToJson(item.second, where.empty() ? key : where + "." + key, depth + 1);
    }
    return object;
  }
  // numpy arrays and scalars: as the Python lists and numbers they hold.
  if (py::isinstance<py::array>(value) || py::hasattr(value, "dtype")) {
    return ToJson(value.attr("tolist")(), where, depth + 1);
  }
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    nlohmann::json array = nlohmann::json::array();
    int i = 0;
    for (py::handle item : value) array.push_back(ToJson(item, where + "[" + std::to_string(i++) + "]", depth + 1));
    return array;
  }
  if (py::hasattr(value, "__fspath__")) return py::str(value.attr("__fspath__")()).cast<std::string>();
  WAAM_THROW(where << ": a value of type " << std::string(py::str(value.get_type().attr("__name__")))
                   << " (expected a number, string, bool, None, list or dict)");
}

std::vector<std::string> OverridesOf(const py::object& overrides) {
  std::vector<std::string> out;
  if (overrides.is_none()) return out;
  WAAM_THROW_UNLESS(py::isinstance<py::dict>(overrides), "overrides: expected a dict of key paths to values, got "
                                                             << std::string(py::str(overrides.get_type())));
  for (auto item : overrides.cast<py::dict>()) {
    WAAM_THROW_UNLESS(py::isinstance<py::str>(item.first), "overrides: keys must be strings such as 'path.pattern'");
    const std::string key = item.first.cast<std::string>();
    // A string stays as written (YAML reads `hybrid`); other values go as JSON, which YAML reads as flow values.
    const std::string value = py::isinstance<py::str>(item.second)
                                  ? item.second.cast<std::string>()
                                  : JsonText(ToJson(item.second, "overrides." + key), -1);
    out.push_back(key + "=" + value);
  }
  return out;
}

void CheckProgressCallback(const py::object& progress) {
  WAAM_THROW_UNLESS(progress.is_none() || PyCallable_Check(progress.ptr()),
                    "progress: expected None or a callable progress(label, done, total), got "
                        << std::string(py::str(progress.get_type().attr("__name__"))));
}

std::shared_ptr<ScenarioHolder> LoadHolder(const fs::path& file, const nlohmann::json& document,
                                           const fs::path& base_dir, const std::vector<std::string>& overrides) {
  auto holder = std::make_shared<ScenarioHolder>();
  holder->file = file;
  holder->document = document;
  std::error_code ec;
  holder->base_dir = document.is_null() ? fs::path() : fs::absolute(base_dir, ec).lexically_normal();
  holder->overrides = overrides;
  py::gil_scoped_release release;
  holder->scenario = document.is_null() ? analysis::LoadScenario(file, overrides)
                                        : analysis::ScenarioFromJson(document, base_dir, overrides);
  return holder;
}

fs::path ScenarioFileFor(const ScenarioHolder& scenario, const fs::path& tmp_dir, std::vector<std::string>* overrides) {
  *overrides = scenario.overrides;
  if (scenario.document.is_null()) return scenario.file;
  // A document's relative paths are taken from its base_dir argument, and a base_dir key in it from there.
  nlohmann::json document = scenario.document;
  const fs::path given = document.contains("base_dir") && document["base_dir"].is_string()
                             ? fs::path(document["base_dir"].get<std::string>())
                             : fs::path();
  document["base_dir"] = (scenario.base_dir / given).lexically_normal().string();
  std::error_code ec;
  fs::create_directories(tmp_dir, ec);
  const fs::path file = tmp_dir / "scenario.yaml";
  WriteFileAtomic(file, JsonText(document) + "\n");  // JSON is YAML
  return file;
}

}  // namespace waam::python
