#!/usr/bin/env bash
# Installs the dependencies, builds waam-twin (Release, build/) and runs the whole test suite with CTest, then builds
# it again with AddressSanitizer + UndefinedBehaviorSanitizer (build-asan/) and runs the suite under them
# (tools/sanitize.sh). Both builds are unity builds through ccache (CMakeLists.txt), with Ninja.
#   --quick   the inner loop: the Release build and its tests only (no dependency check, no sanitizer run)
# WAAM_SKIP_SANITIZE=1 is the same as --quick apart from the dependency check.
set -euo pipefail
cd "$(dirname "$0")/.."
quick=0
for arg in "$@"; do
  case "$arg" in
    --quick) quick=1 ;;
    -h|--help) sed -n '2,6p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "test.sh: unknown argument '$arg' (see --help)" >&2; exit 2 ;;
  esac
done
if [ "$quick" = 0 ]; then
  ./tools/install_deps.sh
fi
jobs=${WAAM_JOBS:-$(nproc)}
start=$(date +%s)
generator=(-G Ninja)
[ -f build/CMakeCache.txt ] && generator=()  # an existing build keeps the generator it was made with
cmake -S . -B build "${generator[@]}" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$jobs"
ctest --test-dir build --output-on-failure -j"$jobs" -LE cluster
# The scheduler tests (label cluster) drive real Slurm and Dask daemons, one with a task cancelled mid-run and
# requeued; they run once more if they fail (Cluster.slurm_array failed once in four fresh-clone runs on 2026-11-28:
# the requeued task ended FAILED, exit 1, before printing anything; not reproduced in five runs since, two of them
# under load). A second failure fails the suite; the first one's output stays in the log.
ctest --test-dir build --output-on-failure -j"$jobs" -L cluster --repeat until-pass:2
echo "test.sh: Release build and tests took $(( $(date +%s) - start )) s"
if [ "$quick" = 0 ] && [ "${WAAM_SKIP_SANITIZE:-0}" != 1 ]; then
  bash tools/sanitize.sh
  echo "test.sh: both builds and test runs took $(( $(date +%s) - start )) s"
fi
