// The sweep file reader and its expansion into bench runs.
#include "analysis/sweep.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>

#include "models/core/error.h"
#include "models/core/files.h"

namespace waam::analysis {
namespace fs = std::filesystem;

namespace {

// "file:line" of a node.
std::string SweepWhere(const fs::path& file, const YAML::Node& node) {
  return file.string() + ":" + std::to_string(node.Mark().line + 1);
}

// A value as the YAML text a --set override takes: a scalar as written, a list in flow style.
std::string SweepValueText(const YAML::Node& node) {
  if (node.IsScalar()) return node.Scalar();
  YAML::Emitter out;
  out << YAML::Flow << node;
  return out.c_str();
}

bool IsKeyPath(const std::string& key) {
  if (key.empty() || key.front() == '.' || key.back() == '.' || key.find("..") != std::string::npos) return false;
  return std::all_of(key.begin(), key.end(),
                     [](unsigned char c) { return std::isalnum(c) || c == '_' || c == '.'; });
}

// A swept or set value: a scalar or a list of scalars (a vector setting such as part.generator.size_mm).
void CheckSweepValue(const fs::path& file, const std::string& key, const YAML::Node& value) {
  bool ok = value.IsScalar();
  if (value.IsSequence()) {
    ok = value.size() > 0;
    for (const YAML::Node& item : value) ok = ok && item.IsScalar();
  }
  WAAM_THROW_UNLESS(ok, SweepWhere(file, value) << ": " << key
                                                << ": a value must be a number, a name or a list of numbers");
}

std::string SweepKey(const fs::path& file, const YAML::Node& key_node, const char* section) {
  WAAM_THROW_UNLESS(key_node.IsScalar() && IsKeyPath(key_node.Scalar()),
                    SweepWhere(file, key_node) << ": " << section << ": key '"
                                               << (key_node.IsScalar() ? key_node.Scalar() : std::string("?"))
                                               << "' is not a setting's key path (e.g. path.bead_width_mm)");
  return key_node.Scalar();
}

// The id of run `index` of `count`: the zero-padded index, then the values, reduced to file-name characters.
std::string SweepRunId(std::size_t index, std::size_t count, const SweepRun& run) {
  std::string id = std::to_string(index);
  const std::size_t width = std::max<std::size_t>(3, std::to_string(count - 1).size());
  id.insert(0, width - id.size(), '0');
  for (const auto& [key, value] : run.values) {
    std::string part;
    for (unsigned char c : value.substr(0, 24)) part += (std::isalnum(c) || c == '.' || c == '_') ? char(c) : '_';
    id += "-" + part;
    if (id.size() > 96) break;
  }
  return id;
}

// Reads the sweep's `set:` mapping (key.path: value, the same for every run) into sweep->set.
void ParseSweepSet(const fs::path& file, const YAML::Node& key_node, const YAML::Node& value, Sweep* sweep) {
  WAAM_THROW_UNLESS(value.IsMap(), SweepWhere(file, key_node) << ": set: must be a mapping of key.path: value");
  for (const auto& kv : value) {
    const std::string k = SweepKey(file, kv.first, "set");
    CheckSweepValue(file, k, kv.second);
    sweep->set.push_back(k + "=" + SweepValueText(kv.second));
  }
}

// Reads the sweep's `grid:` mapping (key.path: [values]) into sweep->keys and one run per combination.
void ParseSweepGrid(const fs::path& file, const YAML::Node& key_node, const YAML::Node& value, Sweep* sweep) {
  WAAM_THROW_UNLESS(value.IsMap() && value.size() > 0,
                    SweepWhere(file, key_node) << ": grid: must be a mapping of key.path: [values]");
  std::vector<std::vector<std::string>> axes;
  std::size_t count = 1;
  for (const auto& kv : value) {
    const std::string k = SweepKey(file, kv.first, "grid");
    WAAM_THROW_UNLESS(kv.second.IsSequence() && kv.second.size() > 0,
                      SweepWhere(file, kv.first) << ": grid: " << k << ": must be a non-empty list of values");
    WAAM_THROW_UNLESS(std::find(sweep->keys.begin(), sweep->keys.end(), k) == sweep->keys.end(),
                      SweepWhere(file, kv.first) << ": grid: " << k << ": key given twice");
    std::vector<std::string> values;
    for (const YAML::Node& v : kv.second) {
      CheckSweepValue(file, k, v);
      values.push_back(SweepValueText(v));
    }
    count *= values.size();
    WAAM_THROW_UNLESS(count <= kMaxSweepRuns, SweepWhere(file, key_node) << ": grid: more than " << kMaxSweepRuns
                                                                         << " runs; split the sweep");
    sweep->keys.push_back(k);
    axes.push_back(std::move(values));
  }
  // Every combination, the last key varying fastest.
  for (std::size_t r = 0; r < count; ++r) {
    SweepRun run;
    std::size_t rest = r;
    std::vector<std::pair<std::string, std::string>> values(axes.size());
    for (std::size_t a = axes.size(); a-- > 0;) {
      values[a] = {sweep->keys[a], axes[a][rest % axes[a].size()]};
      rest /= axes[a].size();
    }
    run.values = std::move(values);
    sweep->runs.push_back(std::move(run));
  }
}

// Reads the sweep's `list:` of runs (each a mapping of key.path: value) into sweep->keys and sweep->runs.
void ParseSweepList(const fs::path& file, const YAML::Node& key_node, const YAML::Node& value, Sweep* sweep) {
  WAAM_THROW_UNLESS(value.IsSequence() && value.size() > 0,
                    SweepWhere(file, key_node) << ": list: must be a non-empty list of mappings");
  WAAM_THROW_UNLESS(value.size() <= kMaxSweepRuns,
                    SweepWhere(file, key_node) << ": list: more than " << kMaxSweepRuns << " runs; split the sweep");
  for (const YAML::Node& entry : value) {
    WAAM_THROW_UNLESS(entry.IsMap() && entry.size() > 0,
                      SweepWhere(file, entry) << ": list: each run must be a mapping of key.path: value");
    SweepRun run;
    for (const auto& kv : entry) {
      const std::string k = SweepKey(file, kv.first, "list");
      CheckSweepValue(file, k, kv.second);
      for (const auto& [other, unused] : run.values) {
        WAAM_THROW_UNLESS(other != k, SweepWhere(file, kv.first) << ": list: " << k << ": key given twice");
      }
      run.values.emplace_back(k, SweepValueText(kv.second));
      if (std::find(sweep->keys.begin(), sweep->keys.end(), k) == sweep->keys.end()) sweep->keys.push_back(k);
    }
    sweep->runs.push_back(std::move(run));
  }
}

// Reads the sweep's `metrics:` list of step.metric names into sweep->metrics.
void ParseSweepMetrics(const fs::path& file, const YAML::Node& key_node, const YAML::Node& value, Sweep* sweep) {
  WAAM_THROW_UNLESS(value.IsSequence(), SweepWhere(file, key_node) << ": metrics: must be a list of step.metric");
  for (const YAML::Node& m : value) {
    const std::string name = m.IsScalar() ? m.Scalar() : "";
    const std::size_t dot = name.find('.');
    WAAM_THROW_UNLESS(dot != std::string::npos && dot > 0 && dot + 1 < name.size(),
                      SweepWhere(file, m) << ": metrics: '" << name
                                          << "' is not step.metric (e.g. simulate.deviation/rms_mm)");
    sweep->metrics.push_back(name);
  }
}

}  // namespace

Sweep ParseSweep(const std::string& text, const fs::path& file) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    WAAM_THROW(file.string() << ":" << e.mark.line + 1 << ": YAML syntax error: " << e.msg);
  } catch (const YAML::Exception& e) {
    WAAM_THROW(file.string() << ":" << e.mark.line + 1 << ": YAML error: " << e.msg);
  }
  WAAM_THROW_UNLESS(root.IsMap(), file.string() << ":1: a sweep file is a mapping with base, grid or list, "
                                                    "and optionally name, set and metrics");
  Sweep sweep;
  sweep.file = file;
  sweep.name = file.stem().string();
  bool has_grid = false, has_list = false;
  std::vector<std::string> seen;
  for (const auto& item : root) {
    const YAML::Node& key_node = item.first;
    const YAML::Node& value = item.second;
    const std::string key = key_node.IsScalar() ? key_node.Scalar() : "?";
    WAAM_THROW_UNLESS(std::find(seen.begin(), seen.end(), key) == seen.end(),
                      SweepWhere(file, key_node) << ": " << key << ": key given twice");
    seen.push_back(key);
    if (key == "base" || key == "name") {
      WAAM_THROW_UNLESS(value.IsScalar() && !value.Scalar().empty(),
                        SweepWhere(file, key_node) << ": " << key << ": must be a non-empty string");
      if (key == "name") {
        sweep.name = value.Scalar();
      } else {
        sweep.base = (file.parent_path() / value.Scalar()).lexically_normal();
      }
    } else if (key == "set") {
      ParseSweepSet(file, key_node, value, &sweep);
    } else if (key == "grid") {
      has_grid = true;
      ParseSweepGrid(file, key_node, value, &sweep);
    } else if (key == "list") {
      has_list = true;
      ParseSweepList(file, key_node, value, &sweep);
    } else if (key == "metrics") {
      ParseSweepMetrics(file, key_node, value, &sweep);
    } else {
      WAAM_THROW(SweepWhere(file, key_node) << ": unknown key '" << key
                                            << "' (a sweep has base, name, set, grid or list, metrics)");
    }
  }
  WAAM_THROW_UNLESS(!sweep.base.empty(), file.string() << ":1: base: missing (the scenario file the runs start from)");
  WAAM_THROW_UNLESS(has_grid != has_list, file.string() << ":1: a sweep has exactly one of grid and list");
  if (sweep.metrics.empty()) {
    sweep.metrics = {"plan.layers", "plan.weld_length_mm", "check.violation_count", "simulate.volume_error_pct",
                     "simulate.deviation/rms_mm"};
  }
  for (std::size_t i = 0; i < sweep.runs.size(); ++i) sweep.runs[i].id = SweepRunId(i, sweep.runs.size(), sweep.runs[i]);
  return sweep;
}

Sweep ReadSweep(const fs::path& file) {
  Sweep sweep = ParseSweep(ReadFile(file), file);
  std::error_code ec;
  WAAM_THROW_UNLESS(fs::is_regular_file(sweep.base, ec),
                    file.string() << ": base: scenario file " << sweep.base.string() << " not found");
  return sweep;
}

std::vector<BenchRun> SweepBenchRuns(const Sweep& sweep) {
  std::vector<BenchRun> runs;
  for (const SweepRun& r : sweep.runs) {
    BenchRun run{sweep.base, r.id, {}};
    for (const auto& [key, value] : r.values) run.overrides.push_back(key + "=" + value);
    runs.push_back(std::move(run));
  }
  return runs;
}

nlohmann::json SweepJson(const Sweep& sweep) {
  nlohmann::json runs = nlohmann::json::array();
  for (const SweepRun& r : sweep.runs) {
    nlohmann::json values = nlohmann::json::object();
    for (const auto& [key, value] : r.values) values[key] = value;
    runs.push_back({{"id", r.id}, {"values", values}});
  }
  return {{"name", sweep.name},        {"file", sweep.file.generic_string()}, {"base", sweep.base.generic_string()},
          {"set", sweep.set},          {"keys", sweep.keys},                  {"metrics", sweep.metrics},
          {"runs", runs}};
}

nlohmann::json RunSweep(const Sweep& sweep, BenchOptions options) {
  std::vector<std::string> overrides = sweep.set;
  overrides.insert(overrides.end(), options.overrides.begin(), options.overrides.end());
  options.overrides = std::move(overrides);
  options.scenarios.clear();
  options.runs = SweepBenchRuns(sweep);
  options.sweep = SweepJson(sweep);
  return RunBench(options);
}

}  // namespace waam::analysis
