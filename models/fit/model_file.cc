// Model JSON files: checked reading, atomic writing, the default model folder.
#include "models/fit/model_file.h"

#include "models/core/data_dir.h"
#include "models/core/error.h"
#include "models/core/files.h"
#include "models/core/json_text.h"


namespace waam::models {

std::filesystem::path DefaultModelPath(const std::string& name) {
  return DataDir() / "models" / "data" / (name + ".json");
}

nlohmann::json ReadModelJson(const std::filesystem::path& path, std::string_view expected_model) {
  const std::string text = ReadFile(path);
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    WAAM_THROW(path.string() << ": not valid JSON: " << e.what());
  }
  WAAM_THROW_UNLESS(j.is_object() && j.contains("model") && j["model"].is_string(),
                    path.string() << ": not a waam model file (no \"model\" field)");
  const std::string model = j["model"].get<std::string>();
  WAAM_THROW_UNLESS(model == expected_model,
                    path.string() << ": holds a '" << model << "' model, expected '" << expected_model << "'");
  const int version = j.value("format_version", 0);
  WAAM_THROW_UNLESS(version == kModelFormatVersion, path.string() << ": format_version " << version
                                                                  << " is not supported (expected "
                                                                  << kModelFormatVersion << ")");
  return j;
}

void WriteModelJson(const std::filesystem::path& path, const nlohmann::json& model) {
  WriteFileAtomic(path, JsonText(model) + "\n");
}

double JsonNumber(const nlohmann::json& j, const std::string& key, const std::string& where) {
  const nlohmann::json::json_pointer pointer(key);
  WAAM_THROW_UNLESS(j.contains(pointer) && j.at(pointer).is_number(),
                    where << ": " << key << " is missing or not a number");
  return j.at(pointer).get<double>();
}

}  // namespace waam::models
