// The library of cells (see cell_presets.h). Kinematics, limits and speeds live in the preset files, which cite
// their sources; this table holds what the files do not: the vendor name, the reach and the placement.
#include "twin/cell/cell_presets.h"

#include "models/core/data_dir.h"
#include "models/core/error.h"

namespace waam::twin {
namespace {

// The positioner stands in front of the arm at about 70 % of its reach, tilt axis across the line between them, so
// that a small part on the plate is reached on every branch the wall needs (scenarios/cell/preset_*.yaml).
// The turntable and fixed-table cells are the KUKA and ABB arms of the library with the positioner replaced (see
// PositionerMjcf in cell_compose.cc: the same plate at the same 600 mm working height, so the same placement).
constexpr std::array<CellPresetInfo, 6> kPresets = {{
    {CellPreset::kFanucArcMate100ic, "FANUC ARC Mate 100iC/12", "", 1420.0, {1050.0, 0.0, 0.0}, {}},
    {CellPreset::kAbbIrb1600, "ABB IRB 1600-8/1.45", "abb_irb1600_145.urdf", 1450.0, {1000.0, 0.0, 0.0}, {}},
    {CellPreset::kKukaKr16, "KUKA KR 16-2", "kuka_kr16_2.urdf", 1611.0, {1150.0, 0.0, 0.0}, {}},
    {CellPreset::kYaskawaMh12, "Yaskawa Motoman MH12", "yaskawa_mh12.urdf", 1440.0, {1000.0, 0.0, 0.0}, {}},
    {CellPreset::kKukaKr16Turntable, "KUKA KR 16-2", "kuka_kr16_2.urdf", 1611.0, {1150.0, 0.0, 0.0}, {},
     planner::PositionerType::kTurntable},
    {CellPreset::kAbbIrb1600Table, "ABB IRB 1600-8/1.45", "abb_irb1600_145.urdf", 1450.0, {1000.0, 0.0, 0.0}, {},
     planner::PositionerType::kNone},
}};

}  // namespace

const CellPresetInfo& PresetInfo(CellPreset preset) {
  for (const CellPresetInfo& info : kPresets) {
    if (info.preset == preset) return info;
  }
  WAAM_DEMAND(false);
  return kPresets[0];
}

std::filesystem::path PresetUrdf(CellPreset preset) {
  const CellPresetInfo& info = PresetInfo(preset);
  if (info.urdf.empty()) return {};
  return DataDir() / "twin" / "data" / "presets" / std::string(info.urdf);
}

planner::ProgramFormat PresetDialect(CellPreset preset) {
  switch (preset) {
    case CellPreset::kFanucArcMate100ic: return planner::ProgramFormat::kFanucLs;
    case CellPreset::kAbbIrb1600: return planner::ProgramFormat::kAbbRapid;
    case CellPreset::kKukaKr16: return planner::ProgramFormat::kKukaKrl;
    case CellPreset::kKukaKr16Turntable: return planner::ProgramFormat::kKukaKrl;
    case CellPreset::kAbbIrb1600Table: return planner::ProgramFormat::kAbbRapid;
    case CellPreset::kYaskawaMh12: return planner::ProgramFormat::kYaskawaJbi;
  }
  WAAM_DEMAND(false);
  return planner::ProgramFormat::kFanucLs;
}

void ApplyPreset(CellPreset preset, CellSettings* cell) {
  const CellPresetInfo& info = PresetInfo(preset);
  cell->preset = preset;
  cell->mjcf.clear();
  cell->robot_urdf = PresetUrdf(preset);
  cell->robot_package_paths.clear();
  cell->robot_joints.clear();
  cell->robot_flange.clear();
  cell->torch = info.torch;
  cell->robot_base_mm = {0.0, 0.0, 0.0};
  cell->robot_yaw_deg = 0.0;
  cell->positioner_base_mm = info.positioner_base_mm;
  cell->positioner_yaw_deg = 90.0;
  cell->positioner_type = info.positioner;
}

}  // namespace waam::twin
