// Tests of cell.resolve optimise: a wall whose fixed torch rotation drives J6 past its limit (a cell whose J6 range
// leaves the fixed rule's angles out) passes once the torch's spin is chosen, with the same weld points and tool axes;
// the choice is the same on every run and thread count; a path the fixed rule serves keeps it; pruning the resolved
// check by the fixed rule's margin changes no report.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include <unistd.h>

#include <gtest/gtest.h>

#include "models/core/files.h"
#include "analysis/cell_files.h"
#include "models/core/numbers.h"
#include "models/core/parallel.h"
#include "tests/twin/test_plans.h"
#include "twin/cell/cell_check.h"
#include "twin/cell/mujoco_cell.h"

namespace waam::twin {
namespace cell_resolve_test {
using analysis::LoadCell;
namespace fs = std::filesystem;

// The built-in cell with J6's range set to [lo, hi] deg, written to a temporary file.
fs::path CellWithJ6Range(double lo, double hi) {
  const std::string text = ReadFile(analysis::BuiltinCellPath());
  const std::string changed = std::regex_replace(
      text, std::regex(R"(<joint name="j6" axis="-1 0 0" range="-360 360"/>)"),
      "<joint name=\"j6\" axis=\"-1 0 0\" range=\"" + std::to_string(lo) + " " + std::to_string(hi) + "\"/>");
  EXPECT_NE(changed, text) << "the built-in cell's j6 line changed; update this test";
  const fs::path path = fs::temp_directory_path() / ("cell_resolve_test_" + std::to_string(getpid()) + ".xml");
  std::ofstream(path) << changed;
  return path;
}

std::size_t Count(const CheckReport& r, ViolationKind kind, const std::string& joint) {
  std::size_t n = 0;
  for (const CheckViolation& v : r.violations) n += v.kind == kind && v.joint == joint;
  return n;
}

TEST(CellResolve, SpinTakesJ6BackInsideItsLimitsWithTheSameWeld) {
  const planner::Plan wall = testing::RectangleWall(4, 120.0, 40.0, 2.0, 8.0);
  // Where J6 stands under the fixed rule on the unrestricted cell.
  CellSettings settings;
  settings.resolve = CellResolve::kFixed;
  const CheckReport free = CheckPlan(LoadCell(settings), wall, settings, 100.0, nullptr);
  ASSERT_TRUE(free.ok);
  double lo = 1e9, hi = -1e9;
  for (const planner::CellSample& s : free.motion) {
    lo = std::min(lo, s.q[5] * kDeg);
    hi = std::max(hi, s.q[5] * kDeg);
  }
  // A J6 range starting 40 deg past the fixed rule's largest angle: the fixed rule fails, a spin of 45-90 deg does
  // not (the torch is coaxial with the flange, so the spin moves J6 one for one).
  const fs::path file = CellWithJ6Range(hi + 40.0, hi + 40.0 + (hi - lo) + 60.0);
  settings.mjcf = file;
  const CellModel cell = LoadCell(settings);
  const CheckReport fixed = CheckPlan(cell, wall, settings, 100.0, nullptr);
  EXPECT_GT(Count(fixed, ViolationKind::kJointLimit, "j6"), 0u);

  settings.resolve = CellResolve::kOptimise;
  const CheckReport resolved = CheckPlan(cell, wall, settings, 100.0, nullptr);
  EXPECT_TRUE(resolved.ok) << resolved.violations.size() << " violations, first " << NameOf(resolved.violations[0].kind);
  EXPECT_FALSE(resolved.resolve.kept_fixed);
  EXPECT_GT(resolved.resolve.before.violating_samples, 0u);
  EXPECT_EQ(resolved.resolve.after.violating_samples, 0u);
  // The weld is the same: the TCP and the torch axis of every sample.
  ASSERT_EQ(resolved.motion.size(), fixed.motion.size());
  for (std::size_t i = 0; i < fixed.motion.size(); ++i) {
    const planner::CellSample& a = fixed.motion[i];
    const planner::CellSample& b = resolved.motion[i];
    EXPECT_EQ(a.p_P, b.p_P);
    EXPECT_LT((a.X_WT.translation() - b.X_WT.translation()).norm(), 1e-9);
    EXPECT_LT((a.X_WT.linear().col(2) - b.X_WT.linear().col(2)).norm(), 1e-12);
  }
  for (double spin : resolved.resolve.layer_spin_deg) EXPECT_GE(std::abs(spin), 40.0);

  // Deterministic: the same spins again, and on one thread.
  const CheckReport again = CheckPlan(cell, wall, settings, 100.0, nullptr);
  EXPECT_EQ(again.resolve.layer_spin_deg, resolved.resolve.layer_spin_deg);
  SetThreadCount(1);
  const CheckReport one = CheckPlan(cell, wall, settings, 100.0, nullptr);
  SetThreadCount(0);
  EXPECT_EQ(one.resolve.layer_spin_deg, resolved.resolve.layer_spin_deg);
  fs::remove(file);
}

TEST(CellResolve, APathTheFixedRuleServesKeepsItsMotion) {
  // The default is optimise; a path whose fixed-rule margins are all comfortable keeps that motion untouched.
  const planner::Plan wall = testing::RectangleWall(3, 100.0, 30.0, 2.0, 8.0);
  CellSettings settings;
  EXPECT_EQ(settings.resolve, CellResolve::kOptimise);
  const CellModel cell = LoadCell(settings);
  const CheckReport r = CheckPlan(cell, wall, settings, 100.0, nullptr);
  EXPECT_TRUE(r.ok);
  EXPECT_TRUE(r.resolve.kept_fixed);
  EXPECT_GE(CheckMargin(r.resolve.after, settings), 1.0);
  settings.resolve = CellResolve::kFixed;
  const CheckReport f = CheckPlan(cell, wall, settings, 100.0, nullptr);
  ASSERT_EQ(f.motion.size(), r.motion.size());
  for (std::size_t i = 0; i < f.motion.size(); ++i) EXPECT_EQ(f.motion[i].q, r.motion[i].q);
}

// The pruned resolution (the resolved motion's check stopped once proven worse than the fixed rule's) gives the same
// report as the whole check, on J6 ranges that leave the fixed rule a small margin, on one and four threads.
TEST(CellResolve, PruningByTheFixedRulesMarginGivesTheSameReport) {
  const planner::Plan wall = testing::RectangleWall(2, 100.0, 30.0, 2.0, 8.0);
  CellSettings settings;
  settings.resolve = CellResolve::kFixed;
  const CheckReport free = CheckPlan(LoadCell(settings), wall, settings, 100.0, nullptr);
  double lo = 1e9, hi = -1e9;
  for (const planner::CellSample& s : free.motion) {
    lo = std::min(lo, s.q[5] * kDeg);
    hi = std::max(hi, s.q[5] * kDeg);
  }
  settings.resolve = CellResolve::kOptimise;
  for (double pad : {3.0, 6.0, 9.0}) {
    const fs::path file = CellWithJ6Range(lo - pad, hi + pad);
    settings.mjcf = file;
    const CellModel cell = LoadCell(settings);
    for (int threads : {1, 4}) {
      SetThreadCount(threads);
      settings.prune = false;
      const CheckReport whole = CheckPlan(cell, wall, settings, 100.0, nullptr);
      settings.prune = true;
      const CheckReport pruned = CheckPlan(cell, wall, settings, 100.0, nullptr);
      SetThreadCount(0);
      EXPECT_FALSE(whole.resolve.abandoned);
      EXPECT_EQ(pruned.resolve.kept_fixed, whole.resolve.kept_fixed) << "pad " << pad;
      EXPECT_EQ(pruned.resolve.layer_spin_deg, whole.resolve.layer_spin_deg) << "pad " << pad;
      EXPECT_EQ(CheckMargin(pruned.resolve.after, settings), CheckMargin(whole.resolve.after, settings));
      EXPECT_EQ(pruned.violations.size(), whole.violations.size());
      EXPECT_EQ(pruned.min_clearance_mm, whole.min_clearance_mm);
      ASSERT_EQ(pruned.motion.size(), whole.motion.size());
      for (std::size_t i = 0; i < whole.motion.size(); ++i) EXPECT_EQ(pruned.motion[i].q, whole.motion[i].q);
    }
    fs::remove(file);
  }
}

}  // namespace cell_resolve_test
}  // namespace waam::twin
