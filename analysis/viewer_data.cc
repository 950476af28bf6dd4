// The data of viewer.html: the cell's bodies once (geoms in the body frame), the body and part poses per animation
// frame, the planned path and beads in the part frame, the target mesh and the violations, arrays as base64.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string_view>

#include "analysis/viewer.h"
#include "planner/kinematics/positioner.h"

namespace waam::analysis {

namespace internal {

std::string Base64(std::string_view bytes) {
  static const char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const std::uint32_t v = (std::uint32_t(std::uint8_t(bytes[i])) << 16) |
                            (std::uint32_t(std::uint8_t(bytes[i + 1])) << 8) | std::uint8_t(bytes[i + 2]);
    out += kDigits[(v >> 18) & 63];
    out += kDigits[(v >> 12) & 63];
    out += kDigits[(v >> 6) & 63];
    out += kDigits[v & 63];
  }
  const std::size_t rest = bytes.size() - i;
  if (rest > 0) {
    std::uint32_t v = std::uint32_t(std::uint8_t(bytes[i])) << 16;
    if (rest == 2) v |= std::uint32_t(std::uint8_t(bytes[i + 1])) << 8;
    out += kDigits[(v >> 18) & 63];
    out += kDigits[(v >> 12) & 63];
    out += rest == 2 ? kDigits[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

}  // namespace internal

namespace {

// A little-endian typed array (x86-64 and every browser's typed arrays agree) as base64.
template <class T>
std::string Pack(const std::vector<T>& values) {
  return internal::Base64(
      std::string_view(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T)));
}

const char* TypeName(twin::CellShape::Type type) {
  switch (type) {
    case twin::CellShape::Type::kPlane: return "plane";
    case twin::CellShape::Type::kSphere: return "sphere";
    case twin::CellShape::Type::kCapsule: return "capsule";
    case twin::CellShape::Type::kCylinder: return "cylinder";
    case twin::CellShape::Type::kBox: return "box";
    case twin::CellShape::Type::kMesh: return "mesh";
    default: return "other";
  }
}

// Position (mm) then quaternion (x, y, z, w, three.js order) of a pose.
void AppendPose(const Eigen::Isometry3d& X, std::vector<float>* out) {
  const Eigen::Quaterniond q(X.linear());
  const Eigen::Vector3d p = X.translation();
  out->insert(out->end(), {float(p.x()), float(p.y()), float(p.z()), float(q.x()), float(q.y()), float(q.z()),
                           float(q.w())});
}

nlohmann::json BodiesJson(const std::vector<twin::CellBody>& bodies) {
  nlohmann::json out = nlohmann::json::array();
  for (const twin::CellBody& body : bodies) {
    nlohmann::json geoms = nlohmann::json::array();
    for (std::size_t g = 0; g < body.geoms.size(); ++g) {
      const twin::CellShape& s = body.geoms[g];
      std::vector<float> pose;
      AppendPose(s.X_WG, &pose);
      nlohmann::json j = {{"type", TypeName(s.type)},
                          {"size", {s.size_mm.x(), s.size_mm.y(), s.size_mm.z()}},
                          {"pose", pose},
                          {"rgba", {s.rgba[0], s.rgba[1], s.rgba[2], s.rgba[3]}}};
      if (!body.mesh_vertices_mm[g].empty()) {
        std::vector<float> v;
        for (const Eigen::Vector3f& p : body.mesh_vertices_mm[g]) v.insert(v.end(), {p.x(), p.y(), p.z()});
        std::vector<std::uint32_t> f;
        for (const Eigen::Vector3i& t : body.mesh_triangles[g]) {
          f.insert(f.end(), {std::uint32_t(t.x()), std::uint32_t(t.y()), std::uint32_t(t.z())});
        }
        j["vertices"] = Pack(v);
        j["triangles"] = Pack(f);
      }
      geoms.push_back(std::move(j));
    }
    out.push_back({{"name", body.name}, {"joint", body.joint}, {"geoms", std::move(geoms)}});
  }
  return out;
}

std::string OneIn(std::size_t stride) { return stride == 1 ? "all" : "1 in " + std::to_string(stride); }

// The motion samples shown: every k-th one, the last one and each listed violation's worst sample.
std::vector<std::size_t> FrameSamples(const twin::CheckReport& report, std::size_t max_frames, std::size_t* stride) {
  const std::size_t n = report.motion.size();
  std::vector<std::size_t> picked;
  *stride = std::max<std::size_t>(1, (n + max_frames - 1) / std::max<std::size_t>(1, max_frames));
  if (n == 0) return picked;
  for (std::size_t i = 0; i < n; i += *stride) picked.push_back(i);
  picked.push_back(n - 1);
  for (const twin::CheckViolation& v : report.violations) {
    if (v.sample >= 0 && std::size_t(v.sample) < n) picked.push_back(std::size_t(v.sample));
  }
  std::sort(picked.begin(), picked.end());
  picked.erase(std::unique(picked.begin(), picked.end()), picked.end());
  return picked;
}

// The frames' body and part poses, TCP, time, layer and arc state.
nlohmann::json FramesJson(const twin::CellModel& cell, const planner::CellKinematics& kin,
                          const twin::CheckReport& report, const std::vector<std::size_t>& frames) {
  std::vector<float> t, body_poses, part_poses, tcp_W;
  std::vector<std::int32_t> frame_layer;
  std::vector<std::uint8_t> frame_weld;
  twin::CellState state(cell);
  for (std::size_t i : frames) {
    const planner::CellSample& s = report.motion[i];
    state.SetJoints(s.q);
    for (const Eigen::Isometry3d& X_WB : state.BodyPoses()) AppendPose(X_WB, &body_poses);
    AppendPose(kin.X_WB * planner::PartPose(kin.positioner, s.q[6], s.q[7]), &part_poses);
    const Eigen::Vector3d p = s.X_WT.translation();
    tcp_W.insert(tcp_W.end(), {float(p.x()), float(p.y()), float(p.z())});
    t.push_back(float(s.t_s));
    frame_layer.push_back(s.layer);
    frame_weld.push_back(s.weld ? 1 : 0);
  }
  return {{"count", frames.size()},     {"t", Pack(t)},         {"body_poses", Pack(body_poses)},
          {"part_poses", Pack(part_poses)}, {"tcp_W", Pack(tcp_W)}, {"layer", Pack(frame_layer)},
          {"weld", Pack(frame_weld)}};
}

// What the page's path holds, for the sampling note and the summary.
struct PathCounts {
  std::size_t total_points = 0;  // plan points
  std::size_t path_points = 0;   // kept
  std::size_t stride = 1;        // every stride-th point kept (and each layer's first and last)
  std::size_t beads = 0;         // kept points that end a bead segment
};

// The path and its beads in the part frame: every k-th point, and each layer's first and last, with the time the
// torch reaches each.
nlohmann::json PathJson(const planner::Plan& plan, const twin::CheckReport& report, const ViewerBudget& budget,
                        PathCounts* counts) {
  // When the torch reaches each plan point (the last sample of the move ending there), s.
  std::size_t total_points = 0;
  for (const planner::LayerPath& layer : plan.layers) total_points += layer.points.size();
  std::vector<double> reached(total_points, -1.0);
  for (const planner::CellSample& s : report.motion) {
    if (s.point >= 0 && std::size_t(s.point) < total_points) reached[s.point] = s.t_s;
  }
  double last = 0.0;
  for (double& r : reached) r = r < 0.0 ? last : (last = r);

  const std::size_t path_stride = std::max<std::size_t>(
      1, (total_points + budget.max_path_points - 1) / std::max<std::size_t>(1, budget.max_path_points));
  std::vector<float> p_P, up_P, width, height, reach_t;
  std::vector<std::int32_t> layer_of;
  std::vector<std::uint8_t> weld;
  std::size_t g = 0, beads = 0;
  for (const planner::LayerPath& layer : plan.layers) {
    bool weld_since_kept = false;
    for (std::size_t k = 0; k < layer.points.size(); ++k, ++g) {
      const planner::PathPoint& p = layer.points[k];
      weld_since_kept = weld_since_kept || p.weld;
      if (g % path_stride != 0 && k != 0 && k + 1 != layer.points.size()) continue;
      p_P.insert(p_P.end(), {float(p.p_P.x()), float(p.p_P.y()), float(p.p_P.z())});
      up_P.insert(up_P.end(), {float(p.tool_dir_P.x()), float(p.tool_dir_P.y()), float(p.tool_dir_P.z())});
      width.push_back(float(p.bead_width_mm));
      height.push_back(float(p.bead_height_mm));
      reach_t.push_back(float(reached[g]));
      layer_of.push_back(layer.index);
      // A kept point welds when any move since the previous kept point did (a bead needs a previous point).
      const bool welds = weld_since_kept && k != 0;
      weld.push_back(welds ? 1 : 0);
      beads += welds ? 1 : 0;
      weld_since_kept = false;
    }
  }
  *counts = {total_points, weld.size(), path_stride, beads};
  return {{"count", weld.size()},  {"p_P", Pack(p_P)},  {"up_P", Pack(up_P)},      {"width", Pack(width)},
          {"height", Pack(height)}, {"t", Pack(reach_t)}, {"layer", Pack(layer_of)}, {"weld", Pack(weld)}};
}

// The target as a ghost in the part frame into data["target"], unless it is too large for the page; the note
// saying which.
std::string AddTarget(const planner::TriangleMesh* target, const ViewerBudget& budget, nlohmann::json* data) {
  if (target && !target->facets.empty() && target->facets.size() <= budget.max_target_facets) {
    std::vector<float> v;
    for (const Eigen::Vector3d& p : target->vertices) v.insert(v.end(), {float(p.x()), float(p.y()), float(p.z())});
    std::vector<std::uint32_t> f;
    for (const std::array<int, 3>& t3 : target->facets) {
      f.insert(f.end(), {std::uint32_t(t3[0]), std::uint32_t(t3[1]), std::uint32_t(t3[2])});
    }
    (*data)["target"] = {{"vertices", Pack(v)}, {"triangles", Pack(f)}};
    return "target mesh: " + std::to_string(target->facets.size()) + " facets";
  }
  if (target && !target->facets.empty()) {
    return "target mesh left out (" + std::to_string(target->facets.size()) + " facets, over the budget of " +
           std::to_string(budget.max_target_facets) + ")";
  }
  return "no target mesh";
}

// Violations (those check.json lists) with the frame of their worst sample and the bodies to highlight.
nlohmann::json ViolationsJson(const twin::CheckReport& report, const std::vector<twin::CellBody>& bodies,
                              const std::vector<std::size_t>& frames) {
  nlohmann::json violations = nlohmann::json::array();
  for (std::size_t i = 0; i < report.violations.size() && i < 1000; ++i) {
    const twin::CheckViolation& v = report.violations[i];
    if (v.sample < 0 || std::size_t(v.sample) >= report.motion.size()) continue;
    const planner::CellSample& s = report.motion[v.sample];
    const bool collision = v.kind == twin::ViolationKind::kCollision;
    nlohmann::json highlight = nlohmann::json::array();
    for (const twin::CellBody& b : bodies) {
      const bool hit = collision ? (b.name == v.body1 || b.name == v.body2) : (!v.joint.empty() && b.joint == v.joint);
      if (hit) highlight.push_back(b.name);
    }
    const auto frame = std::lower_bound(frames.begin(), frames.end(), std::size_t(v.sample)) - frames.begin();
    violations.push_back({{"kind", v.kind},
                          {"layer", v.layer},
                          {"point", v.point},
                          {"joint", v.joint},
                          {"bodies", collision ? nlohmann::json{v.body1, v.body2} : nlohmann::json::array()},
                          {"value", std::isfinite(v.value) ? v.value : 0.0},
                          {"unit", v.unit},
                          {"t_s", s.t_s},
                          {"frame", frame},
                          {"p_P", {s.p_P.x(), s.p_P.y(), s.p_P.z()}},
                          {"highlight", highlight}});
  }
  return violations;
}

}  // namespace

nlohmann::json ViewerData(const std::string& scenario_name, const twin::CellModel& cell,
                          const planner::CellKinematics& kin, const planner::Plan& plan,
                          const planner::TriangleMesh* target, const twin::CheckReport& report,
                          const ViewerBudget& budget, ViewerSummary* summary) {
  const std::vector<twin::CellBody> bodies = cell.Bodies();
  std::size_t stride = 1;
  const std::vector<std::size_t> frames = FrameSamples(report, budget.max_frames, &stride);
  PathCounts path;
  nlohmann::json data = {
      {"scenario", scenario_name},
      {"samples", report.motion.size()},
      {"duration_s", report.duration_s},
      {"layers", plan.layers.size()},
      {"bodies", BodiesJson(bodies)},
      {"frames", FramesJson(cell, kin, report, frames)},
      {"path", PathJson(plan, report, budget, &path)},
  };
  const std::string target_note = AddTarget(target, budget, &data);
  const nlohmann::json violations = ViolationsJson(report, bodies, frames);
  data["violations"] = violations;

  std::ostringstream sampling;
  sampling << frames.size() << " frames of " << report.motion.size() << " checked samples (" << OneIn(stride)
           << ", the last one and each violation's worst); path: " << path.path_points << " of " << path.total_points
           << " plan points (" << OneIn(path.stride) << " and each layer's ends), " << path.beads
           << " planned bead segments; " << target_note;
  data["sampling"] = sampling.str();

  if (summary) {
    summary->frames = frames.size();
    summary->bodies = bodies.size();
    summary->violations = violations.size();
    summary->path_points = path.path_points;
    summary->beads = path.beads;
  }
  return data;
}

}  // namespace waam::analysis
