// The scenario's program: section.
#include "planner/program/program_section.h"

#include "models/core/error.h"

namespace waam::planner::internal {

ProgramSettings ParseProgramSection(YamlMap& top, const std::filesystem::path& scenario_dir) {
  ProgramSettings s;
  if (top.Has("target")) {
    // The intended part of a program made elsewhere (a planned part is its own target).
    WAAM_THROW_UNLESS(top.Has("program"), top.Where("target") << ": only with a program: section (a part: is its own "
                                                                 "target)");
    s.target = top.String("target");
    WAAM_THROW_UNLESS(!s.target.empty(), top.Where("target") << ": must name an STL file");
    if (s.target.is_relative()) s.target = scenario_dir / s.target;
    s.target = s.target.lexically_normal();
    std::error_code ec;
    WAAM_THROW_UNLESS(std::filesystem::is_regular_file(s.target, ec),
                      top.Where("target") << ": target file " << s.target.string() << " not found");
  }
  if (!top.Has("program")) return s;
  YamlMap section = top.Map("program");
  s.present = true;
  s.where = section.Where("");
  s.file = section.String("file");
  WAAM_THROW_UNLESS(!s.file.empty(), section.Where("file") << ": must name the program file");
  if (s.file.is_relative()) s.file = scenario_dir / s.file;
  std::error_code ec;
  WAAM_THROW_UNLESS(std::filesystem::is_regular_file(s.file, ec),
                    section.Where("file") << ": program file " << s.file.string() << " not found");
  const std::string format = section.String("format", "auto");
  if (format != "auto") {
    const std::optional<ProgramFormat> f = ParseEnum<ProgramFormat>(format);
    WAAM_THROW_UNLESS(f.has_value(), section.Where("format") << " = '" << format << "': must be auto or one of "
                                                             << EnumNameList<ProgramFormat>(", "));
    s.format = f;
  }
  if (section.Has("frame")) {
    YamlMap frame = section.Map("frame");
    if (frame.Has("user_frame_mm")) {
      const std::vector<double> v = frame.Numbers("user_frame_mm", 6, -1e6, 1e6);
      s.user_frame_mm = std::array<double, 6>{v[0], v[1], v[2], v[3], v[4], v[5]};
    }
    frame.CheckNoUnknownKeys();
  }
  s.layers = section.Enum("layers", ProgramLayers::kAuto);
  s.layer_tolerance_mm = section.Number("layer_tolerance_mm", 0.0, 1000.0, 0.0);
  if (section.Has("gcode")) {
    YamlMap gcode = section.Map("gcode");
    s.gcode_arc_on_m = gcode.Integer("arc_on_m", 0, 999, 3);
    s.gcode_arc_off_m = gcode.Integer("arc_off_m", 0, 999, 5);
    WAAM_THROW_UNLESS(s.gcode_arc_on_m != s.gcode_arc_off_m,
                      gcode.Where("arc_off_m") << " = " << s.gcode_arc_off_m << ": must differ from arc_on_m");
    gcode.CheckNoUnknownKeys();
  }
  if (section.Has("yaskawa")) {
    YamlMap yaskawa = section.Map("yaskawa");
    if (yaskawa.Has("pulses_per_deg")) {
      const std::vector<double> v = yaskawa.Numbers("pulses_per_deg", 6, 1e-3, 1e7);
      for (int j = 0; j < 6; ++j) s.yaskawa_pulses_per_deg[j] = v[j];
    }
    if (yaskawa.Has("station_pulses_per_deg")) {
      const std::vector<double> v = yaskawa.Numbers("station_pulses_per_deg", 2, 1e-3, 1e7);
      s.yaskawa_station_pulses_per_deg = {v[0], v[1]};
    }
    yaskawa.CheckNoUnknownKeys();
  }
  section.CheckNoUnknownKeys();
  return s;
}

}  // namespace waam::planner::internal
