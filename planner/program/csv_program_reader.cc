// Reader of the CSV program table that `waam check` writes (ProgramToCsv): one linear move per row.
#include "models/core/csv.h"
#include "models/core/error.h"
#include "models/core/numbers.h"
#include "planner/program/program_reader.h"

namespace waam::planner {

ParsedProgram ReadProgramCsv(std::string_view text, const std::string& file) {
  WAAM_THROW_UNLESS(text.size() <= kMaxProgramBytes, file << ": the program has " << text.size()
                                                          << " bytes, more than the limit of " << kMaxProgramBytes);
  const CsvTable table = CsvTable::Parse(text, file);
  WAAM_THROW_UNLESS(table.rows() <= kMaxProgramMotions,
                    file << ": " << table.rows() << " rows, more than the limit of " << kMaxProgramMotions);
  const char* const kColumns[] = {"x_mm", "y_mm", "z_mm", "a_deg", "b_deg", "c_deg",
                                  "tilt_deg", "rotation_deg", "speed_mm_min", "weld"};
  std::vector<std::vector<double>> columns;
  for (const char* name : kColumns) {
    // The positioner columns are those of the cell that wrote it: a turntable's table has no tilt_deg, a cell
    // without a positioner neither; a missing one reads as 0.
    const bool positioner = std::string_view(name) == "tilt_deg" || std::string_view(name) == "rotation_deg";
    columns.push_back(positioner && !table.HasColumn(name) ? std::vector<double>(table.rows(), 0.0)
                                                           : table.Numbers(name));
  }
  ParsedProgram program;
  program.format = ProgramFormat::kCsv;
  program.name = std::filesystem::path(file).stem().string();
  for (std::size_t r = 0; r < table.rows(); ++r) {
    auto at = [&](int c) { return columns[static_cast<std::size_t>(c)][r]; };
    ProgramMotion m;
    m.kind = MotionKind::kLinear;
    m.line = table.line(r);
    m.has_pose = true;
    m.frame = TargetFrame::kUser;
    m.X_UT.translation() = Eigen::Vector3d(at(0), at(1), at(2));
    m.X_UT.linear() = internal::RotationZyx(at(3) * kPi / 180.0, at(4) * kPi / 180.0, at(5) * kPi / 180.0);
    m.has_positioner = table.HasColumn("tilt_deg") || table.HasColumn("rotation_deg");
    m.tilt_rad = at(6) * kPi / 180.0;
    m.rotation_rad = at(7) * kPi / 180.0;
    WAAM_THROW_UNLESS(at(8) >= 0.0, file << ":" << m.line << ": speed_mm_min " << at(8) << " must be >= 0");
    m.speed_mm_s = at(8) / 60.0;
    WAAM_THROW_UNLESS(at(9) == 0.0 || at(9) == 1.0, file << ":" << m.line << ": weld must be 0 or 1, got " << at(9));
    m.weld = at(9) == 1.0;
    program.motions.push_back(m);
  }
  return program;
}

}  // namespace waam::planner
