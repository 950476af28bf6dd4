// The `cell:` scenario section: placement of arm, positioner and part, and the margins of `waam check`.
#include "twin/cell/cell_section.h"

#include <cmath>
#include <system_error>

#include "models/core/error.h"
#include "twin/cell/cell_presets.h"

namespace waam::twin::internal {
namespace fs = std::filesystem;

namespace {

std::array<double, 3> Xyz(YamlMap& map, const std::string& key, const std::array<double, 3>& fallback) {
  const std::vector<double> v =
      map.Numbers(key, 3, -20000.0, 20000.0, std::vector<double>(fallback.begin(), fallback.end()));
  return {v[0], v[1], v[2]};
}

}  // namespace

CellSettings ParseCellSection(YamlMap& top, const fs::path& scenario_dir) {
  CellSettings cell;
  if (!top.Has("cell")) return cell;
  YamlMap map = top.Map("cell");
  cell.where = map.Where("");
  if (map.Has("preset")) {
    // A whole cell; a model of one's own is a different cell, so it may not be given too.
    const CellPreset preset = map.Enum<CellPreset>("preset");
    const bool urdf = map.Has("robot") && map.Map("robot").Has("urdf");
    WAAM_THROW_UNLESS(!map.Has("mjcf") && !urdf, map.Where("preset") << ": give cell.preset or cell."
                                                                     << (urdf ? "robot.urdf" : "mjcf") << ", not both");
    ApplyPreset(preset, &cell);
  }
  if (map.Has("mjcf")) {
    cell.mjcf = fs::path(map.String("mjcf"));
    if (cell.mjcf.is_relative()) cell.mjcf = scenario_dir / cell.mjcf;
    cell.mjcf = cell.mjcf.lexically_normal();
    std::error_code ec;
    WAAM_THROW_UNLESS(fs::is_regular_file(cell.mjcf, ec),
                      map.Where("mjcf") << ": MJCF file " << cell.mjcf.string() << " not found");
  }
  if (map.Has("robot")) {
    YamlMap robot = map.Map("robot");
    if (robot.Has("urdf")) {
      WAAM_THROW_UNLESS(!map.Has("mjcf"), robot.Where("urdf") << ": give cell.mjcf or cell.robot.urdf, not both");
      cell.robot_urdf = fs::path(robot.String("urdf"));
      if (cell.robot_urdf.is_relative()) cell.robot_urdf = scenario_dir / cell.robot_urdf;
      cell.robot_urdf = cell.robot_urdf.lexically_normal();
      std::error_code ec;
      WAAM_THROW_UNLESS(fs::is_regular_file(cell.robot_urdf, ec),
                        robot.Where("urdf") << ": URDF file " << cell.robot_urdf.string() << " not found");
      for (const std::string& dir : robot.Strings("package_paths", {})) {
        fs::path d(dir);
        if (d.is_relative()) d = scenario_dir / d;
        cell.robot_package_paths.push_back(d.lexically_normal());
      }
      cell.robot_joints = robot.Strings("joints", {});
      WAAM_THROW_UNLESS(cell.robot_joints.empty() || cell.robot_joints.size() == 6,
                        robot.Where("joints") << ": name the six arm joints, got " << cell.robot_joints.size());
      cell.robot_flange = robot.String("flange", "");
    }
    cell.robot_base_mm = Xyz(robot, "base_mm", cell.robot_base_mm);
    cell.robot_yaw_deg = robot.Number("yaw_deg", -360.0, 360.0, cell.robot_yaw_deg);
    robot.CheckNoUnknownKeys();
  }
  if (map.Has("positioner")) {
    YamlMap pos = map.Map("positioner");
    if (pos.Has("type")) cell.positioner_type = pos.Enum<planner::PositionerType>("type");
    cell.positioner_base_mm = Xyz(pos, "base_mm", cell.positioner_base_mm);
    cell.positioner_yaw_deg = pos.Number("yaw_deg", -360.0, 360.0, cell.positioner_yaw_deg);
    cell.positioner_rotation_deg = pos.Number("rotation_deg", -240.0, 240.0, cell.positioner_rotation_deg);
    cell.positioner_follow = pos.Enum("follow", cell.positioner_follow);
    cell.positioner_tilt_tolerance_deg =
        pos.Number("tilt_tolerance_deg", 0.0, 45.0, cell.positioner_tilt_tolerance_deg);
    pos.CheckNoUnknownKeys();
  }
  if (map.Has("torch")) {
    YamlMap torch = map.Map("torch");
    const std::vector<double> tcp = torch.Numbers("tcp_mm", 3, -2000.0, 2000.0,
                                                  {cell.torch.tcp_mm[0], cell.torch.tcp_mm[1], cell.torch.tcp_mm[2]});
    cell.torch.tcp_mm = {tcp[0], tcp[1], tcp[2]};
    const double length = std::sqrt(tcp[0] * tcp[0] + tcp[1] * tcp[1] + tcp[2] * tcp[2]);
    WAAM_THROW_UNLESS(length >= 50.0, torch.Where("tcp_mm") << ": the TCP must lie at least 50 mm from the flange");
    cell.torch.nozzle_radius_mm = torch.Number("nozzle_radius_mm", 1.0, 50.0, cell.torch.nozzle_radius_mm);
    cell.torch.nozzle_length_mm = torch.Number("nozzle_length_mm", 1.0, 500.0, cell.torch.nozzle_length_mm);
    WAAM_THROW_UNLESS(cell.torch.nozzle_length_mm + cell.torch.nozzle_radius_mm + 15.0 < length,
                      torch.Where("nozzle_length_mm") << ": the nozzle (plus its radius and 15 mm above the TCP) "
                                                         "must be shorter than the torch");
    cell.torch.spin_range_deg = torch.Number("spin_range_deg", 0.0, 180.0, cell.torch.spin_range_deg);
    cell.torch.spin_step_deg = torch.Number("spin_step_deg", 1.0, 90.0, cell.torch.spin_step_deg);
    cell.torch.max_spin_deg_per_mm = torch.Number("max_spin_deg_per_mm", 0.01, 90.0, cell.torch.max_spin_deg_per_mm);
    torch.CheckNoUnknownKeys();
  }
  cell.resolve = map.Enum("resolve", cell.resolve);
  cell.axis_ramp_s = map.Number("axis_ramp_s", 0.01, 10.0, cell.axis_ramp_s);
  if (map.Has("part")) {
    YamlMap part = map.Map("part");
    cell.part_offset_mm = Xyz(part, "offset_mm", cell.part_offset_mm);
    cell.part_yaw_deg = part.Number("yaw_deg", -360.0, 360.0, cell.part_yaw_deg);
    part.CheckNoUnknownKeys();
  }
  if (map.Has("checks")) {
    YamlMap checks = map.Map("checks");
    cell.joint_margin_deg = checks.Number("joint_margin_deg", 0.0, 45.0, cell.joint_margin_deg);
    cell.singularity_deg = checks.Number("singularity_deg", 0.0, 45.0, cell.singularity_deg);
    cell.step_mm = checks.Number("step_mm", 0.1, 100.0, cell.step_mm);
    cell.collision_tolerance_mm = checks.Number("collision_tolerance_mm", 0.0, 50.0, cell.collision_tolerance_mm);
    cell.part_collision = checks.Bool("part_collision", cell.part_collision);
    checks.CheckNoUnknownKeys();
  }
  map.CheckNoUnknownKeys();
  return cell;
}

}  // namespace waam::twin::internal
