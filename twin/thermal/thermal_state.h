// The thermal model's data: the grid, the active cells and their enthalpy, the arc steps waiting to be solved, and
// the solver's entry points shared by the files of twin/thermal/ (internal to the module).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "models/core/parallel.h"
#include "twin/thermal/thermal_multigrid.h"
#include "twin/thermal/thermal_simulation.h"
#include "twin/thermal/thermal_tables.h"

namespace waam::twin::internal {

constexpr double kStefanBoltzmann = 5.670374419e-8;  // W/(m^2 K^4), CODATA 2018
constexpr double kKelvin = 273.15;
constexpr int kNoCell = -1;
// The conductance factor of a face touching a re-entrant edge (three of the four cells around the edge are metal, as
// where a wall stands on a plate): with it the two-point flux between the two cells' means is exact for the edge's
// singular solution r^(2/3) cos(2 (theta - pi/2) / 3) between insulated faces (docs/THERMAL.md, "Re-entrant
// edges"; checked by quadrature in tests/twin/thermal_reentrant_test.cc).
constexpr double kReentrantFaceFactor = 1.2626829;
constexpr int kDeposit = 0;    // material index of the deposit
constexpr int kSubstrate = 1;  // material index of the plate
// The local error a level's backward-Euler step may make in a cell, K of heating at its material's reference
// temperature: a cell whose estimated error over the level's step exceeds it takes the finer level's steps
// (docs/THERMAL.md, "Time stepping").
constexpr double kStepErrorK = 1.0;
// ... or this share of the cell's enthalpy above its start (its rise, at the reference capacity), whichever is larger.
constexpr double kStepErrorShare = 0.02;
// How far, K, a corrected temperature may lie outside the maximum principle's bounds before the coupling's check
// counts it (CouplingViolations): ten of the linear solver's default tolerance, so that no solve's own residual is
// repaired.
constexpr double kCouplingSlackK = 0.01;

// Cells per chunk of the deterministic parallel loops: every reduction sums per-chunk partials in chunk order, and
// the chunks do not depend on the thread count, so the results are bit-identical on any number of threads.
constexpr std::size_t kChunk = 4096;
// Below this many cells a loop runs on the calling thread (the pool's dispatch would cost more than it saves).
constexpr std::size_t kParallelCells = 24576;

inline std::size_t Chunks(std::size_t n) { return (n + kChunk - 1) / kChunk; }

// Runs body(begin, end, chunk) over the chunks of [0, n), in parallel when n is large.
template <typename Body>
void ForChunks(std::size_t n, const Body& body) {
  const std::size_t chunks = Chunks(n);
  auto run = [&](std::size_t c) { body(c * kChunk, std::min(n, (c + 1) * kChunk), c); };
  if (n >= kParallelCells) {
    ParallelFor(chunks, run);
  } else {
    for (std::size_t c = 0; c < chunks; ++c) run(c);
  }
}

// What a grid cell can hold.
enum class CellKind : std::uint8_t { kEmpty, kPlate, kDeposit };

// One micro step of the arc: its duration, the cells it switches on and the heat it puts into cells, and the
// ambient and table temperatures over it (the time means of its pieces').
struct ArcStep {
  double seconds = 0.0;
  std::vector<std::pair<int, double>> heat_w;  // (active cell, W) over the step
  Eigen::AlignedBox3d swept_mm;                // the bead laid in this step, mm (empty for no bead)
  double ambient_c = 20.0, table_c = 20.0;     // degC
};

// The time mean of piecewise-constant ambient and table temperatures over an interval, and their least and greatest
// values (docs/THERMAL.md, "Boundary temperatures that change"). Where a temperature is the same in every piece, the
// mean is that value exactly (no rounding of the sum), so constant temperatures give the results they always did.
class BoundaryMean {
 public:
  // Adds `seconds` (> 0) at ambient_c and table_c, degC.
  void Add(double seconds, double ambient_c, double table_c);
  double ambient_c() const { return Mean(ambient_); }
  double table_c() const { return Mean(table_); }
  double low_c() const { return std::min(ambient_.low, table_.low); }   // least of both, degC
  double high_c() const { return std::max(ambient_.high, table_.high); }  // greatest of both, degC

 private:
  struct Sum {
    double weighted = 0.0, seconds = 0.0;  // degC s, s
    double low = 1e300, high = -1e300;     // degC
  };
  static double Mean(const Sum& sum);
  Sum ambient_, table_;
};

// A piece of the arc's path no longer than one cell, waiting to be grouped into micro steps; or a pause (no arc, no
// bead), a micro step of its own.
struct ArcPiece {
  Eigen::Vector3d p0_mm, p1_mm;
  double width_mm = 0.0, height_mm = 0.0, heat_w = 0.0, seconds = 0.0;
  bool pause = false;
  Eigen::Vector2d travel = Eigen::Vector2d::Zero();  // a standing arc's pool orientation (zero: round)
  std::vector<int> records;  // probe records taken at this piece's end (ThermalSimulation::RecordProbes)
  double ambient_c = 20.0, table_c = 20.0;  // the ambient and table temperatures over the piece, degC
};

// One probe's temperature wanted at the end of micro step `boundary - 1` of the batch: written into
// records[record][probe] by the level that finishes `cell` over an interval holding that time.
struct SampleRequest {
  int cell = kNoCell;
  int boundary = 0;  // index into batch_start_s
  int record = 0, probe = 0;
  int next = -1;     // the next request of the same cell, or -1
};

struct ThermalState;

// A level's state before its finer levels run: what they and the level's corrector change, so that the level's step
// can run them again over a larger finer region. Kept in the level's LevelSystem and filled again at each step.
struct CouplingSnapshot {
  std::vector<int> cells;                // the predictor's cells
  std::vector<double> predicted;         // the predictor's temperatures, degC (the finer levels' boundary line)
  // Per cell of `cells`, the values of each of kSnapshotFields: everything of a cell that the finer levels and the
  // corrector change and a re-run reads.
  std::vector<std::vector<double>> values;
  // The snapshot's values of one of kSnapshotFields.
  const std::vector<double>& Values(std::vector<double> ThermalState::*field) const;
  std::vector<std::pair<int, double>> outside_inflow;  // inflow_j of present cells outside the level's region, J
  EnergyBalance energy;
};

// The conjugate gradients' work arrays of one level, kept from solve to solve (no allocation per step once sized).
struct LevelScratch {
  PaddedStencil stencil;                     // the level's system without branches
  std::vector<double> z, p;                  // degC, n + 1 values (the last the zero slot)
  std::vector<double> x, r, ap;              // degC, W, W
  std::vector<double> inverse_diagonal;      // K/W
  // The stopping test's weight of each cell's residual: 1 / A_ii, or 0 for a cell left out of the test (SolveLevel's
  // `deepest_tested`); sgs_stop the same in the symmetric Gauss-Seidel's order.
  std::vector<double> stop, sgs_stop;
  std::vector<double> part_a, part_b, part_max;  // per-chunk partial sums and maxima
  // Whether the stencil, the level's multigrid and the symmetric Gauss-Seidel system below were built on the cells,
  // faces and conductances of the level's last system (a nonlinear round changes only the diagonal).
  bool stencil_faces = false, multigrid_faces = false, sgs_faces = false;
  // The symmetric Gauss-Seidel preconditioner's system (thermal_cg.cc): the cells in wavefront order (order[k] is the
  // local index of the k-th), and per position k the lower faces (-x, -y, -z: earlier positions) and the upper ones
  // (+x, +y, +z: later positions), each a position or the zero slot n with conductance 0.
  std::vector<int> order;
  std::vector<int> sgs_start, sgs_at;  // scratch of the sort
  std::vector<std::array<int, 3>> lower, upper;
  std::vector<std::array<double, 3>> lower_g, upper_g;
  std::vector<double> sgs_diagonal, sgs_inverse;     // W/K, K/W in that order
  std::vector<double> sgs_x, sgs_t, sgs_s, sgs_r;    // degC, degC, degC, W: the iterate, the solves' vectors, r
  std::vector<double> sgs_rh, sgs_z, sgs_p, sgs_q, sgs_et;  // the transformed system's vectors
};

// One level of the multirate scheme: its region (active cells, in solve order) and its backward-Euler system.
// StencilSystem: the local index of each face's neighbour in the region (or kNoCell, or a finer level's cell), the
// conductance W/K through each face to a present neighbour (else 0), the diagonal W/K.
struct LevelSystem : StencilSystem {
  std::vector<int> cells;                     // active-cell ids of the region, present in the level's interval
  std::vector<double> rhs, source_w, t_new;   // W, W, degC (the step's solution)
  std::vector<double> base_diagonal, base_rhs; // W/K, W: the diagonal and right-hand side without the capacity's terms
  std::vector<std::array<int, 3>> ijk;        // grid coordinates of the cells (for the multigrid's blocks)
  AdditiveCorrectionMultigrid multigrid;
  LevelScratch scratch;
  std::vector<double> capacity;                        // J/(m^3 K) the step used for each cell
  CouplingSnapshot snapshot;                           // the state before the finer levels of the level's step
  std::vector<std::uint8_t> flags;                     // a flag per cell (FirstLinearisation's, SolveStep's scratch)
  double seconds = 0.0;
  double end_time_s = 0.0;
  // The ambient and table temperatures the step uses (time means over its micro steps) in its system and its losses,
  // and the least and greatest of either over those micro steps (the coupling's bounds), degC.
  double ambient_c = 20.0, table_c = 20.0;
  double boundary_low_c = 20.0, boundary_high_c = 20.0;
  int m0 = 0, m1 = 0;                                  // the micro steps [m0, m1) of the batch the step spans
};

// The contacts of one column (i, j) of the grid with the clamps and the table, area-weighted over the column's face:
// a face's loss to the table's temperature is conductance x area x (T - table_c), and by convection and radiation
// over its `air` share.
struct ColumnContact {
  double top_w_m2k = 0.0;     // the plate's top face to the clamps, W/(m^2 K)
  double top_air = 1.0;       // share of the top face open to the air
  double bottom_w_m2k = 0.0;  // the plate's bottom face to the table, W/(m^2 K)
  double bottom_air = 1.0;    // share of the bottom face open to the air
};

struct ThermalState {
  // As built, except ambient_c and table_c: the values SetBoundaryTemperatures last set, which the pieces queued from
  // then on carry (the enthalpy tables' references and the table body's start used the values built with).
  ThermalSettings settings;
  Eigen::Vector3d origin_mm = Eigen::Vector3d::Zero();  // corner of the grid's first cell
  Eigen::Vector3i size = Eigen::Vector3i::Zero();       // cells along x, y, z
  double dx_mm = 2.0;
  double dx_m = 0.002;
  int plate_bottom_k = 0;                               // z index of the plate's lowest cells
  int plate_top_k = 0;                                  // z index of the plate's highest cells
  // The table body (settings.table_thickness_mm > 0): its cells (plate cells of the substrate's material) fill the
  // z indices [table_bottom_k, plate_bottom_k) under the table's footprint and start at settings.table_c.
  bool table_body = false;
  int table_bottom_k = 0;
  double start_enthalpy_j = 0.0;                        // J: the table body's enthalpy at t = 0 (plate reference)
  // Per column i + size.x j, with settings.clamps only (empty: no clamp; the bottom's contact is the table's).
  std::vector<ColumnContact> contact;
  std::array<ThermalPropertyTable, 2> table;            // deposit, substrate
  std::array<double, 2> emissivity = {0.0, 0.0};        // per material
  std::array<double, 2> reference_h = {0.0, 0.0};       // J/m^3 of a cell as it starts (plate) or switches on
  // J/m^3 per material: a step whose estimated local error in a cell's enthalpy exceeds this (kStepErrorK of
  // heating at the reference temperature) is too coarse for it, and it takes the finer level's steps.
  std::array<double, 2> step_error_h = {0.0, 0.0};

  std::vector<CellKind> kind;      // per grid cell
  std::vector<int> active_of;      // per grid cell: its active-cell id or kNoCell

  // Active cells (ids in the order they switched on).
  std::vector<int> grid_of;
  std::vector<std::array<int, 3>> cell_ijk;  // the cell's grid coordinates (i, j, k)
  std::vector<std::uint8_t> material;
  std::vector<std::array<int, 6>> neighbour;  // active-cell id across -x, +x, -y, +y, -z, +z, or kNoCell
  std::vector<int> born;            // index of the micro step of the pending batch that lays it; -1 = present
  std::vector<std::uint8_t> linked;  // bit f set when neighbour[f] is an active cell
  std::vector<std::uint8_t> pending; // bit f set when neighbour[f] is laid in the pending batch (born >= 0)
  int latest_born = -1;             // the highest born of the pending batch (-1: no cell laid in it)
  std::vector<double> enthalpy;     // J/m^3 (relative to each table's reference temperature)
  std::vector<double> temperature;  // degC, the state's temperature (from the enthalpy)
  std::vector<double> conductivity; // W/(m K) at that temperature
  std::vector<double> rate;         // dT/dt over the cell's last step, K/s (extrapolated for the solver's first guess)
  std::vector<double> heat_rate;    // dH/dt over the cell's last step, W/m^3 (latent heat included)
  std::vector<double> rate_step_s;  // length of that step, s (0: none yet)
  std::vector<double> guess;        // scratch: the solver's first guess, degC
  std::vector<double> chord;        // scratch: the nonlinear iteration's temperature T_k = T(H_k), degC
  std::vector<double> iterate_h;    // scratch: the nonlinear iteration's enthalpy H_k, J/m^3
  std::vector<double> inflow_j;     // energy received through faces solved at finer levels, J, not yet applied
  std::vector<int> depth;           // deepest multirate level whose region holds the cell (-1: none)
  std::vector<double> bound_start, bound_end;  // Dirichlet line in time seen by finer levels, degC
  std::vector<int> bound_level;     // the level whose interval the line spans
  std::vector<int> sample_head;     // the cell's first SampleRequest of the batch, or -1

  // Pending arc motion, and the batch of micro steps being solved.
  std::vector<ArcPiece> pieces;
  double pieces_seconds = 0.0;
  std::vector<ArcStep> batch;
  std::vector<double> batch_start_s;   // time of each micro step's start since the batch start, s
  // Multirate levels: 0 is the whole model; level l > 0 covers the cells within level_radius_mm[l] of the beads laid
  // in its parent's interval, in steps of at least level_step_s[l] (0: one micro step).
  std::vector<double> level_step_s, level_radius_mm;
  std::vector<LevelSystem> levels;
  std::vector<std::pair<double, double>> level_interval;  // [start, end] time of each level's current interval

  // Probes recorded inside batches: their points (mm), the records (degC per probe, NaN where no metal is), whether
  // each record is filled, the pending batch's record marks (boundary index into batch_start_s, record) and requests.
  std::vector<Eigen::Vector3d> probe_mm;
  std::vector<std::vector<double>> records;
  std::vector<std::uint8_t> record_done;
  std::vector<std::pair<int, int>> batch_marks;
  std::vector<SampleRequest> requests;

  double time_s = 0.0;
  double last_step_s = 0.0;  // length of the last step, s (the next cooling step grows from it)
  EnergyBalance energy;
  ThermalStats stats;

  // The solver's choices (SolverChoices): made freely, made and recorded, or followed from a record.
  enum class ChoiceMode { kFree, kRecord, kFollow };
  ChoiceMode choice_mode = ChoiceMode::kFree;
  SolverChoices recorded;
  std::shared_ptr<const SolverChoices> followed;
  std::size_t followed_at = 0;  // the next value of `followed`

  double CellVolume() const { return dx_m * dx_m * dx_m; }
  int GridIndex(int i, int j, int k) const { return i + size.x() * (j + size.y() * k); }
  Eigen::Vector3i CellIndex(int grid) const;
  Eigen::Vector3d Centre(int i, int j, int k) const;
  // Switches on the cell `grid` (plate or deposit) at the enthalpy `h`, linking its neighbours; returns its id.
  int Activate(int grid, int material_index, double h, int born_step);
  // The contact of face `face` of active cell `cell` with the table or a clamp: conductance (W/(m^2 K)) to the
  // table's temperature and the share of the face open to the air. Faces of neither kind: (0, 1).
  void FaceContact(int cell, int face, double* conductance_w_m2k, double* air) const;
  // With a table body: the contact conductance (W/(m^2 K)) across face `face` of active cell `cell` when that face
  // joins the plate's bottom to the table's top, else 0.
  double InterfaceContact(int cell, int face) const;
};

// Fills s.contact from the settings' clamps (the grid already built): each column's share of each patch, exact
// for a patch that cuts a column's face.
void BuildColumnContacts(ThermalState& s);

// The active cell whose temperature TemperatureAt(p_mm) reads among the cells present at batch boundary `boundary`
// (born before it; INT_MAX: every active cell): the cell holding the point, else the nearest-centred active cell of
// the 3 x 3 x 3 around it; kNoCell when none.
int ProbeCell(const ThermalState& s, const Eigen::Vector3d& p_mm, int boundary);

// Builds the grid and switches on the plate (settings already checked).
void InitialiseThermalState(ThermalState& s);

// Lays the bead of `piece` (cells whose centre lies in it switch on at the ambient temperature, born at micro step
// `step`) and returns the cells that receive its heat (the new ones and those under the arc).
std::vector<int> LayPiece(ThermalState& s, const ArcPiece& piece, int step);

// Lays the bead of `piece` (LayPiece) and returns the share (summing to 1) of its heat each cell takes, by
// settings.heat_source; empty when no metal lies in or under the piece. Adds the cells heated to `heated_mm`.
std::vector<std::pair<int, double>> HeatPiece(ThermalState& s, const ArcPiece& piece, int step,
                                              Eigen::AlignedBox3d* heated_mm);

// The cells of `region` (multirate level `level`'s, depth == level, present before micro step m1) that lie within
// `radius_mm` of the beads laid in micro steps [m0, m1), and then, repeatedly, every cell with at least half of its
// present neighbours among them: they take the finer level's steps, marked depth = level + 1.
std::vector<int> FinerRegion(ThermalState& s, const std::vector<int>& region, int level, int m0, int m1,
                             double radius_mm);

// After the predictor of level `level` (s.levels[level] solved, s.iterate_h its enthalpies) adds to `near` the cells
// left to the level whose estimated local error over the step exceeds step_error_h or kStepErrorShare of the cell's
// enthalpy (backward Euler's dt^2/2 |d2H/dt2|, from the change of the cell's rate between its last step and the
// predicted one), with their face neighbours, then closes the region as FinerRegion does; marks them depth = level + 1.
void AddInaccurateCells(ThermalState& s, int level, std::vector<int>& near);

// After the predictor of level `level`: adds to `near` the `cells` still left to the level (depth == level) whose
// enthalpy iteration the predictor did not converge (SolveStep), with their face neighbours, and closes the region
// as FinerRegion does; marks them depth = level + 1. The finer levels' shorter steps take them through the latent
// heat instead of the level's re-solves of its whole region (docs/THERMAL.md, "Discretisation").
void AddUnconvergedCells(ThermalState& s, int level, const std::vector<int>& cells, std::vector<int>& near);

// Closes the finer region `near` of level `level + 1` (cells marked depth = level + 1) from its entry `from` on:
// repeatedly joins every cell of `level` (depth == level, present before micro step m1) with at least half of its
// present neighbours in the region. Cells that join are appended to `near`.
void CloseFinerRegion(ThermalState& s, std::vector<int>& near, std::size_t from, int level, int m1);

// Solves the level's assembled system (L's cells, stencil, diagonal and right-hand side) into L.t_new, from `guess`
// (degC by active cell), by preconditioned conjugate gradients (thermal_cg.cc); with `same_faces` only the diagonal
// and right-hand side changed since the last solve. The solve stops when every cell of depth <= `deepest_tested` meets
// the tolerance (a predictor leaves its finer region, which the finer levels solve again, out of the test). Returns
// the iterations.
int SolveLevel(ThermalState& s, LevelSystem& L, const std::vector<double>& guess, bool same_faces,
               int deepest_tested = std::numeric_limits<int>::max());

// Calls visit(record, f) for each probe record wanted of `cell` at a batch boundary inside the level's step
// (L.m0, L.m1]: `record` the value (degC), f the boundary's fraction of the step (1 at its end).
template <class Visit>
void ForStepRecords(ThermalState& s, const LevelSystem& L, int cell, const Visit& visit) {
  const double start = s.batch_start_s[L.m0];
  const double length = s.batch_start_s[L.m1] - start;
  for (int r = s.sample_head[cell]; r >= 0; r = s.requests[r].next) {
    const SampleRequest& q = s.requests[r];
    if (q.boundary <= L.m0 || q.boundary > L.m1) continue;
    visit(s.records[q.record][q.probe], q.boundary == L.m1 ? 1.0 : (s.batch_start_s[q.boundary] - start) / length);
  }
}

// The coupling between multirate levels (thermal_coupling.cc; docs/THERMAL.md, "Why the coupling between levels is
// monotone").

// The Dirichlet value a finer level sees on a cell outside its region at time t: linear in time between the values
// the coarser level that owns the cell had at its interval's ends.
double Bound(const ThermalState& s, int cell, double t);

// The per-cell values a level's finer levels and corrector change and a re-run of them reads: all of them go back,
// or the re-run starts from a mix of two runs (a stale rate_step_s halved the step-error estimate of cells the
// first run had stepped finely, left them to an 8 s step, and put a plate probe 6 K off).
inline constexpr std::array kSnapshotFields = {
    &ThermalState::enthalpy, &ThermalState::temperature, &ThermalState::conductivity, &ThermalState::rate,
    &ThermalState::heat_rate, &ThermalState::rate_step_s, &ThermalState::inflow_j, &ThermalState::chord,
    &ThermalState::iterate_h};

inline const std::vector<double>& CouplingSnapshot::Values(std::vector<double> ThermalState::*field) const {
  const auto* it = std::find(kSnapshotFields.begin(), kSnapshotFields.end(), field);
  return values[static_cast<std::size_t>(it - kSnapshotFields.begin())];
}
// Fills `snap` with the level's state (its vectors reused).
void TakeSnapshot(const ThermalState& s, const LevelSystem& L, int level, CouplingSnapshot& snap);
void RestoreSnapshot(ThermalState& s, const CouplingSnapshot& snap);

// What CouplingViolations found: the cells outside the maximum principle's bounds and how far.
struct CouplingCheck {
  std::vector<int> outside;      // cells outside [low, high] by more than one solver tolerance, in L.cells' order
  std::vector<int> violations;   // those of them outside by more than the slack too
  double low = 0.0, high = 0.0;  // degC
  bool source = false;           // a heat source in the step: no upper bound
  double worst = 0.0;            // the largest excursion of the violations beyond the bounds, K
};

// The discrete maximum principle's check of the cells the level's corrector updated (L.cells), against the state
// `snap` held before the finer levels ran. `local_of` is scratch (all kNoCell), returned so.
CouplingCheck CouplingViolations(ThermalState& s, const LevelSystem& L, const CouplingSnapshot& snap, int level,
                                 std::vector<int>& local_of);

// Sets each cell of check.outside to the bound it crossed, conservatively: the energy comes from (or goes to) the
// cells of the level's region around it. `local_of` is scratch (all kNoCell), returned so.
void RepairBounds(ThermalState& s, const LevelSystem& L, const CouplingSnapshot& snap, const CouplingCheck& check,
                  std::vector<int>& local_of);

// The solver's choices (thermal_choices.cc). A count: records `value` and returns it, returns the followed one, or
// returns `value` when choices are free.
int ChooseCount(ThermalState& s, int value);
// A list of indices below `limit`: records `list`, or replaces it with the followed one; free: leaves it.
void ChooseList(ThermalState& s, std::vector<int>& list, std::size_t limit);
inline bool FollowingChoices(const ThermalState& s) { return s.choice_mode == ThermalState::ChoiceMode::kFollow; }

// Solves the pending batch of micro steps (multirate backward Euler) and clears it.
void SolveBatch(ThermalState& s);
// Advances the whole state by one backward-Euler step of `seconds` with no heat input.
void CoolStep(ThermalState& s, double seconds);

}  // namespace waam::twin::internal
