// The cell's MuJoCo geoms as convex shapes for distance queries: their pairs as MuJoCo 2.2's collision detection
// filters them, the lever arm of every axis over every shape, and the shapes' poses.
#include <array>
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "models/core/error.h"
#include "twin/cell/mujoco_cell.h"
#include "twin/cell/mujoco_cell_internal.h"

namespace waam::twin {
namespace {

constexpr double kGeomMm = 1000.0;  // model metres -> mm

double Norm3(const mjtNum* v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

// Whether MuJoCo's collision detection tests geoms g1 and g2 (engine_collision_driver.c of MuJoCo 2.2: contype and
// conaffinity, the same weld body, the weld-parent filter, <contact><exclude> body pairs; explicit <pair> elements
// are added by the caller).
bool MujocoTestsPair(const mjModel* m, int g1, int g2) {
  if (!((m->geom_contype[g1] & m->geom_conaffinity[g2]) || (m->geom_contype[g2] & m->geom_conaffinity[g1]))) {
    return false;
  }
  const int b1 = m->geom_bodyid[g1], b2 = m->geom_bodyid[g2];
  const int w1 = m->body_weldid[b1], w2 = m->body_weldid[b2];
  if (w1 == w2) return false;
  const bool filter_parent = !(m->opt.disableflags & mjDSBL_FILTERPARENT);
  if (filter_parent && w1 != 0 && w2 != 0 &&
      (w1 == m->body_weldid[m->body_parentid[w2]] || w2 == m->body_weldid[m->body_parentid[w1]])) {
    return false;
  }
  // mjmodel.h: exclude_signature = (body1 + 1) << 16 + body2 + 1.
  for (int i = 0; i < m->nexclude; ++i) {
    const int s = m->exclude_signature[i];
    if (s == ((b1 + 1) << 16) + b2 + 1 || s == ((b2 + 1) << 16) + b1 + 1) return false;
  }
  return m->geom_type[g1] != mjGEOM_PLANE || m->geom_type[g2] != mjGEOM_PLANE;
}

// Bound on the distance from joint `jnt`'s anchor to any point of geom g, when the joint's body is g's body or an
// ancestor of it; 0 otherwise, mm. Along the chain each body's origin lies within |body_pos| + 2 |jnt_pos| of its
// parent's (a hinge turns the body about its anchor), the joint's anchor within |jnt_pos| of its body's origin.
double LeverBound(const mjModel* m, int jnt, int g) {
  const int joint_body = m->jnt_bodyid[jnt];
  double length = Norm3(m->geom_pos + 3 * g) + m->geom_rbound[g];
  for (int b = m->geom_bodyid[g]; b != joint_body; b = m->body_parentid[b]) {
    if (b == 0) return 0.0;  // reached the world: the joint does not move g
    length += Norm3(m->body_pos + 3 * b);
    for (int k = m->body_jntadr[b]; k >= 0 && k < m->body_jntadr[b] + m->body_jntnum[b]; ++k) {
      length += 2.0 * Norm3(m->jnt_pos + 3 * k);
    }
  }
  return (length + Norm3(m->jnt_pos + 3 * jnt)) * kGeomMm;
}

std::string GeomName(const mjModel* m, int g) {
  const char* name = mj_id2name(m, mjOBJ_GEOM, g);
  return name ? std::string(name) : "#" + std::to_string(g);
}

std::string BodyName(const mjModel* m, int g) {
  const char* name = mj_id2name(m, mjOBJ_BODY, m->geom_bodyid[g]);
  return name ? std::string(name) : "world";
}

// How many edges of a triangle mesh are not shared by exactly two of its faces (0: closed; MuJoCo 2.2 merges repeated
// vertices when it loads an STL, so faces that meet share vertex indices).
int OpenEdges(const std::vector<std::array<int, 3>>& faces) {
  std::map<std::pair<int, int>, int> uses;
  for (const std::array<int, 3>& f : faces) {
    for (int k = 0; k < 3; ++k) ++uses[std::minmax(f[k], f[(k + 1) % 3])];
  }
  int open = 0;
  for (const auto& [edge, n] : uses) open += n != 2;
  return open;
}

// Geom g as a convex shape, or the reason it cannot be one: a height field, an empty mesh or a mesh that is not
// closed. A plane is one (MuJoCo 2.2 refuses a plane on a body that moves when it loads the model).
bool ShapeOf(const mjModel* m, int g, ConvexShape* shape, std::string* why) {
  shape->size_mm = Eigen::Vector3d(m->geom_size[3 * g], m->geom_size[3 * g + 1], m->geom_size[3 * g + 2]) * kGeomMm;
  shape->rbound_mm = m->geom_rbound[g] * kGeomMm;
  switch (m->geom_type[g]) {
    case mjGEOM_PLANE: shape->type = ConvexShape::Type::kPlane; return true;
    case mjGEOM_SPHERE: shape->type = ConvexShape::Type::kSphere; return true;
    case mjGEOM_CAPSULE: shape->type = ConvexShape::Type::kCapsule; return true;
    case mjGEOM_CYLINDER: shape->type = ConvexShape::Type::kCylinder; return true;
    case mjGEOM_BOX: shape->type = ConvexShape::Type::kBox; return true;
    case mjGEOM_ELLIPSOID: shape->type = ConvexShape::Type::kEllipsoid; return true;
    case mjGEOM_MESH: {
      shape->type = ConvexShape::Type::kMesh;
      const int mesh = m->geom_dataid[g];
      if (mesh < 0 || m->mesh_vertnum[mesh] == 0) break;
      const float* vert = m->mesh_vert + 3 * m->mesh_vertadr[mesh];
      const auto add = [&](int i) {
        shape->hull_mm.emplace_back(vert[3 * i] * kGeomMm, vert[3 * i + 1] * kGeomMm, vert[3 * i + 2] * kGeomMm);
      };
      for (int i = 0; i < m->mesh_vertnum[mesh]; ++i) {
        const float* v = vert + 3 * i;
        shape->mesh_mm.emplace_back(v[0] * kGeomMm, v[1] * kGeomMm, v[2] * kGeomMm);
      }
      const int* face = m->mesh_face + 3 * m->mesh_faceadr[mesh];
      for (int f = 0; f < m->mesh_facenum[mesh]; ++f) shape->faces.push_back({face[3 * f], face[3 * f + 1], face[3 * f + 2]});
      const int open = OpenEdges(shape->faces);
      if (open > 0) {
        *why = "geom " + GeomName(m, g) + " (body " + BodyName(m, g) + "): its mesh is not closed (" +
               std::to_string(open) + " edges not shared by exactly two faces): no solid to bound the distance to";
        return false;
      }
      const int graph = m->mesh_graphadr[mesh];
      if (graph >= 0) {
        // MuJoCo's convex hull: numvert, numface, vert_edgeadr[numvert], vert_globalid[numvert], ...
        const int* data = m->mesh_graph + graph;
        const int hull_vertices = data[0];
        for (int i = 0; i < hull_vertices; ++i) add(data[2 + hull_vertices + i]);
      } else {
        for (int i = 0; i < m->mesh_vertnum[mesh]; ++i) add(i);
      }
      return true;
    }
    default:
      break;
  }
  *why = "geom " + GeomName(m, g) + " is a height field or an empty mesh: no distance bound for it";
  return false;
}

}  // namespace

CellCollisionGeometry CellModel::CollisionGeometry() const {
  const mjModel* m = impl_->m;
  CellCollisionGeometry geometry;
  std::vector<int> shape_of(m->ngeom, -1);
  geometry.unsupported = impl_->robot.incomplete_geometry;
  for (int g = 0; g < m->ngeom; ++g) {
    if (!m->geom_contype[g] && !m->geom_conaffinity[g]) continue;
    ConvexShape shape;
    std::string why;
    if (!ShapeOf(m, g, &shape, &why)) {
      if (geometry.unsupported.empty()) geometry.unsupported = why;
      continue;
    }
    Eigen::Matrix<double, 8, 1> lever = Eigen::Matrix<double, 8, 1>::Zero();
    for (int j = 0; j < 8; ++j) {
      if (impl_->jnt[j] >= 0) lever[j] = LeverBound(m, impl_->jnt[j], g);
    }
    // MuJoCo 2.2 refuses a plane on a body that is not static ("plane and hfield only allowed in static bodies").
    WAAM_DEMAND(shape.type != ConvexShape::Type::kPlane || lever.maxCoeff() == 0.0);
    shape_of[g] = static_cast<int>(geometry.shapes.size());
    geometry.shapes.push_back(std::move(shape));
    geometry.geom.push_back(g);
    geometry.body.push_back(BodyName(m, g));
    geometry.lever_mm.push_back(lever);
  }
  // The tree: every body with its fixed pose in its parent and the axis that turns it.
  const auto pose_of = [](const mjtNum* pos, const mjtNum* quat) {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.translation() = Eigen::Vector3d(pos[0], pos[1], pos[2]) * kGeomMm;
    X.linear() = Eigen::Quaterniond(quat[0], quat[1], quat[2], quat[3]).normalized().toRotationMatrix();
    return X;
  };
  geometry.links.resize(m->nbody);
  for (int b = 1; b < m->nbody; ++b) {
    CellCollisionGeometry::Link& link = geometry.links[b];
    link.parent = m->body_parentid[b];
    link.X_PL = pose_of(m->body_pos + 3 * b, m->body_quat + 4 * b);
    // Joints other than the eight axes stay at their reference (SetJoints never moves them): no motion.
    for (int k = m->body_jntadr[b]; k >= 0 && k < m->body_jntadr[b] + m->body_jntnum[b]; ++k) {
      for (int j = 0; j < 8; ++j) {
        if (impl_->jnt[j] != k) continue;
        link.axis = j;
        link.anchor_L = Eigen::Vector3d(m->jnt_pos[3 * k], m->jnt_pos[3 * k + 1], m->jnt_pos[3 * k + 2]) * kGeomMm;
        link.axis_L = Eigen::Vector3d(m->jnt_axis[3 * k], m->jnt_axis[3 * k + 1], m->jnt_axis[3 * k + 2]).normalized();
        link.q0 = m->qpos0[m->jnt_qposadr[k]];
      }
    }
  }
  const int nozzle = impl_->nozzle;
  geometry.nozzle_link = m->geom_bodyid[nozzle];
  geometry.X_LN = pose_of(m->geom_pos + 3 * nozzle, m->geom_quat + 4 * nozzle);
  for (int j = 0; j < 8; ++j) {
    if (impl_->jnt[j] >= 0) geometry.nozzle_lever_mm[j] = LeverBound(m, impl_->jnt[j], nozzle);
  }
  for (int g : geometry.geom) {
    geometry.link.push_back(m->geom_bodyid[g]);
    geometry.X_LG.push_back(pose_of(m->geom_pos + 3 * g, m->geom_quat + 4 * g));
  }
  for (int g1 = 0; g1 < m->ngeom; ++g1) {
    for (int g2 = g1 + 1; g2 < m->ngeom; ++g2) {
      if (shape_of[g1] >= 0 && shape_of[g2] >= 0 && MujocoTestsPair(m, g1, g2)) {
        geometry.pairs.push_back({shape_of[g1], shape_of[g2]});
      }
    }
  }
  for (int p = 0; p < m->npair; ++p) {
    const int a = shape_of[m->pair_geom1[p]], b = shape_of[m->pair_geom2[p]];
    if (a >= 0 && b >= 0) geometry.pairs.push_back({a, b});
  }
  return geometry;
}

void LinkPosesAt(const CellCollisionGeometry& geometry, const planner::Joints8& q,
                 std::vector<Eigen::Isometry3d>* X_WL_out) {
  // mj_kinematics of MuJoCo 2.2 per body: the parent's frame times the body's fixed pose, then each hinge turns the
  // body about its anchor (x_anchor fixed, rotation by q - q0 about the axis in the body frame).
  std::vector<Eigen::Isometry3d>& X_WL = *X_WL_out;
  X_WL.resize(geometry.links.size());
  if (!X_WL.empty()) X_WL[0].setIdentity();
  for (std::size_t b = 1; b < geometry.links.size(); ++b) {
    const CellCollisionGeometry::Link& link = geometry.links[b];
    Eigen::Isometry3d X = X_WL[link.parent] * link.X_PL;
    if (link.axis >= 0) {
      const Eigen::Vector3d anchor_W = X * link.anchor_L;
      X.linear() = X.linear() * Eigen::AngleAxisd(q[link.axis] - link.q0, link.axis_L).toRotationMatrix();
      X.translation() = anchor_W - X.linear() * link.anchor_L;
    }
    X_WL[b] = X;
  }
}

void ShapePosesAt(const CellCollisionGeometry& geometry, const planner::Joints8& q,
                  std::vector<Eigen::Isometry3d>* X_WG) {
  thread_local std::vector<Eigen::Isometry3d> X_WL;
  LinkPosesAt(geometry, q, &X_WL);
  X_WG->resize(geometry.link.size());
  for (std::size_t i = 0; i < geometry.link.size(); ++i) (*X_WG)[i] = X_WL[geometry.link[i]] * geometry.X_LG[i];
}

void CellState::ShapePoses(const CellCollisionGeometry& geometry, std::vector<Eigen::Isometry3d>* X_WG) const {
  const mjData* d = data_->d.get();
  X_WG->resize(geometry.geom.size());
  for (std::size_t i = 0; i < geometry.geom.size(); ++i) {
    const int g = geometry.geom[i];
    Eigen::Isometry3d& X = (*X_WG)[i];
    X.setIdentity();
    X.translation() = Eigen::Vector3d(d->geom_xpos[3 * g], d->geom_xpos[3 * g + 1], d->geom_xpos[3 * g + 2]) * kGeomMm;
    X.linear() = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(d->geom_xmat + 9 * g);
  }
}

}  // namespace waam::twin
