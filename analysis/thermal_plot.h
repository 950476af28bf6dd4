// Plot frames for the thermal pictures (internal to the analysis module's .cc files; exposes OpenCV): axes with
// ticks in units, a colour bar, a title, and atomic PNG writing.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace waam::analysis::internal {

// Round tick values covering [lo, hi] with about `count` steps of 1, 2 or 5 x 10^n.
std::vector<double> NiceTicks(double lo, double hi, int count);

// A rectangle of the image that shows x in [x0, x1] and y in [y0, y1] (y up).
struct PlotFrame {
  cv::Rect area;
  double x0 = 0.0, x1 = 1.0, y0 = 0.0, y1 = 1.0;
  bool grid = true;  // light lines across the plot at the y ticks
  cv::Point Px(double x, double y) const;
  // Draws the frame, ticks with their values, and the axis titles (units in the titles, e.g. "time [s]").
  void DrawAxes(cv::Mat& image, const std::string& x_title, const std::string& y_title) const;
};

// Text in the image's usual font: `scale` 0.5 is the tick size, 0.65 a title.
void PutLabel(cv::Mat& image, const std::string& text, cv::Point at, double scale = 0.5,
              const cv::Scalar& colour = cv::Scalar(0, 0, 0));

// A vertical colour bar of `map` (an OpenCV colormap) in `area`, its ticks from lo (bottom) to hi (top) and a title.
void DrawColourBar(cv::Mat& image, cv::Rect area, int map, double lo, double hi, const std::string& title);

// The colour of `value` in [lo, hi] on colormap `map` (BGR).
cv::Vec3b MapColour(int map, double value, double lo, double hi);

}  // namespace waam::analysis::internal
