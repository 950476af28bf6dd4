// Procedural parts: a table of generator types with their parameters (defaults, counts, ranges) and the builders.
//
// The four `ding_*` shapes stand in for the four test geometries of Ding et al. 2014, Table 2 (section 4). The
// figures of that table are not in the text we have, only its description: cases 1-3 are non-convex layer
// geometries on which the convex-decomposition method shines, case 4 is a larger solid for which it produces more
// path elements than the hybrid method, and the worked example of section 3.1 (Fig. 3, 5, 8) is "a simple polygon
// with an inside island" with circular holes. Ours follow that description, not the exact drawings:
//   ding_a: a non-convex polygon with four notches (interior angle > pi), like Fig. 3(a) (about 120 x 100 mm);
//   ding_b: the same kind of outline with a circular island (hole) and a small second hole, like Fig. 3(b)/5/8;
//   ding_c: a thin-walled pocketed frame (two rectangular pockets and a round one, walls about 10 mm);
//   ding_d: a large solid cross-shaped plate with four notches (160 x 160 mm), the "solid structure" of case 4.
#include "planner/mesh/generators.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <sstream>

#include "models/core/error.h"
#include "models/core/numbers.h"
#include "planner/geometry/clipper_adapter.h"
#include "planner/mesh/blade_generators.h"
#include "planner/mesh/cup_generator.h"
#include "planner/mesh/extrude.h"
#include "planner/mesh/mesh_ops.h"
#include "planner/mesh/tube_generators.h"

namespace waam::planner {
namespace {

using Vec2 = Eigen::Vector2d;

struct ParamSpec {
  std::string name;
  std::vector<double> default_value;
  std::size_t count;  // required number of values; 0 = any number (including none)
  double min;
  double max;
  bool integer;
  std::string help;
};

// Parameter values after defaults and checks; builders read them by name.
class Args {
 public:
  Args(std::map<std::string, std::vector<double>> values, std::string where)
      : values_(std::move(values)), where_(std::move(where)) {}
  double operator()(const std::string& name, std::size_t i = 0) const { return values_.at(name).at(i); }
  int Int(const std::string& name, std::size_t i = 0) const { return static_cast<int>(std::lround((*this)(name, i))); }
  const std::vector<double>& List(const std::string& name) const { return values_.at(name); }
  const std::string& where() const { return where_; }
  const std::map<std::string, std::vector<double>>& values() const { return values_; }

 private:
  std::map<std::string, std::vector<double>> values_;
  std::string where_;
};

struct GeneratorSpec {
  std::string summary;
  std::vector<ParamSpec> params;
  std::function<TriangleMesh(const Args&)> build;
  bool keep_frame = false;  // true: the part stays in the frame it was built in (not centred, not set on z = 0)
  // The parameters as field-table rows and their defaults (made from `params` once the registry is built).
  std::vector<Field<GeneratorParams>> fields = {};
  GeneratorParams defaults = {};
};

// A parameter's row of the field table: its unit from its name (_mm, _deg).
Field<GeneratorParams> ParamRow(const ParamSpec& p) {
  const auto ends = [&](std::string_view tail) {
    return p.name.size() > tail.size() && p.name.compare(p.name.size() - tail.size(), tail.size(), tail) == 0;
  };
  const std::string_view unit = ends("_mm") ? "mm" : ends("_deg") ? "deg" : "";
  return EntryField<GeneratorParams>(p.name, unit, p.min, p.max, static_cast<int>(p.count), p.integer, p.help);
}

Ring Polygon(std::initializer_list<std::pair<double, double>> points, double scale) {
  Ring ring;
  for (const auto& [x, y] : points) ring.emplace_back(scale * x, scale * y);
  return ring;
}

TriangleMesh Extrude(PolygonWithHoles region, double height) { return ExtrudeRegions({std::move(region)}, 0.0, height); }

TriangleMesh BuildSphere(double r, int segments, int rings) {
  TriangleMesh mesh;
  mesh.vertices.emplace_back(0.0, 0.0, 0.0);  // south pole
  for (int k = 1; k < rings; ++k) {
    const double lat = -kPi / 2 + kPi * k / rings;
    for (int j = 0; j < segments; ++j) {
      const double lon = 2 * kPi * j / segments;
      mesh.vertices.emplace_back(r * std::cos(lat) * std::cos(lon), r * std::cos(lat) * std::sin(lon),
                                 r + r * std::sin(lat));
    }
  }
  const int north = static_cast<int>(mesh.vertices.size());
  mesh.vertices.emplace_back(0.0, 0.0, 2 * r);
  auto at = [&](int k, int j) { return 1 + (k - 1) * segments + (j % segments); };
  for (int j = 0; j < segments; ++j) {
    mesh.facets.push_back({0, at(1, j + 1), at(1, j)});
    for (int k = 1; k + 1 < rings; ++k) {
      mesh.facets.push_back({at(k, j), at(k, j + 1), at(k + 1, j + 1)});
      mesh.facets.push_back({at(k, j), at(k + 1, j + 1), at(k + 1, j)});
    }
    mesh.facets.push_back({at(rings - 1, j), at(rings - 1, j + 1), north});
  }
  return mesh;
}

TriangleMesh BuildTorus(double major, double minor, int nu, int nv) {
  TriangleMesh mesh;
  for (int i = 0; i < nu; ++i) {
    const double u = 2 * kPi * i / nu;
    for (int j = 0; j < nv; ++j) {
      const double v = 2 * kPi * j / nv;
      const double rho = major + minor * std::cos(v);
      mesh.vertices.emplace_back(rho * std::cos(u), rho * std::sin(u), minor + minor * std::sin(v));
    }
  }
  auto at = [&](int i, int j) { return (i % nu) * nv + (j % nv); };
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      mesh.facets.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      mesh.facets.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  }
  return mesh;
}

TriangleMesh BuildPlateWithHoles(const Args& a) {
  const double sx = a("size_mm", 0), sy = a("size_mm", 1), sz = a("size_mm", 2);
  const std::vector<double>& d = a.List("hole_diameters_mm");
  const std::vector<double>& c = a.List("hole_centers_mm");
  WAAM_THROW_UNLESS(c.size() == 2 * d.size(), a.where() << ": plate_with_holes.hole_centers_mm has " << c.size()
                                                        << " values: needs 2 (x, y) per hole, 2 x " << d.size() << " = "
                                                        << 2 * d.size());
  PolygonWithHoles region{RectangleRing(-sx / 2, -sy / 2, sx / 2, sy / 2), {}};
  constexpr double kMinWallMm = 1.0;  // thinnest ligament between holes or to the edge
  for (std::size_t i = 0; i < d.size(); ++i) {
    const Vec2 center(c[2 * i], c[2 * i + 1]);
    const double r = d[i] / 2;
    WAAM_THROW_UNLESS(std::abs(center.x()) + r + kMinWallMm <= sx / 2 && std::abs(center.y()) + r + kMinWallMm <= sy / 2,
                      a.where() << ": plate_with_holes hole " << i + 1 << " (diameter " << d[i] << " mm at "
                                << center.x() << ", " << center.y() << " mm from the plate centre) must lie inside the "
                                << sx << " x " << sy << " mm plate with at least " << kMinWallMm << " mm of wall");
    for (std::size_t k = 0; k < i; ++k) {
      const double gap = (center - Vec2(c[2 * k], c[2 * k + 1])).norm() - r - d[k] / 2;
      WAAM_THROW_UNLESS(gap >= kMinWallMm, a.where() << ": plate_with_holes holes " << k + 1 << " and " << i + 1
                                                     << " are " << gap << " mm apart: must be >= " << kMinWallMm
                                                     << " mm (holes may not overlap)");
    }
    region.holes.push_back(CircleRing(center, r, a.Int("segments")));
  }
  return Extrude(std::move(region), sz);
}

// Defaults follow the rib-web of Nguyen 2022, section 4.6.5: walls about 9.0 mm (two overlapping 5.3 mm beads),
// parts about 45 mm high, five contours per layer with the standard path (Table 13: outer wall + 4 cells, so 2 x 2
// cells). The rib pitch is only drawn (Fig. 47), not given in the text; 60 mm is our choice.
TriangleMesh BuildRibWeb(const Args& a) {
  const int nx = a.Int("cells", 0), ny = a.Int("cells", 1);
  const double px = a("pitch_mm", 0), py = a("pitch_mm", 1), wall = a("wall_mm");
  WAAM_THROW_UNLESS(wall < std::min(px, py), a.where() << ": rib_web.wall_mm = " << wall
                                                       << ": must be smaller than the rib pitch (" << std::min(px, py)
                                                       << " mm) to leave open cells");
  // Walls are centred on the pitch lines x = i px, y = j py; the outer wall is as thick as the ribs.
  PolygonWithHoles region{RectangleRing(-wall / 2, -wall / 2, nx * px + wall / 2, ny * py + wall / 2), {}};
  for (int i = 0; i < nx; ++i) {
    for (int j = 0; j < ny; ++j) {
      region.holes.push_back(RectangleRing(i * px + wall / 2, j * py + wall / 2, (i + 1) * px - wall / 2,
                                           (j + 1) * py - wall / 2));
    }
  }
  return Extrude(std::move(region), a("height_mm"));
}

// A rib junction (003 Fig. 30-32): straight ribs `wall_mm` thick running `arm_mm` out from the centre at the given
// directions, united with a hub of the ribs' half-thickness so the back of the junction has no notch.
TriangleMesh BuildJunction(const Args& a) {
  std::vector<double> angles = a.List("arm_angles_deg");
  const double half = a("wall_mm") / 2, arm = a("arm_mm");
  WAAM_THROW_UNLESS(angles.size() >= 2, a.where() << ": junction.arm_angles_deg: needs at least 2 arms");
  WAAM_THROW_UNLESS(arm > 2 * a("wall_mm"), a.where() << ": junction.arm_mm = " << arm
                                                      << ": must be more than twice wall_mm (" << a("wall_mm") << ")");
  std::sort(angles.begin(), angles.end());
  for (std::size_t k = 0; k < angles.size(); ++k) {
    const double next = k + 1 < angles.size() ? angles[k + 1] : angles[0] + 360.0;
    WAAM_THROW_UNLESS(next - angles[k] >= 15.0, a.where() << ": junction.arm_angles_deg: arms at " << angles[k]
                                                          << " and " << std::fmod(next, 360.0)
                                                          << " deg are less than 15 deg apart");
  }
  std::vector<PolygonWithHoles> parts;
  for (double deg : angles) {
    const Vec2 d(std::cos(deg * kPi / 180.0), std::sin(deg * kPi / 180.0));
    const Vec2 n(-d.y(), d.x());
    parts.push_back({{-half * n, arm * d - half * n, arm * d + half * n, half * n}, {}});
  }
  Ring hub;
  for (int k = 0; k < 64; ++k) hub.push_back(half * Vec2(std::cos(2 * kPi * k / 64), std::sin(2 * kPi * k / 64)));
  parts.push_back({hub, {}});
  std::vector<PolygonWithHoles> united = internal::Union(parts);
  WAAM_THROW_UNLESS(united.size() == 1, a.where() << ": junction: the arms do not form one part");
  return Extrude(std::move(united[0]), a("height_mm"));
}

const std::map<PartGenerator, GeneratorSpec>& Registry() {
  static const std::map<PartGenerator, GeneratorSpec> registry = [] {
    const double kBig = 5000.0;  // mm: larger than any WAAM cell
    std::map<PartGenerator, GeneratorSpec> r;
    const ParamSpec height{"height_mm", {30.0}, 1, 0.1, kBig, false, "extrusion height (mm)"};
    const ParamSpec scale{"scale", {1.0}, 1, 0.01, 100.0, false, "scale factor applied to the plan outline"};
    r[PartGenerator::kBox] = {"rectangular block",
                {{"size_mm", {100.0, 60.0, 40.0}, 3, 0.1, kBig, false, "x, y, z edge lengths (mm)"}},
                [](const Args& a) {
                  return Extrude({RectangleRing(0, 0, a("size_mm", 0), a("size_mm", 1)), {}}, a("size_mm", 2));
                }};
    r[PartGenerator::kCylinder] = {"upright cylinder (regular polygon prism)",
                     {{"radius_mm", {30.0}, 1, 0.1, kBig, false, "radius (mm)"},
                      {"height_mm", {60.0}, 1, 0.1, kBig, false, "height (mm)"},
                      {"segments", {64.0}, 1, 3, 4096, true, "polygon sides"}},
                     [](const Args& a) {
                       return Extrude({CircleRing(Vec2::Zero(), a("radius_mm"), a.Int("segments")), {}}, a("height_mm"));
                     }};
    r[PartGenerator::kSphere] = {"UV sphere resting on its south pole",
                   {{"radius_mm", {40.0}, 1, 0.1, kBig, false, "radius (mm)"},
                    {"segments", {64.0}, 1, 3, 8192, true, "meridians"},
                    {"rings", {32.0}, 1, 2, 8192, true, "latitude bands"}},
                   [](const Args& a) { return BuildSphere(a("radius_mm"), a.Int("segments"), a.Int("rings")); }};
    r[PartGenerator::kTorus] = {"torus with a vertical axis, lying flat",
                  {{"major_radius_mm", {50.0}, 1, 0.1, kBig, false, "axis to tube centre (mm)"},
                   {"minor_radius_mm", {15.0}, 1, 0.1, kBig, false, "tube radius (mm), < major_radius_mm"},
                   {"major_segments", {96.0}, 1, 3, 8192, true, "segments around the axis"},
                   {"minor_segments", {48.0}, 1, 3, 8192, true, "segments around the tube"}},
                  [](const Args& a) {
                    WAAM_THROW_UNLESS(a("minor_radius_mm") < a("major_radius_mm"),
                                      a.where() << ": torus.minor_radius_mm = " << a("minor_radius_mm")
                                                << ": must be smaller than major_radius_mm = " << a("major_radius_mm"));
                    return BuildTorus(a("major_radius_mm"), a("minor_radius_mm"), a.Int("major_segments"),
                                      a.Int("minor_segments"));
                  }};
    r[PartGenerator::kBentTube] = {"thin-walled tube swept along a straight-arc-straight axis (dissertation 6.2, parts I-IV)",
                      {{"diameter_mm", {100.0, 100.0}, 2, 1.0, kBig, false,
                        "mid-wall section size at base and top: diameter, or width across flats (mm)"},
                       {"sides", {0.0, 0.0}, 2, 0, 64, true, "section at base and top: 0 circle, 4 rounded square, n n-gon"},
                       {"squareness_exponent", {6.0}, 1, 2.0, 50.0, false, "rounded square |x|^p + |y|^p = a^p"},
                       {"wall_mm", {4.0}, 1, 0.1, 100.0, false, "wall thickness (mm)"},
                       {"bend_radius_mm", {150.0}, 1, 1.0, kBig, false, "radius of the central axis' arc (mm)"},
                       {"bend_angle_deg", {90.0}, 1, 1.0, 180.0, false, "bend angle (deg)"},
                       {"straight_mm", {20.0, 0.0}, 2, 0.0, kBig, false, "straight lengths before and after the bend (mm)"},
                       {"section_points", {128.0}, 1, 8, 4096, true, "points around the section"},
                       {"axis_step_mm", {1.0}, 1, 0.1, 100.0, false, "section spacing along the axis (mm)"}},
                      [](const Args& a) { return BuildBentTube(BentTubeSpecFromParams(a.values()), a.where()).mesh; }};
    r[PartGenerator::kPlateWithHoles] = {"plate with round through-holes",
                             {{"size_mm", {160.0, 100.0, 12.0}, 3, 0.1, kBig, false, "x, y, thickness (mm)"},
                              {"hole_diameters_mm", {30.0, 20.0, 20.0}, 0, 0.1, kBig, false, "one per hole (mm)"},
                              {"hole_centers_mm", {-35.0, 0.0, 35.0, 25.0, 35.0, -25.0}, 0, -kBig, kBig, false,
                               "x, y per hole from the plate centre (mm)"},
                              {"segments", {48.0}, 1, 3, 4096, true, "polygon sides per hole"}},
                             BuildPlateWithHoles};
    r[PartGenerator::kLShape] = {"L-section block",
                    {{"size_mm", {120.0, 80.0, 40.0}, 3, 0.1, kBig, false, "x, y, z overall (mm)"},
                     {"leg_mm", {25.0, 25.0}, 2, 0.1, kBig, false, "width of the vertical and horizontal legs (mm)"}},
                    [](const Args& a) {
                      const double x = a("size_mm", 0), y = a("size_mm", 1), lx = a("leg_mm", 0), ly = a("leg_mm", 1);
                      WAAM_THROW_UNLESS(lx < x && ly < y, a.where() << ": l_shape.leg_mm = [" << lx << ", " << ly
                                                                    << "]: must be smaller than size_mm [" << x << ", "
                                                                    << y << "]");
                      return Extrude({Polygon({{0, 0}, {x, 0}, {x, ly}, {lx, ly}, {lx, y}, {0, y}}, 1.0), {}},
                                     a("size_mm", 2));
                    }};
    r[PartGenerator::kTShape] = {"T-section block (flange on top of a centred web)",
                    {{"size_mm", {120.0, 100.0, 40.0}, 3, 0.1, kBig, false, "x, y, z overall (mm)"},
                     {"flange_mm", {25.0}, 1, 0.1, kBig, false, "flange depth along y (mm)"},
                     {"web_mm", {30.0}, 1, 0.1, kBig, false, "web width along x (mm)"}},
                    [](const Args& a) {
                      const double x = a("size_mm", 0), y = a("size_mm", 1), f = a("flange_mm"), w = a("web_mm");
                      WAAM_THROW_UNLESS(f < y && w < x, a.where() << ": t_shape flange_mm = " << f << " and web_mm = "
                                                                  << w << ": must be smaller than size_mm y = " << y
                                                                  << " and x = " << x);
                      const double l = (x - w) / 2, rr = (x + w) / 2;
                      return Extrude({Polygon({{l, 0}, {rr, 0}, {rr, y - f}, {x, y - f}, {x, y}, {0, y}, {0, y - f},
                                               {l, y - f}},
                                              1.0),
                                      {}},
                                     a("size_mm", 2));
                    }};
    r[PartGenerator::kRibWeb] = {"rib-web grid: outer wall and inner ribs around open cells",
                    {{"cells", {2.0, 2.0}, 2, 1, 100, true, "open cells along x and y"},
                     {"pitch_mm", {60.0, 60.0}, 2, 1.0, kBig, false, "rib spacing along x and y (mm)"},
                     {"wall_mm", {9.0}, 1, 0.1, kBig, false, "wall and rib thickness (mm)"},
                     {"height_mm", {45.0}, 1, 0.1, kBig, false, "height (mm)"}},
                    BuildRibWeb};
    r[PartGenerator::kJunction] = {"rib junction: straight ribs from a common centre (003 Fig. 30-32)",
                     {{"arm_angles_deg", {0.0, 90.0, 180.0, 270.0}, 0, -360.0, 360.0, false,
                       "directions of the ribs (deg from +x), at least 2, 15 deg apart"},
                      {"arm_mm", {40.0}, 1, 1.0, kBig, false, "rib length from the centre (mm)"},
                      {"wall_mm", {9.0}, 1, 0.1, kBig, false, "rib thickness (mm)"},
                      {"height_mm", {21.6}, 1, 0.1, kBig, false, "height (mm)"}},
                     BuildJunction};
    // Outlines of the Ding et al. 2014 stand-ins (see the top of this file), in mm before scaling.
    r[PartGenerator::kDingA] = {"Ding 2014 case-1-like non-convex polygon with four notches",
                   {height, scale},
                   [](const Args& a) {
                     return Extrude({Polygon({{0, 0}, {60, 15}, {120, 0}, {120, 30}, {80, 45}, {120, 60}, {120, 100},
                                              {60, 80}, {0, 100}, {20, 50}},
                                             a("scale")),
                                     {}},
                                    a("height_mm"));
                   }};
    r[PartGenerator::kDingB] = {"Ding 2014 Fig. 3(b)-like notched polygon with a round island and a small hole",
                   {height, scale, {"segments", {48.0}, 1, 8, 4096, true, "polygon sides per hole"}},
                   [](const Args& a) {
                     const double s = a("scale");
                     PolygonWithHoles region{Polygon({{0, 0}, {60, 15}, {120, 0}, {120, 30}, {80, 45}, {120, 60},
                                                      {120, 100}, {60, 80}, {0, 100}, {20, 50}},
                                                     s),
                                             {}};
                     region.holes.push_back(CircleRing(Vec2(55 * s, 50 * s), 15 * s, a.Int("segments")));
                     region.holes.push_back(CircleRing(Vec2(105 * s, 80 * s), 6 * s, a.Int("segments")));
                     return Extrude(std::move(region), a("height_mm"));
                   }};
    r[PartGenerator::kDingC] = {"Ding 2014 case-3-like thin-walled frame with three pockets",
                   {height, scale, {"segments", {48.0}, 1, 8, 4096, true, "polygon sides of the round pocket"}},
                   [](const Args& a) {
                     const double s = a("scale");
                     PolygonWithHoles region{Polygon({{0, 0}, {140, 0}, {140, 70}, {110, 100}, {0, 100}}, s), {}};
                     region.holes.push_back(Polygon({{10, 10}, {60, 10}, {60, 90}, {10, 90}}, s));
                     region.holes.push_back(Polygon({{70, 10}, {130, 10}, {130, 45}, {70, 45}}, s));
                     region.holes.push_back(CircleRing(Vec2(95 * s, 72 * s), 14 * s, a.Int("segments")));
                     return Extrude(std::move(region), a("height_mm"));
                   }};
    r[PartGenerator::kThrusterBlades] = {
        "blades on the cone x^2+y^2 = R^2 (z/H-1)^2 round the z axis (Dai 2020 thruster; kept in the cone's frame: "
        "axis x = y = 0, radius R at z = 0, for slicing.type cone)",
        {{"blades", {6.0}, 1, 1, 64, true, "blades round the axis"},
         {"R_mm", {60.0}, 1, 1.0, kBig, false, "cone radius at z = 0 (mm)"},
         {"H_mm", {200.0}, 1, 0.0, kBig, false, "height of the apex above z = 0 (mm); 0 = a cylinder of radius R"},
         {"root_z_mm", {60.0}, 1, -kBig, kBig, false, "height of the blade root centre on the cone (mm)"},
         {"span_mm", {70.0}, 1, 1.0, kBig, false, "blade length along the cone normal (mm)"},
         {"chord_mm", {60.0}, 1, 1.0, kBig, false, "blade chord (mm)"},
         {"thickness_mm", {24.0, 14.0}, 2, 0.5, kBig, false, "thickness at the root and at the tip (mm)"},
         {"pitch_deg", {25.0, 45.0}, 2, -89.0, 89.0, false, "pitch at the root and the tip (deg, 0 = along the axis)"}},
        [](const Args& a) {
          ConeBladeParams p;
          p.blades = a.Int("blades");
          p.R_mm = a("R_mm");
          p.H_mm = a("H_mm") > 0.0 ? a("H_mm") : std::numeric_limits<double>::infinity();
          WAAM_THROW_UNLESS(!std::isfinite(p.H_mm) || a("root_z_mm") + a("chord_mm") < p.H_mm,
                            a.where() << ": thruster_blades.root_z_mm + chord_mm must stay below the apex H_mm");
          p.root_z_mm = a("root_z_mm");
          p.span_mm = a("span_mm");
          p.chord_mm = a("chord_mm");
          p.root_thickness_mm = a("thickness_mm", 0);
          p.tip_thickness_mm = a("thickness_mm", 1);
          p.pitch_root_deg = a("pitch_deg", 0);
          p.pitch_tip_deg = a("pitch_deg", 1);
          return BuildConeBlades(p);
        },
        true};
    r[PartGenerator::kPropeller] = {
        "Lim & Soh-like propeller: square hub (blade roots on its flats) and blades round the z axis, kept in the "
        "hub's frame (axis x = y = 0, hub from z = 0), for slicing.type multi_directional",
        {{"blades", {4.0}, 1, 1, 4, true, "blades, one per hub flat (at 0, 90, 180, 270 deg)"},
         {"hub_mm", {126.0, 120.0}, 2, 1.0, kBig, false, "hub width across the flats and height (mm)"},
         {"span_mm", {287.0}, 1, 1.0, kBig, false, "blade length from the hub flat (mm)"},
         {"chord_mm", {120.0}, 1, 1.0, kBig, false, "blade chord (mm)"},
         {"thickness_mm", {50.0, 20.0}, 2, 0.5, kBig, false, "thickness at the root and at the tip (mm)"},
         {"pitch_deg", {30.0, 60.0}, 2, -89.0, 89.0, false, "pitch at the root and the tip (deg, 0 = along the axis)"}},
        [](const Args& a) {
          ConeBladeParams p;
          p.blades = a.Int("blades");
          p.R_mm = 0.5 * a("hub_mm", 0);
          p.span_mm = a("span_mm");
          p.chord_mm = a("chord_mm");
          p.root_thickness_mm = a("thickness_mm", 0);
          p.tip_thickness_mm = a("thickness_mm", 1);
          p.pitch_root_deg = a("pitch_deg", 0);
          p.pitch_tip_deg = a("pitch_deg", 1);
          return BuildPropeller(p, a("hub_mm", 1));
        },
        true};
    r[PartGenerator::kCupTwoHandles] = {
        "cup with two handles (dissertation 003 Fig. 52, the overhang decomposition example): a cylindrical shell "
        "with a bottom, axis x = y = 0 from z = 0, two half-torus handles on +x and -x, for slicing.type "
        "multi_directional with split: centroid_shift",
        {{"radius_mm", {37.5}, 1, 1.0, kBig, false, "outer radius of the cup (mm)"},
         {"height_mm", {90.0}, 1, 1.0, kBig, false, "height of the cup (mm)"},
         {"wall_mm", {4.0}, 1, 0.1, kBig, false, "wall thickness (mm)"},
         {"bottom_mm", {5.0}, 1, 0.1, kBig, false, "bottom thickness (mm)"},
         {"handle_mm", {22.0, 5.0}, 2, 0.1, kBig, false, "handle centre-line radius and tube radius (mm)"},
         {"handle_z_mm", {58.0}, 1, 0.0, kBig, false, "height of the handles' centre on the wall (mm)"}},
        [](const Args& a) {
          CupParams p;
          p.radius_mm = a("radius_mm");
          p.height_mm = a("height_mm");
          p.wall_mm = a("wall_mm");
          p.bottom_mm = a("bottom_mm");
          p.handle_radius_mm = a("handle_mm", 0);
          p.handle_tube_mm = a("handle_mm", 1);
          p.handle_z_mm = a("handle_z_mm");
          return BuildCupTwoHandles(p, a.where());
        },
        true};
    r[PartGenerator::kDingD] = {"Ding 2014 case-4-like large solid cross with four notches",
                   {height, scale},
                   [](const Args& a) {
                     return Extrude({Polygon({{50, 0}, {110, 0}, {110, 50}, {160, 50}, {160, 110}, {110, 110},
                                              {110, 160}, {50, 160}, {50, 110}, {0, 110}, {0, 50}, {50, 50}},
                                             a("scale")),
                                     {}},
                                    a("height_mm"));
                   }};
    for (auto& [type, spec] : r) {
      for (const ParamSpec& p : spec.params) {
        spec.fields.push_back(ParamRow(p));
        spec.defaults[p.name] = p.default_value;
      }
    }
    return r;
  }();
  return registry;
}

std::string Join(const std::vector<double>& values) {
  std::ostringstream out;
  out << "[";
  for (std::size_t i = 0; i < values.size(); ++i) out << (i ? ", " : "") << values[i];
  out << "]";
  return out.str();
}

}  // namespace

PartGenerator ParsePartGenerator(const std::string& name, const std::string& where) {
  const std::optional<PartGenerator> type = ParseEnum<PartGenerator>(name);
  WAAM_THROW_UNLESS(type, where << ": unknown generator type '" << name << "' (known: " << EnumNameList<PartGenerator>()
                                << ")");
  return *type;
}

GeneratorParams ResolveGeneratorParams(PartGenerator generator, const GeneratorParams& params,
                                       const std::string& where) {
  const auto it = Registry().find(generator);
  WAAM_DEMAND(it != Registry().end());  // a type the table names and the registry lacks
  const GeneratorSpec& spec = it->second;
  const std::string type(NameOf(generator));
  // A plain loop variable, not a structured binding: clang 14 cannot capture bindings in the lambdas below.
  for (const auto& param : params) {
    const std::string& name = param.first;
    const bool known = std::any_of(spec.params.begin(), spec.params.end(), [&](const ParamSpec& p) { return p.name == name; });
    if (!known) {
      std::ostringstream names;
      for (const ParamSpec& p : spec.params) names << (names.tellp() ? ", " : "") << p.name;
      WAAM_THROW(where << ": unknown parameter '" << name << "' for generator " << type << " (known: " << names.str()
                       << ")");
    }
  }
  GeneratorParams values = spec.defaults;
  for (const auto& param : params) values[param.first] = param.second;
  CheckFields<GeneratorParams>(spec.fields, values, where + ": " + type);
  return values;
}

std::span<const Field<GeneratorParams>> GeneratorFields(PartGenerator type) { return Registry().at(type).fields; }

const GeneratorParams& GeneratorDefaults(PartGenerator type) { return Registry().at(type).defaults; }

TriangleMesh GeneratePart(const std::string& type, const GeneratorParams& params, const std::string& where) {
  return GeneratePart(ParsePartGenerator(type, where), params, where);
}

TriangleMesh GeneratePart(PartGenerator type, const GeneratorParams& params, const std::string& where) {
  GeneratorParams values = ResolveGeneratorParams(type, params, where);
  const GeneratorSpec& spec = Registry().at(type);
  TriangleMesh mesh = spec.build(Args(std::move(values), where));
  if (spec.keep_frame) return mesh;
  // Centre the bounding box on x = y = 0 and rest the part on z = 0.
  Eigen::Vector3d lo, hi;
  BoundingBox(mesh, &lo, &hi);
  Translate(&mesh, Eigen::Vector3d(-(lo.x() + hi.x()) / 2, -(lo.y() + hi.y()) / 2, -lo.z()));
  return mesh;
}

std::vector<std::string> GeneratorTypes() {
  std::vector<std::string> types;
  for (const EnumName<PartGenerator>& entry : EnumNames(PartGenerator{})) types.emplace_back(entry.name);
  return types;
}

std::string GeneratorHelp() {
  std::ostringstream out;
  for (const auto& [type, spec] : Registry()) {
    out << "  " << NameOf(type) << ": " << spec.summary << "\n";
    for (const ParamSpec& p : spec.params) {
      out << "      " << p.name << " = " << Join(p.default_value) << "  " << p.help << "\n";
    }
  }
  return out.str();
}

}  // namespace waam::planner
