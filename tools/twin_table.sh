#!/usr/bin/env bash
# Runs the deposition twin on the reproduction scenarios and prints its measures: the 003 Table 9 block with the
# existing and the proposed overlap model (boundary lag), and Ding's four shapes planned hybrid and continuous,
# three layers as Ding measured (Ra, waviness). Needs a built ./build/waam.
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-out/twin_table}"
field() { python3 -c "import json; d=json.load(open('$1/simulate.json')); print($2)"; }
printf '%-16s %-10s %6s %8s %8s %8s %8s %10s %8s %8s\n' scenario variant passes ra_mm wt_mm lag_mm voids vol_err_pct \
  top_mean top_min
for model in existing proposed; do
  dir="$out/block-$model"
  ./build/waam simulate scenarios/twin/block_proposed.yaml --set "path.overlap_model=$model" -o "$dir" -q \
    --no-images >/dev/null
  printf '%-16s %-10s %6s %8.3f %8.2f %8.2f %8s %10.4f %8.2f %8.2f\n' block_table9 "$model" "$(field "$dir" "d['beads']")" \
    "$(field "$dir" "d['ra_mm']")" "$(field "$dir" "d['waviness_mm']")" "$(field "$dir" "d['boundary_lag_mm']")" \
    "$(field "$dir" "d['voids']['count']")" "$(field "$dir" "d['volume_error_pct']")" \
    "$(field "$dir" "d['top_height']['mean_mm']")" "$(field "$dir" "d['top_height']['min_mm']")"
done
for shape in ding_a ding_b ding_c ding_d; do
  for pattern in hybrid continuous; do
    dir="$out/$shape-$pattern"
    ./build/waam simulate "scenarios/twin/${shape}_3layers.yaml" --set "path.pattern=$pattern" -o "$dir" -q \
      --no-images >/dev/null
    printf '%-16s %-10s %6s %8.3f %8.2f %8.2f %8s %10.4f %8.2f %8.2f\n' "$shape" "$pattern" "$(field "$dir" "d['beads']")" \
      "$(field "$dir" "d['ra_mm']")" "$(field "$dir" "d['waviness_mm']")" "$(field "$dir" "d['boundary_lag_mm']")" \
      "$(field "$dir" "d['voids']['count']")" "$(field "$dir" "d['volume_error_pct']")" \
      "$(field "$dir" "d['top_height']['mean_mm']")" "$(field "$dir" "d['top_height']['min_mm']")"
  done
done
echo "(Ra: Ding eq. 7 over the top layer, w/2 in from its outline; top_mean / top_min: Ding Fig. 13 over the same columns;"
echo " lag: 003 Fig. 24 along the mid section lines)"
