// Strict reading of YAML maps (scenario sections, settings files): typed fields, ranges, unknown keys refused, errors
// naming file:line and key. Every module's section parser reads through it (models/core/field_table.h on top).
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "models/core/enum_names.h"

namespace waam {

// A file a document names (YamlMap::File), checked by CheckNamedFiles where the document is loaded.
struct NamedFile {
  std::string where;            // "file:line: key.path" of the key that names it
  std::filesystem::path path;   // resolved, normalized
  std::string noun;             // "model file", "URDF file", ... for the message
};

// A YAML mapping at a dotted key path (e.g. "path" or "cell.robot"). Every accessor records the key as known;
// CheckNoUnknownKeys() then refuses any key that was never asked for, naming it.
class YamlMap {
 public:
  // Throws InputError if `node` is not a mapping.
  YamlMap(YAML::Node node, std::string key_path, std::string file);

  bool Has(const std::string& key);
  // Throws InputError "file:line: section: missing required key 'key'" unless the key is present (not null).
  void Require(const std::string& key);
  // Numbers: must parse as a finite number within [min, max] (inclusive); `what` completes "must be ...".
  double Number(const std::string& key, double min, double max);
  double Number(const std::string& key, double min, double max, double fallback);
  int Integer(const std::string& key, int min, int max);
  int Integer(const std::string& key, int min, int max, int fallback);
  bool Bool(const std::string& key, bool fallback);
  std::string String(const std::string& key);
  std::string String(const std::string& key, const std::string& fallback);
  // A name from the table of E (models/core/enum_names.h): required, or `fallback` when the key is absent. An unknown
  // name is an InputError listing the table's names.
  template <typename E>
  E Enum(const std::string& key) {
    return NamedValue<E>(key, String(key));
  }
  template <typename E>
  E Enum(const std::string& key, E fallback) {
    return Has(key) ? NamedValue<E>(key, String(key)) : fallback;
  }
  // A list of numbers of length `size` (any length if size < 0), each within [min, max].
  std::vector<double> Numbers(const std::string& key, int size, double min, double max);
  std::vector<double> Numbers(const std::string& key, int size, double min, double max,
                              const std::vector<double>& fallback);
  // A list of strings (`fallback` when the key is absent).
  std::vector<std::string> Strings(const std::string& key, const std::vector<std::string>& fallback);
  // A file named by a required string key: relative paths are taken from `dir`. Returns the normalized path and
  // records it in named_files() without touching the file system (the section parsers of the planner and the twin
  // open no file): the loader checks them all with CheckNamedFiles.
  std::filesystem::path File(const std::string& key, const std::filesystem::path& dir, const std::string& noun);
  // The folder relative paths are taken from (FileField, PathsField): the one SetBaseDir gave this map or the map it
  // was taken from, else the folder of the file. Set on the top level before its sections are read.
  std::filesystem::path base_dir() const;
  void SetBaseDir(const std::filesystem::path& dir) { *base_dir_ = dir; }
  // True if `key` holds a mapping (a value with two forms: a word or a mapping).
  bool IsMapping(const std::string& key);
  // A nested mapping.
  YamlMap Map(const std::string& key);
  // A list of mappings.
  std::vector<YamlMap> Maps(const std::string& key);
  // The keys of this mapping when the user names them (thermal.probes: {NAME: ...}), in file order. Throws
  // InputError "file:line: key.NAME: a <noun> name must be a non-empty word without '/' or spaces" or "...: a second
  // <noun> of this name". The caller reads each name's value (which makes it known).
  std::vector<std::string> Names(const std::string& noun) const;
  // The keys of this mapping when they are whole numbers (program.frames.uframe: {6: ...}), with their text, in file
  // order. Throws InputError "file:line: key.K: must be a <noun> number in [min, max]" for another key, or "...: a
  // second <noun> N" for a number given twice (6 and 06).
  std::vector<std::pair<int, std::string>> NumberKeys(const std::string& noun, int min, int max) const;
  // True if `key` holds a list (a value with two forms: a number or a list, numbers or a word).
  bool IsList(const std::string& key);

  // The mapping itself.
  const YAML::Node& node() const { return node_; }
  // Throws InputError naming the first key that no accessor asked for.
  void CheckNoUnknownKeys() const;

  // "file:line: key.path" prefix for messages about `key` (or about the map itself when key is empty).
  std::string Where(const std::string& key) const;
  const std::string& file() const { return file_; }
  const std::string& key_path() const { return key_path_; }
  // The files File() returned, from this map and every map taken from it (Map, Maps), in the order asked for.
  const std::vector<NamedFile>& named_files() const { return *files_; }

 private:
  template <typename E>
  E NamedValue(const std::string& key, const std::string& name) const {
    const std::optional<E> value = ParseEnum<E>(name);
    if (!value) ThrowUnknownName(key, name, EnumNameList<E>());
    return *value;
  }
  [[noreturn]] void ThrowUnknownName(const std::string& key, const std::string& name, const std::string& names) const;
  YAML::Node Get(const std::string& key);
  std::string Child(const std::string& key) const;
  YAML::Node node_;
  std::string key_path_;
  std::string file_;
  std::set<std::string> known_;
  std::shared_ptr<std::vector<NamedFile>> files_;  // shared with the maps taken from this one
  std::shared_ptr<std::filesystem::path> base_dir_;  // shared with the maps taken from this one; empty: the file's
};

// Throws InputError "file:line: key: <noun> <path> not found" (or "...: <path> is a directory, expected a file
// (<noun>)") for the first of `files` that is not a regular file.
void CheckNamedFiles(const std::vector<NamedFile>& files);

// Parses a YAML document from a file, throwing InputError with file:line for syntax errors.
YAML::Node LoadYamlFile(const std::string& path);

}  // namespace waam
