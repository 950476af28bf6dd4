// The thermal run: the timeline's spans drive twin::ThermalSimulation, with interpass waits and recorded histories.
#include "analysis/thermal_run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

#include "models/core/error.h"
#include "models/core/progress.h"

namespace waam::analysis {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The box every bead of the plan fills: each weld point's bead hangs below its TCP by the bead height along the
// layer's build direction and spreads half its width around it.
Eigen::AlignedBox3d BeadBounds(const planner::Plan& plan) {
  Eigen::AlignedBox3d box;
  for (const planner::LayerPath& layer : plan.layers) {
    for (std::size_t i = 0; i < layer.points.size(); ++i) {
      const planner::PathPoint& p = layer.points[i];
      const bool welded = p.weld || (i + 1 < layer.points.size() && layer.points[i + 1].weld);
      if (!welded) continue;
      // Half a bead width across the build direction, the bead height below the TCP along it.
      const double half = 0.5 * std::max(p.bead_width_mm, 0.0);
      const Eigen::Vector3d& d = layer.build_dir_P;
      for (int axis = 0; axis < 3; ++axis) {
        const Eigen::Vector3d across = Eigen::Vector3d::Unit(axis) - d[axis] * d;
        box.extend(p.p_P + half * across);
        box.extend(p.p_P - half * across);
      }
      box.extend(p.p_P - p.bead_height_mm * d);
    }
  }
  return box;
}

std::string BoxText(const Eigen::AlignedBox3d& box) {
  std::ostringstream s;
  s << "[" << box.min().x() << ", " << box.min().y() << ", " << box.min().z() << "] .. [" << box.max().x() << ", "
    << box.max().y() << ", " << box.max().z() << "] mm";
  return s.str();
}

}  // namespace

twin::ThermalSettings ThermalSettingsFor(const Scenario& scenario, const planner::Plan& plan) {
  const ThermalSection& thermal = scenario.thermal;
  WAAM_THROW_UNLESS(thermal.given, scenario.file.string() << ": the scenario has no thermal: section "
                                                             "(docs/THERMAL.md)");
  const Eigen::AlignedBox3d beads = BeadBounds(plan);
  WAAM_THROW_UNLESS(!beads.isEmpty(), scenario.file.string() << ": the plan has no weld move: nothing to heat");
  twin::ThermalSettings s = SectionSettings(thermal, beads);
  for (const ThermalProbe& probe : thermal.probes) CheckProbeInMetal(s, probe.p_mm, probe.where);
  return s;
}

twin::ThermalSettings SectionSettings(const ThermalSection& thermal, const Eigen::AlignedBox3d& beads) {
  twin::ThermalSettings s;
  s.deposit = thermal.deposit.material;
  s.substrate = thermal.substrate.material;
  s.cell_mm = thermal.cell_mm;
  s.initial_c = thermal.InitialC();
  s.ambient_c = thermal.ambient_c;
  s.convection_w_m2k = thermal.convection_w_m2k;
  s.emissivity = thermal.Emissivity();
  s.table_conductance_w_m2k = thermal.table_conductance_w_m2k;
  s.table_thickness_mm = thermal.table_thickness_mm;
  s.table_margin_mm = thermal.table_margin_mm;
  s.table_c = thermal.TableC();
  s.heat_source = thermal.heat_source;
  s.pool_depth_beads = thermal.pool_depth_beads;
  s.pool_front_widths = thermal.pool_front_widths;
  s.pool_rear_widths = thermal.pool_rear_widths;
  s.liquid_conductivity_factor = thermal.liquid_conductivity_factor;
  s.substrate_box_mm = SubstrateBoxMm(thermal, beads);
  s.clamps = ClampPatches(thermal, s.substrate_box_mm);
  // The deposit may grow one cell beyond its beads (the solver snaps beads to its cells).
  const Eigen::Vector3d cell = Eigen::Vector3d::Constant(thermal.cell_mm);
  s.deposit_box_mm = Eigen::AlignedBox3d(beads.min() - cell, beads.max() + cell);
  return s;
}

void CheckProbeInMetal(const twin::ThermalSettings& settings, const Eigen::Vector3d& p_mm, const std::string& where) {
  const Eigen::AlignedBox3d table = twin::TableBoxMm(settings);
  WAAM_THROW_UNLESS(settings.substrate_box_mm.contains(p_mm) || settings.deposit_box_mm.contains(p_mm) ||
                        table.contains(p_mm),
                    where << " = [" << p_mm.x() << ", " << p_mm.y() << ", " << p_mm.z() << "]: outside the plate "
                          << BoxText(settings.substrate_box_mm) << " and the part " << BoxText(settings.deposit_box_mm)
                          << (table.isEmpty() ? "" : " and the table " + BoxText(table))
                          << "; a probe must lie in the metal");
}

namespace {

// Steps the simulation along the timeline and records what thermal.json and thermal.h5 report.
class ThermalDriver {
 public:
  ThermalDriver(const Scenario& scenario, const planner::Plan& plan, const twin::ThermalSettings& settings,
                ThermalRunResult* out)
      : scenario_(scenario), plan_(plan), sim_(settings), out_(out), sample_s_(scenario.thermal.sample_s) {
    everything_ = settings.substrate_box_mm;
    everything_.extend(settings.deposit_box_mm);
    heat_w_ = scenario.process.arc.HeatW();
    for (const ThermalProbe& probe : scenario.thermal.probes) {
      out_->probes.push_back({probe.name, probe.p_mm, {}, kNaN, 0.0});
    }
    Sample();  // t = 0
  }

  // Runs every span; returns the interpass wait added before each layer.
  std::vector<double> Run(const planner::Timeline& timeline, Progress* progress);

  twin::ThermalSimulation& sim() { return sim_; }

 private:
  void Sample();
  // Advances `seconds` with the arc going from a to b (weld) or not (cool), sampling on the way.
  // `travel` orients a standing arc's pool (a = b).
  void Advance(double seconds, bool weld, const Eigen::Vector3d& a, const Eigen::Vector3d& b, double width_mm,
               double height_mm, const Eigen::Vector3d& travel = Eigen::Vector3d::Zero());
  void RunSpan(const planner::TimedSpan& span);
  // The temperature process.interpass.at names, before `layer` starts at `start_P`.
  double InterpassTemperature(int layer, const Eigen::Vector3d& start_P) const;
  double WaitForInterpass(int layer, const Eigen::Vector3d& start_P, ThermalLayer* record);

  const Scenario& scenario_;
  const planner::Plan& plan_;
  twin::ThermalSimulation sim_;
  ThermalRunResult* out_;
  double sample_s_;
  long long samples_ = 0;              // samples taken; the next is due at samples_ x sample_s_
  double heat_w_ = 0.0;
  Eigen::AlignedBox3d everything_;
  int current_layer_ = -1;             // the layer whose arc burnt last (for peak_c)
  std::vector<double> laid_on_sum_;    // per layer: sum and count of the metal temperatures under its weld moves
  std::vector<int> laid_on_n_;
  bool in_layer_ = false;              // between a layer's first arc start and its last arc end
};

void ThermalDriver::Sample() {
  const double t = sim_.time_s();
  out_->sample_time_s.push_back(t);
  for (ThermalProbeHistory& probe : out_->probes) {
    const double value = sim_.TemperatureAt(probe.p_mm);
    probe.temperature_c.push_back(value);
    if (!std::isnan(value) && (std::isnan(probe.max_c) || value > probe.max_c)) {
      probe.max_c = value;
      probe.time_of_max_s = t;
    }
  }
  if (in_layer_ && current_layer_ >= 0) {
    const double hottest = sim_.MaxTemperatureIn(everything_);
    double& peak = out_->layers[current_layer_].peak_c;
    if (!std::isnan(hottest) && (std::isnan(peak) || hottest > peak)) peak = hottest;
  }
  ++samples_;
}

void ThermalDriver::Advance(double seconds, bool weld, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                            double width_mm, double height_mm, const Eigen::Vector3d& travel) {
  const double eps = 1e-9 * std::max(1.0, seconds);
  double done = 0.0;
  while (seconds - done > eps) {
    const double due = static_cast<double>(samples_) * sample_s_ - sim_.time_s();
    if (due <= eps) {
      Sample();
      continue;
    }
    const double step = std::min(seconds - done, due);
    if (weld) {
      const Eigen::Vector3d p0 = a + (b - a) * (done / seconds);
      const Eigen::Vector3d p1 = a + (b - a) * ((done + step) / seconds);
      sim_.Weld(p0, p1, width_mm, height_mm, heat_w_, step, travel);
    } else {
      sim_.Cool(step);
    }
    done += step;
    CheckInterrupt();
  }
  if (static_cast<double>(samples_) * sample_s_ - sim_.time_s() <= eps) Sample();
}

void ThermalDriver::RunSpan(const planner::TimedSpan& span) {
  const double seconds = span.end_s - span.start_s;
  if (seconds <= 0.0) return;
  const planner::LayerPath& layer = plan_.layers[span.layer];
  const std::size_t n = layer.points.size();
  WAAM_DEMAND(span.point < n);
  const planner::PathPoint& at = layer.points[span.point];
  switch (span.kind) {
    case planner::SpanKind::kArcOn: {
      // The metal the move lays its bead on, just before: the first metal found one cell below the new bead's bottom
      // (nearer, the cell the arc heats right now); the grid resolves no less.
      if (span.layer > 0) {
        const double cell = scenario_.thermal.cell_mm;
        const double height = std::max(0.5, at.bead_height_mm);
        for (double d = height + cell; d <= 3.0 * height + 3.0 * cell; d += 0.25 * cell) {
          const double t = sim_.TemperatureAt(at.p_P - d * layer.build_dir_P);
          if (std::isnan(t)) continue;
          laid_on_sum_[span.layer] += t;
          laid_on_n_[span.layer] += 1;
          break;
        }
      }
      // A continuous spiral carries its weld from one layer into the next: the move into a layer's first point
      // starts at the previous layer's last point.
      WAAM_DEMAND(span.point > 0 || (span.layer > 0 && !plan_.layers[span.layer - 1].points.empty()));
      const Eigen::Vector3d& from =
          span.point > 0 ? layer.points[span.point - 1].p_P : plan_.layers[span.layer - 1].points.back().p_P;
      Advance(seconds, true, from, at.p_P, at.bead_width_mm, at.bead_height_mm);
      out_->arc_energy_j += scenario_.process.arc.power_w * seconds;
      break;
    }
    case planner::SpanKind::kArcStart:
    case planner::SpanKind::kArcEnd: {
      // The arc burns where the torch stands: a weld of zero length, with the bead of the nearest weld move, its
      // heat spread over that move's pool (oriented along the move).
      std::size_t w = span.point;
      if (span.kind == planner::SpanKind::kArcStart) {
        while (w + 1 < n && !layer.points[w].weld) ++w;
      } else {
        while (w > 0 && !layer.points[w].weld) --w;
      }
      const planner::PathPoint& bead = layer.points[w];
      const Eigen::Vector3d travel = w > 0 ? Eigen::Vector3d(bead.p_P - layer.points[w - 1].p_P)
                                           : Eigen::Vector3d::Zero();
      Advance(seconds, true, at.p_P, at.p_P, bead.bead_width_mm, bead.bead_height_mm, travel);
      out_->arc_energy_j += scenario_.process.arc.power_w * seconds;
      break;
    }
    case planner::SpanKind::kTravel:
    case planner::SpanKind::kPositioner:
    case planner::SpanKind::kWait:
      Advance(seconds, false, at.p_P, at.p_P, 0.0, 0.0);
      break;
  }
}

double ThermalDriver::InterpassTemperature(int layer, const Eigen::Vector3d& start_P) const {
  const planner::InterpassSettings& rule = scenario_.process.interpass;
  const double cell = scenario_.thermal.cell_mm;
  switch (rule.at) {
    case planner::InterpassAt::kProbe:
      for (const ThermalProbe& probe : scenario_.thermal.probes) {
        if (probe.name == rule.probe) return sim_.TemperatureAt(probe.p_mm);
      }
      return kNaN;
    case planner::InterpassAt::kTopMax: {
      // The previous layer's beads: every weld point and the bead below it, widened by half a bead and a cell.
      if (layer == 0) return kNaN;
      const planner::LayerPath& below = plan_.layers[layer - 1];
      Eigen::AlignedBox3d box;
      for (const planner::PathPoint& p : below.points) {
        if (!p.weld) continue;
        const Eigen::Vector3d half = Eigen::Vector3d::Constant(0.5 * p.bead_width_mm + cell);
        box.extend(p.p_P + half);
        box.extend(p.p_P - p.bead_height_mm * below.build_dir_P - half);
      }
      return box.isEmpty() ? kNaN : sim_.MaxTemperatureIn(box);
    }
    case planner::InterpassAt::kNextStart: {
      // The metal under the arc start: the first metal found going down from the TCP along the build direction.
      const planner::LayerPath& next = plan_.layers[layer];
      const double height = std::max(0.5, next.points.empty() ? 0.0 : next.points.front().bead_height_mm);
      for (double d = 0.0; d <= 3.0 * height + 2.0 * cell; d += 0.25 * cell) {
        const double t = sim_.TemperatureAt(start_P - d * next.build_dir_P);
        if (!std::isnan(t)) return t;
      }
      return kNaN;
    }
  }
  return kNaN;
}

double ThermalDriver::WaitForInterpass(int layer, const Eigen::Vector3d& start_P, ThermalLayer* record) {
  const planner::InterpassSettings& rule = scenario_.process.interpass;
  double t = InterpassTemperature(layer, start_P);
  double waited = 0.0;
  if (layer > 0 && rule.HasMax()) {
    // Cool in steps of whole sample intervals: half the time a straight-line extrapolation of the last step
    // predicts (cooling slows down, so this does not overshoot by more than one interval), at most 60 s.
    double step = sample_s_;
    while (!std::isnan(t) && t > rule.max_c && waited < kMaxInterpassWaitS) {
      const double before = t;
      Advance(step, false, start_P, start_P, 0.0, 0.0);
      waited += step;
      t = InterpassTemperature(layer, start_P);
      const double rate = (before - t) / step;
      const double predicted = rate > 0.0 ? (t - rule.max_c) / rate : sample_s_;
      step = sample_s_ * std::clamp(std::floor(0.5 * predicted / sample_s_), 1.0, std::max(1.0, 60.0 / sample_s_));
    }
    record->interpass_reached = std::isnan(t) || t <= rule.max_c;
  }
  record->interpass_c = t;
  return waited;
}

std::vector<double> ThermalDriver::Run(const planner::Timeline& timeline, Progress* progress) {
  const std::size_t layers = plan_.layers.size();
  // The last arc span of every layer: its field is taken when that span ends.
  std::vector<std::ptrdiff_t> last_arc(layers, -1);
  for (std::size_t i = 0; i < timeline.spans.size(); ++i) {
    const planner::SpanKind kind = timeline.spans[i].kind;
    if (kind == planner::SpanKind::kArcOn || kind == planner::SpanKind::kArcEnd) {
      last_arc[timeline.spans[i].layer] = static_cast<std::ptrdiff_t>(i);
    }
  }
  std::vector<double> waits(layers, 0.0);
  std::vector<bool> started(layers, false);
  out_->layers.resize(layers);
  for (std::size_t l = 0; l < layers; ++l) {
    out_->layers[l].layer = static_cast<int>(l);
    out_->layers[l].interpass_c = out_->layers[l].peak_c = out_->layers[l].laid_on_c = kNaN;
  }
  laid_on_sum_.assign(layers, 0.0);
  laid_on_n_.assign(layers, 0);
  for (std::size_t i = 0; i < timeline.spans.size(); ++i) {
    const planner::TimedSpan& span = timeline.spans[i];
    const bool arc = span.kind == planner::SpanKind::kArcStart || span.kind == planner::SpanKind::kArcOn;
    if (arc && !started[span.layer]) {
      // The layer's first arc start: wait for the interpass rule, then weld.
      started[span.layer] = true;
      const planner::LayerPath& layer = plan_.layers[span.layer];
      // Where the arc starts: the move's first point; a spiral's layer begins at the previous layer's last point.
      const Eigen::Vector3d start_P =
          span.kind != planner::SpanKind::kArcOn ? layer.points[span.point].p_P
          : span.point > 0                       ? layer.points[span.point - 1].p_P
          : span.layer > 0                       ? plan_.layers[span.layer - 1].points.back().p_P
                                                 : layer.points.front().p_P;
      ThermalLayer& record = out_->layers[span.layer];
      waits[span.layer] = WaitForInterpass(span.layer, start_P, &record);
      record.wait_s = waits[span.layer];
      record.start_s = sim_.time_s();
      current_layer_ = span.layer;
      in_layer_ = true;
      const double hottest = sim_.MaxTemperatureIn(everything_);
      record.peak_c = hottest;
    }
    RunSpan(span);
    if (static_cast<std::ptrdiff_t>(i) == last_arc[span.layer]) {
      ThermalLayer& record = out_->layers[span.layer];
      record.end_s = sim_.time_s();
      const double hottest = sim_.MaxTemperatureIn(everything_);
      if (!std::isnan(hottest) && (std::isnan(record.peak_c) || hottest > record.peak_c)) record.peak_c = hottest;
      in_layer_ = false;
      out_->fields.push_back({span.layer, sim_.time_s(), sim_.Field()});
    }
    if (progress != nullptr) progress->Update(i + 1);
  }
  // A last sample at the end of the build when it fell between two sample times.
  if (out_->sample_time_s.back() < sim_.time_s() - 1e-9) Sample();
  for (std::size_t l = 0; l < layers; ++l) {
    if (laid_on_n_[l] > 0) out_->layers[l].laid_on_c = laid_on_sum_[l] / laid_on_n_[l];
  }
  return waits;
}

}  // namespace

ThermalRunResult RunThermalModel(const Scenario& scenario, const planner::Plan& plan, const TimelineBuilder& build,
                                 Progress* progress) {
  ThermalRunResult result;
  result.settings = ThermalSettingsFor(scenario, plan);
  result.heat_w = scenario.process.arc.HeatW();
  const planner::Timeline first = build(std::vector<double>(plan.layers.size(), 0.0));
  if (progress != nullptr) progress->SetTotal(first.spans.size());
  const auto start = std::chrono::steady_clock::now();
  ThermalDriver driver(scenario, plan, result.settings, &result);
  const std::vector<double> waits = driver.Run(first, progress);
  result.energy = driver.sim().Energy();
  result.stats = driver.sim().Stats();
  result.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.timeline = build(waits);
  return result;
}

}  // namespace waam::analysis
