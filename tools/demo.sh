#!/usr/bin/env bash
# Installs the dependencies, builds waam-twin (Release) and runs the main job on the default scenario into out/:
# `waam run` plans the weld path, checks it on the robot cell and deposits it in the voxel twin.
set -euo pipefail
cd "$(dirname "$0")/.."
scenario="${1:-scenarios/planar_demo.yaml}"
./tools/install_deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)" --target waam
name="$(basename "${scenario%.*}")"
./build/waam run "$scenario" -o "out/$name"
echo "outputs in out/$name/: summary.json, plan/ (plan.json, plan.h5, layers/), check/ (check.json, program.ls), simulate/ (simulate.json, part.stl, PNGs)"
