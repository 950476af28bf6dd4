// Yaskawa INFORM job (.JBI) writer.
#include "planner/program/yaskawa_jbi.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>

#include "models/core/error.h"
#include "models/core/numbers.h"

namespace waam::planner {
namespace {

// ///RCONF of an IK branch: flip (0 flip, 1 no flip), arm (0 upper, 1 lower), front/back (0 front, 1 back), then
// R, T, S at 180 deg or more (1), two reserved digits. The branch bits: 0 shoulder back, 1 elbow down, 2 wrist
// flipped (as KRL's S).
std::string Rconf(const ProgramPoint& p) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "///RCONF %d,%d,%d,%d,%d,%d,0,0", (p.branch & 4) ? 0 : 1, (p.branch & 2) ? 1 : 0,
                (p.branch & 1) ? 1 : 0, std::abs(p.q[3]) >= kPi ? 1 : 0, std::abs(p.q[5]) >= kPi ? 1 : 0,
                std::abs(p.q[0]) >= kPi ? 1 : 0);
  return buf;
}

}  // namespace

std::string ProgramToYaskawaJbi(const RobotProgram& program, const YaskawaJbiOptions& options) {
  WAAM_THROW_UNLESS(options.station_pulses_per_deg[0] > 0.0 && options.station_pulses_per_deg[1] > 0.0 &&
                        std::isfinite(options.station_pulses_per_deg[0]) &&
                        std::isfinite(options.station_pulses_per_deg[1]),
                    "yaskawa_jbi: the station's pulses per degree (tilt, rotation) must be > 0 to write its EC "
                    "positions (program.yaskawa.station_pulses_per_deg or --station-pulses-per-deg)");
  std::string name;
  for (char c : program.name.substr(0, 32)) name += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  if (name.empty()) name = "WAAM";
  const std::size_t n = program.points.size();
  char buf[512];
  std::string out = "/JOB\n//NAME " + name + "\n//POS\n";
  std::snprintf(buf, sizeof(buf), "///NPOS %zu,0,%zu,0,0,0\n///TOOL %d\n///POSTYPE ROBOT\n///RECTAN\n", n, n,
                options.tool);
  out += buf;
  std::string rconf;
  for (std::size_t i = 0; i < n; ++i) {
    const ProgramPoint& p = program.points[i];
    const std::string r = Rconf(p);
    if (r != rconf) out += r + "\n", rconf = r;
    // The TCP in the robot frame: the table's pose (user frame U, R = Rz(A) Ry(B) Rx(C)) through X_RU.
    Eigen::Isometry3d X_UT = Eigen::Isometry3d::Identity();
    X_UT.translation() = p.tcp_mm;
    X_UT.linear() = (Eigen::AngleAxisd(p.a_deg / kDeg, Eigen::Vector3d::UnitZ()) *
                     Eigen::AngleAxisd(p.b_deg / kDeg, Eigen::Vector3d::UnitY()) *
                     Eigen::AngleAxisd(p.c_deg / kDeg, Eigen::Vector3d::UnitX()))
                        .toRotationMatrix();
    const Eigen::Isometry3d X_RT = options.X_RU * X_UT;
    const Eigen::Vector3d abc = EulerZyx(X_RT.linear()) * kDeg;  // (Rz, Ry, Rx)
    std::snprintf(buf, sizeof(buf), "C%05zu=%.3f,%.3f,%.3f,%.4f,%.4f,%.4f\n", i, ProgramValue(X_RT.translation().x()),
                  ProgramValue(X_RT.translation().y()), ProgramValue(X_RT.translation().z()), ProgramValue(abc[2]),
                  ProgramValue(abc[1]), ProgramValue(abc[0]));
    out += buf;
  }
  out += "///POSTYPE PULSE\n///PULSE\n";
  for (std::size_t i = 0; i < n; ++i) {
    const ProgramPoint& p = program.points[i];
    std::snprintf(buf, sizeof(buf), "EC%05zu=%.0f,%.0f\n", i,
                  ProgramValue(std::round(p.tilt_deg * options.station_pulses_per_deg[0])),
                  ProgramValue(std::round(p.rotation_deg * options.station_pulses_per_deg[1])));
    out += buf;
  }
  out +=
      "//INST\n///DATE 2000/01/01 00:00\n///COMM WAAM-TWIN\n///ATTR SC,RW\n///GROUP1 RB1,ST1\nNOP\n"
      "'waam-twin: C in the robot frame, EC = positioner tilt, rotation (pulses)\n";
  bool arc_on = false;
  for (std::size_t i = 0; i < n; ++i) {
    const ProgramPoint& p = program.points[i];
    if (p.weld && !arc_on) {
      std::snprintf(buf, sizeof(buf), "ARCON ASF#(%d)\n", options.arc_start_file);
      out += buf;
      arc_on = true;
    } else if (!p.weld && arc_on) {
      std::snprintf(buf, sizeof(buf), "ARCOF AEF#(%d)\n", options.arc_end_file);
      out += buf;
      arc_on = false;
    }
    if (i == 0) {
      std::snprintf(buf, sizeof(buf), "MOVJ C%05zu EC%05zu VJ=20.00\n", i, i);
    } else {
      // V= in mm/s with the controller's 0.1 mm/s resolution.
      std::snprintf(buf, sizeof(buf), "MOVL C%05zu EC%05zu V=%.1f%s\n", i, i, std::max(0.1, p.speed_mm_s),
                    p.weld ? "" : " PL=0");
    }
    out += buf;
  }
  if (arc_on) {
    std::snprintf(buf, sizeof(buf), "ARCOF AEF#(%d)\n", options.arc_end_file);
    out += buf;
  }
  out += "END\n";
  return out;
}

}  // namespace waam::planner
