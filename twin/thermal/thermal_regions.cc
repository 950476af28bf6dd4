// Which cells of a multirate level take the finer level's steps: those near the arc's beads and those whose enthalpy
// changes fast, closed so that no coarse cell is wrapped in finer ones (docs/THERMAL.md, "Time stepping").
#include <cmath>

#include "twin/thermal/thermal_state.h"

namespace waam::twin::internal {

// The region's rules are documented at the declaration (thermal_state.h); why the closing: a coarse cell wrapped in
// finer ones is a Dirichlet value to them for the whole coarse step while they pass it far more energy than its own
// small capacity holds (scattered fast cells made such cells hundreds of K wrong in the multirate test).
std::vector<int> FinerRegion(ThermalState& s, const std::vector<int>& region, int level, int m0, int m1,
                             double radius_mm, double seconds) {
  Eigen::AlignedBox3d box;
  for (int m = m0; m < m1; ++m) {
    if (!s.batch[m].swept_mm.isEmpty()) box.extend(s.batch[m].swept_mm);
  }
  if (!box.isEmpty()) {
    box.min().array() -= radius_mm;
    box.max().array() += radius_mm;
  }
  auto join = [&](int c, std::vector<int>& near) {
    near.push_back(c);
    s.depth[c] = level + 1;
  };
  // Whether cell j of this level, present in the interval, is outside the finer region so far.
  auto outside = [&](int j) { return j != kNoCell && s.depth[j] == level && s.born[j] < m1; };
  std::vector<int> near, fast;
  for (int c : region) {
    const Eigen::Vector3i g = s.CellIndex(s.grid_of[c]);
    if (!box.isEmpty() && box.contains(s.Centre(g.x(), g.y(), g.z()))) {
      join(c, near);
    } else if (std::abs(s.heat_rate[c]) * seconds > s.fast_h[s.material[c]]) {
      join(c, near);
      fast.push_back(c);
    }
  }
  for (int c : fast) {
    for (int f = 0; f < 6; ++f) {
      if (outside(s.neighbour[c][f])) join(s.neighbour[c][f], near);
    }
  }
  CloseFinerRegion(s, near, 0, level, m1);
  return near;
}

void CloseFinerRegion(ThermalState& s, std::vector<int>& near, std::size_t from, int level, int m1) {
  for (std::size_t q = from; q < near.size(); ++q) {
    for (int f = 0; f < 6; ++f) {
      const int j = s.neighbour[near[q]][f];
      if (j == kNoCell || s.depth[j] != level || s.born[j] >= m1) continue;
      int inside = 0, present = 0;
      for (int e = 0; e < 6; ++e) {
        const int k = s.neighbour[j][e];
        if (k == kNoCell || s.born[k] >= m1) continue;
        ++present;
        if (s.depth[k] == level + 1) ++inside;
      }
      if (2 * inside >= present) {
        near.push_back(j);
        s.depth[j] = level + 1;
      }
    }
  }
}

}  // namespace waam::twin::internal
