// Picture of one planned layer in its slice plane: slice filled grey, weld moves coloured by sequence, travel dashed,
// starts and stops.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "analysis/png_file.h"
#include "analysis/picture_frame.h"
#include "analysis/plan_command.h"
#include "models/core/error.h"
#include "models/core/files.h"

namespace waam::analysis {
namespace {

constexpr int kImageSize = 800;  // px, longest side
constexpr int kMargin = 40;      // px

// Maps part coordinates (mm) to pixels, y up.
struct LayerView {
  Eigen::Vector2d min;
  double scale = 1.0;  // px per mm
  int width = kImageSize;
  int height = kImageSize;
  cv::Point ToPixel(const Eigen::Vector2d& p) const {
    return {kMargin + static_cast<int>(std::lround((p.x() - min.x()) * scale)),
            height - kMargin - static_cast<int>(std::lround((p.y() - min.y()) * scale))};
  }
};

std::vector<cv::Point> ToPixels(const planner::Ring& ring, const LayerView& view) {
  std::vector<cv::Point> pixels;
  pixels.reserve(ring.size());
  for (const Eigen::Vector2d& p : ring) pixels.push_back(view.ToPixel(p));
  return pixels;
}

// Blue -> green -> red along the sequence (OpenCV is BGR).
cv::Scalar SequenceColour(double t) {
  cv::Mat in(1, 1, CV_8UC1, cv::Scalar(static_cast<int>(std::clamp(t, 0.0, 1.0) * 255)));
  cv::Mat out;
  cv::applyColorMap(in, out, cv::COLORMAP_JET);
  const cv::Vec3b c = out.at<cv::Vec3b>(0, 0);
  return cv::Scalar(c[0], c[1], c[2]);
}

void DashedLine(cv::Mat& image, cv::Point a, cv::Point b, const cv::Scalar& colour) {
  const double length = std::hypot(b.x - a.x, b.y - a.y);
  const int dashes = std::max(1, static_cast<int>(length / 8.0));
  for (int i = 0; i < dashes; i += 2) {
    const double t0 = static_cast<double>(i) / dashes;
    const double t1 = std::min(1.0, static_cast<double>(i + 1) / dashes);
    cv::line(image, a + (b - a) * t0, a + (b - a) * t1, colour, 1, cv::LINE_AA);
  }
}

// The view that fits the slice's outer boundaries and the points `at` (mm, the picture's plane) into the image.
LayerView FitView(const std::vector<planner::PolygonWithHoles>& slice, const std::vector<Eigen::Vector2d>& at) {
  Eigen::Vector2d lo(1e300, 1e300);
  Eigen::Vector2d hi(-1e300, -1e300);
  auto grow = [&](const Eigen::Vector2d& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  };
  for (const planner::PolygonWithHoles& region : slice) {
    for (const Eigen::Vector2d& p : region.outer) grow(p);
  }
  for (const Eigen::Vector2d& p : at) grow(p);
  if (lo.x() > hi.x()) lo = hi = Eigen::Vector2d::Zero();
  const Eigen::Vector2d extent = (hi - lo).cwiseMax(1e-6);
  LayerView view;
  view.min = lo;
  view.scale = (kImageSize - 2 * kMargin) / std::max(extent.x(), extent.y());
  view.width = 2 * kMargin + static_cast<int>(std::ceil(extent.x() * view.scale));
  view.height = 2 * kMargin + static_cast<int>(std::ceil(extent.y() * view.scale));
  return view;
}

// Slice: outer boundaries grey, holes back to white.
void DrawSlice(const std::vector<planner::PolygonWithHoles>& slice, const LayerView& view, cv::Mat& image) {
  for (const planner::PolygonWithHoles& region : slice) {
    std::vector<std::vector<cv::Point>> outer = {ToPixels(region.outer, view)};
    cv::fillPoly(image, outer, cv::Scalar(225, 225, 225), cv::LINE_AA);
    for (const planner::Ring& hole : region.holes) {
      std::vector<std::vector<cv::Point>> h = {ToPixels(hole, view)};
      cv::fillPoly(image, h, cv::Scalar(255, 255, 255), cv::LINE_AA);
    }
  }
}

// Beads at their planned width, translucent, so uncovered parts of the slice stay visible.
void DrawBeads(const planner::LayerPath& layer, const std::vector<Eigen::Vector2d>& at, const LayerView& view,
               cv::Mat& image) {
  cv::Mat beads = image.clone();
  for (std::size_t i = 1; i < layer.points.size(); ++i) {
    if (!layer.points[i].weld) continue;
    const int thickness = std::max(1, static_cast<int>(std::lround(layer.points[i].bead_width_mm * view.scale)));
    cv::line(beads, view.ToPixel(at[i - 1]), view.ToPixel(at[i]), cv::Scalar(150, 200, 245), thickness, cv::LINE_AA);
  }
  cv::addWeighted(beads, 0.6, image, 0.4, 0.0, image);
}

// Path centre line: weld moves in sequence colours, travel dashed grey; green dot at arc start, red cross at stop.
// Coloured by path length travelled, so the sequence reads the same however finely a curve is divided. Returns the
// length of the colour scale (mm).
double DrawPath(const planner::LayerPath& layer, const std::vector<Eigen::Vector2d>& at, const LayerView& view,
                cv::Mat& image) {
  const std::size_t n = layer.points.size();
  std::vector<double> along(n, 0.0);
  for (std::size_t i = 1; i < n; ++i) along[i] = along[i - 1] + (layer.points[i].p_P - layer.points[i - 1].p_P).norm();
  const double total = n > 0 ? std::max(along.back(), 1e-9) : 1.0;
  for (std::size_t i = 1; i < n; ++i) {
    const cv::Point a = view.ToPixel(at[i - 1]);
    const cv::Point b = view.ToPixel(at[i]);
    if (layer.points[i].weld) {
      cv::line(image, a, b, SequenceColour(along[i] / total), 2, cv::LINE_AA);
    } else {
      DashedLine(image, a, b, cv::Scalar(150, 150, 150));
    }
  }
  for (std::size_t i = 1; i < n; ++i) {
    const bool starts = layer.points[i].weld && !layer.points[i - 1].weld;
    const bool stops = layer.points[i].weld && (i + 1 == n || !layer.points[i + 1].weld);
    if (starts) cv::circle(image, view.ToPixel(at[i - 1]), 6, cv::Scalar(0, 160, 0), -1);
    if (stops) {
      cv::drawMarker(image, view.ToPixel(at[i]), cv::Scalar(0, 0, 220), cv::MARKER_TILTED_CROSS, 14, 2);
    }
  }
  return total;
}

// The note in the picture's corner on how the layer is seen: a curved layer from +z, a tilted one along its build
// direction; none for a flat layer seen from +z.
void DrawViewNote(const planner::LayerPath& layer, cv::Mat& image) {
  char note[128];
  const Eigen::Vector3d& dir = layer.build_dir_P;
  if (!layer.slice_in_plane) {
    std::snprintf(note, sizeof(note), "curved layer seen from +z; its slice (development plane) not drawn");
  } else if ((dir - Eigen::Vector3d::UnitZ()).norm() > 1e-9) {
    std::snprintf(note, sizeof(note), "seen along the build direction (%.2f, %.2f, %.2f)", dir.x(), dir.y(), dir.z());
  } else {
    return;
  }
  cv::putText(image, note, cv::Point(10, 20), cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
}

}  // namespace

void WriteLayerPng(const planner::LayerPath& layer, const std::string& part, const std::filesystem::path& path) {
  // Draw in the slice plane, seen along the build direction, so the slice and the path overlay; a cone or cylinder
  // layer (slice in the development plane) shows its path seen from +z and no slice.
  const std::vector<planner::PolygonWithHoles> no_slice;
  const std::vector<planner::PolygonWithHoles>& slice = layer.slice_in_plane ? layer.slice : no_slice;
  const Eigen::Matrix<double, 3, 2> axes =
      layer.slice_in_plane ? layer.slice_axes_P : Eigen::Matrix<double, 3, 2>::Identity();
  const Eigen::Vector3d origin = layer.slice_in_plane ? layer.slice_origin_P : Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector2d> at(layer.points.size());  // the points in the picture's plane
  for (std::size_t i = 0; i < at.size(); ++i) at[i] = axes.transpose() * (layer.points[i].p_P - origin);

  const LayerView view = FitView(slice, at);
  cv::Mat image(view.height, view.width, CV_8UC3, cv::Scalar(255, 255, 255));
  DrawSlice(slice, view, image);
  DrawBeads(layer, at, view, image);
  const double total = DrawPath(layer, at, view, image);
  DrawViewNote(layer, image);

  // The picture spans its margins too: x_mm = lo.x + (px - kMargin) / scale, rows with y up.
  const double x0 = view.min.x() - kMargin / view.scale, y0 = view.min.y() - kMargin / view.scale;
  const ColourScale sequence = ColourMapScale(cv::COLORMAP_JET, 0.0, total, "weld path [mm]");
  const bool xy = layer.slice_in_plane ? layer.slice_axes_P.isApprox(Eigen::Matrix<double, 3, 2>::Identity(), 1e-9)
                                       : true;
  char caption[128];
  std::snprintf(caption, sizeof(caption), "%s: layer %d, z = %.2f mm: weld path by sequence; green start, red stop",
                part.c_str(), layer.index, layer.z_mm);
  const FramedPicture framed = FramePicture(image, x0, x0 + image.cols / view.scale, y0, y0 + image.rows / view.scale,
                                            caption, xy ? "x [mm]" : "slice u [mm]", xy ? "y [mm]" : "slice v [mm]",
                                            &sequence);
  internal::WritePngAtomic(framed.image, path);
}

}  // namespace waam::analysis
