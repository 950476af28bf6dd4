// The layer picture draws the slice and the path in the slice plane, whatever the build direction.
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <tuple>
#include <utility>

#include <gtest/gtest.h>

#include "analysis/picture_frame.h"
#include "analysis/plan_command.h"
#include "models/core/files.h"

namespace waam::analysis {
namespace {
namespace fs = std::filesystem;

// Width and height (px) from a PNG's IHDR chunk.
std::pair<std::uint32_t, std::uint32_t> PngSize(const fs::path& file) {
  const std::string bytes = ReadFile(file);
  EXPECT_GE(bytes.size(), 24u);
  auto be32 = [&](std::size_t at) {
    std::uint32_t v = 0;
    for (std::size_t k = 0; k < 4; ++k) v = (v << 8) | static_cast<unsigned char>(bytes[at + k]);
    return v;
  };
  return {be32(16), be32(20)};
}

// A sideways layer (build direction -x, as a propeller blade's): a 40 mm square slice in its plane at x = 100 mm
// and a weld path round it. Drawn in the part's XY, the path would sit 100 mm from the slice and the picture would
// be wide; drawn in the slice plane, both fill the same square.
TEST(LayerPng, SidewaysLayerIsDrawnInItsSlicePlane) {
  planner::LayerPath layer;
  layer.build_dir_P = -Eigen::Vector3d::UnitX();
  layer.slice = {{{{0, 0}, {40, 0}, {40, 40}, {0, 40}}, {}}};
  layer.slice_axes_P.col(0) = Eigen::Vector3d::UnitY();
  layer.slice_axes_P.col(1) = Eigen::Vector3d::UnitZ();
  layer.slice_origin_P = Eigen::Vector3d(100, 0, 0);
  for (const auto& [y, z, weld] : {std::tuple{3.0, 3.0, false}, {37.0, 3.0, true}, {37.0, 37.0, true},
                                   {3.0, 37.0, true}, {3.0, 3.0, true}}) {
    planner::PathPoint p;
    p.p_P = Eigen::Vector3d(100, y, z);
    p.bead_width_mm = 6;
    p.weld = weld;
    layer.points.push_back(p);
  }
  const fs::path dir = fs::temp_directory_path() / ("waam_layer_png_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  WriteLayerPng(layer, "square", dir / "sideways.png");
  const auto [w, h] = PngSize(dir / "sideways.png");
  const cv::Size margins = FrameMargins(true);  // title, axes and colour bar around the plot
  EXPECT_EQ(w - margins.width, h - margins.height) << "slice and path overlay in a square plot";

  layer.slice_in_plane = false;  // a cone layer: the path seen from +z (a line along y at x = 100), no slice
  WriteLayerPng(layer, "square", dir / "curved.png");
  const auto [wc, hc] = PngSize(dir / "curved.png");
  EXPECT_EQ(hc - margins.height, 800) << "only the path, edge-on: its length fills the plot's height";
  EXPECT_LT(wc, 800) << "only the path, edge-on";
  fs::remove_all(dir);
}

}  // namespace
}  // namespace waam::analysis
