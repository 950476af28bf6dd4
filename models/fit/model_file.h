// Reading and writing model JSON files, typed access to their fields, and where the default models live.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace waam::models {

// Version of the model file layout written by every model's ToJson().
inline constexpr int kModelFormatVersion = 1;

// The path of the default fitted model `name` ("csw", "speed_height", "width_height", "void_length") in the
// source tree's models/data folder. Does not check that the file exists.
std::filesystem::path DefaultModelPath(const std::string& name);

// Parses the model file `path` and checks its "model" field equals `expected_model`. Throws InputError naming the
// file if it is missing, not JSON, or holds another model.
nlohmann::json ReadModelJson(const std::filesystem::path& path, std::string_view expected_model);

// Writes `model` pretty-printed to `path` atomically.
void WriteModelJson(const std::filesystem::path& path, const nlohmann::json& model);

// The number at `key` (a JSON pointer such as "/params/m"). Throws InputError "<where>: <key> is missing or not a
// number" otherwise.
double JsonNumber(const nlohmann::json& j, const std::string& key, const std::string& where);

}  // namespace waam::models
