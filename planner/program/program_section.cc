// The scenario's program: section.
#include "planner/program/program_section.h"

#include "models/core/error.h"
#include "planner/scenario/scenario_fields.h"

namespace waam::planner {

ProgramSettings ParseProgramSection(YamlMap& top) {
  ProgramSettings s;
  if (top.Has("target")) {
    // The intended part of a program made elsewhere (a planned part is its own target).
    WAAM_THROW_UNLESS(top.Has("program"), top.Where("target") << ": only with a program: section (a part: is its own "
                                                                 "target)");
    ReadField<ProgramSettings>(top, kProgramTargetFields, "target", &s);
  }
  if (!top.Has("program")) return s;
  YamlMap section = top.Map("program");
  s.present = true;
  s.where = section.Where("");
  ReadField<ProgramSettings>(section, kProgramFields, "file", &s, true);
  if (ReadFieldMap<ProgramSettings>(section, "frame", kProgramFrameFields, &s)) {
    s.frames.user_frame = s.user_frame_mm.has_value();
  }
  ReadFields<ProgramSettings>(section, kProgramFields, &s);
  if (section.Has("gcode")) {
    YamlMap gcode = section.Map("gcode");
    ReadFields<ProgramSettings>(gcode, kProgramGcodeFields, &s);
    WAAM_THROW_UNLESS(s.gcode_arc_on_m != s.gcode_arc_off_m,
                      gcode.Where("arc_off_m") << " = " << s.gcode_arc_off_m << ": must differ from arc_on_m");
    gcode.CheckNoUnknownKeys();
  }
  if (section.Has("frames")) {
    // A frame is never the torch (the word a tool may be): said before the numbers' message.
    YamlMap frames = section.Map("frames");
    if (frames.Has("uframe")) {
      YamlMap uframe = frames.Map("uframe");
      for (const auto& entry : uframe.NumberKeys("frame", 1, 999)) {
        WAAM_THROW_UNLESS(uframe.IsList(entry.second) || uframe.IsMapping(entry.second) ||
                              uframe.String(entry.second) != "torch",
                          uframe.Where(entry.second) << " = torch: only a tool (utool) can be the cell's torch");
      }
    }
    ReadFieldMap<ProgramFrames>(section, "frames", kProgramFramesFields, &s.frames);
  }
  if (section.Has("yaskawa")) {
    YamlMap yaskawa = section.Map("yaskawa");
    ReadFields<ProgramSettings>(yaskawa, kProgramYaskawaFields, &s);
    yaskawa.CheckNoUnknownKeys();
  }
  section.CheckNoUnknownKeys();
  return s;
}

GcodeReadOptions GcodeOptionsOf(const ProgramSettings& settings) {
  GcodeReadOptions options;
  options.arc_on = settings.gcode_arc_on.empty() ? std::vector<std::string>{"M" + std::to_string(settings.gcode_arc_on_m)}
                                                 : settings.gcode_arc_on;
  options.arc_off = settings.gcode_arc_off.empty()
                        ? std::vector<std::string>{"M" + std::to_string(settings.gcode_arc_off_m)}
                        : settings.gcode_arc_off;
  options.feed_unit = settings.gcode_feed_unit;
  options.dwell_p_unit = settings.gcode_dwell_p_unit;
  return options;
}

}  // namespace waam::planner
