// `waam bench --merge`: the shards of one bench (run on several machines) put back together as one bench.
#include <algorithm>
#include <chrono>
#include <map>

#include "analysis/bench_command.h"
#include "models/core/error.h"
#include "models/core/files.h"
#include "models/core/json_text.h"
#include "models/core/output_lock.h"

namespace waam::analysis {
namespace fs = std::filesystem;

namespace {

// Puts the folder `from` at `to`: hard links where the file system allows, copies otherwise.
void LinkOrCopyTree(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  fs::remove_all(to, ec);
  fs::copy(from, to, fs::copy_options::recursive | fs::copy_options::create_hard_links, ec);
  if (ec) {
    fs::remove_all(to, ec);
    fs::copy(from, to, fs::copy_options::recursive, ec);
    WAAM_THROW_UNLESS(!ec, "cannot copy " << from.string() << " to " << to.string() << ": " << ec.message());
  }
}

bool SameFolder(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  return fs::exists(a, ec) && fs::exists(b, ec) && fs::equivalent(a, b, ec);
}

// One bench folder given to --merge and its bench.json.
struct Part {
  fs::path dir;
  nlohmann::json bench;
};

// A scenario entry of a bench.json and the folder holding its results.
using Entries = std::vector<std::pair<nlohmann::json, fs::path>>;

// Reads the bench.json of each folder; throws InputError for one that waam bench did not write.
std::vector<Part> ReadParts(const std::vector<fs::path>& dirs) {
  std::vector<Part> parts;
  for (const fs::path& dir : dirs) {
    const fs::path file = dir / "bench.json";
    const nlohmann::json bench = nlohmann::json::parse(ReadFile(file), nullptr, false);
    WAAM_THROW_UNLESS(!bench.is_discarded() && bench.is_object() && bench.contains("scenarios") &&
                          bench["scenarios"].is_array(),
                      file.string() << ": not a bench.json written by waam bench");
    parts.push_back({dir, bench});
  }
  return parts;
}

// The shards ordered by index; throws InputError for a part that is not a shard of the same bench as the first,
// a shard given twice or missing.
std::vector<const Part*> ShardsByIndex(const std::vector<Part>& parts) {
  const nlohmann::json& first = parts.front().bench["shard"];
  const int count = first.value("count", 0);
  const std::size_t total = first.value("runs_total", std::size_t{0});
  std::vector<const Part*> by_index(static_cast<std::size_t>(std::max(count, 0)), nullptr);
  for (const Part& part : parts) {
    WAAM_THROW_UNLESS(part.bench.contains("shard"), (part.dir / "bench.json").string()
                                                        << ": not a shard, but " << (parts.front().dir / "bench.json").string()
                                                        << " is; merge the shards of one bench");
    const nlohmann::json& shard = part.bench["shard"];
    const int index = shard.value("index", -1);
    WAAM_THROW_UNLESS(shard.value("count", 0) == count && shard.value("runs_total", std::size_t{0}) == total &&
                          index >= 0 && index < count,
                      (part.dir / "bench.json").string() << ": shard " << index << "/" << shard.value("count", 0)
                                                         << " of " << shard.value("runs_total", std::size_t{0})
                                                         << " runs is not of the same bench as shard 0.."
                                                         << count - 1 << " of " << total << " runs");
    WAAM_THROW_UNLESS(by_index[index] == nullptr, "shard " << index << "/" << count << " given twice: "
                                                           << by_index[index]->dir.string() << " and "
                                                           << part.dir.string());
    WAAM_THROW_UNLESS(part.bench.value("sweep", nlohmann::json()) == parts.front().bench.value("sweep", nlohmann::json()),
                      part.dir.string() << " and " << parts.front().dir.string() << " hold different sweeps");
    by_index[index] = &part;
  }
  for (int k = 0; k < count; ++k) {
    WAAM_THROW_UNLESS(by_index[k] != nullptr, "shard " << k << "/" << count << " missing from --merge");
  }
  return by_index;
}

// The shards' entries in the order of one run: run i is entry i / count of shard i % count.
Entries ShardEntries(const std::vector<Part>& parts) {
  const std::vector<const Part*> by_index = ShardsByIndex(parts);
  const std::size_t count = by_index.size();
  const std::size_t total = parts.front().bench["shard"].value("runs_total", std::size_t{0});
  Entries entries;
  for (std::size_t i = 0; i < total; ++i) {
    const Part& part = *by_index[i % count];
    const std::size_t m = i / count;
    WAAM_THROW_UNLESS(m < part.bench["scenarios"].size(),
                      (part.dir / "bench.json").string() << ": shard holds " << part.bench["scenarios"].size()
                                                         << " scenarios, fewer than its share of " << total);
    entries.emplace_back(part.bench["scenarios"][m], part.dir);
  }
  return entries;
}

// The entries of unsharded benches, one after the other; throws InputError for a shard among them.
Entries ConcatenatedEntries(const std::vector<Part>& parts) {
  Entries entries;
  for (const Part& part : parts) {
    WAAM_THROW_UNLESS(!part.bench.contains("shard"), (part.dir / "bench.json").string()
                                                         << ": a shard, but " << (parts.front().dir / "bench.json").string()
                                                         << " is not; merge the shards of one bench");
    for (const nlohmann::json& e : part.bench["scenarios"]) entries.emplace_back(e, part.dir);
  }
  return entries;
}

// Throws InputError for an entry without a usable folder name as id, or an id in two entries.
void CheckUniqueIds(const Entries& entries) {
  std::map<std::string, fs::path> seen;
  for (const auto& [entry, dir] : entries) {
    const std::string id = entry.value("id", "");
    WAAM_THROW_UNLESS(!id.empty() && id.find('/') == std::string::npos && id != "." && id != "..",
                      (dir / "bench.json").string() << ": scenario entry without a usable id");
    const auto [it, fresh] = seen.emplace(id, dir);
    WAAM_THROW_UNLESS(fresh, "scenario '" << id << "' is in both " << it->second.string() << " and " << dir.string());
  }
}

}  // namespace

nlohmann::json MergeBench(const std::vector<fs::path>& dirs, const fs::path& out_dir) {
  WAAM_THROW_UNLESS(!dirs.empty(), "--merge needs at least one bench folder");
  const auto start = std::chrono::steady_clock::now();
  const std::vector<Part> parts = ReadParts(dirs);
  // Shards go back in the order of one run; unsharded benches are concatenated.
  Entries entries = parts.front().bench.contains("shard") ? ShardEntries(parts) : ConcatenatedEntries(parts);
  CheckUniqueIds(entries);

  ClaimOutputDirectory(out_dir);
  nlohmann::json scenarios = nlohmann::json::array();
  nlohmann::json counts = {{"pass", 0}, {"expected_fail", 0}, {"fail", 0}, {"total", entries.size()}};
  double wall_s = 0.0;
  std::size_t reused = 0;
  for (auto& [entry, dir] : entries) {
    const std::string id = entry["id"];
    std::error_code ec;
    if (!SameFolder(dir, out_dir) && fs::is_directory(dir / id, ec)) LinkOrCopyTree(dir / id, out_dir / id);
    const std::string outcome = entry.value("outcome", "fail");
    if (counts.contains(outcome)) counts[outcome] = counts[outcome].get<int>() + 1;
    if (entry.contains("timing") && entry["timing"].is_object()) wall_s += entry["timing"].value("wall_s", 0.0);
    scenarios.push_back(std::move(entry));
  }
  for (const Part& part : parts) reused += part.bench.value("timing", nlohmann::json::object()).value("reused_results", 0);
  nlohmann::json merged_from = nlohmann::json::array();
  for (const fs::path& dir : dirs) merged_from.push_back(dir.generic_string());
  nlohmann::json bench = {
      {"scenarios", scenarios},
      {"counts", counts},
      {"reference", ReferenceComparison(scenarios)},
      {"merged_from", merged_from},
      {"timing",
       {{"total_s", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()},
        {"scenarios_wall_s", wall_s},
        {"reused_results", reused},
        {"hardware_threads", parts.front().bench.value("timing", nlohmann::json::object()).value("hardware_threads", 0)},
        {"perf", parts.front().bench.value("timing", nlohmann::json::object()).value("perf", nlohmann::json::array())}}},
  };
  const nlohmann::json sweep = parts.front().bench.value("sweep", nlohmann::json());
  if (!sweep.is_null()) bench["sweep"] = sweep;
  WriteFileAtomic(out_dir / "bench.json", JsonText(bench) + "\n");
  WriteBenchReport(bench, out_dir);
  return bench;
}

}  // namespace waam::analysis
