#!/usr/bin/env bash
# Prints the Ding et al. (2014) Table 2 comparison for the four Ding-like scenarios: passes and weld path elements
# per layer with the hybrid baseline and the continuous path. Needs a built ./build/waam.
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-out/ding_table}"
printf '%-8s %10s %14s %16s %20s\n' shape hybrid_passes hybrid_elements continuous_passes continuous_elements
for shape in ding_a ding_b ding_c ding_d; do
  row="$shape"
  for pattern in hybrid continuous; do
    ./build/waam plan "scenarios/$shape.yaml" --set "path.pattern=$pattern" -o "$out/$shape-$pattern" -q --no-images >/dev/null
    row="$row $(python3 -c "import json,sys; d=json.load(open('$out/$shape-$pattern/plan.json')); print(d['passes']/d['layers'], d['path_elements']/d['layers'])")"
  done
  printf '%-8s %10s %14s %16s %20s\n' $row
done
echo "(per layer, averaged over the layers; bead width and layer height from each scenario)"
