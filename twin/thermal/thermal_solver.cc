// The thermal solver: one backward-Euler step of a region of active cells (system assembly, the enthalpy iteration
// around the linear solve of thermal_cg.cc, conservative enthalpy update) and the multirate recursion over regions
// nearer and nearer the arc, coupled as thermal_coupling.cc checks. Derivations and stability in docs/THERMAL.md.
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>

#include "models/core/error.h"
#include "models/core/parallel.h"
#include "twin/thermal/thermal_state.h"

namespace waam::twin::internal {
namespace {

// The nonlinear (chord) iteration of a step stops when every cell's enthalpy maps back to within this + 10 % of its
// temperature change, or after kChordRounds re-solves: it exists to keep big steps from jumping the latent heat
// (hundreds of K of mismatch), not to polish micro steps.
constexpr double kChordToleranceK = 10.0;
constexpr int kChordRounds = 6;
// LocalBalance's bisection stops within this, K.
constexpr double kBalanceToleranceK = 1e-3;
// A face towards a cell that a finer level solves: no flux in this level's system (its energy arrives in inflow_j).
constexpr int kFinerCell = -2;
// A level's step runs its finer levels and its corrector at most this many times: again when the corrector leaves
// cells outside the maximum principle's bounds by more than the step's accuracy, those cells then in the finer
// region (CouplingViolations); after the last round the cells still outside are repaired (RepairBounds).
constexpr int kCouplingRounds = 2;


// The losses of one boundary face, W.
struct FaceLoss {
  double convection = 0.0, radiation = 0.0, table = 0.0;
};

// Convection, radiation (linearised about the state's temperature t_old) and table (and clamp) losses of one face,
// each linear in the face's temperature t: loss = slope t + offset (W/K and W), to the ambient and table temperatures
// of the level's step (L.ambient_c, L.table_c), given the face's contact conductance and open share (FaceContact).
// The system's linearised loss (LinearLoss) and the energy accounts' (LossOfFace) both come from here, so they are
// the same function of t.
struct FaceLossLine {
  FaceLoss slope, offset;
};
FaceLossLine LossLine(const ThermalState& s, const LevelSystem& L, int cell, double contact, double air,
                      double t_old) {
  const double area = s.dx_m * s.dx_m;
  FaceLossLine line;
  line.slope.table = contact * area;
  line.offset.table = -contact * area * L.table_c;
  if (air <= 0.0) return line;
  const double h = air * s.settings.convection_w_m2k * area;
  line.slope.convection = h;
  line.offset.convection = -h * L.ambient_c;
  const double radiation = air * s.emissivity[s.material[cell]] * kStefanBoltzmann * area;
  const double tk = t_old + kKelvin;
  const double ta = L.ambient_c + kKelvin;
  const double tk3 = tk * tk * tk;
  line.slope.radiation = radiation * 4.0 * tk3;
  line.offset.radiation = radiation * (tk3 * tk - ta * ta * ta * ta - 4.0 * tk3 * t_old);
  return line;
}

// The losses of face `face` of `cell` at t, W, its contact looked up.
FaceLoss LossOfFace(const ThermalState& s, const LevelSystem& L, int cell, int face, double t_old, double t) {
  double contact = 0.0, air = 1.0;
  s.FaceContact(cell, face, &contact, &air);
  const FaceLossLine line = LossLine(s, L, cell, contact, air, t_old);
  return {line.slope.convection * t + line.offset.convection, line.slope.radiation * t + line.offset.radiation,
          line.slope.table * t + line.offset.table};
}

// d(loss)/dT of a boundary face and the loss at T = 0 degC of its linearisation, so loss(T) = slope T + offset (the
// contact looked up once for both).
void LinearLoss(const ThermalState& s, const LevelSystem& L, int cell, int face, double t_old, double* slope,
                double* offset) {
  double contact = 0.0, air = 1.0;
  s.FaceContact(cell, face, &contact, &air);
  const FaceLossLine line = LossLine(s, L, cell, contact, air, t_old);
  *slope = line.slope.convection + line.slope.radiation + line.slope.table;
  *offset = line.offset.convection + line.offset.radiation + line.offset.table;
}

// kReentrantFaceFactor to the power 0..4.
constexpr std::array<double, 5> kEdgePowers = {1.0, kReentrantFaceFactor, kReentrantFaceFactor * kReentrantFaceFactor,
                                               kReentrantFaceFactor * kReentrantFaceFactor * kReentrantFaceFactor,
                                               kReentrantFaceFactor * kReentrantFaceFactor * kReentrantFaceFactor *
                                                   kReentrantFaceFactor};

// The number of set bits of each 6-bit mask (a table: std::popcount is a library call without the POPCNT
// instruction, which the build does not assume).
constexpr std::array<std::uint8_t, 64> kBitCounts = [] {
  std::array<std::uint8_t, 64> counts{};
  for (unsigned m = 0; m < 64; ++m) counts[m] = static_cast<std::uint8_t>(std::popcount(m));
  return counts;
}();

// The link bits of the faces across the edges of face f (the faces off f's own axis).
constexpr std::array<std::uint8_t, 6> kAcross = [] {
  std::array<std::uint8_t, 6> across{};
  for (unsigned f = 0; f < 6; ++f) across[f] = static_cast<std::uint8_t>(63u & ~(3u << (2 * (f / 2))));
  return across;
}();

// The factor on the conductance of the face f between cells c and j (both present before micro step m1):
// kReentrantFaceFactor for each of the face's four edges where exactly one of the two cells beyond it (c's and j's
// neighbours across the edge) is present, i.e. three of the four cells around the edge are metal.
double EdgeFactor(const ThermalState& s, int c, int j, int f, int m1) {
  const unsigned across = kAcross[static_cast<std::size_t>(f)];
  if (s.latest_born < m1 || ((s.pending[c] | s.pending[j]) & across) == 0) {
    // Every linked cell beyond the edges is present (none of them is laid later in the batch): the edges where the
    // two cells' links differ.
    return kEdgePowers[kBitCounts[(s.linked[c] ^ s.linked[j]) & across]];
  }
  double factor = 1.0;
  for (int e = 0; e < 6; ++e) {
    if (e / 2 == f / 2) continue;
    const int p = s.neighbour[c][e], q = s.neighbour[j][e];
    const bool p_metal = p != kNoCell && s.born[p] < m1, q_metal = q != kNoCell && s.born[q] < m1;
    if (p_metal != q_metal) factor *= kReentrantFaceFactor;
  }
  return factor;
}

// Assembles the backward-Euler system of `level` over the candidates present in micro steps [m0, m1):
// (C V / dt) (T - T_old) = Q + E / dt + sum_faces G (T_nb - T) - losses(T), C = dH/dT at T_old (eq. 3 of
// docs/THERMAL.md), E the energy already passed in by finer levels. With `finer_apart`, faces towards cells of a
// finer level (depth > level) carry no flux. Only the terms without the capacity are assembled, into base_diagonal
// and base_rhs: the capacity's terms are added where the step is linearised (FirstLinearisation, Relinearise).
void Assemble(ThermalState& s, int level, const std::vector<int>& candidates, int m0, int m1, bool finer_apart,
              std::vector<int>& local_of) {
  LevelSystem& L = s.levels[level];
  L.cells.clear();
  for (int c : candidates) {
    if (s.born[c] < m1) L.cells.push_back(c);
  }
  const std::size_t n = L.cells.size();
  for (std::size_t i = 0; i < n; ++i) local_of[L.cells[i]] = static_cast<int>(i);
  L.neighbour.resize(n);
  L.conductance.resize(n);
  L.diagonal.resize(n);
  L.rhs.resize(n);
  L.base_diagonal.resize(n);
  L.base_rhs.resize(n);
  L.source_w.assign(n, 0.0);
  L.t_new.resize(n);
  L.capacity.resize(n);
  for (int m = m0; m < m1; ++m) {
    for (const auto& [cell, watts] : s.batch[m].heat_w) {
      if (local_of[cell] != kNoCell) L.source_w[local_of[cell]] += watts * s.batch[m].seconds / L.seconds;
    }
  }
  ForChunks(n, [&](std::size_t begin, std::size_t end, std::size_t) {
    for (std::size_t i = begin; i < end; ++i) {
      const int c = L.cells[i];
      const double t = s.temperature[c];
      const double k = s.conductivity[c];
      double diagonal = 0.0;
      double rhs = L.source_w[i] + s.inflow_j[c] / L.seconds;
      for (int f = 0; f < 6; ++f) {
        const int j = s.neighbour[c][f];
        L.neighbour[i][f] = kNoCell;
        L.conductance[i][f] = 0.0;
        if (j != kNoCell && s.born[j] < m1 && finer_apart && s.depth[j] > level) {
          L.neighbour[i][f] = kFinerCell;
        } else if (j != kNoCell && s.born[j] < m1) {
          const double kj = s.conductivity[j];
          // Two half cells in series: G = A / (dx/2k + dx/2kj), A = dx^2, times the factor of each re-entrant
          // edge the face touches.
          double g = 2.0 * k * kj / (k + kj) * s.dx_m * EdgeFactor(s, c, j, f, m1);
          // The plate's bottom on a table body: the contact conductance h A in series (docs/THERMAL.md).
          if (s.table_body) {
            const double h = s.InterfaceContact(c, f);
            if (h > 0.0) g = 1.0 / (1.0 / g + 1.0 / (h * s.dx_m * s.dx_m));
          }
          L.conductance[i][f] = g;
          diagonal += g;
          if (local_of[j] != kNoCell) {
            L.neighbour[i][f] = local_of[j];
          } else {
            rhs += g * Bound(s, j, L.end_time_s);
          }
        } else {
          double slope = 0.0, offset = 0.0;
          LinearLoss(s, L, c, f, t, &slope, &offset);
          diagonal += slope;
          rhs -= offset;
        }
      }
      L.base_diagonal[i] = diagonal;
      L.base_rhs[i] = rhs;
    }
  });
  for (int c : L.cells) local_of[c] = kNoCell;
}

// Adds one solve of `cells` cells taking `iterations` CG iterations at `level` to the statistics.
void Count(ThermalState& s, int level, std::size_t cells, int iterations) {
  ThermalStats& st = s.stats;
  const std::size_t need = static_cast<std::size_t>(level) + 1;
  if (st.level_solves.size() < need) {
    st.level_solves.resize(need, 0);
    st.level_cell_solves.resize(need, 0);
    st.level_iterations.resize(need, 0);
  }
  st.iterations += static_cast<std::size_t>(iterations);
  st.level_solves[level] += 1;
  st.level_cell_solves[level] += cells;
  st.level_iterations[level] += static_cast<std::size_t>(iterations);
}

// The nonlinear iteration's next linearisation (the enthalpy iteration of Swaminathan & Voller 1992, Metall. Trans.
// B 23B 651):
// with the iterate H_k, T_k = T(H_k) and C_k = dH/dT at T_k, the step's equation
// V/dt (H_k + C_k (T - T_k) - H_old) = Q + E/dt + sum_faces G (T_nb - T) - losses(T)
// changes from the first linearisation only in the capacity's terms of the diagonal and the right-hand side. For
// cell i of the level's system; `storage_per_capacity` = V / dt.
void RelineariseCell(ThermalState& s, LevelSystem& L, std::size_t i, double storage_per_capacity) {
  const int c = L.cells[i];
  const double capacity = s.table[s.material[c]].Capacity(s.chord[c]);
  const double storage = capacity * storage_per_capacity;
  L.capacity[i] = capacity;
  L.diagonal[i] = L.base_diagonal[i] + storage;
  L.rhs[i] = L.base_rhs[i] + storage * s.chord[c] - storage_per_capacity * (s.iterate_h[c] - s.enthalpy[c]);
}

// The same for every cell of the level's system.
void Relinearise(ThermalState& s, LevelSystem& L) {
  const double storage_per_capacity = s.CellVolume() / L.seconds;
  ForChunks(L.cells.size(), [&](std::size_t begin, std::size_t end, std::size_t) {
    for (std::size_t i = begin; i < end; ++i) RelineariseCell(s, L, i, storage_per_capacity);
  });
}

// `load` plus the neighbours' part of cell i's equation in the level's system at their temperatures L.t_new: the sum
// over its faces of G T_nb, W (added face by face in face order).
double AddNeighbourFlow(const LevelSystem& L, std::size_t i, double load) {
  for (int f = 0; f < 6; ++f) {
    const int j = L.neighbour[i][f];
    if (j >= 0) load += L.conductance[i][f] * L.t_new[static_cast<std::size_t>(j)];
  }
  return load;
}

// The temperature at which cell i of the level's system balances its step's nonlinear equation with its
// neighbours in the system held at their solved temperatures:
// V/dt (H(T) - H_old) + D_i T = R_i + sum_faces G T_nb (D_i, R_i: base_diagonal and base_rhs),
// found by bisection (the left side increases with T). Where the linearisation crossed the latent heat's edge, this
// lands on the right side of it, where the enthalpy update H_k + C_k (T - T_k) overshoots by up to the ratio of the
// capacities on the two sides.
double LocalBalance(const ThermalState& s, const LevelSystem& L, std::size_t i) {
  const int c = L.cells[i];
  const ThermalPropertyTable& table = s.table[s.material[c]];
  const double storage = s.CellVolume() / L.seconds;
  const double load = AddNeighbourFlow(L, i, L.base_rhs[i]);
  auto excess = [&](double t) {
    return storage * (table.Enthalpy(t) - s.enthalpy[c]) + L.base_diagonal[i] * t - load;
  };
  double low = std::min(L.t_new[i], s.chord[c]), high = std::max(L.t_new[i], s.chord[c]);
  for (double widen = 16.0; excess(low) > 0.0 && widen < 1e5; widen *= 2.0) low -= widen;
  for (double widen = 16.0; excess(high) < 0.0 && widen < 1e5; widen *= 2.0) high += widen;
  double excess_low = excess(low), excess_high = excess(high);
  while (high - low > kBalanceToleranceK) {
    const double mid = 0.5 * (low + high);
    const double e = excess(mid);
    if (e > 0.0) {
      high = mid, excess_high = e;
    } else {
      low = mid, excess_low = e;
    }
  }
  // The root of the excess's chord over the last bracket: exact where no table node lies inside it (H is linear
  // between nodes), and continuous in the cell's inputs, which the bracket's midpoint is not.
  const double span = excess_high - excess_low;
  return span > 0.0 ? low - excess_low * (high - low) / span : 0.5 * (low + high);
}

// The choice of which cells of a level's system take a flag (1): recorded, or replaced by the followed one.
void ChooseFlags(ThermalState& s, std::vector<std::uint8_t>& flags) {
  if (s.choice_mode == ThermalState::ChoiceMode::kFree) return;
  std::vector<int> set;
  for (std::size_t i = 0; i < flags.size(); ++i) {
    if (flags[i] != 0) set.push_back(static_cast<int>(i));
  }
  ChooseList(s, set, flags.size());
  std::fill(flags.begin(), flags.end(), std::uint8_t{0});
  for (int i : set) flags[static_cast<std::size_t>(i)] = 1;
}

// What a level's solve of a step is: the predictor (all the level's cells; with a finer region, its temperatures are
// the finer levels' boundary values and the corrector's first guess) or the corrector (the cells left to the level,
// with the energy the finer levels passed).
enum class StepRole { kPredictor, kCorrector };

// Whether the enthalpy iteration must converge on cell c of a step of `level`: a predictor's need not converge in the
// finer region (depth > level), which the finer levels solve again with their own enthalpy iteration.
bool MustConverge(const ThermalState& s, StepRole role, int c, int level) {
  return role != StepRole::kPredictor || s.depth[c] <= level;
}

// A predictor's first linearisation: the old state (H_old, T_old), except for the cells whose equation, linearised
// there with their neighbours at the first guess, maps back further than the enthalpy iteration allows: those start
// at their local balance with the neighbours at the first guess (cells about to melt or freeze, new metal under the
// arc), so that the first solve already sees the latent heat on the side where they end. Leaves the system
// linearised there (the capacity's terms, as Relinearise).
void FirstLinearisation(ThermalState& s, LevelSystem& L, StepRole role, int level, const std::vector<double>& guess) {
  const double volume = s.CellVolume();
  const std::size_t n = L.cells.size();
  std::vector<std::uint8_t>& balance = L.flags;
  balance.assign(n, 0);
  ForChunks(n, [&](std::size_t begin, std::size_t end, std::size_t) {
    for (std::size_t i = begin; i < end; ++i) L.t_new[i] = guess[L.cells[i]];
  });
  ForChunks(n, [&](std::size_t begin, std::size_t end, std::size_t) {
    for (std::size_t i = begin; i < end; ++i) {
      const int c = L.cells[i];
      s.chord[c] = s.temperature[c];
      s.iterate_h[c] = s.enthalpy[c];
      if (!MustConverge(s, role, c, level) || FollowingChoices(s)) continue;
      // The system linearised at the old state: capacity C at T_old (eq. 3).
      const double capacity = s.table[s.material[c]].Capacity(s.temperature[c]);
      const double storage = capacity * volume / L.seconds;
      const double load = AddNeighbourFlow(L, i, L.base_rhs[i] + storage * s.temperature[c]);
      const double t = load / (L.base_diagonal[i] + storage);
      const double h = s.enthalpy[c] + capacity * (t - s.temperature[c]);
      const double back = s.table[s.material[c]].Temperature(h, t);
      balance[i] = std::abs(back - t) > kChordToleranceK + 0.1 * std::abs(t - s.temperature[c]) ? 1 : 0;
    }
  });
  ChooseFlags(s, balance);
  // The flagged cells' local balance, and every cell's linearisation (Relinearise: LocalBalance reads none of it).
  const double storage_per_capacity = volume / L.seconds;
  ForChunks(n, [&](std::size_t begin, std::size_t end, std::size_t) {
    for (std::size_t i = begin; i < end; ++i) {
      if (balance[i] != 0) {
        const int c = L.cells[i];
        s.chord[c] = LocalBalance(s, L, i);
        s.iterate_h[c] = s.table[s.material[c]].Enthalpy(s.chord[c]);
      }
      RelineariseCell(s, L, i, storage_per_capacity);
    }
  });
}

// Solves the level's backward-Euler step over the candidates: the system linearised at T_old or where
// FirstLinearisation puts a cell (a corrector: at the predictor's last iterate, H_k and T_k = T(H_k), which the finer
// levels leave to the cells outside their region),
// then, while some cell's linearised enthalpy H_k + C_k (T - T_k) maps back to a temperature more than
// kChordToleranceK + 10 % of its change over the step away from the solved T (a cell melting or freezing in the
// step), again linearised at that enthalpy (Relinearise): the nonlinear step converged (on the cells MustConverge
// names), so that the latent heat cannot be jumped over. `guess` is the first guess by active cell. Only the
// capacity changes between the rounds, so the conductances and losses are assembled once. With `unconverged` (a
// predictor whose level has finer levels in this step) there is no second round: the cells off the curve after the
// first solve are appended to it, for the finer levels to take through the latent heat in their shorter steps
// (AddUnconvergedCells), and the step stands for the others.
void SolveStep(ThermalState& s, int level, const std::vector<int>& candidates, int m0, int m1, StepRole role,
               const std::vector<double>& guess, std::vector<int>& local_of, std::vector<int>* unconverged = nullptr) {
  LevelSystem& L = s.levels[level];
  const bool corrector = role == StepRole::kCorrector;
  Assemble(s, level, candidates, m0, m1, corrector, local_of);
  if (corrector) {
    Relinearise(s, L);
  } else {
    FirstLinearisation(s, L, role, level, guess);
  }
  // A predictor with finer levels need not converge in their region (MustConverge), neither its enthalpy iteration
  // nor its linear solve: the finer levels solve the region again from the predicted values around it.
  const int deepest_tested = unconverged != nullptr ? level : std::numeric_limits<int>::max();
  Count(s, level, L.cells.size(), SolveLevel(s, L, guess, false, deepest_tested));
  const std::size_t n = L.cells.size();
  const double storage_per_capacity = s.CellVolume() / L.seconds;
  std::vector<std::uint8_t>& off = L.flags;
  off.resize(n);
  for (int round = 0; round < kChordRounds; ++round) {
    // The next iterate H_k+1 = H_k + C_k (T - T_k), T_k+1 = T(H_k+1), and whether it maps back close enough.
    ForChunks(n, [&](std::size_t begin, std::size_t end, std::size_t) {
      for (std::size_t i = begin; i < end; ++i) {
        const int c = L.cells[i];
        const double h = s.iterate_h[c] + L.capacity[i] * (L.t_new[i] - s.chord[c]);
        const double t = s.table[s.material[c]].Temperature(h, L.t_new[i]);
        const double change = L.t_new[i] - s.temperature[c];
        const bool ok = std::abs(t - L.t_new[i]) <= kChordToleranceK + 0.1 * std::abs(change) ||
                        !MustConverge(s, role, c, level);
        off[i] = ok ? 0 : 1;
        s.iterate_h[c] = h;
        s.chord[c] = t;
      }
    });
    // Converged when no cell is off the curve (a run following choices: when the recorded run's round had none).
    ChooseFlags(s, off);
    if (std::none_of(off.begin(), off.end(), [](std::uint8_t v) { return v != 0; })) return;
    if (unconverged != nullptr) {
      // A predictor with finer levels: the cells off the curve go to them (AddUnconvergedCells), the rest stand.
      for (std::size_t i = 0; i < n; ++i) {
        if (off[i] != 0) unconverged->push_back(L.cells[i]);
      }
      return;
    }
    // The cells off the curve are linearised next at their local balance instead (on the curve: H_k = H(T_k)), and
    // every cell at its new iterate (Relinearise).
    ForChunks(n, [&](std::size_t begin, std::size_t end, std::size_t) {
      for (std::size_t i = begin; i < end; ++i) {
        if (off[i] != 0) {
          const int c = L.cells[i];
          s.chord[c] = LocalBalance(s, L, i);
          s.iterate_h[c] = s.table[s.material[c]].Enthalpy(s.chord[c]);
        }
        RelineariseCell(s, L, i, storage_per_capacity);
      }
    });
    Count(s, level, n, SolveLevel(s, L, s.chord, true));
  }
}

// Fills the probe records wanted of `cell` at the batch boundaries in (m0, m1] of the level's step, which takes the
// cell from t_start to t_end (degC): linear in time in between, as the finer levels see the coarser ones' cells.
// Each request has its own slot, so chunks running in parallel write different values.
void RecordSamples(ThermalState& s, const LevelSystem& L, int cell, double t_start, double t_end) {
  ForStepRecords(s, L, cell, [&](double& record, double f) { record = t_start + f * (t_end - t_start); });
}

// Per-chunk energy accounts of an update, J.
struct UpdateAccount {
  double input = 0.0, convection = 0.0, radiation = 0.0, table = 0.0;
};

// Moves each cell's enthalpy by the energy its faces pass at the solved temperatures (eq. 4 of docs/THERMAL.md):
// every interior face's flux leaves one cell and enters the other, so energy is conserved whatever the solver's
// residual. Faces towards finer cells carry no flux here (their energy arrived in inflow_j); faces towards cells
// outside the region put their energy into those cells' inflow_j (serial then).
void Update(ThermalState& s, int level) {
  LevelSystem& L = s.levels[level];
  const std::size_t n = L.cells.size();
  const double dt = L.seconds;
  const double volume = s.CellVolume();
  std::vector<UpdateAccount> part(Chunks(n));
  // A cell's update reads its own old state and its neighbours' solved temperatures (L.t_new), never another
  // region cell's state, so each cell is updated as soon as its energy is summed.
  auto body = [&](std::size_t begin, std::size_t end, std::size_t chunk) {
    UpdateAccount acc;
    for (std::size_t i = begin; i < end; ++i) {
      const int c = L.cells[i];
      const double t_solved = L.t_new[i];
      double power = L.source_w[i];
      acc.input += L.source_w[i] * dt;
      for (int f = 0; f < 6; ++f) {
        const double g = L.conductance[i][f];
        const int j = L.neighbour[i][f];
        if (j == kFinerCell) continue;
        if (j != kNoCell) {
          power += g * (L.t_new[j] - t_solved);
        } else if (g > 0.0) {
          const int other = s.neighbour[c][f];
          const double flux = g * (Bound(s, other, L.end_time_s) - t_solved);
          power += flux;
          s.inflow_j[other] -= flux * dt;
        } else {
          const FaceLoss loss = LossOfFace(s, L, c, f, s.temperature[c], t_solved);
          power -= loss.convection + loss.radiation + loss.table;
          acc.convection += loss.convection * dt;
          acc.radiation += loss.radiation * dt;
          acc.table += loss.table * dt;
        }
      }
      const double dh = (power * dt + s.inflow_j[c]) / volume;
      s.enthalpy[c] += dh;
      s.inflow_j[c] = 0.0;
      const double t = s.table[s.material[c]].Temperature(s.enthalpy[c], t_solved);
      if (s.sample_head[c] >= 0) RecordSamples(s, L, c, s.temperature[c], t);
      s.rate[c] = (t - s.temperature[c]) / dt;
      s.heat_rate[c] = dh / dt;
      s.rate_step_s[c] = dt;
      s.temperature[c] = t;
      s.conductivity[c] = s.table[s.material[c]].Conductivity(t);
    }
    part[chunk] = acc;
  };
  if (level == 0) {
    ForChunks(n, body);  // no cell lies outside the top region, so no other cell's inflow is written
  } else {
    for (std::size_t c = 0; c < Chunks(n); ++c) body(c * kChunk, std::min(n, (c + 1) * kChunk), c);
  }
  for (const UpdateAccount& acc : part) {
    s.energy.input_j += acc.input;
    s.energy.convection_j += acc.convection;
    s.energy.radiation_j += acc.radiation;
    s.energy.table_j += acc.table;
  }
}

void Advance(ThermalState& s, int level, const std::vector<int>& candidates, int m0, int m1,
             std::vector<int>& local_of);

// The finer levels over the level's interval [m0, m1): sub-intervals of at least the finer level's step, cut at
// micro-step boundaries, each an Advance of level + 1 over the finer region `near` (left marked depth = level + 1).
void RunFinerLevels(ThermalState& s, int level, const std::vector<int>& near, int m0, int m1,
                    std::vector<int>& local_of) {
  const double step = s.level_step_s[level + 1];
  int a = m0;
  while (a < m1) {
    int b = a;
    double length = 0.0;
    while (b < m1 && (b == a || length < step * (1.0 - 1e-9))) length += s.batch[b++].seconds;
    for (int c : near) s.depth[c] = level + 1;
    Advance(s, level + 1, near, a, b, local_of);
    a = b;
  }
  for (int c : near) s.depth[c] = level + 1;
}

// Starts the level's step over micro steps [m0, m1): its length, interval, and the ambient and table temperatures
// over it (backward Euler with their time means: docs/THERMAL.md, "Boundary temperatures that change").
void BeginLevelStep(ThermalState& s, int level, int m0, int m1) {
  LevelSystem& L = s.levels[level];
  L.seconds = 0.0;
  BoundaryMean boundary;
  for (int m = m0; m < m1; ++m) {
    L.seconds += s.batch[m].seconds;
    boundary.Add(s.batch[m].seconds, s.batch[m].ambient_c, s.batch[m].table_c);
  }
  L.ambient_c = boundary.ambient_c();
  L.table_c = boundary.table_c();
  L.boundary_low_c = boundary.low_c();
  L.boundary_high_c = boundary.high_c();
  const double start = s.time_s + s.batch_start_s[m0];
  L.end_time_s = start + L.seconds;
  L.m0 = m0;
  L.m1 = m1;
  s.level_interval[level] = {start, L.end_time_s};
}

// After the level's predictor: the finer levels over the region `near`, the corrector of the cells left to the
// level (returned) and its update, checked against the maximum principle. Where the step broke it by more than the
// step's accuracy, those cells join the finer region and the finer levels and the corrector run again from the
// predictor; what is left is repaired (docs/THERMAL.md, "Why the coupling between levels is monotone").
std::vector<int> CoupleFinerLevels(ThermalState& s, int level, std::vector<int>& near, std::vector<int>& local_of) {
  LevelSystem& L = s.levels[level];
  const int m0 = L.m0, m1 = L.m1;
  TakeSnapshot(s, L, level, L.snapshot);
  const CouplingSnapshot& snap = L.snapshot;
  std::vector<int> rest;
  for (int round = 0;; ++round) {
    for (std::size_t i = 0; i < snap.cells.size(); ++i) {
      const int c = snap.cells[i];
      s.bound_start[c] = s.temperature[c];
      s.bound_end[c] = snap.predicted[i];
      s.bound_level[c] = level;
    }
    RunFinerLevels(s, level, near, m0, m1, local_of);
    rest.clear();
    for (int c : snap.cells) {
      if (s.depth[c] == level) rest.push_back(c);
    }
    SolveStep(s, level, rest, m0, m1, StepRole::kCorrector, s.bound_end, local_of);
    Update(s, level);
    CouplingCheck check = CouplingViolations(s, L, snap, level, local_of);
    // An excursion within the accuracy the step choice asks (AddInaccurateCells: kStepErrorK, or kStepErrorShare of
    // the bounds' range here) is repaired; a larger one moves its cells to the finer levels once, then is repaired.
    // Whether to re-run and the cells that join are choices (a run following them repairs what it finds outside).
    const bool rerun = ChooseCount(s, !check.outside.empty() && round + 1 < kCouplingRounds &&
                                          check.worst > std::max(kStepErrorK,
                                                                 kStepErrorShare * (check.high - check.low))) != 0;
    if (!rerun) {
      if (!check.outside.empty()) RepairBounds(s, L, snap, check, local_of);
      s.stats.coupling_repairs += check.outside.size();
      return rest;
    }
    WAAM_THROW_UNLESS(round + 1 < kCouplingRounds, "solver choices: a re-run past the last coupling round (the "
                                                   "record does not fit this run)");
    ChooseList(s, check.violations, s.grid_of.size());
    RestoreSnapshot(s, snap);
    const std::size_t from = near.size();
    for (int c : check.violations) {
      near.push_back(c);
      s.depth[c] = level + 1;
    }
    CloseFinerRegion(s, near, from, level, m1);
    s.stats.coupling_retries += 1;
  }
}

// One level of the multirate scheme over micro steps [m0, m1) (docs/THERMAL.md, "Multirate"): a backward-Euler
// step of the whole region; near the arc, finer steps with this step's temperatures as their boundary moving
// linearly in time; then the cells left to this level solved again, implicitly, with the energy the finer steps
// passed through their faces as a source, and updated.
void Advance(ThermalState& s, int level, const std::vector<int>& candidates, int m0, int m1,
             std::vector<int>& local_of) {
  BeginLevelStep(s, level, m0, m1);
  LevelSystem& L = s.levels[level];
  // First guess: each cell's last rate of change carried over the step (the far field changes smoothly), but no
  // further than the step it was taken over: a rate taken over a micro step under the arc says little of the next
  // 32 s, and carried over them it put guesses thousands of K off (docs/THERMAL.md, "Where the CG iterations go").
  for (int c : candidates) s.guess[c] = s.temperature[c] + s.rate[c] * std::min(L.seconds, s.rate_step_s[c]);
  std::vector<int> present;
  for (int c : candidates) {
    if (s.born[c] < m1) present.push_back(c);
  }
  const bool finest = level + 1 >= static_cast<int>(s.levels.size()) || m1 - m0 <= 1;
  // The predictor's nonlinear iteration need not converge in the finer region: the finer levels solve it again.
  for (int c : present) s.depth[c] = level;
  std::vector<int> near;
  if (!finest) near = FinerRegion(s, present, level, m0, m1, s.level_radius_mm[level + 1]);
  std::vector<int> unconverged;
  SolveStep(s, level, candidates, m0, m1, StepRole::kPredictor, s.guess, local_of, finest ? nullptr : &unconverged);
  if (!finest) {
    AddUnconvergedCells(s, level, unconverged, near);
    AddInaccurateCells(s, level, near);
  }
  for (int c : L.cells) s.depth[c] = level;
  if (near.empty()) {
    Update(s, level);
    for (int c : L.cells) s.depth[c] = level - 1;
    return;
  }
  const std::vector<int> rest = CoupleFinerLevels(s, level, near, local_of);
  for (int c : near) s.depth[c] = level - 1;
  for (int c : rest) s.depth[c] = level - 1;
}

}  // namespace

void BoundaryMean::Add(double seconds, double ambient_c, double table_c) {
  for (auto [sum, value] : {std::pair<Sum*, double>{&ambient_, ambient_c}, {&table_, table_c}}) {
    sum->weighted += seconds * value;
    sum->seconds += seconds;
    sum->low = std::min(sum->low, value);
    sum->high = std::max(sum->high, value);
  }
}

double BoundaryMean::Mean(const Sum& sum) {
  WAAM_DEMAND(sum.seconds > 0.0);
  if (sum.low == sum.high) return sum.low;  // one value over the interval: exactly it
  return std::clamp(sum.weighted / sum.seconds, sum.low, sum.high);
}

void SolveBatch(ThermalState& s) {
  const int steps = static_cast<int>(s.batch.size());
  if (steps == 0) return;
  s.batch_start_s.assign(steps + 1, 0.0);
  for (int m = 0; m < steps; ++m) s.batch_start_s[m + 1] = s.batch_start_s[m] + s.batch[m].seconds;
  const int levels = static_cast<int>(s.level_step_s.size());
  s.levels.resize(levels);
  s.level_interval.resize(levels);
  std::vector<int> all(s.grid_of.size());
  for (std::size_t c = 0; c < all.size(); ++c) all[c] = static_cast<int>(c);
  std::vector<int> local_of(all.size(), kNoCell);
  // The probe records wanted inside the batch: the cell each reads at its time, and its requests.
  s.requests.clear();
  for (const auto& [boundary, record] : s.batch_marks) {
    for (std::size_t p = 0; p < s.probe_mm.size(); ++p) {
      const int cell = ProbeCell(s, s.probe_mm[p], boundary);
      if (cell == kNoCell) continue;  // no metal there yet: the record keeps NaN
      s.requests.push_back({cell, boundary, record, static_cast<int>(p), s.sample_head[cell]});
      s.sample_head[cell] = static_cast<int>(s.requests.size()) - 1;
    }
    s.record_done[record] = 1;
  }
  s.batch_marks.clear();
  Advance(s, 0, all, 0, steps, local_of);
  for (const SampleRequest& q : s.requests) s.sample_head[q.cell] = -1;
  s.requests.clear();
  for (int& b : s.born) b = -1;
  std::fill(s.pending.begin(), s.pending.end(), std::uint8_t{0});
  s.latest_born = -1;
  s.time_s += s.batch_start_s[steps];
  s.last_step_s = s.batch.back().seconds;
  s.stats.steps += static_cast<std::size_t>(steps);
  s.batch.clear();
}

void CoolStep(ThermalState& s, double seconds) {
  WAAM_DEMAND(s.batch.empty() && seconds > 0.0);
  ArcStep step;
  step.seconds = seconds;
  step.ambient_c = s.settings.ambient_c;
  step.table_c = s.settings.table_c;
  s.batch.push_back(step);
  SolveBatch(s);
}

}  // namespace waam::twin::internal
