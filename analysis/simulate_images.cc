// Pictures of the simulated part: top height map, vertical sections by layer, and the deviation map.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "analysis/png_file.h"
#include "analysis/picture_frame.h"
#include "analysis/simulate_command.h"
#include "models/core/error.h"
#include "models/core/files.h"

namespace waam::analysis {
namespace {

// Flips `raw` (row 0 = lowest y or z) so +y (or +z) points up, scales it (nearest, so voxels stay crisp) so that its
// longer side is about 800 px, frames it (title, axes in mm, colour bar) and writes it atomically as PNG.
void Save(const cv::Mat& raw, double x_lo, double x_hi, double y_lo, double y_hi, const std::string& title,
          const std::string& x_label, const std::string& y_label, const ColourScale& scale,
          const std::filesystem::path& path) {
  cv::Mat image;
  cv::flip(raw, image, 0);
  const int longer = std::max(image.cols, image.rows);
  const double zoom = std::clamp(800.0 / std::max(1, longer), 1.0, 16.0);
  if (zoom > 1.0) cv::resize(image, image, cv::Size(), zoom, zoom, cv::INTER_NEAREST);
  internal::WritePngAtomic(FramePicture(image, x_lo, x_hi, y_lo, y_hi, title, x_label, y_label, &scale).image, path);
}

std::string Format(const char* format, double a, double b) {
  char text[160];
  std::snprintf(text, sizeof(text), format, a, b);
  return text;
}

}  // namespace

void WriteHeightMapPng(const twin::HeightMap& map, const std::string& part, const std::filesystem::path& path) {
  const int nx = std::max(1, map.nx), ny = std::max(1, map.ny);
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (float z : map.top_mm) {
    if (std::isnan(z)) continue;
    lo = std::min(lo, static_cast<double>(z));
    hi = std::max(hi, static_cast<double>(z));
  }
  if (!std::isfinite(lo)) lo = hi = 0.0;
  cv::Mat gray(ny, nx, CV_8UC1, cv::Scalar(0));
  cv::Mat empty(ny, nx, CV_8UC1, cv::Scalar(1));
  for (int j = 0; j < map.ny; ++j) {
    for (int i = 0; i < map.nx; ++i) {
      const float z = map.top_mm[static_cast<std::size_t>(j) * map.nx + i];
      if (std::isnan(z)) continue;
      gray.at<unsigned char>(j, i) = static_cast<unsigned char>(hi > lo ? 255.0 * (z - lo) / (hi - lo) : 128.0);
      empty.at<unsigned char>(j, i) = 0;
    }
  }
  cv::Mat colour;
  cv::applyColorMap(gray, colour, cv::COLORMAP_VIRIDIS);
  colour.setTo(cv::Scalar(255, 255, 255), empty);
  const double v = map.voxel_mm;
  Save(colour, map.i0 * v, (map.i0 + nx) * v, map.j0 * v, (map.j0 + ny) * v, part + ": top height, seen from +z",
       "x [mm]", "y [mm]", ColourMapScale(cv::COLORMAP_VIRIDIS, lo, hi, "top height z [mm]"), path);
}

void WriteSectionPng(const twin::TwinResult& result, int axis, const std::string& part,
                     const std::filesystem::path& path) {
  WAAM_THROW_UNLESS(axis == 0 || axis == 1, "section picture: axis " << axis << " must be 0 (x) or 1 (y)");
  const twin::VoxelGrid& grid = result.depositor.grid();
  twin::VoxelIndex lo, hi;
  if (!grid.Bounds(&lo, &hi)) {
    lo = hi = twin::VoxelIndex::Zero();
  }
  // The section plane is normal to the other horizontal axis, through the middle of the part.
  const int across = 1 - axis;
  const int middle = (lo[across] + hi[across]) / 2;
  const int width = hi[axis] - lo[axis] + 1;
  const int height = hi.z() - lo.z() + 1;
  const int layers = std::max<int>(1, static_cast<int>(result.measures.layers));
  cv::Mat gray(height, width, CV_8UC1, cv::Scalar(0));
  cv::Mat empty(height, width, CV_8UC1, cv::Scalar(1));
  for (int k = lo.z(); k <= hi.z(); ++k) {
    for (int a = lo[axis]; a <= hi[axis]; ++a) {
      twin::VoxelIndex v;
      v[axis] = a;
      v[across] = middle;
      v.z() = k;
      const twin::VoxelData* data = grid.Get(v);
      if (data == nullptr) continue;
      const int layer = result.depositor.LayerOf(*data);
      gray.at<unsigned char>(k - lo.z(), a - lo[axis]) =
          static_cast<unsigned char>(layers > 1 ? 255.0 * (layer % layers) / (layers - 1) : 0.0);
      empty.at<unsigned char>(k - lo.z(), a - lo[axis]) = 0;
    }
  }
  cv::Mat colour;
  cv::applyColorMap(gray, colour, cv::COLORMAP_TURBO);
  colour.setTo(cv::Scalar(255, 255, 255), empty);
  const double v = grid.voxel_mm();
  const char* name = axis == 0 ? "x" : "y";
  Save(colour, lo[axis] * v, (hi[axis] + 1) * v, lo.z() * v, (hi.z() + 1) * v,
       part + ": layers in the section " + name + "-z at " + (axis == 0 ? "y" : "x") +
           Format(" = %.1f mm", (middle + 0.5) * v, 0.0),
       std::string(name) + " [mm]", "z [mm]",
       ColourMapScale(cv::COLORMAP_TURBO, 1.0, std::max(2, layers), "layer (1 = first)"), path);
}

void WriteDeviationPng(const twin::TwinResult& result, const std::string& part,
                       const std::filesystem::path& path) {
  const twin::HeightMap& map = result.top;
  const int nx = std::max(1, map.nx), ny = std::max(1, map.ny);
  // The deviation of the highest upward face of every column: the top surface seen by a scanner from above.
  std::vector<double> dev(static_cast<std::size_t>(nx) * ny, std::numeric_limits<double>::quiet_NaN());
  std::vector<double> top(dev.size(), -std::numeric_limits<double>::infinity());
  const double v = map.voxel_mm;
  double extent = 1e-9;
  for (const twin::SurfaceSample& s : result.deviation.points) {
    if (s.face.z() != 1) continue;
    const int i = static_cast<int>(std::floor(s.p_P.x() / v)) - map.i0;
    const int j = static_cast<int>(std::floor(s.p_P.y() / v)) - map.j0;
    if (i < 0 || j < 0 || i >= nx || j >= ny) continue;
    const std::size_t n = static_cast<std::size_t>(j) * nx + i;
    if (s.p_P.z() > top[n]) {
      top[n] = s.p_P.z();
      dev[n] = s.deviation_mm;
    }
    extent = std::max(extent, std::abs(s.deviation_mm));
  }
  // Diverging scale: blue (below the target) - white - red (above), BGR; entry 0 is -extent, 255 is +extent.
  ColourScale scale;
  scale.lut = cv::Mat(1, 256, CV_8UC3);
  for (int e = 0; e < 256; ++e) {
    const double t = e / 127.5 - 1.0;
    const auto fade = static_cast<unsigned char>(std::lround(255.0 * (1.0 - std::abs(t))));
    scale.lut.at<cv::Vec3b>(0, e) = t < 0 ? cv::Vec3b(255, fade, fade) : cv::Vec3b(fade, fade, 255);
  }
  scale.lo = -extent;
  scale.hi = extent;
  scale.label = "deviation [mm], + above target";
  cv::Mat colour(ny, nx, CV_8UC3, cv::Scalar(255, 255, 255));
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const double d = dev[static_cast<std::size_t>(j) * nx + i];
      if (std::isnan(d)) continue;
      const double t = std::clamp(d / extent, -1.0, 1.0);
      colour.at<cv::Vec3b>(j, i) = scale.lut.at<cv::Vec3b>(0, static_cast<int>(std::lround(127.5 * (t + 1.0))));
    }
  }
  Save(colour, map.i0 * v, (map.i0 + nx) * v, map.j0 * v, (map.j0 + ny) * v,
       part + ": top-surface deviation from the target, seen from +z", "x [mm]", "y [mm]", scale, path);
}

}  // namespace waam::analysis
