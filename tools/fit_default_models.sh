#!/usr/bin/env bash
# Refits the default process models in models/data/*.json from the transcribed tables with `waam fit`.
# Run from anywhere after building (build/waam); the JSON files record the data file relative to the repository.
set -euo pipefail
cd "$(dirname "$0")/.."
WAAM=${WAAM:-build/waam}
D=models/data
"$WAAM" fit csw "$D/dai2020_csw_table1.csv" -o "$D/csw.json"
# Table 18: the dissertation's fits use the feasible window 150-900 mm/min (row 1, 100 mm/min, gave a wavy wall).
"$WAAM" fit speed-height "$D/nguyen2022_table18_bead_vs_speed.csv" --speed-range 150 900 -o "$D/speed_height.json"
"$WAAM" fit width-height "$D/nguyen2022_table18_bead_vs_speed.csv" --speed-range 150 900 --degree 4 \
  -o "$D/width_height.json"
"$WAAM" fit void-length "$D/nguyen2022_appendixA1_junction_voids.csv" -q -o "$D/void_length.json"
