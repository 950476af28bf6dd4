// End-to-end tests of `waam fit` through the built executable, and of the committed default models.
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>

#include "models/bead/csw_model.h"
#include "models/bead/speed_height_model.h"
#include "models/bead/width_height_model.h"
#include "models/core/csv.h"
#include "models/core/error.h"
#include "models/fit/model_file.h"
#include "models/voids/void_length_model.h"
#include "tests/models/test_util.h"

namespace waam::models {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;

struct CliRun {
  int exit_code = -1;
  std::string output;  // stdout and stderr
};

CliRun Waam(const std::string& args) {
  const std::string command = std::string(WAAM_BINARY) + " " + args + " 2>&1";
  CliRun run;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return run;
  char buffer[4096];
  while (fgets(buffer, sizeof buffer, pipe) != nullptr) run.output += buffer;
  const int status = pclose(pipe);
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

std::string Data(const std::string& name) { return waam::testing::ModelsData(name).string(); }

TEST(FitCliTest, CswWritesAModelThatLoadsBack) {
  const fs::path out = waam::testing::TestDir() / "csw.json";
  const CliRun run = Waam("fit csw " + Data("dai2020_csw_table1.csv") + " -o " + out.string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_THAT(run.output, HasSubstr("r2       = 0.9802"));
  EXPECT_THAT(run.output, HasSubstr("rmse_dof = 0.2774"));
  const CswModel model = CswModel::Load(out);
  EXPECT_NEAR(model.fit().stats.r2, 0.9802, 5e-5);
  EXPECT_EQ(model.fit().data.provenance.size(), 3u) << "the CSV's '#' lines travel with the model";
}

TEST(FitCliTest, SpeedRangeExcludesRowsAndSaysWhich) {
  const fs::path out = waam::testing::TestDir() / "wh.json";
  const CliRun run = Waam("fit width-height " + Data("nguyen2022_table18_bead_vs_speed.csv") +
                       " --speed-range 150 900 -o " + out.string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_THAT(run.output, HasSubstr("excluded: line 10 (100 mm/min)"));
  EXPECT_EQ(WidthHeightModel::Load(out).fit().stats.n, 16u);
}

TEST(FitCliTest, SpeedRangeTakesACommaSeparatedPair) {
  const fs::path out = waam::testing::TestDir() / "wh_comma.json";
  const CliRun run = Waam("fit width-height " + Data("nguyen2022_table18_bead_vs_speed.csv") +
                          " --speed-range 150,900 -o " + out.string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_EQ(WidthHeightModel::Load(out).fit().stats.n, 16u) << "the same rows as --speed-range 150 900";
}

TEST(FitCliTest, VoidLengthPrintsCrossValidationAndHoldOut) {
  const fs::path out = waam::testing::TestDir() / "void.json";
  const CliRun run = Waam("fit void-length " + Data("nguyen2022_appendixA1_junction_voids.csv") +
                       " --hidden 4 --restarts 1 --folds 3 -q -o " + out.string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_THAT(run.output, HasSubstr("3-fold cross-validation"));
  EXPECT_THAT(run.output, HasSubstr("F7"));
  std::ifstream in(out);
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["holdout"].size(), 3u);
  EXPECT_TRUE(j["cross_validation"]["network"]["cv_mae_mm"].is_number());
  EXPECT_TRUE(j["cross_validation"]["baseline"]["cv_share_under_tolerance"].is_number());
  EXPECT_EQ(LoadVoidLengthModel(out)->kind(), "network");
}

// --angle-order takes the model file's names (as_given, sorted_descending) and its first spelling `sorted`; the file
// gets the model's name whichever was given.
TEST(FitCliTest, AngleOrderTakesTheModelFilesNames) {
  const fs::path dir = waam::testing::TestDir();
  for (const std::string order : {"sorted_descending", "sorted"}) {
    const fs::path out = dir / ("void_" + order + ".json");
    const CliRun run = Waam("fit void-length " + Data("nguyen2022_appendixA1_junction_voids.csv") +
                            " --hidden 2 --restarts 1 --folds 2 -q --angle-order " + order + " -o " +
                            out.string());
    ASSERT_EQ(run.exit_code, 0) << order << ": " << run.output;
    std::ifstream in(out);
    EXPECT_EQ(nlohmann::json::parse(in)["params"]["angle_order"], "sorted_descending") << order;
  }
  const CliRun bad = Waam("fit void-length " + Data("nguyen2022_appendixA1_junction_voids.csv") +
                          " --angle-order descending -o " + (dir / "x.json").string());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_THAT(bad.output, HasSubstr("--angle-order 'descending': must be as_given or sorted_descending (or sorted)"));
  EXPECT_FALSE(fs::exists(dir / "x.json"));
}

TEST(FitCliTest, BadCsvGivesOneLineNamingFileLineAndColumn) {
  const fs::path dir = waam::testing::TestDir();
  const fs::path bad = waam::testing::WriteText(
      dir, "bad.csv", "travel_speed_mm_per_min,curvature_radius_mm,width_mm\n300,30,12.5\n600,abc,9.8\n");
  CliRun run = Waam("fit csw " + bad.string() + " -o " + (dir / "x.json").string());
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.output, HasSubstr("waam: error: " + bad.string() + ":3: column 'curvature_radius_mm': 'abc' is not a number"));
  EXPECT_FALSE(fs::exists(dir / "x.json")) << "no output on bad input";

  run = Waam("fit csw " + bad.string() + " --columns width=w -o " + (dir / "x.json").string());
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.output, HasSubstr(bad.string() + ": no column 'w'"));

  run = Waam("fit csw " + bad.string() + " --columns colour=w -o " + (dir / "x.json").string());
  EXPECT_THAT(run.output, HasSubstr("unknown role 'colour' for csw (roles: speed, radius, width)"));

  const fs::path nan = waam::testing::WriteText(dir, "nan.csv", "height_mm,width_mm\n1.0,3.0\nNaN,4.0\n");
  run = Waam("fit width-height " + nan.string() + " -o " + (dir / "x.json").string());
  EXPECT_THAT(run.output, HasSubstr(nan.string() + ":3: column 'height_mm': 'NaN' is not a number"));

  const fs::path few = waam::testing::WriteText(dir, "few.csv", "travel_speed_mm_per_min,height_mm\n300,1.5\n600,1.0\n");
  run = Waam("fit speed-height " + few.string() + " -o " + (dir / "x.json").string());
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.output, HasSubstr(few.string() + ": 2 rows: the power law has 2 parameters and needs at least 3"));
}

TEST(FitCliTest, HelpExplainsModelsAndColumns) {
  const CliRun run = Waam("fit --help");
  EXPECT_EQ(run.exit_code, 0);
  EXPECT_THAT(run.output, HasSubstr("w = m v^(-1/3) + p/r + t"));
  EXPECT_THAT(run.output, HasSubstr("radius=curvature_radius_mm"));
  EXPECT_THAT(run.output, HasSubstr("--loo"));
}

// The defaults the planner and twin load are `waam fit` outputs of the committed tables, not typed-in numbers:
// refitting with the options recorded in the file gives the same parameters.
TEST(DefaultModelsTest, BeadDefaultsAreFitsOfTheCommittedTables) {
  const CswModel csw = CswModel::Load(DefaultModelPath("csw"));
  const CsvTable t1 = CsvTable::Read(fs::path(WAAM_SOURCE_DIR) / csw.fit().data.file);
  const CswFit refit = FitCsw({t1.Numbers("travel_speed_mm_per_min"), t1.Numbers("curvature_radius_mm"),
                               t1.Numbers("width_mm")},
                              csw.fit().data);
  EXPECT_NEAR(refit.model.params().m, csw.params().m, 1e-9);
  EXPECT_NEAR(refit.model.params().t, csw.params().t, 1e-9);

  const SpeedHeightModel sh = SpeedHeightModel::Load(DefaultModelPath("speed_height"));
  const WidthHeightModel wh = WidthHeightModel::Load(DefaultModelPath("width_height"));
  EXPECT_EQ(sh.fit().stats.n, 16u);
  EXPECT_EQ(wh.degree(), 4);
  const BeadSetpoint setpoint = SetpointForHeight(sh, wh, 1.8);
  EXPECT_EQ(setpoint.speed.clamp, SpeedClamp::kNone);
  EXPECT_GT(setpoint.width_mm, 5.0);
  EXPECT_LT(setpoint.width_mm, 6.5) << "Table 18: h = 1.79 mm came with w = 5.72 mm";
}

TEST(DefaultModelsTest, VoidLengthDefaultLoads) {
  const std::unique_ptr<VoidLengthModel> model = LoadVoidLengthModel(DefaultModelPath("void_length"));
  EXPECT_EQ(model->kind(), "network");
  EXPECT_EQ(model->fit().stats.n, 63u);
  const double f8 = model->PredictMm(Junction{4, {165, 15, 165, 15}});
  EXPECT_NEAR(f8, 28.3, 2.0) << "F8 is in the training set (measured 28.3 mm)";
}

TEST(DefaultModelsTest, WrongModelKindIsNamed) {
  try {
    CswModel::Load(DefaultModelPath("speed_height"));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("speed_height.json: holds a 'speed_height' model, expected 'csw'"));
  }
}

}  // namespace
}  // namespace waam::models
