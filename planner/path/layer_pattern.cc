// Overlap spacings of the dissertation's bead model and the dispatch of a slice to its fill pattern.
#include "planner/path/layer_pattern.h"

#include <algorithm>
#include <cmath>

#include "models/core/error.h"
#include "planner/geometry/clipper_adapter.h"
#include "planner/geometry/simplify.h"
#include "planner/path/continuous_pattern.h"
#include "planner/path/contour_pattern.h"
#include "planner/path/eulerian_pattern.h"
#include "planner/path/hybrid_pattern.h"
#include "planner/path/pattern_common.h"
#include "planner/path/zigzag_pattern.h"

namespace waam::planner {

OverlapSpacing OverlapSpacingFor(OverlapModel model, double bead_width_mm) {
  WAAM_THROW_UNLESS(std::isfinite(bead_width_mm) && bead_width_mm > 0.0,
                    "overlap spacing: bead width = " << bead_width_mm << " mm: must be > 0");
  const double w = bead_width_mm;
  OverlapSpacing s;
  // The outer contour bead is laid with its centre half a bead inside the outline, so its flank meets the wall.
  s.boundary_offset_mm = 0.5 * w;
  // l = 0.738 w between zigzag beads (Ding et al.'s step-over, dissertation 003 Fig. 20 and Table 9).
  s.zigzag_mm = 0.738 * w;
  switch (model) {
    case OverlapModel::kProposed:
      // eq. 3.13-3.15: equal empty and overlapping volume between a contour and the zigzag ends gives d1 = 0.47 w.
      s.contour_to_zigzag_mm = 0.47 * w;
      // eq. 3.16-3.17: one-sided overlap of boundary beads is compensated with d2 = 0.5 w.
      s.contour_to_contour_mm = 0.5 * w;
      break;
    case OverlapModel::kExisting:
      // The existing model uses the zigzag step-over everywhere: d1 = d2 = l = 0.738 w (Table 9, right columns).
      s.contour_to_zigzag_mm = 0.738 * w;
      s.contour_to_contour_mm = 0.738 * w;
      break;
  }
  return s;
}

std::vector<Move2D> PlanLayerPattern(const std::vector<PolygonWithHoles>& slice, const PatternOptions& options,
                                     std::vector<std::string>* notes) {
  internal::ValidatePatternOptions(options);
  std::vector<std::string> unread_notes;  // a caller that passed no `notes` asked not to hear them
  if (notes == nullptr) notes = &unread_notes;
  const OverlapSpacing spacing = OverlapSpacingFor(options.overlap_model, options.bead_width_mm);
  // Clean the slice through Clipper first: consistent orientation, no self-touching rings, no duplicate points; with
  // a tolerance, the rings simplified to it first (a facetted slice has a vertex per facet, and every offset and
  // clip of the pattern pays for each).
  const std::vector<PolygonWithHoles> regions = options.contour_tolerance_mm > 0.0
                                                    ? SimplifyRegions(slice, options.contour_tolerance_mm)
                                                    : internal::Union(slice);
  std::vector<Move2D> moves;
  for (const PolygonWithHoles& region : regions) {
    switch (options.pattern) {
      case Pattern::kContour: internal::PlanContour(region, options, spacing, &moves); break;
      case Pattern::kZigzag: internal::PlanZigzag(region, options, spacing, &moves); break;
      case Pattern::kEulerian: internal::PlanEulerian(region, options, spacing, &moves); break;
      case Pattern::kHybrid: internal::PlanHybrid(region, options, spacing, &moves); break;
      case Pattern::kContinuous: internal::PlanContinuous(region, options, spacing, &moves, notes); break;
      case Pattern::kSpiral: WAAM_DEMAND(options.pattern != Pattern::kSpiral);  // skeleton slicing plans spirals
    }
  }
  // Round joins and faceted meshes leave runs of tiny, nearly collinear moves: one straight move each is what the
  // robot should get (Ding Table 2 counts such lines as path elements).
  return internal::SimplifyMoves(moves, internal::kStraightPathToleranceMm);
}

bool HasWeldOrNoRoom(const std::vector<PolygonWithHoles>& slice, const std::vector<Move2D>& moves,
                     double bead_width_mm) {
  return std::any_of(moves.begin(), moves.end(), [](const Move2D& m) { return m.weld; }) ||
         Area(internal::Offset(slice, -0.5 * bead_width_mm)) <= 0.0;
}

}  // namespace waam::planner
