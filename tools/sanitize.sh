#!/usr/bin/env bash
# Builds waam-twin with AddressSanitizer + UndefinedBehaviorSanitizer (Debug, -O1, in build-asan/) and runs the
# whole test suite under them (about 3x the release run's time). Any sanitizer report fails the test that
# triggered it (no recovery). Extra arguments go to ctest, e.g. `tools/sanitize.sh -R StlIo` for a quick look.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${WAAM_ASAN_BUILD_DIR:-build-asan}
jobs=${WAAM_JOBS:-$(nproc)}
launcher=()
if command -v ccache >/dev/null; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
fi
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g" -DCMAKE_C_FLAGS_DEBUG="-O1 -g" \
  -DWAAM_SANITIZE=ON -DWAAM_BUILD_BENCHMARKS=OFF "${launcher[@]}"
cmake --build "$build" -j"$jobs"

# Debian's libraries (MuJoCo, OpenCV, HDF5, yaml-cpp, Ceres) are not instrumented: ASan still checks every access
# our code makes to their memory; tools/sanitize.supp lists the leak reports that are theirs, each with its reason.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:strict_string_checks=1}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$(pwd)/tools/sanitize.supp:print_suppressions=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
ctest --test-dir "$build" --output-on-failure -j"$jobs" "$@"
