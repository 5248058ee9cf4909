#!/usr/bin/env bash
# Degenerate input against generic input: manifolds through lattice vertices (the moment curve
# through the origin, a plane through it) traced with and without a small generic offset of the
# triangulation; the exact rule must keep the degenerate runs within 2× of the generic ones.
#   bench/run_degenerate.sh [path/to/coxmesh]   (default: build/src/coxmesh)
# Each case: the least CPU time (user + system) of the whole command over RUNS runs (default 5);
# CPU time rather than wall time, which swings with the load of a shared machine.
set -euo pipefail
bin=${1:-build/src/coxmesh}
runs=${RUNS:-5}
run() {
  /usr/bin/python3 - "$bin" "$runs" "$@" <<'PY'
import resource, subprocess, sys
cmd = [sys.argv[1], "trace", *sys.argv[3:], "--threads", "1", "--no-output", "-q"]
best = float("inf")
for _ in range(int(sys.argv[2])):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(cmd, check=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    best = min(best, after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime)
print(f"{best:.4f}")
PY
}
offset() { /usr/bin/python3 -c "print(','.join(['0.0123'] * $1))"; }
row() {  # name, degenerate seconds, generic seconds
  printf "%-22s %10.3f %10.3f %7.2f\n" "$1" "$2" "$3" "$(/usr/bin/python3 -c "print($2 / $3)")"
}
printf "%-22s %10s %10s %7s\n" case "vertex(s)" "generic(s)" ratio
for d in $(seq 3 20); do
  row "moment curve, d=$d" "$(run --preset moment-curve --dim "$d")" \
    "$(run --preset moment-curve --dim "$d" --offset "$(offset "$d")")"
done
for d in $(seq 3 10) 12 14; do
  row "plane m=2, d=$d" "$(run --preset plane --dim "$d")" "$(run --preset plane --dim "$d" --offset "$(offset "$d")")"
done
