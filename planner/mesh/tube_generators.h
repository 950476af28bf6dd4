// Bent thin-walled tubes (dissertation seed 003, sec. 6.2, parts I-IV): a section swept along a straight-arc-straight
// central axis, as a closed solid wall mesh plus the axis itself.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "planner/mesh/generators.h"
#include "planner/mesh/triangle_mesh.h"

namespace waam::planner {

// The tube: the section's mid-wall outline is swept along a central axis that runs up +z for `straight_start_mm`,
// bends towards +x on an arc of `bend_radius_mm` through `bend_angle_rad`, then runs straight for `straight_end_mm`.
// The section size and shape blend linearly along the axis from the start to the end values.
struct BentTubeSpec {
  double diameter_start_mm = 100.0;  // mid-wall section size at the base: diameter, or width across flats, mm
  double diameter_end_mm = 100.0;    // the same at the top, mm
  int sides_start = 0;               // section at the base: 0 = circle, 4 = rounded square, n >= 3 = n-gon
  int sides_end = 0;                 // section at the top (same code)
  double squareness = 6.0;           // exponent of the rounded square |x|^p + |y|^p = a^p (sides 4), >= 2
  double wall_mm = 4.0;              // wall thickness of the solid mesh, mm (centred on the mid-wall outline)
  double bend_radius_mm = 150.0;     // radius of the central axis' arc, mm
  double bend_angle_rad = 1.5707963267948966;  // rad, in (0, pi]
  double straight_start_mm = 20.0;   // straight foot before the bend, mm (>= 0)
  double straight_end_mm = 0.0;      // straight end after the bend, mm (>= 0)
  int section_points = 128;          // points around the section
  // Longest spacing of the sweep's sections along the axis, mm. The skeleton slicer follows the facets faithfully:
  // every kink between sections turns the next plane at once, so steps well below a layer keep the layers smooth.
  double axis_step_mm = 1.0;
};

// A generated tube: the closed wall mesh (part frame, base on z = 0, axis starting at the origin) and its axis.
struct TubePart {
  TriangleMesh mesh;
  std::vector<Eigen::Vector3d> axis_P;  // central axis polyline from the base to the top, mm
  double extent_in_bend_plane_mm = 0.0;  // largest section extent towards the bend centre (d of eq. 6.4), mm
};

// Sweeps the spec's section along its axis. Throws InputError (prefixed by `where`) for a wall thicker than the
// section can hold or a bend that folds the inner wall onto itself (bend radius <= half the section extent).
TubePart BuildBentTube(const BentTubeSpec& spec, const std::string& where);

// The spec from the `bent_tube` generator parameters (already validated and completed by ResolveGeneratorParams).
BentTubeSpec BentTubeSpecFromParams(const GeneratorParams& params);

// Mid-wall distance from the axis [mm] of the section `sides`/`size_mm` at polar angle `phi` (rad) in the section
// plane, phi = 0 pointing towards the bend centre; flats of an n-gon face phi = 0.
double SectionRadius(int sides, double size_mm, double squareness, double phi);

}  // namespace waam::planner
