// waam_twin.thermal: the thermal model along the build's timeline (`waam thermal`) in memory, probe histories and
// the temperature field at each layer's end as numpy views.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "analysis/plan_timeline.h"
#include "analysis/thermal_command.h"
#include "analysis/thermal_run.h"
#include "python/bindings.h"
#include "python/steps.h"

namespace waam::python {
namespace fs = std::filesystem;

namespace {

struct ThermalHolder {
  std::shared_ptr<const ScenarioHolder> scenario;
  analysis::ThermalRunResult result;
  nlohmann::json document;  // thermal.json
};

std::shared_ptr<ThermalHolder> Thermal(const std::shared_ptr<const ScenarioHolder>& scn,
                                       std::shared_ptr<const PlanHolder> plan, const py::object& progress) {
  const analysis::Scenario& s = scn->scenario;
  WAAM_THROW_UNLESS(s.thermal.given, s.file.string() << ": no thermal: section: thermal needs the metals and the "
                                                        "plate (docs/THERMAL.md)");
  return RunLong(progress, [&] {
    if (!plan) plan = PlanOf(scn);
    auto h = std::make_shared<ThermalHolder>();
    h->scenario = scn;
    Progress bar("thermal", 0, "spans", /*quiet=*/true);
    h->result = analysis::RunThermalModel(s, plan->result.plan, analysis::TimelineBuilderFor(s, plan->result.plan),
                                          &bar);
    bar.Finish();
    h->document = analysis::ThermalToJson(s, h->result);
    return h;
  });
}

// A read-only 1-D numpy view of `values`, owned by `owner`.
template <typename T>
py::array Vector(const std::vector<T>& values, py::handle owner) {
  py::array a(py::dtype::of<T>(), {values.size()}, {sizeof(T)}, values.data(), owner);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

py::dict Probes(py::object self) {
  const auto& h = self.cast<const ThermalHolder&>();
  py::dict probes;
  for (const analysis::ThermalProbeHistory& p : h.result.probes) probes[py::str(p.name)] = Vector(p.temperature_c, self);
  return probes;
}

// The temperature field at the end of the i-th layer with an arc, (nz x ny x nx) float32 view, degC, NaN where no
// metal is, with its origin and cell size.
py::dict Field(py::object self, int i) {
  const auto& h = self.cast<const ThermalHolder&>();
  const int count = static_cast<int>(h.result.fields.size());
  WAAM_THROW_UNLESS(i >= 0 && i < count, "field " << i << ": the run has fields 0.." << count - 1
                                                  << " (one per layer with an arc)");
  const analysis::ThermalLayerField& f = h.result.fields[i];
  const auto nx = static_cast<std::size_t>(f.field.size.x()), ny = static_cast<std::size_t>(f.field.size.y()),
             nz = static_cast<std::size_t>(f.field.size.z());
  py::array a(py::dtype::of<float>(), {nz, ny, nx}, {ny * nx * sizeof(float), nx * sizeof(float), sizeof(float)},
              f.field.temperature_c.data(), self);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  py::dict out;
  out["layer"] = f.layer;
  out["time_s"] = f.time_s;
  out["origin_mm"] = py::make_tuple(f.field.origin_mm.x(), f.field.origin_mm.y(), f.field.origin_mm.z());
  out["cell_mm"] = f.field.cell_mm;
  out["temperature_c"] = a;
  return out;
}

void SaveThermal(const ThermalHolder& h, const fs::path& dir, bool images) {
  py::gil_scoped_release release;
  analysis::ThermalOptions options;
  options.out_dir = dir;
  options.quiet = true;
  options.images = images;
  analysis::WriteThermalOutputs(h.scenario->scenario, h.result, options);
}

}  // namespace

void BindThermal(py::module_& m) {
  py::class_<ThermalHolder, std::shared_ptr<ThermalHolder>>(
      m, "ThermalResult", "The thermal model run along the build's timeline (interpass waits included).")
      .def_property_readonly(
          "sample_time_s", [](py::object self) { return Vector(self.cast<const ThermalHolder&>().result.sample_time_s, self); },
          "The probe sample times, s, a float64 view (every thermal.sample_s, and the end).")
      .def_property_readonly("probes", &Probes,
                             "Each probe's temperature at every sample time: {name: float64 view, degC, NaN while\n"
                             "no metal is there}, in thermal.probes order.")
      .def_property_readonly("field_count", [](const ThermalHolder& h) { return h.result.fields.size(); },
                             "The number of temperature fields (one per layer with an arc).")
      .def("field", &Field, py::arg("i"),
           "The temperature field at the end of the i-th layer with an arc: a dict with layer, time_s, origin_mm,\n"
           "cell_mm and temperature_c, a (nz x ny x nx) float32 view, degC, NaN where no metal is.")
      .def_property_readonly("timeline", [](const ThermalHolder& h) { return ToPython(analysis::TimelineToJson(h.result.timeline)); },
                             "The timeline with the interpass waits, as thermal.json has it.")
      .def_property_readonly("layers", [](const ThermalHolder& h) { return ToPython(h.document["layers"]); },
                             "Per layer: start_s, end_s, interpass_c, peak_c, wait_s, interpass_reached.")
      .def_property_readonly("energy_balance", [](const ThermalHolder& h) { return ToPython(h.document["energy_balance"]); },
                             "The solver's accounts: heat input = stored + lost (J), and the relative error.")
      .def("to_dict", [](const ThermalHolder& h) { return ToPython(h.document); }, "The content of thermal.json.")
      .def("save", &SaveThermal, py::arg("dir"), py::arg("images") = true,
           "Writes what `waam thermal` writes into dir (thermal.json, thermal.h5, the pictures with images), by\n"
           "the same writers.");
  m.def("_thermal", &Thermal, py::arg("scenario"), py::arg("plan") = nullptr, py::arg("progress") = py::none());
}

}  // namespace waam::python
