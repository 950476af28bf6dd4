// Small hand-built plans for the cell tests: a rectangular wall of a few layers in the part frame.
#pragma once

#include "planner/path/tool_path.h"

namespace waam::twin::testing {

// `layers` layers of a `length` x `width` mm rectangle contour centred on the part origin, `height` mm per layer,
// one path point per corner (weld on), welded at `speed_mm_s`.
inline planner::Plan RectangleWall(int layers, double length, double width, double height, double speed_mm_s) {
  planner::Plan plan;
  plan.name = "rectangle_wall";
  for (int l = 0; l < layers; ++l) {
    planner::LayerPath layer;
    layer.index = l;
    layer.z_mm = height * (l + 1);
    const double x = 0.5 * length, y = 0.5 * width, z = layer.z_mm;
    const Eigen::Vector3d corners[5] = {{-x, -y, z}, {x, -y, z}, {x, y, z}, {-x, y, z}, {-x, -y, z}};
    for (int i = 0; i < 5; ++i) {
      planner::PathPoint p;
      p.p_P = corners[i];
      p.bead_width_mm = 6.0;
      p.bead_height_mm = height;
      p.speed_mm_s = speed_mm_s;
      p.weld = i > 0;
      layer.points.push_back(p);
    }
    plan.layers.push_back(layer);
  }
  return plan;
}

}  // namespace waam::twin::testing
