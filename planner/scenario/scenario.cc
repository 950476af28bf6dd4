// Scenario loading: every section validated up front, with the key path in each message.
#include "planner/scenario/scenario.h"

#include <algorithm>
#include <cmath>

#include "models/core/error.h"
#include "planner/scenario/yaml_fields.h"

namespace waam::planner {
namespace fs = std::filesystem;
using internal::YamlMap;

namespace {

// part: either `mesh: file.stl` (relative to the scenario file) or `generator: {type: name, <param>: value...}`.
PartSpec ParsePart(YamlMap part, const YAML::Node& node, const fs::path& scenario_dir) {
  PartSpec spec;
  spec.where = part.Where("");
  const bool has_mesh = part.Has("mesh");
  const bool has_generator = part.Has("generator");
  WAAM_THROW_UNLESS(has_mesh != has_generator, spec.where << ": give exactly one of 'mesh' or 'generator'");
  if (has_mesh) {
    spec.mesh_path = fs::path(part.String("mesh"));
    if (spec.mesh_path.is_relative()) spec.mesh_path = scenario_dir / spec.mesh_path;
    spec.mesh_path = spec.mesh_path.lexically_normal();
    std::error_code ec;
    WAAM_THROW_UNLESS(fs::exists(spec.mesh_path, ec),
                      part.Where("mesh") << ": mesh file " << spec.mesh_path.string() << " not found");
    WAAM_THROW_UNLESS(!fs::is_directory(spec.mesh_path, ec),
                      part.Where("mesh") << ": " << spec.mesh_path.string() << " is a directory, expected an STL file");
  } else {
    YamlMap generator = part.Map("generator");
    spec.generator = generator.String("type");
    spec.where = generator.Where("");
    // Every other key is a numeric parameter (a number or a list); the generator checks names and ranges.
    const YAML::Node gen_node = node["generator"];
    for (auto it = gen_node.begin(); it != gen_node.end(); ++it) {
      const std::string key = it->first.Scalar();
      if (key == "type") continue;
      spec.params[key] = it->second.IsSequence() ? generator.Numbers(key, -1, -1e9, 1e9)
                                                 : std::vector<double>{generator.Number(key, -1e9, 1e9)};
    }
    generator.CheckNoUnknownKeys();
  }
  part.CheckNoUnknownKeys();
  return spec;
}

// Applies one "key.path=value" override to the document, creating intermediate maps as needed.
void ApplyOverride(YAML::Node root, const std::string& override_text) {
  const std::size_t eq = override_text.find('=');
  WAAM_THROW_UNLESS(eq != std::string::npos && eq > 0,
                    "--set '" << override_text << "': expected key.path=value, e.g. path.pattern=hybrid");
  const std::string key_path = override_text.substr(0, eq);
  YAML::Node value;
  try {
    value = YAML::Load(override_text.substr(eq + 1));
  } catch (const YAML::Exception& e) {
    WAAM_THROW("--set '" << override_text << "': value is not valid YAML: " << e.msg);
  }
  YAML::Node node;
  node.reset(root);
  std::size_t start = 0;
  while (true) {
    const std::size_t dot = key_path.find('.', start);
    const std::string key = key_path.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    WAAM_THROW_UNLESS(!key.empty(), "--set '" << override_text << "': empty key in '" << key_path << "'");
    WAAM_THROW_UNLESS(node.IsMap() || node.IsNull(),
                      "--set '" << override_text << "': '" << key_path.substr(0, start) << "' is not a section");
    if (dot == std::string::npos) {
      node[key] = value;
      return;
    }
    if (!node[key].IsDefined()) node[key] = YAML::Node(YAML::NodeType::Map);  // an absent optional section
    YAML::Node child = node[key];
    node.reset(child);
    start = dot + 1;
  }
}

}  // namespace

namespace internal {

YamlMap LoadScenarioTop(const fs::path& file, const std::vector<std::string>& overrides) {
  YAML::Node root = LoadYamlFile(file.string());
  for (const std::string& override_text : overrides) ApplyOverride(root, override_text);
  return YamlMap(root, "", file.string());
}

Scenario ParsePlannerSections(YamlMap& top) {
  Scenario scenario;
  std::error_code ec;
  scenario.file = fs::absolute(top.file(), ec).lexically_normal();
  scenario.dir = scenario.file.parent_path();
  if (top.Has("base_dir")) {
    const fs::path base = top.String("base_dir");
    scenario.dir = (base.is_relative() ? scenario.dir / base : base).lexically_normal();
    WAAM_THROW_UNLESS(fs::is_directory(scenario.dir, ec),
                      top.Where("base_dir") << ": folder " << scenario.dir.string() << " not found");
  }
  const YAML::Node root = top.node();

  scenario.name = top.String("name");
  WAAM_THROW_UNLESS(!scenario.name.empty(), top.Where("name") << ": must not be empty");

  // A scenario with a program: section (planner/program/program_section.h) needs no part, slicing or path.
  const bool from_program = root.IsMap() && root["program"];
  WAAM_THROW_UNLESS(!from_program || !root["part"],
                    top.Where("part") << ": give either part (planned here) or program (planned elsewhere), not both");
  if (!from_program) scenario.part = ParsePart(top.Map("part"), root["part"], scenario.dir);

  // slicing
  if (!from_program || top.Has("slicing")) {
    YamlMap slicing = top.Map("slicing");
    SlicingSettings& sl = scenario.slicing;
    sl.type = slicing.Enum("type", SlicingType::kPlanar);
    if (sl.type == SlicingType::kSkeleton) {
      sl.layer_height_mm = slicing.Number("layer_height_mm", 0.05, 20.0, 1.5);
      sl.h_min_mm = slicing.Number("h_min_mm", 0.05, 20.0, 1.0);
      sl.h_max_mm = slicing.Number("h_max_mm", 0.05, 20.0, 2.0);
      WAAM_THROW_UNLESS(sl.h_max_mm >= sl.h_min_mm, slicing.Where("h_max_mm") << " = " << sl.h_max_mm
                                                     << ": must be >= slicing.h_min_mm = " << sl.h_min_mm);
      sl.point_spacing_mm = slicing.Number("point_spacing_mm", 0.1, 100.0, 2.0);
      sl.first_step_mm = slicing.Number("first_step_mm", 0.0, 20.0, 0.0);
      sl.beta_deg = slicing.Number("beta_deg", 1e-4, 10.0, 0.1);
      sl.wall_mm = slicing.Number("wall_mm", 0.0, 100.0, 0.0);
    } else {
      sl.layer_height_mm = slicing.Number("layer_height_mm", 0.05, 20.0);
    }
    if (sl.type == SlicingType::kCone || sl.type == SlicingType::kCylinder) {
      SlicingSettings& s = scenario.slicing;
      s.cone_R_mm = slicing.Number("R_mm", 0.1, 1e5);
      if (s.type == SlicingType::kCone) {
        s.cone_H_mm = slicing.Number("H_mm", -1e6, 1e6);
        WAAM_THROW_UNLESS(std::abs(s.cone_H_mm) >= 1.0, slicing.Where("H_mm") << " = " << s.cone_H_mm
                              << ": |H| must be >= 1 mm (a cylinder is slicing.type: cylinder)");
      }
      const std::vector<double> axis = slicing.Numbers("axis_mm", 3, -1e5, 1e5, {0.0, 0.0, 0.0});
      std::copy(axis.begin(), axis.end(), s.cone_axis_mm.begin());
      s.cone_rotation_step_deg = slicing.Number("rotation_step_deg", 1.0, 180.0, 11.0);
    }
    if (sl.type == SlicingType::kMultiDirectional) {
      sl.split = slicing.Enum("split", SplitMethod::kPlanes);
      if (sl.split == SplitMethod::kCentroidShift) {
        sl.overhang_deg = slicing.Number("overhang_deg", 1.0, 80.0, 15.0);
        WAAM_THROW_UNLESS(!slicing.Has("sub_volumes"), slicing.Where("sub_volumes")
                              << ": split = centroid_shift finds the sub-volumes itself: remove sub_volumes");
      }
    }
    if (sl.type == SlicingType::kMultiDirectional && sl.split == SplitMethod::kPlanes) {
      for (YamlMap sub : slicing.Maps("sub_volumes")) {
        SubVolumeSpec spec;
        spec.name = sub.String("name");
        const std::vector<double> d = sub.Numbers("direction", 3, -1e3, 1e3);
        const double norm = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        WAAM_THROW_UNLESS(norm > 1e-9, sub.Where("direction") << ": must not be the zero vector");
        for (int k = 0; k < 3; ++k) spec.direction[k] = d[k] / norm;
        const std::vector<double> keep = sub.Numbers("keep", -1, -1e6, 1e6, {});
        WAAM_THROW_UNLESS(keep.size() % 4 == 0, sub.Where("keep") << ": " << keep.size()
                              << " numbers: give 4 per half-space n . p <= c (nx, ny, nz, c in mm)");
        for (std::size_t k = 0; k < keep.size(); k += 4) {
          spec.keep.push_back({keep[k], keep[k + 1], keep[k + 2], keep[k + 3]});
        }
        sub.CheckNoUnknownKeys();
        scenario.slicing.sub_volumes.push_back(std::move(spec));
      }
      WAAM_THROW_UNLESS(!scenario.slicing.sub_volumes.empty(),
                        slicing.Where("sub_volumes") << ": give at least one sub-volume");
    }
    slicing.CheckNoUnknownKeys();
  }

  // path
  if (!from_program || top.Has("path")) {
    YamlMap path = top.Map("path");
    PathSettings& s = scenario.path;
    const bool skeleton = scenario.slicing.type == SlicingType::kSkeleton;
    s.pattern = path.Enum<Pattern>("pattern");
    WAAM_THROW_UNLESS(skeleton || s.pattern != Pattern::kSpiral,
                      path.Where("pattern") << " = spiral: needs slicing.type = skeleton");
    WAAM_THROW_UNLESS(!skeleton || s.pattern == Pattern::kSpiral || s.pattern == Pattern::kContour,
                      path.Where("pattern") << " = " << NameOf(s.pattern)
                                            << ": slicing.type = skeleton plans a single-bead wall: use spiral "
                                               "(one pass) or contour (one closed pass per layer)");
    // Skeleton slicing takes the width at every point from the width-height model (eq. 6.7).
    s.bead_width_mm = skeleton ? path.Number("bead_width_mm", 0.5, 50.0, s.bead_width_mm)
                                                          : path.Number("bead_width_mm", 0.5, 50.0);
    s.overlap_model = path.Enum("overlap_model", OverlapModel::kProposed);
    if (path.Has("zigzag_angle_deg")) {
      const std::string raw = path.String("zigzag_angle_deg");
      if (raw == "auto") {
        s.zigzag_angle_auto = true;
      } else {
        s.zigzag_angle_auto = false;
        s.zigzag_angle_deg = path.Number("zigzag_angle_deg", -360.0, 360.0);
      }
    }
    s.alternate_start = path.Bool("alternate_start", true);
    s.seed = static_cast<std::uint64_t>(path.Integer("seed", 0, 2147483647, 1));
    s.retract_mm = path.Number("retract_mm", 0.0, 500.0, s.retract_mm);
    s.island_order = path.Enum("island_order", s.island_order);
    internal::ParseVoidFillingSection(path, scenario.dir, &s.void_filling);
    path.CheckNoUnknownKeys();
  }

  // process
  {
    YamlMap process = top.Map("process");
    ProcessSettings& p = scenario.process;
    // Skeleton slicing takes the speed at every point from the speed-height model (eq. 6.6).
    p.travel_speed_mm_min = scenario.slicing.type == SlicingType::kSkeleton
                                ? process.Number("travel_speed_mm_min", 10.0, 10000.0, p.travel_speed_mm_min)
                                : process.Number("travel_speed_mm_min", 10.0, 10000.0);
    p.wire_feed_mm_min = process.Number("wire_feed_mm_min", 100.0, 30000.0);
    p.wire_diameter_mm = process.Number("wire_diameter_mm", 0.6, 2.4, 1.0);
    p.deposition_efficiency = process.Number("deposition_efficiency", 0.05, 1.0, 1.0);
    p.bead_model = process.Enum("bead_model", BeadModel::kVolumeBalance);
    const bool curved = scenario.slicing.type == SlicingType::kCone || scenario.slicing.type == SlicingType::kCylinder;
    WAAM_THROW_UNLESS(curved || p.bead_model != BeadModel::kCsw, process.Where("bead_model")
                          << " = csw: needs slicing.type cone or cylinder (planar planning has no csw mode)");
    WAAM_THROW_UNLESS(!curved || p.bead_model != BeadModel::kSpeedHeight, process.Where("bead_model")
                          << " = speed_height: not available with slicing.type " << NameOf(scenario.slicing.type)
                          << " (use csw or volume_balance)");
    for (auto [key, target] : {std::pair{"csw_model", &p.csw_model},
                               std::pair{"speed_height_model", &p.speed_height_model},
                               std::pair{"width_height_model", &p.width_height_model}}) {
      if (!process.Has(key)) continue;
      fs::path file = process.String(key);
      if (file.is_relative()) file = scenario.dir / file;
      std::error_code ec;
      WAAM_THROW_UNLESS(fs::is_regular_file(file, ec),
                        process.Where(key) << ": model file " << file.string() << " not found");
      *target = file.lexically_normal();
    }
    p.rapid_speed_mm_min = process.Number("rapid_speed_mm_min", 100.0, 100000.0, 6000.0);
    p.arc_start_s = process.Number("arc_start_s", 0.0, 60.0, p.arc_start_s);
    p.arc_end_s = process.Number("arc_end_s", 0.0, 60.0, p.arc_end_s);
    ParseArcAndInterpass(process, &p.arc, &p.interpass);
    process.CheckNoUnknownKeys();
  }

  return scenario;
}

}  // namespace internal

Scenario LoadScenario(const fs::path& file, const std::vector<std::string>& overrides) {
  YamlMap top = internal::LoadScenarioTop(file, overrides);
  return internal::ParsePlannerSections(top);
}

}  // namespace waam::planner
