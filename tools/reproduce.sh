#!/usr/bin/env bash
# Regenerates the tables of measured figures that the docs print, from the build, and writes each into the docs
# between its markers <!-- reproduce:NAME --> and <!-- /reproduce:NAME -->, so the docs cannot drift from the code.
#   tools/reproduce.sh [--only NAME] [--list] [--out DIR]     (default: every table; outputs under out/reproduce)
# Tables (and what they cost on a 2-core machine):
#   ding_table     Ding Table 2: passes and elements per layer, hybrid vs continuous (seconds)
#   twin_table     the deposition twin on Table 9's block and Ding's four shapes (a few minutes)
#   compensation   waam compensate on the four bent tubes (several minutes)
#   twin_tests     the twin's reproductions inside its tests: Table 9 block, 30 passes vs one, X-junction voids (a minute)
#   deposition_bench  waam_deposition_bench: build hour at three voxel sizes, the largest part (a minute)
#   distortion_fit    waam fit distortion from twin scans at known parameters (several minutes)
#   published      the papers' figures next to ours: waam bench on the scenarios models/data/reference_figures.csv names
# Needs a built ./build/waam (bash tools/test.sh --quick builds it).
set -euo pipefail
cd "$(dirname "$0")/.."
tables=(ding_table twin_table compensation twin_tests deposition_bench distortion_fit published)
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
    mkdir -p "$out/compensation"
    /usr/bin/time -f '%e %U %M' -o "$out/compensation/part_$n.time" \
      ./build/waam compensate "scenarios/tubes/part_$n.yaml" -o "$out/compensation/part_$n" \
      --model models/data/distortion_part1_demo.json --mode reduced --no-program --no-images -q --max-iter 2 \
      >/dev/null
  done
  python3 - "$out/compensation" <<'PY' | put compensation_memory
import sys
print("| part | peak RSS | wall | user CPU |")
print("| --- | --- | --- | --- |")
for n, name in zip(range(1, 5), ["I", "II", "III", "IV"]):
    wall, user, rss = open(f"{sys.argv[1]}/part_{n}.time").read().split()[-3:]
    w = float(wall)
    print(f"| {name} | {int(rss) / 1048576:.2f} GB | {int(w // 60)}:{w % 60:04.1f} | {float(user):.1f} s |")
PY
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

twin_tests() {
  local filter='SurfaceMetrics.BlockExperimentBoundaryLag:SurfaceMetrics.ContinuousPathIsSmootherThanManyStarts'
  filter+=':Voids.XJunctionVoidGrowsAsTheAngleSharpens'
  [ -x build/tests/waam_twin_tests ] || { echo "reproduce.sh: build/tests/waam_twin_tests is missing" >&2; exit 2; }
  # The tests print one line per figure next to the paper's; gtest's own lines start with '[' or 'Note:'.
  { echo '```'; ./build/tests/waam_twin_tests --gtest_filter="$filter" | grep -vE '^(\[|Note:|Running main|$)'
    echo '```'; } | put twin_tests
}

deposition_bench() {
  local bench=build/analysis/benchmarks/waam_deposition_bench
  [ -x "$bench" ] || { echo "reproduce.sh: $bench is missing" >&2; exit 2; }
  "$bench" --benchmark_format=json --benchmark_out="$out/deposition_bench.json" >/dev/null
  python3 - "$out/deposition_bench.json" <<'PY' | { echo '```'; cat; echo '```'; } | put deposition_bench
import json, sys
runs = json.load(open(sys.argv[1]))["benchmarks"]
print("%-34s %8s %8s %11s %11s %9s %9s %9s" % ("case", "bead_m", "wall_s", "bead_mm/s", "voxels/s", "x_real", "vol_err%",
                                               "rss_MB"))
for r in runs:
    name = r["name"].split("/manual_time")[0]
    print("%-34s %8.1f %8.2f %11.0f %11.0f %9.0f %9.4f %9.0f" % (
        name, r["bead_m"], r["real_time"], r["bead_mm_per_s"], r["voxels_per_s"], r["faster_than_real"],
        r["volume_error_pct"], r["peak_rss_mb"]))
print("(BM_DepositBuildHour/N: voxel N/100 mm; wall time on this machine; x_real = arc time at 8 mm/s over wall time)")
PY
}

distortion_fit() {
  local d="$out/distortion_fit" sb=scenarios/distortion/small_bent_tube.yaml p1=scenarios/tubes/part_1.yaml
  local demo=models/data/distortion_part1_demo.json fe=models/data/distortion.json
  mkdir -p "$d"
  # Start files: the truth with strain and vertical_ratio scaled.
  scale() { python3 - "$1" "$2" "$3" "$4" <<'PY'
import json, sys
m = json.load(open(sys.argv[1]))
m["params"]["strain"] *= float(sys.argv[3]); m["params"]["vertical_ratio"] *= float(sys.argv[4])
m.pop("note", None)
open(sys.argv[2], "w").write(json.dumps(m, indent=2))
PY
  }
  scale "$demo" "$d/start_sb.json" 0.5 1.5
  scale "$fe" "$d/start_fe.json" 0.5 1.5
  scale "$demo" "$d/start_p1_mild.json" 0.8 1.2
  scale "$demo" "$d/start_p1.json" 0.5 1.5
  local q=(--no-program --no-images -q --max-iter 0)
  ./build/waam compensate "$sb" --model "$demo" "${q[@]}" --tol-mm 1 -o "$d/scan_sb" >/dev/null
  ./build/waam compensate "$sb" "${q[@]}" --tol-mm 1 -o "$d/scan_sb_fe" >/dev/null
  ./build/waam compensate "$p1" --model "$demo" "${q[@]}" -o "$d/scan_p1" >/dev/null
  fit() {  # name scan scenario start extra...
    local name=$1 scan=$2 scenario=$3 start=$4; shift 4
    /usr/bin/time -f '%e %M' -o "$d/$name.time" ./build/waam fit distortion "$scan" --scenario "$scenario" \
      --start "$start" -q -o "$d/$name.json" "$@" >/dev/null || true
  }
  fit sb_reduced "$d/scan_sb/scan_before.ply" "$sb" "$d/start_sb.json" --mode reduced
  fit sb_fe "$d/scan_sb_fe/scan_before.ply" "$sb" "$d/start_fe.json"
  fit p1_mild "$d/scan_p1/scan_before.ply" "$p1" "$d/start_p1_mild.json" --mode reduced
  fit p1_far "$d/scan_p1/scan_before.ply" "$p1" "$d/start_p1.json" --mode reduced
  python3 - "$d" "$demo" "$fe" <<'PY' | put distortion_fit
import json, os, sys
d, demo, fe = sys.argv[1], json.load(open(sys.argv[2]))["params"], json.load(open(sys.argv[3]))["params"]
rows = [("small bent tube, reduced", "sb_reduced", demo, "x0.5, x1.5"),
        ("small bent tube, fe", "sb_fe", fe, "x0.5, x1.5"),
        ("part I, reduced", "p1_mild", demo, "x0.8, x1.2"),
        ("part I, reduced", "p1_far", demo, "x0.5, x1.5")]
print("| case | truth (strain, vertical_ratio) | start | fitted | error | rms start -> fitted | Ceres iterations "
      "(termination) | wall, peak RSS |")
print("| --- | --- | --- | --- | --- | --- | --- | --- |")
for label, name, truth, start in rows:
    wall, rss = open(os.path.join(d, name + ".time")).read().split()[-2:]
    t = (truth["strain"], truth["vertical_ratio"])
    path = os.path.join(d, name + ".json")
    if not os.path.exists(path):
        print(f"| {label} | {t[0]:g}, {t[1]:g} | {start} | not converged (not written) | - | - | - | "
              f"{float(wall):.0f} s, {int(rss) / 1024:.0f} MB |")
        continue
    f = json.load(open(path))["fit"]
    s, v = f["fitted"]["strain"], f["fitted"]["vertical_ratio"]
    err = "%+.3g %%, %+.3g %%" % (100 * (s / t[0] - 1), 100 * (v / t[1] - 1))
    print(f"| {label} | {t[0]:g}, {t[1]:g} | {start} | {s:.7g}, {v:.7g} | {err} | "
          f"{f['rms_start_mm']:.3g} -> {f['rms_mm']:.2g} mm | {f['solver']['iterations']} "
          f"({f['solver']['termination']}) | {float(wall):.0f} s, {int(rss) / 1024:.0f} MB |")
PY
}

published() {
  local d="$out/published" names
  names=$(python3 - <<'PY'
import csv
rows = csv.DictReader(l for l in open("models/data/reference_figures.csv") if not l.startswith("#"))
print(" ".join(sorted({r["scenario"] for r in rows if r["scenario"]})))
PY
)
  local files=()
  for n in $names; do
    f=$(grep -lE "^name: *$n *$" scenarios/*.yaml scenarios/*/*.yaml | head -n 1)
    [ -n "$f" ] || { echo "reproduce.sh: no scenario named $n" >&2; exit 1; }
    files+=("$f")
  done
  ./build/waam bench "${files[@]}" -o "$d" -q >/dev/null
  python3 - "$d/bench.json" <<'PY' | put published
import json, sys
rows = json.load(open(sys.argv[1]))["reference"]
print("| source | quantity | published | ours | scenario |")
print("| --- | --- | --- | --- | --- |")
for r in rows:
    ours = r["ours"]
    if isinstance(ours, float):
        ours = "%.4g" % ours
    elif ours is None:
        ours = "-"
    unit = "" if r["unit"] == "1" else " " + r["unit"]
    print(f"| {r['source']} | {r['quantity']} | {r['published']} | {ours}{unit} | `{r['scenario']}` |")
PY
}

for table in "${tables[@]}"; do
  if [ -z "$only" ] || [ "$only" = "$table" ]; then "$table"; fi
done
