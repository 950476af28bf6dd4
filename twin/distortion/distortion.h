// Shrinkage and distortion of the deposited part: the inherent-strain method on a coarse voxel hexahedral mesh
// (mode fe) or layer-wise shrinkage and bending of the central axis (mode reduced), one interface for both.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

#include "models/distortion/distortion_params.h"
#include "twin/deposition/voxel_grid.h"
#include "twin/distortion/deposit_history.h"

namespace waam::twin {

// The FE system's solver: cg (ConjugateGradient, incomplete Cholesky; half the time and memory) or ldlt.
enum class FeSolver { kCg, kLdlt };
constexpr std::array<EnumName<FeSolver>, 2> EnumNames(FeSolver) {
  return {{{FeSolver::kCg, "cg"}, {FeSolver::kLdlt, "ldlt"}}};
}
WAAM_ENUM_JSON(FeSolver)

// What the thermal model computed for one plan layer (analysis/thermal_run), the data the thermal strain law reads.
struct LayerHeat {
  double interpass_c = 0.0;  // temperature of the metal the layer is laid on, just before its first arc, degC
  double peak_c = 0.0;       // hottest metal while the layer is welded, degC
};

struct DistortionOptions {
  models::DistortionMode mode = models::DistortionMode::kFe;
  double element_mm = 2.0;      // edge of the hexahedral elements, mm (rounded to a whole number of voxels)
  int groups = 4;               // layer groups activated one after the other (fe), >= 1
  FeSolver solver = FeSolver::kCg;
  // The build's thermal history, one entry per plan layer: each voxel's strain is scaled by
  // DistortionParams::ThermalFactor of its layer. Empty = the strains as fitted.
  std::vector<LayerHeat> layer_heat;
};

// Throws InputError "distortion.<field> = value: must be ..." for an option out of range.
void ValidateDistortionOptions(const DistortionOptions& options);

// Size and cost of one distortion solve.
struct DistortionStats {
  std::size_t elements = 0;        // active hexahedra of the final part
  std::size_t nodes = 0;
  std::size_t dofs = 0;            // unknowns of the largest linear system (3 per node)
  std::size_t nonzeros = 0;        // stored entries (lower triangle) of the largest stiffness matrix
  std::size_t dropped_elements = 0;  // elements not connected to the substrate through the mesh (left rigid)
  int solves = 0;
  double solve_s = 0.0;            // wall-clock time of assembly and solves, s
  double max_displacement_mm = 0.0;
};

// The displacement field of the part after cooling, on the nodes of the hexahedral mesh (part frame, mm).
class DistortionField {
 public:
  DistortionField() = default;
  // Node displacements (mm) and active elements of a mesh of `element_mm` cubes, each keyed by the CellKey of its
  // (i, j, k): node (i, j, k) lies at (i, j, k) * element_mm; element (i, j, k) spans nodes (i, j, k) to
  // (i+1, j+1, k+1).
  DistortionField(double element_mm, std::unordered_map<std::uint64_t, Eigen::Vector3d> nodes,
                  std::unordered_map<std::uint64_t, std::uint8_t> elements);

  // Displacement at `p_P` (mm): trilinear in the element containing it, or in the nearest active element within one
  // element, else within two (clamped); zero farther from the part.
  Eigen::Vector3d Displacement(const Eigen::Vector3d& p_P) const;
  double element_mm() const { return element_mm_; }
  std::size_t nodes() const { return nodes_.size(); }

 private:
  const Eigen::Vector3d* Node(int i, int j, int k) const;
  double element_mm_ = 1.0;
  std::unordered_map<std::uint64_t, Eigen::Vector3d> nodes_;  // by CellKey of the node (i, j, k)
  std::unordered_map<std::uint64_t, std::uint8_t> elements_;  // CellKeys of the active elements (value unused)
};

// Computes the distortion of the part in `grid` whose voxels were deposited as `history` records, with the
// inherent strains of `params` (scaled by the thermal law when options.layer_heat is given). Throws InputError for
// invalid params or options, an empty grid, or a thermal history with too few layers or no reference temperature.
DistortionField ComputeDistortion(const VoxelGrid& grid, const DepositHistory& history,
                                  const models::DistortionParams& params, const DistortionOptions& options,
                                  DistortionStats* stats = nullptr);

}  // namespace waam::twin
