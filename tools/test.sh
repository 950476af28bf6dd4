#!/usr/bin/env bash
# Installs the dependencies, builds waam-twin (Release) and runs the whole test suite with CTest, then builds it
# again with AddressSanitizer + UndefinedBehaviorSanitizer and runs the suite under them (tools/sanitize.sh).
# WAAM_SKIP_SANITIZE=1 skips the second run (a quick local check).
set -euo pipefail
cd "$(dirname "$0")/.."
./tools/install_deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)"
ctest --test-dir build --output-on-failure -j"$(nproc)"
if [ "${WAAM_SKIP_SANITIZE:-0}" != 1 ]; then
  bash tools/sanitize.sh
fi
