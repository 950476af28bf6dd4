// viewer.html: the page template (analysis/data/viewer/) with three.js, OrbitControls and the data inlined, so the
// page needs no server and no network.
#include <string_view>

#include "analysis/viewer.h"
#include "models/core/data_dir.h"
#include "models/core/error.h"
#include "models/core/files.h"
#include "models/core/json_text.h"

namespace waam::analysis {
namespace fs = std::filesystem;

namespace {

constexpr const char* kThreeDir = "/usr/share/javascript/three";

// A script's text may not contain "</script" (it would end the element early): "<\/script" means the same in JS
// strings and regular expressions.
std::string ScriptSafe(std::string_view text) {
  std::string out;
  out.reserve(text.size() + text.size() / 64);
  std::size_t from = 0;
  for (std::size_t at = text.find("</"); at != std::string_view::npos; at = text.find("</", from)) {
    out.append(text.substr(from, at + 1 - from));
    out.append("\\");
    from = at + 1;
  }
  out.append(text.substr(from));
  return out;
}

// Replaces the one `marker` of `page` by `text`.
void Fill(std::string* page, std::string_view marker, const std::string& text) {
  const std::size_t at = page->find(marker);
  WAAM_DEMAND(at != std::string::npos);
  page->replace(at, marker.size(), text);
}

std::string ReadLibrary(const fs::path& path) {
  std::error_code ec;
  WAAM_THROW_UNLESS(fs::is_regular_file(path, ec),
                    path.string() << ": not found; viewer.html inlines three.js from the Debian package libjs-three "
                                     "(apt-get install libjs-three, or tools/install_deps.sh), or skip the "
                                     "pictures and the viewer with --no-images");
  return ReadFile(path);
}

}  // namespace

fs::path ThreeJsPath() { return fs::path(kThreeDir) / "three.min.js"; }
fs::path OrbitControlsPath() { return fs::path(kThreeDir) / "examples" / "js" / "controls" / "OrbitControls.js"; }

std::string ViewerPage(const nlohmann::json& data) {
  const std::string three = ReadLibrary(ThreeJsPath());
  const std::string orbit = ReadLibrary(OrbitControlsPath());
  const fs::path dir = DataDir() / "analysis" / "data" / "viewer";
  std::string page = ReadFile(dir / "viewer.html");
  const std::string script = ReadFile(dir / "viewer.js");
  Fill(&page, "/*WAAM_THREE_JS*/", ScriptSafe(three));
  Fill(&page, "/*WAAM_ORBIT_CONTROLS*/", ScriptSafe(orbit));
  Fill(&page, "/*WAAM_VIEWER_SHAPES_JS*/", ScriptSafe(ReadFile(dir / "viewer_shapes.js")));
  Fill(&page, "/*WAAM_VIEWER_JS*/", ScriptSafe(script));
  // JSON inside <script type="application/json">: "<\/" is the same JSON string, and no element ends early.
  Fill(&page, "/*WAAM_DATA*/", ScriptSafe(JsonText(data, -1)));
  return page;
}

ViewerSummary WriteViewer(const std::string& scenario_name, const twin::CellModel& cell,
                          const planner::CellKinematics& kin, const planner::Plan& plan,
                          const planner::TriangleMesh* target, const twin::CheckReport& report, const fs::path& path,
                          const ViewerBudget& budget) {
  ViewerSummary summary;
  const std::string page =
      ViewerPage(ViewerData(scenario_name, cell, kin, plan, target, report, budget, &summary));
  WriteFileAtomic(path, page);
  summary.bytes = page.size();
  return summary;
}

}  // namespace waam::analysis
