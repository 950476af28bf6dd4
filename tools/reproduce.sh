#!/usr/bin/env bash
# Regenerates the tables of measured figures that the docs print, from the build, and writes each into the docs
# between its markers <!-- reproduce:NAME --> and <!-- /reproduce:NAME -->, so the docs cannot drift from the code.
#   tools/reproduce.sh [--only NAME] [--list] [--out DIR]     (default: every table; outputs under out/reproduce)
# Tables (and what they cost on a 2-core machine):
#   ding_table     Ding Table 2: passes and elements per layer, hybrid vs continuous (seconds)
#   twin_table     the deposition twin on Table 9's block and Ding's four shapes (a few minutes)
#   compensation   waam compensate on the four bent tubes (several minutes)
# Needs a built ./build/waam (bash tools/test.sh --quick builds it).
set -euo pipefail
cd "$(dirname "$0")/.."
tables=(ding_table twin_table compensation)
only=""
out="out/reproduce"
while [ $# -gt 0 ]; do
  case "$1" in
    --list) printf '%s\n' "${tables[@]}"; exit 0 ;;
    --only) only="$2"; shift ;;
    --out) out="$2"; shift ;;
    -h|--help) sed -n '2,10p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "reproduce.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
  shift
done
if [ -n "$only" ] && ! printf '%s\n' "${tables[@]}" | grep -qx "$only"; then
  echo "reproduce.sh: unknown table '$only' (see --list)" >&2; exit 2
fi
[ -x build/waam ] || { echo "reproduce.sh: build/waam is missing: run bash tools/test.sh --quick first" >&2; exit 2; }
mkdir -p "$out"

# Writes stdin into every doc that has the markers of table $1 (between them, replacing what was there).
put() {
  local name=$1 text
  text=$(cat)
  local found=0
  for doc in README.md docs/*.md models/MODELS.md; do
    grep -q "<!-- reproduce:$name -->" "$doc" || continue
    found=1
    NAME="$name" TEXT="$text" python3 - "$doc" <<'PY'
import os, sys
path, name, text = sys.argv[1], os.environ["NAME"], os.environ["TEXT"]
doc = open(path).read()
begin, end = f"<!-- reproduce:{name} -->", f"<!-- /reproduce:{name} -->"
head, rest = doc.split(begin, 1)
_, tail = rest.split(end, 1)
tmp = path + ".tmp-reproduce"
open(tmp, "w").write(head + begin + "\n" + text + "\n" + end + tail)
os.replace(tmp, path)
PY
    echo "reproduce.sh: $name -> $doc"
  done
  [ "$found" = 1 ] || { echo "reproduce.sh: no doc has the markers of $name" >&2; exit 1; }
}

ding_table() {
  { echo '```'; bash tools/ding_table.sh "$out/ding_table"; echo '```'; } | put ding_table
}

twin_table() {
  { echo '```'; bash tools/twin_table.sh "$out/twin_table"; echo '```'; } | put twin_table
}

compensation() {
  for n in 1 2 3 4; do
    ./build/waam compensate "scenarios/tubes/part_$n.yaml" -o "$out/compensation/part_$n" \
      --model models/data/distortion_part1_demo.json --mode reduced --no-program --no-images -q --max-iter 2 \
      >/dev/null
  done
  python3 - "$out/compensation" <<'PY' | put compensation
import json, sys
names = {1: "I (circular 100 mm, R 150 mm, 90 deg)", 2: "II (80 -> 53 mm, R 314 mm)",
         3: "III (square-to-round 60 mm, R 260 mm, 60 deg)", 4: "IV (hexagonal 80 mm, R 250 mm)"}
print("| part | tolerance | build 0 max / p99 / axis | build 1 max / p99 / axis | max S-e (twin) | status |")
print("| --- | --- | --- | --- | --- | --- |")
for n in range(1, 5):
    j = json.load(open(f"{sys.argv[1]}/part_{n}/compensate.json"))
    it = j["iterations"]
    cell = lambda b: "%.2f / %.2f / %.2f" % (b["max_abs_deviation_mm"], b["p99_abs_deviation_mm"], b["axis_deviation_mm"])
    last = cell(it[1]) if len(it) > 1 else "-"
    print(f"| {names[n]} | {j['tolerance_mm']:.2f} | {cell(it[0])} | {last} | "
          f"{it[0].get('twin_correction_error_mm', 0.0):.2f} | {j['status']} |")
PY
}

for table in "${tables[@]}"; do
  if [ -z "$only" ] || [ "$only" = "$table" ]; then "$table"; fi
done
