// Blades on a cone or cylinder (the thruster blades of Dai et al. 2020 sec. 5): a test part for cone slicing.
#pragma once

#include "planner/mesh/triangle_mesh.h"

namespace waam::planner {

// Blades standing on the cone x^2 + y^2 = R^2 (z/H - 1)^2 (axis = z axis, radius R at z = 0, apex at z = H; H = +inf
// for a cylinder), spaced evenly round the axis. Each blade grows along the surface normal from `root_mm` inside the
// surface (so it is rooted in the spindle) to `span_mm`; its section is an ellipse of `chord_mm` by a thickness
// tapering from `root_thickness_mm` to `tip_thickness_mm`, centred at height `root_z_mm` on the surface and turned
// in the tangent plane by a pitch going from `pitch_root_deg` to `pitch_tip_deg` (0: chord along the generatrix).
// Lengths mm, angles deg. The mesh is closed, one shell per blade, outward normals.
struct ConeBladeParams {
  int blades = 6;
  double R_mm = 60.0;
  double H_mm = 200.0;
  double root_z_mm = 60.0;
  double root_mm = 2.0;
  double span_mm = 70.0;
  double chord_mm = 60.0;
  double root_thickness_mm = 24.0;
  double tip_thickness_mm = 14.0;
  double pitch_root_deg = 25.0;
  double pitch_tip_deg = 45.0;
  int sections = 24;
  int section_points = 32;
};

TriangleMesh BuildConeBlades(const ConeBladeParams& p);

// A propeller like Lim & Soh's (seed 002): a square hub prism of half-width p.R_mm (the blade roots sit on its flats,
// the split planes of the hub-and-blade decomposition) and `hub_height_mm` tall from z = 0, with p.blades blades (a
// cylinder of radius R: p.H_mm is ignored) rooted on the flats (root_mm is taken as 0: the hub stands 0.01 mm
// clear of the blade roots so that the shells do not touch). Needs 4 blades at most (one per flat).
TriangleMesh BuildPropeller(ConeBladeParams p, double hub_height_mm);

}  // namespace waam::planner
