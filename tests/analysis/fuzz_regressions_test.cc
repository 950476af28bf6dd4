// Replays every input kept in fuzz/regressions/ (inputs that once crashed or hung a fuzz target, see tools/fuzz.sh)
// through the same reader as its fuzz target: each must give a result or an InputError, nothing else.
#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "analysis/png_file.h"
#include "analysis/scenario.h"
#include "analysis/sweep.h"
#include "analysis/thermal_material_io.h"
#include "fuzz/program_fuzz.h"
#include "fuzz/replay_log_fuzz.h"
#include "models/core/csv.h"
#include "models/core/error.h"
#include "models/core/json_text.h"
#include "models/core/files.h"
#include "analysis/stl_file.h"
#include "planner/mesh/stl_io.h"
#include "planner/program/program_plan.h"
#include "planner/program/program_reader.h"

namespace waam::planner {
namespace {
namespace fs = std::filesystem;

std::vector<fs::path> Inputs(const std::string& target) {
  std::vector<fs::path> files;
  const fs::path dir = fs::path(WAAM_SOURCE_DIR) / "fuzz" / "regressions" / target;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.is_regular_file() && entry.path().filename() != "README.md") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

// Runs `read` on every kept input of `target`; an InputError is a fine answer, any other exception fails.
template <typename Read>
void Replay(const std::string& target, Read read) {
  const std::vector<fs::path> inputs = Inputs(target);
  ASSERT_FALSE(inputs.empty()) << "fuzz/regressions/" << target << " holds no input";
  for (const fs::path& input : inputs) {
    try {
      read(input);
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << input << ": the message must be one line";
    } catch (const std::exception& e) {
      ADD_FAILURE() << input << ": expected a result or an InputError, got another exception: " << e.what();
    }
  }
}

TEST(FuzzRegressions, StlInputsGiveAMeshOrAnInputError) {
  Replay("stl", [](const fs::path& input) {
    MeshReport report;
    analysis::ReadStl(input, 0.01, &report);
    (void)MeshReportJson(report);
    CheckSliceable(report);
  });
}

TEST(FuzzRegressions, ScenarioInputsGiveAScenarioOrAnInputError) {
  Replay("scenario", [](const fs::path& input) { (void)analysis::LoadScenario(input); });
}

TEST(FuzzRegressions, CsvInputsGiveATableOrAnInputError) {
  Replay("csv", [](const fs::path& input) {
    const CsvTable table = CsvTable::Parse(ReadFile(input), input.string());
    for (const std::string& column : table.header()) {
      try {
        (void)table.Numbers(column, true);
      } catch (const InputError&) {
      }
    }
  });
}

TEST(FuzzRegressions, SweepInputsGiveASweepOrAnInputError) {
  Replay("sweep", [](const fs::path& input) {
    const analysis::Sweep sweep = analysis::ParseSweep(ReadFile(input), input);
    (void)analysis::SweepBenchRuns(sweep);
    (void)JsonText(analysis::SweepJson(sweep));
  });
}

TEST(FuzzRegressions, PngInputsGiveAPictureOrAnInputError) {
  Replay("png", [](const fs::path& input) {
    for (const int channels : {1, 3, 4}) (void)analysis::internal::ReadPng(input, channels);
  });
}

// The program readers, then the conversion into a plan, as their fuzz targets run them.
void ReplayProgram(const std::string& target, ProgramFormat format) {
  Replay(target, [format](const fs::path& input) {
    fuzz::ReadAndPlanProgram(ReadFile(input), input.string(), format);
  });
}

TEST(FuzzRegressions, FanucLsInputsGiveAPlanOrAnInputError) { ReplayProgram("fanuc_ls", ProgramFormat::kFanucLs); }
TEST(FuzzRegressions, AbbRapidInputsGiveAPlanOrAnInputError) { ReplayProgram("abb_rapid", ProgramFormat::kAbbRapid); }
TEST(FuzzRegressions, GcodeInputsGiveAPlanOrAnInputError) { ReplayProgram("gcode", ProgramFormat::kGcode); }
TEST(FuzzRegressions, KukaKrlInputsGiveAPlanOrAnInputError) { ReplayProgram("kuka_krl", ProgramFormat::kKukaKrl); }
TEST(FuzzRegressions, YaskawaJbiInputsGiveAPlanOrAnInputError) {
  ReplayProgram("yaskawa_jbi", ProgramFormat::kYaskawaJbi);
}
TEST(FuzzRegressions, ProgramCsvInputsGiveAPlanOrAnInputError) { ReplayProgram("program_csv", ProgramFormat::kCsv); }

TEST(FuzzRegressions, ThermalMaterialInputsGiveAMaterialOrAnInputError) {
  Replay("thermal_material", [](const fs::path& input) {
    const models::ThermalMaterial m = analysis::ParseThermalMaterial(ReadFile(input), input.string(), "fuzz");
    for (double t : {-300.0, 20.0, 1500.0, 1e300}) EXPECT_GT(m.EffectiveHeatCapacity(t), 0.0) << input;
  });
}

TEST(FuzzRegressions, ReplayLogInputsGiveAnOrderedLogOrAnInputError) {
  Replay("replay_log", [](const fs::path& input) {
    const std::string bytes = ReadFile(input);
    ASSERT_FALSE(bytes.empty()) << input;
    EXPECT_TRUE(fuzz::ReplayLogFuzzOne(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()))
        << input << ": an accepted log must be in strict time order with finite values";
  });
}

}  // namespace
}  // namespace waam::planner
