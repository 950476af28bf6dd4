#!/usr/bin/env bash
# Installs the dependencies, builds waam-twin (Release) and runs the main job on the default scenario into out/.
set -euo pipefail
cd "$(dirname "$0")/.."
scenario="${1:-scenarios/planar_demo.yaml}"
./tools/install_deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DWAAM_BUILD_TESTS=OFF -DWAAM_BUILD_BENCHMARKS=OFF
cmake --build build -j"$(nproc)" --target waam
name="$(basename "${scenario%.*}")"
./build/waam plan "$scenario" -o "out/$name"
echo "outputs in out/$name (plan.json, plan.h5, layers/*.png)"
