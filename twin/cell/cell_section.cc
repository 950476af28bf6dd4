// The `cell:` scenario section: placement of arm, positioner and part, and the margins of `waam check`.
#include "twin/cell/cell_section.h"

#include <cmath>

#include "models/core/error.h"
#include "twin/cell/cell_presets.h"

namespace waam::twin {

namespace {

// The torch's rules across keys: the TCP at least 50 mm out, the nozzle shorter than the torch. `where` names it.
void CheckTorch(const TorchSettings& torch, const std::string& where_tcp, const std::string& where_nozzle) {
  const std::array<double, 3>& tcp = torch.tcp_mm;
  const double length = std::sqrt(tcp[0] * tcp[0] + tcp[1] * tcp[1] + tcp[2] * tcp[2]);
  WAAM_THROW_UNLESS(length >= 50.0, where_tcp << ": the TCP must lie at least 50 mm from the flange");
  WAAM_THROW_UNLESS(torch.nozzle_length_mm + torch.nozzle_radius_mm + 15.0 < length,
                    where_nozzle << ": the nozzle (plus its radius and 15 mm above the TCP) "
                                    "must be shorter than the torch");
}

// cell.robot: the URDF keys only with a URDF arm (a preset's arm is not renamed), then the placement.
void ParseRobot(YamlMap& map, CellSettings* cell) {
  YamlMap robot = map.Map("robot");
  if (robot.Has("urdf")) {
    WAAM_THROW_UNLESS(!map.Has("mjcf"), robot.Where("urdf") << ": give cell.mjcf or cell.robot.urdf, not both");
    for (const char* key : {"urdf", "package_paths", "joints", "flange"}) {
      ReadField<CellSettings>(robot, kCellRobotFields, key, cell);
    }
  }
  ReadField<CellSettings>(robot, kCellRobotFields, "base_mm", cell);
  ReadField<CellSettings>(robot, kCellRobotFields, "yaw_deg", cell);
  robot.CheckNoUnknownKeys();
}

}  // namespace

void ValidateCellSettings(const CellSettings& cell) {
  CheckFields<CellSettings>(kCellFields, cell, "cell");
  CheckFields<CellSettings>(kCellRobotFields, cell, "cell.robot");
  CheckFields<CellSettings>(kCellPositionerFields, cell, "cell.positioner");
  CheckFields<TorchSettings>(kTorchFields, cell.torch, "cell.torch");
  CheckFields<CellSettings>(kCellPartFields, cell, "cell.part");
  CheckFields<CellSettings>(kCellChecksFields, cell, "cell.checks");
  CheckTorch(cell.torch, "cell.torch.tcp_mm", "cell.torch.nozzle_length_mm");
}

CellSettings ParseCellSection(YamlMap& top) {
  CellSettings cell;
  if (!top.Has("cell")) return cell;
  YamlMap map = top.Map("cell");
  cell.where = map.Where("");
  if (map.Has("preset")) {
    // A whole cell; a model of one's own is a different cell, so it may not be given too.
    ReadField<CellSettings>(map, kCellFields, "preset", &cell);
    const CellPreset preset = *cell.preset;
    const bool urdf = map.Has("robot") && map.Map("robot").Has("urdf");
    WAAM_THROW_UNLESS(!map.Has("mjcf") && !urdf, map.Where("preset") << ": give cell.preset or cell."
                                                                     << (urdf ? "robot.urdf" : "mjcf") << ", not both");
    ApplyPreset(preset, &cell);
  }
  ReadField<CellSettings>(map, kCellFields, "mjcf", &cell);
  if (map.Has("robot")) ParseRobot(map, &cell);
  if (map.Has("positioner")) {
    YamlMap pos = map.Map("positioner");
    ReadFields<CellSettings>(pos, kCellPositionerFields, &cell);
    pos.CheckNoUnknownKeys();
  }
  if (map.Has("torch")) {
    YamlMap torch = map.Map("torch");
    ReadFields<TorchSettings>(torch, kTorchFields, &cell.torch);
    CheckTorch(cell.torch, torch.Where("tcp_mm"), torch.Where("nozzle_length_mm"));
    torch.CheckNoUnknownKeys();
  }
  ReadField<CellSettings>(map, kCellFields, "resolve", &cell);
  ReadField<CellSettings>(map, kCellFields, "axis_ramp_s", &cell);
  if (map.Has("part")) {
    YamlMap part = map.Map("part");
    ReadFields<CellSettings>(part, kCellPartFields, &cell);
    part.CheckNoUnknownKeys();
  }
  if (map.Has("checks")) {
    YamlMap checks = map.Map("checks");
    ReadFields<CellSettings>(checks, kCellChecksFields, &cell);
    checks.CheckNoUnknownKeys();
  }
  map.CheckNoUnknownKeys();
  return cell;
}

}  // namespace waam::twin
