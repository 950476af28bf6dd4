// Picking a reader: by the format given, the file's extension or its first lines.
#include "planner/program/program_reader.h"

#include "models/core/error.h"
#include "models/core/files.h"

namespace waam::planner {

ProgramFormat DetectProgramFormat(const std::filesystem::path& path, std::string_view text) {
  const std::string ext = internal::Upper(path.extension().string());
  if (ext == ".LS") return ProgramFormat::kFanucLs;
  if (ext == ".MOD" || ext == ".PRG" || ext == ".MODX") return ProgramFormat::kAbbRapid;
  if (ext == ".SRC" || ext == ".DAT") return ProgramFormat::kKukaKrl;
  if (ext == ".JBI") return ProgramFormat::kYaskawaJbi;
  if (ext == ".NC" || ext == ".GCODE" || ext == ".NGC" || ext == ".TAP" || ext == ".G" || ext == ".MPF") {
    return ProgramFormat::kGcode;
  }
  if (ext == ".CSV") return ProgramFormat::kCsv;
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
                           << "(csv, fanuc_ls, abb_rapid, gcode)");
}

ParsedProgram ReadProgramText(std::string_view text, const std::string& file, ProgramFormat format,
                              const GcodeReadOptions& gcode) {
  switch (format) {
    case ProgramFormat::kCsv: return ReadProgramCsv(text, file);
    case ProgramFormat::kFanucLs: return ReadFanucLs(text, file);
    case ProgramFormat::kAbbRapid: return ReadAbbRapid(text, file);
    case ProgramFormat::kGcode: return ReadGcode(text, file, gcode);
    case ProgramFormat::kKukaKrl:
    case ProgramFormat::kYaskawaJbi: break;
  }
  WAAM_THROW(file << ": reading " << NameOf(format) << " programs is not supported yet (csv, fanuc_ls, abb_rapid, "
                  << "gcode are)");
}

ParsedProgram ReadProgramFile(const std::filesystem::path& path, std::optional<ProgramFormat> format,
                              const GcodeReadOptions& gcode) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  WAAM_THROW_UNLESS(!ec, path.string() << ": cannot read the program: " << ec.message());
  WAAM_THROW_UNLESS(size <= kMaxProgramBytes, path.string() << ": the program has " << size
                                                            << " bytes, more than the limit of " << kMaxProgramBytes);
  const std::string text = ReadFile(path);
  const ProgramFormat f = format ? *format : DetectProgramFormat(path, text);
  ParsedProgram program = ReadProgramText(text, path.string(), f, gcode);
  if (program.name.empty()) program.name = path.stem().string();
  return program;
}

}  // namespace waam::planner
