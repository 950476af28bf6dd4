#!/usr/bin/env bash
# Builds and runs every Google Benchmark executable (analysis/benchmarks/*_bench.cc) at low priority and writes one
# JSON file per executable into the given folder (default out/bench/perf), which `waam bench -o out/bench` puts in
# its report. Usage: tools/perf_bench.sh [out_dir] [regex]; the regex (Google Benchmark --benchmark_filter) runs a
# subset, e.g. 'Offset|Ik|Slice|Fit'.
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-out/bench/perf}"
filter="${2:-.}"
mkdir -p "$out"
targets=()
for src in analysis/benchmarks/*_bench.cc; do
  targets+=("waam_$(basename "${src%.cc}")")
done
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build -j"$(nproc)" --target "${targets[@]}"
for target in "${targets[@]}"; do
  exe="$(find build -type f -name "$target" -perm -u+x | head -n 1)"
  [ -n "$exe" ] || { echo "perf_bench: $target not built" >&2; exit 1; }
  echo "perf_bench: $target" >&2
  nice -n 10 "$exe" --benchmark_filter="$filter" --benchmark_out="$out/$target.json.tmp" \
    --benchmark_out_format=json > /dev/null
  mv "$out/$target.json.tmp" "$out/$target.json"
done
echo "perf_bench: results in $out/ (waam bench -o $(dirname "$out") includes them in report.html)" >&2
