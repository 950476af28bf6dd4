// Helpers shared by the fuzz targets: a scratch folder for readers that take a file path, the one-line check.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>

#include "models/core/error.h"

namespace waam::fuzz {

// Writes `size` bytes to `name` inside a per-process scratch folder (created once, under $TMPDIR or /tmp, with
// `meshes` linked to the repository's scenarios/meshes both inside it and in its parent, so the scenario files'
// relative mesh paths resolve) and returns the file's path. Aborts if the file cannot be written.
std::filesystem::path WriteScratchFile(const char* name, const std::uint8_t* data, std::size_t size);

// Aborts (a finding of the fuzz run) unless the refusal's message is one printable line: no byte below 0x20 and no
// 0x7f, whatever control characters the input held (the one-line rule of waam::InputError).
void CheckOneLine(const waam::InputError& error);

}  // namespace waam::fuzz
