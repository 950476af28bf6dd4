// `waam material`: command-line options for checking and printing a thermal material file.
#include <memory>

#include "analysis/material_command.h"
#include "analysis/thermal_material_io.h"
#include "app/commands.h"

namespace waam::app {

void AddMaterialCommand(CLI::App& app, CommandRunner* runner) {
  auto options = std::make_shared<analysis::MaterialOptions>();
  std::string known;
  for (const std::string& name : analysis::KnownThermalMaterials()) known += (known.empty() ? "" : ", ") + name;
  CLI::App* command = app.add_subcommand(
      "material",
      "Load a thermal material as the thermal model reads it (temperature-dependent conductivity, density and\n"
      "specific heat, solidus, liquidus, latent heat, emissivity, with its cited sources) and print it as JSON.\n"
      "MATERIAL is a shipped name (" + known + ") or the path of your own .csv file in the same format\n"
      "(docs/THERMAL.md, \"Materials\"). Exit code 2 with a one-line message naming the file and the row or key for\n"
      "a file that breaks a rule (temperatures not strictly increasing, a property <= 0, text in a number, ...).");
  command->add_option("material", options->material, "material name or .csv file")->required();
  command->add_option("-o,--output", options->out_dir, "folder to write material.json into (atomically)");
  command->add_flag("-q,--quiet", options->quiet, "do not print the JSON");
  command->callback([runner, options] {
    *runner = [options] {
      analysis::RunMaterialCommand(*options);
      return kExitOk;
    };
  });
}

}  // namespace waam::app
