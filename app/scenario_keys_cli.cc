// `waam scenario-keys`: prints every scenario key (docs/SCENARIO_KEYS.md), generated from the field tables.
#include <iostream>

#include "analysis/scenario_keys.h"
#include "app/commands.h"

namespace waam::app {

void AddScenarioKeysCommand(CLI::App& app, CommandRunner* runner) {
  CLI::App* command = app.add_subcommand(
      "scenario-keys",
      "Print every key of a scenario file as Markdown tables (type, unit, default, range, meaning), generated from\n"
      "the field tables the scenario loader reads with: the text of docs/SCENARIO_KEYS.md.");
  command->callback([runner] {
    *runner = [] {
      std::cout << analysis::ScenarioKeysMarkdown();
      return kExitOk;
    };
  });
}

}  // namespace waam::app
