// `waam generate`: writes a procedural test part (box, plate with holes, Ding 2014 shapes, rib-web...) as binary STL.
#include <algorithm>
#include <charconv>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "app/commands.h"
#include "models/core/error.h"
#include "planner/mesh/generators.h"
#include "planner/mesh/mesh_ops.h"
#include "analysis/stl_file.h"

namespace waam::app {
namespace {

// Parses "key=v1,v2,..." (or "key=v1 v2 ...": commas or spaces, like every list option) into (key, values).
// Throws InputError naming the option for anything else.
std::pair<std::string, std::vector<double>> ParseParam(const std::string& text) {
  const std::size_t eq = text.find('=');
  WAAM_THROW_UNLESS(eq != std::string::npos && eq > 0 && eq + 1 < text.size(),
                    "waam generate --param '" << text << "': expected key=v1[,v2,...], e.g. size_mm=100,60,40");
  // One comma with any spaces round it, or spaces alone, separate two values.
  std::string list;
  for (std::size_t k = eq + 1; k < text.size(); ++k) {
    if (text[k] != ' ') {
      list += text[k];
    } else if (!list.empty() && list.back() != ',' && k + 1 < text.size() && text[k + 1] != ' ' &&
               text[k + 1] != ',') {
      list += ',';
    }
  }
  std::vector<double> values;
  std::size_t start = 0;
  while (start <= list.size()) {
    const std::size_t comma = std::min(list.find(',', start), list.size());
    const std::string item = list.substr(start, comma - start);
    double value = 0.0;
    const auto [end, ec] = std::from_chars(item.data(), item.data() + item.size(), value);
    WAAM_THROW_UNLESS(!item.empty() && ec == std::errc() && end == item.data() + item.size(),
                      "waam generate --param '" << text << "': '" << item << "' is not a number");
    values.push_back(value);
    start = comma + 1;
  }
  return {text.substr(0, eq), values};
}

}  // namespace

void AddGenerateCommand(CLI::App& app, CommandRunner* runner) {
  struct Options {
    std::string type;
    std::vector<std::string> params;
    std::string output;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand(
      "generate",
      "Write a procedural part as a binary STL (mm, closed, outward normals, centred on x = y = 0, resting on z = 0).\n"
      "Parameters not given take their defaults. Example:\n"
      "  waam generate plate_with_holes --param size_mm=200,120,10 --param hole_diameters_mm=40 \\\n"
      "      --param hole_centers_mm=0,0 -o plate.stl\n"
      "Types, parameters and defaults:\n" +
          planner::GeneratorHelp());
  command->add_option("type", options->type, "generator type (see the list above)")->required();
  command->add_option("--param", options->params, "a parameter as key=v1[,v2,...] (repeatable), e.g. size_mm=100,60,40 or \"size_mm=100 60 40\"")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  command->add_option("-o,--output", options->output, "STL file to write (written atomically)")->required();
  command->callback([runner, options] {
    *runner = [options] {
      planner::GeneratorParams params;
      for (const std::string& text : options->params) {
        auto [key, values] = ParseParam(text);
        WAAM_THROW_UNLESS(params.count(key) == 0, "waam generate --param " << key << " is given twice");
        params[key] = values;
      }
      const planner::TriangleMesh mesh = planner::GeneratePart(options->type, params, "waam generate " + options->type);
      analysis::WriteStlBinary(mesh, options->output);
      const planner::MeshReport report = planner::InspectMesh(mesh, 0.0, options->type);
      std::cout << options->output << ": " << options->type << ", " << report.facets << " facets, volume "
                << report.volume_mm3 << " mm^3, bbox [" << report.bbox_max.x() - report.bbox_min.x() << " x "
                << report.bbox_max.y() - report.bbox_min.y() << " x " << report.bbox_max.z() - report.bbox_min.z()
                << "] mm\n";
      return kExitOk;
    };
  });
}

}  // namespace waam::app
