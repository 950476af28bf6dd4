// The scenario's program: section.
#include "planner/program/program_section.h"

#include "models/core/error.h"
#include "planner/scenario/scenario_fields.h"

namespace waam::planner {

ProgramSettings ParseProgramSection(YamlMap& top, const std::filesystem::path& scenario_dir) {
  ProgramSettings s;
  if (top.Has("target")) {
    // The intended part of a program made elsewhere (a planned part is its own target).
    WAAM_THROW_UNLESS(top.Has("program"), top.Where("target") << ": only with a program: section (a part: is its own "
                                                                 "target)");
    WAAM_THROW_UNLESS(!top.String("target").empty(), top.Where("target") << ": must name an STL file");
    s.target = top.File("target", scenario_dir, "target file");
  }
  if (!top.Has("program")) return s;
  YamlMap section = top.Map("program");
  s.present = true;
  s.where = section.Where("");
  WAAM_THROW_UNLESS(!section.String("file").empty(), section.Where("file") << ": must name the program file");
  s.file = section.File("file", scenario_dir, "program file");
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
  ReadFields<ProgramSettings>(section, kProgramFields, &s);
  if (section.Has("gcode")) {
    YamlMap gcode = section.Map("gcode");
    ReadFields<ProgramSettings>(gcode, kProgramGcodeFields, &s);
    WAAM_THROW_UNLESS(s.gcode_arc_on_m != s.gcode_arc_off_m,
                      gcode.Where("arc_off_m") << " = " << s.gcode_arc_off_m << ": must differ from arc_on_m");
    gcode.CheckNoUnknownKeys();
  }
  if (section.Has("yaskawa")) {
    YamlMap yaskawa = section.Map("yaskawa");
    ReadFields<ProgramSettings>(yaskawa, kProgramYaskawaFields, &s);
    yaskawa.CheckNoUnknownKeys();
  }
  section.CheckNoUnknownKeys();
  return s;
}

}  // namespace waam::planner
