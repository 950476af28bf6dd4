// place_margin.png: the coarse pass's margin over the plane of the first two searched variables.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "analysis/png_file.h"
#include "analysis/place_command.h"
#include "models/core/files.h"

namespace waam::analysis {
namespace fs = std::filesystem;

namespace {

std::string Fixed(double v, int digits) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.*f", digits, v);
  return buf;
}

// Green from pale (margin 0) to dark (margin 1) for a passing layout; red, darker with more violating samples.
cv::Scalar CellColour(const LayoutScore& s) {
  if (s.violating_samples == 0) {
    const double m = std::clamp(s.margin, 0.0, 1.0);
    return cv::Scalar(200 - 140 * m, 235 - 75 * m, 200 - 140 * m);  // BGR
  }
  const double f = std::clamp(std::log10(static_cast<double>(s.violating_samples)) / 4.0, 0.0, 1.0);
  return cv::Scalar(200 - 170 * f, 200 - 170 * f, 255 - 55 * f);
}

// Grey diagonal hatching over `r`: a cell whose best coarse check was stopped early (its figure is a bound).
void Hatch(cv::Mat& img, const cv::Rect& r) {
  const int step = std::max(6, r.width / 6);
  for (int d = step; d < r.width + r.height; d += step) {
    const cv::Point a(r.x + std::max(0, d - r.height), r.y + std::min(d, r.height));
    const cv::Point b(r.x + std::min(d, r.width), r.y + std::max(0, d - r.width));
    cv::line(img, a, b, cv::Scalar(110, 110, 110), 1, cv::LINE_AA);
  }
}

}  // namespace

void WritePlaceMarginPng(const PlaceResult& result, const fs::path& path) {
  // The axes: the first two searched variables (one or none searched: a strip or a single cell).
  std::vector<int> axes;
  for (int v = 0; v < kPlaceVars && axes.size() < 2; ++v) {
    if (result.values[v].size() > 1) axes.push_back(v);
  }
  const int vx = axes.empty() ? -1 : axes[0];
  const int vy = axes.size() < 2 ? -1 : axes[1];
  const std::size_t nx = vx < 0 ? 1 : result.values[vx].size();
  const std::size_t ny = vy < 0 ? 1 : result.values[vy].size();
  const auto index_of = [&](int v, double value) {
    if (v < 0) return std::size_t{0};
    const std::vector<double>& values = result.values[v];
    return static_cast<std::size_t>(std::find(values.begin(), values.end(), value) - values.begin());
  };
  // Per cell the best layout over the other variables, by the coarse pass.
  std::vector<int> cell_best(nx * ny, -1);
  for (std::size_t i = 0; i < result.layouts.size(); ++i) {
    const std::size_t c = index_of(vy, vy < 0 ? 0.0 : result.layouts[i][vy]) * nx +
                          index_of(vx, vx < 0 ? 0.0 : result.layouts[i][vx]);
    if (cell_best[c] < 0 || BetterLayout(result.coarse[i], result.coarse[cell_best[c]])) cell_best[c] = static_cast<int>(i);
  }

  const int cell = static_cast<int>(std::clamp<std::size_t>(720 / std::max(nx, ny), 12, 90));
  const int left = 110, top = 90, bottom = 110;
  const int width = std::max(720, left + cell * static_cast<int>(nx) + 40);
  const int height = top + cell * static_cast<int>(ny) + bottom;
  cv::Mat img(height, width, CV_8UC3, cv::Scalar(255, 255, 255));
  const auto text = [&](const std::string& s, int x, int y, double scale, const cv::Scalar& colour) {
    cv::putText(img, s, {x, y}, cv::FONT_HERSHEY_SIMPLEX, scale, colour, 1, cv::LINE_AA);
  };
  text(std::string("waam place: ") + (result.feasible ? "feasible" : "no layout passes") +
           " - best margin per cell over the other variables (coarse pass)",
       10, 25, 0.55, cv::Scalar(0, 0, 0));
  text("green: passes (darker = larger margin, 1 = 10 deg / 10 mm); red: violating samples; circle: the answer",
       10, 50, 0.45, cv::Scalar(60, 60, 60));
  if (result.coarse_bounded > 0) {
    text("hatched: pruned early (a bound: margin <= / violating samples >= the figure)", 10, 68, 0.45,
         cv::Scalar(60, 60, 60));
  }
  const Layout& best = result.layouts[result.best];
  for (std::size_t iy = 0; iy < ny; ++iy) {
    for (std::size_t ix = 0; ix < nx; ++ix) {
      const int b = cell_best[iy * nx + ix];
      const cv::Rect r(left + static_cast<int>(ix) * cell, top + static_cast<int>(ny - 1 - iy) * cell, cell, cell);
      if (b < 0) continue;
      const LayoutScore& s = result.coarse[b];
      cv::rectangle(img, r, CellColour(s), cv::FILLED);
      if (s.bounded) Hatch(img, r);
      cv::rectangle(img, r, cv::Scalar(255, 255, 255), 1);
      if (cell >= 40) {
        std::string label = s.violating_samples == 0 ? Fixed(s.margin, 2) : std::to_string(s.violating_samples);
        if (s.bounded) label = (s.violating_samples == 0 ? "<=" : ">=") + label;
        text(label, r.x + 4, r.y + cell / 2 + 5, 0.4, cv::Scalar(0, 0, 0));
      }
      const bool is_best = (vx < 0 || result.layouts[b][vx] == best[vx]) && (vy < 0 || result.layouts[b][vy] == best[vy]);
      if (is_best) cv::circle(img, {r.x + cell / 2, r.y + cell / 2}, cell / 3, cv::Scalar(0, 0, 0), 2, cv::LINE_AA);
    }
  }
  // Axis labels: every value when they fit, else every k-th.
  const int every_x = std::max(1, 60 / cell);
  for (std::size_t ix = 0; ix < nx; ix += every_x) {
    if (vx < 0) break;
    text(Fixed(result.values[vx][ix], 0), left + static_cast<int>(ix) * cell + 2, top + static_cast<int>(ny) * cell + 18,
         0.4, cv::Scalar(0, 0, 0));
  }
  const int every_y = std::max(1, 20 / cell);
  for (std::size_t iy = 0; iy < ny; iy += every_y) {
    if (vy < 0) break;
    text(Fixed(result.values[vy][iy], 0), left - 50, top + static_cast<int>(ny - 1 - iy) * cell + cell / 2 + 5, 0.4,
         cv::Scalar(0, 0, 0));
  }
  text(vx < 0 ? "(nothing searched)" : PlaceVariableName(vx), left, top + static_cast<int>(ny) * cell + 45, 0.5,
       cv::Scalar(0, 0, 0));
  if (vy >= 0) text(PlaceVariableName(vy), 10, top - 8, 0.5, cv::Scalar(0, 0, 0));
  std::string answer = "answer:";
  for (int v = 0; v < kPlaceVars; ++v) {
    if (result.values[v].size() > 1) answer += std::string(" ") + PlaceVariableName(v) + "=" + Fixed(best[v], 0);
  }
  answer += "  margin " + Fixed(result.best_score.margin, 2) + (result.feasible ? "" : ", still violating");
  text(answer, 10, height - 25, 0.5, cv::Scalar(0, 0, 0));

  internal::WritePngAtomic(img, path);
}

}  // namespace waam::analysis
