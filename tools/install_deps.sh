#!/usr/bin/env bash
# Installs every Debian 12 package waam-twin needs to build, test and benchmark; idempotent.
# With --fuzz it also installs clang and libFuzzer (tools/fuzz.sh); the normal build does not need them.
set -euo pipefail

packages=(
  build-essential cmake ninja-build ccache pkg-config
  libeigen3-dev libceres-dev libtbb-dev
  libmujoco-dev libqhull-dev libtinyxml2-dev
  libopencv-dev libpng-dev
  libhdf5-dev
  libpolyclipping-dev
  libyaml-cpp-dev nlohmann-json3-dev libcli11-dev
  googletest libgtest-dev libgmock-dev libbenchmark-dev
  libjs-three chromium
  slurmctld slurmd slurm-client munge python3-distributed
  pybind11-dev python3-dev python3-numpy python3-pytest
  python3-pandas python3-matplotlib python3-h5py python3-nbclient python3-nbformat python3-ipykernel mypy
)
if [ "${1:-}" = "--fuzz" ]; then
  packages+=(clang-14 libclang-rt-14-dev)
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install_deps: all ${#packages[@]} packages already installed"
  exit 0
fi

echo "install_deps: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
