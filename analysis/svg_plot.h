// Small inline-SVG x-y plots (markers for measured data, lines for models) for the self-contained bench report.
#pragma once

#include <string>
#include <vector>

namespace waam::analysis {

struct SvgSeries {
  std::string label;           // legend text
  std::vector<double> x, y;    // same length
  std::string colour = "#1f77b4";
  bool line = false;           // true: a polyline (model), false: circle markers (data)
};

// An SVG plot of `series` (width x height px) with axes, ticks, axis titles and a legend; the ranges cover every
// point. Non-finite points are skipped.
std::string SvgPlot(const std::string& title, const std::string& x_label, const std::string& y_label,
                    const std::vector<SvgSeries>& series, int width = 520, int height = 340);

// One bar of an SvgBarChart: its label and value; a non-finite value draws no bar and writes "n/a".
struct SvgBar {
  std::string label;
  double value = 0.0;
  std::string colour = "#1f77b4";
};

// A horizontal bar chart (one row per bar, label left, value at the bar's end) `width` px wide, with an x axis of
// `x_label` from min(0, values) to the largest value; `reference` (if finite) draws a dashed line at that value
// (e.g. 1 for ratios).
std::string SvgBarChart(const std::string& title, const std::string& x_label, const std::vector<SvgBar>& bars,
                        double reference, int width = 640);

// Escapes &, <, >, " for HTML text and attributes.
std::string HtmlEscape(const std::string& text);

}  // namespace waam::analysis
