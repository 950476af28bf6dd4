// Which cells of a multirate level take the finer level's steps: those near the arc's beads and those whose estimated
// backward-Euler error over the level's step is too large, closed so that no coarse cell is wrapped in finer ones
// (docs/THERMAL.md, "Time stepping").
#include <algorithm>
#include <cmath>

#include "twin/thermal/thermal_state.h"

namespace waam::twin::internal {
namespace {

// Whether cell j, present before micro step m1, is left to `level` so far (outside the finer region).
bool Outside(const ThermalState& s, int j, int level, int m1) {
  return j != kNoCell && s.depth[j] == level && s.born[j] < m1;
}

void Join(ThermalState& s, int c, int level, std::vector<int>& near) {
  near.push_back(c);
  s.depth[c] = level + 1;
}

// Joins the `cells` still left to the level, then one cell of margin around them, then closes the region.
void JoinWithMargin(ThermalState& s, int level, int m1, const std::vector<int>& cells, std::vector<int>& near) {
  const std::size_t first = near.size();
  for (int c : cells) {
    if (s.depth[c] == level) Join(s, c, level, near);
  }
  const std::size_t joined = near.size();
  for (std::size_t q = first; q < joined; ++q) {
    for (int f = 0; f < 6; ++f) {
      const int j = s.neighbour[near[q]][f];
      if (Outside(s, j, level, m1)) Join(s, j, level, near);
    }
  }
  CloseFinerRegion(s, near, first, level, m1);
}

}  // namespace

// The closing (declared in thermal_state.h). Why: a coarse cell wrapped in finer ones is a Dirichlet value to them
// for the whole coarse step while they pass it far more energy than its own small capacity holds (scattered finer
// cells made such cells hundreds of K wrong in the multirate test).
void CloseFinerRegion(ThermalState& s, std::vector<int>& near, std::size_t from, int level, int m1) {
  for (std::size_t q = from; q < near.size(); ++q) {
    for (int f = 0; f < 6; ++f) {
      const int j = s.neighbour[near[q]][f];
      if (!Outside(s, j, level, m1)) continue;
      int inside = 0, present = 0;
      for (int e = 0; e < 6; ++e) {
        const int k = s.neighbour[j][e];
        if (k == kNoCell || s.born[k] >= m1) continue;
        ++present;
        if (s.depth[k] == level + 1) ++inside;
      }
      if (2 * inside >= present) Join(s, j, level, near);
    }
  }
}

std::vector<int> FinerRegion(ThermalState& s, const std::vector<int>& region, int level, int m0, int m1,
                             double radius_mm) {
  Eigen::AlignedBox3d box;
  for (int m = m0; m < m1; ++m) {
    if (!s.batch[m].swept_mm.isEmpty()) box.extend(s.batch[m].swept_mm);
  }
  std::vector<int> near;
  if (box.isEmpty()) return near;
  box.min().array() -= radius_mm;
  box.max().array() += radius_mm;
  for (int c : region) {
    const std::array<int, 3>& g = s.cell_ijk[static_cast<std::size_t>(c)];
    if (box.contains(s.Centre(g[0], g[1], g[2]))) Join(s, c, level, near);
  }
  CloseFinerRegion(s, near, 0, level, m1);
  return near;
}

// The estimate: a cell's mean rates over two successive steps of dt_prev and dt, r_old = heat_rate and
// r_new = (H_pred - H_old) / dt, differ by about d2H/dt2 (dt_prev + dt) / 2, so backward Euler's local error
// dt^2/2 |d2H/dt2| is about dt^2 |r_new - r_old| / (dt + dt_prev) = dt / (dt + dt_prev) |H_pred - (H_old + dt r_old)|:
// the predictor against the cell's last rate carried over the step. It needs no extra solve and reads only the cell's
// own values, so the region does not depend on the order or the thread count.
void AddInaccurateCells(ThermalState& s, int level, std::vector<int>& near) {
  const LevelSystem& L = s.levels[level];
  const double dt = L.seconds;
  std::vector<int> inaccurate;
  for (int c : L.cells) {
    if (s.depth[c] != level || FollowingChoices(s)) continue;
    const double change = s.iterate_h[c] - s.enthalpy[c];
    const double error = std::abs(change - dt * s.heat_rate[c]) * dt / (dt + s.rate_step_s[c]);
    if (error > std::max(s.step_error_h[s.material[c]], kStepErrorShare * std::abs(s.enthalpy[c]))) {
      inaccurate.push_back(c);
    }
  }
  ChooseList(s, inaccurate, s.grid_of.size());  // which cells are inaccurate is a choice (SolverChoices)
  JoinWithMargin(s, level, L.m1, inaccurate, near);
}

void AddUnconvergedCells(ThermalState& s, int level, const std::vector<int>& cells, std::vector<int>& near) {
  s.stats.unconverged_cells += cells.size();
  JoinWithMargin(s, level, s.levels[level].m1, cells, near);
}

}  // namespace waam::twin::internal
