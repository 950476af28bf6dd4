// Shared pieces of the program readers: warnings, lines, numbers, limits.
#include "planner/program/program_motion.h"

#include <cctype>
#include <charconv>
#include <cmath>

#include "models/core/error.h"
#include "models/core/numbers.h"

namespace waam::planner {

std::map<std::string, std::size_t> ParsedProgram::MotionsByKind() const {
  std::map<std::string, std::size_t> counts;
  for (const auto& entry : EnumNames(MotionKind{})) counts[std::string(entry.name)] = 0;
  for (const ProgramMotion& m : motions) ++counts[std::string(NameOf(m.kind))];
  return counts;
}

namespace internal {

void WarningList::Add(const std::string& what, int line) {
  auto [it, inserted] = index_.emplace(what, list_.size());
  if (inserted) list_.push_back({what, 0, line});
  ++list_[it->second].count;
}

std::vector<std::string_view> SplitProgramLines(std::string_view text, const std::string& file) {
  WAAM_THROW_UNLESS(text.size() <= kMaxProgramBytes, file << ": the program has " << text.size()
                                                          << " bytes, more than the limit of " << kMaxProgramBytes);
  std::vector<std::string_view> lines;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(start, end - start);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    lines.push_back(line);
    start = end + 1;
  }
  return lines;
}

double ParseProgramNumber(std::string_view text, const std::string& file, int line, std::string_view what) {
  std::string_view t = TrimBlank(text);
  if (!t.empty() && t.front() == '+') t.remove_prefix(1);
  double value = 0.0;
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
  WAAM_THROW_UNLESS(!t.empty() && ec == std::errc() && end == t.data() + t.size() && std::isfinite(value),
                    file << ":" << line << ": " << what << " '" << std::string(TrimBlank(text).substr(0, 40))
                         << "' is not a finite number");
  return value;
}

int ParseProgramInteger(std::string_view text, const std::string& file, int line, std::string_view what, int lo,
                        int hi) {
  const double v = ParseProgramNumber(text, file, line, what);
  WAAM_THROW_UNLESS(v >= lo && v <= hi && v == std::floor(v), file << ":" << line << ": " << what << " '"
                                                                    << std::string(TrimBlank(text).substr(0, 40))
                                                                    << "' must be a whole number in [" << lo << ", "
                                                                    << hi << "]");
  return static_cast<int>(v);
}

std::string_view TrimBlank(std::string_view text) {
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front()))) text.remove_prefix(1);
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.remove_suffix(1);
  return text;
}

std::string Upper(std::string_view text) {
  std::string out(text);
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

void CheckMotionCount(std::size_t motions, const std::string& file, int line) {
  WAAM_THROW_UNLESS(motions < kMaxProgramMotions,
                    file << ":" << line << ": more than " << kMaxProgramMotions << " motions, the limit per program");
}

Eigen::Matrix3d RotationZyx(double a, double b, double c) {
  return (Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(b, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(c, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

Eigen::Isometry3d PoseXyzAbc(double x, double y, double z, double a_deg, double b_deg, double c_deg) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(x, y, z);
  X.linear() = RotationZyx(a_deg * kPi / 180.0, b_deg * kPi / 180.0, c_deg * kPi / 180.0);
  return X;
}

void AddDwell(std::vector<ProgramMotion>* motions, double seconds, int line, WarningList* warnings) {
  if (motions->empty()) {
    warnings->Add("wait before the first motion: not in the timeline", line);
    return;
  }
  motions->back().dwell_s += seconds;
}

}  // namespace internal
}  // namespace waam::planner
