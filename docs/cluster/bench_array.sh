#!/bin/bash
# Usage: sbatch --array=0-15 docs/cluster/bench_array.sh <sweep.yaml | scenario folder> <out dir>
#SBATCH --job-name=waam-shard
#SBATCH --cpus-per-task=8
#SBATCH --mem=16G
#SBATCH --time=04:00:00
set -euo pipefail
input=$1 out=$2
shards=$SLURM_ARRAY_TASK_COUNT
shard="$SLURM_ARRAY_TASK_ID/$shards"
threads=${SLURM_CPUS_PER_TASK:-1}
mem_gb=$(( ${SLURM_MEM_PER_NODE:-16384} * 8 / 10 / 1024 ))   # stay inside the job's allocation
if [[ -f $input ]] && grep -q '^base:' "$input"; then   # a sweep file, else scenarios
  waam sweep "$input" --shard "$shard" -j 2 --threads "$threads" --mem-gb "$mem_gb" -q -o "$out/shard_$SLURM_ARRAY_TASK_ID"
else
  waam bench "$input" --shard "$shard" -j 2 --threads "$threads" --mem-gb "$mem_gb" -q -o "$out/shard_$SLURM_ARRAY_TASK_ID"
fi
