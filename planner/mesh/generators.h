// Procedural test parts (boxes, plates with holes, L/T sections, Ding et al. 2014 test shapes, rib-web grids,
// cylinders, spheres, tori) as closed meshes in millimetres.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "planner/mesh/triangle_mesh.h"

namespace waam::planner {

// Parameter values by name; each is a number or a list of numbers (units in the name: _mm, counts unitless).
using GeneratorParams = std::map<std::string, std::vector<double>>;

// Builds the part `type` with `params` (missing ones take their defaults; see GeneratorHelp()). The mesh is closed,
// with outward normals, deterministic, in mm, centred on x = y = 0 (bounding box centre) and sitting on z = 0.
// `where` prefixes every message ("file:line: part.generator"). Throws InputError for an unknown type, an unknown
// parameter, a wrong number of values, a value out of range or parameters that contradict each other.
TriangleMesh GeneratePart(const std::string& type, const GeneratorParams& params, const std::string& where);

// The parameters of `type` after the same checks as GeneratePart, with every default filled in.
GeneratorParams ResolveGeneratorParams(const std::string& type, const GeneratorParams& params,
                                       const std::string& where);

// The generator type names, sorted.
std::vector<std::string> GeneratorTypes();

// Multi-line description of every type and its parameters with defaults and units (for `waam generate --help`).
std::string GeneratorHelp();

}  // namespace waam::planner
