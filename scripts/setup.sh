#!/usr/bin/env bash
# Installs the Debian packages coxmesh needs, then configures and builds it (Release) in ./build.
#   ./scripts/setup.sh           the library and the command-line tool only (what the first
#                                command of the README runs)
#   ./scripts/setup.sh --python  the same and the Python package (build/python)
#   ./scripts/setup.sh --all     everything: also the tests, benchmarks and the Python package
# Further arguments go to cmake's configure step (e.g. -DCOXMESH_SANITIZE=ON), except
# "--target NAME" (once or more), which builds those targets only.
set -euo pipefail
cd "$(dirname "$0")/.."
mode=cli
case "${1:-}" in --all) mode=all; shift ;; --python) mode=python; shift ;; esac

packages=(g++ cmake make libeigen3-dev libcli11-dev nlohmann-json3-dev libmuparser-dev libboost-dev libphat-dev
          libnanoflann-dev libopenmpi-dev)  # (MPI: `mpirun coxmesh trace`; -DCOXMESH_MPI=OFF builds without it)
python_packages=(pybind11-dev python3-dev python3-numpy python3-pytest)  # the Python package and its tests
# python3-vtk9: the VTU read-back test uses VTK's own reader; libcgal-demo: real point clouds
test_packages=(libgtest-dev libgmock-dev libbenchmark-dev libgudhi-dev python3-vtk9 libcgal-demo
               clang libclang-rt-14-dev  # clang's libFuzzer: the fuzz targets (fuzz/run.sh)
               clang-format  # the format test
               openmpi-bin)  # mpirun: the test of several processes
configure=(-DCMAKE_BUILD_TYPE=Release) target=()
case $mode in
  cli) configure+=(-DCOXMESH_TESTS=OFF -DCOXMESH_BENCHMARKS=OFF -DCOXMESH_PYTHON=OFF); target=(--target coxmesh) ;;
  python) packages+=("${python_packages[@]}")
          configure+=(-DCOXMESH_TESTS=OFF -DCOXMESH_BENCHMARKS=OFF -DCOXMESH_PYTHON=ON); target=(--target coxmesh_python) ;;
  all) packages+=("${python_packages[@]}" "${test_packages[@]}")
       configure+=(-DCOXMESH_TESTS=ON -DCOXMESH_BENCHMARKS=ON -DCOXMESH_PYTHON=ON) ;;
esac

missing=()
for p in "${packages[@]}"; do dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p"); done
if [ ${#missing[@]} -gt 0 ]; then
  sudo=""; [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}"
fi
build=${COXMESH_BUILD_DIR:-build}
targets=()
while [ $# -gt 0 ]; do
  if [ "$1" = "--target" ]; then targets+=("$2"); shift 2; else configure+=("$1"); shift; fi
done
[ ${#targets[@]} -eq 0 ] || target=(--target "${targets[@]}")
cmake -S . -B "$build" "${configure[@]}"
cmake --build "$build" -j "$(nproc)" "${target[@]}"
