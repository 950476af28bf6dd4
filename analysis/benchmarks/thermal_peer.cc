// Peer driver: solves the conduction problem of tools/peers/thermal_wall.json on waam's thermal model
// (twin::ThermalSimulation) and prints the probe histories as JSON, as tools/peers/thermal_fenicsx.py does for FEniCSx.
// Usage: waam_thermal_peer <problem.json> [stepping [refine [threads]]]  (tools/peers.sh runs both and compares them).
// stepping: "-" (or none) for the solver's default multirate stepping (ThermalSettings), 0 to solve the whole model
// every micro step (single-rate), a number for far_step_s, or key=value pairs (ApplyStepping). The probes are
// recorded inside the solver's batches, so the multirate levels keep their steps. refine (default 1) splits each
// problem cell into refine^3 cells with the same source: the heat of a step goes into the same 2 x 2 x 2 problem
// cells, so the refined runs converge to the problem's answer. threads (default 0: all hardware threads) caps the
// thread pool; tools/peers.sh passes 1, so that both sides' CPU times are one core's (FEniCSx runs one process with
// OMP_NUM_THREADS=1, and a second thread's waits would count as CPU time too).
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <exception>
#include <iostream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "models/core/files.h"
#include "models/core/parallel.h"
#include "models/thermal/material.h"
#include "twin/thermal/thermal_simulation.h"

namespace {

using nlohmann::json;

Eigen::Vector3d Point(const json& j) { return {j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>()}; }

Eigen::AlignedBox3d Box(const json& j) { return {Point(j.at("min")), Point(j.at("max"))}; }

// The problem's constant properties as a one-row table, no latent heat (the peer comparison allows constant ones).
waam::models::ThermalMaterial ConstantMaterial(const json& spec) {
  waam::models::ThermalMaterial m;
  m.name = "peer_constant";
  m.source = "tools/peers/thermal_wall.json";
  m.temperature_c = {spec.at("initial_c").get<double>()};
  m.conductivity_w_mk = {spec.at("conductivity_w_mk").get<double>()};
  m.density_kg_m3 = {spec.at("density_kg_m3").get<double>()};
  m.specific_heat_j_kgk = {spec.at("specific_heat_j_kgk").get<double>()};
  m.solidus_c = 1.0e4;
  m.liquidus_c = 1.0e4;
  m.latent_heat_j_kg = 0.0;
  m.emissivity = 0.0;
  return m;
}

// One problem probe read as FEniCSx evaluates its field at the point: trilinear in the values of the 8 cell centres
// around it (a cell's value is its centre's to second order); at a cell centre, that cell's value.
struct ProbeStencil {
  std::vector<std::size_t> probes;  // the centres' ThermalSimulation probe indices
  std::vector<double> weights;      // trilinear weights, summing to 1
};

// Registers the centres around p (mm) as the simulation's probes (ThermalSimulation::AddProbe, recorded inside the
// solver's batches) with their weights. `origin` is the grid's corner as ThermalSimulation lays it (x, y at the
// boxes' corner, z shifted to put the plate's top on a face).
ProbeStencil AddProbeStencil(waam::twin::ThermalSimulation& sim, const Eigen::Vector3d& p,
                             const Eigen::Vector3d& origin, double cell_mm) {
  const Eigen::Vector3d u = (p - origin) / cell_mm - Eigen::Vector3d::Constant(0.5);
  const Eigen::Vector3d lo = u.array().floor();
  const Eigen::Vector3d w = u - lo;
  ProbeStencil stencil;
  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector3i corner(c & 1, (c >> 1) & 1, (c >> 2) & 1);
    double weight = 1.0;
    for (int a = 0; a < 3; ++a) weight *= corner[a] ? w[a] : 1.0 - w[a];
    if (weight < 1e-12) continue;
    const Eigen::Vector3d centre = origin + (lo + corner.cast<double>() + Eigen::Vector3d::Constant(0.5)) * cell_mm;
    stencil.probes.push_back(sim.AddProbe(centre));
    stencil.weights.push_back(weight);
  }
  return stencil;
}

// Each problem probe's temperatures (degC) over the records, by name.
json ProbeHistories(const waam::twin::ThermalSimulation& sim, const std::vector<std::size_t>& records,
                    const std::vector<std::string>& names, const std::vector<ProbeStencil>& stencils) {
  json history = json::object();
  for (std::size_t r = 0; r < records.size(); ++r) {
    const std::vector<double> values = sim.ProbeRecord(records[r]);
    for (std::size_t i = 0; i < names.size(); ++i) {
      const ProbeStencil& stencil = stencils[i];
      double value = 0.0;
      for (std::size_t c = 0; c < stencil.probes.size(); ++c) value += stencil.weights[c] * values[stencil.probes[c]];
      history[names[i]].push_back(value);
    }
  }
  return history;
}

// The time stepping: "-" or empty keeps ThermalSettings' defaults; a number sets far_step_s (0: single-rate); else
// comma-separated key=value pairs of the multirate settings (far_step_s, whole_step_s, whole_radius_mm,
// near_step_s, near_radius_mm, arc_radius_mm, max_step_s, step_growth).
void ApplyStepping(const std::string& stepping, waam::twin::ThermalSettings& st) {
  if (stepping.empty() || stepping == "-") return;
  if (stepping.find('=') == std::string::npos) {
    st.far_step_s = std::stod(stepping);
    return;
  }
  const std::pair<const char*, double*> keys[] = {
      {"far_step_s", &st.far_step_s},         {"whole_step_s", &st.whole_step_s},
      {"whole_radius_mm", &st.whole_radius_mm}, {"near_step_s", &st.near_step_s},
      {"near_radius_mm", &st.near_radius_mm}, {"arc_radius_mm", &st.arc_radius_mm},
      {"max_step_s", &st.max_step_s},         {"step_growth", &st.step_growth}};
  std::size_t at = 0;
  while (at < stepping.size()) {
    const std::size_t end = std::min(stepping.find(',', at), stepping.size());
    const std::string pair = stepping.substr(at, end - at);
    const std::size_t eq = pair.find('=');
    bool known = false;
    for (const auto& [key, value] : keys) {
      if (eq != std::string::npos && pair.substr(0, eq) == key) {
        *value = std::stod(pair.substr(eq + 1));
        known = true;
      }
    }
    if (!known) throw std::invalid_argument("unknown stepping setting '" + pair + "'");
    at = end + 1;
  }
}

// The stepping as thermal_compare.py prints it: "single-rate" or the multirate levels' steps and reaches.
std::string StepLabel(const waam::twin::ThermalSettings& st) {
  if (st.far_step_s <= 0.0) return "single-rate";
  std::string text = "multirate: the whole model every ";
  char part[120];
  if (st.whole_step_s > st.far_step_s) {
    std::snprintf(part, sizeof part, "%g s, within %g mm every %g s", st.whole_step_s, st.whole_radius_mm,
                  st.far_step_s);
  } else {
    std::snprintf(part, sizeof part, "%g s", st.far_step_s);
  }
  text += part;
  if (st.near_step_s > 0.0) {
    std::snprintf(part, sizeof part, ", within %g mm every %g s", st.near_radius_mm, st.near_step_s);
    text += part;
  }
  std::snprintf(part, sizeof part, ", within %g mm every micro step", st.arc_radius_mm);
  return text + part;
}

json Run(const json& spec, const std::string& stepping, int refine) {
  waam::twin::ThermalSettings st;
  st.deposit = st.substrate = ConstantMaterial(spec);
  st.substrate_box_mm = Box(spec.at("plate_mm"));
  st.deposit_box_mm = Box(spec.at("wall_mm"));
  const double problem_cell_mm = spec.at("cell_mm").get<double>();
  st.cell_mm = problem_cell_mm / refine;
  st.initial_c = spec.at("initial_c").get<double>();
  st.ambient_c = spec.at("ambient_c").get<double>();
  st.convection_w_m2k = spec.at("convection_w_m2k").get<double>();
  st.emissivity = 0.0;
  st.table_conductance_w_m2k = 0.0;
  // The problem FEniCSx solves: the bead rule's cell-wise constant source, constant properties (no liquid).
  st.heat_source = waam::twin::HeatSourceShape::kUniformBead;
  st.liquid_conductivity_factor = 1.0;
  ApplyStepping(stepping, st);
  // One micro step per problem step: the arc moves one problem cell (refine fine cells) in each.
  st.arc_step_cells = refine;
  const double dt = spec.at("step_s").get<double>();
  const double width = spec.at("bead_width_mm").get<double>(), height = spec.at("bead_height_mm").get<double>();
  // The bead rule heats the bead's cross-section and one (fine) cell below it: the source's bead is deepened by the
  // rest of one problem cell, so the heated volume is the problem's whatever the refinement.
  const double source_height = height + problem_cell_mm - st.cell_mm;
  const Eigen::Vector3d a = Point(spec.at("path_mm").at(0)), b = Point(spec.at("path_mm").at(1));
  const Eigen::AlignedBox3d wall = st.deposit_box_mm;

  const auto wall0 = std::chrono::steady_clock::now();
  const std::clock_t cpu0 = std::clock();
  waam::twin::ThermalSimulation sim(st);
  // The wall stands before the pass: its cells switch on at the ambient temperature (the initial one), with no heat
  // and no step solved.
  sim.LayAtAmbient(wall);
  const double t0 = sim.time_s();
  const double setup_wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  const double setup_cpu_s = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
  std::vector<std::string> names;
  std::vector<ProbeStencil> stencils;
  Eigen::Vector3d origin = st.substrate_box_mm.min().cwiseMin(st.deposit_box_mm.min());
  const double plate_top = st.substrate_box_mm.max().z();
  origin.z() = plate_top - std::ceil((plate_top - origin.z()) / st.cell_mm - 1e-9) * st.cell_mm;
  for (const auto& [name, p] : spec.at("probes_mm").items()) {
    names.push_back(name);
    stencils.push_back(AddProbeStencil(sim, Point(p), origin, st.cell_mm));
  }
  // The probes are recorded inside the solver's batches (as `waam replay` records them), so the multirate levels
  // keep their steps: the arc's region steps with the arc, the far field in its own longer steps.
  std::vector<std::size_t> records;
  json times = json::array();
  const int weld_steps = static_cast<int>(std::lround((b - a).norm() / (spec.at("speed_mm_s").get<double>() * dt)));
  const int cool_steps = static_cast<int>(std::lround(spec.at("cool_s").get<double>() / dt));
  for (int i = 0; i < weld_steps; ++i) {
    const Eigen::Vector3d p0 = a + (b - a) * (static_cast<double>(i) / weld_steps);
    const Eigen::Vector3d p1 = a + (b - a) * (static_cast<double>(i + 1) / weld_steps);
    sim.Weld(p0, p1, width, source_height, spec.at("heat_w").get<double>(), dt);
    times.push_back(sim.time_s() - t0);
    records.push_back(sim.RecordProbes());
  }
  for (int i = 0; i < cool_steps; ++i) {
    sim.Cool(dt);
    times.push_back(sim.time_s() - t0);
    records.push_back(sim.RecordProbes());
  }
  const json history = ProbeHistories(sim, records, names, stencils);
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  const double cpu_s = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
  const waam::twin::ThermalStats stats = sim.Stats();
  const waam::twin::EnergyBalance energy = sim.Energy();
  return {{"peer", "waam"}, {"wall_s", wall_s}, {"cpu_s", cpu_s}, {"setup_s", setup_wall_s},
          {"setup_cpu_s", setup_cpu_s}, {"cells", stats.active_cells},
          {"steps", stats.steps}, {"iterations", stats.iterations}, {"coupling_retries", stats.coupling_retries},
          {"coupling_repairs", stats.coupling_repairs},
          {"level_solves", stats.level_solves}, {"level_cell_solves", stats.level_cell_solves},
          {"far_step_s", st.far_step_s},
          {"stepping", StepLabel(st)}, {"refine", refine},
          {"energy_relative_error", energy.RelativeError()}, {"time_s", times}, {"probes_c", history}};
}

// A whole-number argument, or an error naming it.
int IntegerArgument(std::string_view text, const char* what) {
  int value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size()) {
    throw std::invalid_argument(std::string(what) + " '" + std::string(text) + "': not a whole number (or too large)");
  }
  return value;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argc > 5) {
    std::fprintf(stderr, "usage: waam_thermal_peer <problem.json> [stepping|- [refine [threads]]]\n");
    return 2;
  }
  try {
    const json spec = json::parse(waam::ReadFile(argv[1]));
    const int refine = argc >= 4 ? IntegerArgument(argv[3], "refine") : 1;
    if (refine < 1) throw std::invalid_argument("refine must be >= 1");
    const int threads = argc == 5 ? IntegerArgument(argv[4], "threads") : 0;
    waam::SetThreadCount(threads);
    json result = Run(spec, argc >= 3 ? std::string(argv[2]) : std::string(), refine);
    result["threads"] = waam::ThreadCount();
    std::cout << result.dump() << std::endl;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "waam_thermal_peer: %s\n", e.what());
    return 2;
  }
  return 0;
}
