// ThermalSimulation: checks the settings, cuts the arc's path into micro steps and batches, and answers queries on
// the temperature field (the numerics are in thermal_solver.cc, the grid in thermal_grid.cc).
#include "twin/thermal/thermal_simulation.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "models/core/error.h"
#include "twin/thermal/thermal_state.h"

namespace waam::twin {

using internal::ThermalState;

namespace {

// Grid cells the solver accepts (5 bytes each for the grid's maps; the active cells cost about 200 bytes each).
constexpr double kMaxGridCells = 6.4e7;
constexpr double kSlack = 1e-9;

void CheckRange(bool ok, const char* name, double value, const char* rule) {
  WAAM_THROW_UNLESS(ok, "thermal setting " << name << " = " << value << ": " << rule);
}

void CheckBox(const Eigen::AlignedBox3d& box, const char* name) {
  const bool finite = box.min().allFinite() && box.max().allFinite();
  WAAM_THROW_UNLESS(finite && !box.isEmpty() && (box.sizes().array() > 0.0).all(),
                    "thermal setting " << name << " is empty or flat (min " << box.min().transpose() << ", max "
                                       << box.max().transpose() << " mm): it must have a positive size along x, y, z");
}

// Each clamp: a patch of positive size inside the plate's top face (x, y), with finite conductances >= 0.
void CheckClamps(const ThermalSettings& st) {
  const Eigen::AlignedBox2d top(st.substrate_box_mm.min().head<2>(), st.substrate_box_mm.max().head<2>());
  constexpr double kToleranceMm = 1e-6;
  for (std::size_t n = 0; n < st.clamps.size(); ++n) {
    const ClampPatch& c = st.clamps[n];
    const bool finite = c.xy_mm.min().allFinite() && c.xy_mm.max().allFinite();
    WAAM_THROW_UNLESS(finite && (c.xy_mm.sizes().array() > 0.0).all(),
                      "thermal setting clamps[" << n << "] is empty (min " << c.xy_mm.min().transpose() << ", max "
                                                << c.xy_mm.max().transpose() << " mm): it must have a positive size");
    const bool inside = (c.xy_mm.min().array() >= top.min().array() - kToleranceMm).all() &&
                        (c.xy_mm.max().array() <= top.max().array() + kToleranceMm).all();
    WAAM_THROW_UNLESS(inside, "thermal setting clamps[" << n << "] (x, y from " << c.xy_mm.min().transpose() << " to "
                                                        << c.xy_mm.max().transpose()
                                                        << " mm) reaches off the plate's top face (from "
                                                        << top.min().transpose() << " to " << top.max().transpose()
                                                        << " mm): a clamp's contact patch must lie on the plate");
    WAAM_THROW_UNLESS(std::isfinite(c.conductance_w_m2k) && c.conductance_w_m2k >= 0.0,
                      "thermal setting clamps[" << n << "].conductance_w_m2k = " << c.conductance_w_m2k
                                                << ": must be >= 0");
    WAAM_THROW_UNLESS(std::isfinite(c.under_conductance_w_m2k),
                      "thermal setting clamps[" << n << "].under_conductance_w_m2k = " << c.under_conductance_w_m2k
                                                << ": must be finite (< 0: the table's)");
  }
}

// One arc piece per micro step's travel (at most a cell) and per max_arc_step_s of time.
std::vector<internal::ArcPiece> CutIntoPieces(const ThermalState& s, const internal::ArcPiece& weld) {
  const double length = (weld.p1_mm - weld.p0_mm).norm();
  const double piece_mm = s.dx_mm * std::min(1.0, s.settings.arc_step_cells);
  const int by_length = static_cast<int>(std::ceil(length / piece_mm - kSlack));
  const int by_time = static_cast<int>(std::ceil(weld.seconds / s.settings.max_arc_step_s - kSlack));
  const int n = std::max({1, by_length, by_time});
  std::vector<internal::ArcPiece> pieces(n, weld);
  for (int i = 0; i < n; ++i) {
    pieces[i].p0_mm = weld.p0_mm + (weld.p1_mm - weld.p0_mm) * (static_cast<double>(i) / n);
    pieces[i].p1_mm = weld.p0_mm + (weld.p1_mm - weld.p0_mm) * (static_cast<double>(i + 1) / n);
    pieces[i].seconds = weld.seconds / n;
  }
  return pieces;
}

// Lays the pieces [first, last) as micro step `step` of the batch.
internal::ArcStep LayStep(ThermalState& s, std::size_t first, std::size_t last, int step) {
  internal::ArcStep arc;
  internal::BoundaryMean boundary;
  for (std::size_t p = first; p < last; ++p) {
    arc.seconds += s.pieces[p].seconds;
    boundary.Add(s.pieces[p].seconds, s.pieces[p].ambient_c, s.pieces[p].table_c);
  }
  arc.ambient_c = boundary.ambient_c();
  arc.table_c = boundary.table_c();
  for (std::size_t p = first; p < last; ++p) {
    const internal::ArcPiece& piece = s.pieces[p];
    if (piece.pause) continue;
    // The region of the micro steps follows the bead laid and the cells the source heats.
    Eigen::AlignedBox3d heated_mm;
    const std::vector<std::pair<int, double>> shares = internal::HeatPiece(s, piece, step, &heated_mm);
    const double half = 0.5 * std::max(piece.width_mm, s.dx_mm);
    Eigen::AlignedBox3d swept(piece.p0_mm);
    swept.extend(piece.p1_mm);
    swept.min() -= Eigen::Vector3d(half, half, piece.height_mm + s.dx_mm);
    swept.max() += Eigen::Vector3d(half, half, 0.0);
    arc.swept_mm.extend(swept);
    if (!heated_mm.isEmpty()) arc.swept_mm.extend(heated_mm);
    if (shares.empty() || piece.heat_w <= 0.0) continue;
    const double watts = piece.heat_w * piece.seconds / arc.seconds;
    for (const auto& [c, share] : shares) arc.heat_w.emplace_back(c, watts * share);
  }
  return arc;
}

// Solves the pending arc motion in batches of far_step_s (or of one micro step without multirate); with `flush`,
// solves all of it, else leaves what does not fill a batch of whole micro steps.
void Pump(ThermalState& s, bool flush) {
  const double micro_length = s.settings.arc_step_cells * s.dx_mm * (1.0 - kSlack);
  const double micro_time = s.settings.max_arc_step_s * (1.0 - kSlack);
  const double batch_time = s.level_step_s.front() * (1.0 - kSlack);
  while (!s.pieces.empty()) {
    std::vector<std::pair<std::size_t, std::size_t>> steps;
    std::size_t p = 0;
    double time = 0.0;
    while (p < s.pieces.size() && (steps.empty() || time < batch_time)) {
      std::size_t q = p;
      double length = 0.0, seconds = 0.0;
      if (s.pieces[q].pause) {
        seconds = s.pieces[q++].seconds;  // a pause is a micro step of its own
      } else {
        while (q < s.pieces.size() && !s.pieces[q].pause && length < micro_length && seconds < micro_time) {
          length += (s.pieces[q].p1_mm - s.pieces[q].p0_mm).norm();
          seconds += s.pieces[q].seconds;
          if (!s.pieces[q++].records.empty()) break;  // a probe record ends the micro step at its time
        }
      }
      const bool closed = s.pieces[p].pause || (q < s.pieces.size() && s.pieces[q].pause) || length >= micro_length ||
                          seconds >= micro_time || !s.pieces[q - 1].records.empty();
      if (!flush && !closed) break;  // an unfinished micro step
      steps.emplace_back(p, q);
      time += seconds;
      p = q;
    }
    if (steps.empty() || (!flush && time < batch_time)) return;
    for (std::size_t m = 0; m < steps.size(); ++m) {
      s.batch.push_back(LayStep(s, steps[m].first, steps[m].second, static_cast<int>(m)));
      for (int record : s.pieces[steps[m].second - 1].records) s.batch_marks.emplace_back(m + 1, record);
    }
    s.pieces.erase(s.pieces.begin(), s.pieces.begin() + static_cast<std::ptrdiff_t>(p));
    s.pieces_seconds = 0.0;
    for (const internal::ArcPiece& piece : s.pieces) s.pieces_seconds += piece.seconds;
    internal::SolveBatch(s);
  }
}

}  // namespace

Eigen::AlignedBox3d TableBoxMm(const ThermalSettings& st) {
  if (!(st.table_thickness_mm > 0.0)) return Eigen::AlignedBox3d();
  const Eigen::Vector3d margin(st.table_margin_mm, st.table_margin_mm, 0.0);
  Eigen::Vector3d lo = st.substrate_box_mm.min() - margin, hi = st.substrate_box_mm.max() + margin;
  hi.z() = st.substrate_box_mm.min().z();
  lo.z() = hi.z() - st.table_thickness_mm;
  return Eigen::AlignedBox3d(lo, hi);
}

double EnergyBalance::RelativeError() const {
  return input_j > 0.0 ? std::abs(input_j - stored_j - lost_j) / input_j : 0.0;
}

void CheckThermalSettings(const ThermalSettings& st) {
  internal::CheckThermalMaterial(st.deposit, "thermal deposit material");
  internal::CheckThermalMaterial(st.substrate, "thermal substrate material");
  CheckBox(st.substrate_box_mm, "substrate_box_mm");
  CheckBox(st.deposit_box_mm, "deposit_box_mm");
  CheckRange(std::isfinite(st.cell_mm) && st.cell_mm > 0.0, "cell_mm", st.cell_mm, "must be > 0");
  CheckRange(std::isfinite(st.table_thickness_mm) && st.table_thickness_mm >= 0.0, "table_thickness_mm",
             st.table_thickness_mm, "must be >= 0 (0: no table body)");
  CheckRange(std::isfinite(st.table_margin_mm) && st.table_margin_mm >= 0.0, "table_margin_mm", st.table_margin_mm,
             "must be >= 0");
  CheckRange(st.table_thickness_mm == 0.0 || st.table_conductance_w_m2k > 0.0, "table_conductance_w_m2k",
             st.table_conductance_w_m2k, "must be > 0 with a table body (table_thickness_mm > 0)");
  Eigen::AlignedBox3d all = st.substrate_box_mm;
  all.extend(st.deposit_box_mm);
  if (st.table_thickness_mm > 0.0) all.extend(TableBoxMm(st));
  const Eigen::Vector3d cells = all.sizes() / st.cell_mm + Eigen::Vector3d::Constant(2.0);
  CheckRange(cells.prod() <= kMaxGridCells, "cell_mm", st.cell_mm,
             "the grid over the plate and the deposit box would exceed 6.4e7 cells: use larger cells");
  CheckRange(std::isfinite(st.initial_c) && st.initial_c > -273.15, "initial_c", st.initial_c,
             "must be above absolute zero");
  CheckRange(std::isfinite(st.ambient_c) && st.ambient_c > -273.15, "ambient_c", st.ambient_c,
             "must be above absolute zero");
  CheckRange(std::isfinite(st.table_c) && st.table_c > -273.15, "table_c", st.table_c, "must be above absolute zero");
  CheckRange(std::isfinite(st.convection_w_m2k) && st.convection_w_m2k >= 0.0, "convection_w_m2k",
             st.convection_w_m2k, "must be >= 0");
  CheckRange(std::isfinite(st.emissivity) && st.emissivity <= 1.0, "emissivity", st.emissivity,
             "must be <= 1 (< 0: each material's own)");
  CheckRange(std::isfinite(st.table_conductance_w_m2k) && st.table_conductance_w_m2k >= 0.0,
             "table_conductance_w_m2k", st.table_conductance_w_m2k, "must be >= 0 (0: insulated)");
  CheckClamps(st);
  CheckRange(std::isfinite(st.arc_step_cells) && st.arc_step_cells > 0.0, "arc_step_cells", st.arc_step_cells,
             "must be > 0");
  CheckRange(std::isfinite(st.max_arc_step_s) && st.max_arc_step_s > 0.0, "max_arc_step_s", st.max_arc_step_s,
             "must be > 0");
  CheckRange(std::isfinite(st.far_step_s) && st.far_step_s >= 0.0, "far_step_s", st.far_step_s,
             "must be >= 0 (0: no multirate)");
  CheckRange(std::isfinite(st.whole_step_s) && st.whole_step_s >= 0.0, "whole_step_s", st.whole_step_s,
             "must be >= 0 (0: the whole model steps every far_step_s)");
  CheckRange(std::isfinite(st.whole_radius_mm) &&
                 (st.whole_step_s <= st.far_step_s || st.whole_radius_mm >= st.near_radius_mm),
             "whole_radius_mm", st.whole_radius_mm, "must be >= near_radius_mm");
  CheckRange(std::isfinite(st.near_step_s) && st.near_step_s >= 0.0, "near_step_s", st.near_step_s,
             "must be >= 0 (0: no middle level)");
  CheckRange(std::isfinite(st.arc_radius_mm) && st.arc_radius_mm >= 2.0 * st.cell_mm, "arc_radius_mm",
             st.arc_radius_mm, "must be >= 2 cell_mm");
  CheckRange(std::isfinite(st.near_radius_mm) && st.near_radius_mm >= st.arc_radius_mm, "near_radius_mm",
             st.near_radius_mm, "must be >= arc_radius_mm");
  CheckRange(std::isfinite(st.max_step_s) && st.max_step_s > 0.0, "max_step_s", st.max_step_s, "must be > 0");
  CheckRange(std::isfinite(st.step_growth) && st.step_growth >= 1.0, "step_growth", st.step_growth, "must be >= 1");
  CheckRange(std::isfinite(st.pool_depth_beads) && st.pool_depth_beads > 0.0, "pool_depth_beads",
             st.pool_depth_beads, "must be > 0");
  CheckRange(std::isfinite(st.pool_front_widths) && st.pool_front_widths > 0.0, "pool_front_widths",
             st.pool_front_widths, "must be > 0");
  CheckRange(std::isfinite(st.pool_rear_widths) && st.pool_rear_widths > 0.0, "pool_rear_widths",
             st.pool_rear_widths, "must be > 0");
  CheckRange(std::isfinite(st.liquid_conductivity_factor) && st.liquid_conductivity_factor >= 1.0,
             "liquid_conductivity_factor", st.liquid_conductivity_factor, "must be >= 1 (1: none)");
  CheckRange(std::isfinite(st.solver_tolerance_c) && st.solver_tolerance_c > 0.0, "solver_tolerance_c",
             st.solver_tolerance_c, "must be > 0");
}

struct ThermalSimulation::Impl {
  ThermalState s;
};

ThermalSimulation::ThermalSimulation(const ThermalSettings& settings) : impl_(std::make_unique<Impl>()) {
  CheckThermalSettings(settings);
  ThermalState& s = impl_->s;
  s.settings = settings;
  // Enthalpy tables every 1 K from below every start temperature to far above boiling; the deposit's enthalpy is 0
  // at the ambient temperature (a cell switches on there), the plate's at the initial temperature.
  const double low = std::min({settings.initial_c, settings.ambient_c, settings.table_c, 0.0}) - 100.0;
  for (int m = 0; m < 2; ++m) {
    const models::ThermalMaterial& material = m == internal::kDeposit ? settings.deposit : settings.substrate;
    const double high = std::max({4000.0, material.liquidus_c + 1500.0, material.temperature_c.back()});
    const double reference = m == internal::kDeposit ? settings.ambient_c : settings.initial_c;
    s.table[m] = internal::ThermalPropertyTable(material, low, high, 1.0, reference,
                                                settings.liquid_conductivity_factor);
    s.emissivity[m] = settings.emissivity >= 0.0 ? settings.emissivity : material.emissivity;
    s.reference_h[m] = 0.0;
    s.step_error_h[m] = internal::kStepErrorK * s.table[m].Capacity(reference);
  }
  if (settings.far_step_s > 0.0) {
    s.level_step_s = {settings.far_step_s};
    s.level_radius_mm = {std::numeric_limits<double>::infinity()};
    if (settings.whole_step_s > settings.far_step_s) {
      s.level_step_s = {settings.whole_step_s, settings.far_step_s};
      s.level_radius_mm.push_back(settings.whole_radius_mm);
    }
    if (settings.near_step_s > 0.0) {
      s.level_step_s.push_back(settings.near_step_s);
      s.level_radius_mm.push_back(settings.near_radius_mm);
    }
    s.level_step_s.push_back(0.0);
    s.level_radius_mm.push_back(settings.arc_radius_mm);
  } else {
    s.level_step_s = {0.0};
    s.level_radius_mm = {std::numeric_limits<double>::infinity()};
  }
  s.last_step_s = settings.max_arc_step_s;
  internal::InitialiseThermalState(s);
}

ThermalSimulation::~ThermalSimulation() = default;
ThermalSimulation::ThermalSimulation(ThermalSimulation&&) noexcept = default;
ThermalSimulation& ThermalSimulation::operator=(ThermalSimulation&&) noexcept = default;

void ThermalSimulation::Weld(const Eigen::Vector3d& p0_mm, const Eigen::Vector3d& p1_mm, double width_mm,
                             double height_mm, double heat_w, double seconds, const Eigen::Vector3d& travel) {
  WAAM_THROW_UNLESS(travel.allFinite(), "thermal weld: the travel direction is not finite");
  WAAM_THROW_UNLESS(p0_mm.allFinite() && p1_mm.allFinite(), "thermal weld: a path point is not finite");
  WAAM_THROW_UNLESS(std::isfinite(width_mm) && width_mm >= 0.0, "thermal weld width_mm = " << width_mm
                                                                                           << ": must be >= 0");
  WAAM_THROW_UNLESS(std::isfinite(height_mm) && height_mm >= 0.0, "thermal weld height_mm = " << height_mm
                                                                                             << ": must be >= 0");
  WAAM_THROW_UNLESS(std::isfinite(heat_w) && heat_w >= 0.0, "thermal weld heat_w = " << heat_w << ": must be >= 0");
  WAAM_THROW_UNLESS(std::isfinite(seconds) && seconds >= 0.0, "thermal weld seconds = " << seconds
                                                                                       << ": must be >= 0");
  if (seconds == 0.0) return;
  ThermalState& s = impl_->s;
  internal::ArcPiece weld{p0_mm, p1_mm, width_mm, height_mm, heat_w, seconds, false, travel.head<2>(), {}};
  weld.ambient_c = s.settings.ambient_c;
  weld.table_c = s.settings.table_c;
  for (const internal::ArcPiece& piece : CutIntoPieces(s, weld)) {
    s.pieces.push_back(piece);
    s.pieces_seconds += piece.seconds;
  }
  Pump(s, false);
}

void ThermalSimulation::Cool(double seconds) {
  WAAM_THROW_UNLESS(std::isfinite(seconds) && seconds >= 0.0, "thermal cool seconds = " << seconds
                                                                                       << ": must be >= 0");
  ThermalState& s = impl_->s;
  double left = seconds;
  if (s.settings.far_step_s > 0.0) {
    // With multirate, up to far_step_s of the pause joins the batch as micro steps growing from the last one, so
    // that short travel between beads does not cost whole-model steps.
    double step = s.pieces.empty() ? s.last_step_s : s.pieces.back().seconds;
    double queued = 0.0;
    while (left > 0.0 && queued < s.level_step_s.front()) {
      step = std::min({left, s.settings.max_step_s, step * s.settings.step_growth});
      if (left <= 1.25 * step) step = left;
      internal::ArcPiece pause;
      pause.p0_mm = pause.p1_mm = s.pieces.empty() ? Eigen::Vector3d::Zero() : s.pieces.back().p1_mm;
      pause.seconds = step;
      pause.pause = true;
      pause.ambient_c = s.settings.ambient_c;
      pause.table_c = s.settings.table_c;
      s.pieces.push_back(pause);
      s.pieces_seconds += step;
      queued += step;
      left -= step;
    }
    Pump(s, left > 0.0);
    if (left <= 0.0) return;
  }
  Pump(s, true);
  while (left > 0.0) {
    double dt = std::min({left, s.settings.max_step_s, s.last_step_s * s.settings.step_growth});
    if (left <= 1.25 * dt) dt = left;  // no sliver of a step at the end
    internal::CoolStep(s, dt);
    s.last_step_s = std::min(dt, s.settings.max_step_s);
    left -= dt;
  }
}

std::size_t ThermalSimulation::LayAtAmbient(const Eigen::AlignedBox3d& box_mm) {
  WAAM_THROW_UNLESS(box_mm.min().allFinite() && box_mm.max().allFinite(),
                    "thermal lay: the box (min " << box_mm.min().transpose() << ", max " << box_mm.max().transpose()
                                                 << " mm) is not finite");
  ThermalState& s = impl_->s;
  Pump(s, true);  // the cells switch on after the motion held back, present (born -1) from now on
  if (box_mm.isEmpty()) return 0;
  Eigen::Vector3i lo, hi;
  for (int a = 0; a < 3; ++a) {
    lo[a] = std::max(0, static_cast<int>(std::floor((box_mm.min()[a] - s.origin_mm[a]) / s.dx_mm - 0.5)));
    hi[a] = std::min(s.size[a] - 1, static_cast<int>(std::ceil((box_mm.max()[a] - s.origin_mm[a]) / s.dx_mm - 0.5)));
  }
  std::size_t laid = 0;
  for (int k = lo.z(); k <= hi.z(); ++k) {
    for (int j = lo.y(); j <= hi.y(); ++j) {
      for (int i = lo.x(); i <= hi.x(); ++i) {
        const int g = s.GridIndex(i, j, k);
        const Eigen::Vector3d c = s.Centre(i, j, k);
        const bool inside = (c.array() >= box_mm.min().array() - kSlack).all() &&
                            (c.array() <= box_mm.max().array() + kSlack).all();
        if (!inside || s.kind[g] != internal::CellKind::kDeposit || s.active_of[g] != internal::kNoCell) continue;
        s.Activate(g, internal::kDeposit, s.reference_h[internal::kDeposit], -1);
        ++laid;
      }
    }
  }
  return laid;
}

void ThermalSimulation::SetBoundaryTemperatures(double ambient_c, double table_c) {
  WAAM_THROW_UNLESS(std::isfinite(ambient_c) && ambient_c > -273.15,
                    "thermal ambient_c = " << ambient_c << ": must be above absolute zero");
  WAAM_THROW_UNLESS(std::isfinite(table_c) && table_c > -273.15,
                    "thermal table_c = " << table_c << ": must be above absolute zero");
  // The motion held back keeps the temperatures it was queued under; what follows takes these (each piece carries
  // its own, so the batch goes on: docs/THERMAL.md, "Boundary temperatures that change").
  ThermalState& s = impl_->s;
  s.settings.ambient_c = ambient_c;
  s.settings.table_c = table_c;
}

double ThermalSimulation::time_s() const { return impl_->s.time_s + impl_->s.pieces_seconds; }

// The queries first solve the arc motion held back for the next batch, so that they see the state at time_s().
double ThermalSimulation::TemperatureAt(const Eigen::Vector3d& p_mm) const {
  ThermalState& s = impl_->s;
  Pump(s, true);
  const int cell = internal::ProbeCell(s, p_mm, std::numeric_limits<int>::max());
  return cell == internal::kNoCell ? std::numeric_limits<double>::quiet_NaN() : s.temperature[cell];
}

std::size_t ThermalSimulation::AddProbe(const Eigen::Vector3d& p_mm) {
  WAAM_THROW_UNLESS(p_mm.allFinite(), "thermal probe: the point is not finite");
  ThermalState& s = impl_->s;
  WAAM_THROW_UNLESS(s.records.empty(), "thermal probe: probes must be added before the first RecordProbes");
  s.probe_mm.push_back(p_mm);
  return s.probe_mm.size() - 1;
}

std::size_t ThermalSimulation::RecordProbes() {
  ThermalState& s = impl_->s;
  const int record = static_cast<int>(s.records.size());
  s.records.emplace_back(s.probe_mm.size(), std::numeric_limits<double>::quiet_NaN());
  s.record_done.push_back(0);
  if (!s.pieces.empty()) {
    s.pieces.back().records.push_back(record);  // filled when the batch holding that time is solved
    return static_cast<std::size_t>(record);
  }
  for (std::size_t p = 0; p < s.probe_mm.size(); ++p) {
    const int cell = internal::ProbeCell(s, s.probe_mm[p], std::numeric_limits<int>::max());
    if (cell != internal::kNoCell) s.records[record][p] = s.temperature[cell];
  }
  s.record_done[record] = 1;
  return static_cast<std::size_t>(record);
}

std::vector<double> ThermalSimulation::ProbeRecord(std::size_t index) const {
  ThermalState& s = impl_->s;
  WAAM_THROW_UNLESS(index < s.records.size(), "thermal probe record " << index << ": only " << s.records.size()
                                                                      << " were recorded");
  if (!s.record_done[index]) Pump(s, true);
  WAAM_DEMAND(s.record_done[index]);
  return s.records[index];
}

bool ThermalSimulation::ProbeRecordSolved(std::size_t index) const {
  const ThermalState& s = impl_->s;
  WAAM_THROW_UNLESS(index < s.records.size(), "thermal probe record " << index << ": only " << s.records.size()
                                                                      << " were recorded");
  return s.record_done[index] != 0;
}

double ThermalSimulation::MaxTemperatureIn(const Eigen::AlignedBox3d& box_mm) const {
  ThermalState& s = impl_->s;
  Pump(s, true);
  double hottest = std::numeric_limits<double>::quiet_NaN();
  if (box_mm.isEmpty()) return hottest;
  Eigen::Vector3i lo, hi;
  for (int a = 0; a < 3; ++a) {
    lo[a] = std::max(0, static_cast<int>(std::floor((box_mm.min()[a] - s.origin_mm[a]) / s.dx_mm)));
    hi[a] = std::min(s.size[a] - 1, static_cast<int>(std::floor((box_mm.max()[a] - s.origin_mm[a]) / s.dx_mm)));
  }
  // Every cell the box touches.
  for (int k = lo.z(); k <= hi.z(); ++k) {
    for (int j = lo.y(); j <= hi.y(); ++j) {
      for (int i = lo.x(); i <= hi.x(); ++i) {
        const int id = s.active_of[s.GridIndex(i, j, k)];
        if (id == internal::kNoCell) continue;
        if (!(s.temperature[id] <= hottest)) hottest = s.temperature[id];
      }
    }
  }
  return hottest;
}

EnergyBalance ThermalSimulation::Energy() const {
  ThermalState& s = impl_->s;
  Pump(s, true);
  EnergyBalance e = s.energy;
  e.stored_j = 0.0;
  for (std::size_t c = 0; c < s.enthalpy.size(); ++c) e.stored_j += s.enthalpy[c] - s.reference_h[s.material[c]];
  e.stored_j = e.stored_j * s.CellVolume() - s.start_enthalpy_j;
  e.lost_j = e.convection_j + e.radiation_j + e.table_j;
  return e;
}

void ThermalSimulation::RecordChoices() {
  ThermalState& s = impl_->s;
  s.choice_mode = ThermalState::ChoiceMode::kRecord;
  s.recorded.values.clear();
}

SolverChoices ThermalSimulation::TakeChoices() {
  ThermalState& s = impl_->s;
  SolverChoices choices = std::move(s.recorded);
  s.recorded.values.clear();
  s.choice_mode = ThermalState::ChoiceMode::kFree;
  return choices;
}

void ThermalSimulation::FollowChoices(std::shared_ptr<const SolverChoices> choices) {
  WAAM_DEMAND(choices != nullptr);
  ThermalState& s = impl_->s;
  s.choice_mode = ThermalState::ChoiceMode::kFollow;
  s.followed = std::move(choices);
  s.followed_at = 0;
}

ThermalStats ThermalSimulation::Stats() const {
  ThermalState& s = impl_->s;
  Pump(s, true);
  ThermalStats stats = s.stats;
  stats.cells = s.kind.size();
  stats.active_cells = s.grid_of.size();
  return stats;
}

TemperatureField ThermalSimulation::Field() const {
  ThermalState& s = impl_->s;
  Pump(s, true);
  TemperatureField field;
  field.origin_mm = s.origin_mm;
  field.cell_mm = s.dx_mm;
  field.size = s.size;
  field.temperature_c.assign(s.kind.size(), std::numeric_limits<float>::quiet_NaN());
  for (std::size_t c = 0; c < s.grid_of.size(); ++c) {
    field.temperature_c[s.grid_of[c]] = static_cast<float>(s.temperature[c]);
  }
  return field;
}

}  // namespace waam::twin
