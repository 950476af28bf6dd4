// The scenario's program: section.
#include "planner/program/program_section.h"

#include "models/core/error.h"
#include "planner/scenario/scenario_fields.h"

namespace waam::planner {
namespace {

// frames: {uframe: {6: [x, y, z, w, p, r]}, utool: {5: [...] or torch}} (mm, deg).
ProgramFrames ParseProgramFrames(YamlMap& frames) {
  ProgramFrames out;
  for (const char* kind : {"uframe", "utool"}) {
    if (!frames.Has(kind)) continue;
    YamlMap table = frames.Map(kind);
    for (const auto& entry : table.node()) {
      WAAM_THROW_UNLESS(entry.first.IsScalar(), table.Where("") << ": keys must be frame numbers");
      const std::string key = entry.first.as<std::string>();
      int n = -1;
      try {
        std::size_t used = 0;
        n = std::stoi(key, &used);
        if (used != key.size()) n = -1;
      } catch (const std::exception&) {
        n = -1;
      }
      WAAM_THROW_UNLESS(n >= 1 && n <= 999, table.Where(key) << ": must be a frame number in [1, 999]");
      const bool torch = entry.second.IsScalar() && entry.second.as<std::string>() == "torch";
      WAAM_THROW_UNLESS(!torch || std::string(kind) == "utool",
                        table.Where(key) << " = torch: only a tool (utool) can be the cell's torch");
      if (torch) {
        (void)table.String(key);
        out.utool[n] = std::nullopt;
        continue;
      }
      const std::vector<double> v = table.Numbers(key, 6, -1e6, 1e6);
      const std::array<double, 6> f = {v[0], v[1], v[2], v[3], v[4], v[5]};
      if (std::string(kind) == "uframe") out.uframe[n] = f;
      else out.utool[n] = f;
    }
    table.CheckNoUnknownKeys();
  }
  frames.CheckNoUnknownKeys();
  return out;
}

}  // namespace

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
  if (ReadFieldMap<ProgramSettings>(section, "frame", kProgramFrameFields, &s)) {
    s.frames.user_frame = s.user_frame_mm.has_value();
  }
  ReadFields<ProgramSettings>(section, kProgramFields, &s);
  if (section.Has("gcode")) {
    YamlMap gcode = section.Map("gcode");
    ReadFields<ProgramSettings>(gcode, kProgramGcodeFields, &s);
    WAAM_THROW_UNLESS(s.gcode_arc_on_m != s.gcode_arc_off_m,
                      gcode.Where("arc_off_m") << " = " << s.gcode_arc_off_m << ": must differ from arc_on_m");
    s.gcode_feed_unit = gcode.Enum("feed_unit", GcodeFeedUnit::kMmPerMin);
    s.gcode_dwell_p_unit = gcode.Enum("dwell_p_unit", GcodeDwellUnit::kMs);
    for (const char* key : {"arc_on", "arc_off"}) {
      std::vector<std::string>& list = std::string(key) == "arc_on" ? s.gcode_arc_on : s.gcode_arc_off;
      list = gcode.Strings(key, {});
      WAAM_THROW_UNLESS(!gcode.Has(key) || !list.empty(), gcode.Where(key) << ": must list at least one signal");
      for (const std::string& signal : list) CheckGcodeSignal(signal, gcode.Where(key));
    }
    gcode.CheckNoUnknownKeys();
  }
  if (section.Has("frames")) {
    YamlMap frames = section.Map("frames");
    const bool user_frame = s.frames.user_frame;
    s.frames = ParseProgramFrames(frames);
    s.frames.user_frame = user_frame;
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
