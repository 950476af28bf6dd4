// The scenario's optional `replay:` section: a process log (CSV) of a real build, its columns and frame, which
// `waam thermal replay` and `waam fit thermal` drive the thermal model with (docs/REPLAY.md).
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "models/core/enum_names.h"
#include "models/core/field_table.h"

namespace waam::analysis {

// How the log's time column is written.
enum class LogTimeUnit {
  kSeconds,      // seconds (any origin)
  kDayFraction,  // a spreadsheet time: days (a time of day as a fraction of a day, or a date serial)
  kClock,        // hh:mm:ss[.fff] time of day (a date before it, separated by a space or 'T', is ignored)
};
constexpr std::array<EnumName<LogTimeUnit>, 3> EnumNames(LogTimeUnit) {
  return {{{LogTimeUnit::kSeconds, "s"}, {LogTimeUnit::kDayFraction, "day_fraction"}, {LogTimeUnit::kClock, "hh:mm:ss"}}};
}

// The cell separator of the log: detected from the line of column names, or named.
enum class LogDelimiter { kAuto, kComma, kSemicolon, kTab };
constexpr std::array<EnumName<LogDelimiter>, 4> EnumNames(LogDelimiter) {
  return {{{LogDelimiter::kAuto, "auto"}, {LogDelimiter::kComma, "comma"}, {LogDelimiter::kSemicolon, "semicolon"},
           {LogDelimiter::kTab, "tab"}}};
}

// A thermocouple of the log: its column and where it sits in the part frame.
struct ReplayProbe {
  std::string name;
  std::string column;
  Eigen::Vector3d at_mm = Eigen::Vector3d::Zero();  // part frame, mm
  std::string where;                                // "file:line: replay.probes.NAME.at_mm"
};

// The log's columns by name (replay.columns); an empty name = not in the log.
struct ReplayColumns {
  std::string time = "time";
  std::string power_w;      // arc power, W; or voltage_v and current_a
  std::string voltage_v;
  std::string current_a;
  std::string arc_on = "arc_on";
  std::string x = "x";
  std::string y = "y";
  std::string z = "z";
  std::string ambient;      // replay.ambient_column: measured air temperature, degC (optional)
  std::string table;        // replay.table_column: measured table temperature, degC (optional)
};

struct ReplaySection {
  bool given = false;
  std::string where;                   // "file:line: replay"
  std::filesystem::path log;           // replay.log, resolved against the scenario's folder
  std::string log_where;               // "file:line: replay.log"
  int header_rows = 0;                 // metadata lines before the line of column names
  LogTimeUnit time_unit = LogTimeUnit::kSeconds;
  LogDelimiter delimiter = LogDelimiter::kAuto;
  double max_gap_s = 0.0;              // a step between rows longer than this is a gap; 0 = 3 x the median step, s
  ReplayColumns columns;
  std::array<double, 3> frame_offset_mm = {0.0, 0.0, 0.0};  // replay.frame.offset_mm: the log's origin, part frame, mm
  double frame_rotation_deg = 0.0;     // replay.frame.rotation_deg: the log's axes turned about z into the part's
  double bead_width_mm = 6.0;          // replay.bead.width_mm: bead laid while the arc is on, mm
  double bead_height_mm = 2.0;         // replay.bead.height_mm, mm
  double arc_on_min_w = 0.0;           // with arc_on absent from columns: the arc burns while power > this, W
  std::vector<ReplayProbe> probes;     // replay.probes, in file order
};

// A thermocouple read from replay.probes.NAME: column and at_mm are required, and its `where` names at_mm. Throws
// InputError "file:line: replay.probes.NAME: missing required key 'column'".
void FinishReplayProbe(YamlMap& element, ReplayProbe* probe);

// The keys of one thermocouple, replay.probes.NAME (NamesField).
inline constexpr std::array kReplayProbeFields = {
    OptField<&ReplayProbe::column>("column", "the log's column of this thermocouple, degC (required)"),
    NumField<&ReplayProbe::at_mm>("at_mm", "mm", -1e5, 1e5, "[x, y, z] in the part frame (required)"),
};
// The log's optional temperature columns, named at replay's own level (replay.ambient_column, replay.table_column).
inline constexpr std::array kReplayExtraColumnFields = {
    OptField<&ReplayColumns::ambient>("ambient_column", "measured air temperature, degC (optional)"),
    OptField<&ReplayColumns::table>("table_column", "measured table temperature, degC (optional)"),
};

// The keys of `replay:` (models/core/field_table.h); columns, frame and bead are read by analysis/replay_section.cc.
inline constexpr std::array kReplayFields = {
    FileField<&ReplaySection::log>("log", "process log", "the process log, a CSV file (relative to the scenario)"),
    NumField<&ReplaySection::header_rows>("header_rows", "", 0, 1000, "metadata lines before the column names"),
    OptField<&ReplaySection::time_unit>("time_unit", "how the time column is written"),
    OptField<&ReplaySection::delimiter>("delimiter", "cell separator; auto: from the line of column names"),
    NumField<&ReplaySection::max_gap_s>("max_gap_s", "s", 0.0, 1e6, "a longer step is a gap; 0: 3 x the median"),
    NumField<&ReplaySection::arc_on_min_w>("arc_on_min_w", "W", 0.0, 1e6,
                                           "without an arc_on column: the arc burns while power > this"),
    CustomField<ReplaySection>("columns", FieldType::kMap, "column names of the log (replay.columns)"),
    CustomField<ReplaySection>("frame", FieldType::kMap, "the log's frame in the part frame (replay.frame)"),
    CustomField<ReplaySection>("bead", FieldType::kMap, "the bead laid while the arc is on (replay.bead)"),
    NamesField<&ReplaySection::probes, kReplayProbeFields, -1, &FinishReplayProbe>(
        "probes", "probe", "NAME: {column, at_mm: [x, y, z] part frame} (replay.probes.<NAME>; required)"),
    MemberField<&ReplaySection::columns, kReplayExtraColumnFields>("ambient_column"),
    MemberField<&ReplaySection::columns, kReplayExtraColumnFields>("table_column"),
};
inline constexpr std::array kReplayColumnFields = {
    OptField<&ReplayColumns::time>("time", "time of each row (replay.time_unit)"),
    OptField<&ReplayColumns::power_w>("power_w", "arc power, W; or voltage_v and current_a"),
    OptField<&ReplayColumns::voltage_v>("voltage_v", "arc voltage, V"),
    OptField<&ReplayColumns::current_a>("current_a", "arc current, A"),
    OptField<&ReplayColumns::arc_on>("arc_on", "arc on (1, true, on) or off (0, false, off); empty: power"),
    OptField<&ReplayColumns::x>("x", "head position x in the log's frame, mm"),
    OptField<&ReplayColumns::y>("y", "head position y, mm"),
    OptField<&ReplayColumns::z>("z", "head position z (the bead's top), mm"),
};
inline constexpr std::array kReplayFrameFields = {
    NumField<&ReplaySection::frame_offset_mm>("offset_mm", "mm", -1e5, 1e5, "the log's origin in the part frame"),
    NumField<&ReplaySection::frame_rotation_deg>("rotation_deg", "deg", -360.0, 360.0,
                                                 "the log's axes turned about z into the part's"),
};
inline constexpr std::array kReplayBeadFields = {
    NumField<&ReplaySection::bead_width_mm>("width_mm", "mm", 0.1, 100.0, "bead width"),
    NumField<&ReplaySection::bead_height_mm>("height_mm", "mm", 0.1, 100.0, "bead height below the head"),
};

}  // namespace waam::analysis

namespace waam::analysis::internal {
// Reads the optional `replay:` mapping of the scenario's top level into `out`; the log path is resolved against
// top.base_dir() and must exist. Throws InputError naming file:line and key for unknown keys, out-of-range values,
// a missing log, no power column (or both forms), a column named twice, and duplicate probe names.
void ParseReplaySection(YamlMap& top, ReplaySection* out);
}  // namespace waam::analysis::internal
