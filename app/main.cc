// The `waam` executable: a thin main over the libraries that parses the command line and maps errors to exit codes.
#include <cstdio>
#include <exception>
#include <iostream>

#include "app/commands.h"
#include "models/core/data_dir.h"
#include "models/core/error.h"
#include "models/core/parallel.h"
#include "models/core/progress.h"

int main(int argc, char** argv) {
  using namespace waam::app;
  CLI::App app{
      "waam: a simulation and digital-twin testbed for wire-arc additive manufacturing.\n"
      "Plans weld paths from STL parts, checks them on a MuJoCo robot cell, deposits them in a voxel twin,\n"
      "fits process models and reports against published measurements.\n\n"
      "Exit codes: 0 success, 1 internal error, 2 bad input, 3 check found violations, 130 interrupted.",
      "waam"};
  app.require_subcommand(1);
  app.set_version_flag("--version", [] {
    return "waam " + waam::VersionString() + "\ndata: " + waam::DataDir().string();
  });

  CommandRunner runner;
  AddPlanCommand(app, &runner);
  AddInspectCommand(app, &runner);
  AddGenerateCommand(app, &runner);
  AddFitCommand(app, &runner);
  AddCheckCommand(app, &runner);
  AddPlaceCommand(app, &runner);
  AddSimulateCommand(app, &runner);
  AddTuneVoidsCommand(app, &runner);
  AddRunCommand(app, &runner);
  AddBenchCommand(app, &runner);
  AddSweepCommand(app, &runner);
  AddDeviationCommand(app, &runner);
  AddCompensateCommand(app, &runner);
  AddImportCommand(app, &runner);
  AddExportCommand(app, &runner);
  AddThermalCommand(app, &runner);
  AddMaterialCommand(app, &runner);
  AddScenarioKeysCommand(app, &runner);

  // Every command takes --threads; the outputs are the same for any number of threads.
  int threads = 0;
  for (CLI::App* command : app.get_subcommands([](CLI::App*) { return true; })) {
    command->add_option("--threads", threads, "Threads for the parallel steps (default 0 = all hardware threads)")
        ->check(CLI::Range(0, 4096));
  }

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kExitBadInput;
  }

  waam::InstallInterruptHandler();
  try {
    waam::SetThreadCount(threads);
    return runner ? runner() : kExitBadInput;
  } catch (const waam::InputError& e) {
    std::cerr << "waam: error: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const waam::Interrupted&) {
    std::cerr << "waam: interrupted; partial outputs were removed\n";
    return kExitInterrupted;
  } catch (const std::exception& e) {
    std::cerr << "waam: internal error: " << e.what() << "\n";
    return kExitInternalError;
  }
}
