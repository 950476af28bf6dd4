// A wall build's process log from the thermal model, for round trips and benchmarks.
#include "analysis/replay_synthetic.h"

#include <cmath>
#include <cstdio>
#include <random>

#include "models/core/error.h"

namespace waam::analysis {

ReplayLog WallBuildLog(const WallBuildSpec& spec) {
  WAAM_DEMAND(spec.layers >= 1 && spec.length_mm > 0.0 && spec.speed_mm_s > 0.0 && spec.row_s > 0.0);
  ReplayLog log;
  log.file = "wall_build.csv";
  const double bead_s = spec.length_mm / spec.speed_mm_s;
  const double layer_s = bead_s + spec.dwell_s;
  const double total_s = spec.layers * layer_s - spec.dwell_s + spec.tail_s;
  const long long rows = static_cast<long long>(std::floor(total_s / spec.row_s)) + 1;
  for (long long r = 0; r < rows; ++r) {
    const double t = static_cast<double>(r) * spec.row_s;
    const int layer = std::min(spec.layers - 1, static_cast<int>(std::floor(t / layer_s)));
    const double in_layer = t - layer * layer_s;
    const bool on = in_layer < bead_s - 1e-9 && t < spec.layers * layer_s;
    // Along the bead while welding, at its end while dwelling; odd layers run back.
    const double s = std::min(in_layer, bead_s) * spec.speed_mm_s;
    const double x = (layer % 2 == 0 ? -0.5 * spec.length_mm + s : 0.5 * spec.length_mm - s);
    log.line.push_back(static_cast<int>(r + 2));
    log.time_s.push_back(t);
    log.power_w.push_back(on ? spec.power_w : 0.0);
    log.arc_on.push_back(on ? 1 : 0);
    log.head_mm.emplace_back(x, 0.0, (layer + 1) * spec.layer_mm);
    log.gap_before.push_back(0);
  }
  log.gap_s = 3.0 * spec.row_s;
  return log;
}

std::string ReplayLogCsv(const ReplayLog& log, const std::vector<std::string>& columns,
                         const std::vector<std::vector<double>>& probe_c, double noise_c, unsigned seed) {
  WAAM_DEMAND(columns.size() == probe_c.size());
  std::mt19937 random(seed);
  std::normal_distribution<double> noise(0.0, noise_c);
  std::string text = "time,power_w,arc_on,x,y,z";
  for (const std::string& c : columns) text += "," + c;
  text += "\n";
  char cell[64];
  for (std::size_t i = 0; i < log.time_s.size(); ++i) {
    std::snprintf(cell, sizeof(cell), "%.3f,%.1f,%d,%.3f,%.3f,%.3f", log.time_s[i], log.power_w[i], log.arc_on[i],
                  log.head_mm[i].x(), log.head_mm[i].y(), log.head_mm[i].z());
    text += cell;
    for (const std::vector<double>& probe : probe_c) {
      const double v = probe[i];
      const double e = noise_c > 0.0 ? noise(random) : 0.0;
      if (std::isfinite(v)) {
        std::snprintf(cell, sizeof(cell), ",%.2f", v + e);
        text += cell;
      } else {
        text += ",";
      }
    }
    text += "\n";
  }
  return text;
}

}  // namespace waam::analysis
