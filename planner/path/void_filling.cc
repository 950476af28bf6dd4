// Adaptive void filling (dissertation 003 sec. 4.4.1-4.4.2, Fig. 28, eq. 4.1-4.7): at a junction the turning point P
// of the path is moved deeper into the junction, so the torch lays metal where plain contours leave a void.
#include "planner/path/void_filling.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "models/core/error.h"
#include "models/core/numbers.h"

namespace waam::planner {
namespace {

using Vec = Eigen::Vector2d;
// Below this angle 1/sin(theta/2) explodes (eq. 4.3: 15 degrees already shifts P by 6.7 l) and the corner's legs
// rarely hold E and F; the dissertation's junctions go down to 18 degrees (Appendix A1, F8).
constexpr double kMinCorrectableDeg = 15.0;

std::string Point(const Vec& p) {
  std::ostringstream out;
  out.precision(1);
  out << std::fixed << "(" << p.x() << ", " << p.y() << ") mm";
  return out.str();
}

}  // namespace

CornerCorrection CorrectCorner(const Vec& a, const Vec& p, const Vec& b, const Vec& into_junction, double lambda,
                               double l_mm, const std::string& where) {
  WAAM_THROW_UNLESS(std::isfinite(l_mm) && l_mm > 0.0, where << ": bead spacing l = " << l_mm << " mm: must be > 0");
  WAAM_THROW_UNLESS(std::isfinite(lambda) && lambda >= 0.0, where << ": lambda = " << lambda << ": must be >= 0");
  const Vec pa = a - p, pb = b - p;
  WAAM_THROW_UNLESS(pa.norm() > 1e-9 && pb.norm() > 1e-9,
                    where << ": turning point at " << Point(p) << " coincides with its neighbour");
  const double theta = std::acos(std::clamp(pa.normalized().dot(pb.normalized()), -1.0, 1.0));
  const double theta_deg = theta * 180.0 / kPi;
  WAAM_THROW_UNLESS(theta_deg >= kMinCorrectableDeg, where << ": turning point at " << Point(p) << " has theta = "
                                                           << theta_deg << " deg: too small to correct (must be >= "
                                                           << kMinCorrectableDeg << " deg)");
  const double s = std::sin(0.5 * theta);
  CornerCorrection c;
  c.p = p;
  c.theta_deg = theta_deg;
  c.lambda = lambda;
  // eq. 4.1-4.3: P_o (the corner of the neighbouring bead's curve, l away) lies l / sin(theta/2) from P; P_N keeps l
  // from P_o, so |P P_N| = l (1/sin(theta/2) - 1). eq. 4.5 weights it by lambda.
  c.shift_mm = lambda * l_mm * (1.0 / s - 1.0);
  c.p_n = p + c.shift_mm * into_junction.normalized();
  // eq. 4.4: the path leaves PA at E and rejoins PB at F, |PE| = |PF| = l / (2 sin(theta/2)).
  const double pe = l_mm / (2.0 * s);
  WAAM_THROW_UNLESS(pe < pa.norm() && pe < pb.norm(),
                    where << ": turning point at " << Point(p) << " with theta = " << theta_deg
                          << " deg is too sharp to correct: E and F lie " << pe
                          << " mm from P (eq. 4.4) but its legs are "
                          << std::min(pa.norm(), pb.norm()) << " mm long");
  c.e = p + pe * pa.normalized();
  c.f = p + pe * pb.normalized();
  return c;
}

double LambdaForVoidLength(double void_length_mm, double theta_min_rad, double l_mm) {
  // eq. 4.6 is printed as lambda = l (1/sin(theta_min/2) - 1) / L, which with eq. 4.5 gives a shift l^2 (...)^2 / L
  // that shrinks as the void grows. The text around it says the opposite: a void is filled when PP_N* >= L, and the
  // four-arm junction's best shift (27 mm) is within 1.3 mm of its L (28.3 mm). We use the reciprocal, which makes
  // the shift at the sharpest turn equal to L.
  return void_length_mm / (l_mm * (1.0 / std::sin(0.5 * theta_min_rad) - 1.0));
}

VoidFiller::VoidFiller(const VoidFillingSettings& settings, double bead_width_mm, double l_mm)
    : settings_(settings),
      bead_width_mm_(bead_width_mm),
      l_mm_(settings.spacing_mm > 0.0 ? settings.spacing_mm : l_mm) {
  const std::string& where = settings_.where;
  WAAM_THROW_UNLESS(std::isfinite(l_mm_) && l_mm_ > 0.0, where << ": bead spacing l = " << l_mm_ << " mm: must be > 0");
  // The model and the tune file's shifts come loaded with the scenario (analysis::LoadScenario).
  if (settings_.mode == VoidFillingMode::kModel) {
    model_ = settings_.void_length;
    WAAM_DEMAND(model_ != nullptr);
  }
}

double VoidFiller::ShiftFor(const Junction& junction, double* lambda) const {
  const double theta_min = junction.turning_points[junction.SharpestTurn()].theta_rad;
  const double unit_shift = l_mm_ * (1.0 / std::sin(0.5 * theta_min) - 1.0);  // eq. 4.3
  double lam = settings_.lambda;
  if (settings_.mode == VoidFillingMode::kModel) {
    WAAM_THROW_UNLESS(junction.ribs >= 3 && junction.ribs <= 4,
                      settings_.where << ": junction " << junction.ClassName() << " at " << Point(junction.centre)
                                      << ": the void-length model covers 3 or 4 ribs (Appendix A1)");
    models::Junction j;
    j.turning_points = static_cast<int>(junction.turning_points.size());
    for (std::size_t k = 0; k < junction.angles_deg.size(); ++k) j.angles_deg[k] = junction.angles_deg[k];
    lam = LambdaForVoidLength(std::max(0.0, model_->PredictMm(j)), theta_min, l_mm_);
  } else if (settings_.mode == VoidFillingMode::kTuned) {
    const auto it = settings_.shift_by_class_mm.find(junction.ClassName());
    WAAM_THROW_UNLESS(it != settings_.shift_by_class_mm.end(),
                      settings_.where << ".tune_file: no tuned shift for junction class '" << junction.ClassName()
                                      << "' at " << Point(junction.centre) << " (run waam tune-voids on this part)");
    lam = it->second / unit_shift;
  }
  if (lambda) *lambda = lam;
  return lam * unit_shift;
}

std::vector<Move2D> VoidFiller::Apply(const std::vector<PolygonWithHoles>& slice, const std::vector<Move2D>& moves,
                                      int layer_index, std::vector<CornerCorrection>* out) const {
  if (!enabled()) return moves;
  std::vector<Junction> junctions = FindJunctions(slice, moves, bead_width_mm_, settings_.min_ribs);
  std::vector<CornerCorrection> corrections;
  std::vector<std::size_t> at_move;
  for (const Junction& junction : junctions) {
    // "One of the four turning points on the examined junction was chosen" (sec. 4.6.2): the sharpest; of equally
    // sharp ones, the next each layer.
    const double theta_min = junction.turning_points[junction.SharpestTurn()].theta_rad;
    std::vector<std::size_t> sharpest;
    for (std::size_t k = 0; k < junction.turning_points.size(); ++k) {
      if (junction.turning_points[k].theta_rad < theta_min + 1e-3) sharpest.push_back(k);
    }
    const TurningPoint& t = junction.turning_points[sharpest[layer_index % sharpest.size()]];
    double lambda = 0.0;
    ShiftFor(junction, &lambda);
    std::ostringstream where;
    where << settings_.where << ": layer " << layer_index << ", junction " << junction.ClassName();
    CornerCorrection c = CorrectCorner(moves[t.move - 1].p, t.p, moves[t.move + 1].p, t.into_junction, lambda,
                                       l_mm_, where.str());
    c.layer = layer_index;
    c.junction_class = junction.ClassName();
    corrections.push_back(c);
    at_move.push_back(t.move);
  }
  // Replace each P by E, P_N, F (path A-E-P_N-F-B of sec. 4.4.1), from the back so indices stay valid.
  std::vector<std::size_t> order(corrections.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return at_move[x] > at_move[y]; });
  std::vector<Move2D> result = moves;
  for (std::size_t k : order) {
    const CornerCorrection& c = corrections[k];
    const auto it = result.begin() + static_cast<std::ptrdiff_t>(at_move[k]);
    *it = Move2D{c.f, true};
    result.insert(it, {Move2D{c.e, true}, Move2D{c.p_n, true}});
  }
  if (out) out->insert(out->end(), corrections.begin(), corrections.end());
  return result;
}

}  // namespace waam::planner
