// Coordinated motion along the path: the positioner leads (eq. 5.13 per layer), the TCP follows the path in the
// moving part frame (eq. 5.14-5.18), the arm joints come from the closed-form IK.
#include "planner/kinematics/cell_motion.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

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

// The samples of the path in the part frame, with what the pose pass needs of each.
struct PathSamples {
  std::vector<CellSample> samples;
  std::vector<Eigen::Vector3d> tool_dirs_P;  // per sample: the torch axis in the part frame (unit)
  std::vector<double> spins;                 // per sample: the torch's spin about its axis, rad
};

// Where the sampling stands: the positioner at the last sample, the last layer's angles and spin, the last point.
struct SamplingState {
  PositionerAngles angles;
  PositionerAngles previous_layer_angles;
  double previous_spin = 0.0;         // rad
  const PathPoint* prev = nullptr;
  int global_point = -1;              // index of the last point over the whole plan
};

// How a layer is entered: its positioner angles (eq. 5.13) and spin, and whether a weld move enters it.
struct LayerEntry {
  PositionerAngles angles;
  double spin = 0.0;                  // rad
  bool welded = false;
  double length_mm = 0.0;             // welded: path length from the last layer's end to this layer's end, mm
};

// eq. 5.13 / Appendix B: the positioner turns the layer's build direction up, nearest to the last layer. A layer
// entered by a weld move (a spiral: no arc-off move between layers to turn the positioner in) turns from the last
// layer's angles to its own along its whole length, as coordinated motion does, instead of within the first move:
// turning 30 deg during one 2 mm weld step asks the positioner for several times its speed.
LayerEntry EnterLayer(const CellKinematics& cell, const MotionOptions& options, const LayerPath& layer, double spin,
                      const SamplingState& st) {
  LayerEntry entry;
  entry.angles = SolvePositionerAnglesWithin(cell.positioner, layer.build_dir_P, st.angles,
                                             options.tilt_tolerance_rad);
  entry.spin = spin;
  entry.welded = st.prev != nullptr && !layer.points.empty() && layer.points.front().weld;
  if (entry.welded) {
    const PathPoint* q = st.prev;
    for (const PathPoint& p : layer.points) entry.length_mm += (p.p_P - q->p_P).norm(), q = &p;
  }
  return entry;
}

// The positioner at fraction f of the move to `cur` (which started at `move_start`); sets s.positioner_at_limit.
// `g`, when set, is how far the layer's entry has turned from the last layer's angles to its own.
PositionerAngles PositionerAt(const CellKinematics& cell, const MotionOptions& options, const PathPoint& cur,
                              const Eigen::Vector3d& tool_dir_P, const PositionerAngles& move_start,
                              const SamplingState& st, const LayerEntry& entry, double f, std::optional<double> g,
                              CellSample& s) {
  PositionerAngles angles = st.angles;
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
    angles = entry.angles;
    if (g) {
      const PositionerAngles& from = st.previous_layer_angles;
      angles.tilt = from.tilt + *g * (entry.angles.tilt - from.tilt);
      angles.rotation = from.rotation + *g * (entry.angles.rotation - from.rotation);
    }
    s.positioner_at_limit = entry.angles.at_limit;
  }
  return angles;
}

// Samples one layer's moves at most options.step_mm apart, in the part frame.
void SampleLayer(const CellKinematics& cell, const MotionOptions& options, const LayerPath& layer,
                 const LayerEntry& entry, SamplingState& st, PathSamples& out) {
  double along = 0.0;  // path length from the last layer's end to the current sample, for a welded entry
  for (std::size_t i = 0; i < layer.points.size(); ++i) {
    const PathPoint& cur = layer.points[i];
    const PathPoint* prev = st.prev;
    ++st.global_point;
    const double length = prev ? (cur.p_P - prev->p_P).norm() : 0.0;
    const int n = prev ? Subdivisions(length, options.step_mm) : 1;
    // The move into a layer's first point carries the positioner from the last layer's angles to this layer's.
    const bool reorient = (i == 0);
    const PositionerAngles move_start = st.angles;  // where the positioner is when this move starts
    for (int k = 1; k <= n; ++k) {
      const double f = prev ? static_cast<double>(k) / n : 1.0;
      if (entry.welded) along += length / n;
      std::optional<double> g;  // how far the layer's entry has turned
      if (entry.welded && entry.length_mm > 0.0) {
        g = std::min(1.0, along / entry.length_mm);
      } else if (reorient) {
        g = f;
      }
      CellSample s;
      s.layer = layer.index;
      s.point = st.global_point;
      s.weld = cur.weld && prev != nullptr;
      s.p_P = prev ? Eigen::Vector3d(prev->p_P + f * (cur.p_P - prev->p_P)) : cur.p_P;
      const Eigen::Vector3d tool_dir_P =
          (prev ? Eigen::Vector3d((1.0 - f) * prev->tool_dir_P + f * cur.tool_dir_P) : cur.tool_dir_P).normalized();
      s.bead_width_mm = cur.bead_width_mm;
      s.bead_height_mm = cur.bead_height_mm;
      s.speed_mm_s = (s.weld && cur.speed_mm_s > 0.0) ? cur.speed_mm_s : options.rapid_speed_mm_s;
      st.angles = PositionerAt(cell, options, cur, tool_dir_P, move_start, st, entry, f, g, s);
      s.q[6] = st.angles.tilt;
      s.q[7] = st.angles.rotation;
      out.spins.push_back(g ? st.previous_spin + *g * (entry.spin - st.previous_spin) : entry.spin);
      out.tool_dirs_P.push_back(tool_dir_P);
      out.samples.push_back(s);
    }
    st.prev = &cur;
  }
}

// The path sampled in the part frame: the positioner leads, layer by layer.
PathSamples SampleAlongPath(const CellKinematics& cell, const Plan& plan, const MotionOptions& options) {
  PathSamples out;
  out.samples.reserve(CountCellSamples(plan, options.step_mm));
  out.tool_dirs_P.reserve(out.samples.capacity());
  out.spins.reserve(out.samples.capacity());
  const auto layer_spin = [&](std::size_t l) {
    return l < options.layer_spin_rad.size() ? options.layer_spin_rad[l] : 0.0;
  };
  SamplingState st;
  st.angles.rotation = options.rotation_rad;
  st.previous_layer_angles = st.angles;
  st.previous_spin = layer_spin(0);
  for (std::size_t l = 0; l < plan.layers.size(); ++l) {
    const LayerEntry entry = EnterLayer(cell, options, plan.layers[l], layer_spin(l), st);
    if (l == 0) st.previous_layer_angles = entry.angles;
    SampleLayer(cell, options, plan.layers[l], entry, st, out);
    st.previous_layer_angles = entry.angles;
    st.previous_spin = entry.spin;
  }
  return out;
}

// eq. 5.14-5.18: TCP point and torch axis from the (turned) part frame into the world, in parallel (each sample on
// its own).
void PoseTorches(const CellKinematics& cell, PathSamples& path) {
  std::vector<CellSample>& samples = path.samples;
  const std::size_t chunks = (samples.size() + kPoseChunk - 1) / kPoseChunk;
  ParallelFor(chunks, [&](std::size_t c) {
    const std::size_t end = std::min(samples.size(), (c + 1) * kPoseChunk);
    for (std::size_t i = c * kPoseChunk; i < end; ++i) {
      CellSample& s = samples[i];
      const Eigen::Isometry3d X_WP = cell.X_WB * PartPose(cell.positioner, s.q[6], s.q[7]);
      const Eigen::Vector3d p_W = X_WP * s.p_P;
      const Eigen::Vector3d tool_dir_W = X_WP.linear() * path.tool_dirs_P[i];
      s.torch_tilt_rad = std::acos(std::clamp(tool_dir_W.z(), -1.0, 1.0));
      s.X_WT = TorchPose(cell, p_W, tool_dir_W, path.spins[i]);
    }
  });
}

// The arm joints of one sample (flange pose X_RF in the arm base frame), from the previous sample's: `seed` and
// `seed_branch` (the OPW branch of the last solution, -1: none yet) move on to this sample's solution when it has one.
void SolveArmAt(const CellKinematics& cell, const Eigen::Isometry3d& X_RF, Joints6& seed, int& seed_branch,
                CellSample& s) {
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
}

// Time of the move from `last` to `s`: weld moves at the planned speed relative to the part; arc-off moves at the
// rapid speed, slowed down so that no axis exceeds its speed. s.
double MoveTime(const CellKinematics& cell, const CellSample& last, const CellSample& s) {
  const double ds = (s.p_P - last.p_P).norm();
  double dt = ds / s.speed_mm_s;
  if (!s.weld) {
    for (int j = 0; j < 6; ++j) dt = std::max(dt, std::abs(s.q[j] - last.q[j]) / cell.arm.max_speed[j]);
    dt = std::max(dt, std::abs(s.q[6] - last.q[6]) / cell.positioner.tilt_max_speed);
    dt = std::max(dt, std::abs(s.q[7] - last.q[7]) / cell.positioner.rotation_max_speed);
  }
  return dt;
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
  PathSamples path = SampleAlongPath(cell, plan, options);
  PoseTorches(cell, path);
  std::vector<CellSample>& samples = path.samples;
  const Eigen::Isometry3d X_RW = cell.X_WR.inverse();
  const Eigen::Isometry3d X_TF = cell.X_FT.inverse();
  // The arm joints, each from the previous sample's (the branch kept continuous), and the time stamps: in order.
  // Home posture of the arm: upper arm up, forearm forward, flange pointing down (j5 = -90 deg).
  Joints6 seed;
  seed << 0.0, 0.0, 0.0, 0.0, -(kPi / 2), 0.0;
  int seed_branch = -1;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    CellSample& s = samples[i];
    SolveArmAt(cell, X_RW * s.X_WT * X_TF, seed, seed_branch, s);
    if (i > 0) {
      s.dt_s = MoveTime(cell, samples[i - 1], s);
      s.t_s = samples[i - 1].t_s + s.dt_s;
    }
    if (progress && ((i + 1) & 1023u) == 0) progress(i + 1);
  }
  if (progress) progress(samples.size());
  return std::move(samples);
}

}  // namespace waam::planner
