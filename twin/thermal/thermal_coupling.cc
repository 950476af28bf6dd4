// The coupling between multirate levels: the state a level's step restores before it re-runs its finer levels, the
// discrete maximum principle's check of its corrector and the repair of what the check finds (docs/THERMAL.md,
// "Why the coupling between levels is monotone").
#include <algorithm>
#include <cmath>
#include <limits>

#include "twin/thermal/thermal_state.h"

namespace waam::twin::internal {
namespace {

// Sets cell c's enthalpy (J/m^3) at the end of the level's step and what follows from it: its temperature,
// conductivity, the rates the next step's guess and error estimate read, and its probe records inside the step (the
// change ramped in over the level's step).
void SetEnthalpy(ThermalState& s, const LevelSystem& L, int c, double h) {
  const ThermalPropertyTable& table = s.table[s.material[c]];
  const double t = table.Temperature(h, s.temperature[c]);
  const double change = t - s.temperature[c];
  ForStepRecords(s, L, c, [&](double& record, double f) { record += f * change; });
  s.heat_rate[c] += (h - s.enthalpy[c]) / s.rate_step_s[c];
  s.rate[c] += (t - s.temperature[c]) / s.rate_step_s[c];
  s.enthalpy[c] = h;
  s.temperature[c] = t;
  s.conductivity[c] = table.Conductivity(t);
}

}  // namespace

// The Dirichlet value a finer level sees on a cell outside its region at time t: linear in time between the
// values the coarser level that owns the cell had at its interval's ends.
double Bound(const ThermalState& s, int cell, double t) {
  const auto [t0, t1] = s.level_interval[s.bound_level[cell]];
  const double f = t1 > t0 ? (t - t0) / (t1 - t0) : 1.0;
  return s.bound_start[cell] + f * (s.bound_end[cell] - s.bound_start[cell]);
}


void TakeSnapshot(const ThermalState& s, const LevelSystem& L, int level, CouplingSnapshot& snap) {
  snap.cells = L.cells;
  snap.predicted = L.t_new;
  snap.values.resize(kSnapshotFields.size());
  for (std::size_t k = 0; k < kSnapshotFields.size(); ++k) {
    const std::vector<double>& field = s.*kSnapshotFields[k];
    std::vector<double>& values = snap.values[k];
    values.resize(L.cells.size());
    for (std::size_t i = 0; i < L.cells.size(); ++i) values[i] = field[L.cells[i]];
  }
  snap.outside_inflow.clear();
  for (int c : L.cells) {
    for (int f = 0; f < 6; ++f) {
      const int j = s.neighbour[c][f];
      if (j != kNoCell && s.born[j] < L.m1 && s.depth[j] < level) snap.outside_inflow.emplace_back(j, s.inflow_j[j]);
    }
  }
  snap.energy = s.energy;
}

void RestoreSnapshot(ThermalState& s, const CouplingSnapshot& snap) {
  for (std::size_t k = 0; k < kSnapshotFields.size(); ++k) {
    std::vector<double>& field = s.*kSnapshotFields[k];
    for (std::size_t i = 0; i < snap.cells.size(); ++i) field[snap.cells[i]] = snap.values[k][i];
  }
  for (const auto& [j, joules] : snap.outside_inflow) s.inflow_j[j] = joules;
  s.energy = snap.energy;
}


// The discrete maximum principle on the cells the level's corrector updated (L.cells): backward Euler with
// conductances and losses makes the new temperatures weighted means of the old ones, the boundary lines' ends of the
// cells outside the level, the finer neighbours' over the step (taken between their old and new values), and the
// ambient and table temperatures (the least and greatest over the step's micro steps, of which the step and its
// finer levels use time means): none may lie below the least of those values, nor above the greatest unless a
// cell has a source. The finer levels' energy, taken at a fixed boundary line, breaks it where that line runs away
// from what the coarse cell did (docs/THERMAL.md, "Why the coupling between levels is monotone"). Finds the cells
// outside those bounds by more than the slack (kCouplingSlackK and, with latent heat, the enthalpy
// iteration's own mismatch |T(H) - T_solved|). `local_of` is scratch (all kNoCell), returned so.
CouplingCheck CouplingViolations(ThermalState& s, const LevelSystem& L, const CouplingSnapshot& snap, int level,
                                 std::vector<int>& local_of) {
  for (std::size_t i = 0; i < snap.cells.size(); ++i) local_of[snap.cells[i]] = static_cast<int>(i);
  CouplingCheck check;
  const std::vector<double>& old_t = snap.Values(&ThermalState::temperature);
  double low = std::numeric_limits<double>::infinity(), high = -low;
  auto take = [&](double t) {
    low = std::min(low, t);
    high = std::max(high, t);
  };
  for (std::size_t i = 0; i < L.cells.size(); ++i) {
    const int c = L.cells[i];
    take(old_t[static_cast<std::size_t>(local_of[c])]);
    check.source = check.source || L.source_w[i] > 0.0;
    for (int f = 0; f < 6; ++f) {
      const int j = s.neighbour[c][f];
      if (j == kNoCell || s.born[j] >= L.m1) {
        take(L.boundary_low_c);
        take(L.boundary_high_c);
      } else if (s.depth[j] > level) {
        take(old_t[static_cast<std::size_t>(local_of[j])]);
        take(s.temperature[j]);
      } else if (local_of[j] == kNoCell) {
        take(Bound(s, j, L.end_time_s));
      }
    }
  }
  check.low = low;
  check.high = high;
  for (std::size_t i = 0; i < L.cells.size(); ++i) {
    const int c = L.cells[i];
    const double t = s.temperature[c];
    const double margin = kCouplingSlackK + std::abs(t - L.t_new[i]);
    const double excursion = std::max(low - t, check.source ? 0.0 : t - high);
    if (excursion > kCouplingSlackK) check.outside.push_back(c);
    if (excursion > margin) {
      check.violations.push_back(c);
      check.worst = std::max(check.worst, excursion);
    }
  }
  for (int c : snap.cells) local_of[c] = kNoCell;
  return check;
}

// The repair of Shashkov & Wendroff (2004, J. Comput. Phys. 198, 265, section 3): each cell the check found outside
// [low, high] is set to the bound it crossed, and the energy that takes comes from (or goes to) the cells of the
// level's region around it, ring of faces by ring, each giving in proportion to its room before it would cross the
// same bound itself. Conservative and bounded; deterministic (the violations in order, serially).
void RepairBounds(ThermalState& s, const LevelSystem& L, const CouplingSnapshot& snap, const CouplingCheck& check,
                  std::vector<int>& local_of) {
  constexpr int kRings = 4;
  for (std::size_t i = 0; i < snap.cells.size(); ++i) local_of[snap.cells[i]] = static_cast<int>(i);
  std::vector<int> seen, ring, next;
  std::vector<double> room;
  for (int c : check.outside) {
    const bool below = s.temperature[c] < check.low;
    const double bound = below ? check.low : check.high;
    // The energy the cell lacks (> 0) or holds in excess (< 0), J/m^3 (every cell has the same volume).
    double need = s.table[s.material[c]].Enthalpy(bound) - s.enthalpy[c];
    seen.assign(1, c);
    ring.assign(1, c);
    for (int r = 0; r < kRings && std::abs(need) > 0.0; ++r) {
      next.clear();
      for (int q : ring) {
        for (int f = 0; f < 6; ++f) {
          const int j = s.neighbour[q][f];
          if (j == kNoCell || s.born[j] >= L.m1 || local_of[j] == kNoCell) continue;
          if (std::find(seen.begin(), seen.end(), j) != seen.end()) continue;
          seen.push_back(j);
          next.push_back(j);
        }
      }
      room.assign(next.size(), 0.0);
      double total = 0.0;
      for (std::size_t k = 0; k < next.size(); ++k) {
        const int j = next[k];
        const double h_bound = s.table[s.material[j]].Enthalpy(bound);
        room[k] = std::max(0.0, below ? s.enthalpy[j] - h_bound : h_bound - s.enthalpy[j]);
        total += room[k];
      }
      if (total > 0.0) {
        const double share = std::min(1.0, std::abs(need) / total);
        double moved = 0.0;
        for (std::size_t k = 0; k < next.size(); ++k) {
          const double dh = share * room[k];
          moved += dh;
          SetEnthalpy(s, L, next[k], s.enthalpy[next[k]] + (below ? -dh : dh));
        }
        SetEnthalpy(s, L, c, s.enthalpy[c] + (below ? moved : -moved));
        if (share < 1.0) break;  // this ring held all the cell needed
        need -= below ? moved : -moved;
      }
      ring.swap(next);
    }
  }
  for (int c : snap.cells) local_of[c] = kNoCell;
}

}  // namespace waam::twin::internal
