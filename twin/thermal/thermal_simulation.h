// Transient heat conduction in a WAAM deposit and its substrate plate: material switched on as it is laid, arc heat
// spread over the bead of each step, losses by convection and radiation and into the table (issue "Time and heat").
// The solver computes on data (no file is read here): materials come loaded (models/thermal/material.h).
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "models/thermal/material.h"
#include "twin/thermal/heat_source.h"

namespace waam::twin {

// A clamp on the plate: a contact patch on the plate's top face through which heat flows into the clamp, a steel
// mass bolted to the table and taken at the table's temperature (docs/THERMAL.md "Clamps"). Where the clamp presses
// the plate onto the table, the plate's bottom under the patch may take its own table contact.
struct ClampPatch {
  Eigen::AlignedBox2d xy_mm;               // the patch on the plate's top face, part frame x and y, mm
  double conductance_w_m2k = 0.0;          // plate top to the clamp (at table_c), W/(m^2 K)
  double under_conductance_w_m2k = -1.0;   // plate bottom under the patch to the table; < 0 = table_conductance
};

// Everything the solver needs, resolved (lengths in mm, temperatures in degC, SI otherwise).
struct ThermalSettings {
  models::ThermalMaterial deposit;          // the wire's metal
  models::ThermalMaterial substrate;        // the plate's metal
  Eigen::AlignedBox3d substrate_box_mm;     // the plate in the part frame; its top is usually z = 0
  Eigen::AlignedBox3d deposit_box_mm;       // where the deposit may grow (the part's bounds plus a margin)
  double cell_mm = 2.0;                     // grid spacing near the deposit, mm
  double initial_c = 20.0;                  // plate temperature at t = 0, degC
  double ambient_c = 20.0;                  // air temperature for convection and radiation, degC
  double convection_w_m2k = 10.0;           // h on every exposed face, W/(m^2 K)
  double emissivity = -1.0;                 // < 0: each material's own; else this for every exposed face
  // Contact with the table under the plate's bottom face; conductance 0 = an insulated bottom (losses by convection
  // and radiation there instead).
  double table_conductance_w_m2k = 0.0;     // W/(m^2 K)
  double table_c = 20.0;                    // table temperature, degC
  // The table as a body (docs/THERMAL.md "The table as a body"): with table_thickness_mm > 0, a slab of the plate's
  // material that thick lies under the plate, reaching table_margin_mm beyond it on every side and starting at
  // table_c; the plate's bottom conducts into it through table_conductance_w_m2k (under a clamp: the clamp's
  // under_conductance_w_m2k) in series with the two half cells, and the slab's other faces lose by convection and
  // radiation. 0 = no body: the plate's bottom loses to a table held at table_c.
  double table_thickness_mm = 0.0;          // mm, >= 0
  double table_margin_mm = 0.0;             // mm, >= 0
  // Clamps on the plate's top face, each inside the plate's top face (x and y); a face partly under a patch loses
  // through the patch in proportion to the area covered, and by convection and radiation through the rest.
  std::vector<ClampPatch> clamps;

  // The arc's heat source (docs/THERMAL.md, "Heat source and activation"). The double ellipsoid's semi-axes follow
  // each bead: a = width / 2, b = pool_depth_beads x height, c_f = pool_front_widths x width, c_r =
  // pool_rear_widths x width (Goldak et al. 1984: "one half the weld width" ahead and "two times the weld width"
  // behind when no measured pool is at hand).
  HeatSourceShape heat_source = HeatSourceShape::kDoubleEllipsoid;
  double pool_depth_beads = 2.0;            // b over the bead height: the new bead and the layer below it
  double pool_front_widths = 0.5;           // c_f over the bead width
  double pool_rear_widths = 2.0;            // c_r over the bead width
  // The liquid's conductivity is multiplied by this above the liquidus, ramped from 1 across the mushy zone: the
  // heat the pool's stirring carries, which conduction alone lacks (Goldak et al. 1986, Metall. Trans. B 17B 587);
  // 1 = none.
  double liquid_conductivity_factor = 5.0;

  // Time stepping and the solver (docs/THERMAL.md). While the arc burns, each micro step moves it arc_step_cells
  // cells (and lasts at most max_arc_step_s). Multirate: the whole model steps every far_step_s, the cells within
  // near_radius_mm of the arc's path every near_step_s, and the cells within arc_radius_mm every micro step; cells whose
  // enthalpy changes fast join the finer levels wherever they are.
  // far_step_s = 0 solves the whole model at every micro step (no multirate); near_step_s = 0 drops the middle level.
  double arc_step_cells = 1.0;              // arc travel per micro step, cells
  double max_arc_step_s = 0.5;              // longest micro step (a slow or standing arc), s
  double far_step_s = 8.0;                  // step of the whole model while welding, s
  // A coarser top level: when whole_step_s > far_step_s, the whole model steps every whole_step_s and the far_step_s
  // level covers the cells within whole_radius_mm of the beads laid in a whole step (and the fast-changing cells).
  double whole_step_s = 32.0;               // s; 0 (or <= far_step_s): no such level
  double whole_radius_mm = 48.0;            // mm, >= near_radius_mm
  double near_step_s = 1.0;                 // step of the region near the arc, s
  double near_radius_mm = 16.0;             // that region's reach from the bead laid in a far step, mm
  double arc_radius_mm = 12.0;              // reach of the micro steps' region from the bead laid in a near step, mm
  double max_step_s = 10.0;                 // longest step while no arc burns, s
  double step_growth = 1.5;                 // each step with no arc at most this times the previous one
  // CG stops when every Jacobi correction is below this, K. Tighter than the accuracy a step needs: a run that follows
  // another's solver choices repeats its iteration counts, and the residual left at 0.01 K grew from step to step in
  // the melt pool of such runs (docs/THERMAL.md, "Differencing a run").
  double solver_tolerance_c = 0.001;
};

// The table body's box in the part frame, mm: under the plate, table_margin_mm wider on every side, table_thickness_mm
// thick; empty without a table body (table_thickness_mm = 0). On the grid its top is the plate's lowest cell face.
Eigen::AlignedBox3d TableBoxMm(const ThermalSettings& settings);

// Throws InputError naming the first setting out of its range (e.g. "thermal setting cell_mm = 0: must be > 0"),
// or a material table that is not a function of temperature or has a value <= 0.
void CheckThermalSettings(const ThermalSettings& settings);

// Energy accounts since t = 0, J. input_j = stored_j + lost_j up to the solver's truncation error.
struct EnergyBalance {
  double input_j = 0.0;        // heat put into the metal by the arc (efficiency already applied by the caller)
  double stored_j = 0.0;       // change of enthalpy of every active cell (latent heat included), incl. the heat a cell
                               // brings when switched on at its activation temperature
  double lost_j = 0.0;         // convection + radiation + table
  double convection_j = 0.0;
  double radiation_j = 0.0;
  double table_j = 0.0;         // into the table, through the plate's bottom and the clamps
  double RelativeError() const;  // |input - stored - lost| / input (0 when input is 0)
};

// Solver statistics for thermal.json.
struct ThermalStats {
  std::size_t cells = 0;          // grid cells (active or not)
  std::size_t active_cells = 0;
  std::size_t steps = 0;          // time steps taken
  std::size_t iterations = 0;     // linear-solver iterations, summed (0 for an explicit method)
  // Per multirate level (0: the whole model, then finer): linear systems solved (predictor, corrector and chord
  // re-solves each count) and their cells summed over those solves (cell-solves), and CG iterations.
  std::vector<std::size_t> level_solves, level_cell_solves, level_iterations;
  // Level steps whose finer levels and corrector ran again over a larger finer region, the corrector having left
  // cells outside the maximum principle's bounds (docs/THERMAL.md, "Why the coupling between levels is monotone").
  std::size_t coupling_retries = 0;
  // Cells a level's step left outside those bounds (within the step's accuracy, or after its retry) and repaired:
  // set to the bound, the energy from the cells around them (Shashkov & Wendroff 2004; docs/THERMAL.md).
  std::size_t coupling_repairs = 0;
  // Cells a level's predictor left off the enthalpy curve after its first solve and moved to its finer levels
  // instead of solving the level's region again (docs/THERMAL.md, "Discretisation").
  std::size_t unconverged_cells = 0;
};

// The solver's discrete choices over a run, in the order it made them (docs/THERMAL.md, "Differencing a run"):
// which cells take a coarser level's finer steps, which level steps re-run their finer levels, which cells the
// enthalpy iteration restarts at their local balance and in which round it stops, and each linear solve's
// preconditioner and iteration count. These switch on thresholds, so a run's temperatures jump where a parameter
// moves a value across one; a run that follows another's choices makes none of its own and its temperatures are a
// continuous function of the heat input and the boundary coefficients (what a fit's differences need).
struct SolverChoices {
  std::vector<int> values;  // counts and cell lists, in the order the solver made them
};

// The temperature field on the solver's grid (for thermal.h5 and the pictures): cell (i, j, k) is centred at
// origin_mm + (i + 1/2, j + 1/2, k + 1/2) cell_mm; NaN where no metal is.
struct TemperatureField {
  Eigen::Vector3d origin_mm = Eigen::Vector3d::Zero();
  double cell_mm = 0.0;
  Eigen::Vector3i size = Eigen::Vector3i::Zero();  // cells along x, y, z
  std::vector<float> temperature_c;                // x fastest, then y, then z
};

// The state of one thermal simulation, advanced step by step by its caller (the build's timeline drives it).
class ThermalSimulation {
 public:
  // Throws InputError for settings out of their range (naming the setting).
  explicit ThermalSimulation(const ThermalSettings& settings);
  ~ThermalSimulation();
  ThermalSimulation(ThermalSimulation&&) noexcept;
  ThermalSimulation& operator=(ThermalSimulation&&) noexcept;

  // Moves the arc from p0 to p1 (part frame, mm) over `seconds`, switching on the bead of width x height (mm)
  // laid along it and putting `heat_w` (W, the arc power times its efficiency) into it. `travel` (need not be unit)
  // orients the pool of a standing arc (p0 = p1 in x and y: arc start and end) as the pass's pool; zero: a round
  // pool. Throws InputError for a non-finite point or a negative size, heat or time.
  void Weld(const Eigen::Vector3d& p0_mm, const Eigen::Vector3d& p1_mm, double width_mm, double height_mm,
            double heat_w, double seconds, const Eigen::Vector3d& travel = Eigen::Vector3d::Zero());
  // Advances `seconds` with no heat input (travel, waits).
  void Cool(double seconds);
  // Switches on, at time_s() and with no heat, the deposit cells (those of deposit_box_mm) whose centres lie in box_mm,
  // at the ambient temperature (where a laid bead's cells start): metal already standing when the clock starts, laid
  // without solving the micro steps a zero-heat Weld along it would take. Solves the arc motion held back first;
  // returns the number of cells switched on. Throws InputError for a box that is not finite.
  std::size_t LayAtAmbient(const Eigen::AlignedBox3d& box_mm);
  // Sets the air temperature (convection, radiation) and the table's (and clamps') temperature from time_s() on, degC
  // (a measured ambient drives the losses), without ending the solver's batch: the motion held back keeps the values
  // it was queued under, and a step spanning several values uses their time means. Deposit cells still switch on at
  // the ambient temperature the simulation was built with. Throws InputError unless both are finite and above absolute zero.
  void SetBoundaryTemperatures(double ambient_c, double table_c);

  double time_s() const;
  // Temperature at a point of the metal (plate or deposit), degC; NaN where no metal is (yet).
  double TemperatureAt(const Eigen::Vector3d& p_mm) const;
  // Highest temperature of the metal inside `box` (mm), degC; NaN when the box holds no metal.
  double MaxTemperatureIn(const Eigen::AlignedBox3d& box_mm) const;
  // Probes recorded without ending the solver's batch (a TemperatureAt query solves the arc motion held back, so
  // querying every second makes every batch one second long). AddProbe registers a point (part frame, mm) and
  // returns its index; every probe must be added before the first RecordProbes. Throws InputError for a non-finite
  // point or a probe added after a record.
  std::size_t AddProbe(const Eigen::Vector3d& p_mm);
  // Records every probe's temperature at time_s() and returns the record's index. The value is that of the cell
  // TemperatureAt would read at that time, from the multirate level that solves the cell then: exact where micro
  // steps run, else linear in time over that level's step (as finer levels see coarser ones). Throws nothing.
  std::size_t RecordProbes();
  // The probes' temperatures of record `index` (degC by probe, NaN where no metal was), solving the arc motion held
  // back first if the record is not filled yet. Throws InputError for an index RecordProbes did not return.
  std::vector<double> ProbeRecord(std::size_t index) const;
  // Whether record `index` is filled already (its batch solved), without solving anything. Throws InputError for an
  // index RecordProbes did not return.
  bool ProbeRecordSolved(std::size_t index) const;
  // From now on the solver appends every choice it makes to a record (call before the first Weld or Cool);
  // TakeChoices returns the choices of the steps solved so far (the motion held back is not: a query such as
  // ProbeRecord solves it) and ends the recording.
  void RecordChoices();
  SolverChoices TakeChoices();
  // From now on the solver makes the choices of `choices` instead of its own, in order: the run must be driven as the
  // recorded one was (the same settings but for the heat input and the boundary coefficients, and the same calls with
  // the same arguments but for the heat). Throws InputError when the record runs out or does not fit the cells.
  void FollowChoices(std::shared_ptr<const SolverChoices> choices);
  EnergyBalance Energy() const;
  ThermalStats Stats() const;
  TemperatureField Field() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace waam::twin
