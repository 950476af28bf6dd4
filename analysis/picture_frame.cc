// FramePicture: title, axes with ticks in mm and a colour bar around the maps and layer pictures.
#include "analysis/picture_frame.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "models/core/error.h"
#include "models/core/files.h"

namespace waam::analysis {
namespace {

constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
constexpr double kTextScale = 0.45;
constexpr int kTitleHeight = 30;   // px above the plot
constexpr int kLeft = 64;          // px left of the plot: y ticks and label
constexpr int kBottom = 44;        // px below the plot: x ticks and label
constexpr int kRight = 16;         // px right of the plot (or of the colour bar's labels)
constexpr int kBarGap = 18;        // px between the plot and the colour bar
constexpr int kBarWidth = 18;      // px
constexpr int kBarLabels = 64;     // px right of the bar: its tick labels
const cv::Scalar kInk(0, 0, 0);

std::string TickText(double value, double step) {
  char text[32];
  const int decimals = std::clamp(static_cast<int>(std::ceil(-std::log10(step) - 1e-9)), 0, 4);
  std::snprintf(text, sizeof(text), "%.*f", decimals, std::abs(value) < 1e-12 ? 0.0 : value);
  return text;
}

void Text(cv::Mat& image, const std::string& text, cv::Point at, double scale = kTextScale) {
  cv::putText(image, text, at, kFont, scale, kInk, 1, cv::LINE_AA);
}

cv::Size TextSize(const std::string& text, double scale = kTextScale) {
  int baseline = 0;
  return cv::getTextSize(text, kFont, scale, 1, &baseline);
}

}  // namespace

ColourScale ColourMapScale(int colormap, double lo, double hi, const std::string& label) {
  cv::Mat ramp(1, 256, CV_8UC1);
  for (int i = 0; i < 256; ++i) ramp.at<unsigned char>(0, i) = static_cast<unsigned char>(i);
  ColourScale scale;
  cv::applyColorMap(ramp, scale.lut, colormap);
  scale.lo = lo;
  scale.hi = hi;
  scale.label = label;
  return scale;
}

cv::Size FrameMargins(bool with_scale) {
  return {kLeft + (with_scale ? kBarGap + kBarWidth + kBarLabels : 0) + kRight, kTitleHeight + kBottom};
}

std::vector<double> NiceTicks(double lo, double hi, int count) {
  std::vector<double> ticks;
  if (!(hi > lo) || count < 1) {
    ticks.push_back(lo);
    return ticks;
  }
  const double raw = (hi - lo) / count;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  double step = power;
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    step = m * power;
    if (step >= raw) break;
  }
  for (double t = std::ceil(lo / step - 1e-9) * step; t <= hi + 1e-9 * step; t += step) ticks.push_back(t);
  return ticks;
}

FramedPicture FramePicture(const cv::Mat& plot, double x_lo_mm, double x_hi_mm, double y_lo_mm, double y_hi_mm,
                           const std::string& title, const std::string& x_label, const std::string& y_label,
                           const ColourScale* scale) {
  WAAM_THROW_UNLESS(std::isfinite(x_lo_mm) && std::isfinite(x_hi_mm) && std::isfinite(y_lo_mm) &&
                        std::isfinite(y_hi_mm),
                    "picture '" << title << "': axis range is not finite");
  const int width = std::max(plot.cols + FrameMargins(scale != nullptr).width, TextSize(title).width + 10);
  FramedPicture out;
  out.image = cv::Mat(kTitleHeight + plot.rows + kBottom, width, CV_8UC3, cv::Scalar(255, 255, 255));
  out.plot = cv::Rect(kLeft, kTitleHeight, plot.cols, plot.rows);
  plot.copyTo(out.image(out.plot));
  cv::rectangle(out.image, out.plot, kInk, 1);
  Text(out.image, title, cv::Point(5, 20));
  const double x_step = plot.cols > 0 ? (x_hi_mm - x_lo_mm) / plot.cols : 1.0;  // mm per px
  const double y_step = plot.rows > 0 ? (y_hi_mm - y_lo_mm) / plot.rows : 1.0;
  // x axis: ticks down from the plot's bottom edge, labels centred under them.
  const std::vector<double> xt = NiceTicks(x_lo_mm, x_hi_mm, std::max(3, plot.cols / 90));
  const double xt_step = xt.size() > 1 ? xt[1] - xt[0] : 1.0;
  const int bottom = out.plot.y + out.plot.height;
  for (double t : xt) {
    const int px = out.plot.x + static_cast<int>(std::lround((t - x_lo_mm) / x_step));
    cv::line(out.image, {px, bottom}, {px, bottom + 4}, kInk, 1);
    const std::string label = TickText(t, xt_step);
    Text(out.image, label, {px - TextSize(label).width / 2, bottom + 18});
  }
  Text(out.image, x_label, {out.plot.x + plot.cols / 2 - TextSize(x_label).width / 2, bottom + 38});
  // y axis: ticks left of the plot, labels right-aligned to them; the axis label above the labels.
  const std::vector<double> yt = NiceTicks(y_lo_mm, y_hi_mm, std::max(3, plot.rows / 70));
  const double yt_step = yt.size() > 1 ? yt[1] - yt[0] : 1.0;
  for (double t : yt) {
    const int py = bottom - static_cast<int>(std::lround((t - y_lo_mm) / y_step));
    cv::line(out.image, {out.plot.x - 4, py}, {out.plot.x, py}, kInk, 1);
    const std::string label = TickText(t, yt_step);
    Text(out.image, label, {out.plot.x - 7 - TextSize(label).width, py + 5});
  }
  cv::Mat rotated(TextSize(y_label).height + 8, TextSize(y_label).width + 4, CV_8UC3, cv::Scalar(255, 255, 255));
  Text(rotated, y_label, {2, rotated.rows - 4});
  cv::rotate(rotated, rotated, cv::ROTATE_90_COUNTERCLOCKWISE);
  const int label_y = std::max(0, out.plot.y + plot.rows / 2 - rotated.rows / 2);
  if (label_y + rotated.rows <= out.image.rows) rotated.copyTo(out.image(cv::Rect(2, label_y, rotated.cols, rotated.rows)));
  // The colour bar: hi at the top, lo at the bottom, ticks and the label (with its unit) above.
  if (scale != nullptr && plot.rows > 1) {
    out.bar = cv::Rect(out.plot.x + plot.cols + kBarGap, out.plot.y, kBarWidth, plot.rows);
    for (int r = 0; r < plot.rows; ++r) {
      const int entry = static_cast<int>(std::lround(255.0 * (plot.rows - 1 - r) / (plot.rows - 1)));
      out.image(cv::Rect(out.bar.x, out.bar.y + r, kBarWidth, 1)).setTo(scale->lut.at<cv::Vec3b>(0, entry));
    }
    cv::rectangle(out.image, out.bar, kInk, 1);
    const std::vector<double> bt = NiceTicks(scale->lo, scale->hi, std::max(4, plot.rows / 60));
    const double bt_step = bt.size() > 1 ? bt[1] - bt[0] : 1.0;
    const double span = scale->hi > scale->lo ? scale->hi - scale->lo : 1.0;
    for (double t : bt) {
      const int py = out.bar.y + plot.rows - 1 - static_cast<int>(std::lround((t - scale->lo) / span * (plot.rows - 1)));
      const int x = out.bar.x + kBarWidth;
      cv::line(out.image, {x, py}, {x + 4, py}, kInk, 1);
      Text(out.image, TickText(t, bt_step), {x + 7, py + 5});
    }
    const std::string& label = scale->label;
    Text(out.image, label, {std::max(0, std::min(out.bar.x, width - TextSize(label).width - 2)), bottom + 38});
  }
  return out;
}

}  // namespace waam::analysis
