// Picking a reader: by the format given, the file's extension or its first lines.
#include "planner/program/program_reader.h"

#include "models/core/error.h"
#include "models/core/files.h"

namespace waam::planner {

std::optional<ProgramFormat> ProgramFormatOfExtension(const std::filesystem::path& path) {
  const std::string ext = internal::Upper(path.extension().string());
  if (ext == ".LS") return ProgramFormat::kFanucLs;
  if (ext == ".MOD" || ext == ".PRG" || ext == ".MODX") return ProgramFormat::kAbbRapid;
  if (ext == ".SRC" || ext == ".DAT") return ProgramFormat::kKukaKrl;
  if (ext == ".JBI") return ProgramFormat::kYaskawaJbi;
  if (ext == ".NC" || ext == ".GCODE" || ext == ".NGC" || ext == ".TAP" || ext == ".G" || ext == ".MPF") {
    return ProgramFormat::kGcode;
  }
  if (ext == ".CSV") return ProgramFormat::kCsv;
  return std::nullopt;
}

ProgramFormat DetectProgramFormat(const std::filesystem::path& path, std::string_view text) {
  if (const std::optional<ProgramFormat> f = ProgramFormatOfExtension(path)) return *f;
  const std::string head = internal::Upper(internal::TrimBlank(text.substr(0, std::min<std::size_t>(text.size(), 4096))));
  if (head.compare(0, 5, "/PROG") == 0) return ProgramFormat::kFanucLs;
  if (head.compare(0, 6, "MODULE") == 0 || head.find("\nMODULE") != std::string::npos) return ProgramFormat::kAbbRapid;
  if (head.compare(0, 4, "/JOB") == 0) return ProgramFormat::kYaskawaJbi;
  if (head.find("DEF ") != std::string::npos && head.find("&ACCESS") != std::string::npos) return ProgramFormat::kKukaKrl;
  if (head.find("\nG1") != std::string::npos || head.compare(0, 2, "G1") == 0 || head.find("\nG0") != std::string::npos ||
      head.compare(0, 2, "G0") == 0) {
    return ProgramFormat::kGcode;
  }
  WAAM_THROW(path.string() << ": cannot tell the program's format from its extension or first lines; give --format "
                           << "(csv, fanuc_ls, abb_rapid, kuka_krl, yaskawa_jbi, gcode)");
}

ParsedProgram ReadProgramText(std::string_view text, const std::string& file, ProgramFormat format,
                              const GcodeReadOptions& gcode, const JbiReadOptions& jbi, const ProgramFrames& frames) {
  switch (format) {
    case ProgramFormat::kCsv: return ReadProgramCsv(text, file);
    case ProgramFormat::kFanucLs: return ReadFanucLs(text, file, frames);
    case ProgramFormat::kAbbRapid: return ReadAbbRapid(text, file);
    case ProgramFormat::kGcode: return ReadGcode(text, file, gcode);
    case ProgramFormat::kKukaKrl: {
      std::size_t dat = text.find("\nDEFDAT");
      if (dat == std::string_view::npos) dat = text.find("\ndefdat");
      return ReadKukaKrl(text, dat == std::string_view::npos ? std::string_view() : text.substr(dat + 1), file, file,
                         frames);
    }
    case ProgramFormat::kYaskawaJbi: return ReadYaskawaJbi(text, file, jbi, frames);
  }
  WAAM_DEMAND(false);
  return {};
}

ParsedProgram ReadProgramFile(const std::filesystem::path& path, std::optional<ProgramFormat> format,
                              const GcodeReadOptions& gcode, const JbiReadOptions& jbi, const ProgramFrames& frames) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  WAAM_THROW_UNLESS(!ec, path.string() << ": cannot read the program: " << ec.message());
  WAAM_THROW_UNLESS(size <= kMaxProgramBytes, path.string() << ": the program has " << size
                                                            << " bytes, more than the limit of " << kMaxProgramBytes);
  const std::string text = ReadFile(path);
  const ProgramFormat f = format ? *format : DetectProgramFormat(path, text);
  ParsedProgram program;
  if (f == ProgramFormat::kKukaKrl) {
    // The .src and its .dat beside it (same name), whichever of the two was given.
    const bool given_dat = internal::Upper(path.extension().string()) == ".DAT";
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
    WAAM_THROW_UNLESS(src_text.size() <= kMaxProgramBytes && dat_text.size() <= kMaxProgramBytes,
                      src.string() << ": the program is more than the limit of " << kMaxProgramBytes << " bytes");
    program = ReadKukaKrl(src_text, dat_text, src.string(), dat.string(), frames);
  } else {
    program = ReadProgramText(text, path.string(), f, gcode, jbi, frames);
  }
  if (program.name.empty()) program.name = path.stem().string();
  return program;
}

}  // namespace waam::planner
