#!/usr/bin/env bash
# Degenerate input against generic input: manifolds through lattice vertices (the moment curve
# through the origin, a plane through it) traced with and without a small generic offset of the
# triangulation; the exact rule must keep the degenerate runs close to the generic ones.
#   bench/run_degenerate.sh [path/to/coxmesh]   (default: build/src/coxmesh)
set -euo pipefail
bin=${1:-build/src/coxmesh}
run() {  # seconds of the fastest of 3 runs
  local best=
  for _ in 1 2 3; do
    local t0 t1
    t0=$(date +%s.%N); "$bin" trace "$@" --threads 1 --no-output -q; t1=$(date +%s.%N)
    best=$(python3 -c "print(min(float('${best:-1e9}'), $t1 - $t0))")
  done
  echo "$best"
}
offset() { python3 -c "print(','.join(['0.0123'] * $1))"; }
printf "%-22s %10s %10s %7s\n" case "vertex(s)" "generic(s)" ratio
for d in 3 4 6 8 10 12 14 16 18 20; do
  a=$(run --preset moment-curve --dim "$d"); b=$(run --preset moment-curve --dim "$d" --offset "$(offset "$d")")
  printf "%-22s %10.3f %10.3f %7.1f\n" "moment curve, d=$d" "$a" "$b" "$(python3 -c "print($a / $b)")"
done
for d in 3 4 6 8 10; do
  a=$(run --preset plane --dim "$d"); b=$(run --preset plane --dim "$d" --offset "$(offset "$d")")
  printf "%-22s %10.3f %10.3f %7.1f\n" "plane m=2, d=$d" "$a" "$b" "$(python3 -c "print($a / $b)")"
done
