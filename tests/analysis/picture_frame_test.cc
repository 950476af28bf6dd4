// Pictures people read: a title, axes with ticks in mm, and a colour bar whose gradient and labels are where the
// frame says (analysis/picture_frame.h), on a rendered height map.
#include "analysis/picture_frame.h"

#include <filesystem>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "analysis/png_file.h"
#include "analysis/simulate_command.h"

namespace waam::analysis {
namespace {

namespace fs = std::filesystem;

// Number of dark (text or line) pixels in `area` of `image`.
int DarkPixels(const cv::Mat& image, const cv::Rect& area) {
  cv::Mat gray;
  cv::cvtColor(image(area & cv::Rect(0, 0, image.cols, image.rows)), gray, cv::COLOR_BGR2GRAY);
  return cv::countNonZero(gray < 100);
}

int ColourDistance(const cv::Vec3b& a, const cv::Vec3b& b) {
  return std::abs(a[0] - b[0]) + std::abs(a[1] - b[1]) + std::abs(a[2] - b[2]);
}

TEST(PictureFrame, ColourBarRunsFromHighAtTheTopToLowAtTheBottomWithLabels) {
  const cv::Mat plot(100, 200, CV_8UC3, cv::Scalar(200, 200, 200));
  const ColourScale scale = ColourMapScale(cv::COLORMAP_VIRIDIS, 2.0, 7.0, "top height z [mm]");
  const FramedPicture f = FramePicture(plot, -10.0, 30.0, 0.0, 20.0, "part: quantity", "x [mm]", "y [mm]", &scale);
  ASSERT_FALSE(f.bar.empty());
  EXPECT_GE(f.bar.x, f.plot.x + f.plot.width) << "the bar is right of the plot";
  EXPECT_EQ(f.bar.height, f.plot.height);
  const int cx = f.bar.x + f.bar.width / 2;
  EXPECT_LT(ColourDistance(f.image.at<cv::Vec3b>(f.bar.y + 1, cx), scale.lut.at<cv::Vec3b>(0, 255)), 20)
      << "top of the bar: the highest value's colour";
  EXPECT_LT(ColourDistance(f.image.at<cv::Vec3b>(f.bar.y + f.bar.height - 2, cx), scale.lut.at<cv::Vec3b>(0, 0)), 20)
      << "bottom of the bar: the lowest value's colour";
  EXPECT_GT(DarkPixels(f.image, {f.bar.x + f.bar.width + 6, f.bar.y - 6, 60, f.bar.height + 12}), 30)
      << "tick labels right of the bar";
  EXPECT_GT(DarkPixels(f.image, {0, 0, f.image.cols, f.plot.y - 2}), 30) << "a title above the plot";
  EXPECT_GT(DarkPixels(f.image, {f.plot.x, f.plot.y + f.plot.height + 6, f.plot.width, 36}), 30)
      << "x tick labels and the axis label under the plot";
  EXPECT_GT(DarkPixels(f.image, {0, f.plot.y, f.plot.x - 6, f.plot.height}), 30) << "y tick labels left of the plot";
}

TEST(PictureFrame, NiceTicksAreRoundAndInside) {
  const std::vector<double> t = NiceTicks(-3.2, 41.0, 5);
  ASSERT_GE(t.size(), 3u);
  EXPECT_GE(t.front(), -3.2);
  EXPECT_LE(t.back(), 41.0);
  EXPECT_DOUBLE_EQ(t[1] - t[0], 10.0);
  EXPECT_DOUBLE_EQ(t.front(), 0.0);
}

// The top-height map as written: its colour bar's gradient right of the plot, from yellow (high) to purple (low).
TEST(PictureFrame, HeightMapHasItsColourBar) {
  twin::HeightMap map;
  map.nx = 40;
  map.ny = 20;
  map.voxel_mm = 0.5;
  map.top_mm.resize(40 * 20);
  for (int j = 0; j < 20; ++j)
    for (int i = 0; i < 40; ++i) map.top_mm[j * 40 + i] = static_cast<float>(1.0 + 0.1 * i);
  const fs::path path = fs::path(::waam_test_env::TempDir()) / "top_height_frame.png";
  WriteHeightMapPng(map, "plate", path);
  const cv::Mat image = internal::ReadPng(path, 3);
  ASSERT_FALSE(image.empty());
  // The plot is 40 x 20 columns at 16 px each: 640 x 320 px, then the bar.
  const cv::Size margins = FrameMargins(true);
  EXPECT_EQ(image.cols, 640 + margins.width);
  EXPECT_EQ(image.rows, 320 + margins.height);
  const ColourScale viridis = ColourMapScale(cv::COLORMAP_VIRIDIS, 0, 1, "");
  // Find the bar: the column right of the plot whose top pixel is viridis' top colour.
  int bar_x = -1;
  const int top = margins.height - 44 + 1;  // the plot's (and bar's) first row inside its border
  for (int x = image.cols - 1; x > 640 && bar_x < 0; --x) {
    if (ColourDistance(image.at<cv::Vec3b>(top, x), viridis.lut.at<cv::Vec3b>(0, 255)) < 20) bar_x = x;
  }
  ASSERT_GT(bar_x, 640) << "no colour bar right of the plot";
  EXPECT_LT(ColourDistance(image.at<cv::Vec3b>(top + 318 - 1, bar_x), viridis.lut.at<cv::Vec3b>(0, 0)), 20)
      << "the bar ends in viridis' lowest colour";
  EXPECT_GT(DarkPixels(image, {bar_x + 10, top, 60, 320}), 30) << "tick labels beside the bar";
}

}  // namespace
}  // namespace waam::analysis
