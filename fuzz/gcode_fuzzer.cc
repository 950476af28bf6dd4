// libFuzzer target: the gcode program reader, then the conversion of what it read into a plan on the default cell
// kinematics. Any input may be refused with waam::InputError; anything else is a bug.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "models/core/error.h"
#include "planner/program/program_plan.h"
#include "planner/program/program_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  static const waam::planner::CellKinematics cell = [] {
    waam::planner::CellKinematics c;
    c.arm = waam::planner::OpwArm::ArcMate100iC12();
    c.X_WB.translation() = Eigen::Vector3d(1050.0, 0.0, 0.0);
    return c;
  }();
  try {
    const waam::planner::ParsedProgram program = waam::planner::ReadGcode(text, "fuzz.nc");
    (void)program.MotionsByKind();
    waam::planner::ImportSettings settings;
    settings.arc_step_mm = 5.0;
    (void)waam::planner::ProgramToPlan(program, cell, settings);
  } catch (const waam::InputError&) {
  }
  return 0;
}
