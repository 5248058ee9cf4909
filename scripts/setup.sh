#!/usr/bin/env bash
# Installs the Debian packages coxmesh needs, then configures and builds it (Release) in ./build.
# Extra arguments go to cmake's configure step, e.g. -DCOXMESH_SANITIZE=ON.
set -euo pipefail
cd "$(dirname "$0")/.."
packages=(g++ cmake make libeigen3-dev libcli11-dev nlohmann-json3-dev libmuparser-dev
          libgtest-dev libgmock-dev libbenchmark-dev libgudhi-dev libboost-dev libphat-dev
          python3-vtk9   # python3-vtk9: the VTU read-back test uses VTK's own reader
          clang libclang-rt-14-dev)  # the fuzz targets (fuzz/run.sh): clang's libFuzzer
missing=()
for p in "${packages[@]}"; do dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p"); done
if [ ${#missing[@]} -gt 0 ]; then
  sudo=""; [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}"
fi
build=${COXMESH_BUILD_DIR:-build}
# Arguments before an optional "--target NAME" go to the configure step.
configure=() target=()
while [ $# -gt 0 ]; do
  if [ "$1" = "--target" ]; then target=(--target "$2"); shift 2; else configure+=("$1"); shift; fi
done
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release "${configure[@]}"
cmake --build "$build" -j "$(nproc)" "${target[@]}"
