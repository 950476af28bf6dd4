#!/usr/bin/env bash
# Builds one libFuzzer target (clang, ASan + UBSan, in build-fuzz/) and runs it for a given time.
#   tools/fuzz.sh <stl|scenario|csv|urdf|mjcf|sweep|fanuc_ls|abb_rapid|gcode|program_csv|kuka_krl|yaskawa_jbi|thermal_material|replay_log|png> <seconds> [more libFuzzer flags]
# The seed corpus is the repository's own files (meshes, scenarios, data tables) plus fuzz/regressions/<target>;
# the growing corpus stays in build-fuzz/corpus/<target>, crashing inputs go to build-fuzz/artifacts/<target>/.
# The 60 s timeout is for a shared, loaded machine (a unit normally takes milliseconds); a real hang still trips it.
# Keep every crashing input in fuzz/regressions/<target>/ once fixed: the normal build replays them
# (tests/analysis/fuzz_regressions_test.cc).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
target=${1:?usage: tools/fuzz.sh <stl|scenario|csv|urdf|mjcf|sweep|fanuc_ls|abb_rapid|gcode|program_csv|kuka_krl|yaskawa_jbi|thermal_material|replay_log|png> <seconds> [libFuzzer flags]}
seconds=${2:?usage: tools/fuzz.sh <stl|scenario|csv|urdf|mjcf|sweep|fanuc_ls|abb_rapid|gcode|program_csv|kuka_krl|yaskawa_jbi|thermal_material|replay_log|png> <seconds> [libFuzzer flags]}
shift 2
build=${WAAM_FUZZ_BUILD_DIR:-$root/build-fuzz}

# find over the named folders that exist: a target's fuzz/seeds/<target> folder is optional.
find_seeds() {
  local dirs=()
  while [ $# -gt 0 ] && [ "${1#-}" = "$1" ]; do
    if [ -e "$1" ]; then dirs+=("$1"); fi
    shift
  done
  find "${dirs[@]}" "$@"
}

case "$target" in
  stl) seeds=$(find_seeds scenarios/meshes fuzz/seeds/stl -name '*.stl' -size -64k); max_len=65536 ;;
  scenario) seeds=$(find_seeds scenarios fuzz/seeds/scenario -name '*.yaml'); max_len=4096 ;;
  csv) seeds=$(find_seeds models/data fuzz/seeds/csv -name '*.csv'); max_len=8192 ;;
  urdf) seeds=$(find_seeds scenarios/cell/robots -name '*.urdf'); max_len=16384 ;;
  mjcf) seeds=$(find_seeds twin/data -name '*.xml'); max_len=16384 ;;
  sweep) seeds=$(find_seeds docs fuzz/regressions/sweep -name '*sweep*.yaml'); max_len=4096 ;;
  fanuc_ls) seeds=$(find_seeds tests/data/programs -name '*.ls'); max_len=16384 ;;
  abb_rapid) seeds=$(find_seeds tests/data/programs -name '*.mod'); max_len=16384 ;;
  gcode) seeds=$(find_seeds tests/data/programs -name '*.nc'); max_len=16384 ;;
  kuka_krl) seeds=$(mkdir -p build-fuzz/seeds && for p in wall base_tool; do cat tests/data/programs/$p.src tests/data/programs/$p.dat > build-fuzz/seeds/${p}_krl.src; echo build-fuzz/seeds/${p}_krl.src; done); max_len=16384 ;;
  yaskawa_jbi) seeds=$(find_seeds tests/data/programs fuzz/seeds/yaskawa_jbi -name '*.JBI'); max_len=16384 ;;
  program_csv) seeds=$(find_seeds tests/data/programs -name '*.csv'); max_len=16384 ;;
  thermal_material) seeds=$(find_seeds models/data/materials fuzz/regressions/thermal_material -name '*.csv'); max_len=8192 ;;
  replay_log) seeds=$(find_seeds fuzz/seeds/replay_log fuzz/regressions/replay_log -type f ! -name README.md); max_len=8192 ;;
  png) seeds=$(find_seeds docs/images -name '*.png' -size -64k); max_len=65536 ;;
  *) echo "fuzz.sh: unknown target '$target' (stl, scenario, csv, urdf, mjcf, sweep, fanuc_ls, abb_rapid, gcode, program_csv, kuka_krl, yaskawa_jbi, thermal_material, replay_log, png)" >&2; exit 2 ;;
esac

if [ ! -f "$build/CMakeCache.txt" ]; then
  # ccache comes from CMakeLists.txt (WAAM_CCACHE, with CCACHE_BASEDIR), so a fresh worktree hits an earlier one's cache.
  cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
    -DWAAM_BUILD_FUZZERS=ON -DWAAM_BUILD_TESTS=OFF -DWAAM_BUILD_BENCHMARKS=OFF
fi
cmake --build "$build" -j"${WAAM_FUZZ_JOBS:-2}" --target "waam_fuzz_$target"

corpus=$build/corpus/$target
artifacts=$build/artifacts/$target
mkdir -p "$corpus" "$artifacts"
# shellcheck disable=SC2086
cp $seeds "$corpus"/
if [ -d "fuzz/regressions/$target" ]; then cp "fuzz/regressions/$target"/* "$corpus"/ 2>/dev/null || true; fi

export ASAN_OPTIONS=${ASAN_OPTIONS:-}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1}
exec "$build/fuzz/waam_fuzz_$target" "$corpus" -max_total_time="$seconds" -max_len="$max_len" -timeout=60 \
  -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$artifacts/" "$@"
