// The scenario's key paths, docs tables and validation, from each module's field tables.
#include "analysis/scenario_keys.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "analysis/place_settings.h"
#include "analysis/replay_settings.h"
#include "analysis/run_settings.h"
#include "analysis/thermal_settings.h"
#include "models/core/error.h"
#include "planner/scenario/arc_settings.h"
#include "planner/scenario/scenario_fields.h"
#include "twin/cell/cell_settings.h"
#include "twin/simulation_settings.h"

namespace waam::analysis {
namespace {

template <typename S, std::size_t N>
SectionKeys Section(std::string path, const std::array<Field<S>, N>& fields) {
  return {std::move(path), Describe<S>(fields)};
}

// part.generator: its type, then one section per type of that type's parameters (planner/mesh/generators.h).
void AddGeneratorSections(std::vector<SectionKeys>* sections) {
  sections->push_back({"part.generator", Describe<planner::PartSpec>(planner::kPartGeneratorFields)});
  for (const EnumName<planner::PartGenerator>& entry : EnumNames(planner::PartGenerator{})) {
    sections->push_back({"part.generator",
                         Describe<planner::GeneratorParams>(planner::GeneratorFields(entry.value),
                                                            planner::GeneratorDefaults(entry.value)),
                         std::string(entry.name)});
  }
}

std::vector<SectionKeys> MakeSections() {
  std::vector<SectionKeys> sections = {
      Section("", planner::kScenarioTopFields),
      Section("part", planner::kPartFields),
      Section("slicing", planner::kSlicingFields),
      Section("slicing.sub_volumes[]", planner::kSubVolumeFields),
      Section("path", planner::kPathFields),
      Section("path.void_filling", planner::kVoidFillingFields),
      Section("process", planner::kProcessFields),
      Section("process.arc", planner::kArcFields),
      Section("process.interpass", planner::kInterpassFields),
      Section("cell", twin::kCellFields),
      Section("cell.robot", twin::kCellRobotFields),
      Section("cell.positioner", twin::kCellPositionerFields),
      Section("cell.torch", twin::kTorchFields),
      Section("cell.part", twin::kCellPartFields),
      Section("cell.checks", twin::kCellChecksFields),
      Section("simulation", twin::kSimulationFields),
      Section("run", kRunFields),
      Section("place", kPlaceFields),
      Section("program", planner::kProgramFields),
      Section("program.frame", planner::kProgramFrameFields),
      Section("program.gcode", planner::kProgramGcodeFields),
      Section("program.yaskawa", planner::kProgramYaskawaFields),
      Section("program.frames", planner::kProgramFramesFields),
      Section("thermal", kThermalFields),
      Section("thermal.substrate", kThermalSubstrateFields),
      Section("thermal.table", kThermalTableFields),
      Section("thermal.clamps[]", kThermalClampFields),
      Section("thermal.pool", kThermalPoolFields),
      Section("thermal.shape", kThermalShapeFields),
      Section("replay", kReplayFields),
      Section("replay.probes.<NAME>", kReplayProbeFields),
      Section("replay.columns", kReplayColumnFields),
      Section("replay.frame", kReplayFrameFields),
      Section("replay.bead", kReplayBeadFields),
  };
  // The top level's `target` is read with the program section (planner/scenario/scenario_fields.h).
  for (FieldInfo& f : Describe<planner::ProgramSettings>(planner::kProgramTargetFields)) {
    sections.front().fields.push_back(std::move(f));
  }
  AddGeneratorSections(&sections);
  std::stable_partition(sections.begin(), sections.end(), [](const SectionKeys& s) {
    return s.path.empty() || s.path == "part" || s.path.rfind("part.", 0) == 0;
  });
  // The top level holds the sections too.
  for (const SectionKeys& s : sections) {
    if (s.path.empty() || s.path.find('.') != std::string::npos) continue;
    bool listed = false;
    for (const FieldInfo& f : sections.front().fields) listed = listed || f.key == s.path;
    if (!listed) sections.front().fields.push_back({s.path, FieldType::kMap, "", "", "", "the " + s.path + " section"});
  }
  return sections;
}

const SectionKeys* FindSection(const std::string& path) {
  for (const SectionKeys& s : ScenarioSections()) {
    if (s.path == path) return &s;
  }
  return nullptr;
}

// The row of `key` in any section at `path` (part.generator has one section per generator type).
const FieldInfo* FindKey(const std::string& path, const std::string& key) {
  for (const SectionKeys& s : ScenarioSections()) {
    if (s.path != path) continue;
    for (const FieldInfo& f : s.fields) {
      if (f.key == key) return &f;
    }
  }
  return nullptr;
}

}  // namespace

const std::vector<SectionKeys>& ScenarioSections() {
  static const std::vector<SectionKeys> sections = MakeSections();
  return sections;
}

bool IsScenarioKeyPath(const std::string& key_path) {
  if (key_path.empty() || FindSection(key_path)) return !key_path.empty();
  // The longest section that is a prefix, then one key of it.
  std::string section = key_path;
  while (true) {
    const std::size_t dot = section.rfind('.');
    const std::string parent = dot == std::string::npos ? "" : section.substr(0, dot);
    const std::string rest = key_path.substr(parent.empty() ? 0 : parent.size() + 1);
    if (FindSection(parent)) {
      const std::string key = rest.substr(0, rest.find('.'));
      const FieldInfo* f = FindKey(parent, key);
      // A key itself, or a key below a mapping or list (program.frames.uframe.6).
      return f && (rest == key || f->type == FieldType::kMap || f->type == FieldType::kList);
    }
    if (dot == std::string::npos) return false;
    section = parent;
  }
}

void CheckOverrideKeys(const std::vector<std::string>& overrides) {
  for (const std::string& text : overrides) {
    const std::size_t eq = text.find('=');
    if (eq == std::string::npos || eq == 0) continue;  // the loader names a malformed override
    const std::string key_path = text.substr(0, eq);
    if (IsScenarioKeyPath(key_path)) continue;
    // Below a key that is not a section: the loader says so ("'name' is not a section").
    bool below_a_value = false;
    for (std::size_t dot = key_path.find('.'); dot != std::string::npos; dot = key_path.find('.', dot + 1)) {
      const std::string prefix = key_path.substr(0, dot);
      below_a_value = below_a_value || (IsScenarioKeyPath(prefix) && !FindSection(prefix));
    }
    if (below_a_value) continue;
    const std::size_t dot = key_path.rfind('.');
    const SectionKeys* section = FindSection(dot == std::string::npos ? "" : key_path.substr(0, dot));
    std::ostringstream known;
    if (section) {
      known << " (keys of " << (section->path.empty() ? "the top level" : section->path) << ":";
      for (const FieldInfo& f : section->fields) known << " " << f.key;
      known << ")";
    }
    WAAM_THROW("--set '" << text << "': unknown key '" << key_path << "'" << known.str()
                         << "; docs/SCENARIO_KEYS.md lists every key");
  }
}

std::string ScenarioKeysMarkdown() {
  std::ostringstream out;
  out << "# Scenario keys\n\n"
      << "Every key of a scenario file, by section, generated from the field tables of the code\n"
      << "(`waam scenario-keys > docs/SCENARIO_KEYS.md`; a test fails when this file differs). Ranges are inclusive;\n"
      << "a default is the value when the key is absent. `--set key.path=value` and a sweep take these key paths.\n";
  for (const SectionKeys& s : ScenarioSections()) {
    out << "\n## " << (s.path.empty() ? "(top level)" : "`" + s.path + "`")
        << (s.variant.empty() ? "" : " (type: " + s.variant + ")") << "\n\n"
        << "| key | type | unit | default | range | meaning |\n| --- | --- | --- | --- | --- | --- |\n";
    for (const FieldInfo& f : s.fields) {
      out << "| `" << f.key << "` | " << NameOf(f.type) << " | " << f.unit << " | " << f.default_text << " | "
          << f.range << " | " << f.doc << " |\n";
    }
  }
  return out.str();
}

void ValidateScenario(const Scenario& s) {
  if (s.part.generator) planner::ResolveGeneratorParams(*s.part.generator, s.part.params, "part.generator");
  CheckFields<planner::SlicingSettings>(planner::kSlicingFields, s.slicing, "slicing");
  // The rules across slicing keys, as the file's reader checks them (planner/scenario/scenario.cc, ParseSlicing).
  if (s.slicing.type == planner::SlicingType::kSkeleton) {
    WAAM_THROW_UNLESS(s.slicing.h_max_mm >= s.slicing.h_min_mm, "slicing.h_max_mm = " << s.slicing.h_max_mm
                                                                 << ": must be >= slicing.h_min_mm = "
                                                                 << s.slicing.h_min_mm);
  }
  if (s.slicing.type == planner::SlicingType::kCone) {
    WAAM_THROW_UNLESS(std::abs(s.slicing.cone_H_mm) >= 1.0,
                      "slicing.H_mm = " << s.slicing.cone_H_mm
                                        << ": |H| must be >= 1 mm (a cylinder is slicing.type: cylinder)");
  }
  CheckFields<planner::PathSettings>(planner::kPathFields, s.path, "path");
  CheckFields<planner::VoidFillingSettings>(planner::kVoidFillingFields, s.path.void_filling, "path.void_filling");
  CheckFields<planner::ProcessSettings>(planner::kProcessFields, s.process, "process");
  planner::ValidateArcAndInterpass(s.process.arc, s.process.interpass);
  twin::ValidateCellSettings(s.cell);
  CheckFields<planner::ProgramSettings>(planner::kProgramFields, s.program, "program");
  CheckFields<planner::ProgramSettings>(planner::kProgramFrameFields, s.program, "program.frame");
  CheckFields<planner::ProgramSettings>(planner::kProgramGcodeFields, s.program, "program.gcode");
  CheckFields<planner::ProgramSettings>(planner::kProgramYaskawaFields, s.program, "program.yaskawa");
  WAAM_THROW_UNLESS(s.program.gcode_arc_on_m != s.program.gcode_arc_off_m,
                    "program.gcode.arc_off_m = " << s.program.gcode_arc_off_m << ": must differ from arc_on_m");
  CheckFields<planner::ProgramFrames>(planner::kProgramFramesFields, s.program.frames, "program.frames");
  twin::ValidateSimulationSettings(s.simulation);
  CheckFields<RunSettings>(kRunFields, s.run, "run");
  WAAM_THROW_UNLESS(s.run.expected_exit_code == 0 || s.run.expected_exit_code == 3,
                    "run.expected_exit_code = " << s.run.expected_exit_code
                                                << ": must be 0 (success) or 3 (check violations)");
  CheckFields<PlaceSettings>(kPlaceFields, s.place, "place");
  CheckPlaceLayouts(s.place, "place");
  ValidateThermalSection(s.thermal);
  CheckFields<ReplaySection>(kReplayFields, s.replay, "replay");
  CheckFields<ReplaySection>(kReplayFrameFields, s.replay, "replay.frame");
  CheckFields<ReplaySection>(kReplayBeadFields, s.replay, "replay.bead");
}

}  // namespace waam::analysis
