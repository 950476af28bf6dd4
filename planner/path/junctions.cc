// Junction detection on a layer path (003 sec. 4.4, Fig. 28 and Fig. 32): turning points at cell corners and the
// junction class (number of ribs, angles between ribs in descending order, Appendix A1).
#include "planner/path/junctions.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

#include "models/core/error.h"
#include "models/core/numbers.h"

namespace waam::planner {
namespace {

using Vec = Eigen::Vector2d;
// A vertex turns the path when APB is sharper than this (a straighter vertex is a facet of a curve, not a corner).
constexpr double kMaxTurnAngleRad = 170.0 * kPi / 180.0;
// Cell corners of one junction add up to 360 degrees; a shortfall above this is one more rib's sector.
constexpr double kOpenSectorRad = 5.0 * kPi / 180.0;

bool InSlice(const std::vector<PolygonWithHoles>& slice, const Vec& p) {
  for (const PolygonWithHoles& region : slice) {
    if (!PointInRing(p, region.outer)) continue;
    bool in_hole = false;
    for (const Ring& hole : region.holes) in_hole = in_hole || PointInRing(p, hole);
    if (!in_hole) return true;
  }
  return false;
}

}  // namespace

std::string Junction::ClassName() const {
  std::ostringstream out;
  out << ribs << " ribs ";
  for (std::size_t k = 0; k < angles_deg.size(); ++k) out << (k ? "/" : "") << std::lround(angles_deg[k]);
  return out.str();
}

std::size_t Junction::SharpestTurn() const {
  std::size_t best = 0;
  for (std::size_t k = 1; k < turning_points.size(); ++k) {
    if (turning_points[k].theta_rad < turning_points[best].theta_rad - 1e-9) best = k;
  }
  return best;
}

std::vector<Junction> FindJunctions(const std::vector<PolygonWithHoles>& slice, const std::vector<Move2D>& moves,
                                    double bead_width_mm, int min_ribs) {
  WAAM_THROW_UNLESS(std::isfinite(bead_width_mm) && bead_width_mm > 0.0,
                    "junctions: bead width = " << bead_width_mm << " mm: must be > 0");
  std::vector<TurningPoint> points;
  for (std::size_t k = 1; k + 1 < moves.size(); ++k) {
    if (!moves[k].weld || !moves[k + 1].weld) continue;
    const Vec p = moves[k].p;
    const Vec to_a = moves[k - 1].p - p, to_b = moves[k + 1].p - p;
    if (to_a.norm() < 1e-9 || to_b.norm() < 1e-9) continue;
    const Vec u_a = to_a.normalized(), u_b = to_b.normalized();
    const double theta = std::acos(std::clamp(u_a.dot(u_b), -1.0, 1.0));
    if (theta > kMaxTurnAngleRad || theta < 1e-6) continue;
    // The bisector inside APB points at the cell corner, which a bead centre w/2 off the walls leaves
    // (w/2) / sin(theta/2) away: just beyond it the slice must be empty (a cell), else P is a convex corner of the
    // part or a connector's turn, with metal inside the angle.
    const Vec bisector = (u_a + u_b).normalized();
    const double reach = 0.5 * bead_width_mm / std::sin(0.5 * theta) + 0.25 * bead_width_mm;
    if (InSlice(slice, p + reach * bisector)) continue;
    points.push_back(TurningPoint{k, p, theta, -bisector});
  }
  // Single-linkage groups of turning points closer than two bead widths. The dissertation classifies junctions by
  // hand from the CAD model (Fig. 32); here they are found on the path, which holds for walls up to about two bead
  // widths thick and cells larger than two bead widths (else neighbouring junctions merge).
  std::vector<int> group(points.size(), -1);
  int groups = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (group[i] >= 0) continue;
    group[i] = groups;
    std::vector<std::size_t> todo{i};
    while (!todo.empty()) {
      const std::size_t a = todo.back();
      todo.pop_back();
      for (std::size_t b = 0; b < points.size(); ++b) {
        if (group[b] < 0 && (points[a].p - points[b].p).norm() < 2.0 * bead_width_mm) {
          group[b] = groups;
          todo.push_back(b);
        }
      }
    }
    ++groups;
  }
  std::vector<Junction> junctions(groups);
  for (std::size_t i = 0; i < points.size(); ++i) junctions[group[i]].turning_points.push_back(points[i]);
  std::vector<Junction> out;
  for (Junction& j : junctions) {
    double sum = 0.0;
    for (const TurningPoint& t : j.turning_points) {
      j.centre += t.p;
      j.angles_deg.push_back(t.theta_rad * 180.0 / kPi);
      sum += t.theta_rad;
    }
    j.centre /= static_cast<double>(j.turning_points.size());
    if (2.0 * kPi - sum > kOpenSectorRad) j.angles_deg.push_back((2.0 * kPi - sum) * 180.0 / kPi);
    j.ribs = static_cast<int>(j.angles_deg.size());
    std::sort(j.angles_deg.begin(), j.angles_deg.end(), std::greater<>());
    if (j.ribs >= min_ribs) out.push_back(std::move(j));
  }
  return out;
}

}  // namespace waam::planner
