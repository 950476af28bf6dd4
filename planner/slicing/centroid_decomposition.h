// Overhang decomposition by the centroid shift between consecutive slices (dissertation 003 sec. 5.4, Fig. 52-57):
// splits a part into a body built along +z and overhanging features, each with its own split plane and direction.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "planner/mesh/triangle_mesh.h"
#include "planner/scenario/scenario.h"

namespace waam::planner {

struct CentroidSplitOptions {
  double step_mm = 1.0;        // z slicing step of the analysis, mm (> 0)
  double overhang_deg = 15.0;  // self-supporting overhang: a layer may step out t tan(overhang) past the one below
                               // it, and a feature is split off when its centroid chain leans more than this, deg
  double min_area_mm2 = 1.0;   // pieces smaller than this never start a feature, mm^2
};

// One overhanging feature split off the body.
struct OverhangFeature {
  std::string name;                      // "overhang_<k>", k from 1 in order of first layer
  Eigen::Vector3d split_normal = Eigen::Vector3d::UnitX();  // unit, part frame, pointing into the feature
  double split_offset_mm = 0.0;          // the split plane is split_normal . p = split_offset_mm
  Eigen::Vector3d centroid_mm = Eigen::Vector3d::Zero();  // of the feature's slices, part frame
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();  // centroidal axis: split-line centre to centroid (unit)
  double max_gamma_deg = 0.0;            // largest angle between +z and consecutive centroids (eq. 5.25-5.26)
  double z_min_mm = 0.0;                 // first and last slice heights holding the feature, mm
  double z_max_mm = 0.0;
  double volume_mm3 = 0.0;               // sum of its slice areas x step
};

struct CentroidDecomposition {
  std::vector<SubVolumeSpec> sub_volumes;   // "body" (+z, on the build plate) first, then one per feature
  std::vector<OverhangFeature> features;
  int slices = 0;                           // slices analysed
  int candidates_merged = 0;                // overhang candidates whose centroid chain stayed within overhang_deg
};

// Slices `mesh` (closed, mm) along z every options.step_mm, follows each slice region upwards and splits off the
// overhanging features: a piece of a slice outside the slice below grown by t tan(overhang) starts a candidate; the
// candidate becomes a feature when the centroids of its consecutive slices lean more than overhang_deg from +z.
// Each feature gets the split plane through its first and last split lines (where it meets the body) and is built
// along that plane's normal, away from the body; the body keeps the other side of every split plane. A part without
// such features gives the body alone. Throws InputError (prefixed by `where`) for bad options or a feature that
// never meets the body (it cannot be built).
CentroidDecomposition DecomposeByCentroidShift(const TriangleMesh& mesh, const CentroidSplitOptions& options,
                                               const std::string& where);

}  // namespace waam::planner
