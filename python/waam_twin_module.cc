// The Python module waam_twin._core: the exceptions, the thread count, and the bindings of python/*_bindings.cc.
#include <pybind11/stl/filesystem.h>

#include "models/core/data_dir.h"
#include "models/core/error.h"
#include "models/core/parallel.h"
#include "python/bindings.h"

PYBIND11_MODULE(_core, m) {
  using namespace waam;
  using namespace waam::python;
  m.doc() = "waam-twin's C++ core: scenarios, the steps and the fits in memory (use the waam_twin package).";
  static py::exception<InputError> input_error(m, "InputError", PyExc_ValueError);
  static py::exception<OutputError> output_error(m, "OutputError", input_error.ptr());
  static py::exception<InternalError> internal_error(m, "InternalError", PyExc_RuntimeError);
  input_error.doc() = "Bad input (a scenario, a key, a file, an argument): the command line's one-line message.";
  output_error.doc() = "An output that could not be written (disk full, no permission), an InputError naming the file.";
  internal_error.doc() = "The code's own mistake (an invariant that failed): please report it.";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const OutputError& e) {
      output_error(e.what());
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
  m.def(
      "data_dir", [] { return DataDir().string(); },
      "Where the data are read from: $WAAM_DATA_DIR, else <prefix>/share/waam-twin of an installed package, else\n"
      "the source tree the build came from.");
  m.def("version", &VersionString, "The version and the git commit of the build.");
  BindScenario(m);
  BindSteps(m);
  BindThermal(m);
  BindCommands(m);
}
