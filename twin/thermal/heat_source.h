// The arc's heat source of the thermal model: Goldak's double ellipsoid (the pool's shape) integrated exactly over
// grid cells, or the uniform bead rule (docs/THERMAL.md, "Heat source and activation").
#pragma once

#include <array>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "models/core/enum_names.h"

namespace waam::twin {

// How a micro step's heat is spread over the cells (ThermalSettings::heat_source).
enum class HeatSourceShape {
  kDoubleEllipsoid,  // Goldak's double ellipsoid around the arc, each cell taking its exact integral (default)
  kUniformBead,      // evenly over the cells of the bead laid in the step and the cells one below it
};
constexpr std::array<EnumName<HeatSourceShape>, 2> EnumNames(HeatSourceShape) {
  return {{{HeatSourceShape::kDoubleEllipsoid, "double_ellipsoid"}, {HeatSourceShape::kUniformBead, "uniform_bead"}}};
}
WAAM_ENUM_JSON(HeatSourceShape)

// The semi-axes of Goldak's double ellipsoid (Goldak, Chakravarti & Bibby 1984, Metall. Trans. B 15B 299), mm:
// across the travel (a), down from the surface (b), ahead of the arc (c_f) and behind it (c_r). The front and rear
// shares are f_f = 2 c_f / (c_f + c_r) and f_r = 2 c_r / (c_f + c_r) (f_f + f_r = 2, and the density is continuous
// where the lobes meet).
struct DoubleEllipsoid {
  double half_width_mm = 3.0;  // a
  double depth_mm = 4.0;       // b
  double front_mm = 3.0;       // c_f
  double rear_mm = 12.0;       // c_r
};

// Throws InputError when a semi-axis is not finite and > 0 (naming it).
void CheckDoubleEllipsoid(const DoubleEllipsoid& source);

// The share (0..1) of the source's power inside the box [lo, hi] of the source's own frame (mm): x along the travel
// from the arc point, y across it, z up (the surface at z = 0, the heat below it). Exact: a product of erf
// differences. The share of all space is 1.
double DoubleEllipsoidShare(const DoubleEllipsoid& source, const Eigen::Vector3d& lo_mm, const Eigen::Vector3d& hi_mm);

// The share of the source's power in the axis-aligned `cell` (part frame, mm) with the arc at `arc_mm` travelling
// along `travel` (its x and y; need not be unit; zero: a standing arc, whose pool is taken as the moving pool's
// front, c_r = c_f). Exact (erf products) when the travel is along x or y or zero; otherwise the cell's footprint is
// integrated on 4 x 4 columns, each exact in z.
double DoubleEllipsoidCellShare(const DoubleEllipsoid& source, const Eigen::Vector3d& arc_mm,
                                const Eigen::Vector2d& travel, const Eigen::AlignedBox3d& cell_mm);

// The box (part frame, mm) outside which the source holds less than about 2.5e-4 of its power along each axis: 1.5
// semi-axes around the arc point (the cells' shares are renormalised over this box, so the power stays exact).
Eigen::AlignedBox3d DoubleEllipsoidSupport(const DoubleEllipsoid& source, const Eigen::Vector3d& arc_mm,
                                           const Eigen::Vector2d& travel);

}  // namespace waam::twin
