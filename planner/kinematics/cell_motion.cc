// Coordinated motion along the path: the positioner leads (eq. 5.13 per layer), the TCP follows the path in the
// moving part frame (eq. 5.14-5.18), the arm joints come from the closed-form IK.
#include "planner/kinematics/cell_motion.h"

#include <algorithm>
#include <cmath>

#include "models/core/numbers.h"
#include "models/core/parallel.h"

namespace waam::planner {
namespace {

// Samples per task of the parallel pose pass.
constexpr std::size_t kPoseChunk = 4096;

// Samples per move: at least one, at most step_mm apart.
int Subdivisions(double length_mm, double step_mm) {
  return std::max(1, static_cast<int>(std::ceil(length_mm / step_mm - 1e-9)));
}

}  // namespace

Eigen::Isometry3d TorchPose(const CellKinematics& cell, const Eigen::Vector3d& p_W, const Eigen::Vector3d& tool_dir_W,
                            double spin_rad) {
  const Eigen::Vector3d z = -tool_dir_W.normalized();
  Eigen::Vector3d radial = p_W - cell.X_WR.translation();
  radial.z() = 0.0;
  Eigen::Vector3d x = radial - radial.dot(z) * z;
  if (x.norm() < 1e-6 * std::max(1.0, radial.norm())) {
    // TCP above the j1 axis (or a horizontal torch pointing at it): fall back to the arm's x axis.
    const Eigen::Vector3d xr = cell.X_WR.linear().col(0);
    x = xr - xr.dot(z) * z;
    if (x.norm() < 1e-9) x = Eigen::Vector3d::UnitZ() - z.z() * z;
  }
  x.normalize();
  if (spin_rad != 0.0) x = Eigen::AngleAxisd(spin_rad, z) * x;
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear().col(0) = x;
  X.linear().col(1) = z.cross(x);
  X.linear().col(2) = z;
  X.translation() = p_W;
  return X;
}

std::size_t CountCellSamples(const Plan& plan, double step_mm) {
  std::size_t n = 0;
  const PathPoint* prev = nullptr;
  for (const LayerPath& layer : plan.layers) {
    for (const PathPoint& p : layer.points) {
      n += prev ? static_cast<std::size_t>(Subdivisions((p.p_P - prev->p_P).norm(), step_mm)) : 1u;
      prev = &p;
    }
  }
  return n;
}

std::vector<CellSample> PlanCellMotion(const CellKinematics& cell, const Plan& plan, const MotionOptions& options,
                                       const std::function<void(std::size_t)>& progress) {
  std::vector<CellSample> samples;
  std::vector<Eigen::Vector3d> tool_dirs_P;  // per sample: the torch axis in the part frame (unit)
  std::vector<double> spins;                 // per sample: the torch's spin about its axis, rad
  samples.reserve(CountCellSamples(plan, options.step_mm));
  tool_dirs_P.reserve(samples.capacity());
  spins.reserve(samples.capacity());
  const auto layer_spin = [&](std::size_t l) {
    return l < options.layer_spin_rad.size() ? options.layer_spin_rad[l] : 0.0;
  };
  double previous_spin = layer_spin(0);
  const Eigen::Isometry3d X_RW = cell.X_WR.inverse();
  const Eigen::Isometry3d X_TF = cell.X_FT.inverse();

  // Home posture of the arm: upper arm up, forearm forward, flange pointing down (j5 = -90 deg).
  Joints6 seed;
  seed << 0.0, 0.0, 0.0, 0.0, -(kPi / 2), 0.0;
  PositionerAngles angles;
  angles.rotation = options.rotation_rad;
  PositionerAngles previous_layer_angles = angles;
  bool first_layer = true;

  const PathPoint* prev = nullptr;
  int global_point = -1;
  for (std::size_t l = 0; l < plan.layers.size(); ++l) {
    const LayerPath& layer = plan.layers[l];
    const double spin = layer_spin(l);
    // eq. 5.13 / Appendix B: the positioner turns this layer's build direction up; nearest to the last layer.
    const PositionerAngles layer_angles =
        SolvePositionerAnglesWithin(cell.positioner, layer.build_dir_P, angles, options.tilt_tolerance_rad);
    if (first_layer) previous_layer_angles = layer_angles;
    first_layer = false;
    // A layer entered by a weld move (a spiral: no arc-off move between layers to turn the positioner in) turns
    // from the last layer's angles to its own along its whole length, as coordinated motion does, instead of within
    // the first move: turning 30 deg during one 2 mm weld step asks the positioner for several times its speed.
    const bool welded_entry = prev != nullptr && !layer.points.empty() && layer.points.front().weld;
    double layer_length = 0.0;
    if (welded_entry) {
      const PathPoint* q = prev;
      for (const PathPoint& p : layer.points) layer_length += (p.p_P - q->p_P).norm(), q = &p;
    }
    double along = 0.0;  // path length from the last layer's end to the current sample, for welded_entry
    for (std::size_t i = 0; i < layer.points.size(); ++i) {
      const PathPoint& cur = layer.points[i];
      ++global_point;
      const double length = prev ? (cur.p_P - prev->p_P).norm() : 0.0;
      const int n = prev ? Subdivisions(length, options.step_mm) : 1;
      // The move into a layer's first point carries the positioner from the last layer's angles to this layer's.
      const bool reorient = (i == 0);
      const PositionerAngles move_start = angles;  // where the positioner is when this move starts
      for (int k = 1; k <= n; ++k) {
        const double f = prev ? static_cast<double>(k) / n : 1.0;
        if (welded_entry) along += length / n;
        CellSample s;
        s.layer = layer.index;
        s.point = global_point;
        s.weld = cur.weld && prev != nullptr;
        s.p_P = prev ? Eigen::Vector3d(prev->p_P + f * (cur.p_P - prev->p_P)) : cur.p_P;
        const Eigen::Vector3d tool_dir_P =
            (prev ? Eigen::Vector3d((1.0 - f) * prev->tool_dir_P + f * cur.tool_dir_P) : cur.tool_dir_P).normalized();
        s.bead_width_mm = cur.bead_width_mm;
        s.bead_height_mm = cur.bead_height_mm;
        s.speed_mm_s = (s.weld && cur.speed_mm_s > 0.0) ? cur.speed_mm_s : options.rapid_speed_mm_s;

        if (cur.positioner_rad.allFinite()) {
          // The program's own angles (a program made elsewhere), reached linearly along the move.
          angles.tilt = move_start.tilt + f * (cur.positioner_rad[0] - move_start.tilt);
          angles.rotation = move_start.rotation + f * (cur.positioner_rad[1] - move_start.rotation);
          s.positioner_at_limit = false;
        } else if (options.positioner_per_point) {
          // The local normal (the point's tool direction) turned up, nearest to the previous sample's angles.
          angles = SolvePositionerAnglesWithin(cell.positioner, tool_dir_P, angles, options.tilt_tolerance_rad);
          s.positioner_at_limit = angles.at_limit;
        } else {
          angles = layer_angles;
          if (welded_entry && layer_length > 0.0) {
            const double g = std::min(1.0, along / layer_length);
            angles.tilt = previous_layer_angles.tilt + g * (layer_angles.tilt - previous_layer_angles.tilt);
            angles.rotation =
                previous_layer_angles.rotation + g * (layer_angles.rotation - previous_layer_angles.rotation);
          } else if (reorient) {
            angles.tilt = previous_layer_angles.tilt + f * (layer_angles.tilt - previous_layer_angles.tilt);
            angles.rotation =
                previous_layer_angles.rotation + f * (layer_angles.rotation - previous_layer_angles.rotation);
          }
          s.positioner_at_limit = layer_angles.at_limit;
        }

        s.q[6] = angles.tilt;
        s.q[7] = angles.rotation;
        if (welded_entry && layer_length > 0.0) {
          spins.push_back(previous_spin + std::min(1.0, along / layer_length) * (spin - previous_spin));
        } else {
          spins.push_back(reorient ? previous_spin + f * (spin - previous_spin) : spin);
        }
        tool_dirs_P.push_back(tool_dir_P);
        samples.push_back(s);
      }
      prev = &cur;
    }
    previous_layer_angles = layer_angles;
    previous_spin = spin;
  }

  // eq. 5.14-5.18: TCP point and torch axis from the (turned) part frame into the world, in parallel (each sample
  // on its own).
  const std::size_t chunks = (samples.size() + kPoseChunk - 1) / kPoseChunk;
  ParallelFor(chunks, [&](std::size_t c) {
    const std::size_t end = std::min(samples.size(), (c + 1) * kPoseChunk);
    for (std::size_t i = c * kPoseChunk; i < end; ++i) {
      CellSample& s = samples[i];
      const Eigen::Isometry3d X_WP = cell.X_WB * PartPose(cell.positioner, s.q[6], s.q[7]);
      const Eigen::Vector3d p_W = X_WP * s.p_P;
      const Eigen::Vector3d tool_dir_W = X_WP.linear() * tool_dirs_P[i];
      s.torch_tilt_rad = std::acos(std::clamp(tool_dir_W.z(), -1.0, 1.0));
      s.X_WT = TorchPose(cell, p_W, tool_dir_W, spins[i]);
    }
  });

  // The arm joints, each from the previous sample's (the branch kept continuous), and the time stamps: in order.
  int seed_branch = -1;  // the OPW branch of the last solution (-1: none yet)
  for (std::size_t i = 0; i < samples.size(); ++i) {
    CellSample& s = samples[i];
    const Eigen::Isometry3d X_RF = X_RW * s.X_WT * X_TF;
    if (cell.numeric_ik) {
      // A user's arm without a closed form: local solution from the previous joints; failures are reported.
      Joints6 q = seed;
      double residual = 0.0;
      if (cell.numeric_ik(X_RF, seed, &q, &residual)) {
        seed = q;
        int joint = 0;
        s.arm_within_limits = LimitMargin(cell.arm, q, &joint) >= 0.0;
      } else {
        s.reachable = false;
        s.reach_excess_mm = residual;
        s.arm_within_limits = false;
      }
    } else {
      // The seed's branch alone where it decides the nearest solution, every branch otherwise.
      const IkNearest ik = SolveIkNearest(cell.arm, X_RF, seed, seed_branch);
      if (!ik.reachable) {
        s.reachable = false;
        s.reach_excess_mm = ik.reach_excess_mm;
        s.arm_within_limits = false;
      } else {
        seed = ik.solution.q;
        seed_branch = ik.solution.opw_branch;
        s.branch = ik.solution.branch;
        s.arm_within_limits = ik.solution.within_limits;
      }
    }
    s.q.head<6>() = seed;

    // Time: weld moves at the planned speed relative to the part; arc-off moves at the rapid speed, slowed down so
    // that no axis exceeds its speed.
    if (i > 0) {
      const CellSample& last = samples[i - 1];
      const double ds = (s.p_P - last.p_P).norm();
      double dt = ds / s.speed_mm_s;
      if (!s.weld) {
        for (int j = 0; j < 6; ++j) dt = std::max(dt, std::abs(s.q[j] - last.q[j]) / cell.arm.max_speed[j]);
        dt = std::max(dt, std::abs(s.q[6] - last.q[6]) / cell.positioner.tilt_max_speed);
        dt = std::max(dt, std::abs(s.q[7] - last.q[7]) / cell.positioner.rotation_max_speed);
      }
      s.dt_s = dt;
      s.t_s = last.t_s + dt;
    }
    if (progress && ((i + 1) & 1023u) == 0) progress(i + 1);
  }
  if (progress) progress(samples.size());
  return samples;
}

}  // namespace waam::planner
