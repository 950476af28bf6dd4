// The largest plan waam-twin accepts (layers, weld length, path points), checked before memory runs out.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "planner/geometry/polygon.h"

namespace waam::planner {

// Most layers one part may be sliced into: a 2 m tall part at 0.02 mm, or 100 m at 1 mm; more means wrong units.
inline constexpr std::size_t kMaxLayers = 100'000;

// Longest total weld path accepted (mm): 100 km, about 200 times the largest scenario (scenarios/twin/
// large_block.yaml, 510 m) and 170 days of arc time at 400 mm/min.
inline constexpr double kMaxWeldLengthMm = 1.0e8;

// Most path points one plan may hold: 20 M points are about 1.6 GB in memory (80 bytes each) before the check
// and the twin copy them; the whole run then stays well inside 24 GB.
inline constexpr std::size_t kMaxPathPoints = 20'000'000;

// Throws InputError naming `where` (the part) if `part_height_mm` / `layer_height_mm` is more than kMaxLayers.
void CheckLayerCount(double part_height_mm, double layer_height_mm, const std::string& where);

// Estimates the weld length of all layers as the sliced area over the bead spacing (mm^2 / mm) and throws
// InputError naming `where` if it is above kMaxWeldLengthMm. `bead_spacing_mm` > 0.
void CheckWeldLengthEstimate(const std::vector<std::vector<PolygonWithHoles>>& slices, double bead_spacing_mm,
                             const std::string& where);

// Throws InputError naming `where` and the layer (0-based `layer_index`) once `points_so_far` exceeds
// kMaxPathPoints.
void CheckPathPoints(std::size_t points_so_far, int layer_index, const std::string& where);

}  // namespace waam::planner
