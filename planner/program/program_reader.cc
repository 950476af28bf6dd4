// Picking a reader: by the format given, the file's extension or its first lines.
#include "planner/program/program_reader.h"

#include "models/core/error.h"

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

}  // namespace waam::planner
