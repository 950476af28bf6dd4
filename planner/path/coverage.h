// How much of a layer's slice its planned beads leave uncovered.
#pragma once

#include "planner/path/tool_path.h"

namespace waam::planner {

// Area (mm^2) of `layer.slice` that no weld move covers with its bead at planned width (each move swept by a disc
// of half its bead width, in the slice plane). NaN for a layer whose slice lies in no plane of the part (cone and
// cylinder layers keep theirs in the development plane): their coverage is not measured here. A pattern that fits
// the region leaves a few per cent at cusps and sharp corners; much more means the pattern does not suit it (a
// zigzag without contour on a curved wall, for example).
double UncoveredArea(const LayerPath& layer);

}  // namespace waam::planner
