// `waam export`: plan, move the cell, write one dialect.
#include "analysis/export_command.h"


#include "analysis/cell_files.h"
#include "analysis/import_command.h"
#include "analysis/scenario_plan.h"
#include "models/core/error.h"
#include "models/core/files.h"
#include "models/core/progress.h"
#include "planner/program/abb_rapid.h"
#include "planner/program/fanuc_ls.h"
#include "planner/program/gcode.h"
#include "planner/program/kuka_krl.h"
#include "planner/program/program_reader.h"
#include "planner/program/yaskawa_jbi.h"
#include "twin/cell/cell_check.h"
#include "twin/cell/cell_presets.h"
#include "twin/cell/mujoco_cell.h"

namespace waam::analysis {
namespace fs = std::filesystem;

std::string WriteProgramText(planner::ProgramFormat format, const planner::RobotProgram& program,
                             const planner::CellKinematics& kin, const planner::JbiReadOptions& jbi) {
  switch (format) {
    case planner::ProgramFormat::kCsv: return planner::ProgramToCsv(program);
    case planner::ProgramFormat::kFanucLs: return planner::ProgramToFanucLs(program, planner::FanucLsOptions{});
    case planner::ProgramFormat::kAbbRapid: {
      planner::AbbRapidOptions options;
      options.X_RU = kin.X_WR.inverse() * planner::ProgramUserFrame(kin);
      options.X_FT = kin.X_FT;
      return planner::ProgramToAbbRapid(program, options);
    }
    case planner::ProgramFormat::kGcode: return planner::ProgramToGcode(program, planner::GcodeOptions{});
    case planner::ProgramFormat::kKukaKrl: {
      // One text: the .src, then its .dat (RunExport writes them as two files).
      planner::KukaKrlOptions options;
      options.X_RU = kin.X_WR.inverse() * planner::ProgramUserFrame(kin);
      const planner::KukaKrlFiles files = planner::ProgramToKukaKrl(program, options);
      return files.src + files.dat;
    }
    case planner::ProgramFormat::kYaskawaJbi: {
      planner::YaskawaJbiOptions options;
      options.X_RU = kin.X_WR.inverse() * planner::ProgramUserFrame(kin);
      options.station_pulses_per_deg = jbi.station_pulses_per_deg;
      return planner::ProgramToYaskawaJbi(program, options);
    }
  }
  WAAM_DEMAND(false);
  return {};
}

ProgramFiles ExportPlan(const Scenario& scenario, const planner::Plan& plan,
                        std::optional<planner::ProgramFormat> format,
                        const std::vector<double>& station_pulses_per_deg, bool quiet) {
  ProgramFiles out;
  out.format = format ? *format
                      : scenario.cell.preset ? twin::PresetDialect(*scenario.cell.preset)
                                             : planner::ProgramFormat::kFanucLs;
  const planner::JbiReadOptions jbi = JbiOptionsOf(scenario, {}, station_pulses_per_deg);
  const twin::CellModel cell = LoadCell(scenario.cell);
  twin::CheckReport report;
  {
    Progress progress("check", 0, "samples", quiet);
    report = twin::CheckPlan(cell, plan, scenario.cell, scenario.process.rapid_speed_mm_min / 60.0, &progress);
    progress.Finish();
  }
  const planner::CellKinematics kin = twin::PartKinematics(cell, scenario.cell);
  const planner::RobotProgram program = planner::BuildProgram(kin, report.motion, scenario.name);
  if (out.format == planner::ProgramFormat::kKukaKrl) {
    // <name>.src and <name>.dat side by side.
    planner::KukaKrlOptions krl;
    krl.X_RU = kin.X_WR.inverse() * planner::ProgramUserFrame(kin);
    const planner::KukaKrlFiles files = planner::ProgramToKukaKrl(program, krl);
    out.files = {{".src", files.src}, {".dat", files.dat}};
  } else {
    out.files = {{"", WriteProgramText(out.format, program, kin, jbi)}};
  }
  out.points = program.points.size();
  out.violations = report.violations.size();
  return out;
}

ExportResult RunExport(const ExportOptions& options) {
  const Scenario scenario = LoadScenario(options.scenario, options.overrides);
  std::optional<planner::ProgramFormat> format = options.format;
  if (!format) format = planner::ProgramFormatOfExtension(options.out_file);
  planner::PlanResult planned = PlanForCommand(scenario, options.quiet);
  const ProgramFiles program =
      ExportPlan(scenario, planned.plan, format, options.station_pulses_per_deg, options.quiet);
  if (program.files.size() == 2) {
    // KUKA KRL: <name>.src and <name>.dat side by side, the .dat first.
    fs::path src = options.out_file, dat = options.out_file;
    src.replace_extension(".src");
    dat.replace_extension(".dat");
    WriteFileAtomic(dat, program.files[1].second);
    WriteFileAtomic(src, program.files[0].second);
  } else {
    WriteFileAtomic(options.out_file, program.files[0].second);
  }
  ExportResult result;
  result.format = program.format;
  result.points = program.points;
  result.violations = program.violations;
  return result;
}

}  // namespace waam::analysis
