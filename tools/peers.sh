#!/usr/bin/env bash
# Runs waam's peers beside it on the same inputs in one run and prints the ratios (peer time / waam time):
#  - PrusaSlicer's CLI (Debian prusa-slicer) against `waam plan --no-images` with the four fill patterns
#    (continuous, hybrid, contour, zigzag) on the 1 M-facet torus at 1.5 mm layers and 2 mm beads, and on the bunny
#    and torus PrusaSlicer's package ships (/usr/share/PrusaSlicer/shapes);
#  - KDL's numerical IK (Debian liborocos-kdl-dev, tools/peers/kdl_vs_opw.cc compiled here, not in the project
#    build) against waam's closed-form IK on the same arm: the built-in FANUC, then the KR 16-2 class URDF arm;
#  - FCL 0.7 (Debian libfcl-dev, tools/peers/fcl_check.cc compiled here) against `waam check` on the build hour of
#    BM_CheckBuildHourUrdfArm (URDF mesh arm): the benchmark exports the cell's shapes and the motion's poses, FCL
#    checks every sample (broadphase + boolean narrow phase, poses given); CPU times of the same run;
#  - FEniCSx (Debian python3-dolfinx, tools/peers/thermal_fenicsx.py, one process) against waam's thermal model
#    (build/analysis/benchmarks/waam_thermal_peer) on the wall of tools/peers/thermal_wall.json: probe temperatures
#    (target: within 2 % of the peak rise) and the time ratios; with WAAM_PEERS_THERMAL_FINE=1 also both on the same
#    problem on cells refined twice (1 mm, the same source and 0.4 s steps; docs/THERMAL.md, "FEniCSx comparison"),
#    and the 2 mm runs measured against those finer ones (which side the 2 mm difference comes from); with
#    WAAM_PEERS_THERMAL_Q2=1 as well FEniCSx's Q2 elements on the 2 mm mesh as one more finer run (~80 s CPU).
#    waam runs single-rate there, then with its multirate steppings (WAAM_PEERS_THERMAL_MULTIRATE, a list of
#    waam_thermal_peer stepping arguments; default: the solver's default and two with 1.2 s and 1.6 s far steps).
# Installs the peers it needs (apt-get, as root or through sudo); not part of tools/install_deps.sh.
# Usage: tools/peers.sh [out_dir] (default out/peers; needs a built build/waam); WAAM_PEERS_ONLY=thermal runs the
# FEniCSx comparison alone. Times are wall clock (the thermal comparison also prints CPU time), one run each; a ratio
# above 1 means waam is faster. On a machine shared with other work, compare the ratios of one run.
set -euo pipefail
cd "$(dirname "$0")/.."
repo="$PWD"
out="${1:-out/peers}"
mkdir -p "$out"
out="$(cd "$out" && pwd)"
waam="$repo/build/waam"
only="${WAAM_PEERS_ONLY:-}"
[ -z "$only" ] || [ "$only" = thermal ] || { echo "peers: WAAM_PEERS_ONLY=$only: must be thermal or unset" >&2; exit 2; }
[ -n "$only" ] || [ -x "$waam" ] || { echo "peers: build waam first (build/waam)" >&2; exit 1; }

# The peers, installed once.
if { [ -z "$only" ] && { ! command -v prusa-slicer > /dev/null || [ ! -f /usr/include/kdl/chain.hpp ] ||
  [ ! -f /usr/include/fcl/fcl.h ]; }; } ||
  ! /usr/bin/python3 -c "import dolfinx" 2> /dev/null; then
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  peers=(python3-dolfinx)
  [ -n "$only" ] || peers+=(prusa-slicer liborocos-kdl-dev libfcl-dev)
  $sudo apt-get install -y "${peers[@]}" > "$out/apt.log" 2>&1 ||
    { $sudo apt-get update > /dev/null && $sudo apt-get install -y "${peers[@]}" > "$out/apt.log" 2>&1; }
fi

seconds() { date +%s.%N; }
# Wall seconds of a command; its output goes to "$out/<name>.log".
timed() {
  local name="$1"
  shift
  local t0 t1
  t0=$(seconds)
  "$@" > "$out/$name.log" 2>&1 || { echo "peers: $name failed (see $out/$name.log)" >&2; exit 1; }
  t1=$(seconds)
  awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.3f", b - a }' 
}

# PrusaSlicer wants a rectilinear fill for 100 % density, a bed the part fits on, and (to slice the same layers as
# waam) a first layer as high as the others.
prusa() {
  prusa-slicer --export-gcode --nozzle-diameter 2 --layer-height 1.5 --first-layer-height 1.5 --perimeters 2 \
    --fill-density 100% --fill-pattern rectilinear --bed-shape 0x0,400x0,400x400,0x400 --max-print-height 400 \
    --loglevel 1 -o "$2" "$1"
}

# The scenario of a mesh: 1.5 mm layers, 2 mm beads (the pattern is set per run).
scenario() {
  cat > "$2" << YAML
# tools/peers.sh: $(basename "$1") at 1.5 mm layers and 2 mm beads.
name: $(basename "${1%.stl}")
part:
  mesh: $1
slicing:
  type: planar
  layer_height_mm: 1.5
path:
  pattern: continuous
  bead_width_mm: 2
process:
  travel_speed_mm_min: 400
  wire_feed_mm_min: 3200
YAML
}

echo "peers: $(nproc) hardware threads, load average $(cut -d' ' -f1-3 /proc/loadavg); wall seconds, one run each"
# PrusaSlicer, KDL and FCL (not with WAAM_PEERS_ONLY=thermal).
if [ -z "$only" ]; then
"$waam" generate torus --param major_radius_mm=120 --param minor_radius_mm=40 --param major_segments=1224 \
  --param minor_segments=408 -o "$out/torus_1m.stl" > /dev/null
models=("$out/torus_1m.stl")
for shape in bunny torus; do
  f="/usr/share/PrusaSlicer/shapes/$shape.stl"
  [ -f "$f" ] && models+=("$f")
done

printf "%-16s %10s" model prusa_s
for p in continuous hybrid contour zigzag; do printf " %11s %7s" "${p:0:11}_s" ratio; done
echo
for model in "${models[@]}"; do
  name="$(basename "${model%.stl}")"
  [ "$model" = "$out/torus_1m.stl" ] || name="prusa_$name"
  scenario "$model" "$out/$name.yaml"
  t_prusa=$(timed "$name.prusa" prusa "$model" "$out/$name.gcode")
  printf "%-16s %10.2f" "$name" "$t_prusa"
  for p in continuous hybrid contour zigzag; do
    t=$(timed "$name.$p" "$waam" plan "$out/$name.yaml" -o "$out/$name.$p" --set path.pattern=$p --no-images -q)
    printf " %11.2f %7.2f" "$t" "$(awk -v a="$t_prusa" -v b="$t" 'BEGIN { print a / b }')"
  done
  echo
done

g++ -O2 -std=c++20 -I"$repo" -isystem /usr/include/eigen3 tools/peers/kdl_vs_opw.cc planner/kinematics/opw_arm.cc \
  planner/kinematics/opw_detect.cc planner/kinematics/angles.cc -o "$out/kdl_vs_opw" -lorocos-kdl -ltinyxml2
"$out/kdl_vs_opw" 20000
# The same on the KUKA KR 16-2 class URDF arm of BM_CheckBuildHourUrdfArm (KDL's chain from the URDF's joints).
"$out/kdl_vs_opw" 20000 scenarios/cell/robots/waam_kr16_support/urdf/kr16_2.urdf

# FCL's discrete check against waam's (discrete and continuous) on the same motion, CPU times on one core.
[ -x build/analysis/benchmarks/waam_check_bench ] || cmake --build build --target waam_check_bench > /dev/null
g++ -O2 -std=c++20 -isystem /usr/include/eigen3 tools/peers/fcl_check.cc -o "$out/fcl_check" -lfcl -lccd
WAAM_CHECK_EXPORT="$out/fcl" taskset -c 0 build/analysis/benchmarks/waam_check_bench \
  --benchmark_filter='BM_CheckBuildHourUrdfArm' --benchmark_format=json > "$out/check_bench.json" 2> /dev/null
fcl_line=$(taskset -c 0 "$out/fcl_check" "$out/fcl" 3)
/usr/bin/python3 - "$out/check_bench.json" "$fcl_line" << 'PY'
import json, sys
runs = {b["name"].split("/")[1]: b for b in json.load(open(sys.argv[1]))["benchmarks"]}
fcl = dict(kv.split("=") for kv in sys.argv[2].split()[1:])
fcl_ms, samples = 1000 * float(fcl["cpu_s"]), int(fcl["samples"])
print(f"check peer: FCL 0.7 discrete {fcl_ms:.0f} ms per build hour ({float(fcl['us_per_sample']):.2f} us/sample, "
      f"{samples} samples, {fcl['narrow_phase']} narrow-phase pairs, {fcl['contacts']} contacts; poses given)")
for arg, mode in (("0", "discrete"), ("1", "continuous")):
    b = runs[arg]
    ms = b["cpu_time"] if b["time_unit"] == "ms" else b["cpu_time"] / 1e6
    print(f"check peer: waam {mode:10s} {ms:.0f} ms per build hour ({1000 * ms / b['samples']:.2f} us/sample, "
          f"IK and every check included), FCL / waam = {fcl_ms / ms:.1f}")
PY
fi

# FEniCSx and waam's thermal model on the same wall (same cells, step, source, losses; constant properties). The
# FEniCSx setup includes its form compile on the first run (cached in ~/.cache/fenics afterwards; printed apart).
# waam steps single-rate (the whole model every 0.4 s step, as FEniCSx); then, against the same FEniCSx run, with
# each multirate stepping of WAAM_PEERS_THERMAL_MULTIRATE (waam_thermal_peer's stepping argument; "-" is the solver's
# default), the probes recorded inside the batches as `waam replay` records them. Both sides run on one thread
# (waam_thermal_peer's last argument; FEniCSx with OMP_NUM_THREADS=1), so their CPU times are one core's.
thermal="$repo/tools/peers/thermal_wall.json"
multirate=(${WAAM_PEERS_THERMAL_MULTIRATE:--
  whole_step_s=0,far_step_s=1.2,near_step_s=0.4,near_radius_mm=24 whole_step_s=0,far_step_s=1.6,near_step_s=0.4,near_radius_mm=24})
[ -x build/analysis/benchmarks/waam_thermal_peer ] || cmake --build build --target waam_thermal_peer > /dev/null
# thermal_pair <refine> <suffix>: waam single-rate, FEniCSx, the comparison, then waam's multirate steppings.
thermal_pair() {
  local refine="$1" suffix="$2" n=0
  build/analysis/benchmarks/waam_thermal_peer "$thermal" 0 "$refine" 1 > "$out/thermal_waam$suffix.json" ||
    { echo "peers: waam_thermal_peer failed (refine $refine)" >&2; exit 1; }
  OMP_NUM_THREADS=1 /usr/bin/python3 tools/peers/thermal_fenicsx.py "$thermal" --refine "$refine" \
    > "$out/thermal_fenicsx$suffix.json" 2> "$out/thermal_fenicsx$suffix.log" ||
    { echo "peers: thermal_fenicsx.py failed (see $out/thermal_fenicsx$suffix.log)" >&2; exit 1; }
  /usr/bin/python3 tools/peers/thermal_compare.py "$out/thermal_waam$suffix.json" "$out/thermal_fenicsx$suffix.json" \
    "$thermal"
  echo "waam's multirate stepping against the same FEniCSx run:"
  for stepping in "${multirate[@]}"; do
    n=$((n + 1))
    build/analysis/benchmarks/waam_thermal_peer "$thermal" "$stepping" "$refine" 1 \
      > "$out/thermal_waam${suffix}_multirate$n.json" ||
      { echo "peers: waam_thermal_peer $stepping failed (refine $refine)" >&2; exit 1; }
    /usr/bin/python3 tools/peers/thermal_compare.py "$out/thermal_waam${suffix}_multirate$n.json" \
      "$out/thermal_fenicsx$suffix.json" "$thermal" --brief
  done
}
thermal_pair 1 ""
if [ "${WAAM_PEERS_THERMAL_FINE:-0}" = 1 ]; then
  echo "the same problem on 1 mm cells (refine 2):"
  thermal_pair 2 _1mm
  finer=("$out/thermal_waam_1mm.json" "$out/thermal_fenicsx_1mm.json")
  if [ "${WAAM_PEERS_THERMAL_Q2:-0}" = 1 ]; then
    OMP_NUM_THREADS=1 /usr/bin/python3 tools/peers/thermal_fenicsx.py "$thermal" --degree 2 \
      > "$out/thermal_fenicsx_q2.json" 2> "$out/thermal_fenicsx_q2.log" ||
      { echo "peers: thermal_fenicsx.py --degree 2 failed (see $out/thermal_fenicsx_q2.log)" >&2; exit 1; }
    finer+=("$out/thermal_fenicsx_q2.json")
  fi
  echo "the 2 mm runs against the finer ones:"
  /usr/bin/python3 tools/peers/thermal_compare.py "$out/thermal_waam.json" "$out/thermal_fenicsx.json" "$thermal" \
    --against "${finer[@]}" | sed -n '/^against finer/,$p'
fi
