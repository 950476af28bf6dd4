// The whole scenario: the document read once with its overrides, each module's sections parsed from it, and the files
// they name (the part's STL, the fitted models, a tune file) read here, so that the planner and the twin read none.
#include "analysis/scenario.h"

#include <cmath>

#include <nlohmann/json.hpp>

#include "analysis/scenario_keys.h"
#include "models/core/error.h"
#include "models/core/files.h"
#include "models/fit/model_file.h"
#include "planner/program/program_section.h"
#include "planner/scenario/scenario_document.h"
#include "twin/cell/cell_section.h"

namespace waam::analysis {
namespace {

// Applies one "key.path=value" override to the document, creating intermediate maps as needed.
void ApplyOverride(YAML::Node root, const std::string& override_text) {
  const std::size_t eq = override_text.find('=');
  WAAM_THROW_UNLESS(eq != std::string::npos && eq > 0,
                    "--set '" << override_text << "': expected key.path=value, e.g. path.pattern=hybrid");
  const std::string key_path = override_text.substr(0, eq);
  YAML::Node value;
  try {
    value = YAML::Load(override_text.substr(eq + 1));
  } catch (const YAML::Exception& e) {
    WAAM_THROW("--set '" << override_text << "': value is not valid YAML: " << e.msg);
  }
  YAML::Node node;
  node.reset(root);
  std::size_t start = 0;
  while (true) {
    const std::size_t dot = key_path.find('.', start);
    const std::string key = key_path.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    WAAM_THROW_UNLESS(!key.empty(), "--set '" << override_text << "': empty key in '" << key_path << "'");
    WAAM_THROW_UNLESS(node.IsMap() || node.IsNull(),
                      "--set '" << override_text << "': '" << key_path.substr(0, start) << "' is not a section");
    if (dot == std::string::npos) {
      node[key] = value;
      return;
    }
    if (!node[key].IsDefined()) node[key] = YAML::Node(YAML::NodeType::Map);  // an absent optional section
    YAML::Node child = node[key];
    node.reset(child);
    start = dot + 1;
  }
}

// The model at `path`, or the default fitted model `name` when the path is empty.
template <class Model>
std::shared_ptr<const Model> LoadModel(const std::filesystem::path& path, const char* name) {
  return std::make_shared<const Model>(Model::Load(path.empty() ? models::DefaultModelPath(name) : path));
}

// The shifts by junction class of a tune.json of `waam tune-voids`.
void ReadTuneFile(planner::VoidFillingSettings* settings) {
  const std::string& where = settings->where;
  std::string text;
  try {
    text = ReadFile(settings->tune_file);
  } catch (const InputError&) {
    WAAM_THROW(where << ".tune_file: cannot read " << settings->tune_file.string());
  }
  try {
    const nlohmann::json doc = nlohmann::json::parse(text);
    for (const nlohmann::json& j : doc.at("junctions")) {
      settings->shift_by_class_mm[j.at("class").get<std::string>()] = j.at("shift_mm").get<double>();
    }
  } catch (const nlohmann::json::exception& e) {
    WAAM_THROW(where << ".tune_file: " << settings->tune_file.string()
                     << " is not a tune.json of waam tune-voids (junctions[].class, shift_mm): " << e.what());
  }
}

}  // namespace

YamlMap LoadScenarioTop(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  return ScenarioTop(LoadYamlFile(file.string()), file, overrides);
}

YamlMap ScenarioTop(YAML::Node root, const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  for (const std::string& override_text : overrides) ApplyOverride(root, override_text);
  return YamlMap(root, "", file.string());
}

void LoadScenarioFiles(Scenario* scenario) {
  planner::PartSpec& part = scenario->part;
  if (!part.mesh_path.empty()) {
    std::error_code ec;
    WAAM_THROW_UNLESS(std::filesystem::exists(part.mesh_path, ec),
                      part.mesh_where << ": mesh file " << part.mesh_path.string() << " not found");
    WAAM_THROW_UNLESS(!std::filesystem::is_directory(part.mesh_path, ec),
                      part.mesh_where << ": " << part.mesh_path.string() << " is a directory, expected an STL file");
    part.mesh_data = std::make_shared<const std::string>(ReadFile(part.mesh_path));
  }
  planner::ProcessSettings& process = scenario->process;
  process.csw = LoadModel<models::CswModel>(process.csw_model, "csw");
  process.speed_height = LoadModel<models::SpeedHeightModel>(process.speed_height_model, "speed_height");
  process.width_height = LoadModel<models::WidthHeightModel>(process.width_height_model, "width_height");
  planner::VoidFillingSettings& voids = scenario->path.void_filling;
  voids.void_length = models::LoadVoidLengthModel(voids.model.empty() ? models::DefaultModelPath("void_length")
                                                                      : voids.model);
  if (voids.mode == planner::VoidFillingMode::kTuned && voids.shift_by_class_mm.empty()) ReadTuneFile(&voids);
  twin::SimulationSettings& simulation = scenario->simulation;
  simulation.csw = simulation.csw_model == process.csw_model
                       ? process.csw
                       : LoadModel<models::CswModel>(simulation.csw_model, "csw");
}

namespace {

// A JSON value as the YAML node a file with the same content would give: maps, sequences and scalars (numbers in
// JSON's shortest round-trip form; NaN and infinities as YAML's .nan and .inf, which the range checks refuse).
YAML::Node ToYaml(const nlohmann::json& value) {
  switch (value.type()) {
    case nlohmann::json::value_t::object: {
      YAML::Node node(YAML::NodeType::Map);
      for (const auto& [key, child] : value.items()) node[key] = ToYaml(child);
      return node;
    }
    case nlohmann::json::value_t::array: {
      YAML::Node node(YAML::NodeType::Sequence);
      for (const nlohmann::json& child : value) node.push_back(ToYaml(child));
      return node;
    }
    case nlohmann::json::value_t::string:
      return YAML::Node(value.get<std::string>());
    case nlohmann::json::value_t::null:
      return YAML::Node(YAML::NodeType::Null);
    case nlohmann::json::value_t::number_float: {
      const double x = value.get<double>();
      if (std::isnan(x)) return YAML::Node(".nan");
      if (std::isinf(x)) return YAML::Node(x > 0 ? ".inf" : "-.inf");
      return YAML::Node(value.dump());
    }
    default:
      return YAML::Node(value.dump());  // booleans and integers
  }
}

// Every module parses its own sections from the scenario's top-level map.
Scenario ParseScenario(YamlMap& top) {
  Scenario scenario;
  static_cast<planner::PlannerSections&>(scenario) = planner::ParsePlannerSections(top);
  const std::filesystem::path dir = scenario.dir;
  std::error_code ec;
  WAAM_THROW_UNLESS(scenario.base_dir_where.empty() || std::filesystem::is_directory(dir, ec),
                    scenario.base_dir_where << ": folder " << dir.string() << " not found");
  scenario.cell = twin::ParseCellSection(top);
  twin::ParseSimulationSection(top, &scenario.simulation);
  internal::ParseRunSection(top, &scenario.run);
  internal::ParsePlaceSection(top, &scenario.place);
  internal::ParseThermalSection(top, &scenario.thermal);
  internal::ParseReplaySection(top, &scenario.replay);
  scenario.program = planner::ParseProgramSection(top);
  // The CSW radius clamp is one rule for the planner's speed and the twin's bead width (simulation section).
  scenario.process.csw_min_radius_mm = scenario.simulation.csw_min_radius_mm;
  top.CheckNoUnknownKeys();
  CheckNamedFiles(top.named_files());  // the sections name files; the planner's and the twin's parsers open none
  internal::CheckThermalScenario(scenario.process, scenario.thermal);
  internal::LoadThermalMaterials(dir, &scenario.thermal);
  internal::LoadThermalShape(dir, &scenario.thermal);
  LoadScenarioFiles(&scenario);
  // Every scenario handed out meets the tables' limits, the values a preset or the loader filled in as well.
  ValidateScenario(scenario);
  return scenario;
}

}  // namespace

Scenario LoadScenario(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  CheckOverrideKeys(overrides);
  YamlMap top = LoadScenarioTop(file, overrides);
  return ParseScenario(top);
}

Scenario ScenarioFromJson(const nlohmann::json& document, const std::filesystem::path& base_dir,
                          const std::vector<std::string>& overrides) {
  const std::filesystem::path name = base_dir / kScenarioDocumentName;
  WAAM_THROW_UNLESS(document.is_object(), name.string() << ": a scenario is a mapping of sections (name, part, "
                                                           "slicing, ...), got " << document.type_name());
  std::error_code ec;
  WAAM_THROW_UNLESS(std::filesystem::is_directory(base_dir, ec),
                    "base_dir: folder " << base_dir.string() << " not found");
  CheckOverrideKeys(overrides);
  YamlMap top = ScenarioTop(ToYaml(document), name, overrides);
  return ParseScenario(top);
}

}  // namespace waam::analysis
