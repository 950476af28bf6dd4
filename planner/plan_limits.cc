// Plan size limits: refuse a plan that would not fit in memory with one clear line instead of running out.
#include "planner/plan_limits.h"

#include "models/core/error.h"

namespace waam::planner {

void CheckLayerCount(double part_height_mm, double layer_height_mm, const std::string& where) {
  const double layers = part_height_mm / layer_height_mm;
  WAAM_THROW_UNLESS(layers <= static_cast<double>(kMaxLayers),
                    where << ": the part is " << part_height_mm << " mm tall: " << static_cast<long long>(layers)
                          << " layers at slicing.layer_height_mm = " << layer_height_mm << " mm, more than the limit of "
                          << kMaxLayers << " (wrong units? the mesh is read in mm)");
}

void CheckWeldLengthEstimate(const std::vector<std::vector<PolygonWithHoles>>& slices, double bead_spacing_mm,
                             const std::string& where) {
  double area_mm2 = 0.0;
  for (const std::vector<PolygonWithHoles>& layer : slices) area_mm2 += Area(layer);
  const double length_mm = area_mm2 / bead_spacing_mm;
  WAAM_THROW_UNLESS(length_mm <= kMaxWeldLengthMm,
                    where << ": the plan needs about " << length_mm / 1e6 << " km of weld path (sliced area "
                          << area_mm2 << " mm^2 at a bead spacing of " << bead_spacing_mm << " mm), more than the "
                          << "limit of " << kMaxWeldLengthMm / 1e6 << " km (wrong units, or a wider bead?)");
}

void CheckPathPoints(std::size_t points_so_far, int layer_index, const std::string& where) {
  WAAM_THROW_UNLESS(points_so_far <= kMaxPathPoints,
                    where << ": the path has more than " << kMaxPathPoints << " points by layer " << layer_index + 1
                          << "; plan fewer layers (larger slicing.layer_height_mm) or a wider bead");
}

}  // namespace waam::planner
