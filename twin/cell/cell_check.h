// Pre-build check of a planned path on the cell: reach, joint limits, joint speeds, wrist singularity and
// collisions (MuJoCo between cell bodies, a height map between the torch and the layers deposited so far).
#pragma once

#include <array>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "planner/kinematics/cell_motion.h"
#include "planner/path/tool_path.h"
#include "twin/cell/cell_settings.h"
#include "twin/cell/cell_resolve.h"
#include "twin/cell/mujoco_cell.h"

namespace waam {
class Progress;
}

namespace waam::twin {

class CellModel;   // twin/cell/mujoco_cell.h
struct CellFiles;  // twin/cell/cell_compose.h

// What a violation is; its name is check.json's `kind`.
enum class ViolationKind { kUnreachable, kJointLimit, kJointSpeed, kSingularity, kCollision };
constexpr std::array<EnumName<ViolationKind>, 5> EnumNames(ViolationKind) {
  return {{{ViolationKind::kUnreachable, "unreachable"},
           {ViolationKind::kJointLimit, "joint_limit"},
           {ViolationKind::kJointSpeed, "joint_speed"},
           {ViolationKind::kSingularity, "singularity"},
           {ViolationKind::kCollision, "collision"}}};
}
WAAM_ENUM_JSON(ViolationKind)

// One violation: all samples of one layer with the same kind and joint (or body pair), merged.
struct CheckViolation {
  ViolationKind kind = ViolationKind::kUnreachable;
  int point = 0;           // path point (over the whole plan) where it is worst
  int layer = 0;           // layer of that point
  int first_point = 0;     // first and last path point in this layer with this violation
  int last_point = 0;
  int samples = 0;         // checked samples with this violation in this layer
  std::string joint;       // joint_limit, joint_speed: j1..j6, pos_tilt, pos_rot; singularity: j5
  std::string body1;       // collision: the two bodies ("part" is the deposited metal)
  std::string body2;
  double value = 0.0;      // worst value: see `unit`
  std::string unit;        // reach_excess_mm | margin_deg | speed_ratio | j5_deg | penetration_mm
  int sample = 0;          // index into CheckReport::motion where it is worst
  // Continuous mode: the earliest time this entry's contact (collision) or crossing (singularity) begins, -1 when
  // not known (discrete mode), s; and whether one of its samples' contacts or crossings lies strictly between two
  // samples (a discrete check at the samples does not see it there).
  double t_s = -1.0;
  bool between_samples = false;
};

// The figures of a check the redundancy resolution compares.
struct CheckMargins {
  std::size_t violations = 0;          // merged violations
  std::size_t violating_samples = 0;   // summed over them
  double min_arm_margin_deg = 0.0;
  double min_j5_deg = 0.0;
  double min_clearance_mm = 0.0;
  double max_joint_speed_ratio = 0.0;
};

// A check to beat: a check stopped early (CheckPlanBounded) only once it is proven worse than one with these
// figures (more violating samples; with none, any violation or a CheckMargin below `margin`).
struct CheckBar {
  std::size_t violating_samples = 0;
  double margin = 0.0;
};

// What `cell.resolve` did (check.json `resolve`).
struct ResolveSummary {
  CellResolve mode = CellResolve::kFixed;
  bool kept_fixed = false;            // optimise checked worse than the fixed rule, which was kept
  bool abandoned = false;             // ... proven so before its check was whole (CellSettings::prune)
  CheckMargins before;                // the fixed rule's check
  CheckMargins after;                 // the check reported (the resolved motion's, or the fixed one's when kept)
  std::vector<double> layer_spin_deg; // per layer: the torch's spin about its axis, deg
};

// What `waam check` reports.
struct CheckReport {
  bool ok = true;
  std::string ik = "closed_form";  // closed_form (OPW arm) | numerical (a user's arm; failures are unreachable)
  CellModel::RobotInfo robot;      // the arm: name, source (builtin, preset, file) and its joint names
  planner::PositionerType positioner_type = planner::PositionerType::kTiltRotate;  // the axes the cell's model has
  std::size_t points = 0;    // path points
  std::size_t samples = 0;   // checked samples (path points and the points inserted every step_mm)
  std::vector<CheckViolation> violations;
  double min_joint_margin_deg = 0.0;  // smallest distance of any axis to its limit over the path, deg
  std::string min_margin_joint;
  double min_arm_margin_deg = 0.0;     // the same over the arm's six joints only, deg (the positioner holds its
                                       // tilt at exactly the margin where a layer needs more tilt than it has)
  double max_joint_speed_ratio = 0.0;  // largest |joint speed| / axis limit over weld moves
  std::string max_speed_joint;
  double min_j5_deg = 0.0;             // closest approach to the wrist singularity, deg
  // Smallest distance between two cell bodies that may collide (negative: penetrating), capped at
  // CellModel::kClearanceMarginMm; the torch against the deposited part is not included, mm. Discrete mode: over
  // the samples; continuous mode: the certified clearance over the whole motion.
  double min_clearance_mm = 0.0;
  Eigen::Matrix<double, 8, 1> max_accel_deg_s2 = Eigen::Matrix<double, 8, 1>::Zero();  // per axis, weld moves
  double duration_s = 0.0;             // motion time of the whole path, s
  int positioner_limit_layers = 0;     // layers whose build direction needs more tilt than the positioner has
  double max_torch_tilt_deg = 0.0;     // largest torch angle from vertical while welding, deg
  int worst_sample = 0;                // index into `motion` of the worst sample (for the picture)
  std::vector<planner::CellSample> motion;  // the eight-axis trajectory
  ResolveSummary resolve;                    // optimise: what was chosen, margins before and after
  CheckMode mode = CheckMode::kDiscrete;     // the mode that ran
  std::string mode_fallback;                 // why continuous was asked for but discrete ran (empty otherwise)
  // Distance queries: discrete, MuJoCo's collision detections; continuous, pair distance bounds (spheres or GJK).
  std::size_t distance_queries = 0;
  // Continuous mode: the sweep's figures (certified clearance over the whole motion, uncapped; first contact).
  double certified_clearance_mm = 0.0;
  double sweep_min_distance_mm = 0.0;        // the smallest distance found between two points of a pair, mm
  std::string closest_body1, closest_body2;  // that pair
  double closest_t_s = 0.0;                  // and when, s
  double first_contact_s = -1.0;             // the first contact found, -1 when none, s
  std::size_t gjk_queries = 0, poses = 0, refinements = 0;
  // Continuous mode with part_collision: the certified clearance between the nozzle and the part built so far over
  // every move (+inf when no move was swept; minus the deepest penetration when there is a contact), mm, and the
  // deposit-map distance bounds it took.
  double part_clearance_mm = std::numeric_limits<double>::infinity();
  std::size_t part_queries = 0;
  // CheckPlanBounded stopped before the check was whole: `violations` is empty, `violating_samples_found` counts the
  // violating samples found before the stop (a lower bound), and min_arm_margin_deg, min_j5_deg and
  // min_clearance_mm are the smallest found so far (so CheckMargin is an upper bound on the whole check's).
  bool bounded = false;
  std::size_t violating_samples_found = 0;
};

// The figures of `report` the resolution and `waam place` compare (a bounded report's: its bounds).
CheckMargins MarginsOf(const CheckReport& report);
// The smallest margin, each in excess of its violation threshold and scaled so that 1 is comfortable:
// min((arm joint margin - joint_margin_deg) / 10 deg, (|J5| - singularity_deg) / 10 deg, clearance / 10 mm).
double CheckMargin(const CheckMargins& margins, const twin::CellSettings& settings);

// |J5| from the wrist-singular pose (j5 near 0 or 180 deg aligns j4 and j6), deg: the singularity check's figure.
double J5Deg(const planner::Joints8& q);

// Axis j's distance from q to the nearer of its limits lo..hi, deg: the joint-limit check's figure.
double JointMarginDeg(const planner::Joints8& q, int j, double lo, double hi);

// Names of the eight axes: j1..j6, pos_tilt, pos_rot.
const char* AxisName(int axis);

// The cell model of `settings` from `files` (read by analysis::ReadCellFiles(settings)), with the arm base and the
// positioner placed as it says: the built-in cell (composed with another positioner type when the settings name
// one), a preset, a URDF arm or the cell.mjcf model. Throws InputError for a model that cannot be used, and for a
// cell.mjcf whose positioner is not of the type the settings name.
CellModel BuildCell(const twin::CellSettings& settings, const CellFiles& files);

// The kinematics of `cell` (made by BuildCell(settings, ...)) with the part placed on the plate as `settings` says.
planner::CellKinematics PartKinematics(const CellModel& cell, const twin::CellSettings& settings);
// The kinematics the motion is solved with: the positioner's tilt and rotation ranges pulled in by the settings'
// joint margin on each side (where the range is wider than twice the margin).
planner::CellKinematics MarginKinematics(const planner::CellKinematics& kin, const twin::CellSettings& settings);
// The motion options of the cell settings (sample step, positioner rotation, follow mode, tilt tolerance) with
// arc-off moves at `rapid_speed_mm_s`.
planner::MotionOptions MotionOptionsOf(const twin::CellSettings& settings, double rapid_speed_mm_s);

// Checks `plan` (part frame P) on `cell`, which BuildCell(settings, ...) made. Arc-off moves run at `rapid_speed_mm_s`.
// With settings.resolve optimise (the default) the fixed rule's motion is checked first; unless it passes with every
// margin comfortable (CheckMargin >= 1), the torch's spin per layer is chosen (twin/cell/cell_resolve.h) and the result
// is the better of that motion's check and the fixed rule's. `progress` may be null.
CheckReport CheckPlan(const CellModel& cell, const planner::Plan& plan, const twin::CellSettings& settings,
                      double rapid_speed_mm_s, Progress* progress);

// CheckPlan with cell.resolve fixed that stops as soon as its figures prove the check worse than `bar` (branch and
// bound; `waam place`'s coarse pass): the motion's unreachable samples, joint-limit and |J5| figures first, then the
// cell bodies' contacts and clearance (discrete mode: each 1024-sample chunk stops on its own once it proves it,
// so the figures found do not depend on the threads). The report is then `bounded`; otherwise it is CheckPlan's.
// Throws what CheckPlan throws.
CheckReport CheckPlanBounded(const CellModel& cell, const planner::Plan& plan, const twin::CellSettings& settings,
                             double rapid_speed_mm_s, const CheckBar& bar);

}  // namespace waam::twin
