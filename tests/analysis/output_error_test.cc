// An output that cannot be written is an output error (exit 2, "cannot write <path>: <reason>"), never an internal
// error, for JSON, PNG, HDF5, STL and HTML alike. The tests run as root, which may write anywhere a permission test
// would forbid, so they make writes fail in ways root meets too: a path under a regular file, a path that is a
// directory, /proc, and a full disk stood in for by a file-size limit (ulimit -f, with SIGXFSZ ignored so that the
// write fails with EFBIG instead of killing the process).
#include <filesystem>
#include <fstream>
#include <string>

#include <sys/wait.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/analysis/cli_test_util.h"

namespace waam::analysis {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;
using cli_test::FilesUnder;
using cli_test::RunWaam;
using cli_test::TempDir;

fs::path WriteTinyScenario(const fs::path& dir) {
  const fs::path file = dir / "tiny.yaml";
  std::ofstream(file) << cli_test::kTinyBlockScenario;
  return file;
}

// Runs `waam <args>` under a file-size limit of `limit_kib` KiB; returns its exit code and its stderr in `*err`.
int RunWaamWithFileLimit(int limit_kib, const std::string& args, std::string* err) {
  const fs::path err_file = TempDir("file_limit_stderr") / "stderr.txt";
  const std::string command = "bash -c \"trap '' XFSZ; ulimit -f " + std::to_string(limit_kib) + "; exec " +
                              std::string(WAAM_BINARY) + " " + args + "\" >/dev/null 2>" + err_file.string();
  const int status = std::system(command.c_str());
  *err = cli_test::Slurp(err_file);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// Expects exit 2 and one output-error line naming `path`, and no internal error.
void ExpectOutputError(int code, const std::string& err, const fs::path& path) {
  EXPECT_EQ(code, 2) << err;
  EXPECT_THAT(err, HasSubstr("waam: error: cannot write " + path.string() + ": ")) << err;
  EXPECT_THAT(err, Not(HasSubstr("internal error"))) << err;
}

TEST(OutputError, OutputFolderUnderARegularFile) {
  const fs::path dir = TempDir("output_under_file");
  const fs::path scenario = WriteTinyScenario(dir);
  std::ofstream(dir / "a_file") << "not a folder";
  std::string err;
  const int code = RunWaam("plan " + scenario.string() + " -q -o " + (dir / "a_file" / "out").string(), &err);
  ExpectOutputError(code, err, dir / "a_file" / "out");
  EXPECT_THAT(err, HasSubstr("Not a directory"));
}

TEST(OutputError, OutputFolderInProc) {
  const fs::path dir = TempDir("output_in_proc");
  std::string err;
  const int code = RunWaam("plan " + WriteTinyScenario(dir).string() + " -q -o /proc/waam_no_such_folder", &err);
  ExpectOutputError(code, err, "/proc/waam_no_such_folder");
}

// Each output name taken by a directory: the rename onto it fails, and nothing under the name is replaced.
TEST(OutputError, HdfPngJsonAndHtmlOntoADirectory) {
  const fs::path dir = TempDir("output_onto_directory");
  const fs::path scenario = WriteTinyScenario(dir);
  const std::string names[] = {"plan.h5", "layers/layer_0000.png", "plan.json"};
  for (int i = 0; i < 3; ++i) {
    const std::string& name = names[i];
    const fs::path out = dir / ("plan_" + std::to_string(i));
    fs::create_directories(out / name / "kept");
    std::string err;
    const int code = RunWaam("plan " + scenario.string() + " -q -o " + out.string(), &err);
    ExpectOutputError(code, err, out / name);
    EXPECT_TRUE(fs::is_directory(out / name / "kept")) << name;
  }
  const fs::path out = dir / "check";
  fs::create_directories(out / "viewer.html");
  std::string err;
  ExpectOutputError(RunWaam("check " + scenario.string() + " -q -o " + out.string(), &err), err, out / "viewer.html");
}

// A full disk: the first write past the limit fails with "File too large", and no temporary file is left behind.
TEST(OutputError, FullDiskForHdfJsonAndStl) {
  const fs::path dir = TempDir("output_disk_full");
  const fs::path scenario = WriteTinyScenario(dir);
  struct Case {
    std::string args;
    fs::path file;
    int limit_kib;
  };
  const fs::path csv = fs::path(WAAM_SOURCE_DIR) / "models" / "data" / "dai2020_csw_table1.csv";
  const Case cases[] = {
      {"plan " + scenario.string() + " -q --no-images -o " + (dir / "plan").string(), dir / "plan" / "plan.h5", 2},
      {"fit csw " + csv.string() + " -o " + (dir / "fit" / "csw.json").string(), dir / "fit" / "csw.json", 1},
      {"simulate " + scenario.string() + " -q --no-images -o " + (dir / "sim").string(), dir / "sim" / "part.stl", 8},
  };
  for (const Case& c : cases) {
    std::string err;
    const int code = RunWaamWithFileLimit(c.limit_kib, c.args, &err);
    ExpectOutputError(code, err, c.file);
    EXPECT_THAT(err, HasSubstr("File too large")) << c.args;
    for (const std::string& file : FilesUnder(c.file.parent_path())) {
      EXPECT_THAT(file, Not(HasSubstr(".tmp-"))) << "a temporary file was left behind";
    }
  }
}

}  // namespace
}  // namespace waam::analysis
