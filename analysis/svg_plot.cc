// Inline-SVG x-y plots with "nice" axis ticks.
#include "analysis/svg_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

namespace waam::analysis {

namespace {

// Tick spacing of 1, 2 or 5 x 10^k giving about `count` ticks over `span`.
double NiceStep(double span, int count) {
  const double raw = span / std::max(count, 1);
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  const double r = raw / magnitude;
  return magnitude * (r < 1.5 ? 1.0 : r < 3.5 ? 2.0 : r < 7.5 ? 5.0 : 10.0);
}

std::string Num(double v) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g", std::abs(v) < 1e-12 ? 0.0 : v);
  return text;
}

}  // namespace

std::string HtmlEscape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string SvgPlot(const std::string& title, const std::string& x_label, const std::string& y_label,
                    const std::vector<SvgSeries>& series, int width, int height) {
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
  for (const SvgSeries& s : series) {
    for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      x0 = std::min(x0, s.x[i]); x1 = std::max(x1, s.x[i]);
      y0 = std::min(y0, s.y[i]); y1 = std::max(y1, s.y[i]);
    }
  }
  if (!std::isfinite(x0)) { x0 = 0; x1 = 1; y0 = 0; y1 = 1; }
  if (x1 - x0 < 1e-12) { x0 -= 1; x1 += 1; }
  if (y1 - y0 < 1e-12) { y0 -= 1; y1 += 1; }
  const double xs = NiceStep(x1 - x0, 6), ys = NiceStep(y1 - y0, 5);
  x0 = std::floor(x0 / xs) * xs; x1 = std::ceil(x1 / xs) * xs;
  y0 = std::floor(y0 / ys) * ys; y1 = std::ceil(y1 / ys) * ys;
  const double left = 60, right = width - 15, top = 28, bottom = height - 45;
  auto px = [&](double x) { return left + (x - x0) / (x1 - x0) * (right - left); };
  auto py = [&](double y) { return bottom - (y - y0) / (y1 - y0) * (bottom - top); };

  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
      << "\" font-family=\"sans-serif\" font-size=\"11\">\n";
  svg << "<text x=\"" << width / 2 << "\" y=\"16\" text-anchor=\"middle\" font-size=\"13\">" << HtmlEscape(title)
      << "</text>\n";
  svg << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << right - left << "\" height=\"" << bottom - top
      << "\" fill=\"none\" stroke=\"#444\"/>\n";
  for (double x = x0; x <= x1 + xs * 1e-6; x += xs) {
    svg << "<line x1=\"" << px(x) << "\" y1=\"" << top << "\" x2=\"" << px(x) << "\" y2=\"" << bottom
        << "\" stroke=\"#ddd\"/><text x=\"" << px(x) << "\" y=\"" << bottom + 14 << "\" text-anchor=\"middle\">"
        << Num(x) << "</text>\n";
  }
  for (double y = y0; y <= y1 + ys * 1e-6; y += ys) {
    svg << "<line x1=\"" << left << "\" y1=\"" << py(y) << "\" x2=\"" << right << "\" y2=\"" << py(y)
        << "\" stroke=\"#ddd\"/><text x=\"" << left - 5 << "\" y=\"" << py(y) + 4 << "\" text-anchor=\"end\">"
        << Num(y) << "</text>\n";
  }
  svg << "<text x=\"" << (left + right) / 2 << "\" y=\"" << height - 8 << "\" text-anchor=\"middle\">"
      << HtmlEscape(x_label) << "</text>\n";
  svg << "<text transform=\"translate(14," << (top + bottom) / 2 << ") rotate(-90)\" text-anchor=\"middle\">"
      << HtmlEscape(y_label) << "</text>\n";
  int legend_row = 0;
  for (const SvgSeries& s : series) {
    if (s.line) {
      svg << "<polyline fill=\"none\" stroke=\"" << s.colour << "\" stroke-width=\"1.5\" points=\"";
      for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
        if (std::isfinite(s.x[i]) && std::isfinite(s.y[i])) svg << px(s.x[i]) << "," << py(s.y[i]) << " ";
      }
      svg << "\"/>\n";
    } else {
      for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
        if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
        svg << "<circle cx=\"" << px(s.x[i]) << "\" cy=\"" << py(s.y[i]) << "\" r=\"3\" fill=\"" << s.colour
            << "\" fill-opacity=\"0.75\"/>";
      }
      svg << "\n";
    }
    const double ly = top + 12 + 14 * legend_row++;
    svg << "<rect x=\"" << left + 8 << "\" y=\"" << ly - 8 << "\" width=\"10\" height=\"" << (s.line ? 2 : 8)
        << "\" fill=\"" << s.colour << "\"/><text x=\"" << left + 22 << "\" y=\"" << ly << "\">"
        << HtmlEscape(s.label) << "</text>\n";
  }
  svg << "</svg>\n";
  return svg.str();
}

std::string SvgBarChart(const std::string& title, const std::string& x_label, const std::vector<SvgBar>& bars,
                        double reference, int width) {
  double x0 = 0.0, x1 = std::isfinite(reference) ? reference : 0.0;
  std::size_t longest = 1;
  for (const SvgBar& b : bars) {
    if (std::isfinite(b.value)) {
      x0 = std::min(x0, b.value);
      x1 = std::max(x1, b.value);
    }
    longest = std::max(longest, b.label.size());
  }
  if (x1 - x0 < 1e-12) x1 = x0 + 1.0;
  const double xs = NiceStep(x1 - x0, 6);
  x0 = std::floor(x0 / xs) * xs;
  x1 = std::ceil(x1 / xs) * xs;
  const double row = 16, top = 28;
  const double left = std::min(6.2 * static_cast<double>(longest) + 12.0, 0.45 * width), right = width - 50.0;
  const double bottom = top + row * static_cast<double>(bars.size()) + 4;
  const int height = static_cast<int>(bottom) + 40;
  auto px = [&](double x) { return left + (x - x0) / (x1 - x0) * (right - left); };
  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
      << "\" font-family=\"sans-serif\" font-size=\"11\">\n";
  svg << "<text x=\"" << width / 2 << "\" y=\"16\" text-anchor=\"middle\" font-size=\"13\">" << HtmlEscape(title)
      << "</text>\n";
  for (double x = x0; x <= x1 + xs * 1e-6; x += xs) {
    svg << "<line x1=\"" << px(x) << "\" y1=\"" << top << "\" x2=\"" << px(x) << "\" y2=\"" << bottom
        << "\" stroke=\"#ddd\"/><text x=\"" << px(x) << "\" y=\"" << bottom + 14 << "\" text-anchor=\"middle\">"
        << Num(x) << "</text>\n";
  }
  svg << "<text x=\"" << (left + right) / 2 << "\" y=\"" << height - 8 << "\" text-anchor=\"middle\">"
      << HtmlEscape(x_label) << "</text>\n";
  for (std::size_t i = 0; i < bars.size(); ++i) {
    const SvgBar& b = bars[i];
    const double y = top + row * static_cast<double>(i);
    svg << "<text x=\"" << left - 5 << "\" y=\"" << y + 11 << "\" text-anchor=\"end\">" << HtmlEscape(b.label)
        << "</text>";
    if (std::isfinite(b.value)) {
      const double a = px(std::min(0.0, b.value)), e = px(std::max(0.0, b.value));
      svg << "<rect x=\"" << a << "\" y=\"" << y + 2 << "\" width=\"" << std::max(e - a, 0.5) << "\" height=\""
          << row - 4 << "\" fill=\"" << b.colour << "\"/><text x=\"" << e + 4 << "\" y=\"" << y + 11 << "\">"
          << Num(b.value) << "</text>\n";
    } else {
      svg << "<text x=\"" << px(0.0) + 4 << "\" y=\"" << y + 11 << "\" fill=\"#888\">n/a</text>\n";
    }
  }
  if (std::isfinite(reference)) {
    svg << "<line x1=\"" << px(reference) << "\" y1=\"" << top << "\" x2=\"" << px(reference) << "\" y2=\"" << bottom
        << "\" stroke=\"#444\" stroke-dasharray=\"4,3\"/>\n";
  }
  svg << "<line x1=\"" << left << "\" y1=\"" << top << "\" x2=\"" << left << "\" y2=\"" << bottom
      << "\" stroke=\"#444\"/>\n</svg>\n";
  return svg.str();
}

}  // namespace waam::analysis
