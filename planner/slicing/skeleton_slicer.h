// Skeleton-following adaptive slicing of bent thin-walled parts (dissertation seed 003, sec. 6.3.1, Fig. 56 and 61;
// normal update of sec. 5.4, eq. 5.23-5.26): planes through the section centroids, tilted along the central axis,
// giving layers of non-uniform thickness within [h_min, h_max].
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "models/core/numbers.h"
#include "planner/geometry/polygon.h"
#include "planner/mesh/triangle_mesh.h"

namespace waam {
class Progress;
}

namespace waam::planner {

struct SkeletonSliceOptions {
  double h_min_mm = 1.0;        // smallest layer thickness the process can deposit, mm (Table 16)
  double h_max_mm = 2.0;        // largest, mm (Table 16)
  double first_step_mm = 0.0;   // initial moving distance h' along the normal, mm; 0 = (h_min + h_max) / 2
  double beta_rad = 0.1 * kPi / 180.0;  // re-orient the plane when gamma > beta (eq. 5.26), rad
  double wall_mm = 0.0;         // wall thickness for the mid-wall curve, mm; 0 = area / mean perimeter of the cut
  double tolerance = 0.01;      // relative slack on [h_min, h_max] before a layer counts as out of range
  int max_iterations = 12;      // Fig. 56 rescaling and eq. 5.26 re-orientation rounds per layer
  // Checks the values; throws InputError "<where>.h_min_mm = ...: ..." naming the key that is wrong.
  void Validate(const std::string& where) const;
};

// One slicing plane and what it cuts. Plane coordinates (x, y) map to p_P = origin_P + x e1_P + y e2_P.
struct SkeletonLayer {
  Eigen::Vector3d origin_P = Eigen::Vector3d::Zero();    // point G the plane was placed through, mm
  Eigen::Vector3d centroid_P = Eigen::Vector3d::Zero();  // area centroid I_i of the cut, on the plane, mm
  Eigen::Vector3d normal_P = Eigen::Vector3d::UnitZ();   // unit plane normal N (the layer's build direction)
  Eigen::Vector3d e1_P = Eigen::Vector3d::UnitX();       // in-plane axes, transported from layer to layer
  Eigen::Vector3d e2_P = Eigen::Vector3d::UnitY();
  PolygonWithHoles section;     // the cut nearest the axis, plane coordinates (mm)
  Ring mid_curve;               // mid-wall curve (the nominal path), counter-clockwise, plane coordinates (mm)
  double step_mm = 0.0;         // h' used: distance from the previous centroid to the plane point G, mm
  double min_height_mm = 0.0;   // smallest distance of the mid curve to the previous plane (layer thickness), mm
  double max_height_mm = 0.0;   // largest, mm
  bool in_range = true;         // thickness within [h_min, h_max] (with the tolerance)

  Eigen::Vector3d ToPart(const Eigen::Vector2d& q) const { return origin_P + q.x() * e1_P + q.y() * e2_P; }
};

struct SkeletonSlicing {
  SkeletonLayer base;                   // the cut just above the substrate (z = 0), the plane under layer 0
  std::vector<SkeletonLayer> layers;    // top plane of each deposited layer, from the base up
  int out_of_range_layers = 0;          // layers whose thickness left [h_min, h_max] after Fig. 56 rescaling
  double wall_mm = 0.0;                 // wall thickness used for the mid curves, mm
};

// Slices `mesh` (closed, part frame, base on z = 0) along its skeleton. Throws InputError for bad options or a mesh
// without a section at its base. `progress` may be null.
SkeletonSlicing SliceAlongSkeleton(const TriangleMesh& mesh, const SkeletonSliceOptions& options, Progress* progress);

// The central axis of the slicing: the chain of cut centroids I_0 (base) ... I_n, mm.
std::vector<Eigen::Vector3d> CentroidChain(const SkeletonSlicing& slicing);

// The bend radius needed for a section extent `d_mm` in the bend plane so that layers stay within
// [h_min, h_max] (eq. 6.3-6.4 solved for R): R_min = d/2 (lambda + 1)/(lambda - 1), lambda = h_max / h_min
// (lambda = 2 gives R_min = 1.5 d). Infinite for h_max == h_min.
double MinimumBendRadius(double d_mm, double h_min_mm, double h_max_mm);

// Smallest local bend radius along the centroid chain (angle between layer normals over +-`window` layers), and
// the section extent d in that bend's plane at the same layer, mm. radius is +inf for a straight part.
struct BendEstimate {
  double radius_mm = 0.0;
  double extent_mm = 0.0;
  int layer = -1;
};
BendEstimate EstimateTightestBend(const SkeletonSlicing& slicing, int window);

}  // namespace waam::planner
