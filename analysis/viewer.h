// viewer.html of `waam check`: one self-contained page (three.js from Debian's libjs-three and the data inlined)
// that plays the checked motion of the cell in 3D with the path, the part growing and the violations.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "planner/mesh/triangle_mesh.h"
#include "planner/path/tool_path.h"
#include "twin/cell/cell_check.h"
#include "twin/deposition/bead_deposition.h"
#include "twin/scanner/deviation.h"
#include "twin/cell/mujoco_cell.h"

namespace waam::analysis {

// How much of a run the page carries, so that the largest scenario's page stays under about 30 MB.
struct ViewerBudget {
  std::size_t max_frames = 4000;         // animation frames (every k-th motion sample, plus the violations' samples)
  std::size_t max_path_points = 250000;  // plan points drawn as the path and its beads (every k-th beyond)
  std::size_t max_target_facets = 200000;  // target mesh facets (the ghost is left out beyond)
};

// What the page holds, as written to check.json under "viewer".
struct ViewerSummary {
  std::size_t frames = 0;       // animation frames
  std::size_t bodies = 0;       // cell bodies drawn
  std::size_t violations = 0;   // violation markers
  std::size_t path_points = 0;  // plan points drawn
  std::size_t beads = 0;        // planned bead segments
  std::size_t bytes = 0;        // size of the page
};

// The page's data (bodies, frames, path, beads, target, violations) as one JSON document with base64 Float32
// arrays. `target` may be null. Fills `summary` (its bytes excepted).
nlohmann::json ViewerData(const std::string& scenario_name, const twin::CellModel& cell,
                          const planner::CellKinematics& kin, const planner::Plan& plan,
                          const planner::TriangleMesh* target, const twin::CheckReport& report,
                          const ViewerBudget& budget, ViewerSummary* summary);

// The three.js files the page inlines, from Debian's libjs-three (r111, /usr/share/javascript/three).
std::filesystem::path ThreeJsPath();
std::filesystem::path OrbitControlsPath();

// The page around `data` (ViewerData): the template of <data dir>/analysis/data/viewer/ with three.js, its
// OrbitControls and the data inlined. Throws InputError naming the package when libjs-three is not installed.
std::string ViewerPage(const nlohmann::json& data);

// Writes viewer.html (atomically) for a checked plan; returns what it holds. Throws as ViewerPage.
ViewerSummary WriteViewer(const std::string& scenario_name, const twin::CellModel& cell,
                          const planner::CellKinematics& kin, const planner::Plan& plan,
                          const planner::TriangleMesh* target, const twin::CheckReport& report,
                          const std::filesystem::path& path, const ViewerBudget& budget = {});

// Where a written viewer.html keeps room for the deposited part (AddDepositToViewer).
inline constexpr std::string_view kViewerDepositMarker = "<!--WAAM_DEPOSIT-->";

// Adds the twin's deposit to the viewer.html at `page` (written by WriteViewer for the same plan): the occupied
// voxels merged into cubes of k^3 voxels, k the smallest that keeps at most `max_cells` cubes, each with its layer and
// the time metal first reached it; the page grows them as the torch goes. With `deviation` (may be null) each cube
// holding exposed faces gets the deviation of largest magnitude among them (mm) for the page's deviation colours.
// Rewrites the page atomically; returns the number of cubes. Throws InputError when the page has no room for a
// deposit (not a viewer, or added already).
std::size_t AddDepositToViewer(const std::filesystem::path& page, const twin::Depositor& depositor,
                               const twin::DeviationReport* deviation = nullptr, std::size_t max_cells = 150000);

// Where a written viewer.html keeps room for the thermal model's temperatures (AddThermalToViewer).
inline constexpr std::string_view kViewerThermalMarker = "<!--WAAM_THERMAL-->";

struct ThermalRunResult;

// Adds the thermal run's temperatures to the viewer.html at `page` (written by WriteViewer for the same plan): the
// metal cells of the model's grid on the surface of the part and the plate at the last layer's end, and each one's
// temperature at every layer's end (1 byte each, on one scale from the ambient temperature to the hottest; every
// k-th layer when cells x layers exceed `max_values`); the page colours the part by temperature at the slider's time,
// interpolating between layer ends, with a colour bar in degC. Rewrites the page atomically; returns the number of
// cells. Throws InputError when the page has no room for them (not a viewer, or added already).
std::size_t AddThermalToViewer(const std::filesystem::path& page, const ThermalRunResult& result,
                               std::size_t max_values = 8000000);

namespace internal {
// Standard base64 (RFC 4648 alphabet, '=' padding) of `bytes`.
std::string Base64(std::string_view bytes);
}  // namespace internal

}  // namespace waam::analysis
