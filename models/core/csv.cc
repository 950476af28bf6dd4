// Strict CSV parsing with file:line:column error messages.
#include "models/core/csv.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <system_error>

#include "models/core/error.h"
#include "models/core/files.h"

namespace waam {
namespace {

std::string_view Trim(std::string_view s) {
  const auto is_space = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; };
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

std::vector<std::string> SplitFields(std::string_view line) {
  std::vector<std::string> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    const std::string_view field = line.substr(start, comma == std::string_view::npos ? line.npos : comma - start);
    fields.emplace_back(Trim(field));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return fields;
}

}  // namespace

bool ParseCsvNumber(std::string_view text, bool allow_infinity, double* value) {
  text = Trim(text);
  if (text.empty()) return false;
  if (allow_infinity) {
    std::string lower;
    for (char c : text) lower.push_back(static_cast<char>(std::tolower(static_cast<unsigned char>(c))));
    if (lower == "inf" || lower == "+inf" || lower == "infinity") {
      *value = INFINITY;
      return true;
    }
    if (lower == "-inf" || lower == "-infinity") {
      *value = -INFINITY;
      return true;
    }
  }
  if (text.front() == '+') text.remove_prefix(1);
  double parsed = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), parsed);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(parsed)) return false;
  *value = parsed;
  return true;
}

CsvTable CsvTable::Read(const std::filesystem::path& path) { return Parse(ReadFile(path), path.string()); }

CsvTable CsvTable::Parse(std::string_view text, std::string source) {
  CsvTable table;
  table.source_ = std::move(source);
  int line_number = 0;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const std::size_t eol = text.find('\n', pos);
    const std::string_view raw = text.substr(pos, eol == std::string_view::npos ? text.npos : eol - pos);
    pos = eol == std::string_view::npos ? text.size() + 1 : eol + 1;
    ++line_number;
    const std::string_view line = Trim(raw);
    if (line.empty()) continue;
    if (line.front() == '#') {
      table.provenance_.emplace_back(Trim(line.substr(1)));
      continue;
    }
    std::vector<std::string> fields = SplitFields(line);
    if (table.header_.empty()) {
      for (std::size_t i = 0; i < fields.size(); ++i) {
        WAAM_THROW_UNLESS(!fields[i].empty(),
                          table.source_ << ":" << line_number << ": header column " << i + 1 << " is empty");
        for (std::size_t j = 0; j < i; ++j) {
          WAAM_THROW_UNLESS(fields[j] != fields[i], table.source_ << ":" << line_number << ": header column '"
                                                                  << fields[i] << "' appears twice");
        }
      }
      table.header_ = std::move(fields);
      continue;
    }
    WAAM_THROW_UNLESS(fields.size() == table.header_.size(),
                      table.source_ << ":" << line_number << ": " << fields.size() << " fields, but the header has "
                                    << table.header_.size());
    table.cells_.push_back(std::move(fields));
    table.lines_.push_back(line_number);
  }
  WAAM_THROW_UNLESS(!table.header_.empty(), table.source_ << ": no header row (the file is empty or only comments)");
  return table;
}

bool CsvTable::HasColumn(std::string_view name) const {
  for (const std::string& h : header_) {
    if (h == name) return true;
  }
  return false;
}

std::size_t CsvTable::ColumnIndex(std::string_view name) const {
  for (std::size_t i = 0; i < header_.size(); ++i) {
    if (header_[i] == name) return i;
  }
  std::string columns;
  for (const std::string& h : header_) columns += (columns.empty() ? "" : ", ") + h;
  WAAM_THROW(source_ << ": no column '" << name << "' (columns: " << columns << ")");
}

std::vector<double> CsvTable::Numbers(std::string_view name, bool allow_infinity) const {
  const std::size_t column = ColumnIndex(name);
  std::vector<double> values(rows());
  for (std::size_t row = 0; row < rows(); ++row) {
    const std::string& cell = cells_[row][column];
    WAAM_THROW_UNLESS(ParseCsvNumber(cell, allow_infinity, &values[row]),
                      source_ << ":" << lines_[row] << ": column '" << name << "': '" << cell
                              << "' is not a number" << (cell.empty() ? " (empty cell)" : ""));
  }
  return values;
}

std::vector<std::string> CsvTable::Strings(std::string_view name) const {
  const std::size_t column = ColumnIndex(name);
  std::vector<std::string> values;
  values.reserve(rows());
  for (const auto& row : cells_) values.push_back(row[column]);
  return values;
}

}  // namespace waam
