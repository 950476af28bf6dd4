// Settings of junction void filling (scenario key `path.void_filling`, dissertation 003 sec. 4.4).
#pragma once

#include <array>
#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include "models/core/enum_names.h"
#include "models/voids/void_length_model.h"

namespace waam {
class YamlMap;
}  // namespace waam

namespace waam::planner {

// path.void_filling.mode
enum class VoidFillingMode { kNone, kFixed, kModel, kTuned };
constexpr std::array<EnumName<VoidFillingMode>, 4> EnumNames(VoidFillingMode) {
  return {{{VoidFillingMode::kNone, "none"}, {VoidFillingMode::kFixed, "fixed"}, {VoidFillingMode::kModel, "model"},
           {VoidFillingMode::kTuned, "tuned"}}};
}
WAAM_ENUM_JSON(VoidFillingMode)

struct VoidFillingSettings {
  VoidFillingMode mode = VoidFillingMode::kNone;  // fixed: lambda; model: void-length model, eq. 4.6; tuned: tune.json
  double lambda = 1.0;           // empirical weight of eq. 4.5 for mode fixed; 1 = the geometric correction
  double spacing_mm = 0.0;       // l: centre distance of the two beads of a wall, mm; 0 = the overlap model's d2
  int min_ribs = 3;              // correct junctions of at least this many ribs (2-rib corners are left as they are)
  std::filesystem::path model;   // void-length model JSON (mode model); empty = models/data/void_length.json
  std::filesystem::path tune_file;  // tune.json of `waam tune-voids` (mode tuned), absolute
  // shift PP_N* (mm) by junction class (mode tuned): read from tune_file by the scenario loader, or set in code
  std::map<std::string, double> shift_by_class_mm;
  // The void-length model of `model` (or the default), loaded by the scenario loader; needed by mode model
  std::shared_ptr<const models::VoidLengthModel> void_length;
  std::string where = "path.void_filling";  // "file:line: path.void_filling" for messages
};

namespace internal {
// Reads the optional `void_filling:` mapping of the scenario's `path` map into `out`; relative files are resolved
// against `scenario_dir`. Throws InputError naming file, line and key for unknown keys, out-of-range values, a
// missing file, or a mode without what it needs.
void ParseVoidFillingSection(YamlMap& path, VoidFillingSettings* out);
}  // namespace internal

}  // namespace waam::planner
