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

// The picture's grid: the first two searched variables vx, vy (-1: one or none searched, a strip or a single cell),
// nx x ny cells, per cell the best layout over the other variables by the coarse pass (-1: none).
struct MarginGrid {
  int vx = -1, vy = -1;
  std::size_t nx = 1, ny = 1;
  std::vector<int> cell_best;
};

MarginGrid BestPerCell(const PlaceResult& result) {
  MarginGrid g;
  std::vector<int> axes;
  for (int v = 0; v < kPlaceVars && axes.size() < 2; ++v) {
    if (result.values[v].size() > 1) axes.push_back(v);
  }
  g.vx = axes.empty() ? -1 : axes[0];
  g.vy = axes.size() < 2 ? -1 : axes[1];
  g.nx = g.vx < 0 ? 1 : result.values[g.vx].size();
  g.ny = g.vy < 0 ? 1 : result.values[g.vy].size();
  const auto index_of = [&](int v, double value) {
    if (v < 0) return std::size_t{0};
    const std::vector<double>& values = result.values[v];
    return static_cast<std::size_t>(std::find(values.begin(), values.end(), value) - values.begin());
  };
  g.cell_best.assign(g.nx * g.ny, -1);
  for (std::size_t i = 0; i < result.layouts.size(); ++i) {
    const std::size_t c = index_of(g.vy, g.vy < 0 ? 0.0 : result.layouts[i][g.vy]) * g.nx +
                          index_of(g.vx, g.vx < 0 ? 0.0 : result.layouts[i][g.vx]);
    int& best = g.cell_best[c];
    if (best < 0 || BetterLayout(result.coarse[i], result.coarse[best])) best = static_cast<int>(i);
  }
  return g;
}

// The image and where the grid sits in it: cells `cell` px square, the first column at `left`, the top row at `top`.
struct MarginCanvas {
  cv::Mat img;
  int cell = 0, left = 110, top = 90;
  void Text(const std::string& s, int x, int y, double scale, const cv::Scalar& colour) {
    cv::putText(img, s, {x, y}, cv::FONT_HERSHEY_SIMPLEX, scale, colour, 1, cv::LINE_AA);
  }
};

// Each cell: its colour, hatching when pruned early, its figure when it fits, a circle on the answer's cell.
void DrawCells(const PlaceResult& result, const MarginGrid& g, MarginCanvas& canvas) {
  const Layout& best = result.layouts[result.best];
  const int cell = canvas.cell;
  for (std::size_t iy = 0; iy < g.ny; ++iy) {
    for (std::size_t ix = 0; ix < g.nx; ++ix) {
      const int b = g.cell_best[iy * g.nx + ix];
      const cv::Rect r(canvas.left + static_cast<int>(ix) * cell, canvas.top + static_cast<int>(g.ny - 1 - iy) * cell,
                       cell, cell);
      if (b < 0) continue;
      const LayoutScore& s = result.coarse[b];
      cv::rectangle(canvas.img, r, CellColour(s), cv::FILLED);
      if (s.bounded) Hatch(canvas.img, r);
      cv::rectangle(canvas.img, r, cv::Scalar(255, 255, 255), 1);
      if (cell >= 40) {
        std::string label = s.violating_samples == 0 ? Fixed(s.margin, 2) : std::to_string(s.violating_samples);
        if (s.bounded) label = (s.violating_samples == 0 ? "<=" : ">=") + label;
        canvas.Text(label, r.x + 4, r.y + cell / 2 + 5, 0.4, cv::Scalar(0, 0, 0));
      }
      const bool is_best =
          (g.vx < 0 || result.layouts[b][g.vx] == best[g.vx]) && (g.vy < 0 || result.layouts[b][g.vy] == best[g.vy]);
      if (is_best) {
        cv::circle(canvas.img, {r.x + cell / 2, r.y + cell / 2}, cell / 3, cv::Scalar(0, 0, 0), 2, cv::LINE_AA);
      }
    }
  }
}

// Axis labels (every value when they fit, else every k-th) and the axes' names.
void DrawAxes(const PlaceResult& result, const MarginGrid& g, MarginCanvas& canvas) {
  const int cell = canvas.cell, left = canvas.left, top = canvas.top;
  const int ny = static_cast<int>(g.ny);
  const int every_x = std::max(1, 60 / cell);
  for (std::size_t ix = 0; ix < g.nx; ix += every_x) {
    if (g.vx < 0) break;
    canvas.Text(Fixed(result.values[g.vx][ix], 0), left + static_cast<int>(ix) * cell + 2, top + ny * cell + 18, 0.4,
                cv::Scalar(0, 0, 0));
  }
  const int every_y = std::max(1, 20 / cell);
  for (std::size_t iy = 0; iy < g.ny; iy += every_y) {
    if (g.vy < 0) break;
    canvas.Text(Fixed(result.values[g.vy][iy], 0), left - 50, top + (ny - 1 - static_cast<int>(iy)) * cell + cell / 2 + 5,
                0.4, cv::Scalar(0, 0, 0));
  }
  canvas.Text(g.vx < 0 ? "(nothing searched)" : PlaceVariableName(g.vx), left, top + ny * cell + 45, 0.5,
              cv::Scalar(0, 0, 0));
  if (g.vy >= 0) canvas.Text(PlaceVariableName(g.vy), 10, top - 8, 0.5, cv::Scalar(0, 0, 0));
}

// The answer's line: the searched variables' values and its margin.
std::string AnswerLine(const PlaceResult& result) {
  const Layout& best = result.layouts[result.best];
  std::string answer = "answer:";
  for (int v = 0; v < kPlaceVars; ++v) {
    if (result.values[v].size() > 1) answer += std::string(" ") + PlaceVariableName(v) + "=" + Fixed(best[v], 0);
  }
  answer += "  margin " + Fixed(result.best_score.margin, 2) + (result.feasible ? "" : ", still violating");
  return answer;
}

}  // namespace

void WritePlaceMarginPng(const PlaceResult& result, const fs::path& path) {
  const MarginGrid g = BestPerCell(result);
  MarginCanvas canvas;
  canvas.cell = static_cast<int>(std::clamp<std::size_t>(720 / std::max(g.nx, g.ny), 12, 90));
  const int bottom = 110;
  const int width = std::max(720, canvas.left + canvas.cell * static_cast<int>(g.nx) + 40);
  const int height = canvas.top + canvas.cell * static_cast<int>(g.ny) + bottom;
  canvas.img = cv::Mat(height, width, CV_8UC3, cv::Scalar(255, 255, 255));
  canvas.Text(std::string("waam place: ") + (result.feasible ? "feasible" : "no layout passes") +
                  " - best margin per cell over the other variables (coarse pass)",
              10, 25, 0.55, cv::Scalar(0, 0, 0));
  canvas.Text("green: passes (darker = larger margin, 1 = 10 deg / 10 mm); red: violating samples; circle: the answer",
              10, 50, 0.45, cv::Scalar(60, 60, 60));
  if (result.coarse_bounded > 0) {
    canvas.Text("hatched: pruned early (a bound: margin <= / violating samples >= the figure)", 10, 68, 0.45,
                cv::Scalar(60, 60, 60));
  }
  DrawCells(result, g, canvas);
  DrawAxes(result, g, canvas);
  canvas.Text(AnswerLine(result), 10, height - 25, 0.5, cv::Scalar(0, 0, 0));
  internal::WritePngAtomic(canvas.img, path);
}

}  // namespace waam::analysis
