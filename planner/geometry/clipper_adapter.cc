// Conversions between the planner's polygons and ClipperLib 6.4 paths, offsets and booleans.
#include "planner/geometry/clipper_adapter.h"

#include <algorithm>
#include <cmath>

namespace waam::planner::internal {
namespace {

using ClipperLib::Path;
using ClipperLib::Paths;

void AddRegionNode(const ClipperLib::PolyNode& node, std::vector<PolygonWithHoles>* out) {
  PolygonWithHoles region;
  region.outer = FromPath(node.Contour);
  if (SignedArea(region.outer) < 0.0) std::reverse(region.outer.begin(), region.outer.end());
  for (const ClipperLib::PolyNode* hole : node.Childs) {
    Ring ring = FromPath(hole->Contour);
    if (SignedArea(ring) > 0.0) std::reverse(ring.begin(), ring.end());
    if (ring.size() >= 3) region.holes.push_back(std::move(ring));
    for (const ClipperLib::PolyNode* island : hole->Childs) AddRegionNode(*island, out);
  }
  if (region.outer.size() >= 3) out->push_back(std::move(region));
}

std::vector<PolygonWithHoles> Boolean(ClipperLib::ClipType type, const std::vector<PolygonWithHoles>& a,
                                      const std::vector<PolygonWithHoles>* b) {
  ClipperLib::Clipper clipper;
  clipper.AddPaths(ToPaths(a), ClipperLib::ptSubject, true);
  if (b != nullptr) clipper.AddPaths(ToPaths(*b), ClipperLib::ptClip, true);
  ClipperLib::PolyTree tree;
  clipper.Execute(type, tree, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  return FromPolyTree(tree);
}

}  // namespace

ClipperLib::IntPoint ToClipper(const Eigen::Vector2d& p_mm) {
  return ClipperLib::IntPoint(static_cast<ClipperLib::cInt>(std::llround(p_mm.x() * kClipperUnitsPerMm)),
                              static_cast<ClipperLib::cInt>(std::llround(p_mm.y() * kClipperUnitsPerMm)));
}

Eigen::Vector2d FromClipper(const ClipperLib::IntPoint& p) {
  return Eigen::Vector2d(static_cast<double>(p.X) / kClipperUnitsPerMm, static_cast<double>(p.Y) / kClipperUnitsPerMm);
}

ClipperLib::Path ToPath(const Ring& ring, bool positive) {
  Path path;
  path.reserve(ring.size());
  for (const Eigen::Vector2d& p : ring) path.push_back(ToClipper(p));
  if ((ClipperLib::Area(path) > 0.0) != positive) ClipperLib::ReversePath(path);
  return path;
}

Ring FromPath(const ClipperLib::Path& path) {
  Ring ring;
  ring.reserve(path.size());
  for (const ClipperLib::IntPoint& p : path) ring.push_back(FromClipper(p));
  return ring;
}

ClipperLib::Paths ToPaths(const PolygonWithHoles& region) {
  Paths paths;
  paths.push_back(ToPath(region.outer, true));
  for (const Ring& hole : region.holes) paths.push_back(ToPath(hole, false));
  return paths;
}

ClipperLib::Paths ToPaths(const std::vector<PolygonWithHoles>& regions) {
  Paths paths;
  for (const PolygonWithHoles& region : regions) {
    Paths one = ToPaths(region);
    paths.insert(paths.end(), one.begin(), one.end());
  }
  return paths;
}

std::vector<PolygonWithHoles> FromPolyTree(const ClipperLib::PolyTree& tree) {
  std::vector<PolygonWithHoles> regions;
  for (const ClipperLib::PolyNode* node : tree.Childs) AddRegionNode(*node, &regions);
  return regions;
}

std::vector<PolygonWithHoles> Offset(const std::vector<PolygonWithHoles>& regions, double delta_mm) {
  ClipperLib::ClipperOffset offset(2.0, kArcToleranceMm * kClipperUnitsPerMm);
  offset.AddPaths(ToPaths(regions), ClipperLib::jtRound, ClipperLib::etClosedPolygon);
  ClipperLib::PolyTree tree;
  offset.Execute(tree, delta_mm * kClipperUnitsPerMm);
  return FromPolyTree(tree);
}

std::vector<PolygonWithHoles> Union(const std::vector<PolygonWithHoles>& regions) {
  return Boolean(ClipperLib::ctUnion, regions, nullptr);
}

std::vector<PolygonWithHoles> Intersection(const std::vector<PolygonWithHoles>& a,
                                           const std::vector<PolygonWithHoles>& b) {
  return Boolean(ClipperLib::ctIntersection, a, &b);
}

std::vector<PolygonWithHoles> Difference(const std::vector<PolygonWithHoles>& a,
                                         const std::vector<PolygonWithHoles>& b) {
  return Boolean(ClipperLib::ctDifference, a, &b);
}

std::vector<Polyline> ClipPolylines(const std::vector<Polyline>& lines, const std::vector<PolygonWithHoles>& regions) {
  ClipperLib::Clipper clipper;
  for (const Polyline& line : lines) {
    if (line.size() < 2) continue;
    Path path;
    for (const Eigen::Vector2d& p : line) path.push_back(ToClipper(p));
    clipper.AddPath(path, ClipperLib::ptSubject, false);
  }
  clipper.AddPaths(ToPaths(regions), ClipperLib::ptClip, true);
  ClipperLib::PolyTree tree;
  clipper.Execute(ClipperLib::ctIntersection, tree, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  Paths open;
  ClipperLib::OpenPathsFromPolyTree(tree, open);
  std::vector<Polyline> out;
  for (const Path& path : open) {
    Polyline line;
    for (const ClipperLib::IntPoint& p : path) line.push_back(FromClipper(p));
    if (line.size() >= 2) out.push_back(std::move(line));
  }
  return out;
}

std::vector<PolygonWithHoles> BufferPolylines(const std::vector<Polyline>& lines, double radius_mm,
                                              double arc_tolerance_mm) {
  ClipperLib::ClipperOffset offset(2.0, arc_tolerance_mm * kClipperUnitsPerMm);
  for (const Polyline& line : lines) {
    if (line.size() < 2) continue;
    Path path;
    for (const Eigen::Vector2d& p : line) path.push_back(ToClipper(p));
    offset.AddPath(path, ClipperLib::jtRound, ClipperLib::etOpenRound);
  }
  ClipperLib::PolyTree tree;
  offset.Execute(tree, radius_mm * kClipperUnitsPerMm);
  return FromPolyTree(tree);
}

double Length(const Polyline& line) {
  double length = 0.0;
  for (std::size_t i = 1; i < line.size(); ++i) length += (line[i] - line[i - 1]).norm();
  return length;
}

}  // namespace waam::planner::internal

namespace waam::planner {

std::vector<PolygonWithHoles> OffsetRegions(const std::vector<PolygonWithHoles>& regions, double delta_mm) {
  return internal::Offset(regions, delta_mm);
}

}  // namespace waam::planner
