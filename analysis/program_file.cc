// Reading a robot program or G-code file (a KRL .src with its .dat) for the planner's readers.
#include "analysis/program_file.h"

#include <cctype>
#include <string>

#include "models/core/error.h"
#include "models/core/files.h"

namespace waam::analysis {

planner::ParsedProgram ReadProgramFile(const std::filesystem::path& path, std::optional<planner::ProgramFormat> format,
                                       const planner::GcodeReadOptions& gcode, const planner::JbiReadOptions& jbi,
                                       const planner::ProgramFrames& frames) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  WAAM_THROW_UNLESS(!ec, path.string() << ": cannot read the program: " << ec.message());
  WAAM_THROW_UNLESS(size <= planner::kMaxProgramBytes, path.string() << ": the program has " << size
                                                                     << " bytes, more than the limit of "
                                                                     << planner::kMaxProgramBytes);
  const std::string text = ReadFile(path);
  const planner::ProgramFormat f = format ? *format : planner::DetectProgramFormat(path, text);
  planner::ParsedProgram program;
  if (f == planner::ProgramFormat::kKukaKrl) {
    // The .src and its .dat beside it (same name), whichever of the two was given.
    std::string ext = path.extension().string();
    for (char& c : ext) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    const bool given_dat = ext == ".DAT";
    auto sibling = [&](const char* lower, const char* upper) {
      std::filesystem::path p = path;
      p.replace_extension(lower);
      if (!std::filesystem::exists(p)) p.replace_extension(upper);
      return p;
    };
    const std::filesystem::path src = given_dat ? sibling(".src", ".SRC") : path;
    const std::filesystem::path dat = given_dat ? path : sibling(".dat", ".DAT");
    WAAM_THROW_UNLESS(std::filesystem::is_regular_file(src), path.string() << ": no " << src.filename().string()
                                                                            << " beside the .dat");
    const std::string src_text = given_dat ? ReadFile(src) : text;
    const std::string dat_text = given_dat ? text : (std::filesystem::is_regular_file(dat) ? ReadFile(dat) : "");
    WAAM_THROW_UNLESS(src_text.size() <= planner::kMaxProgramBytes && dat_text.size() <= planner::kMaxProgramBytes,
                      src.string() << ": the program is more than the limit of " << planner::kMaxProgramBytes
                                   << " bytes");
    program = planner::ReadKukaKrl(src_text, dat_text, src.string(), dat.string(), frames);
  } else {
    program = planner::ReadProgramText(text, path.string(), f, gcode, jbi, frames);
  }
  if (program.name.empty()) program.name = path.stem().string();
  return program;
}

}  // namespace waam::analysis
