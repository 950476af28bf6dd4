// RunOutputs: remove a run's partial outputs unless it completed.
#include "models/core/run_outputs.h"

#include <system_error>

namespace waam {
namespace fs = std::filesystem;

void RemoveEarlierSummary(const fs::path& summary) {
  std::error_code ec;
  fs::remove(summary, ec);
}

RunOutputs::RunOutputs(fs::path summary) {
  RemoveEarlierSummary(summary);
  outputs_.push_back(std::move(summary));
}

RunOutputs::~RunOutputs() {
  if (complete_) return;
  // Never throws: a file that cannot be removed stays (its summary is missing, which marks the run incomplete).
  for (const fs::path& path : outputs_) {
    std::error_code ec;
    fs::remove(path, ec);
  }
}

fs::path RunOutputs::Add(fs::path path) {
  outputs_.push_back(path);
  return path;
}

}  // namespace waam
