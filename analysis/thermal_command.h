// `waam thermal`: plan a scenario (or read its program), build its timeline and run the thermal model along it,
// then write thermal.json, thermal.h5 and the pictures (docs/THERMAL.md, "Commands and outputs").
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "analysis/scenario.h"
#include "analysis/thermal_run.h"
#include "planner/planar_planner.h"

namespace waam::analysis {

struct ThermalOptions {
  std::filesystem::path scenario;      // scenario YAML (with a thermal: section and process.arc)
  std::filesystem::path out_dir;       // output directory (created if missing)
  std::vector<std::string> overrides;  // "key.path=value" scenario overrides (--set)
  bool quiet = false;                  // no progress bar
  bool images = true;                  // write the PNGs
};

// Loads the scenario, plans it (or reads its program: PlanScenarioOrProgram), then ThermalPlanned. Throws InputError
// for a bad scenario (no thermal section, unknown material, probe outside the metal, ...), Interrupted on Ctrl-C.
ThermalRunResult RunThermal(const ThermalOptions& options);

// Runs the thermal model on an already planned scenario and writes every output atomically: thermal.h5,
// interpass.png, probes.png, maps/layer_NNNN.png, and thermal.json last (its presence marks a complete run).
ThermalRunResult ThermalPlanned(const Scenario& scenario, const planner::Plan& plan, const ThermalOptions& options);

// Writes what `waam thermal` writes for a thermal run already made into options.out_dir (claimed first; thermal.h5,
// the PNGs with options.images, thermal.json last, all atomically) and returns the thermal.json document. Throws
// InputError and OutputError.
nlohmann::json WriteThermalOutputs(const Scenario& scenario, const ThermalRunResult& result,
                                   const ThermalOptions& options);

// The timeline of `plan` with extra interpass waits before layers (planner::BuildTimeline with the scenario's
// process and cell settings).
TimelineBuilder TimelineBuilderFor(const Scenario& scenario, const planner::Plan& plan);

// The thermal.json document (the public contract, documented in `waam thermal --help` and docs/THERMAL.md).
nlohmann::json ThermalToJson(const Scenario& scenario, const ThermalRunResult& result);

// thermal.h5: /probes/time_s and /probes/<NAME> (degC, NaN while no metal is there), /layers/{layer, start_s, end_s,
// interpass_c, peak_c, wait_s}, /timeline/{kind, start_s, end_s, layer, point}, and /fields/layer_NNNN (nz x ny x nx
// float32 degC, NaN where no metal is) with attributes origin_mm, cell_mm, dims [nx, ny, nz], time_s, layer.
void WriteThermalH5(const ThermalRunResult& result, const std::filesystem::path& path);

// Pictures: interpass temperature and wait per layer; probe temperatures over time; a vertical section of the
// temperature field at one layer's end (colour range [lo_c, hi_c], shared by every layer's map). Each title starts
// with `part_name`.
void WriteInterpassPng(const ThermalRunResult& result, const planner::InterpassSettings& interpass,
                       const std::string& part_name, const std::filesystem::path& path);
void WriteProbesPng(const ThermalRunResult& result, const planner::InterpassSettings& interpass,
                    const std::string& part_name, const std::filesystem::path& path);
void WriteTemperatureMapPng(const ThermalLayerField& field, const Eigen::AlignedBox3d& deposit_box_mm, double lo_c,
                            double hi_c, const std::string& part_name, const std::filesystem::path& path);

}  // namespace waam::analysis
