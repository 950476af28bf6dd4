// Plot frames for the thermal pictures: ticks, axes and colour bars drawn with OpenCV (written by png_file.h).
#include "analysis/thermal_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <opencv2/imgproc.hpp>

#include "models/core/error.h"

namespace waam::analysis::internal {

std::vector<double> NiceTicks(double lo, double hi, int count) {
  if (!(hi > lo)) return {lo};
  const double raw = (hi - lo) / std::max(1, count);
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  double step = power;
  for (const double m : {1.0, 2.0, 5.0, 10.0}) {
    step = m * power;
    if (step >= raw) break;
  }
  std::vector<double> ticks;
  for (double t = std::ceil(lo / step - 1e-9) * step; t <= hi + 1e-9 * step; t += step) {
    ticks.push_back(std::abs(t) < 1e-12 * step ? 0.0 : t);
  }
  return ticks;
}

namespace {

std::string TickText(double value) {
  char text[32];
  const double a = std::abs(value);
  std::snprintf(text, sizeof(text), a >= 1000 || a == std::floor(a) ? "%.0f" : a >= 10 ? "%.1f" : "%.2g", value);
  return text;
}

}  // namespace

cv::Point PlotFrame::Px(double x, double y) const {
  const double u = x1 > x0 ? (x - x0) / (x1 - x0) : 0.5;
  const double v = y1 > y0 ? (y - y0) / (y1 - y0) : 0.5;
  return {area.x + static_cast<int>(std::lround(u * area.width)),
          area.y + area.height - static_cast<int>(std::lround(v * area.height))};
}

void PlotFrame::DrawAxes(cv::Mat& image, const std::string& x_title, const std::string& y_title) const {
  const cv::Scalar grey(170, 170, 170), black(0, 0, 0);
  cv::rectangle(image, area, black, 1);
  for (const double t : NiceTicks(x0, x1, 8)) {
    const cv::Point p = Px(t, y0);
    cv::line(image, p, {p.x, p.y - 5}, black, 1);
    const std::string text = TickText(t);
    int base = 0;
    const cv::Size size = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, 0.45, 1, &base);
    PutLabel(image, text, {p.x - size.width / 2, p.y + 18}, 0.45);
  }
  for (const double t : NiceTicks(y0, y1, 6)) {
    const cv::Point p = Px(x0, t);
    cv::line(image, p, {p.x + 5, p.y}, black, 1);
    if (grid) cv::line(image, {p.x + 6, p.y}, {area.x + area.width, p.y}, grey, 1, cv::LINE_4);
    const std::string text = TickText(t);
    int base = 0;
    const cv::Size size = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, 0.45, 1, &base);
    PutLabel(image, text, {p.x - size.width - 6, p.y + 5}, 0.45);
  }
  int base = 0;
  const cv::Size size = cv::getTextSize(x_title, cv::FONT_HERSHEY_SIMPLEX, 0.5, 1, &base);
  PutLabel(image, x_title, {area.x + (area.width - size.width) / 2, area.y + area.height + 38});
  PutLabel(image, y_title, {area.x, area.y - 8});
}

void PutLabel(cv::Mat& image, const std::string& text, cv::Point at, double scale, const cv::Scalar& colour) {
  cv::putText(image, text, at, cv::FONT_HERSHEY_SIMPLEX, scale, colour, 1, cv::LINE_AA);
}

cv::Vec3b MapColour(int map, double value, double lo, double hi) {
  const double u = hi > lo ? std::clamp((value - lo) / (hi - lo), 0.0, 1.0) : 0.5;
  cv::Mat grey(1, 1, CV_8UC1, cv::Scalar(static_cast<int>(std::lround(255.0 * u))));
  cv::Mat colour;
  cv::applyColorMap(grey, colour, map);
  return colour.at<cv::Vec3b>(0, 0);
}

void DrawColourBar(cv::Mat& image, cv::Rect area, int map, double lo, double hi, const std::string& title) {
  cv::Mat ramp(area.height, 1, CV_8UC1);
  for (int r = 0; r < area.height; ++r) {
    ramp.at<unsigned char>(r, 0) = static_cast<unsigned char>(255 - (255 * r) / std::max(1, area.height - 1));
  }
  cv::Mat colour;
  cv::applyColorMap(ramp, colour, map);
  cv::resize(colour, colour, area.size(), 0, 0, cv::INTER_NEAREST);
  colour.copyTo(image(area));
  cv::rectangle(image, area, cv::Scalar(0, 0, 0), 1);
  const PlotFrame frame{area, 0.0, 1.0, lo, hi};
  for (const double t : NiceTicks(lo, hi, 6)) {
    const cv::Point p = frame.Px(1.0, t);
    cv::line(image, p, {p.x + 5, p.y}, cv::Scalar(0, 0, 0), 1);
    PutLabel(image, TickText(t), {p.x + 8, p.y + 5}, 0.45);
  }
  PutLabel(image, title, {area.x - 10, area.y - 10});
}

}  // namespace waam::analysis::internal
