// The reader of a build's process log (CSV, one row per sample, as welding power sources and cell PLCs export it):
// time, arc power, arc on, head position and thermocouples by column name (docs/REPLAY.md "The log").
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "analysis/replay_settings.h"

namespace waam::analysis {

// A row the log cannot vouch for, reported in replay.json `log_issues` and on stderr.
struct LogIssue {
  std::string kind;   // gap | repeated_time | zero_first_row | empty_probe_cell
  int line = 0;       // the file's line (1-based)
  double time_s = 0;  // from the log's first row, s
  std::string detail;
};

// The rows used, in time order (a repeated time and an all-zero first row are dropped and reported).
struct ReplayLog {
  std::string file;
  std::vector<int> line;                     // file line of each row
  std::vector<double> time_s;                // s from the first row
  std::vector<double> power_w;               // electrical arc power, W (>= 0)
  std::vector<unsigned char> arc_on;         // 1 while the arc burns
  std::vector<Eigen::Vector3d> head_mm;      // the head in the part frame (replay.frame applied), mm
  std::vector<std::vector<double>> probe_c;  // [probe][row], degC; NaN where the cell is empty
  std::vector<double> ambient_c;             // measured air temperature per row (empty without ambient_column)
  std::vector<double> table_c;               // measured table temperature per row (empty without table_column)
  std::vector<unsigned char> gap_before;     // 1: the step from the row before is a gap (the arc is taken as off)
  double gap_s = 0.0;                        // the gap threshold used, s
  std::vector<LogIssue> issues;
};

// Reads the log `text` (the contents of `file`) as `section` describes it. Accepts a UTF-8 byte-order mark, CRLF
// line ends, double-quoted cells, blank lines, and decimal commas when the delimiter is not a comma. Throws
// InputError with one line "file:line[:cell]: ..." for: no line of column names, a missing column (naming the
// replay.columns key), a row too short, a cell that is not a number (or arc state), time going backwards, negative
// power, fewer than two rows, a log whose arc never burns.
ReplayLog ParseReplayLog(std::string_view text, const ReplaySection& section, const std::string& file);

// Reads section.log from disk and parses it (InputError as ParseReplayLog, or naming the unreadable file).
ReplayLog ReadReplayLog(const ReplaySection& section);

}  // namespace waam::analysis
