#!/bin/bash
# One shard of a waam bench or sweep per Slurm array task (docs/CLUSTER.md):
#   sbatch --array=0-15 docs/cluster/bench_array.sh <sweep.yaml | scenario folder> <out dir>
# Shard K of N goes to <out dir>/shard_K; merge them with a dependent `waam bench --merge` job. The job's CPUs and
# memory reach waam as --threads and --mem-gb (80 % of the allocation). A bench whose runs did not all end as
# expected exits 3: that is a result (the merge reports it again), so the task still ends with 0. A requeued or
# resubmitted task reuses the runs its shard folder already holds. `waam` is taken from PATH, or from $WAAM.
#SBATCH --job-name=waam-shard
#SBATCH --cpus-per-task=8
#SBATCH --mem=16G
#SBATCH --time=04:00:00
#SBATCH --requeue
set -euo pipefail
[ $# -eq 2 ] || { echo "usage: sbatch --array=0-N bench_array.sh <sweep.yaml | scenario folder> <out dir>" >&2; exit 2; }
input=$1 out=$2
waam=${WAAM:-waam}
shards=${SLURM_ARRAY_TASK_COUNT:?not an array task: submit with sbatch --array=0-N}
index=${SLURM_ARRAY_TASK_ID:?not an array task}
threads=${SLURM_CPUS_PER_TASK:-1}
# The allocation's memory in MB: --mem gives SLURM_MEM_PER_NODE, --mem-per-cpu gives SLURM_MEM_PER_CPU.
if [ -n "${SLURM_MEM_PER_NODE:-}" ]; then
  mem_mb=$SLURM_MEM_PER_NODE
elif [ -n "${SLURM_MEM_PER_CPU:-}" ]; then
  mem_mb=$(( SLURM_MEM_PER_CPU * threads ))
else
  mem_mb=16384
fi
mem_gb=$(awk -v m="$mem_mb" 'BEGIN { printf "%.3f", m * 0.8 / 1024 }')   # stay inside the job's allocation
jobs=$(( threads < 2 ? 1 : 2 ))   # runs at once inside the task; each gets threads / jobs
command=bench
if [[ -f $input ]] && grep -q '^base:' "$input"; then command=sweep; fi   # a sweep file, else scenarios
status=0
"$waam" "$command" "$input" --shard "$index/$shards" -j "$jobs" --threads "$threads" --mem-gb "$mem_gb" -q \
  -o "$out/shard_$index" || status=$?
if [ "$status" -eq 3 ]; then
  echo "bench_array.sh: shard $index/$shards: some runs did not end as expected (exit 3); the merge reports them" >&2
  status=0
fi
exit "$status"
