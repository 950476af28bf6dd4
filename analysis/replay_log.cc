// The process-log reader: a tokenizer for the CSV dialects cells export, then one function per kind of cell.
#include "analysis/replay_log.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>

#include "models/core/error.h"
#include "models/core/files.h"

namespace waam::analysis {

namespace {

constexpr double kLogNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kLogDayS = 86400.0;

std::string_view LogTrim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

// The lines of `text` without their line ends ("\n" or "\r\n"), a leading byte-order mark dropped.
std::vector<std::string_view> LogLines(std::string_view text) {
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  std::vector<std::string_view> lines;
  while (!text.empty()) {
    const std::size_t end = text.find('\n');
    std::string_view line = text.substr(0, end);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    lines.push_back(line);
    if (end == std::string_view::npos) break;
    text.remove_prefix(end + 1);
  }
  return lines;
}

// Splits one line into trimmed cells; a cell in double quotes may hold the delimiter ("" is a quote).
std::vector<std::string> LogCells(std::string_view line, char delimiter) {
  std::vector<std::string> cells(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (c == '"') {
      if (quoted && i + 1 < line.size() && line[i + 1] == '"') {
        cells.back() += '"';
        ++i;
      } else {
        quoted = !quoted;
      }
    } else if (c == delimiter && !quoted) {
      cells.emplace_back();
    } else {
      cells.back() += c;
    }
  }
  for (std::string& cell : cells) cell = std::string(LogTrim(cell));
  return cells;
}

char DelimiterOf(LogDelimiter d, std::string_view names) {
  switch (d) {
    case LogDelimiter::kComma: return ',';
    case LogDelimiter::kSemicolon: return ';';
    case LogDelimiter::kTab: return '\t';
    case LogDelimiter::kAuto: break;
  }
  if (names.find(';') != std::string_view::npos) return ';';
  if (names.find('\t') != std::string_view::npos) return '\t';
  return ',';
}

// Reads cells of one data row, naming file:line:cell in every error.
class RowReader {
 public:
  RowReader(const std::string& file, int line, const std::vector<std::string>& cells, char delimiter)
      : file_(file), line_(line), cells_(cells), comma_decimal_(delimiter != ',') {}

  const std::string& Cell(int index, const std::string& column) const {
    WAAM_THROW_UNLESS(index < static_cast<int>(cells_.size()),
                      Where(index) << ": the row has " << cells_.size() << " cells; column '" << column
                                   << "' is cell " << index + 1);
    return cells_[index];
  }

  // A number; an empty cell is NaN when `empty_ok`, else an error.
  double Number(int index, const std::string& column, bool empty_ok = false) const {
    const std::string& cell = Cell(index, column);
    if (cell.empty() && empty_ok) return kLogNaN;
    const double v = ParseNumber(cell);
    WAAM_THROW_UNLESS(std::isfinite(v), Where(index) << ": column '" << column << "': '" << Shown(cell)
                                                     << "' is not a number");
    return v;
  }

  bool ArcState(int index, const std::string& column) const {
    std::string word = Cell(index, column);
    std::transform(word.begin(), word.end(), word.begin(), [](unsigned char c) { return std::tolower(c); });
    if (word == "true" || word == "on" || word == "yes") return true;
    if (word == "false" || word == "off" || word == "no") return false;
    const double v = ParseNumber(word);
    WAAM_THROW_UNLESS(std::isfinite(v), Where(index) << ": column '" << column << "': '" << Shown(word)
                                                     << "' is not an arc state (1/0, true/false, on/off)");
    return v != 0.0;
  }

  // The time of day of "hh:mm:ss[.fff]" (a date before it, separated by a space or 'T', ignored), s.
  double Clock(int index, const std::string& column) const {
    std::string cell = Cell(index, column);
    const std::size_t cut = cell.find_last_of(" T");
    if (cut != std::string::npos) cell = cell.substr(cut + 1);
    std::vector<std::string> parts(1);
    for (char c : cell) {
      if (c == ':') parts.emplace_back(); else parts.back() += c;
    }
    double seconds = kLogNaN;
    if (parts.size() == 2 || parts.size() == 3) {
      const double h = ParseNumber(parts[0]), m = ParseNumber(parts[1]);
      const double s = parts.size() == 3 ? ParseNumber(parts[2]) : 0.0;
      const bool whole = std::floor(h) == h && std::floor(m) == m;
      if (whole && h >= 0 && h < 48 && m >= 0 && m < 60 && s >= 0 && s < 61) seconds = 3600.0 * h + 60.0 * m + s;
    }
    WAAM_THROW_UNLESS(std::isfinite(seconds), Where(index) << ": column '" << column << "': '" << Shown(cell)
                                                           << "' is not a time hh:mm:ss (replay.time_unit)");
    return seconds;
  }

  std::string Where(int index) const {
    std::ostringstream s;
    s << file_ << ":" << line_ << ":" << index + 1;
    return s.str();
  }

 private:
  double ParseNumber(std::string text) const {
    if (comma_decimal_ && text.find(',') != std::string::npos && text.find('.') == std::string::npos) {
      std::replace(text.begin(), text.end(), ',', '.');
    }
    if (text.empty()) return kLogNaN;
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    return end == text.c_str() + text.size() ? v : kLogNaN;
  }
  static std::string Shown(const std::string& cell) { return cell.size() > 40 ? cell.substr(0, 40) + "..." : cell; }

  const std::string& file_;
  int line_;
  const std::vector<std::string>& cells_;
  bool comma_decimal_;
};

// Where each used column sits in a row.
struct ColumnIndex {
  int time = -1, power = -1, voltage = -1, current = -1, arc_on = -1, x = -1, y = -1, z = -1, ambient = -1,
      table = -1;
  std::vector<int> probes;
};

int FindLogColumn(const std::vector<std::string>& names, const std::string& column, const std::string& key,
         const std::string& where) {
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == column) return static_cast<int>(i);
  }
  std::string known;
  for (std::size_t i = 0; i < names.size() && i < 12; ++i) known += (i ? ", " : "") + names[i];
  if (names.size() > 12) known += ", ...";
  WAAM_THROW(where << ": no column '" << column << "' (" << key << "); the log's columns: " << known);
}

ColumnIndex FindColumns(const std::vector<std::string>& names, const ReplaySection& section, const std::string& where) {
  const ReplayColumns& c = section.columns;
  ColumnIndex index;
  index.time = FindLogColumn(names, c.time, "replay.columns.time", where);
  if (!c.power_w.empty()) {
    index.power = FindLogColumn(names, c.power_w, "replay.columns.power_w", where);
  } else {
    index.voltage = FindLogColumn(names, c.voltage_v, "replay.columns.voltage_v", where);
    index.current = FindLogColumn(names, c.current_a, "replay.columns.current_a", where);
  }
  if (!c.arc_on.empty()) index.arc_on = FindLogColumn(names, c.arc_on, "replay.columns.arc_on", where);
  index.x = FindLogColumn(names, c.x, "replay.columns.x", where);
  index.y = FindLogColumn(names, c.y, "replay.columns.y", where);
  index.z = FindLogColumn(names, c.z, "replay.columns.z", where);
  if (!c.ambient.empty()) index.ambient = FindLogColumn(names, c.ambient, "replay.ambient_column", where);
  if (!c.table.empty()) index.table = FindLogColumn(names, c.table, "replay.table_column", where);
  for (const ReplayProbe& p : section.probes) {
    index.probes.push_back(FindLogColumn(names, p.column, "replay.probes." + p.name + ".column", where));
  }
  return index;
}

}  // namespace

namespace {

// One row as read, before the time checks.
struct LogRow {
  int line = 0;
  double clock_s = 0.0;  // the time as written, s
  double power_w = 0.0;
  bool arc_on = false;
  Eigen::Vector3d head_log = Eigen::Vector3d::Zero();
  std::vector<double> probe_c;
  double ambient_c = kLogNaN, table_c = kLogNaN;
  bool all_zero = false;  // every used cell but time is zero
};

LogRow ReadRow(const RowReader& r, const ColumnIndex& ix, const ReplaySection& section, int line) {
  const ReplayColumns& c = section.columns;
  LogRow row;
  row.line = line;
  switch (section.time_unit) {
    case LogTimeUnit::kSeconds: row.clock_s = r.Number(ix.time, c.time); break;
    case LogTimeUnit::kDayFraction: row.clock_s = kLogDayS * r.Number(ix.time, c.time); break;
    case LogTimeUnit::kClock: row.clock_s = r.Clock(ix.time, c.time); break;
  }
  bool zero = true;
  if (ix.power >= 0) {
    row.power_w = r.Number(ix.power, c.power_w);
    WAAM_THROW_UNLESS(row.power_w >= 0.0, r.Where(ix.power) << ": column '" << c.power_w << "': negative power "
                                                             << row.power_w << " W; arc power must be >= 0");
  } else {
    const double volts = r.Number(ix.voltage, c.voltage_v), amps = r.Number(ix.current, c.current_a);
    row.power_w = volts * amps;
    WAAM_THROW_UNLESS(std::isfinite(row.power_w), r.Where(ix.voltage) << ": columns '" << c.voltage_v << "' x '"
                                                                       << c.current_a << "': power " << volts
                                                                       << " V x " << amps << " A is out of range");
    WAAM_THROW_UNLESS(row.power_w >= 0.0, r.Where(ix.voltage) << ": columns '" << c.voltage_v << "' x '"
                                                              << c.current_a << "': negative power " << row.power_w
                                                              << " W (" << volts << " V x " << amps
                                                              << " A); arc power must be >= 0");
    zero = zero && volts == 0.0 && amps == 0.0;
  }
  zero = zero && row.power_w == 0.0;
  row.arc_on = ix.arc_on >= 0 ? r.ArcState(ix.arc_on, c.arc_on) : row.power_w > section.arc_on_min_w;
  zero = zero && !row.arc_on;
  row.head_log = {r.Number(ix.x, c.x), r.Number(ix.y, c.y), r.Number(ix.z, c.z)};
  zero = zero && row.head_log.isZero(0.0);
  for (std::size_t p = 0; p < ix.probes.size(); ++p) {
    row.probe_c.push_back(r.Number(ix.probes[p], section.probes[p].column, true));
    zero = zero && row.probe_c.back() == 0.0;
  }
  if (ix.ambient >= 0) row.ambient_c = r.Number(ix.ambient, c.ambient);
  if (ix.table >= 0) row.table_c = r.Number(ix.table, c.table);
  row.all_zero = zero;
  return row;
}

// The log's frame in the part frame: p_part = offset + Rz(rotation) p_log.
Eigen::Vector3d ToPart(const ReplaySection& section, const Eigen::Vector3d& p_log) {
  const double a = section.frame_rotation_deg * M_PI / 180.0;
  const double c = std::cos(a), s = std::sin(a);
  const auto& o = section.frame_offset_mm;
  return {o[0] + c * p_log.x() - s * p_log.y(), o[1] + s * p_log.x() + c * p_log.y(), o[2] + p_log.z()};
}

// Marks the steps longer than the gap threshold (max_gap_s, or 3 x the median step) and reports them.
void MarkGaps(const ReplaySection& section, ReplayLog* log) {
  const std::size_t n = log->time_s.size();
  std::vector<double> steps;
  for (std::size_t i = 1; i < n; ++i) steps.push_back(log->time_s[i] - log->time_s[i - 1]);
  std::nth_element(steps.begin(), steps.begin() + steps.size() / 2, steps.end());
  log->gap_s = section.max_gap_s > 0.0 ? section.max_gap_s : 3.0 * steps[steps.size() / 2];
  log->gap_before.assign(n, 0);
  for (std::size_t i = 1; i < n; ++i) {
    const double step = log->time_s[i] - log->time_s[i - 1];
    if (step <= log->gap_s) continue;
    log->gap_before[i] = 1;
    std::ostringstream s;
    s << "no row for " << step << " s (from " << log->time_s[i - 1] << " s; gap threshold " << log->gap_s
      << " s): simulated with the arc off";
    log->issues.push_back({"gap", log->line[i], log->time_s[i - 1], s.str()});
  }
}

}  // namespace

ReplayLog ParseReplayLog(std::string_view text, const ReplaySection& section, const std::string& file) {
  const std::vector<std::string_view> lines = LogLines(text);
  std::size_t at = static_cast<std::size_t>(std::max(0, section.header_rows));
  while (at < lines.size() && LogTrim(lines[at]).empty()) ++at;
  WAAM_THROW_UNLESS(at < lines.size(), file << ": no line of column names after " << section.header_rows
                                            << " header rows (replay.header_rows)");
  const char delimiter = DelimiterOf(section.delimiter, lines[at]);
  const ColumnIndex index =
      FindColumns(LogCells(lines[at], delimiter), section, file + ":" + std::to_string(at + 1));
  ReplayLog log;
  log.file = file;
  log.probe_c.assign(section.probes.size(), {});
  double first_s = kLogNaN, previous_s = kLogNaN, previous_t = kLogNaN, day_s = 0.0;
  int previous_line = 0;
  for (std::size_t l = at + 1; l < lines.size(); ++l) {
    if (LogTrim(lines[l]).empty()) continue;
    const int line = static_cast<int>(l + 1);
    const std::vector<std::string> cells = LogCells(lines[l], delimiter);
    LogRow row = ReadRow(RowReader(file, line, cells, delimiter), index, section, line);
    if (std::isnan(first_s) && row.all_zero) {
      log.issues.push_back({"zero_first_row", line, 0.0, "every used cell but the time is 0: row left out"});
      continue;
    }
    // A time of day (a clock time, or a day fraction below one day: not a date serial) that drops by more than 12 h
    // crossed midnight.
    const bool time_of_day = section.time_unit == LogTimeUnit::kClock ||
                             (section.time_unit == LogTimeUnit::kDayFraction && row.clock_s < kLogDayS);
    if (time_of_day && !std::isnan(previous_s) && row.clock_s + day_s < previous_s - 0.5 * kLogDayS) day_s += kLogDayS;
    const double clock = row.clock_s + day_s;
    if (std::isnan(first_s)) first_s = clock;
    // Times compared as seconds from the first row (what the replay uses), so that two rows whose times differ by
    // less than the rounding of a huge origin count as one time.
    const double t = clock - first_s;
    WAAM_THROW_UNLESS(std::isfinite(t) && std::abs(t) <= 1e9, file << ":" << line << ": time " << t
                                                                   << " s from the first row: must be within 1e9 s");
    if (!std::isnan(previous_t)) {
      WAAM_THROW_UNLESS(t >= previous_t, file << ":" << line << ": time " << t << " s is before the previous "
                                              << "row's " << previous_t << " s (line " << previous_line
                                              << "): time must not go backwards");
      if (t == previous_t) {
        log.issues.push_back({"repeated_time", line, t, "the same time as line " + std::to_string(previous_line) +
                                                            ": row left out"});
        continue;
      }
    }
    previous_s = clock;
    previous_t = t;
    previous_line = line;
    log.line.push_back(line);
    log.time_s.push_back(t);
    log.power_w.push_back(row.power_w);
    log.arc_on.push_back(row.arc_on ? 1 : 0);
    log.head_mm.push_back(ToPart(section, row.head_log));
    for (std::size_t p = 0; p < row.probe_c.size(); ++p) {
      log.probe_c[p].push_back(row.probe_c[p]);
      if (std::isnan(row.probe_c[p])) {
        log.issues.push_back({"empty_probe_cell", line, t, "probe " + section.probes[p].name + ": empty cell"});
      }
    }
    if (index.ambient >= 0) log.ambient_c.push_back(row.ambient_c);
    if (index.table >= 0) log.table_c.push_back(row.table_c);
  }
  WAAM_THROW_UNLESS(log.time_s.size() >= 2, file << ": " << log.time_s.size() << " data rows: a replay needs at least "
                                                 "two rows");
  WAAM_THROW_UNLESS(std::any_of(log.arc_on.begin(), log.arc_on.end(), [](unsigned char on) { return on != 0; }),
                    file << ": the arc never burns in the log (column '"
                         << (section.columns.arc_on.empty() ? section.columns.power_w : section.columns.arc_on)
                         << "'): nothing to replay");
  MarkGaps(section, &log);
  return log;
}

ReplayLog ReadReplayLog(const ReplaySection& section) {
  return ParseReplayLog(ReadFile(section.log), section, section.log.string());
}

}  // namespace waam::analysis
