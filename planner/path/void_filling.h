// Adaptive void filling at rib-web junctions: the turning point moved into the junction (003 sec. 4.4.1).
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "models/voids/void_length_model.h"
#include "planner/geometry/polygon.h"
#include "planner/path/junctions.h"
#include "planner/path/layer_pattern.h"
#include "planner/scenario/void_filling_settings.h"

namespace waam::planner {

// One corrected corner: P replaced by E - P_N - F.
struct CornerCorrection {
  int layer = 0;
  std::string junction_class;
  Eigen::Vector2d p = Eigen::Vector2d::Zero();    // original turning point, mm
  Eigen::Vector2d p_n = Eigen::Vector2d::Zero();  // shifted turning point, mm
  Eigen::Vector2d e = Eigen::Vector2d::Zero(), f = Eigen::Vector2d::Zero();  // where the path leaves / rejoins, mm
  double theta_deg = 0.0;
  double lambda = 0.0;
  double shift_mm = 0.0;                          // |P P_N*|
};

// Geometry of one corrected corner (eq. 4.3-4.5): P moved by lambda l (1/sin(theta/2) - 1) along `into_junction`
// (unit), E and F on PA and PB at l / (2 sin(theta/2)) from P. `a`, `p`, `b` in mm, `l_mm` > 0. Throws InputError
// (prefixed by `where`) when theta is below 15 degrees or E or F would fall beyond A or B (the corner is too sharp
// or its legs too short to correct).
CornerCorrection CorrectCorner(const Eigen::Vector2d& a, const Eigen::Vector2d& p, const Eigen::Vector2d& b,
                               const Eigen::Vector2d& into_junction, double lambda, double l_mm,
                               const std::string& where);

// Lambda of eq. 4.6 for a junction whose void length with plain contours is `void_length_mm`: the lambda that makes
// the shift at the sharpest turn theta_min equal to L (see the .cc on the inverted printed form).
double LambdaForVoidLength(double void_length_mm, double theta_min_rad, double l_mm);

// The void-filling step of the planner: built once per plan (loads the model or tune file), applied per layer.
class VoidFiller {
 public:
  // `bead_width_mm` (> 0) sizes the junction search; `l_mm` (> 0) is the bead spacing l unless settings.spacing_mm
  // is set. Throws InputError (naming settings.where) for an unreadable model or tune file.
  VoidFiller(const VoidFillingSettings& settings, double bead_width_mm, double l_mm);

  bool enabled() const { return settings_.mode != VoidFillingMode::kNone; }
  double l_mm() const { return l_mm_; }

  // Per junction of the layer (FindJunctions) the sharpest turning point is corrected (of equally sharp ones, the
  // next one each layer, so the extra metal does not stack up). Returns the new moves and appends the corrections
  // to `out` (may be null). Throws InputError for a corner that cannot be corrected or, in mode tuned, a junction
  // class the tune file has no shift for.
  std::vector<Move2D> Apply(const std::vector<PolygonWithHoles>& slice, const std::vector<Move2D>& moves,
                            int layer_index, std::vector<CornerCorrection>* out) const;

  // The shift PP_N* (mm) this filler gives the sharpest turn of `junction`, and its lambda.
  double ShiftFor(const Junction& junction, double* lambda) const;

 private:
  VoidFillingSettings settings_;
  double bead_width_mm_ = 0.0;
  double l_mm_ = 0.0;
  std::shared_ptr<const models::VoidLengthModel> model_;
};

}  // namespace waam::planner
