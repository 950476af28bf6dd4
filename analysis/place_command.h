// `waam place`: search the cell layout (the part on the plate, the table's home rotation, the positioner's yaw, the
// arm's base) for one where the scenario's path passes the cell check with the largest smallest margin.
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "analysis/scenario.h"
#include "twin/cell/cell_check.h"

namespace waam::analysis {

struct PlaceOptions {
  std::filesystem::path scenario;      // scenario YAML
  std::filesystem::path out_dir;       // output directory (created if missing)
  std::vector<std::string> overrides;  // "key.path=value" scenario overrides (--set)
  bool quiet = false;                  // no progress bars
  bool images = true;                  // place_margin.png
  bool exhaustive = false;             // no pruning (coarse pass and resolution): the same answer, slower
};

// The searched variables, in this order in every Layout.
enum PlaceVariable { kPartX, kPartY, kPartZ, kPartYaw, kTableRotation, kPositionerYaw, kRobotX, kRobotY, kPlaceVars };
// The variable's name in place.json ("part_x_mm", ...), the same as its key in the `place:` section.
const char* PlaceVariableName(int variable);

using Layout = std::array<double, kPlaceVars>;

// The cell settings with a layout applied.
twin::CellSettings ApplyLayout(const twin::CellSettings& cell, const Layout& layout);
// The `--set` overrides that turn a scenario laid out as `current` into `layout` (cell.part.offset_mm=[x, y, z], ...,
// only the keys whose values differ); `robot_z_mm` is the arm base's height, which is not searched.
std::vector<std::string> LayoutOverrides(const Layout& layout, const Layout& current, double robot_z_mm);

// How a layout fared in one check.
struct LayoutScore {
  bool full = false;                   // the whole path at cell.checks.step_mm (else the coarse pass)
  std::size_t violations = 0;          // merged violations (check.json violation_count)
  std::size_t violating_samples = 0;   // checked samples with a violation (summed over the merged entries)
  std::string worst;                   // the worst violation: "kind subject" ("" when none)
  std::string worst_unit;
  double worst_value = 0.0;
  int worst_layer = 0;
  double min_joint_margin_deg = 0.0;  // over the arm's joints (check.json min_arm_margin_deg)
  double min_j5_deg = 0.0;
  double min_clearance_mm = 0.0;
  // The smallest margin over the path, each in excess of its violation threshold and scaled so 1 is comfortable:
  // min((arm joint margin - cell.checks.joint_margin_deg) / 10 deg, (|j5| - cell.checks.singularity_deg) / 10 deg,
  //     clearance / 10 mm). The clearance is capped at the 10 mm contact margin, so the margin is at most 1.
  double margin = 0.0;
  bool abandoned = false;  // the resolved motion's check stopped once proven worse than the fixed rule's (pruned)
  // The coarse check stopped once proven outside the layouts the whole path may check (branch and bound): `margin`
  // and the three minima are upper bounds (the smallest found when it stopped), `violating_samples` a lower bound,
  // `violations` and `worst` not known.
  bool bounded = false;
};

// The score of a check report of `cell` settings.
LayoutScore ScoreLayout(const twin::CheckReport& report, const twin::CellSettings& cell, bool full);
// True when `a` is the better layout: fewer violating samples, then the larger margin.
bool BetterLayout(const LayoutScore& a, const LayoutScore& b);

struct PlaceResult {
  bool feasible = false;                 // a layout passed the full check
  std::vector<std::vector<double>> values;  // per variable: the values searched (one: not searched)
  std::vector<Layout> layouts;           // every layout tried, in grid order (the last variable fastest)
  std::vector<LayoutScore> coarse;       // per layout: the coarse pass
  std::size_t coarse_bounded = 0;        // coarse checks stopped early (LayoutScore::bounded)
  std::vector<int> full_index;           // layouts that got the full check, in the order checked
  std::vector<LayoutScore> full;         // their full checks, same order
  int best = -1;                         // index into layouts of the best layout (a full check)
  LayoutScore best_score;
  double coarse_s = 0.0;                 // wall time of the coarse pass, s
  double full_s = 0.0;                   // wall time of the full checks, s
  double coarse_cpu_s = 0.0;             // CPU time of the process (all threads) over the coarse pass, s
  double full_cpu_s = 0.0;               // ... over the full checks, s
};

// Plans the scenario once and searches its `place:` ranges: every layout on the coarse pass (place.coarse_layers
// layers at coarse_step_mm with cell.resolve fixed, in parallel over layouts, in batches of 4 x finalists; from the
// second batch on, unless options.exhaustive, a layout's check stops once it is proven worse than the
// 4 x finalists-th best layout of the batches before, which the whole path can then never reach), then the best on
// the whole path with
// the scenario's cell.resolve, `finalists`
// at a time, until one passes or the coarse pass's passing layouts (at most 4 x finalists) are used up. Writes
// place.json, scenario.yaml (the scenario with the best layout and `base_dir` pointing back at its files) and
// place_margin.png. Throws InputError for a bad scenario or cell.
PlaceResult RunPlace(const PlaceOptions& options);

}  // namespace waam::analysis
