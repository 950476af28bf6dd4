// What the files of the Python module waam_twin._core share: the scenario object, JSON <-> Python, numpy views that
// keep their owner alive, and long calls (GIL released, progress callback, Ctrl-C).
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "analysis/scenario.h"
#include "models/core/error.h"
#include "models/core/progress.h"

namespace waam::python {

namespace py = pybind11;

// A loaded scenario and where it came from, so that it can be loaded again (pickling, sweeps on other processes, the
// commands that read a scenario file).
struct ScenarioHolder {
  analysis::Scenario scenario;
  std::filesystem::path file;         // the scenario file; empty for a document
  nlohmann::json document;            // the document (scenario_from_dict); null for a file
  std::filesystem::path base_dir;     // where a document's relative paths are taken from (absolute)
  std::vector<std::string> overrides; // "key.path=value", as --set
};

// Loads a scenario file or a document (document not null) with overrides. Throws InputError.
std::shared_ptr<ScenarioHolder> LoadHolder(const std::filesystem::path& file, const nlohmann::json& document,
                                           const std::filesystem::path& base_dir,
                                           const std::vector<std::string>& overrides);

// A scenario file the file-based commands (place, compensate, run, export) can read, with `overrides` to pass them:
// the scenario's own file, or its document written as YAML into `tmp_dir` with base_dir made absolute.
std::filesystem::path ScenarioFileFor(const ScenarioHolder& scenario, const std::filesystem::path& tmp_dir,
                                      std::vector<std::string>* overrides);

// A JSON document as Python objects (dicts, lists, str, int, float, bool, None).
py::object ToPython(const nlohmann::json& document);
// A Python value (dict with str keys, list, tuple, numpy array or scalar, str, int, float, bool, None, os.PathLike)
// as JSON. Throws InputError naming `where` (a key path) for anything else or nesting deeper than 64.
nlohmann::json ToJson(py::handle value, const std::string& where, int depth = 0);
// A dict of key paths to values as --set strings (strings as written, other values as JSON). Throws InputError.
std::vector<std::string> OverridesOf(const py::object& overrides);

// A read-only (rows x cols) view of rows that lie `row_stride_bytes` apart (cols contiguous values of T at the start
// of each), owned by `owner`: a column block of an array of structs, without a copy.
template <typename T>
py::array StridedView(const T* data, std::size_t rows, std::size_t cols, std::size_t row_stride_bytes,
                      py::handle owner) {
  py::array a(py::dtype::of<T>(), {rows, cols}, {row_stride_bytes, sizeof(T)}, data, owner);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

// A read-only (rows x cols) numpy view of `data`, owned by `owner` (kept alive by the array's base).
template <typename T>
py::array View(const T* data, std::size_t rows, std::size_t cols, py::handle owner) {
  return StridedView(data, rows, cols, cols * sizeof(T), owner);
}

// Checks that `progress` is None or callable. Throws InputError.
void CheckProgressCallback(const py::object& progress);

// Runs `work` (the C++ part of a long call) with the GIL released. Every Progress update it makes calls
// progress(label, done, total) (when not None) at most every 50 ms and checks Python's signal handlers, so a Ctrl-C
// stops the work (Interrupted) and raises KeyboardInterrupt; an exception raised by the callback stops it likewise
// and is raised as is. Called with the GIL held.
template <typename Work>
auto RunLong(const py::object& progress, Work&& work) -> decltype(work()) {
  CheckProgressCallback(progress);
  std::optional<py::error_already_set> error;
  const ProgressObserver observer = [&](const std::string& label, std::size_t done, std::size_t total) {
    py::gil_scoped_acquire gil;
    if (error) return false;
    if (PyErr_CheckSignals() != 0) {
      error.emplace();
      return false;
    }
    if (!progress.is_none()) {
      try {
        progress(label, done, total);
      } catch (py::error_already_set& e) {
        error.emplace(std::move(e));
        return false;
      }
    }
    return true;
  };
  struct Restore {
    const ProgressObserver* previous;
    ~Restore() { SetProgressObserver(previous); }
  } restore{SetProgressObserver(&observer)};
  try {
    py::gil_scoped_release release;
    return work();
  } catch (const Interrupted&) {
    if (error) throw std::move(*error);
    throw;
  }
}

// The parts of the module, each in its own file.
void BindScenario(py::module_& m);
void BindSteps(py::module_& m);
void BindThermal(py::module_& m);
void BindCommands(py::module_& m);

}  // namespace waam::python
