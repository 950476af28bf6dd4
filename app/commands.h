// The subcommands of the `waam` executable; each Add* function registers one on the CLI11 app.
#pragma once

#include <functional>

#include <CLI/CLI.hpp>

namespace waam::app {

// What a subcommand runs once its options are parsed; returns the process exit code.
using CommandRunner = std::function<int()>;

// Exit codes: the public contract documented in docs/COMMANDS.md.
inline constexpr int kExitOk = 0;
inline constexpr int kExitInternalError = 1;
inline constexpr int kExitBadInput = 2;
inline constexpr int kExitViolations = 3;  // `waam check` found violations
inline constexpr int kExitInterrupted = 130;

// Each registers its subcommand and sets `*runner` when it is the one selected.
void AddPlanCommand(CLI::App& app, CommandRunner* runner);      // app/plan_cli.cc
void AddInspectCommand(CLI::App& app, CommandRunner* runner);   // app/inspect_cli.cc
void AddGenerateCommand(CLI::App& app, CommandRunner* runner);  // app/generate_cli.cc
void AddFitCommand(CLI::App& app, CommandRunner* runner);       // app/fit_cli.cc
void AddCheckCommand(CLI::App& app, CommandRunner* runner);     // app/check_cli.cc
void AddPlaceCommand(CLI::App& app, CommandRunner* runner);     // app/place_cli.cc
void AddSimulateCommand(CLI::App& app, CommandRunner* runner);  // app/simulate_cli.cc
void AddTuneVoidsCommand(CLI::App& app, CommandRunner* runner);  // app/tune_voids_cli.cc
void AddRunCommand(CLI::App& app, CommandRunner* runner);       // app/run_cli.cc
void AddBenchCommand(CLI::App& app, CommandRunner* runner);     // app/bench_cli.cc
void AddSweepCommand(CLI::App& app, CommandRunner* runner);     // app/sweep_cli.cc
void AddDeviationCommand(CLI::App& app, CommandRunner* runner);   // app/distortion_cli.cc
void AddCompensateCommand(CLI::App& app, CommandRunner* runner);  // app/distortion_cli.cc
void AddImportCommand(CLI::App& app, CommandRunner* runner);      // app/import_cli.cc
void AddExportCommand(CLI::App& app, CommandRunner* runner);      // app/export_cli.cc
void AddThermalCommand(CLI::App& app, CommandRunner* runner);     // app/thermal_cli.cc
// `waam thermal replay`, below `thermal` (app/replay_cli.cc); returns the subcommand.
CLI::App* AddThermalReplayCommand(CLI::App& thermal, CommandRunner* runner);
void AddMaterialCommand(CLI::App& app, CommandRunner* runner);    // app/material_cli.cc
void AddScenarioKeysCommand(CLI::App& app, CommandRunner* runner);  // app/scenario_keys_cli.cc

}  // namespace waam::app
