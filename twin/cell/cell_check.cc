// The check loop: every sample of the eight-axis motion against reach, limits, speeds, singularity and collisions.
#include "twin/cell/cell_check.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>
#include <optional>
#include <tuple>

#include "models/core/error.h"
#include "models/core/numbers.h"
#include "models/core/parallel.h"
#include "models/core/progress.h"
#include "twin/cell/cell_compose.h"
#include "twin/cell/cell_presets.h"
#include "twin/cell/cell_sweep.h"
#include "twin/cell/check_bound.h"
#include "twin/cell/deposit_map.h"
#include "twin/cell/deposit_sweep.h"
#include "twin/cell/mujoco_cell.h"

namespace waam::twin {
using internal::BoundedReport;
using internal::MotionFigures;
using internal::MotionFiguresOf;
using internal::ProvenWorse;

namespace {

// Collects violations, merging the samples of one layer with the same kind and subject into one entry.
class ViolationLog {
 public:
  // `worse_if_larger`: whether a larger value is a worse violation.
  // `t_s`: when the contact or crossing begins (continuous mode; -1 unknown); `between`: strictly between samples.
  void Add(ViolationKind kind, const std::string& subject1, const std::string& subject2,
           const planner::CellSample& s, int sample, double value, const std::string& unit, bool worse_if_larger,
           double t_s = -1.0, bool between = false) {
    const auto key = std::make_tuple(kind, subject1, subject2);
    auto it = open_.find(key);
    if (it != open_.end() && violations_[it->second].layer == s.layer) {
      CheckViolation& v = violations_[it->second];
      if (t_s >= 0.0 && (v.t_s < 0.0 || t_s < v.t_s)) v.t_s = t_s;
      v.between_samples = v.between_samples || between;
      v.last_point = s.point;
      ++v.samples;
      if (worse_if_larger ? value > v.value : value < v.value) {
        v.value = value;
        v.point = s.point;
        v.layer = s.layer;
        v.sample = sample;
      }
      return;
    }
    CheckViolation v;
    v.kind = kind;
    v.point = v.first_point = v.last_point = s.point;
    v.layer = s.layer;
    v.samples = 1;
    if (kind == ViolationKind::kCollision) {
      v.body1 = subject1;
      v.body2 = subject2;
    } else {
      v.joint = subject1;
    }
    v.value = value;
    v.unit = unit;
    v.sample = sample;
    v.t_s = t_s;
    v.between_samples = between;
    open_[key] = violations_.size();
    violations_.push_back(v);
  }
  std::vector<CheckViolation> Take() { return std::move(violations_); }

 private:
  // The entry of the current layer for each kind and subject.
  std::map<std::tuple<ViolationKind, std::string, std::string>, std::size_t> open_;
  std::vector<CheckViolation> violations_;
};

// A contact between cell bodies at one sample of the motion.
struct SampleContacts {
  std::size_t sample = 0;
  CellContact contact;
  double t_s = -1.0;     // continuous mode: time of first contact, s
  bool between = false;  // continuous mode: first contact strictly between samples
};

// Samples per chunk of the parallel collision pass: a fixed number, so the chunks do not depend on the threads.
constexpr std::size_t kCollisionChunk = 1024;

// When a chunk of the discrete collision pass may stop (CheckPlanBounded): once it holds more than `contacts`
// contacts, or its clearance term (clearance / CellModel::kClearanceMarginMm) is below `margin`.
struct ContactStop {
  std::size_t contacts = std::numeric_limits<std::size_t>::max();
  double margin = -std::numeric_limits<double>::infinity();
};

// MuJoCo collision detection at every reachable sample of `motion`, in chunks checked in parallel (one CellState
// each over the shared model): the contacts deeper than `tolerance_mm`, in sample order, and in `*min_clearance_mm`
// the smallest clearance between cell bodies found by the detections (capped at CellModel::kClearanceMarginMm). A
// skipped sample lies at most half the last clearance closer, so the figure overstates the true smallest clearance
// by at most that. Within a chunk a detection
// is skipped while no geom has moved by half the clearance found at the last one (conservative advancement: no
// contact can have appeared); each chunk starts with a detection, so the contacts are those a detection at every
// sample would find, whatever the chunks and the threads. A chunk ends early where `stop` says; what it found up to
// there does not depend on the other chunks. `*detections` counts the collision detections run.
std::vector<SampleContacts> CellContacts(const CellModel& cell, const std::vector<planner::CellSample>& motion,
                                         double tolerance_mm, const ContactStop& stop, double* min_clearance_mm,
                                         std::size_t* detections) {
  const std::size_t chunks = (motion.size() + kCollisionChunk - 1) / kCollisionChunk;
  std::vector<std::vector<SampleContacts>> found(chunks);
  std::vector<double> chunk_clearance(chunks, CellModel::kClearanceMarginMm);
  std::vector<std::size_t> chunk_detections(chunks, 0);
  ParallelFor(chunks, [&](std::size_t c) {
    CellState state(cell);
    std::vector<CellContact> contacts;
    double clearance = -1.0;  // from the last collision detection, mm; <= 0 forces a detection
    const std::size_t end = std::min(motion.size(), (c + 1) * kCollisionChunk);
    for (std::size_t i = c * kCollisionChunk; i < end; ++i) {
      if (!motion[i].reachable) continue;
      state.SetJoints(motion[i].q);
      if (clearance > 0.0 && 2.0 * state.MotionSinceCollide() < clearance) continue;
      contacts.clear();
      state.Collide(tolerance_mm, &contacts, &clearance);
      ++chunk_detections[c];
      chunk_clearance[c] = std::min(chunk_clearance[c], clearance);
      for (CellContact& contact : contacts) found[c].push_back({i, std::move(contact), -1.0, false});
      if (found[c].size() > stop.contacts || chunk_clearance[c] / CellModel::kClearanceMarginMm < stop.margin) break;
    }
  });
  *min_clearance_mm = CellModel::kClearanceMarginMm;
  for (double c : chunk_clearance) *min_clearance_mm = std::min(*min_clearance_mm, c);
  *detections = 0;
  for (std::size_t n : chunk_detections) *detections += n;
  std::vector<SampleContacts> all;
  for (std::vector<SampleContacts>& chunk : found) {
    all.insert(all.end(), std::make_move_iterator(chunk.begin()), std::make_move_iterator(chunk.end()));
  }
  return all;
}

// The continuous mode's contacts (twin/cell/cell_sweep.h), with its figures written into `report`.
std::vector<SampleContacts> SweptContacts(const CellModel& cell, const CellCollisionGeometry& geometry,
                                          const std::vector<planner::CellSample>& motion, double tolerance_mm,
                                          CheckReport* report) {
  SweepOptions options;
  options.tolerance_mm = tolerance_mm;
  SweepResult sweep = SweepMotion(cell, geometry, motion, options);
  report->certified_clearance_mm = sweep.certified_clearance_mm;
  report->min_clearance_mm = std::min(sweep.certified_clearance_mm, CellModel::kClearanceMarginMm);
  report->sweep_min_distance_mm = sweep.min_distance_mm;
  report->closest_body1 = sweep.closest_body1;
  report->closest_body2 = sweep.closest_body2;
  report->closest_t_s = sweep.closest_t_s;
  report->first_contact_s = sweep.first_contact_s;
  report->distance_queries = sweep.distance_queries;
  report->gjk_queries = sweep.gjk_queries;
  report->poses = sweep.poses;
  report->refinements = sweep.refinements;
  std::vector<SampleContacts> contacts;
  for (SweepContact& c : sweep.contacts) {
    contacts.push_back({c.sample, std::move(c.contact), c.t_s, c.between_samples});
  }
  return contacts;
}

// The cell bodies' contacts in the mode `settings` asks for: continuous where every geom has a distance bound, else
// discrete with the reason in report->mode_fallback. Sets the report's mode and collision figures.
// The discrete pass's chunks stop where `stop` says (the continuous sweep runs whole).
std::vector<SampleContacts> ContactsInMode(const CellModel& cell, const CellCollisionGeometry& geometry,
                                           const std::vector<planner::CellSample>& motion,
                                           const twin::CellSettings& settings, const ContactStop& stop,
                                           CheckReport* report) {
  report->mode = settings.check_mode;
  if (report->mode == CheckMode::kContinuous) {
    if (geometry.unsupported.empty()) {
      return SweptContacts(cell, geometry, motion, settings.collision_tolerance_mm, report);
    }
    report->mode = CheckMode::kDiscrete;
    report->mode_fallback = geometry.unsupported;
  }
  std::vector<SampleContacts> contacts = CellContacts(cell, motion, settings.collision_tolerance_mm, stop,
                                                      &report->min_clearance_mm, &report->distance_queries);
  report->certified_clearance_mm = report->min_clearance_mm;
  return contacts;
}

// Continuous mode: where the joint-space line from sample i - 1 to sample i passes j5 = 0 (or 180) deg while both
// samples keep the singularity margin, the time it comes within `singularity_deg` of it (-1 when it does not), s.
double SingularityCrossing(const planner::CellSample& a, const planner::CellSample& b, double singularity_deg) {
  const double margin = singularity_deg / kDeg;
  const double lo = std::min(a.q[4], b.q[4]), hi = std::max(a.q[4], b.q[4]);
  const double k = std::ceil(lo / kPi);
  if (k * kPi > hi) return -1.0;
  // Moving up: the line enters at k pi - margin; moving down, at k pi + margin.
  const double enter = a.q[4] <= b.q[4] ? k * kPi - margin : k * kPi + margin;
  const double f = std::clamp((enter - a.q[4]) / (b.q[4] - a.q[4]), 0.0, 1.0);
  return a.t_s + f * (b.t_s - a.t_s);
}

// The order in which a kind's sample becomes the report's worst_sample: collisions first.
int KindRank(ViolationKind kind) {
  switch (kind) {
    case ViolationKind::kCollision: return 0;
    case ViolationKind::kUnreachable: return 1;
    case ViolationKind::kJointLimit: return 2;
    case ViolationKind::kJointSpeed: return 3;
    case ViolationKind::kSingularity: return 4;
  }
  return 4;
}

}  // namespace

const char* AxisName(int axis) {
  static const char* const kNames[8] = {"j1", "j2", "j3", "j4", "j5", "j6", "pos_tilt", "pos_rot"};
  return (axis >= 0 && axis < 8) ? kNames[axis] : "?";
}

namespace {

// The nozzle capsule (TCP frame) and, for the torch against the part, a deposit map over the motion's footprint.
struct NozzleAndMap {
  Eigen::Vector3d a_T, b_T;
  double r = 0.0;
  DepositMap deposit;
  Eigen::AlignedBox3d part_box_P;  // holds every bead the motion lays, mm
};

NozzleAndMap FootprintMap(const CellModel& cell, const std::vector<planner::CellSample>& motion) {
  Eigen::Vector3d a_T, b_T;
  double r = 0.0, width = 0.0;
  cell.NozzleInTcp(&a_T, &b_T, &r);
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (const planner::CellSample& s : motion) {
    lo = lo.cwiseMin(s.p_P);
    hi = hi.cwiseMax(s.p_P);
    width = std::max(width, s.bead_width_mm);
  }
  if (motion.empty()) lo = hi = Eigen::Vector3d::Zero();
  const double pad = 20.0 + 2.0 * r;
  // The part's box: the beads' widths about the path, from 10 mm below the plate top (or the path) to the path's top.
  const Eigen::AlignedBox3d box(Eigen::Vector3d(lo.x() - width, lo.y() - width, std::min(0.0, lo.z()) - 10.0),
                                Eigen::Vector3d(hi.x() + width, hi.y() + width, std::max(0.0, hi.z())));
  return {a_T, b_T, r, DepositMap(lo.head<2>().array() - pad, hi.head<2>().array() + pad, 1.0), box};
}

// The checks of one sample after another along the motion: each writes its figures into the report and its
// violations into the log; the state between samples (the last joint velocity, the layer) lives here.
class SampleChecks {
 public:
  // The cell bodies' contacts are found here, the discrete pass stopping where `stop` says.
  SampleChecks(const CellModel& cell, const planner::CellKinematics& kin, const twin::CellSettings& settings,
               const ContactStop& stop, CheckReport* report)
      : kin_(kin), settings_(settings), report_(*report), motion_(report->motion),
        nozzle_(FootprintMap(cell, report->motion)) {
    limit_lo_ << kin.arm.lower, kin.positioner.tilt_lower, kin.positioner.rotation_lower;
    limit_hi_ << kin.arm.upper, kin.positioner.tilt_upper, kin.positioner.rotation_upper;
    max_speed_ << kin.arm.max_speed, kin.positioner.tilt_max_speed, kin.positioner.rotation_max_speed;
    report_.min_joint_margin_deg = std::numeric_limits<double>::infinity();
    report_.min_arm_margin_deg = std::numeric_limits<double>::infinity();
    report_.min_j5_deg = std::numeric_limits<double>::infinity();
    if (settings.check_mode == CheckMode::kContinuous) geometry_ = cell.CollisionGeometry();
    cell_contacts_ = ContactsInMode(cell, geometry_, motion_, settings, stop, &report_);
    continuous_ = report_.mode == CheckMode::kContinuous;
    // Continuous: the nozzle against the deposit between the samples too.
    if (continuous_ && settings.part_collision) {
      const SweepOptions sweep;
      part_sweep_.emplace(cell, geometry_, kin, nozzle_.part_box_P, sweep.contact_mm, sweep.probe_mm,
                          settings.collision_tolerance_mm);
    }
  }

  // Every check at sample i, then the bead laid up to it.
  void Sample(std::size_t i) {
    const planner::CellSample& s = motion_[i];
    if (s.layer != last_layer_) {
      if (s.positioner_at_limit) ++report_.positioner_limit_layers;
      last_layer_ = s.layer;
    }
    if (s.weld) report_.max_torch_tilt_deg = std::max(report_.max_torch_tilt_deg, s.torch_tilt_rad * kDeg);
    if (!s.reachable) {
      log_.Add(ViolationKind::kUnreachable, "", "", s, static_cast<int>(i), s.reach_excess_mm,
               kin_.numeric_ik ? "ik_residual_mm" : "reach_excess_mm", true);
      have_velocity_ = false;
    } else {
      JointLimits(i);
      Singularity(i);
      JointSpeeds(i);
      CellCollisions(i);
      PartCollision(i);
    }
    if (s.weld && i > 0) nozzle_.deposit.Deposit(motion_[i - 1].p_P, s.p_P, s.bead_width_mm);
  }

  // The cell bodies' contacts found along the motion (each is one violating sample of a collision violation).
  std::size_t cell_contacts() const { return cell_contacts_.size(); }

  // The report's violations and summary figures once every sample is checked.
  void Finish() {
    if (part_sweep_) {
      report_.part_clearance_mm = part_sweep_->certified_clearance_mm();
      report_.part_queries = part_sweep_->queries();
      report_.poses += part_sweep_->poses();
    }
    report_.violations = log_.Take();
    report_.ok = report_.violations.empty();
    report_.duration_s = motion_.empty() ? 0.0 : motion_.back().t_s;
    if (!std::isfinite(report_.min_joint_margin_deg)) report_.min_joint_margin_deg = 0.0;
    if (!std::isfinite(report_.min_arm_margin_deg)) report_.min_arm_margin_deg = 0.0;
    if (!std::isfinite(report_.min_j5_deg)) report_.min_j5_deg = 0.0;
    report_.worst_sample = min_margin_sample_;
    int best_rank = 99;
    for (const CheckViolation& v : report_.violations) {
      if (KindRank(v.kind) < best_rank) {
        best_rank = KindRank(v.kind);
        report_.worst_sample = v.sample;
      }
    }
  }

 private:
  // Joint limits with margin (every axis the cell has; a missing one stays at 0 and is no limit).
  void JointLimits(std::size_t i) {
    const planner::CellSample& s = motion_[i];
    const int si = static_cast<int>(i);
    for (int j = 0; j < 8; ++j) {
      if (!planner::HasAxis(kin_.positioner.type, j)) continue;
      const double m_deg = JointMarginDeg(s.q, j, limit_lo_[j], limit_hi_[j]);
      if (j < 6) report_.min_arm_margin_deg = std::min(report_.min_arm_margin_deg, m_deg);
      if (m_deg < report_.min_joint_margin_deg) {
        report_.min_joint_margin_deg = m_deg;
        report_.min_margin_joint = AxisName(j);
        min_margin_sample_ = si;
      }
      if (m_deg < settings_.joint_margin_deg) {
        log_.Add(ViolationKind::kJointLimit, AxisName(j), "", s, si, m_deg, "margin_deg", false);
      }
    }
  }

  // Wrist singularity: j5 near 0 (or 180) deg aligns j4 and j6.
  void Singularity(std::size_t i) {
    const planner::CellSample& s = motion_[i];
    const int si = static_cast<int>(i);
    const double j5_deg = J5Deg(s.q);
    report_.min_j5_deg = std::min(report_.min_j5_deg, j5_deg);
    if (j5_deg < settings_.singularity_deg) {
      log_.Add(ViolationKind::kSingularity, "j5", "", s, si, j5_deg, "j5_deg", false);
    }
    if (continuous_ && i > 0 && motion_[i - 1].reachable && j5_deg >= settings_.singularity_deg) {
      // Between the samples: the joint-space line may pass j5 = 0 while both ends keep the margin.
      const double t = SingularityCrossing(motion_[i - 1], s, settings_.singularity_deg);
      if (t >= 0.0) {
        report_.min_j5_deg = 0.0;
        log_.Add(ViolationKind::kSingularity, "j5", "", s, si, 0.0, "j5_deg", false, t, true);
      }
    }
  }

  // Joint speeds and accelerations while welding, at the planned travel speed.
  void JointSpeeds(std::size_t i) {
    const planner::CellSample& s = motion_[i];
    if (!(s.weld && i > 0 && s.dt_s > 0.0 && motion_[i - 1].reachable)) {
      have_velocity_ = false;
      return;
    }
    const Eigen::Matrix<double, 8, 1> v = (s.q - motion_[i - 1].q) / s.dt_s;
    for (int j = 0; j < 8; ++j) {
      if (!planner::HasAxis(kin_.positioner.type, j)) continue;
      const double ratio = std::abs(v[j]) / max_speed_[j];
      if (ratio > report_.max_joint_speed_ratio) {
        report_.max_joint_speed_ratio = ratio;
        report_.max_speed_joint = AxisName(j);
      }
      if (ratio > 1.0) {
        log_.Add(ViolationKind::kJointSpeed, AxisName(j), "", s, static_cast<int>(i), ratio, "speed_ratio", true);
      }
      if (have_velocity_) {
        report_.max_accel_deg_s2[j] =
            std::max(report_.max_accel_deg_s2[j], std::abs(v[j] - prev_velocity_[j]) / s.dt_s * kDeg);
      }
    }
    prev_velocity_ = v;
    have_velocity_ = true;
  }

  // Cell bodies: the contacts found at this sample (ContactsInMode).
  void CellCollisions(std::size_t i) {
    const planner::CellSample& s = motion_[i];
    while (next_contact_ < cell_contacts_.size() && cell_contacts_[next_contact_].sample < i) ++next_contact_;
    for (; next_contact_ < cell_contacts_.size() && cell_contacts_[next_contact_].sample == i; ++next_contact_) {
      const SampleContacts& found = cell_contacts_[next_contact_];
      const CellContact& c = found.contact;
      const bool ordered = c.body1 < c.body2;
      log_.Add(ViolationKind::kCollision, ordered ? c.body1 : c.body2, ordered ? c.body2 : c.body1, s,
               static_cast<int>(i), c.penetration_mm, "penetration_mm", true, found.t_s, found.between);
    }
  }

  // Torch against the layers deposited before this sample (continuous: over the move into it too).
  void PartCollision(std::size_t i) {
    if (!settings_.part_collision) return;
    const planner::CellSample& s = motion_[i];
    // The part's pose changes only when the positioner moves (not at all along most layers).
    if (s.q[6] != part_at_[0] || s.q[7] != part_at_[1]) {
      part_at_ = {s.q[6], s.q[7]};
      X_PW_ = (kin_.X_WB * planner::PartPose(kin_.positioner, s.q[6], s.q[7])).inverse();
    }
    const Eigen::Isometry3d X_PT = X_PW_ * s.X_WT;
    const NozzleInPart nozzle{X_PT * nozzle_.a_T, X_PT * nozzle_.b_T};
    if (part_sweep_ && i > 0 && motion_[i - 1].reachable) {
      // The move into this sample, against the metal laid before it.
      if (const std::optional<DepositContact> c =
              part_sweep_->Move(motion_[i - 1], previous_nozzle_, s, nozzle, nozzle_.deposit)) {
        log_.Add(ViolationKind::kCollision, "part", "torch", s, static_cast<int>(i), c->penetration_mm,
                 "penetration_mm", true, c->t_s, c->between_samples);
        if (report_.first_contact_s < 0.0 || c->t_s < report_.first_contact_s) report_.first_contact_s = c->t_s;
      }
    }
    previous_nozzle_ = nozzle;
    const double pen = nozzle_.deposit.Penetration(nozzle.a_P, nozzle.b_P, nozzle_.r);
    if (pen > settings_.collision_tolerance_mm) {
      log_.Add(ViolationKind::kCollision, "part", "torch", s, static_cast<int>(i), pen, "penetration_mm", true);
    }
  }

  const planner::CellKinematics& kin_;
  const twin::CellSettings& settings_;
  CheckReport& report_;
  const std::vector<planner::CellSample>& motion_;
  NozzleAndMap nozzle_;
  ViolationLog log_;
  Eigen::Matrix<double, 8, 1> limit_lo_, limit_hi_, max_speed_;
  std::vector<SampleContacts> cell_contacts_;
  CellCollisionGeometry geometry_;            // continuous mode's (empty in discrete mode)
  std::optional<DepositSweep> part_sweep_;    // continuous mode with part_collision
  NozzleInPart previous_nozzle_;              // the nozzle at the sample before, in P
  std::array<double, 2> part_at_ = {std::numeric_limits<double>::quiet_NaN(), 0.0};  // positioner of X_PW_
  Eigen::Isometry3d X_PW_ = Eigen::Isometry3d::Identity();
  bool continuous_ = false;
  std::size_t next_contact_ = 0;  // first entry of cell_contacts_ at or after the current sample
  Eigen::Matrix<double, 8, 1> prev_velocity_ = Eigen::Matrix<double, 8, 1>::Zero();
  bool have_velocity_ = false;
  int last_layer_ = std::numeric_limits<int>::min();
  int min_margin_sample_ = 0;
};

// The check of the motion `options` give on `solve` (the kinematics the motion is planned on, the positioner's limits
// kept `margin` inside) against the limits of `kin`. With `bar`: a bounded report (BoundedReport) as soon as the
// motion's figures, then the cell contacts and clearance, prove this check worse than `bar`.
CheckReport CheckWithOptions(const CellModel& cell, const planner::CellKinematics& kin,
                             const planner::CellKinematics& solve, const planner::Plan& plan,
                             const twin::CellSettings& settings, const planner::MotionOptions& options,
                             Progress* progress, const CheckBar* bar = nullptr) {
  CheckReport report;
  report.ik = kin.numeric_ik ? "numerical" : "closed_form";
  report.positioner_type = kin.positioner.type;
  report.robot = cell.robot();
  for (const planner::LayerPath& layer : plan.layers) report.points += layer.points.size();
  const std::size_t total = planner::CountCellSamples(plan, settings.step_mm);
  if (progress) progress->SetTotal(2 * total);
  report.motion = planner::PlanCellMotion(solve, plan, options, [&](std::size_t done) {
    if (progress) progress->Update(done);
  });
  report.samples = report.motion.size();
  ContactStop stop;
  MotionFigures motion;
  if (bar) {
    motion = MotionFiguresOf(report.motion, kin, settings);
    const double term = std::min((motion.min_arm_margin_deg - settings.joint_margin_deg) / 10.0,
                                 (motion.min_j5_deg - settings.singularity_deg) / 10.0);
    if (ProvenWorse(*bar, motion.violating_samples, term)) {
      return BoundedReport(std::move(report), motion, CellModel::kClearanceMarginMm, motion.violating_samples);
    }
    // Each chunk of contacts stops once it alone proves it (every contact is one more violating sample).
    stop.contacts = bar->violating_samples - motion.violating_samples;
    if (bar->violating_samples == 0) stop.margin = bar->margin;
  }

  SampleChecks checks(cell, kin, settings, stop, &report);
  if (bar) {
    const std::size_t violating = motion.violating_samples + checks.cell_contacts();
    if (ProvenWorse(*bar, violating, report.min_clearance_mm / CellModel::kClearanceMarginMm)) {
      const double clearance_mm = report.min_clearance_mm;
      return BoundedReport(std::move(report), motion, clearance_mm, violating);
    }
  }
  for (std::size_t i = 0; i < report.motion.size(); ++i) {
    checks.Sample(i);
    if (progress && (i & 1023u) == 0) progress->Update(total + i);
  }
  checks.Finish();
  if (progress) progress->Update(2 * total);
  return report;
}

}  // namespace

CheckReport CheckPlan(const CellModel& cell, const planner::Plan& plan, const twin::CellSettings& settings,
                      double rapid_speed_mm_s, Progress* progress) {
  planner::CellKinematics kin = PartKinematics(cell, settings);
  if (plan.X_FT) kin.X_FT = *plan.X_FT;  // an imported program's own tool is the TCP that moves
  // The positioner solution keeps the joint margin: where it must hold a limit, it holds it `margin` inside.
  const planner::CellKinematics solve = MarginKinematics(kin, settings);
  planner::MotionOptions options = MotionOptionsOf(settings, rapid_speed_mm_s);  // the spins are set below
  if (settings.resolve == CellResolve::kFixed) {
    return CheckWithOptions(cell, kin, solve, plan, settings, options, progress);
  }

  // optimise: the fixed rule's check, the spins per layer, the check of their motion; the better of the two is kept.
  // The progress bar runs once for the fixed check and again for the resolved one.
  CheckReport fixed = CheckWithOptions(cell, kin, solve, plan, settings, options, progress);
  ResolveSummary summary;
  summary.mode = CellResolve::kOptimise;
  summary.before = MarginsOf(fixed);
  if (summary.before.violating_samples == 0 && CheckMargin(summary.before, settings) >= 1.0) {
    // Nothing to gain: every margin already counts as comfortable (the resolution scores margins up to 1).
    summary.kept_fixed = true;
    summary.after = summary.before;
    summary.layer_spin_deg.assign(plan.layers.size(), 0.0);
    fixed.resolve = std::move(summary);
    return fixed;
  }
  options.layer_spin_rad = ResolveLayerSpins(cell, solve, plan, options, settings);
  if (std::all_of(options.layer_spin_rad.begin(), options.layer_spin_rad.end(), [](double s) { return s == 0.0; })) {
    // Every spin 0: the resolved motion is the fixed rule's (PlanCellMotion turns nothing), so is its check.
    summary.after = summary.before;
    summary.layer_spin_deg.assign(plan.layers.size(), 0.0);
    fixed.resolve = std::move(summary);
    return fixed;
  }
  // A fixed rule with no violation is a bar: the resolved motion's check stops once it is proven below it.
  const double bar = CheckMargin(summary.before, settings);
  const CheckBar beat{0, bar};
  const bool prune = settings.prune && summary.before.violating_samples == 0;
  std::optional<CheckReport> resolved =
      CheckWithOptions(cell, kin, solve, plan, settings, options, progress, prune ? &beat : nullptr);
  if (resolved->bounded) resolved.reset();
  if (resolved) summary.after = MarginsOf(*resolved);
  const bool worse = !resolved || summary.after.violating_samples > summary.before.violating_samples ||
                     (summary.after.violating_samples == summary.before.violating_samples &&
                      CheckMargin(summary.after, settings) < bar);
  for (double spin : options.layer_spin_rad) summary.layer_spin_deg.push_back(spin * kDeg);
  if (worse) {
    summary.kept_fixed = true;
    summary.abandoned = !resolved;
    summary.after = summary.before;
    std::fill(summary.layer_spin_deg.begin(), summary.layer_spin_deg.end(), 0.0);
    resolved = std::move(fixed);
  }
  resolved->resolve = std::move(summary);
  return std::move(*resolved);
}

CheckReport CheckPlanBounded(const CellModel& cell, const planner::Plan& plan, const twin::CellSettings& settings,
                             double rapid_speed_mm_s, const CheckBar& bar) {
  planner::CellKinematics kin = PartKinematics(cell, settings);
  if (plan.X_FT) kin.X_FT = *plan.X_FT;
  const planner::CellKinematics solve = MarginKinematics(kin, settings);
  const planner::MotionOptions options = MotionOptionsOf(settings, rapid_speed_mm_s);
  return CheckWithOptions(cell, kin, solve, plan, settings, options, nullptr, &bar);
}

}  // namespace waam::twin
