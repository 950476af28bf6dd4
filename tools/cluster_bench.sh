#!/usr/bin/env bash
# The scheduler figures of docs/CLUSTER.md "Measured", on this machine, in one run:
#   1. how long tools/slurm_local.sh takes to bring the single-node cluster up (node idle);
#   2. a 12-run sweep (tests/cluster/tiny_block.yaml over 12 bead widths) as a 3-task Slurm array of
#      docs/cluster/bench_array.sh (--cpus-per-task=1) plus the merge, against `waam sweep -j 2` on the same machine;
#   3. `waam bench --merge` of 1,000 runs' results (4 shards of 250 entries, made from one real run's folder).
# Usage: tools/cluster_bench.sh [build dir]   (root; the packages of tools/install_deps.sh). Prints a table.
set -euo pipefail
src=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:-$src/build}" && pwd)
waam="$build/waam"
work=$(mktemp -d)
trap 'bash "$src/tools/slurm_local.sh" down "$work/cluster" >/dev/null 2>&1 || true; rm -rf "$work"' EXIT
now() { date +%s.%N; }
since() { awk -v a="$1" -v b="$(now)" 'BEGIN { printf "%.2f", b - a }'; }

t0=$(now)
bash "$src/tools/slurm_local.sh" up "$work/cluster" >/dev/null
up_s=$(since "$t0")
source "$work/cluster/env"
export PATH="$build:$PATH"

cat > "$work/sweep12.yaml" <<YAML
base: $src/tests/cluster/tiny_block.yaml
name: bench12
grid:
  path.bead_width_mm: [5, 5.25, 5.5, 5.75, 6, 6.25, 6.5, 6.75, 7, 7.25, 7.5, 7.75]
YAML
t0=$(now)
"$waam" sweep "$work/sweep12.yaml" -j 2 -q -o "$work/local" >/dev/null
local_s=$(since "$t0")

t0=$(now)
jid=$(sbatch --parsable --array=0-2 --cpus-per-task=1 --mem=2G -o /dev/null \
  "$src/docs/cluster/bench_array.sh" "$work/sweep12.yaml" "$work/array")
mid=$(sbatch --parsable --dependency=afterany:"$jid" -o /dev/null \
  --wrap "waam bench --merge $work/array/shard_0 $work/array/shard_1 $work/array/shard_2 -q -o $work/array/merged")
while [ -n "$(squeue -h -j "$jid,$mid" 2>/dev/null)" ]; do sleep 0.1; done
array_s=$(since "$t0")
/usr/bin/python3 "$src/tests/cluster/bench_json_equal.py" "$work/local/bench.json" "$work/array/merged/bench.json"

# 1,000 runs: one real run's folder repeated under 1,000 ids, in 4 shards of 250.
/usr/bin/python3 - "$work" <<'PY'
import json, os, shutil, sys
work = sys.argv[1]
local = json.load(open(f"{work}/local/bench.json"))
entry, run_dir = local["scenarios"][0], f"{work}/local/{local['scenarios'][0]['id']}"
for k in range(4):
    shard = dict(local)
    shard["scenarios"] = []
    shard["shard"] = {"index": k, "count": 4, "runs_total": 1000}
    shard.pop("sweep", None)
    os.makedirs(f"{work}/m/shard_{k}")
    for i in range(k, 1000, 4):
        e = dict(entry, id=f"run_{i:04d}")
        shard["scenarios"].append(e)
        shutil.copytree(run_dir, f"{work}/m/shard_{k}/run_{i:04d}", copy_function=os.link)
    json.dump(shard, open(f"{work}/m/shard_{k}/bench.json", "w"))
PY
t0=$(now)
"$waam" bench --merge "$work"/m/shard_0 "$work"/m/shard_1 "$work"/m/shard_2 "$work"/m/shard_3 -q -o "$work/m/merged" \
  >/dev/null || [ $? -eq 3 ]
merge_s=$(since "$t0")

echo "| figure | measured | aim |"
echo "| --- | --- | --- |"
echo "| slurm_local.sh up (node idle) | ${up_s} s | < 5 s |"
echo "| 12-run sweep, 3-task array + merge / waam sweep -j 2 | ${array_s} s / ${local_s} s = $(awk -v a="$array_s" -v b="$local_s" 'BEGIN { printf "%.2f", a / b }') | <= 1.3 |"
echo "| waam bench --merge of 1,000 runs (4 shards) | ${merge_s} s | < 2 s |"
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg), $(nproc) cores"
