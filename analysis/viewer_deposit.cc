// The deposited part of `waam simulate` added to a written viewer.html: the twin's voxels coarsened to a budget of
// cells, each with its layer and the time metal first reached it, so the page grows the part as the torch goes.
#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdint>
#include <sstream>
#include <unordered_map>

#include "analysis/viewer.h"
#include "models/core/error.h"
#include "models/core/files.h"
#include "models/core/json_text.h"

namespace waam::analysis {
namespace fs = std::filesystem;

namespace {

struct Cell {
  float time_s = 0.0f;  // earliest deposition time of its voxels (the twin's clock), s
  int layer = 0;        // layer of that voxel
};

std::uint64_t Key(std::int64_t x, std::int64_t y, std::int64_t z) {
  constexpr std::int64_t kOffset = 1 << 20;  // coarse indices within +-2^20 (a 2 km part at 1 mm voxels)
  return (std::uint64_t(x + kOffset) << 42) | (std::uint64_t(y + kOffset) << 21) | std::uint64_t(z + kOffset);
}

std::int64_t FloorDiv(std::int64_t a, std::int64_t b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

// The occupied voxels merged into cells of `merge`^3 voxels.
std::unordered_map<std::uint64_t, Cell> Coarsen(const twin::Depositor& depositor, int merge) {
  std::unordered_map<std::uint64_t, Cell> cells;
  depositor.grid().ForEach([&](const twin::VoxelIndex& v, const twin::VoxelData& data) {
    const std::uint64_t key = Key(FloorDiv(v.x(), merge), FloorDiv(v.y(), merge), FloorDiv(v.z(), merge));
    auto [it, added] = cells.try_emplace(key, Cell{data.time_s, 0});
    if (added || data.time_s < it->second.time_s) it->second = Cell{data.time_s, depositor.LayerOf(data)};
  });
  return cells;
}

}  // namespace

std::size_t AddDepositToViewer(const fs::path& page_path, const twin::Depositor& depositor,
                               const twin::DeviationReport* deviation, std::size_t max_cells) {
  std::string page = ReadFile(page_path);
  const std::string marker = std::string(kViewerDepositMarker);
  const std::size_t at = page.rfind(marker);  // after the inlined data and libraries, before viewer.js
  WAAM_THROW_UNLESS(at != std::string::npos,
                    page_path.string() << ": not a viewer.html of this waam, or its deposit was added already");

  // The smallest merge factor that fits the budget (the cell count falls about as merge^3).
  int merge = 1;
  std::unordered_map<std::uint64_t, Cell> cells = Coarsen(depositor, merge);
  while (cells.size() > std::max<std::size_t>(1, max_cells) && merge < 64) cells = Coarsen(depositor, ++merge);

  // Cells in deposition order (ties by key, so the page does not depend on the hash map's order).
  std::vector<std::pair<std::uint64_t, Cell>> sorted(cells.begin(), cells.end());
  std::sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) {
    return a.second.time_s != b.second.time_s ? a.second.time_s < b.second.time_s : a.first < b.first;
  });
  const double size_mm = depositor.grid().voxel_mm() * merge;
  std::vector<float> centres, times;
  std::vector<std::int32_t> layers;
  constexpr std::int64_t kOffset = 1 << 20, kMask = (1 << 21) - 1;
  for (const auto& [key, cell] : sorted) {
    const std::int64_t x = std::int64_t(key >> 42 & kMask) - kOffset, y = std::int64_t(key >> 21 & kMask) - kOffset,
                       z = std::int64_t(key & kMask) - kOffset;
    centres.insert(centres.end(), {float((x + 0.5) * size_mm), float((y + 0.5) * size_mm), float((z + 0.5) * size_mm)});
    times.push_back(cell.time_s);
    layers.push_back(cell.layer);
  }
  // Each cube's deviation: the exposed face of largest |deviation| among its voxels (NaN: no exposed face).
  std::vector<float> cube_deviation;
  if (deviation && !deviation->points.empty()) {
    std::unordered_map<std::uint64_t, float> worst;
    const double voxel = depositor.grid().voxel_mm();
    for (const twin::SurfaceSample& s : deviation->points) {
      const twin::VoxelIndex v = depositor.grid().IndexOf(s.p_P - 0.5 * voxel * s.face.cast<double>());
      const std::uint64_t key = Key(FloorDiv(v.x(), merge), FloorDiv(v.y(), merge), FloorDiv(v.z(), merge));
      auto [it, added] = worst.try_emplace(key, float(s.deviation_mm));
      if (!added && std::abs(s.deviation_mm) > std::abs(it->second)) it->second = float(s.deviation_mm);
    }
    for (const auto& [key, cell] : sorted) {
      const auto it = worst.find(key);
      cube_deviation.push_back(it == worst.end() ? std::numeric_limits<float>::quiet_NaN() : it->second);
    }
  }
  std::ostringstream note;
  note << "deposited part: " << sorted.size() << " cells of " << size_mm << " mm (" << depositor.grid().occupied()
       << " voxels of " << depositor.grid().voxel_mm() << " mm merged " << merge << "^3)";
  const nlohmann::json data = {{"count", sorted.size()},
                               {"cell_mm", size_mm},
                               {"centres", internal::Base64(std::string_view(
                                               reinterpret_cast<const char*>(centres.data()), centres.size() * 4))},
                               {"time_s", internal::Base64(std::string_view(
                                              reinterpret_cast<const char*>(times.data()), times.size() * 4))},
                               {"layer", internal::Base64(std::string_view(
                                             reinterpret_cast<const char*>(layers.data()), layers.size() * 4))},
                               {"note", note.str()}};
  nlohmann::json document = data;
  if (!cube_deviation.empty()) {
    document["deviation_mm"] = internal::Base64(std::string_view(reinterpret_cast<const char*>(cube_deviation.data()),
                                                                 cube_deviation.size() * 4));
    document["deviation_rms_mm"] = deviation->rms_mm;
  }
  // (Numbers, base64 and the note: no "</" that could end the script early.)
  page.replace(at, marker.size(),
               "<script type=\"application/json\" id=\"waam-deposit\">" + JsonText(document, -1) + "</script>");
  WriteFileAtomic(page_path, page);
  return sorted.size();
}

}  // namespace waam::analysis
