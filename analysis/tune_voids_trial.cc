// One tune-voids trial: the junction's neighbourhood planned with a given shift, deposited in the voxel twin and
// milled in horizontal cuts as the dissertation measured its junctions (003 sec. 4.4.2.1).
#include <algorithm>
#include <cmath>
#include <string_view>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "analysis/png_file.h"
#include "analysis/tune_voids_internal.h"
#include "models/core/files.h"
#include "twin/deposition/bead_deposition.h"
#include "twin/scanner/target_volume.h"
#include "twin/scanner/voids.h"

namespace waam::analysis::internal {
namespace {

using Vec = Eigen::Vector2d;

// Liang-Barsky clip of segment a-b to the square; false if nothing is left.
bool ClipToSquare(const JunctionCrop& crop, Vec* a, Vec* b) {
  const Vec lo = crop.centre - Vec::Constant(crop.half_mm), hi = crop.centre + Vec::Constant(crop.half_mm);
  double t0 = 0.0, t1 = 1.0;
  const Vec d = *b - *a;
  for (int axis = 0; axis < 2; ++axis) {
    for (double sign : {-1.0, 1.0}) {
      const double p = sign * d[axis];
      const double q = sign > 0 ? hi[axis] - (*a)[axis] : (*a)[axis] - lo[axis];
      if (std::abs(p) < 1e-15) {
        if (q < 0) return false;
        continue;
      }
      const double t = q / p;
      if (p < 0) t0 = std::max(t0, t);
      else t1 = std::min(t1, t);
    }
  }
  if (t0 >= t1) return false;
  const Vec a0 = *a;
  *a = a0 + t0 * d;
  *b = a0 + t1 * d;
  return true;
}

bool InSlice(const std::vector<planner::PolygonWithHoles>& slice, const Vec& p) {
  for (const planner::PolygonWithHoles& region : slice) {
    if (!planner::PointInRing(p, region.outer)) continue;
    bool hole = false;
    for (const planner::Ring& h : region.holes) hole = hole || planner::PointInRing(p, h);
    if (!hole) return true;
  }
  return false;
}

void WriteSectionPicture(const twin::VoxelGrid& grid, const twin::TargetVolume& target, int kz,
                         const std::filesystem::path& path) {
  const Eigen::Vector3i size = target.size();
  cv::Mat image(size.y(), size.x(), CV_8UC3, cv::Scalar(255, 255, 255));
  for (int j = 0; j < size.y(); ++j) {
    for (int i = 0; i < size.x(); ++i) {
      const twin::VoxelIndex v(target.lo().x() + i, target.lo().y() + j, kz);
      cv::Vec3b colour(255, 255, 255);                              // outside the part: white
      if (grid.Occupied(v)) colour = cv::Vec3b(150, 150, 150);      // metal: grey
      else if (target.Inside(v)) colour = cv::Vec3b(40, 40, 220);   // empty inside the part: red (BGR)
      image.at<cv::Vec3b>(size.y() - 1 - j, i) = colour;
    }
  }
  cv::Mat big;
  cv::resize(image, big, cv::Size(), 4.0, 4.0, cv::INTER_NEAREST);
  internal::WritePngAtomic(big, path);
}

}  // namespace

planner::Plan TrialPlan(const planner::Plan& base, int layers, const planner::VoidFiller& filler,
                        const JunctionCrop& crop) {
  planner::Plan plan;
  plan.name = base.name + "_junction";
  for (int k = 0; k < layers && k < static_cast<int>(base.layers.size()); ++k) {
    const planner::LayerPath& in = base.layers[k];
    std::vector<planner::Move2D> moves;
    for (const planner::PathPoint& p : in.points) moves.push_back({p.p_P.head<2>(), p.weld});
    moves = filler.Apply(in.slice, moves, k, nullptr);
    planner::LayerPath layer;
    layer.index = k;
    layer.z_mm = in.z_mm;
    layer.slice = in.slice;
    planner::PathPoint proto = in.points.empty() ? planner::PathPoint{} : in.points.back();
    auto add = [&](const Vec& p, bool weld) {
      proto.p_P = Eigen::Vector3d(p.x(), p.y(), in.z_mm);
      proto.weld = weld;
      layer.points.push_back(proto);
    };
    for (std::size_t i = 1; i < moves.size(); ++i) {
      if (!moves[i].weld) continue;
      Vec a = moves[i - 1].p, b = moves[i].p;
      if (!ClipToSquare(crop, &a, &b)) continue;
      // A piece continues the current pass only if it starts where the last one ended.
      const bool continues = !layer.points.empty() && (layer.points.back().p_P.head<2>() - a).norm() < 1e-9;
      if (!continues) add(a, false);
      add(b, true);
    }
    plan.layers.push_back(std::move(layer));
  }
  return plan;
}

TuneTrial SimulateTrial(const planner::Plan& plan, const twin::SimulationSettings& settings,
                        double rapid_speed_mm_s, const JunctionCrop& crop, const std::filesystem::path& picture) {
  const twin::Depositor deposit = twin::DepositPlan(plan, settings, rapid_speed_mm_s, nullptr);
  const double v = settings.voxel_mm;
  // The target: each layer's slice from the previous layer's top to its own, over the crop square.
  const double top_z = plan.layers.back().z_mm;
  const twin::VoxelIndex lo(static_cast<int>(std::floor((crop.centre.x() - crop.half_mm) / v)),
                            static_cast<int>(std::floor((crop.centre.y() - crop.half_mm) / v)), 0);
  const twin::VoxelIndex hi(static_cast<int>(std::floor((crop.centre.x() + crop.half_mm) / v)),
                            static_cast<int>(std::floor((crop.centre.y() + crop.half_mm) / v)),
                            static_cast<int>(std::floor(top_z / v)));
  twin::TargetVolume target(v, lo, hi);
  for (int k = lo.z(); k <= hi.z(); ++k) {
    const double z = (k + 0.5) * v;
    const auto layer = std::find_if(plan.layers.begin(), plan.layers.end(),
                                    [&](const planner::LayerPath& l) { return z < l.z_mm; });
    if (layer == plan.layers.end()) continue;
    for (int j = lo.y(); j <= hi.y(); ++j) {
      for (int i = lo.x(); i <= hi.x(); ++i) {
        if (InSlice(layer->slice, Vec((i + 0.5) * v, (j + 0.5) * v))) target.SetInside(twin::VoxelIndex(i, j, k), true);
      }
    }
  }
  // Milled sections (sec. 4.4.2.1) every voxel from the first layer up to the bottom of the top layer (the top layer
  // has nothing on it yet, so its gaps are the surface, not voids).
  TuneTrial trial;
  const double below_top = plan.layers.size() >= 2 ? plan.layers[plan.layers.size() - 2].z_mm : top_z;
  const int k_top = static_cast<int>(std::floor(below_top / v));
  for (int k = 1; k < k_top; ++k) {
    for (const twin::EmptyRegion& r : twin::SectionVoids(deposit.grid(), target, (k + 0.5) * v)) {
      if ((r.centroid_mm.head<2>() - crop.centre).norm() > crop.reach_mm) continue;
      trial.void_volume_mm3 += static_cast<double>(r.voxels) * v * v * v;  // one voxel-thick cut
      trial.void_length_mm = std::max(trial.void_length_mm, r.length_mm);
    }
  }
  // Peak: the highest column top within reach against the crowns of the walls around it (the 90th percentile of
  // their column tops: bead flanks and the arc starts at the crop edge are left out).
  const int nx = hi.x() - lo.x() + 1, ny = hi.y() - lo.y() + 1;
  std::vector<int> top(static_cast<std::size_t>(nx) * ny, -1);
  deposit.grid().ForEach([&](const twin::VoxelIndex& idx, const twin::VoxelData&) {
    const int i = idx.x() - lo.x(), j = idx.y() - lo.y();
    if (i < 0 || j < 0 || i >= nx || j >= ny) return;
    int& t = top[static_cast<std::size_t>(j) * nx + i];
    t = std::max(t, idx.z() + 1);
  });
  int near_top = 0;
  std::vector<int> around;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const int t = top[static_cast<std::size_t>(j) * nx + i];
      if (t < 0) continue;
      const double d = (Vec((lo.x() + i + 0.5) * v, (lo.y() + j + 0.5) * v) - crop.centre).norm();
      if (d <= crop.reach_mm) near_top = std::max(near_top, t);
      else if (d <= 2.0 * crop.reach_mm) around.push_back(t);
    }
  }
  if (!around.empty()) {
    const std::size_t p90 = around.size() * 9 / 10;
    std::nth_element(around.begin(), around.begin() + static_cast<std::ptrdiff_t>(p90), around.end());
    trial.peak_height_mm = (near_top - around[p90]) * v;
  }
  if (!picture.empty()) WriteSectionPicture(deposit.grid(), target, std::max(1, k_top / 2), picture);
  return trial;
}

}  // namespace waam::analysis::internal
