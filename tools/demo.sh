#!/usr/bin/env bash
# Installs the dependencies, builds waam-twin (Release) and runs the main job on the default scenario into out/:
# plan the weld path, check it on the robot cell, deposit it in the voxel twin.
set -euo pipefail
cd "$(dirname "$0")/.."
scenario="${1:-scenarios/planar_demo.yaml}"
./tools/install_deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)" --target waam
name="$(basename "${scenario%.*}")"
./build/waam plan "$scenario" -o "out/$name/plan"
./build/waam check "$scenario" -o "out/$name/check"
./build/waam simulate "$scenario" -o "out/$name/simulate"
echo "outputs in out/$name/: plan/ (plan.json, plan.h5, layers/), check/ (check.json, program.ls), simulate/ (simulate.json, part.stl, PNGs)"
