#!/usr/bin/env bash
# Regenerates the tables of measured figures that the docs print, from the build, and writes each into the docs
# between its markers <!-- reproduce:NAME --> and <!-- /reproduce:NAME -->, so the docs cannot drift from the code.
#   tools/reproduce.sh [--only TABLE] [--list] [--check] [--out DIR]   (default: every table; outputs under
#   out/reproduce; --check only checks that every table has its markers in the docs and every marker its table)
# Tables, the markers each one writes (when they differ from its name), where, and their cost on a 2-core machine:
#   ding_table        Ding Table 2: passes and elements per layer, hybrid vs continuous; deposition_twin.md (seconds)
#   twin_table        the deposition twin on Table 9's block and Ding's four shapes; deposition_twin.md (a few minutes)
#   compensation      waam compensate on the four bent tubes; also compensation_memory; compensation.md (several
#                     minutes)
#   twin_tests        the twin's reproductions inside its tests: Table 9 block, 30 passes vs one, X-junction voids;
#                     deposition_twin.md (a minute; needs build/tests/waam_twin_tests)
#   deposition_bench  waam_deposition_bench: build hour at three voxel sizes, the largest part;
#                     deposition_twin.md (a minute)
#   distortion_fit    waam fit distortion from twin scans at known parameters;
#                     deposition_twin.md (several minutes)
#   published         the papers' figures next to ours: waam bench on the scenarios models/data/reference_figures.csv
#                     names; BENCHMARKS.md (several minutes)
#   rib_web           waam plan of the rib web (contour, Eulerian with and without void filling): rib_web_passes;
#                     waam tune-voids on the three junctions: rib_web_junctions; waam simulate of the 12-layer cross:
#                     rib_web_cross; rib_web.md (under a minute)
#   model_fits        waam fit csw / speed-height / width-height next to the papers' values: model_fits, and the
#                     printed laws checked on their tables: model_fit_checks; MODELS.md (seconds)
#   void_length_fit   waam fit void-length and nine variants of it: void_length_variants; MODELS.md (several
#                     minutes, the --loo run most of it)
#   fit_bench         waam_fit_bench: CPU time of each fit; MODELS.md (a minute)
#   check_bench       waam_check_bench: a build hour of path through waam check's checks; CELL.md (seconds)
#   cup_support       waam plan of cup_two_handles.yaml split and in one piece: support metal; RESULTS.md (a minute)
#   peers             tools/peers.sh: PrusaSlicer and KDL beside waam plan and the closed-form IK; BENCHMARKS.md
#                     (installs prusa-slicer and liborocos-kdl-dev; several minutes)
#   readme_figures    waam simulate of the planar demo and the thruster blades: deviation, voids; RESULTS.md (a minute)
#   threads           wall time of plan, check, deviation, compensate, tune-voids and fit distortion on 1 and 2
#                     threads, back to back; BENCHMARKS.md (several minutes)
#   resolve           waam check of every scenario with cell.resolve fixed and optimise: margins before and after,
#                     the spins chosen, both wall times; CELL.md (ten minutes or more)
#   place             waam place on the tube part II and the planted clamp fault: layouts, passes, wall time;
#                     CELL.md (a minute)
#   thermal_wall      waam thermal on scenarios/thermal/wall_interpass.yaml: per-layer interpass temperature, peak
#                     and wait, the energy balance; its pictures into docs/images/thermal_wall_*.png; THERMAL.md
#                     (seconds)
#   notebooks         the example notebooks of python/examples/notebooks run with nbclient; their plots into
#                     docs/images/notebook_*.png; README.md (under a minute; needs the Python module in build/python)
# Needs a built ./build/waam (bash tools/test.sh --quick builds it); the *_bench tables and twin_tests need their
# executables (cmake --build build --target NAME).
set -euo pipefail
cd "$(dirname "$0")/.."
tables=(ding_table twin_table compensation compensation_heat twin_tests deposition_bench distortion_fit published rib_web model_fits
        void_length_fit fit_bench check_bench cup_support readme_figures peers threads resolve place thermal_wall notebooks)
only=""
out="out/reproduce"
check=0
while [ $# -gt 0 ]; do
  case "$1" in
    --list) printf '%s\n' "${tables[@]}"; exit 0 ;;
    --check) check=1 ;;
    --only) only="$2"; shift ;;
    --out) out="$2"; shift ;;
    -h|--help) awk 'NR > 1 && !/^#/ { exit } NR > 1 { sub(/^# ?/, ""); print }' "$0"; exit 0 ;;
    *) echo "reproduce.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
  shift
done
# --check: every marker pair in the docs is written by some `put NAME` here, and every `put NAME` has its markers.
if [ "$check" = 1 ]; then
  python3 - "$0" README.md docs/*.md models/MODELS.md <<'PY'
import re, sys
script, docs = open(sys.argv[1]).read(), sys.argv[2:]
puts = set(re.findall(r"\| put (\w+)", script))
marked = {}
for doc in docs:
    text = open(doc).read()
    for name in re.findall(r"<!-- reproduce:(\w+) -->", text):
        if f"<!-- /reproduce:{name} -->" not in text:
            print(f"{doc}: <!-- reproduce:{name} --> has no closing marker")
        marked.setdefault(name, []).append(doc)
bad = [f"{', '.join(marked[n])}: markers of {n}, which no table writes" for n in sorted(set(marked) - puts)]
bad += [f"table {n} has no markers in any doc" for n in sorted(puts - set(marked))]
print("\n".join(bad) if bad else f"reproduce.sh: {len(puts)} tables, each with its markers")
sys.exit(1 if bad else 0)
PY
  exit $?
fi
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

# Part III today and with the heat shaping its beads and strains (docs/compensation.md, "Heat into shape").
compensation_heat() {
  local d="$out/compensation_heat"
  mkdir -p "$d"
  # part_3_heat with the beads only (its continuous spiral stays above mechanical melting: the strain law refuses
  # it), part_3_interpass with beads and strains after a 250 degC interpass wait (docs/compensation.md).
  for s in part_3 part_3_heat part_3_interpass; do
    local extra=(); [ "$s" = part_3_heat ] && extra=(--set thermal.shape.distortion=false)
    /usr/bin/time -f '%e %U %M' -o "$d/$s.time" ./build/waam compensate "scenarios/tubes/$s.yaml" -o "$d/$s" \
      "${extra[@]}" --model models/data/distortion_part1_demo.json --mode reduced --no-program --no-images -q \
      --max-iter 2 >/dev/null
  done
  python3 - "$d" <<'PY' | put compensation_heat
import json, sys
d = sys.argv[1]
print("| part III | tolerance | build 0 max / p99 / axis | build 1 max / p99 / axis | build 0 vs target | status | user CPU |")
print("| --- | --- | --- | --- | --- | --- | --- |")
for s, label in (("part_3", "today (`part_3.yaml`)"),
                 ("part_3_heat", "heat-shaped beads (`part_3_heat.yaml`, `--set thermal.shape.distortion=false`)"),
                 ("part_3_interpass", "heat-shaped beads and strains, 250 degC interpass (`part_3_interpass.yaml`)")):
    j = json.load(open(f"{d}/{s}/compensate.json"))
    it = j["iterations"]
    cell = lambda b: "%.2f / %.2f / %.2f" % (b["max_abs_deviation_mm"], b["p99_abs_deviation_mm"], b["axis_deviation_mm"])
    last = cell(it[1]) if len(it) > 1 else "-"
    user = float(open(f"{d}/{s}.time").read().split()[-2])
    print(f"| {label} | {j['tolerance_mm']:.2f} | {cell(it[0])} | {last} | {it[0]['max_abs_vs_target_mm']:.2f} | "
          f"{j['status']} | {user:.1f} s |")
h = json.load(open(f"{d}/part_3_heat/compensate.json"))["heat"]
ip = h["interpass_c"][1:]
print()
print(f"Heat run: build {h['build_time_s']:.0f} s, thermal model {h['thermal_wall_s']:.1f} s wall; the temperature a "
      f"layer is laid on {min(ip):.0f}-{max(ip):.0f} degC (mean {sum(ip) / len(ip):.0f}, layers 1-{len(ip)}); "
      f"bead height factor {min(h['bead_height_factor']):.3f}-{max(h['bead_height_factor']):.3f}, width factor "
      f"{min(h['bead_width_factor']):.3f}-{max(h['bead_width_factor']):.3f}.")
h = json.load(open(f"{d}/part_3_interpass/compensate.json"))["heat"]
ip, f = h["interpass_c"][1:], h["strain_factor"]
print()
print(f"Interpass run: thermal model {h['thermal_wall_s']:.1f} s wall; the temperature a layer is laid on "
      f"{min(ip):.0f}-{max(ip):.0f} degC (mean {sum(ip) / len(ip):.0f}, layers 1-{len(ip)}; "
      f"reference {h['reference_interpass_c']:.0f} degC, mechanical melting {h['mechanical_melting_c']:.0f} degC); "
      f"strain factor {min(f):.3f}-{max(f):.3f} (mean {sum(f) / len(f):.3f}); bead height factor "
      f"{min(h['bead_height_factor']):.3f}-{max(h['bead_height_factor']):.3f}.")
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

rib_web() {
  local d="$out/rib_web" r=scenarios/ribweb
  mkdir -p "$d"
  ./build/waam plan "$r/rib_web_contour.yaml" -o "$d/contour" -q >/dev/null
  ./build/waam plan "$r/rib_web_eulerian.yaml" -o "$d/eulerian_none" -q --set path.void_filling.mode=none >/dev/null
  ./build/waam plan "$r/rib_web_eulerian.yaml" -o "$d/eulerian" -q >/dev/null
  python3 - "$d" <<'PY' | put rib_web_passes
import json, sys
d = sys.argv[1]
rows = [("contour (`rib_web_contour.yaml`)", "contour"),
        ("eulerian, no void filling (`rib_web_eulerian.yaml --set path.void_filling.mode=none`)", "eulerian_none"),
        ("eulerian, lambda = 1 at the junctions of 3-4 ribs (`rib_web_eulerian.yaml`)", "eulerian")]
print("| path | passes per layer | layer time (timeline) | arc on / travel per layer | weld / travel per layer | "
      "corrected turning points |")
print("| --- | --- | --- | --- | --- | --- |")
for label, name in rows:
    p = json.load(open(f"{d}/{name}/plan.json"))
    n = p["layers"]
    t = p["timeline"]
    passes = sorted(set(p["passes_per_layer"]))
    print(f"| {label} | {' - '.join(map(str, passes))} | {p['estimated_time_s'] / n:.1f} s | "
          f"{t['arc_on_s'] / n:.1f} / {t['travel_s'] / n:.1f} s | "
          f"{p['weld_length_mm'] / n:.0f} / {p['travel_length_mm'] / n:.0f} mm | "
          f"{p['void_filling']['corrected_corners'] / n:g} |")
# The paper's row, as printed in Nguyen 2022 Table 13 (not computed).
print("| paper, Table 13 (contour vs Eulerian) | 5 vs 1 | 230 s vs 190 s | | | |")
PY
  # Junction classes tuned in the twin; the cross also at a ten times lower threshold.
  local j
  for j in cross_junction k_junction three_rib_junction; do
    ./build/waam tune-voids "$r/$j.yaml" -o "$d/tune_$j" -q >/dev/null
  done
  ./build/waam tune-voids "$r/cross_junction.yaml" -o "$d/tune_cross_fine" --threshold-mm3 0.1 -q >/dev/null
  python3 - "$d" <<'PY' | put rib_web_junctions
import json, sys
d = sys.argv[1]
# Appendix A1 of Nguyen 2022: the measured void length of the same junction class after 5 layers (constants).
a1 = {"cross_junction": "D1: 3.0 mm", "k_junction": "E1: 5.0 mm", "three_rib_junction": "A1: 0.8 mm"}
rows = [("cross_junction", "tune_cross_junction"), ("k_junction", "tune_k_junction"),
        ("three_rib_junction", "tune_three_rib_junction"), ("cross_junction", "tune_cross_fine")]
print("| scenario | junction | threshold | plain: void, L | lambda = 1: shift, void | tuned: shift, void (trials) "
      "| peak: plain / tuned | Appendix A1 L (5 layers) |")
print("| --- | --- | --- | --- | --- | --- | --- | --- |")
for scenario, name in rows:
    t = json.load(open(f"{d}/{name}/tune.json"))
    for j in t["junctions"]:
        p, g, u = j["plain"], j["geometric"], j["tuned"]
        tuned = f"{u['shift_mm']:.2f} mm, {u['void_volume_mm3']:.2f} mm^3 ({j['trials']})"
        if not j["converged"]:
            tuned += ", not converged"
        print(f"| `{scenario}` | {j['class']} | {t['threshold_mm3']:g} mm^3 | {p['void_volume_mm3']:.2f} mm^3, "
              f"{p['void_length_mm']:.1f} mm | {g['shift_mm']:.2f} mm, {g['void_volume_mm3']:.2f} mm^3 | {tuned} | "
              f"{p['peak_height_mm']:.1f} / {u['peak_height_mm']:.1f} mm | {a1[scenario]} |")
PY
  # The whole 12-layer cross with plain contours, lambda = 1 and the shift tuned at the lower threshold.
  local m
  for m in none fixed tuned; do
    ./build/waam simulate "$r/cross_junction.yaml" -o "$d/cross_$m" -q --set path.void_filling.mode=$m \
      --set path.void_filling.tune_file="$PWD/$d/tune_cross_fine/tune.json" >/dev/null
  done
  python3 - "$d" <<'PY' | put rib_web_cross
import json, sys
d = sys.argv[1]
shift = json.load(open(f"{d}/tune_cross_fine/tune.json"))["junctions"][0]["shift_mm"]
rows = [("plain (`mode=none`)", "none"), ("lambda = 1 (`mode=fixed`)", "fixed"),
        (f"tuned, shift {shift:.2f} mm (`mode=tuned`)", "tuned")]
print("| void filling | valleys: count, volume | enclosed voids: count, volume | smaller voids: count, volume |")
print("| --- | --- | --- | --- |")
for label, name in rows:
    s = json.load(open(f"{d}/cross_{name}/simulate.json"))
    v, w = s["valleys"], s["voids"]
    print(f"| {label} | {v['count']}, {v['volume_mm3']:.2f} mm^3 | {w['count']}, {w['volume_mm3']:.2f} mm^3 | "
          f"{w['smaller']['count']}, {w['smaller']['volume_mm3']:.2f} mm^3 |")
PY
}

model_fits() {
  local d="$out/model_fits" D=models/data
  mkdir -p "$d"
  local t18="$D/nguyen2022_table18_bead_vs_speed.csv"
  ./build/waam fit csw "$D/dai2020_csw_table1.csv" -q -o "$d/csw.json" >/dev/null
  ./build/waam fit speed-height "$t18" --speed-range 150 900 -q -o "$d/speed_height.json" >/dev/null
  ./build/waam fit speed-height "$t18" --speed-range 150 900 --space log -q -o "$d/speed_height_log.json" >/dev/null
  ./build/waam fit width-height "$t18" --speed-range 150 900 --degree 4 -q -o "$d/width_height.json" >/dev/null
  ./build/waam fit width-height "$t18" --degree 4 -q -o "$d/width_height_all_rows.json" >/dev/null
  # Table 18 with row 6 at its printed 300 mm/min (our copy has 350: models/data/nguyen2022_table18_bead_vs_speed.csv).
  awk -F, 'BEGIN { OFS = "," } !/^#/ && $1 == "6" { $2 = 300 } { print }' "$t18" >"$d/table18_printed.csv"
  ./build/waam fit speed-height "$d/table18_printed.csv" --speed-range 150 900 -q -o "$d/speed_height_300.json" \
    >/dev/null
  python3 - "$d" <<'PY' | put model_fits
import json, sys
d = sys.argv[1]
csw, sh, wh = (json.load(open(f"{d}/{n}.json")) for n in ("csw", "speed_height", "width_height"))
# The papers' printed values (Dai et al. 2020 sec. 4; Nguyen 2022 eq. 6.6-6.7, Table 18-19), constants.
print("| model (command) | parameter / statistic | this fit | paper |")
print("| --- | --- | --- | --- |")
p, s = csw["params"], csw["fit"]["stats"]
print(f"| CSW `waam fit csw models/data/dai2020_csw_table1.csv` | m | {p['m']:.6g} | 84.65 |")
print(f"| | p [mm^2] | {p['p']:.6g} | 52.74 |")
print(f"| | t [mm] | {p['t']:.6g} | -1.862 |")
print(f"| | R^2 (\"confidence coefficient\") | {s['r2']:.6g} | 98.02 % |")
print(f"| | rmse_dof [mm] (the paper's \"RMSE\") | {s['rmse_dof']:.5g} | 0.2777 |")
print(f"| | rmse [mm] | {s['rmse']:.6g} | - |")
p, s, sl = sh["params"], sh["fit"]["stats"], sh["fit"]["stats_log_v"]
print(f"| speed-height `--speed-range 150 900` (v residuals) | a [mm/min] | {p['a']:.6g} | 686.4 |")
print(f"| | b | {p['b']:.6g} | -2.069 |")
print(f"| | R^2 of ln v | {sl['r2']:.6g} | 0.9923 |")
print(f"| | R^2 of v | {s['r2']:.6g} | - |")
print(f"| | rmse / rmse_dof [mm/min] | {s['rmse']:.2f} / {s['rmse_dof']:.2f} | - |")
c, s = wh["params"]["c"], wh["fit"]["stats"]
w = lambda h: sum(ck * h ** k for k, ck in enumerate(c))
print(f"| width-height quartic `--speed-range 150 900` | c0..c4 [mm] | {', '.join('%.6g' % x for x in c)} | "
      "4.3077, -11.823, 18.132, -8.8702, 1.5093 |")
print(f"| | R^2 | {s['r2']:.6g} | 0.9886 |")
print(f"| | rmse / rmse_dof [mm] | {s['rmse']:.4f} / {s['rmse_dof']:.4f} | - |")
print(f"| | w at h = 1.01 / 1.49 / 1.84 mm (Table 19) | {w(1.01):.3f} / {w(1.49):.3f} / {w(1.84):.3f} | "
      "3.29 / 5.04 / 5.98 |")
PY
  python3 - "$d" "$D" <<'PY' | put model_fit_checks
import csv, json, math, sys
d, data = sys.argv[1], sys.argv[2]
def table(name):
    return list(csv.DictReader(l for l in open(f"{data}/{name}") if not l.startswith("#")))
def stats(y, f, k):  # R^2, rmse_dof of predictions f against y with k parameters
    mean = sum(y) / len(y)
    sse = sum((a - b) ** 2 for a, b in zip(y, f))
    return 1 - sse / sum((a - mean) ** 2 for a in y), math.sqrt(sse / (len(y) - k))
print("| check | R^2 | rmse_dof | parameters |")
print("| --- | --- | --- | --- |")
# The printed laws evaluated on the tables they were fitted to.
t1 = table("dai2020_csw_table1.csv")
y = [float(r["width_mm"]) for r in t1]
f = [84.65 * float(r["travel_speed_mm_per_min"]) ** (-1 / 3) + 52.74 / float(r["curvature_radius_mm"]) - 1.862
     for r in t1]
r2, rd = stats(y, f, 3)
print(f"| Dai's printed CSW law on Table 1 ({len(y)} rows) | {r2:.4f} | {rd:.4f} mm | 84.65, 52.74, -1.862 |")
t18 = [r for r in table("nguyen2022_table18_bead_vs_speed.csv") if 150 <= float(r["travel_speed_mm_per_min"]) <= 900]
y = [float(r["travel_speed_mm_per_min"]) for r in t18]
f = [686.4 * float(r["height_mm"]) ** -2.069 for r in t18]
r2, rd = stats(y, f, 2)
print(f"| Nguyen's printed speed-height law on Table 18 rows 2-17 (R^2 of v) | {r2:.4f} | {rd:.2f} mm/min | "
      "a = 686.4, b = -2.069 |")
j = json.load(open(f"{d}/speed_height_log.json"))
p = j["params"]
print(f"| speed-height fitted in ln v (`--space log`), R^2 of ln v | {j['fit']['stats_log_v']['r2']:.6g} | - | "
      f"a = {p['a']:.6g}, b = {p['b']:.5g} |")
j = json.load(open(f"{d}/speed_height_300.json"))
print(f"| speed-height with Table 18 row 6 at its printed 300 mm/min, R^2 of ln v | "
      f"{j['fit']['stats_log_v']['r2']:.4f} | - | a = {j['params']['a']:.6g}, b = {j['params']['b']:.5g} |")
j = json.load(open(f"{d}/width_height_all_rows.json"))
print(f"| width-height quartic on all {j['fit']['stats']['n']} rows of Table 18 (no `--speed-range`) | "
      f"{j['fit']['stats']['r2']:.4f} | {j['fit']['stats']['rmse_dof']:.4f} mm | "
      f"c = {', '.join('%.3f' % x for x in j['params']['c'])} |")
PY
}

void_length_fit() {
  local d="$out/void_length_fit" csv=models/data/nguyen2022_appendixA1_junction_voids.csv
  mkdir -p "$d"
  # name and extra options of each variant of `waam fit void-length`
  local variants=("default:" "seed2:--seed 2" "seed3:--seed 3" "loo:--loo" "best1:--best-only --seed 1"
                  "best2:--best-only --seed 2" "best3:--best-only --seed 3" "fixed_l2:--no-bayesian --l2 0.1"
                  "sorted:--angle-order sorted_descending" "baseline:--kind baseline")
  local v
  for v in "${variants[@]}"; do
    # shellcheck disable=SC2086  # the options are words
    /usr/bin/time -f '%e %U' -o "$d/${v%%:*}.time" \
      ./build/waam fit void-length "$csv" -q -o "$d/${v%%:*}.json" ${v#*:} >/dev/null
  done
  python3 - "$d" <<'PY' | put void_length_variants
import json, sys
d = sys.argv[1]
rows = [("default (ensemble of 5), 5-fold, seed 1", "default"), ("default, `--seed 2` (restarts and folds)", "seed2"),
        ("default, `--seed 3`", "seed3"), ("default, `--loo`", "loo"),
        ("`--best-only` (seed 1)", "best1"), ("`--best-only --seed 2`", "best2"), ("`--best-only --seed 3`", "best3"),
        ("`--no-bayesian --l2 0.1`", "fixed_l2"), ("`--angle-order sorted_descending`", "sorted")]
def held(j, key):
    return " / ".join("%.2f" % h[key] for h in j["holdout"])
def cpu(name):  # user CPU seconds of the whole `waam fit void-length` run
    return "%.1f s" % float(open(f"{d}/{name}.time").read().split()[-1])
print("| variant (extra options) | in-sample R^2, rmse / rmse_dof [mm] | CV MAE / RMSE / max [mm] | under by > 1.3 mm "
      "| F7 / H3 / H15 from the other 60 [mm] | CPU of the run |")
print("| --- | --- | --- | --- | --- | --- |")
def row(label, j, cv, key, time, fit=None):
    s = (fit or j)["fit"]["stats"]
    print(f"| {label} | {s['r2']:.4f}, {s['rmse']:.2f} / {s['rmse_dof']:.2f} | {cv['cv_mae_mm']:.2f} / "
          f"{cv['cv_rmse_mm']:.2f} / {cv['cv_max_abs_mm']:.2f} | {100 * cv['cv_share_under_tolerance']:.1f} % | "
          f"{held(j, key)} | {time} |")
for label, name in rows:
    j = json.load(open(f"{d}/{name}.json"))
    if "effective_params" in j.get("training", {}) and name == "default":
        label += f"; gamma = {j['training']['effective_params']:.1f} effective parameters"
    row(label, j, j["cross_validation"]["network"], "network_mm", cpu(name))
b = json.load(open(f"{d}/baseline.json"))
p = b["params"]
row(f"baseline (`--kind baseline`; a = {p['a']:.3f} mm, b = {p['b']:.3f} mm), 5-fold", b,
    b["cross_validation"]["baseline"], "baseline_mm", cpu("baseline"))
loo = json.load(open(f"{d}/loo.json"))
row("baseline, `--loo`", loo, loo["cross_validation"]["baseline"], "baseline_mm", "(in the `--loo` run)", fit=b)
# Nguyen 2022 Table 11 and Appendix A2, constants.
print("| dissertation (Table 11, Appendix A2) | - | - | - | 24.42 / 6.3 / 7.93 (measured 24.5 / 5.5 / 7.0) | - |")
PY
}

fit_bench() {
  local bench=build/analysis/benchmarks/waam_fit_bench
  [ -x "$bench" ] || { echo "reproduce.sh: $bench is missing" >&2; exit 2; }
  "$bench" --benchmark_format=json --benchmark_out="$out/fit_bench.json" >/dev/null
  python3 - "$out/fit_bench.json" <<'PY' | put fit_bench
import json, sys
what = {"BM_FitCsw": "CSW fit (Dai Table 1, 12 rows)",
        "BM_FitSpeedHeightPowerLaw": "speed-height power law (Table 18)",
        "BM_FitWidthHeightQuartic": "width-height quartic (Table 18)",
        "BM_TrainVoidNetwork/1": "void-length network, one restart (63 junctions)",
        "BM_TrainVoidNetwork/5": "void-length network, five restarts (the default)",
        "BM_VoidNetworkCrossValidation5Fold/iterations:1": "5-fold CV of the network (5 trainings of 5 restarts)",
        "BM_VoidBaselineCrossValidation5Fold": "5-fold CV of the baseline"}
print("| benchmark | what | CPU time |")
print("| --- | --- | --- |")
def duration(t, unit):  # a CPU time in the unit that keeps it between 1 and 1000
    t *= {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}[unit]
    for scale, name in ((1.0, "s"), (1e-3, "ms"), (1e-6, "us")):
        if t >= scale:
            return "%.3g %s" % (t / scale, name)
    return "%.3g us" % (t / 1e-6)
for r in json.load(open(sys.argv[1]))["benchmarks"]:
    print("| `%s` | %s | %s |" % (r["name"], what.get(r["name"], ""), duration(r["cpu_time"], r["time_unit"])))
PY
}

check_bench() {
  local bench=build/analysis/benchmarks/waam_check_bench
  [ -x "$bench" ] || { echo "reproduce.sh: $bench is missing" >&2; exit 2; }
  # One core: the check's parallel loops get one thread.
  local one=()
  command -v taskset >/dev/null && one=(taskset -c 0)
  WAAM_CHECK_EXPORT="$out/check_fcl" "${one[@]}" "$bench" --benchmark_format=json \
    --benchmark_out="$out/check_bench.json" >/dev/null
  # FCL's discrete check of the same motion (tools/peers/fcl_check.cc) when Debian's libfcl-dev is installed
  # (tools/peers.sh installs it).
  local fcl=""
  if [ -f /usr/include/fcl/fcl.h ]; then
    g++ -O2 -std=c++20 -isystem /usr/include/eigen3 tools/peers/fcl_check.cc -o "$out/fcl_check" -lfcl -lccd
    fcl=$("${one[@]}" "$out/fcl_check" "$out/check_fcl" 3)
  fi
  python3 - "$out/check_bench.json" "$fcl" <<'PY' | put check_bench
import json, sys
what = {"BM_CheckBuildHour": "every check (motion, limits, speeds, MuJoCo collisions, torch against the deposit)",
        "BM_MotionBuildHour": "the kinematics alone (positioner angles, closed-form IK, time stamps)",
        "BM_CheckBuildHourUrdfArm/0": "every check, on the URDF arm of scenarios/cell/robots/waam_kr16_support, "
                                      "discrete (MuJoCo at the samples)",
        "BM_CheckBuildHourUrdfArm/1": "the same, continuous (certified between the samples)"}
print("| benchmark | what | samples | distance queries | clearance (mm) | CPU time per run | samples/s |")
print("| --- | --- | --- | --- | --- | --- | --- |")
for r in json.load(open(sys.argv[1]))["benchmarks"]:
    parts = r["name"].split("/")
    name = "/".join(parts[:2]) if len(parts) > 1 and parts[1].isdigit() else parts[0]
    queries = format(r["queries"], ",.0f") if "queries" in r else ""
    clearance = "%.1f" % r["clearance_mm"] if "clearance_mm" in r else ""
    print("| `%s` | %s | %s | %s | %s | %.0f %s | %s |" % (name, what.get(name, ""), format(r["samples"], ",.0f"),
                                                        queries, clearance, r["cpu_time"], r["time_unit"],
                                                        format(r["samples_per_s"], ",.0f")))
if sys.argv[2]:
    f = dict(kv.split("=") for kv in sys.argv[2].split()[1:])
    n, s = int(f["samples"]), float(f["cpu_s"])
    print("| `fcl_check` | FCL 0.7's discrete check of the same motion (tools/peers/fcl_check.cc: broadphase, boolean "
          "narrow phase on the same pairs; poses given, no IK or kinematics) | %s | %s | | %.0f ms | %s |"
          % (format(n, ",.0f"), format(int(f["narrow_phase"]), ",.0f"), 1000 * s, format(n / s, ",.0f")))
PY
}

cup_support() {
  local d="$out/cup_support" s=scenarios/multiaxis/cup_two_handles.yaml
  ./build/waam plan "$s" -o "$d/one_piece" -q --set slicing.overhang_deg=80 >/dev/null
  ./build/waam plan "$s" -o "$d/split" -q >/dev/null
  python3 - "$d" <<'PY' | put cup_support
import json, sys
d = sys.argv[1]
rows = [("built along +z in one piece (`--set slicing.overhang_deg=80`: no split)", "one_piece"),
        ("centroid-shift decomposition (body +z, handles along the split-plane normals)", "split")]
print("| cup_two_handles.yaml (1.1 mm layers) | sub-volumes | support added (Lim & Soh Table 1) |")
print("| --- | --- | --- |")
for label, name in rows:
    subs = json.load(open(f"{d}/{name}/plan.json"))["sub_volumes"]
    total = sum(s["support_mm3"] for s in subs)
    parts = ", ".join("%s %s" % (s["name"], format(s["support_mm3"], ",.0f")) for s in subs)
    print("| %s | %d | %s mm^3%s |" % (label, len(subs), format(total, ",.0f"), " (%s)" % parts if len(subs) > 1 else ""))
PY
}

readme_figures() {
  local d="$out/readme_figures"
  ./build/waam simulate scenarios/planar_demo.yaml -o "$d/planar_demo" -q >/dev/null
  ./build/waam simulate scenarios/multiaxis/thruster_cone.yaml -o "$d/thruster_cone" -q >/dev/null
  python3 - "$d" <<'PY' | put readme_figures
import json, sys
d = sys.argv[1]
print("| `waam simulate` | layers | deviation from the target: min / max (+ = metal outside it) | voids, valleys |")
print("| --- | --- | --- | --- |")
for name, path in (("planar_demo", "scenarios/planar_demo.yaml"), ("thruster_cone", "scenarios/multiaxis/thruster_cone.yaml")):
    s = json.load(open(f"{d}/{name}/simulate.json"))
    dev = s["deviation"]
    print("| `%s` | %d | %.1f / %.1f mm | %.0f mm^3, %.0f mm^3 |" % (
        path, s["layers"], dev["min_mm"], dev["max_mm"], s["voids"]["volume_mm3"], s["valleys"]["volume_mm3"]))
PY
}

thermal_wall() {
  local d="$out/thermal_wall"
  ./build/waam thermal scenarios/thermal/wall_interpass.yaml -o "$d" -q >/dev/null
  cp "$d/interpass.png" docs/images/thermal_wall_interpass.png
  cp "$d/probes.png" docs/images/thermal_wall_probes.png
  cp "$(ls "$d"/maps/layer_*.png | tail -1)" docs/images/thermal_wall_map.png
  python3 - "$d/thermal.json" <<'PY' | put thermal_wall
import json, sys
j = json.load(open(sys.argv[1]))
t, e = j["timeline"], j["energy_balance"]
print("| layer | start [s] | interpass wait before [s] | interpass temperature [degC] | peak [degC] |")
print("| --- | --- | --- | --- | --- |")
for l in j["layers"]:
    ip = "-" if l["interpass_c"] is None else "%.0f" % l["interpass_c"]
    print("| %d | %.1f | %.0f | %s | %.0f |" % (l["layer"], l["start_s"], l["wait_s"], ip, l["peak_c"]))
print()
print("Build %.0f s: arc on %.0f s, travel %.0f s, waits %.0f s. Arc energy %.0f kJ, heat in %.0f kJ = stored %.0f kJ "
      "+ lost %.0f kJ (relative error %.1e). Probes: %s. Solver: %d cells, %d steps, %.1f s wall." % (
          t["total_s"], t["arc_on_s"], t["travel_s"], t["wait_s"], e["arc_energy_j"] / 1e3, e["heat_input_j"] / 1e3,
          e["stored_j"] / 1e3, e["lost_j"] / 1e3, e["relative_error"],
          ", ".join("%s max %.0f degC at %.0f s" % (n, p["max_c"], p["time_of_max_s"]) for n, p in j["probes"].items()),
          j["solver"]["cells"], j["solver"]["steps"], j["solver"]["wall_s"]))
PY
}

notebooks() {
  local d="$out/notebooks"
  mkdir -p "$d"
  PYTHONPATH="$PWD/build/python${PYTHONPATH:+:$PYTHONPATH}" PYDEVD_DISABLE_FILE_VALIDATION=1 /usr/bin/python3 - "$d" <<'PY'
import pathlib, sys
import nbclient, nbformat
out = pathlib.Path(sys.argv[1]).resolve()
for path in sorted(pathlib.Path("python/examples/notebooks").glob("*.ipynb")):
    work = out / path.stem
    work.mkdir(parents=True, exist_ok=True)
    notebook = nbformat.read(path, as_version=4)
    nbclient.NotebookClient(notebook, timeout=300, kernel_name="python3",
                            resources={"metadata": {"path": str(work)}}).execute()
PY
  cp "$d/pattern_sweep/sweep_deviation.png" docs/images/notebook_sweep_deviation.png
  cp "$d/csw_fit/csw_fit.png" docs/images/notebook_csw_fit.png
  cp "$d/replay_fit/replay_fit.png" docs/images/notebook_replay_fit.png
  cat <<'MD' | put notebooks
![python/examples/notebooks/pattern_sweep.ipynb: a sweep of the path pattern and bead width, plotted with matplotlib](docs/images/notebook_sweep_deviation.png)
![python/examples/notebooks/csw_fit.ipynb: the CSW model fitted from a DataFrame](docs/images/notebook_csw_fit.png)
![python/examples/notebooks/replay_fit.ipynb: a thermocouple log replayed, fitted on its first minute and predicted after it](docs/images/notebook_replay_fit.png)
MD
}

peers() {
  { echo '```'; bash tools/peers.sh "$out/peers"; echo '```'; } | put peers
}

threads() {
  local d="$out/threads" w="$PWD/build/waam"
  mkdir -p "$d"
  "$w" generate torus --param major_radius_mm=120 --param minor_radius_mm=40 --param major_segments=1224 \
    --param minor_segments=408 -o "$d/torus_1m.stl" > /dev/null
  printf 'name: torus_1m\npart:\n  mesh: %s\nslicing:\n  type: planar\n  layer_height_mm: 1.5\npath:\n  bead_width_mm: 2\n%s\n' \
    "$d/torus_1m.stl" 'process: {travel_speed_mm_min: 400, wire_feed_mm_min: 3200}' > "$d/torus_1m.yaml"
  "$w" compensate scenarios/distortion/small_bent_tube.yaml -o "$d/tube_scan" --max-iter 0 --no-program --no-images \
    -q > /dev/null
  python3 - "$d" "$w" <<'PY' | put threads
import os, resource, subprocess, sys, time
d, w = sys.argv[1], sys.argv[2]
tube = "scenarios/distortion/small_bent_tube.yaml"
runs = [
    ("`waam plan` the 1 M-facet torus, contour pattern", ["plan", f"{d}/torus_1m.yaml", "--set", "path.pattern=contour", "--no-images"]),
    ("`waam plan` the 1 M-facet torus, hybrid pattern", ["plan", f"{d}/torus_1m.yaml", "--set", "path.pattern=hybrid", "--no-images"]),
    ("`waam check scenarios/multiaxis/thruster_cone.yaml`", ["check", "scenarios/multiaxis/thruster_cone.yaml", "--no-images"]),
    ("`waam deviation`: the torus's 499,392 vertices against its 998,784 facets", ["deviation", f"{d}/torus_1m.stl", f"{d}/torus_1m.stl", "--no-images"]),
    ("`waam compensate` small_bent_tube, FE, two corrected builds", ["compensate", tube, "--max-iter", "2", "--tol-mm", "0.01", "--no-program", "--no-images"]),
    ("`waam tune-voids scenarios/ribweb/rib_web_eulerian.yaml` (two junction classes)", ["tune-voids", "scenarios/ribweb/rib_web_eulerian.yaml", "--no-images"]),
    ("`waam fit distortion` small_bent_tube's twin scan, reduced model", ["fit", "distortion", f"{d}/tube_scan/scan_before.ply", "--scenario", tube, "--mode", "reduced"]),
]
load = open("/proc/loadavg").read().split()[:3]
rows = []
for i, (label, args) in enumerate(runs):
    wall, cpu = [], []
    for threads in (1, 2):
        out = f"{d}/run{i}_t{threads}"
        extra = ["-o", out + ("/distortion.json" if args[:2] == ["fit", "distortion"] else "")]
        quiet = [] if args[0] == "deviation" else ["-q"]
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        t0 = time.perf_counter()
        subprocess.run([w] + args + extra + quiet + ["--threads", str(threads)], check=True, stdout=subprocess.DEVNULL)
        wall.append(time.perf_counter() - t0)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu.append(after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime)
    rows.append("| %s | %.2f s (%.2f s) | %.2f s (%.2f s) | %.2f |" % (label, wall[0], cpu[0], wall[1], cpu[1],
                                                                      wall[1] / wall[0]))
print("Load average %s before the runs (%d hardware threads)." % (" ".join(load), os.cpu_count()))
print()
print("| run | 1 thread: wall (CPU) | 2 threads: wall (CPU) | wall 2 / 1 |")
print("| --- | --- | --- | --- |")
print("\n".join(rows))
PY
}

resolve() {
  local d="$out/resolve"
  mkdir -p "$d"
  : > "$d/runs.txt"
  for s in $(find scenarios -name '*.yaml' ! -path '*/robots/*' ! -name '*sweep*' | sort); do
    grep -q '^program:' "$s" && continue
    local id=${s#scenarios/}
    id=${id%.yaml}
    id=${id//\//-}
    for mode in fixed optimise; do
      local start end
      start=$(date +%s.%N)
      ./build/waam check "$s" -o "$d/$id/$mode" -q --no-images --no-program --set cell.resolve=$mode >/dev/null 2>&1 || true
      end=$(date +%s.%N)
      echo "$id $mode $(echo "$end - $start" | bc)" >> "$d/runs.txt"
    done
  done
  python3 - "$d" <<'PY' | put resolve
import json, os, sys
d = sys.argv[1]
times = {}
for line in open(os.path.join(d, "runs.txt")):
    i, mode, t = line.split()
    times[(i, mode)] = float(t)
print("| scenario | violations fixed / optimise | arm joint margin deg | J5 deg | clearance mm | spin deg (layers turned) | kept | wall s fixed / optimise |")
print("| --- | --- | --- | --- | --- | --- | --- | --- |")
for i in sorted({k[0] for k in times}):
    f = os.path.join(d, i, "optimise", "check.json")
    if not os.path.exists(f):
        continue
    r = json.load(open(f))["resolve"]
    b, a, sp = r["before"], r["after"], r["spin_deg"]
    print("| `%s` | %d / %d | %.1f / %.1f | %.1f / %.1f | %.1f / %.1f | %+.0f..%+.0f (%d) | %s | %.1f / %.1f |" % (
        i, b["violation_count"], a["violation_count"], b["min_arm_margin_deg"], a["min_arm_margin_deg"],
        b["min_j5_deg"], a["min_j5_deg"], b["min_clearance_mm"], a["min_clearance_mm"], sp["min"], sp["max"],
        sp["layers_turned"], r["kept"], times[(i, "fixed")], times[(i, "optimise")]))
PY
}

place() {
  local d="$out/place"
  mkdir -p "$d"
  ./build/waam place scenarios/tubes/part_2.yaml -o "$d/part_2" -q --no-images \
    --set cell.part.offset_mm=[0,0,0] --set cell.part.yaw_deg=0 >/dev/null || true
  ./build/waam place scenarios/cell/cell_torch_meets_clamp.yaml -o "$d/clamp" -q --no-images >/dev/null || true
  ./build/waam place scenarios/cell/cell_out_of_reach.yaml -o "$d/out_of_reach" -q --no-images \
    --set 'place.part_x_mm=[-100,100,100]' --set place.part_y_mm=0 --set place.part_yaw_deg=0 >/dev/null || true
  python3 - "$d" <<'PY' | put place
import json, sys
d = sys.argv[1]
print("| `waam place` | layouts | coarse pass: wall s (layouts/s) | whole path: layouts, wall s | answer |")
print("| --- | --- | --- | --- | --- |")
for name, label in (("part_2", "`tubes/part_2.yaml` from the centred, unturned layout"),
                    ("clamp", "`cell/cell_torch_meets_clamp.yaml`"),
                    ("out_of_reach", "`cell/cell_out_of_reach.yaml` (part x -100..100)")):
    p = json.load(open(f"{d}/{name}/place.json"))
    t, b = p["timing"], p["best"]
    ans = ("passes: " + ", ".join(b["overrides"]) + ", margin %.2f" % b["margin"]) if p["feasible"] else \
          "none passes; nearest miss: %d violating samples, worst %s" % (b["violating_samples"], b["worst_violation"]["what"])
    print("| %s | %d | %.1f (%.0f) | %d, %.1f | %s |" % (label, p["layouts"], t["coarse_s"], t["coarse_layouts_per_s"],
                                                     p["full_checks"], t["full_s"], ans))
PY
}

for table in "${tables[@]}"; do
  if [ -z "$only" ] || [ "$only" = "$table" ]; then "$table"; fi
done
