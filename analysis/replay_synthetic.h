// A process log made by the thermal model itself: the rows of a straight wall built bead by bead, and a CSV writer
// with seeded noise on the thermocouples (the round-trip test and the replay benchmark; docs/REPLAY.md).
#pragma once

#include <string>
#include <vector>

#include "analysis/replay_log.h"

namespace waam::analysis {

// A wall along x, centred on the origin at y = 0: each layer one bead from one end to the other (alternating), the
// head at the bead's top, then a dwell with the arc off; a cooling tail after the last layer.
struct WallBuildSpec {
  int layers = 3;
  double length_mm = 60.0;
  double speed_mm_s = 8.0;     // travel speed while welding, mm/s
  double layer_mm = 2.0;       // layer height, mm
  double dwell_s = 30.0;       // arc off between layers, s
  double tail_s = 60.0;        // arc off after the last layer, s
  double power_w = 2000.0;     // electrical arc power, W
  double row_s = 1.0;          // log interval, s
};

// The rows of such a build (time, power, arc on, head; no probe values), as ReadReplayLog would return them.
ReplayLog WallBuildLog(const WallBuildSpec& spec);

// The log as CSV: time,power_w,arc_on,x,y,z and one column per probe (`columns`), each probe value plus Gaussian
// noise of `noise_c` (seeded, degC); NaN values are written as empty cells.
std::string ReplayLogCsv(const ReplayLog& log, const std::vector<std::string>& columns,
                         const std::vector<std::vector<double>>& probe_c, double noise_c, unsigned seed);

}  // namespace waam::analysis
