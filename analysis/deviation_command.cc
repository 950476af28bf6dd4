// `waam deviation`: a scan against its target, the summary JSON, the PLY with deviations and the colour map.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "analysis/png_file.h"
#include "analysis/distortion_command.h"
#include "models/core/error.h"
#include "models/core/files.h"
#include "models/core/json_text.h"
#include "models/core/output_lock.h"
#include "analysis/stl_file.h"
#include "planner/mesh/stl_io.h"
#include "analysis/point_cloud_file.h"
#include "twin/scanner/surface_sample.h"

namespace waam::analysis {
namespace {

nlohmann::json SectionJson(const twin::SectionMeasure& m) {
  return {{"points", m.points},
          {"centroid_mm", {m.centroid.x(), m.centroid.y(), m.centroid.z()}},
          {"d_min_mm", m.d_min_mm},
          {"d_max_mm", m.d_max_mm},
          {"ovality_pct", m.ovality_pct}};
}

}  // namespace

nlohmann::json DeviationToJson(const twin::ScanDeviation& scan, const twin::AxisComparison& axis) {
  nlohmann::json stations = nlohmann::json::array();
  for (std::size_t i = 0; i < axis.stations.size(); ++i) {
    const twin::AxisStation& s = axis.stations[i];
    stations.push_back({{"s_mm", s.s_mm},
                        {"center_mm", {s.center.x(), s.center.y(), s.center.z()}},
                        {"deviation_mm", axis.deviation[i].norm()}});
  }
  return {{"points", scan.points.size()},
          {"min_mm", scan.min_mm},
          {"max_mm", scan.max_mm},
          {"mean_mm", scan.mean_mm},
          {"rms_mm", scan.rms_mm},
          {"max_abs_mm", scan.max_abs_mm},
          {"axis",
           {{"max_deviation_mm", axis.max_axis_deviation_mm}, {"stations", stations.size()}, {"samples", stations}}},
          {"sections",
           {{"bottom", {{"target", SectionJson(axis.target_bottom)}, {"scan", SectionJson(axis.scan_bottom)}}},
            {"middle", {{"target", SectionJson(axis.target_middle)}, {"scan", SectionJson(axis.scan_middle)}}},
            {"top", {{"target", SectionJson(axis.target_top)}, {"scan", SectionJson(axis.scan_top)}}}}},
          {"ovality_pct", axis.scan_top.ovality_pct}};
}

void WriteScanDeviationPng(const twin::ScanDeviation& scan, const std::string& title, double range_mm,
                           const std::filesystem::path& path) {
  const double range = range_mm > 0.0 ? range_mm : std::max(scan.max_abs_mm, 1e-6);
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const Eigen::Vector3d& p : scan.points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  if (scan.points.empty()) lo = hi = Eigen::Vector3d::Zero();
  const double span = std::max({hi.x() - lo.x(), hi.y() - lo.y(), hi.z() - lo.z(), 1e-6});
  const double px = 380.0 / span;  // pixels per mm, both views share it
  const int w = static_cast<int>((hi.x() - lo.x()) * px) + 20, w2 = static_cast<int>((hi.y() - lo.y()) * px) + 20;
  const int h = static_cast<int>((hi.z() - lo.z()) * px) + 20;
  cv::Mat image(h + 70, std::max(w + w2 + 10, 520), CV_8UC3, cv::Scalar(255, 255, 255));
  // Painter's order: far points first, so each view shows the near side (front: smallest y; side: largest x).
  std::vector<std::size_t> order(scan.points.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  auto colour = [&](double d) {
    const double t = std::clamp(d / range, -1.0, 1.0);
    const auto fade = static_cast<unsigned char>(255.0 * (1.0 - std::abs(t)));
    return t < 0 ? cv::Vec3b(255, fade, fade) : cv::Vec3b(fade, fade, 255);
  };
  for (int view = 0; view < 2; ++view) {
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return view == 0 ? scan.points[a].y() > scan.points[b].y() : scan.points[a].x() < scan.points[b].x();
    });
    const int x0 = view == 0 ? 10 : w + 10;
    for (std::size_t i : order) {
      const Eigen::Vector3d& p = scan.points[i];
      const int u = x0 + static_cast<int>(((view == 0 ? p.x() - lo.x() : p.y() - lo.y())) * px);
      const int v = 40 + h - 10 - static_cast<int>((p.z() - lo.z()) * px);
      if (u >= 0 && v >= 0 && u < image.cols && v < image.rows) image.at<cv::Vec3b>(v, u) = colour(scan.deviation_mm[i]);
    }
  }
  char caption[256];
  // Two lines: one line of title and colour scale is wider than a narrow part's picture.
  std::snprintf(caption, sizeof(caption), "%s: front (x-z) and side (y-z)", title.c_str());
  cv::putText(image, caption, cv::Point(5, 16), cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  std::snprintf(caption, sizeof(caption), "blue -%.2f .. red +%.2f mm", range, range);
  cv::putText(image, caption, cv::Point(5, 34), cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  std::snprintf(caption, sizeof(caption), "min %.2f mm, max %.2f mm, rms %.2f mm, %zu points", scan.min_mm,
                scan.max_mm, scan.rms_mm, scan.points.size());
  cv::putText(image, caption, cv::Point(5, image.rows - 10), cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(0, 0, 0), 1,
              cv::LINE_AA);
  internal::WritePngAtomic(image, path);
}

nlohmann::json RunDeviation(const DeviationOptions& options) {
  WAAM_THROW_UNLESS(options.axis_step_mm > 0.0, "deviation --axis-step-mm = " << options.axis_step_mm << ": must be > 0");
  planner::MeshReport report;
  const planner::TriangleMesh target = ReadStl(options.target, 0.0, &report);
  const ScanCloud cloud = ReadScan(options.scan, 0.5, !options.keep_bottom);
  ClaimOutputDirectory(options.out_dir);
  const twin::MeshDistance distance(target);
  const twin::ScanDeviation scan = twin::MeasureScanDeviation(cloud.points, distance, cloud.weight);
  const twin::AxisComparison axis = twin::CompareAxis(twin::SampleSurface(target, 0.5 * options.axis_step_mm),
                                                      scan.points, options.axis_step_mm, 0.5 * options.axis_step_mm);
  WritePlyWithDeviation(options.out_dir / "deviation.ply", scan.points, scan.deviation_mm);
  if (options.images) WriteScanDeviationPng(scan, "scan - target", 0.0, options.out_dir / "deviation_map.png");
  nlohmann::json json = DeviationToJson(scan, axis);
  json["target"] = options.target.string();
  json["scan"] = options.scan.string();
  json["target_watertight"] = report.watertight;
  json["weighting"] = cloud.area_weighted ? "area" : "point";
  json["bottom_excluded"] = {{"facets", cloud.bottom_facets_skipped}, {"area_mm2", cloud.bottom_area_skipped_mm2}};
  WriteFileAtomic(options.out_dir / "deviation.json", JsonText(json) + "\n");
  return json;
}

}  // namespace waam::analysis
