// Path patterns that fill one planar slice: contour, zigzag, hybrid, Ding's continuous path, Eulerian rib-web path.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "planner/geometry/polygon.h"
#include "planner/path/pattern_names.h"

namespace waam::planner {

// One move of a 2D layer path. `weld` describes the move that ENDS at `p` (true: arc on, a bead is laid from the
// previous point; false: arc-off travel). The first move of a layer has weld = false (it is where the torch starts).
struct Move2D {
  Eigen::Vector2d p = Eigen::Vector2d::Zero();  // mm, slice plane
  bool weld = false;
};

// Bead spacings (centre to centre, mm) from the dissertation's overlap model (003 ch. 3, eq. 3.15, 3.17, Table 9).
struct OverlapSpacing {
  double boundary_offset_mm = 0.0;      // outline to the centre line of the outer contour bead (w / 2)
  double zigzag_mm = 0.0;               // l: between neighbouring zigzag beads (0.738 w)
  double contour_to_zigzag_mm = 0.0;    // d1: contour bead to the zigzag ends (0.47 w proposed, 0.738 w existing)
  double contour_to_contour_mm = 0.0;   // d2: between parallel boundary beads (0.5 w proposed, 0.738 w existing)
};

// Spacing for `model` ("proposed" or "existing") and bead width `bead_width_mm` (> 0). Throws InputError otherwise.
OverlapSpacing OverlapSpacingFor(OverlapModel model, double bead_width_mm);

struct PatternOptions {
  Pattern pattern = Pattern::kContinuous;  // not kSpiral (skeleton slicing plans its spirals itself)
  double bead_width_mm = 6.0;
  OverlapModel overlap_model = OverlapModel::kProposed;
  bool zigzag_auto = true;             // minimum-width direction per region/piece (Ding Lemma 1)
  double zigzag_angle_rad = 0.0;       // raster direction when not auto, radians from +x
  int layer_index = 0;                 // used to alternate start points layer to layer
  bool alternate_start = true;
  std::uint64_t seed = 1;              // for any random choice
  double contour_tolerance_mm = 0.0;   // slice rings simplified to this before filling (SimplifyRegions); 0: as sliced
};

// Plans the path of one slice (all its regions). Returns the moves in order. Throws InputError for options that
// cannot be planned (unknown pattern, bead wider than anything it could fill is NOT an error: such a region gets
// the best path it can or none, and the region is reported by the caller through uncovered area).
// A region the pattern could not plan as asked and planned otherwise adds a line to `notes` (may be null).
std::vector<Move2D> PlanLayerPattern(const std::vector<PolygonWithHoles>& slice, const PatternOptions& options,
                                     std::vector<std::string>* notes = nullptr);

// True when `moves` hold a weld move, or when `slice` has no room for a bead `bead_width_mm` wide (nothing of it
// lies w/2 inside its outline, as at a blade's tip). A slice with room and no weld move would drop a layer from
// the part, the cell check and the twin without a word: the planners refuse it.
bool HasWeldOrNoRoom(const std::vector<PolygonWithHoles>& slice, const std::vector<Move2D>& moves,
                     double bead_width_mm);

}  // namespace waam::planner
