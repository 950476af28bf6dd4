// Strict, typed reading of scenario YAML with messages that name file, line and key.
#include "models/core/yaml_map.h"

#include <algorithm>
#include <exception>
#include <cmath>
#include <sstream>
#include <system_error>

#include "models/core/error.h"
#include "models/core/files.h"

namespace waam {

YamlMap::YamlMap(YAML::Node node, std::string key_path, std::string file)
    : node_(std::move(node)),
      key_path_(std::move(key_path)),
      file_(std::move(file)),
      files_(std::make_shared<std::vector<NamedFile>>()),
      base_dir_(std::make_shared<std::filesystem::path>()) {
  WAAM_THROW_UNLESS(node_.IsMap(), Where("") << ": must be a mapping of keys to values");
}

std::string YamlMap::Child(const std::string& key) const {
  return key_path_.empty() ? key : key_path_ + "." + key;
}

std::string YamlMap::Where(const std::string& key) const {
  std::ostringstream out;
  out << file_;
  YAML::Mark mark = node_.Mark();
  if (!key.empty() && node_.IsMap() && node_[key]) mark = node_[key].Mark();
  if (mark.line >= 0) out << ":" << mark.line + 1;
  const std::string path = key.empty() ? key_path_ : Child(key);
  out << ": " << (path.empty() ? "(top level)" : path);
  return out.str();
}

YAML::Node YamlMap::Get(const std::string& key) {
  known_.insert(key);
  return node_[key];
}

bool YamlMap::Has(const std::string& key) {
  known_.insert(key);
  return static_cast<bool>(node_[key]) && !node_[key].IsNull();
}

void YamlMap::Require(const std::string& key) {
  WAAM_THROW_UNLESS(Has(key), Where("") << ": missing required key '" << key << "'");
}

double YamlMap::Number(const std::string& key, double min, double max) {
  YAML::Node value = Get(key);
  WAAM_THROW_UNLESS(value && !value.IsNull(), Where("") << ": missing required key '" << key << "'");
  WAAM_THROW_UNLESS(value.IsScalar(), Where(key) << ": must be a number");
  double number = 0.0;
  try {
    number = value.as<double>();
  } catch (const YAML::Exception&) {
    WAAM_THROW(Where(key) << " = '" << value.Scalar() << "': must be a number");
  }
  WAAM_THROW_UNLESS(std::isfinite(number), Where(key) << " = " << value.Scalar() << ": must be finite");
  WAAM_THROW_UNLESS(number >= min && number <= max,
                    Where(key) << " = " << number << ": must be in [" << min << ", " << max << "]");
  return number;
}

double YamlMap::Number(const std::string& key, double min, double max, double fallback) {
  return Has(key) ? Number(key, min, max) : fallback;
}

int YamlMap::Integer(const std::string& key, int min, int max) {
  const double number = Number(key, min, max);
  WAAM_THROW_UNLESS(number == std::floor(number), Where(key) << " = " << number << ": must be a whole number");
  return static_cast<int>(number);
}

int YamlMap::Integer(const std::string& key, int min, int max, int fallback) {
  return Has(key) ? Integer(key, min, max) : fallback;
}

bool YamlMap::Bool(const std::string& key, bool fallback) {
  if (!Has(key)) return fallback;
  YAML::Node value = Get(key);
  try {
    return value.as<bool>();
  } catch (const YAML::Exception&) {
    WAAM_THROW(Where(key) << " = '" << (value.IsScalar() ? value.Scalar() : "?") << "': must be true or false");
  }
}

std::string YamlMap::String(const std::string& key) {
  YAML::Node value = Get(key);
  WAAM_THROW_UNLESS(value && !value.IsNull(), Where("") << ": missing required key '" << key << "'");
  WAAM_THROW_UNLESS(value.IsScalar(), Where(key) << ": must be a string");
  return value.Scalar();
}

std::string YamlMap::String(const std::string& key, const std::string& fallback) {
  return Has(key) ? String(key) : fallback;
}

void YamlMap::ThrowUnknownName(const std::string& key, const std::string& name, const std::string& names) const {
  WAAM_THROW(Where(key) << " = '" << name << "': unknown value, expected one of " << names);
}

std::vector<double> YamlMap::Numbers(const std::string& key, int size, double min, double max) {
  YAML::Node value = Get(key);
  WAAM_THROW_UNLESS(value && !value.IsNull(), Where("") << ": missing required key '" << key << "'");
  WAAM_THROW_UNLESS(value.IsSequence(), Where(key) << ": must be a list of numbers");
  WAAM_THROW_UNLESS(size < 0 || static_cast<int>(value.size()) == size,
                    Where(key) << ": must have " << size << " numbers, has " << value.size());
  std::vector<double> numbers;
  for (std::size_t i = 0; i < value.size(); ++i) {
    double number = 0.0;
    try {
      number = value[i].as<double>();
    } catch (const YAML::Exception&) {
      WAAM_THROW(Where(key) << "[" << i << "]: must be a number");
    }
    WAAM_THROW_UNLESS(std::isfinite(number) && number >= min && number <= max,
                      Where(key) << "[" << i << "] = " << number << ": must be in [" << min << ", " << max << "]");
    numbers.push_back(number);
  }
  return numbers;
}

std::vector<double> YamlMap::Numbers(const std::string& key, int size, double min, double max,
                                     const std::vector<double>& fallback) {
  return Has(key) ? Numbers(key, size, min, max) : fallback;
}

std::vector<std::string> YamlMap::Strings(const std::string& key, const std::vector<std::string>& fallback) {
  if (!Has(key)) return fallback;
  YAML::Node value = Get(key);
  WAAM_THROW_UNLESS(value.IsSequence(), Where(key) << ": must be a list of strings, e.g. [plan, simulate]");
  std::vector<std::string> strings;
  for (std::size_t i = 0; i < value.size(); ++i) {
    WAAM_THROW_UNLESS(value[i].IsScalar(), Where(key) << "[" << i << "]: must be a string");
    strings.push_back(value[i].Scalar());
  }
  return strings;
}

std::filesystem::path YamlMap::File(const std::string& key, const std::filesystem::path& dir,
                                    const std::string& noun) {
  std::filesystem::path file = String(key);
  if (file.is_relative()) file = dir / file;
  files_->push_back({Where(key), file, noun});
  return file.lexically_normal();
}

std::filesystem::path YamlMap::base_dir() const {
  if (!base_dir_->empty()) return *base_dir_;
  std::error_code ec;
  return std::filesystem::absolute(file_, ec).lexically_normal().parent_path();
}

bool YamlMap::IsMapping(const std::string& key) {
  return Has(key) && node_[key].IsMap();
}

void CheckNamedFiles(const std::vector<NamedFile>& files) {
  for (const NamedFile& f : files) {
    std::error_code ec;
    WAAM_THROW_UNLESS(!std::filesystem::is_directory(f.path, ec),
                      f.where << ": " << f.path.string() << " is a directory, expected a file (" << f.noun << ")");
    WAAM_THROW_UNLESS(std::filesystem::is_regular_file(f.path, ec),
                      f.where << ": " << f.noun << " " << f.path.string() << " not found");
  }
}

YamlMap YamlMap::Map(const std::string& key) {
  YAML::Node value = Get(key);
  WAAM_THROW_UNLESS(value && !value.IsNull(), Where("") << ": missing required section '" << key << "'");
  YamlMap child(value, Child(key), file_);
  child.files_ = files_;
  child.base_dir_ = base_dir_;
  return child;
}

std::vector<YamlMap> YamlMap::Maps(const std::string& key) {
  YAML::Node value = Get(key);
  WAAM_THROW_UNLESS(value && value.IsSequence(), Where(key) << ": must be a list");
  std::vector<YamlMap> maps;
  for (std::size_t i = 0; i < value.size(); ++i) {
    maps.emplace_back(value[i], Child(key) + "[" + std::to_string(i) + "]", file_);
    maps.back().files_ = files_;
    maps.back().base_dir_ = base_dir_;
  }
  return maps;
}

std::vector<std::string> YamlMap::Names(const std::string& noun) const {
  std::vector<std::string> names;
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    const std::string name = it->first.Scalar();
    WAAM_THROW_UNLESS(!name.empty() && name.find_first_of("/ \t") == std::string::npos,
                      Where(name) << ": a " << noun << " name must be a non-empty word without '/' or spaces");
    WAAM_THROW_UNLESS(std::find(names.begin(), names.end(), name) == names.end(),
                      Where(name) << ": a second " << noun << " of this name");
    names.push_back(name);
  }
  return names;
}

std::vector<std::pair<int, std::string>> YamlMap::NumberKeys(const std::string& noun, int min, int max) const {
  std::vector<std::pair<int, std::string>> keys;
  for (const std::string& name : Names(noun)) {
    int n = min - 1;
    try {
      std::size_t used = 0;
      n = std::stoi(name, &used);
      if (used != name.size()) n = min - 1;
    } catch (const std::exception&) {
      n = min - 1;
    }
    WAAM_THROW_UNLESS(n >= min && n <= max, Where(name) << ": must be a " << noun << " number in [" << min << ", "
                                                        << max << "]");
    for (const auto& [m, other] : keys) {
      WAAM_THROW_UNLESS(m != n, Where(name) << ": a second " << noun << " " << n << " (also given as '" << other << "')");
    }
    keys.emplace_back(n, name);
  }
  return keys;
}

bool YamlMap::IsList(const std::string& key) {
  YAML::Node value = Get(key);
  return value && value.IsSequence();
}

void YamlMap::CheckNoUnknownKeys() const {
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    const std::string key = it->first.Scalar();
    if (!known_.count(key)) {
      std::ostringstream out;
      out << file_;
      if (it->first.Mark().line >= 0) out << ":" << it->first.Mark().line + 1;
      out << ": " << Child(key) << ": unknown key";
      if (!known_.empty()) {
        out << " (known here:";
        for (const std::string& k : known_) out << " " << k;
        out << ")";
      }
      throw InputError(out.str());
    }
  }
}

YAML::Node LoadYamlFile(const std::string& path) {
  const std::string text = ReadFile(path);
  try {
    return YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    WAAM_THROW(path << ":" << e.mark.line + 1 << ":" << e.mark.column + 1 << ": YAML syntax error: " << e.msg);
  }
}

}  // namespace waam
