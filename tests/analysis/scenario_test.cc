// Tests of scenario loading: valid files load, every malformed one is refused with the key and line named.
#include "analysis/scenario.h"

#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "models/core/error.h"

namespace waam::planner {
namespace {
// The twin's settings types (these tests read whole scenario files, analysis::LoadScenario).
using twin::Blend;
using twin::CurvatureWidth;
using twin::PositionerFollow;
using twin::StartWetting;
using twin::StopCrater;
namespace fs = std::filesystem;
using ::testing::HasSubstr;

class ScenarioTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("waam_scenario_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_ / "meshes" / "adir.stl");
    std::ofstream(dir_ / "meshes" / "part.stl") << "solid x\nendsolid x\n";
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path Write(const std::string& text) {
    const fs::path file = dir_ / "s.yaml";
    std::ofstream(file) << text;
    return file;
  }

  // Loads `text` and returns the InputError message, or fails if it loads.
  std::string ErrorOf(const std::string& text) {
    try {
      analysis::LoadScenario(Write(text));
    } catch (const InputError& e) {
      return e.what();
    }
    ADD_FAILURE() << "expected an InputError for:\n" << text;
    return "";
  }

  static std::string Valid(const std::string& part = "  generator: {type: box, size_mm: [40, 30, 10]}\n",
                           const std::string& extra = "") {
    return "name: demo\npart:\n" + part +
           "slicing:\n  type: planar\n  layer_height_mm: 1.5\n"
           "path:\n  pattern: continuous\n  bead_width_mm: 6\n  overlap_model: proposed\n  zigzag_angle_deg: auto\n"
           "process:\n  travel_speed_mm_min: 400\n  wire_feed_mm_min: 3200\n" +
           extra;
  }

  fs::path dir_;
};

TEST_F(ScenarioTest, ValidScenarioLoads) {
  const analysis::Scenario s = analysis::LoadScenario(Write(Valid()));
  EXPECT_EQ(s.name, "demo");
  EXPECT_EQ(s.part.generator, planner::PartGenerator::kBox);
  ASSERT_EQ(s.part.params.at("size_mm").size(), 3u);
  EXPECT_DOUBLE_EQ(s.part.params.at("size_mm")[1], 30.0);
  EXPECT_DOUBLE_EQ(s.slicing.layer_height_mm, 1.5);
  EXPECT_EQ(NameOf(s.path.pattern), "continuous");
  EXPECT_TRUE(s.path.zigzag_angle_auto);
  EXPECT_DOUBLE_EQ(s.process.travel_speed_mm_min, 400.0);
}

TEST_F(ScenarioTest, MeshPathIsResolvedAgainstTheScenarioFolder) {
  const analysis::Scenario s = analysis::LoadScenario(Write(Valid("  mesh: meshes/part.stl\n")));
  EXPECT_EQ(s.part.mesh_path, (dir_ / "meshes" / "part.stl").lexically_normal());
}

TEST_F(ScenarioTest, ExplicitZigzagAngle) {
  std::string text = Valid();
  text.replace(text.find("zigzag_angle_deg: auto"), 22, "zigzag_angle_deg: 30");
  const analysis::Scenario s = analysis::LoadScenario(Write(text));
  EXPECT_FALSE(s.path.zigzag_angle_auto);
  EXPECT_DOUBLE_EQ(s.path.zigzag_angle_deg, 30.0);
}

TEST_F(ScenarioTest, NegativeLayerHeightNamesKeyAndLine) {
  std::string text = Valid();
  text.replace(text.find("layer_height_mm: 1.5"), 20, "layer_height_mm: -1");
  const std::string message = ErrorOf(text);
  EXPECT_THAT(message, HasSubstr("s.yaml:6: slicing.layer_height_mm = -1: must be in"));
}

TEST_F(ScenarioTest, ZeroBeadWidthIsRefused) {
  std::string text = Valid();
  text.replace(text.find("bead_width_mm: 6"), 16, "bead_width_mm: 0");
  EXPECT_THAT(ErrorOf(text), HasSubstr("path.bead_width_mm = 0: must be in"));
}

TEST_F(ScenarioTest, RetractDefaultsTo15MmAndANegativeOneIsRefused) {
  EXPECT_DOUBLE_EQ(analysis::LoadScenario(Write(Valid())).path.retract_mm, 15.0);
  std::string text = Valid();
  text.replace(text.find("bead_width_mm: 6"), 16, "bead_width_mm: 6\n  retract_mm: 0");
  EXPECT_DOUBLE_EQ(analysis::LoadScenario(Write(text)).path.retract_mm, 0.0) << "0 = the planners' straight rapids";
  text.replace(text.find("retract_mm: 0"), 13, "retract_mm: -5");
  EXPECT_THAT(ErrorOf(text), HasSubstr("path.retract_mm = -5: must be in"));
}

TEST_F(ScenarioTest, WrongTypeIsRefused) {
  std::string text = Valid();
  text.replace(text.find("travel_speed_mm_min: 400"), 24, "travel_speed_mm_min: fast");
  EXPECT_THAT(ErrorOf(text), HasSubstr("process.travel_speed_mm_min = 'fast': must be a number"));
}

TEST_F(ScenarioTest, UnknownPatternListsTheChoices) {
  std::string text = Valid();
  text.replace(text.find("pattern: continuous"), 19, "pattern: wobble");
  EXPECT_THAT(ErrorOf(text), HasSubstr("path.pattern = 'wobble': unknown value, expected one of contour, zigzag, "
                                       "hybrid, continuous, eulerian, spiral"));
}

TEST_F(ScenarioTest, UnknownKeyIsRefusedWithItsPath) {
  EXPECT_THAT(ErrorOf(Valid("  generator: {type: box}\n", "colour: red\n")), HasSubstr("colour: unknown key"));
  std::string text = Valid();
  text.replace(text.find("  type: planar\n"), 15, "  type: planar\n  layer_hieght_mm: 2\n");
  EXPECT_THAT(ErrorOf(text), HasSubstr("slicing.layer_hieght_mm: unknown key"));
}

TEST_F(ScenarioTest, MissingMeshFileIsNamed) {
  EXPECT_THAT(ErrorOf(Valid("  mesh: meshes/missing.stl\n")), HasSubstr("missing.stl not found"));
}

TEST_F(ScenarioTest, MeshPathThatIsADirectoryIsRefused) {
  EXPECT_THAT(ErrorOf(Valid("  mesh: meshes/adir.stl\n")), HasSubstr("is a directory, expected a file (mesh file)"));
}

TEST_F(ScenarioTest, MeshAndGeneratorTogetherAreRefused) {
  EXPECT_THAT(ErrorOf(Valid("  mesh: meshes/part.stl\n  generator: {type: box}\n")),
              HasSubstr("give exactly one of 'mesh' or 'generator'"));
}

TEST_F(ScenarioTest, MissingSectionIsNamed) {
  EXPECT_THAT(ErrorOf("name: x\npart:\n  generator: {type: box}\n"), HasSubstr("missing required section 'slicing'"));
}

TEST_F(ScenarioTest, YamlSyntaxErrorGivesLine) {
  EXPECT_THAT(ErrorOf("name: x\npart: [unclosed\n"), HasSubstr("YAML syntax error"));
}

TEST_F(ScenarioTest, OverridesReplaceAndAddKeys) {
  const analysis::Scenario s =
      analysis::LoadScenario(Write(Valid()), {"path.pattern=hybrid", "slicing.layer_height_mm=2.5", "path.seed=7",
                                    "simulation.voxel_mm=1", "simulation.curvature_width=none"});
  EXPECT_EQ(NameOf(s.path.pattern), "hybrid");
  EXPECT_DOUBLE_EQ(s.slicing.layer_height_mm, 2.5);
  EXPECT_EQ(s.path.seed, 7u);
  // An optional section the file does not have is created by the override.
  EXPECT_DOUBLE_EQ(s.simulation.voxel_mm, 1.0);
  EXPECT_EQ(NameOf(s.simulation.curvature_width), "none");
  const analysis::Scenario t = analysis::LoadScenario(Write(Valid()), {"run.steps=[plan, check]"});
  EXPECT_EQ(t.run.steps, (std::vector<std::string>{"plan", "check"}));
}

TEST_F(ScenarioTest, OverridesAreValidatedLikeTheFile) {
  try {
    analysis::LoadScenario(Write(Valid()), {"path.pattern=wobble"});
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("path.pattern = 'wobble': unknown value"));
  }
  try {
    analysis::LoadScenario(Write(Valid()), {"no_equals_sign"});
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("--set 'no_equals_sign': expected key.path=value"));
  }
  try {
    analysis::LoadScenario(Write(Valid()), {"name.sub=1"});
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("is not a section"));
  }
}

TEST_F(ScenarioTest, ArcStartAndStopChoicesAreChecked) {
  const analysis::Scenario s =
      analysis::LoadScenario(Write(Valid()), {"simulation.stop_crater=lost", "simulation.start_wetting=cold"});
  EXPECT_EQ(NameOf(s.simulation.stop_crater), "lost");
  EXPECT_EQ(NameOf(s.simulation.start_wetting), "cold");
  EXPECT_EQ(NameOf(analysis::LoadScenario(Write(Valid())).simulation.stop_crater), "lip") << "the crater's metal freezes in its lip";
  try {
    analysis::LoadScenario(Write(Valid()), {"simulation.stop_crater=fill"});
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("simulation.stop_crater = 'fill': unknown value"));
  }
}

TEST_F(ScenarioTest, BeadModelAndModelFiles) {
  std::string text = Valid();
  text += "  bead_model: speed_height\n  speed_height_model: models/none.json\n";
  text.replace(text.find("process:\n"), 9, "process:\n");
  EXPECT_THAT(ErrorOf(text), HasSubstr("process.speed_height_model: model file"));
  std::string bad = Valid() + "  bead_model: magic\n";
  EXPECT_THAT(ErrorOf(bad), HasSubstr("process.bead_model = 'magic': unknown value"));
  // The CSW model sets speeds from the curvature of curved-layer paths only.
  EXPECT_THAT(ErrorOf(Valid() + "  bead_model: csw\n"), HasSubstr("csw: needs slicing.type cone or cylinder"));
}

TEST_F(ScenarioTest, SubVolumeKeys) {
  std::string text = Valid();
  text.replace(text.find("type: planar"), 12,
               "type: multi_directional\n  sub_volumes:\n    - {name: hub, direction: [0, 0, 0]}");
  EXPECT_THAT(ErrorOf(text), HasSubstr("direction: must not be the zero vector"));
  text = Valid();
  text.replace(text.find("type: planar"), 12,
               "type: multi_directional\n  sub_volumes:\n    - {name: hub, direction: [0, 0, 1], keep: [1, 0, 0]}");
  EXPECT_THAT(ErrorOf(text), HasSubstr("keep: 3 numbers: give 4 per entry"));
}

TEST_F(ScenarioTest, ConeSlicingKeys) {
  std::string text = Valid();
  text.replace(text.find("type: planar"), 12, "type: cone\n  R_mm: 60\n  H_mm: 0.5");
  EXPECT_THAT(ErrorOf(text), HasSubstr("slicing.H_mm = 0.5: |H| must be >= 1 mm"));
  text = Valid();
  text.replace(text.find("type: planar"), 12, "type: cylinder\n  R_mm: 60\n  H_mm: 200");
  EXPECT_THAT(ErrorOf(text), HasSubstr("H_mm"));
}

TEST_F(ScenarioTest, MissingFileIsNamed) {
  try {
    analysis::LoadScenario(dir_ / "nope.yaml");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("nope.yaml: file not found"));
  }
}

}  // namespace
}  // namespace waam::planner

namespace waam::planner {
namespace {

// The table of setting names in docs/SCENARIOS.md lists exactly the names of each setting's table in the code.
template <typename E>
void ExpectDocRow(const std::string& doc, const std::string& key) {
  const std::string row = "| `" + key + "` | " + EnumNameList<E>() + " |";
  EXPECT_NE(doc.find(row), std::string::npos) << "docs/SCENARIOS.md should have the row\n" << row;
}

TEST(SettingNames, ScenarioDocListsEveryTable) {
  std::ifstream in(std::filesystem::path(WAAM_SOURCE_DIR) / "docs" / "SCENARIOS.md");
  const std::string doc((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_FALSE(doc.empty());
  ExpectDocRow<SlicingType>(doc, "slicing.type");
  ExpectDocRow<SplitMethod>(doc, "slicing.split");
  ExpectDocRow<Pattern>(doc, "path.pattern");
  ExpectDocRow<OverlapModel>(doc, "path.overlap_model");
  ExpectDocRow<VoidFillingMode>(doc, "path.void_filling.mode");
  ExpectDocRow<BeadModel>(doc, "process.bead_model");
  ExpectDocRow<Blend>(doc, "simulation.blend");
  ExpectDocRow<StopCrater>(doc, "simulation.stop_crater");
  ExpectDocRow<StartWetting>(doc, "simulation.start_wetting");
  ExpectDocRow<CurvatureWidth>(doc, "simulation.curvature_width");
  ExpectDocRow<PositionerFollow>(doc, "cell.positioner.follow");
  ExpectDocRow<PositionerType>(doc, "cell.positioner.type");
  ExpectDocRow<twin::CellPreset>(doc, "cell.preset");
  ExpectDocRow<twin::CellResolve>(doc, "cell.resolve");
  ExpectDocRow<ProgramFormat>(doc, "program.format");
  ExpectDocRow<ProgramLayers>(doc, "program.layers");
}

TEST(SettingNames, EveryNameParsesBackToItsValue) {
  for (const EnumName<Pattern>& entry : EnumNames(Pattern{})) {
    EXPECT_EQ(ParseEnum<Pattern>(entry.name), entry.value);
    EXPECT_EQ(NameOf(entry.value), entry.name);
  }
  EXPECT_FALSE(ParseEnum<Pattern>("zigzg").has_value());
}

}  // namespace
}  // namespace waam::planner
