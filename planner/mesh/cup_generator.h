// A cup with two handles (the decomposition example of the dissertation, Fig. 52): a test part for overhang splits.
#pragma once

#include <string>

#include "planner/mesh/triangle_mesh.h"

namespace waam::planner {

// The cup: a cylindrical shell of outer radius `radius_mm` and height `height_mm` (axis x = y = 0, standing on
// z = 0) with a wall `wall_mm` thick and a bottom `bottom_mm` thick. Each handle is a half torus in a vertical plane
// through the axis (at 0 and 180 deg round z): its centre line a half circle of radius `handle_radius_mm` centred on
// the outer wall at height `handle_z_mm`, its section a circle of radius `handle_tube_mm`. The handle ends are
// pressed onto the cylinder r = radius + kCupHandleGapMm, so the three shells (cup, two handles) are closed and do not
// touch. All lengths mm.
struct CupParams {
  double radius_mm = 37.5;
  double height_mm = 90.0;
  double wall_mm = 4.0;
  double bottom_mm = 5.0;
  double handle_radius_mm = 22.0;
  double handle_tube_mm = 5.0;
  double handle_z_mm = 58.0;
  int segments = 96;          // round the cup
  int handle_sections = 48;   // along each handle's half circle
  int handle_points = 24;     // round each handle's section
};

// Clearance between a handle end and the cup wall, mm (the slicer sees the shells apart; a bead bridges it).
inline constexpr double kCupHandleGapMm = 0.05;

// The closed mesh (three shells, outward normals). Throws InputError (prefixed by `where`) when the handles do not
// fit the cup: handle_tube >= handle_radius, a handle reaching below z = 0 or above the rim, wall >= radius,
// bottom >= height or handle_tube > radius / 2.
TriangleMesh BuildCupTwoHandles(const CupParams& p, const std::string& where);

// The analytic volume of the cup and handles (mm^3): pi (R^2 H - (R - w)^2 (H - b)) + 2 pi^2 a^2 r_h (Pappus).
double CupTwoHandlesVolume(const CupParams& p);

}  // namespace waam::planner
