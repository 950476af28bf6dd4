// `waam deviation` (scan vs target: per-point deviation, central axis, ovality) and `waam compensate` (the offline
// shrinkage/distortion compensation loop of 003 sec. 6.5 run against the twin).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "twin/compensation/compensation.h"
#include "twin/scanner/scan_deviation.h"

namespace waam::analysis {

struct DeviationOptions {
  std::filesystem::path target;     // target STL (part frame, mm)
  std::filesystem::path scan;       // scan: .ply, .xyz or .stl (aligned in the part frame, mm)
  std::filesystem::path out_dir;
  double axis_step_mm = 2.0;        // central-axis station spacing, mm
  bool keep_bottom = false;         // an STL scan: keep the facets the part stands on (left out by default)
  bool images = true;
};

// Reads both files, measures and writes deviation.json, deviation.ply (points + deviation_mm) and deviation_map.png
// (deviation.json last). Throws InputError naming the file and line of a bad input.
nlohmann::json RunDeviation(const DeviationOptions& options);

// The deviation summary document of a scan (also used per iteration by compensate).
nlohmann::json DeviationToJson(const twin::ScanDeviation& scan, const twin::AxisComparison& axis);

// Two views (front x-z, side y-z) of the scan points coloured by deviation (blue -, white 0, red +, symmetric range
// `range_mm` > 0, 0 = the scan's max |deviation|) with `title`, written atomically as PNG.
void WriteScanDeviationPng(const twin::ScanDeviation& scan, const std::string& title, double range_mm,
                           const std::filesystem::path& path);

struct CompensateOptions {
  std::filesystem::path scenario;
  std::filesystem::path out_dir;
  std::vector<std::string> overrides;     // --set key.path=value
  int max_iterations = 3;
  double tolerance_mm = 0.0;              // 0 = the simulated part's waviness
  std::filesystem::path first_scan;       // optional real scan of the first part
  std::filesystem::path model;            // distortion model JSON; empty = models/data/distortion.json
  std::string mode;                       // fe | reduced; empty = the model file's
  double element_mm = 2.0;
  int groups = 4;
  std::string correction = "axis";       // axis (central axis + cross sections) | points (per point only)
  int debug_level = 0;                   // diagnostics on stderr: 0 none, 1 every tenth layer, 2 every layer
  bool quiet = false;
  bool images = true;
  bool program = true;                    // write the compensated robot program (needs the scenario's cell)
};

// Plans the scenario, runs the loop and writes compensate.json (last), compensated_path.h5, the pictures
// deviation_before.png / deviation_after.png, scan_before.ply / scan_after.ply and program/ (program.ls, .csv).
// Throws InputError for bad input; non-convergence is reported in the result.
twin::CompensationResult RunCompensate(const CompensateOptions& options);

}  // namespace waam::analysis
