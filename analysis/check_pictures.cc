// Pictures of `waam check`: the cell's collision shapes at the worst point (OpenCV projection, side and top views)
// and the eight joint trajectories with their limits.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "analysis/check_command.h"
#include "analysis/picture_frame.h"
#include "analysis/png_file.h"
#include "models/core/files.h"
#include "models/core/numbers.h"
#include "twin/cell/mujoco_cell.h"

namespace waam::analysis {
namespace fs = std::filesystem;

namespace {

// Surface sample points of a collision shape in the world (mm); their projected convex hull is its silhouette.
std::vector<Eigen::Vector3d> SurfacePoints(const twin::CellShape& s) {
  std::vector<Eigen::Vector3d> local;
  const Eigen::Vector3d& z = s.size_mm;
  auto sphere = [&](double r, double dz) {
    for (int i = 0; i <= 8; ++i) {
      const double th = kPi * i / 8;
      for (int k = 0; k < 16; ++k) {
        const double ph = 2 * kPi * k / 16;
        local.emplace_back(r * std::sin(th) * std::cos(ph), r * std::sin(th) * std::sin(ph), dz + r * std::cos(th));
      }
    }
  };
  switch (s.type) {
    case twin::CellShape::Type::kSphere: sphere(z[0], 0.0); break;
    case twin::CellShape::Type::kCapsule: sphere(z[0], z[1]); sphere(z[0], -z[1]); break;
    case twin::CellShape::Type::kCylinder:
      for (int k = 0; k < 24; ++k) {
        const double ph = 2 * kPi * k / 24;
        local.emplace_back(z[0] * std::cos(ph), z[0] * std::sin(ph), z[1]);
        local.emplace_back(z[0] * std::cos(ph), z[0] * std::sin(ph), -z[1]);
      }
      break;
    case twin::CellShape::Type::kBox:
      for (int c = 0; c < 8; ++c) local.emplace_back((c & 1 ? 1 : -1) * z[0], (c & 2 ? 1 : -1) * z[1], (c & 4 ? 1 : -1) * z[2]);
      break;
    default: break;
  }
  for (Eigen::Vector3d& p : local) p = s.X_WG * p;
  return local;
}

// One orthographic view: world axes (u, v) to the image, depth axis w (larger = nearer the viewer).
struct View {
  int u, v, w;
  double near_sign;  // +1: larger w is nearer the viewer
  cv::Rect area;
  Eigen::Vector2d lo = Eigen::Vector2d::Zero();
  Eigen::Vector2d hi = Eigen::Vector2d::Zero();
  double scale = 1.0;
  cv::Point Px(const Eigen::Vector3d& p) const {
    const double x = area.x + 20 + (p[u] - lo.x()) * scale;
    const double y = area.y + area.height - 20 - (p[v] - lo.y()) * scale;
    return {static_cast<int>(std::lround(x)), static_cast<int>(std::lround(y))};
  }
  void Fit(const std::vector<Eigen::Vector3d>& pts) {
    lo = Eigen::Vector2d::Constant(1e300);
    hi = -lo;
    for (const Eigen::Vector3d& p : pts) {
      lo = lo.cwiseMin(Eigen::Vector2d(p[u], p[v]));
      hi = hi.cwiseMax(Eigen::Vector2d(p[u], p[v]));
    }
    const Eigen::Vector2d span = (hi - lo).cwiseMax(1.0);
    scale = std::min((area.width - 40) / span.x(), (area.height - 40) / span.y());
  }
};

void DrawView(cv::Mat& img, const View& view, const std::vector<twin::CellShape>& shapes,
              const std::vector<std::vector<Eigen::Vector3d>>& surfaces, const std::vector<std::string>& marked,
              const std::vector<Eigen::Vector3d>& path_W, const Eigen::Vector3d& tcp_W) {
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    if (!surfaces[i].empty()) order.push_back(i);
  }
  // Painter's order: far shapes first.
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return view.near_sign * shapes[a].X_WG.translation()[view.w] < view.near_sign * shapes[b].X_WG.translation()[view.w];
  });
  for (std::size_t i : order) {
    std::vector<cv::Point> px, hull;
    for (const Eigen::Vector3d& p : surfaces[i]) px.push_back(view.Px(p));
    cv::convexHull(px, hull);
    const Eigen::Vector4f& c = shapes[i].rgba;
    const cv::Scalar fill(255 * c[2], 255 * c[1], 255 * c[0]);
    cv::fillConvexPoly(img, hull, fill, cv::LINE_AA);
    const bool hit = std::find(marked.begin(), marked.end(), shapes[i].body) != marked.end();
    cv::polylines(img, hull, true, hit ? cv::Scalar(0, 0, 255) : cv::Scalar(40, 40, 40), hit ? 3 : 1, cv::LINE_AA);
  }
  for (std::size_t i = 1; i < path_W.size(); ++i) {
    cv::line(img, view.Px(path_W[i - 1]), view.Px(path_W[i]), cv::Scalar(0, 140, 255), 1, cv::LINE_AA);
  }
  cv::drawMarker(img, view.Px(tcp_W), cv::Scalar(0, 0, 255), cv::MARKER_CROSS, 16, 2);
}

// One view drawn and framed: axes in mm (world frame) and the title.
cv::Mat FramedView(View view, const std::vector<twin::CellShape>& shapes,
                   const std::vector<std::vector<Eigen::Vector3d>>& surfaces, const std::vector<std::string>& marked,
                   const std::vector<Eigen::Vector3d>& path_W, const Eigen::Vector3d& tcp_W,
                   const std::vector<Eigen::Vector3d>& all, const std::string& title) {
  static const char* const kAxis[3] = {"x [mm]", "y [mm]", "z [mm]"};
  view.Fit(all);
  cv::Mat plot(view.area.height, view.area.width, CV_8UC3, cv::Scalar(255, 255, 255));
  DrawView(plot, view, shapes, surfaces, marked, path_W, tcp_W);
  // Px puts lo at 20 px from the left and bottom edges, at `scale` px per mm.
  const double x_lo = view.lo.x() - 20.0 / view.scale, y_lo = view.lo.y() - 20.0 / view.scale;
  return FramePicture(plot, x_lo, x_lo + plot.cols / view.scale, y_lo, y_lo + plot.rows / view.scale, title,
                      kAxis[view.u], kAxis[view.v], nullptr)
      .image;
}

}  // namespace

void WriteCellPng(const twin::CellModel& cell, const planner::CellKinematics& kin, const planner::Plan& plan,
                  const twin::CheckReport& report, const std::string& part_name, const fs::path& path) {
  const planner::CellSample& s = report.motion[report.worst_sample];
  twin::CellState state(cell);
  state.SetJoints(s.q);
  const std::vector<twin::CellShape> shapes = state.Shapes();
  std::vector<std::vector<Eigen::Vector3d>> surfaces;
  std::vector<Eigen::Vector3d> all;
  for (const twin::CellShape& shape : shapes) {
    surfaces.push_back(SurfacePoints(shape));
    all.insert(all.end(), surfaces.back().begin(), surfaces.back().end());
  }
  // The path in the world at this sample's positioner angles.
  const Eigen::Isometry3d X_WP = kin.X_WB * planner::PartPose(kin.positioner, s.q[6], s.q[7]);
  std::vector<Eigen::Vector3d> path_W;
  for (const planner::LayerPath& layer : plan.layers) {
    for (const planner::PathPoint& p : layer.points) path_W.push_back(X_WP * p.p_P);
  }
  std::vector<std::string> marked;
  std::string caption = "no violations: shown at the smallest joint margin";
  for (const twin::CheckViolation& v : report.violations) {
    if (v.sample != report.worst_sample) continue;
    marked.push_back(v.body1);
    marked.push_back(v.body2);
    char text[256];
    std::snprintf(text, sizeof(text), "%s %s%s%s%s  point %d layer %d  %s = %.2f", NameOf(v.kind).data(), v.joint.c_str(),
                  v.body1.c_str(), v.body2.empty() ? "" : "/", v.body2.c_str(), v.point, v.layer, v.unit.c_str(),
                  v.value);
    caption = text;
    break;
  }
  // Side view from -y (x right, z up: nearer = smaller y); top view from +z.
  const View side{0, 2, 1, -1.0, cv::Rect(0, 0, 820, 780), Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero(), 1.0};
  const View top{0, 1, 2, 1.0, cv::Rect(0, 0, 820, 780), Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero(), 1.0};
  const Eigen::Vector3d tcp_W = s.X_WT.translation();
  const cv::Mat a = FramedView(side, shapes, surfaces, marked, path_W, tcp_W, all, "cell at the worst sample, side (from -y)");
  const cv::Mat b = FramedView(top, shapes, surfaces, marked, path_W, tcp_W, all, "cell at the worst sample, top (from +z)");
  const int header = 40;
  cv::Mat img(header + std::max(a.rows, b.rows), a.cols + b.cols, CV_8UC3, cv::Scalar(255, 255, 255));
  a.copyTo(img(cv::Rect(0, header, a.cols, a.rows)));
  b.copyTo(img(cv::Rect(a.cols, header, b.cols, b.rows)));
  cv::putText(img, part_name + ": robot cell, " + caption, {10, 28}, cv::FONT_HERSHEY_SIMPLEX, 0.8, cv::Scalar(0, 0, 180), 2);
  internal::WritePngAtomic(img, path);
}

void WriteJointPlots(const planner::CellKinematics& kin, const twin::CheckReport& report, const std::string& part_name,
                     const fs::path& path) {
  Eigen::Matrix<double, 8, 1> lo, hi;
  lo << kin.arm.lower, kin.positioner.tilt_lower, kin.positioner.rotation_lower;
  hi << kin.arm.upper, kin.positioner.tilt_upper, kin.positioner.rotation_upper;
  const int plot_w = 640, plot_h = 170, cols = 2;
  const double t_end = std::max(1e-9, report.motion.back().t_s);
  std::vector<cv::Mat> panels;
  for (int a = 0; a < 8; ++a) {
    double vmin = 1e300, vmax = -1e300;
    for (const planner::CellSample& s : report.motion) {
      vmin = std::min(vmin, s.q[a] * kDeg);
      vmax = std::max(vmax, s.q[a] * kDeg);
    }
    const double pad = std::max(5.0, 0.1 * (vmax - vmin));
    const double y_lo = vmin - pad, y_hi = vmax + pad;
    cv::Mat plot(plot_h, plot_w, CV_8UC3, cv::Scalar(255, 255, 255));
    auto px = [&](double t, double deg) {
      return cv::Point(static_cast<int>(std::lround(t / t_end * (plot_w - 1))),
                       static_cast<int>(std::lround((y_hi - deg) / (y_hi - y_lo) * (plot_h - 1))));
    };
    for (const double limit : {lo[a] * kDeg, hi[a] * kDeg}) {
      if (limit > y_lo && limit < y_hi) cv::line(plot, px(0, limit), px(t_end, limit), cv::Scalar(0, 0, 255), 1);
    }
    std::vector<cv::Point> line;
    line.reserve(report.motion.size());
    for (const planner::CellSample& s : report.motion) line.push_back(px(s.t_s, s.q[a] * kDeg));
    cv::polylines(plot, line, false, cv::Scalar(160, 60, 0), 1, cv::LINE_AA);
    for (const twin::CheckViolation& v : report.violations) {
      if (v.joint != twin::AxisName(a)) continue;
      const planner::CellSample& s = report.motion[v.sample];
      cv::circle(plot, px(s.t_s, s.q[a] * kDeg), 5, cv::Scalar(0, 0, 255), 2);
    }
    char title[160];
    std::snprintf(title, sizeof(title), "axis %s: %.1f .. %.1f deg (limits %.0f .. %.0f, red)", twin::AxisName(a),
                  vmin, vmax, lo[a] * kDeg, hi[a] * kDeg);
    const std::string y_label = std::string(twin::AxisName(a)) + " [deg]";
    panels.push_back(FramePicture(plot, 0.0, t_end, y_lo, y_hi, title, "time [s]", y_label, nullptr).image);
  }
  int panel_w = 0, panel_h = 0;
  for (const cv::Mat& p : panels) {
    panel_w = std::max(panel_w, p.cols);
    panel_h = std::max(panel_h, p.rows);
  }
  const int rows = (static_cast<int>(panels.size()) + cols - 1) / cols, header = 40;
  cv::Mat img(header + rows * panel_h, cols * panel_w, CV_8UC3, cv::Scalar(255, 255, 255));
  for (std::size_t i = 0; i < panels.size(); ++i) {
    const int c = static_cast<int>(i) % cols, r = static_cast<int>(i) / cols;
    panels[i].copyTo(img(cv::Rect(c * panel_w, header + r * panel_h, panels[i].cols, panels[i].rows)));
  }
  cv::putText(img, part_name + ": robot and positioner axis angles along the path (limits in red)", {10, 28},
              cv::FONT_HERSHEY_SIMPLEX, 0.8, cv::Scalar(0, 0, 0), 2);
  internal::WritePngAtomic(img, path);
}

}  // namespace waam::analysis
