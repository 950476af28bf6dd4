// The frame every map and layer picture shares: a title naming the part and the quantity, axes in mm with ticks,
// and a colour bar with its unit where colour carries a value (OpenCV drawing, no plotting stack).
#pragma once

#include <filesystem>
#include <string>

#include <opencv2/core.hpp>

namespace waam::analysis {

// What the picture's colours mean: a 256-entry BGR lookup table (CV_8UC3, 1 x 256) from `lo` (entry 0) to `hi`
// (entry 255), and the label with its unit, e.g. "height [mm]".
struct ColourScale {
  cv::Mat lut;
  double lo = 0.0;
  double hi = 1.0;
  std::string label;
};

// An OpenCV colour map (cv::COLORMAP_*) as a ColourScale.
ColourScale ColourMapScale(int colormap, double lo, double hi, const std::string& label);

// The labelled picture around a plot: the title on top, the plot with its x axis (ticks and label) below and
// its y axis left, and the colour bar (when `scale` is given) right, with ticks and its label.
struct FramedPicture {
  cv::Mat image;     // BGR
  cv::Rect plot;     // where the plot sits in `image`, px
  cv::Rect bar;      // where the colour bar's gradient sits (empty without a scale), px; its top row is `hi`
};

// Frames `plot` (BGR, drawn with +y up: row 0 is y = y_hi_mm) whose columns span x_lo_mm..x_hi_mm and rows
// y_hi_mm..y_lo_mm. `x_label` and `y_label` name the axes with their units ("x [mm]"). `scale` may be null.
// Throws InputError if the ranges are not finite.
FramedPicture FramePicture(const cv::Mat& plot, double x_lo_mm, double x_hi_mm, double y_lo_mm, double y_hi_mm,
                           const std::string& title, const std::string& x_label, const std::string& y_label,
                           const ColourScale* scale);

// The space FramePicture adds around a plot (title, axes, colour bar when `with_scale`), px, when the title is not
// wider than the result.
cv::Size FrameMargins(bool with_scale);

// Ticks of an axis from `lo` to `hi`: about `count` round values (1, 2 or 5 times a power of ten) inside the range.
std::vector<double> NiceTicks(double lo, double hi, int count);

}  // namespace waam::analysis
