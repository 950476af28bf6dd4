// A small strict CSV reader: '#' comment lines kept as provenance, one header row, typed column access by name.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace waam {

// A CSV table read whole into memory. Lines starting with '#' (before or between rows) are provenance comments,
// kept without the leading '#'. The first other line is the header; blank lines are skipped. Fields are separated
// by commas, surrounding spaces are trimmed; quoted fields are not supported (the project's tables need none).
class CsvTable {
 public:
  // Reads and parses `path`. Throws InputError naming the file (missing, empty, no header, ragged row).
  static CsvTable Read(const std::filesystem::path& path);
  // Parses `text`; `source` names it in error messages (usually the file path).
  static CsvTable Parse(std::string_view text, std::string source);

  const std::string& source() const { return source_; }
  const std::vector<std::string>& provenance() const { return provenance_; }
  const std::vector<std::string>& header() const { return header_; }
  std::size_t rows() const { return cells_.size(); }
  // The 1-based line number in the file of data row `row` (0-based).
  int line(std::size_t row) const { return lines_.at(row); }

  bool HasColumn(std::string_view name) const;
  // Index of column `name`. Throws InputError "file: no column 'x' (columns: a, b)" if absent.
  std::size_t ColumnIndex(std::string_view name) const;
  // The raw text of one cell.
  const std::string& Cell(std::size_t row, std::size_t column) const { return cells_.at(row).at(column); }

  // Every value of column `name` as a finite number. Throws InputError "file:line: column 'x': 'abc' is not a
  // number" for text, an empty cell, NaN, or an infinity (unless `allow_infinity`: then "inf"/"-inf" are accepted,
  // e.g. a straight path's curvature radius).
  std::vector<double> Numbers(std::string_view name, bool allow_infinity = false) const;
  // Every value of column `name` as text.
  std::vector<std::string> Strings(std::string_view name) const;

 private:
  std::string source_;
  std::vector<std::string> provenance_;
  std::vector<std::string> header_;
  std::vector<std::vector<std::string>> cells_;
  std::vector<int> lines_;
};

// Parses one number the way CsvTable::Numbers does (finite, or +-inf if allowed); false if `text` is not one.
bool ParseCsvNumber(std::string_view text, bool allow_infinity, double* value);

}  // namespace waam
