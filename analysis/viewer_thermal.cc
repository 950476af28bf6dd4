// The thermal model's temperatures added to a written viewer.html: the metal cells on the part's and the plate's
// surface with their temperature at each layer's end, so the page colours the part by temperature as the torch goes.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>

#include "analysis/thermal_run.h"
#include "analysis/viewer.h"
#include "models/core/error.h"
#include "models/core/files.h"
#include "models/core/json_text.h"

namespace waam::analysis {
namespace fs = std::filesystem;

namespace {

constexpr std::uint8_t kNoMetalLevel = 255;  // a cell with no metal yet at a snapshot

template <class T>
std::string PackArray(const std::vector<T>& values) {
  return internal::Base64(std::string_view(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T)));
}

// Cells of the last field holding metal with a face towards no metal (or the grid's edge): the visible ones.
std::vector<int> ThermalSurfaceCells(const twin::TemperatureField& f) {
  std::vector<int> cells;
  const Eigen::Vector3i n = f.size;
  const auto metal = [&](int i, int j, int k) {
    if (i < 0 || j < 0 || k < 0 || i >= n.x() || j >= n.y() || k >= n.z()) return false;
    return !std::isnan(f.temperature_c[i + n.x() * (j + n.y() * k)]);
  };
  for (int k = 0; k < n.z(); ++k) {
    for (int j = 0; j < n.y(); ++j) {
      for (int i = 0; i < n.x(); ++i) {
        if (!metal(i, j, k)) continue;
        if (metal(i - 1, j, k) && metal(i + 1, j, k) && metal(i, j - 1, k) && metal(i, j + 1, k) &&
            metal(i, j, k - 1) && metal(i, j, k + 1)) {
          continue;
        }
        cells.push_back(i + n.x() * (j + n.y() * k));
      }
    }
  }
  return cells;
}

}  // namespace

std::size_t AddThermalToViewer(const fs::path& page_path, const ThermalRunResult& result, std::size_t max_values) {
  std::string page = ReadFile(page_path);
  const std::string marker = std::string(kViewerThermalMarker);
  const std::size_t at = page.rfind(marker);
  WAAM_THROW_UNLESS(at != std::string::npos,
                    page_path.string() << ": not a viewer.html of this waam, or its temperatures were added already");
  if (result.fields.empty()) return 0;
  const twin::TemperatureField& last = result.fields.back().field;
  const std::vector<int> cells = ThermalSurfaceCells(last);
  // Every k-th layer's field (and the last) when cells x fields would exceed the budget.
  const std::size_t count = result.fields.size();
  const std::size_t stride =
      std::max<std::size_t>(1, (cells.size() * count + max_values - 1) / std::max<std::size_t>(1, max_values));
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < count; i += stride) kept.push_back(i);
  if (kept.back() != count - 1) kept.push_back(count - 1);

  // One colour scale: from the ambient temperature to the hottest kept cell.
  const double low = result.settings.ambient_c;
  double high = low + 1.0;
  for (std::size_t s : kept) {
    for (int c : cells) {
      const float t = result.fields[s].field.temperature_c[c];
      if (!std::isnan(t)) high = std::max(high, static_cast<double>(t));
    }
  }
  // Per cell its centre; per kept field its layer, its time (the thermal timeline's) and each cell's temperature
  // on 0..254 between low and high (255: no metal there yet).
  std::vector<float> centres;
  for (int c : cells) {
    const int i = c % last.size.x(), j = (c / last.size.x()) % last.size.y(), k = c / (last.size.x() * last.size.y());
    const Eigen::Vector3d p = last.origin_mm + last.cell_mm * Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5);
    centres.insert(centres.end(), {float(p.x()), float(p.y()), float(p.z())});
  }
  std::vector<std::uint8_t> levels;
  std::vector<std::int32_t> layers;
  std::vector<float> times;
  for (std::size_t s : kept) {
    const ThermalLayerField& f = result.fields[s];
    layers.push_back(f.layer);
    times.push_back(float(f.time_s));
    for (int c : cells) {
      const float t = f.field.temperature_c[c];
      levels.push_back(std::isnan(t) ? kNoMetalLevel
                                     : std::uint8_t(std::lround(std::clamp((t - low) / (high - low), 0.0, 1.0) * 254)));
    }
  }
  // Each layer's first arc start and last arc end on the thermal timeline, to map it onto the page's clock.
  std::vector<float> layer_start, layer_end;
  for (const ThermalLayer& l : result.layers) {
    layer_start.push_back(float(l.start_s));
    layer_end.push_back(float(l.end_s));
  }
  std::ostringstream note;
  note << "temperatures: " << cells.size() << " surface cells of " << last.cell_mm << " mm at " << kept.size()
       << " layer ends (" << (stride == 1 ? std::string("all") : "1 in " + std::to_string(stride))
       << "), interpolated between them";
  const nlohmann::json document = {{"count", cells.size()},    {"cell_mm", last.cell_mm},
                                   {"snapshots", kept.size()}, {"low_c", low},
                                   {"high_c", high},           {"centres", PackArray(centres)},
                                   {"levels", PackArray(levels)},   {"layer", PackArray(layers)},
                                   {"time_s", PackArray(times)},    {"layer_start_s", PackArray(layer_start)},
                                   {"layer_end_s", PackArray(layer_end)}, {"note", note.str()}};
  page.replace(at, marker.size(),
               "<script type=\"application/json\" id=\"waam-thermal\">" + JsonText(document, -1) + "</script>");
  WriteFileAtomic(page_path, page);
  return cells.size();
}

}  // namespace waam::analysis
