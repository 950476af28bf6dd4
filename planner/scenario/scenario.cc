// The planner's sections of a scenario document: every section validated up front, with the key path in each message.
#include "planner/scenario/scenario.h"

#include <algorithm>
#include <cmath>

#include "models/core/error.h"
#include "planner/scenario/scenario_document.h"
#include "planner/scenario/scenario_fields.h"

namespace waam::planner {
namespace fs = std::filesystem;

namespace {

// part: either `mesh: file.stl` (relative to the scenario file) or `generator: {type: name, <param>: value...}`.
PartSpec ParsePart(YamlMap part) {
  PartSpec spec;
  spec.where = part.Where("");
  const bool has_mesh = part.Has("mesh");
  const bool has_generator = part.Has("generator");
  WAAM_THROW_UNLESS(has_mesh != has_generator, spec.where << ": give exactly one of 'mesh' or 'generator'");
  if (has_mesh) {
    ReadField<PartSpec>(part, kPartFields, "mesh", &spec);  // the loader checks the file is there, then reads it
    spec.mesh_where = part.Where("mesh");
  } else {
    YamlMap generator = part.Map("generator");
    spec.where = generator.Where("");
    ReadField<PartSpec>(generator, kPartGeneratorFields, "type", &spec, true);
    // Every other key is a parameter of the type, from its field table (planner/mesh/generators.h).
    ReadFields<GeneratorParams>(generator, GeneratorFields(*spec.generator), &spec.params);
    generator.CheckNoUnknownKeys();
  }
  part.CheckNoUnknownKeys();
  return spec;
}

}  // namespace

void FinishSubVolume(YamlMap& element, SubVolumeSpec* sub) {
  element.Require("name");
  element.Require("direction");
  const std::array<double, 3>& d = sub->direction;
  const double norm = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  WAAM_THROW_UNLESS(norm > 1e-9, element.Where("direction") << ": must not be the zero vector");
  for (double& x : sub->direction) x /= norm;
}

namespace {

// slicing: the keys of its type, the sub-volumes of a multi-directional split by planes.
void ParseSlicing(YamlMap& top, SlicingSettings* out) {
  SlicingSettings& sl = *out;
  YamlMap slicing = top.Map("slicing");
  auto read = [&](std::string_view key, bool required = false) {
    ReadField<SlicingSettings>(slicing, kSlicingFields, key, &sl, required);
  };
  read("type");
  if (sl.type == SlicingType::kSkeleton) {
    for (const char* key : {"layer_height_mm", "h_min_mm", "h_max_mm"}) read(key);
    WAAM_THROW_UNLESS(sl.h_max_mm >= sl.h_min_mm, slicing.Where("h_max_mm") << " = " << sl.h_max_mm
                                                   << ": must be >= slicing.h_min_mm = " << sl.h_min_mm);
    for (const char* key : {"point_spacing_mm", "first_step_mm", "beta_deg", "wall_mm"}) read(key);
  } else {
    read("layer_height_mm", true);
  }
  if (sl.type == SlicingType::kCone || sl.type == SlicingType::kCylinder) {
    read("R_mm", true);
    if (sl.type == SlicingType::kCone) {
      read("H_mm", true);
      WAAM_THROW_UNLESS(std::abs(sl.cone_H_mm) >= 1.0, slicing.Where("H_mm") << " = " << sl.cone_H_mm
                            << ": |H| must be >= 1 mm (a cylinder is slicing.type: cylinder)");
    }
    read("axis_mm");
    read("rotation_step_deg");
  }
  if (sl.type == SlicingType::kMultiDirectional) {
    read("split");
    if (sl.split == SplitMethod::kCentroidShift) {
      read("overhang_deg");
      WAAM_THROW_UNLESS(!slicing.Has("sub_volumes"), slicing.Where("sub_volumes")
                            << ": split = centroid_shift finds the sub-volumes itself: remove sub_volumes");
    }
  }
  if (sl.type == SlicingType::kMultiDirectional && sl.split == SplitMethod::kPlanes) {
    read("sub_volumes");
    WAAM_THROW_UNLESS(!sl.sub_volumes.empty(),
                      slicing.Where("sub_volumes") << ": give at least one sub-volume");
  }
  slicing.CheckNoUnknownKeys();
}

// path: the pattern (as the slicing type allows), the bead width, the void filling.
void ParsePath(YamlMap& top, SlicingType slicing_type, PathSettings* out) {
  PathSettings& s = *out;
  YamlMap path = top.Map("path");
  const bool skeleton = slicing_type == SlicingType::kSkeleton;
  auto read = [&](std::string_view key, bool required = false) {
    ReadField<PathSettings>(path, kPathFields, key, &s, required);
  };
  read("pattern", true);
  WAAM_THROW_UNLESS(skeleton || s.pattern != Pattern::kSpiral,
                    path.Where("pattern") << " = spiral: needs slicing.type = skeleton");
  WAAM_THROW_UNLESS(!skeleton || s.pattern == Pattern::kSpiral || s.pattern == Pattern::kContour,
                    path.Where("pattern") << " = " << NameOf(s.pattern)
                                          << ": slicing.type = skeleton plans a single-bead wall: use spiral "
                                             "(one pass) or contour (one closed pass per layer)");
  // Skeleton slicing takes the width at every point from the width-height model (eq. 6.7).
  read("bead_width_mm", !skeleton);
  read("overlap_model");
  if (path.Has("zigzag_angle_deg")) {
    const std::string raw = path.String("zigzag_angle_deg");
    if (raw == "auto") {
      s.zigzag_angle_auto = true;
    } else {
      s.zigzag_angle_auto = false;
      read("zigzag_angle_deg");
    }
  }
  for (const char* key : {"alternate_start", "seed", "retract_mm", "island_order"}) read(key);
  internal::ParseVoidFillingSection(path, &s.void_filling);
  path.CheckNoUnknownKeys();
}

// process: speeds, wire, the bead model (as the slicing type allows), the model files, arc and interpass.
void ParseProcess(YamlMap& top, SlicingType slicing_type, ProcessSettings* out) {
  ProcessSettings& p = *out;
  YamlMap process = top.Map("process");
  // Skeleton slicing takes the speed at every point from the speed-height model (eq. 6.6).
  auto read = [&](std::string_view key, bool required = false) {
    ReadField<ProcessSettings>(process, kProcessFields, key, &p, required);
  };
  read("travel_speed_mm_min", slicing_type != SlicingType::kSkeleton);
  read("wire_feed_mm_min", true);
  for (const char* key : {"wire_diameter_mm", "deposition_efficiency", "bead_model"}) read(key);
  const bool curved = slicing_type == SlicingType::kCone || slicing_type == SlicingType::kCylinder;
  WAAM_THROW_UNLESS(curved || p.bead_model != BeadModel::kCsw, process.Where("bead_model")
                        << " = csw: needs slicing.type cone or cylinder (planar planning has no csw mode)");
  WAAM_THROW_UNLESS(!curved || p.bead_model != BeadModel::kSpeedHeight, process.Where("bead_model")
                        << " = speed_height: not available with slicing.type " << NameOf(slicing_type)
                        << " (use csw or volume_balance)");
  for (const char* key : {"csw_model", "speed_height_model", "width_height_model", "rapid_speed_mm_min", "arc_start_s",
                          "arc_end_s"}) {
    read(key);
  }
  ParseArcAndInterpass(process, &p.arc, &p.interpass);
  process.CheckNoUnknownKeys();
}

}  // namespace

PlannerSections ParsePlannerSections(YamlMap& top) {
  PlannerSections scenario;
  std::error_code ec;
  scenario.file = fs::absolute(top.file(), ec).lexically_normal();
  scenario.dir = scenario.file.parent_path();
  if (top.Has("base_dir")) {
    const fs::path base = top.String("base_dir");
    scenario.dir = (base.is_relative() ? scenario.dir / base : base).lexically_normal();
    scenario.base_dir_where = top.Where("base_dir");  // the scenario loader checks the folder
  }
  top.SetBaseDir(scenario.dir);  // every section's files are taken from it

  ReadField<PlannerSections>(top, kScenarioTopFields, "name", &scenario, true);
  WAAM_THROW_UNLESS(!scenario.name.empty(), top.Where("name") << ": must not be empty");

  // A scenario with a program: section (planner/program/program_section.h) needs no part, slicing or path.
  const bool from_program = top.Has("program");
  WAAM_THROW_UNLESS(!from_program || !top.Has("part"),
                    top.Where("part") << ": give either part (planned here) or program (planned elsewhere), not both");
  if (!from_program) scenario.part = ParsePart(top.Map("part"));

  if (!from_program || top.Has("slicing")) ParseSlicing(top, &scenario.slicing);
  if (!from_program || top.Has("path")) ParsePath(top, scenario.slicing.type, &scenario.path);
  ParseProcess(top, scenario.slicing.type, &scenario.process);
  return scenario;
}

}  // namespace waam::planner
