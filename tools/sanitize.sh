#!/usr/bin/env bash
# Builds waam-twin with AddressSanitizer + UndefinedBehaviorSanitizer (Debug, -O1, in build-asan/) and runs the
# whole test suite under them (about 3x the release run's time). Any sanitizer report fails the test that
# triggered it (no recovery). Extra arguments go to ctest, e.g. `tools/sanitize.sh -R StlIo` for a quick look.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${WAAM_ASAN_BUILD_DIR:-build-asan}
jobs=${WAAM_JOBS:-$(nproc)}
# -g1: line tables only, enough for the sanitizers' stack traces (file:line) at a fraction of -g's compile and link.
generator=(-G Ninja)
[ -f "$build/CMakeCache.txt" ] && generator=()  # an existing build keeps the generator it was made with
cmake -S . -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g1" \
  -DCMAKE_C_FLAGS_DEBUG="-O1 -g1" -DWAAM_SANITIZE=ON -DWAAM_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build "$build" -j"$jobs"

# Debian's libraries (MuJoCo, OpenCV, HDF5, yaml-cpp, Ceres) are not instrumented: ASan still checks every access
# our code makes to their memory; tools/sanitize.supp lists the leak reports that are theirs, each with its reason.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:strict_string_checks=1}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$(pwd)/tools/sanitize.supp:print_suppressions=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
# The scheduler tests (label cluster) run the Release build only: they check Slurm, Dask and the scripts.
# Six thermal tests that each repeat the same six-layer wall run (40-85 s apiece here, a few seconds in Release) run
# in the Release build only; ThermalCli.WritesEveryOutputAndTheTimelineAddsUp runs a three-layer cut of that wall
# under the sanitizers, and the thermal model's own tests (twin/thermal) all run here.
# The 40-layer bent tube's convergence in two compensations (23 s here) checks numbers; the compensation loop's code
# is sanitized by the 16-layer tube's tests (Compensation.LoopThatCannotReachTheTolerance...). The scenarios of
# scenarios/cell/ beyond one per kind of cell (CheckCliTest.EachKindOfCell...) are checked in Release only; their
# faults are sanitized by PlantedFaultTest.*.
# Tests that rerun a whole command on 1 and 4 threads to compare the outputs (24-32 s apiece here) check determinism,
# which the Release build checks as well; the code they run is sanitized by the single-run tests of the same
# commands. So does ThermalMultirate.ResultsDoNotDependOnTheThreadCount (1.3 s in Release), whose solver the other
# ThermalMultirate tests sanitize. The planted-clamp placement search (75 s here) has a smaller sanitized sibling
# (PlaceCliTest.APartOutOfReachEverywhere...), and the viewer's headless-Chromium page tests (5-17 s) time the
# browser; the viewer's data is sanitized by ViewerTest.*.
release_only='^(ThermalCli\.(WaitsHold|ProbeHistories|RunStep)|ThermalRun\.(InterpassWaits|WithoutTheLimit|EnergyBalanceCloses)'
release_only+='|PlanCommandTest\.SamePlanOnOneAndFourThreads|Compensation\.SameOnOneAndFourThreads'
release_only+='|ParallelCheck\.SameCheckJsonOnOneAndFourThreads|PlaceCliTest\.ThePlantedClampFaultGetsAPlacementThatPasses'
release_only+='|Compensation\.BentTubeConvergesWithinTwoIterations|CheckCliTest\.EveryOtherCellScenario'
release_only+='|ViewerBrowserTest\.|ThermalMultirate\.ResultsDoNotDependOnTheThreadCount)'
ctest --test-dir "$build" --output-on-failure -j"$jobs" -LE cluster -E "$release_only" "$@"
