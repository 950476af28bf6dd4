// Pictures of `waam thermal`: interpass temperature and waits per layer, probe histories, and a temperature map of
// a vertical section at each layer's end.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include <opencv2/imgproc.hpp>

#include "analysis/thermal_command.h"
#include "analysis/png_file.h"
#include "analysis/thermal_plot.h"

namespace waam::analysis {
namespace {

using internal::PlotFrame;
using internal::PutLabel;

std::string Printf(const char* format, double a, double b = 0.0, double c = 0.0) {
  char text[200];
  std::snprintf(text, sizeof(text), format, a, b, c);
  return text;
}

// [lo, hi] of the finite values, padded by 5 % (and at least 1) so lines do not sit on the frame.
std::pair<double, double> PaddedRange(const std::vector<double>& values, double floor_lo) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const double v : values) {
    if (!std::isfinite(v)) continue;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  if (!std::isfinite(lo)) lo = hi = floor_lo;
  const double pad = std::max(1.0, 0.05 * (hi - lo));
  return {std::max(floor_lo, lo - pad), hi + pad};
}

// Line colours (BGR) for the series of a plot.
cv::Scalar SeriesColour(std::size_t i) {
  static const cv::Scalar colours[] = {{180, 119, 31}, {14, 127, 255}, {44, 160, 44}, {40, 39, 214},
                                       {189, 103, 148}, {75, 86, 140},  {194, 119, 227}, {34, 189, 188}};
  return colours[i % 8];
}

}  // namespace

void WriteInterpassPng(const ThermalRunResult& result, const planner::InterpassSettings& interpass,
                       const std::string& part_name, const std::filesystem::path& path) {
  cv::Mat image(760, 1000, CV_8UC3, cv::Scalar(255, 255, 255));
  const int layers = static_cast<int>(result.layers.size());
  std::vector<double> temps, waits;
  for (const ThermalLayer& l : result.layers) {
    temps.push_back(l.interpass_c);
    waits.push_back(l.wait_s);
  }
  if (interpass.HasMax()) temps.push_back(interpass.max_c);
  const auto [t_lo, t_hi] = PaddedRange(temps, -273.0);
  const double w_hi = std::max(1.0, 1.1 * *std::max_element(waits.begin(), waits.end()));
  // Layers by their index (0 = the first), as in thermal.json.
  const PlotFrame top{cv::Rect(90, 70, 860, 260), -0.5, layers - 0.5, t_lo, t_hi};
  const PlotFrame bottom{cv::Rect(90, 420, 860, 260), -0.5, layers - 0.5, 0.0, w_hi};
  PutLabel(image, part_name + ": interpass temperature and interpass wait per layer", {90, 28}, 0.7);
  top.DrawAxes(image, "layer (0 = the first)", "interpass temperature [degC] (" +
                                   std::string(interpass.at == planner::InterpassAt::kProbe ? "probe " + interpass.probe
                                                                                            : NameOf(interpass.at)) +
                                   ", before the layer's first arc start)");
  bottom.DrawAxes(image, "layer (0 = the first)", "interpass wait before the layer [s]");
  if (interpass.HasMax()) {
    const cv::Point a = top.Px(-0.5, interpass.max_c), b = top.Px(layers - 0.5, interpass.max_c);
    for (int x = a.x; x < b.x; x += 12) cv::line(image, {x, a.y}, {std::min(x + 6, b.x), a.y}, {0, 0, 220}, 2);
    PutLabel(image, Printf("max_c = %.0f degC", interpass.max_c), {b.x - 150, a.y - 6}, 0.5, {0, 0, 220});
  }
  cv::Point previous(-1, -1);
  for (int i = 0; i < layers; ++i) {
    const ThermalLayer& l = result.layers[i];
    if (std::isfinite(l.interpass_c)) {
      const cv::Point p = top.Px(i, l.interpass_c);
      if (previous.x >= 0) cv::line(image, previous, p, SeriesColour(0), 2, cv::LINE_AA);
      cv::circle(image, p, 4, l.interpass_reached ? SeriesColour(0) : cv::Scalar(0, 0, 220), cv::FILLED, cv::LINE_AA);
      previous = p;
    }
    const double half = 0.4;
    cv::rectangle(image, bottom.Px(i - half, 0.0), bottom.Px(i + half, l.wait_s), SeriesColour(1),
                  cv::FILLED);
  }
  internal::WritePngAtomic(image, path);
}

void WriteProbesPng(const ThermalRunResult& result, const planner::InterpassSettings& interpass,
                    const std::string& part_name, const std::filesystem::path& path) {
  cv::Mat image(620, 1100, CV_8UC3, cv::Scalar(255, 255, 255));
  std::vector<double> all;
  for (const ThermalProbeHistory& probe : result.probes) all.insert(all.end(), probe.temperature_c.begin(),
                                                                    probe.temperature_c.end());
  if (all.empty()) all.push_back(result.settings.ambient_c);
  const auto [lo, hi] = PaddedRange(all, -273.0);
  const double t_end = std::max(1.0, result.sample_time_s.empty() ? 1.0 : result.sample_time_s.back());
  const PlotFrame frame{cv::Rect(90, 70, 800, 460), 0.0, t_end, lo, hi};
  PutLabel(image, part_name + ": probe temperatures (grey lines: layer starts)", {90, 28}, 0.7);
  for (const ThermalLayer& l : result.layers) {
    const cv::Point a = frame.Px(l.start_s, lo), b = frame.Px(l.start_s, hi);
    cv::line(image, a, b, cv::Scalar(215, 215, 215), 1);
  }
  frame.DrawAxes(image, "time from the program's start [s]", "temperature [degC]");
  if (interpass.HasMax() && interpass.max_c < hi) {
    const cv::Point a = frame.Px(0.0, interpass.max_c), b = frame.Px(t_end, interpass.max_c);
    for (int x = a.x; x < b.x; x += 12) cv::line(image, {x, a.y}, {std::min(x + 6, b.x), a.y}, {0, 0, 220}, 1);
  }
  for (std::size_t p = 0; p < result.probes.size(); ++p) {
    const ThermalProbeHistory& probe = result.probes[p];
    std::vector<cv::Point> line;
    auto flush = [&] {
      if (line.size() > 1) cv::polylines(image, line, false, SeriesColour(p), 2, cv::LINE_AA);
      line.clear();
    };
    for (std::size_t i = 0; i < probe.temperature_c.size(); ++i) {
      if (!std::isfinite(probe.temperature_c[i])) {
        flush();
        continue;
      }
      line.push_back(frame.Px(result.sample_time_s[i], probe.temperature_c[i]));
    }
    flush();
    const int y = 90 + 26 * static_cast<int>(p);
    cv::line(image, {905, y - 5}, {935, y - 5}, SeriesColour(p), 3);
    PutLabel(image, probe.name, {942, y});
    PutLabel(image, Printf("(%.0f, %.0f, %.0f) mm", probe.p_mm.x(), probe.p_mm.y(), probe.p_mm.z()), {942, y + 13},
             0.35, {90, 90, 90});
  }
  if (interpass.HasMax()) {
    const int y = 90 + 26 * static_cast<int>(result.probes.size());
    cv::line(image, {905, y - 5}, {935, y - 5}, {0, 0, 220}, 1);
    PutLabel(image, "interpass max_c", {942, y}, 0.45);
    PutLabel(image, Printf("%.0f degC", interpass.max_c), {942, y + 13}, 0.35, {90, 90, 90});
  }
  internal::WritePngAtomic(image, path);
}

void WriteTemperatureMapPng(const ThermalLayerField& layer_field, const Eigen::AlignedBox3d& deposit_box_mm,
                            double lo_c, double hi_c, const std::string& part_name,
                            const std::filesystem::path& path) {
  const twin::TemperatureField& f = layer_field.field;
  const int nx = std::max(1, f.size.x()), ny = std::max(1, f.size.y()), nz = std::max(1, f.size.z());
  // The section along the part's longer horizontal side, through the middle of the other.
  const Eigen::Vector3d extent = deposit_box_mm.sizes();
  const int along = extent.x() >= extent.y() ? 0 : 1;
  const int across = 1 - along;
  const double at_mm = deposit_box_mm.center()[across];
  const int index = std::clamp(static_cast<int>(std::floor((at_mm - f.origin_mm[across]) / std::max(1e-9, f.cell_mm))),
                               0, (across == 0 ? nx : ny) - 1);
  const int columns = along == 0 ? nx : ny;
  const double scale = std::clamp(820.0 / columns, 1.0, 40.0);
  const int width = static_cast<int>(std::lround(columns * scale));
  const int height = std::max(1, static_cast<int>(std::lround(nz * scale)));
  cv::Mat image(height + 150, width + 210, CV_8UC3, cv::Scalar(255, 255, 255));
  const cv::Rect area(90, 60, width, height);
  const int cmap = cv::COLORMAP_INFERNO;
  for (int k = 0; k < nz; ++k) {
    for (int a = 0; a < columns; ++a) {
      const int i = along == 0 ? a : index, j = along == 0 ? index : a;
      const std::size_t n = (static_cast<std::size_t>(k) * ny + j) * nx + i;
      const float t = n < f.temperature_c.size() ? f.temperature_c[n] : std::numeric_limits<float>::quiet_NaN();
      const cv::Vec3b colour = std::isnan(t) ? cv::Vec3b(235, 235, 235) : internal::MapColour(cmap, t, lo_c, hi_c);
      const cv::Point p0(area.x + static_cast<int>(std::lround(a * scale)),
                         area.y + height - static_cast<int>(std::lround((k + 1) * scale)));
      const cv::Point p1(area.x + static_cast<int>(std::lround((a + 1) * scale)) - 1,
                         area.y + height - static_cast<int>(std::lround(k * scale)) - 1);
      cv::rectangle(image, p0, p1, cv::Scalar(colour[0], colour[1], colour[2]), cv::FILLED);
    }
  }
  const double a0 = f.origin_mm[along], z0 = f.origin_mm.z();
  PlotFrame frame{area, a0, a0 + columns * f.cell_mm, z0, z0 + nz * f.cell_mm};
  frame.grid = false;
  const char* names[] = {"x", "y"};
  frame.DrawAxes(image, std::string(names[along]) + " [mm]", "z [mm]");
  internal::DrawColourBar(image, cv::Rect(area.x + width + 40, area.y, 22, std::max(60, height)), cmap, lo_c, hi_c,
                          "T [degC]");
  PutLabel(image,
           part_name + Printf(": temperature at the end of layer %.0f (t = %.1f s), section ", layer_field.layer,
                  layer_field.time_s) + names[across] + Printf(" = %.1f mm (grey: no metal)", at_mm),
           {10, 28}, 0.5);
  internal::WritePngAtomic(image, path);
}

}  // namespace waam::analysis
