// Where waam finds its data files (the fitted default models and the papers' tables in models/data, the cell models
// in twin/data, the example scenarios): one answer for every module.
#pragma once

#include <filesystem>
#include <string>

namespace waam {

// The data root, laid out like the source tree (DataDir() / "models" / "data", DataDir() / "twin" / "data"):
//   1. the environment variable WAAM_DATA_DIR, when set and not empty;
//   2. <prefix>/share/waam-twin when the binary holding this code (the executable <prefix>/bin/waam, or the Python
//      module <prefix>/lib/python3/dist-packages/waam_twin/_core.so) lies under <prefix> and that folder exists (an
//      installed waam, wherever the prefix was moved: nothing of the build's paths is used);
//   3. else the source tree the build came from (running from the build tree, and the tests).
std::filesystem::path DataDir();

// The version and the git commit the build was configured from ("unknown" outside a git checkout).
std::string VersionString();

}  // namespace waam
