// Internal to the distortion model: the two solvers behind ComputeDistortion.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "models/distortion/distortion_params.h"
#include "twin/distortion/distortion.h"
#include "twin/distortion/hex_mesh.h"

namespace waam::twin::internal {

// Nodal displacements (mm, one per mesh node) of the inherent-strain FE model with group activation.
std::vector<Eigen::Vector3d> SolveInherentStrain(const HexMesh& mesh, const models::DistortionParams& params,
                                                 const DistortionOptions& options, DistortionStats* stats);

// Nodal displacements of the reduced model: in-layer shrinkage towards each layer's centroid, build-direction
// shrinkage and the bending of the central axis by the strain gradient across each layer.
std::vector<Eigen::Vector3d> SolveReduced(const HexMesh& mesh, const DepositHistory& history,
                                          const models::DistortionParams& params);

}  // namespace waam::twin::internal
