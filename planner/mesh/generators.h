// Procedural test parts (boxes, plates with holes, L/T sections, Ding et al. 2014 test shapes, rib-web grids,
// cylinders, spheres, tori) as closed meshes in millimetres.
#pragma once

#include <array>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "models/core/enum_names.h"
#include "models/core/field_table.h"
#include "planner/mesh/triangle_mesh.h"

namespace waam::planner {

// The generator types (part.generator.type, `waam generate <type>`), named in sorted order.
enum class PartGenerator {
  kBentTube, kBox, kCupTwoHandles, kCylinder, kDingA, kDingB, kDingC, kDingD, kJunction, kLShape, kPlateWithHoles,
  kPropeller, kRibWeb, kSphere, kTShape, kThrusterBlades, kTorus
};
constexpr std::array<EnumName<PartGenerator>, 17> EnumNames(PartGenerator) {
  return {{{PartGenerator::kBentTube, "bent_tube"},
           {PartGenerator::kBox, "box"},
           {PartGenerator::kCupTwoHandles, "cup_two_handles"},
           {PartGenerator::kCylinder, "cylinder"},
           {PartGenerator::kDingA, "ding_a"},
           {PartGenerator::kDingB, "ding_b"},
           {PartGenerator::kDingC, "ding_c"},
           {PartGenerator::kDingD, "ding_d"},
           {PartGenerator::kJunction, "junction"},
           {PartGenerator::kLShape, "l_shape"},
           {PartGenerator::kPlateWithHoles, "plate_with_holes"},
           {PartGenerator::kPropeller, "propeller"},
           {PartGenerator::kRibWeb, "rib_web"},
           {PartGenerator::kSphere, "sphere"},
           {PartGenerator::kTShape, "t_shape"},
           {PartGenerator::kThrusterBlades, "thruster_blades"},
           {PartGenerator::kTorus, "torus"}}};
}
WAAM_ENUM_JSON(PartGenerator)

// The type named `name`. Throws InputError "<where>: unknown generator type '<name>' (known: ...)" for another name.
PartGenerator ParsePartGenerator(const std::string& name, const std::string& where);

// Parameter values by name; each is a number or a list of numbers (units in the name: _mm, counts unitless).
using GeneratorParams = std::map<std::string, std::vector<double>>;

// The parameters of `type`, one row each (models/core/field_table.h: EntryField; the unit from the name's _mm or
// _deg): they read part.generator with file:line errors, check parameters built in code (ResolveGeneratorParams) and
// make the key tables of docs/SCENARIO_KEYS.md.
std::span<const Field<GeneratorParams>> GeneratorFields(PartGenerator type);
// The default of every parameter of `type`.
const GeneratorParams& GeneratorDefaults(PartGenerator type);

// Builds the part `type` with `params` (missing ones take their defaults; see GeneratorHelp()). The mesh is closed,
// with outward normals, deterministic, in mm, centred on x = y = 0 (bounding box centre) and sitting on z = 0,
// except the parts built in the frame of the surface they grow on (thruster_blades: the cone's frame).
// `where` prefixes every message ("file:line: part.generator"). Throws InputError for an unknown type, an unknown
// parameter, a wrong number of values, a value out of range or parameters that contradict each other.
TriangleMesh GeneratePart(PartGenerator type, const GeneratorParams& params, const std::string& where);
// The same for the type named `type` (ParsePartGenerator).
TriangleMesh GeneratePart(const std::string& type, const GeneratorParams& params, const std::string& where);

// The parameters of `type` after the same checks as GeneratePart, with every default filled in.
GeneratorParams ResolveGeneratorParams(PartGenerator type, const GeneratorParams& params, const std::string& where);

// The generator type names, sorted (the names of PartGenerator).
std::vector<std::string> GeneratorTypes();

// Multi-line description of every type and its parameters with defaults and units (for `waam generate --help`).
std::string GeneratorHelp();

}  // namespace waam::planner
