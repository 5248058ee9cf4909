#!/usr/bin/env bash
# What a user of `coxmesh trace` waits for: each case in a fresh process, one thread by default,
# with its phases (trace, cell complex, topology, writing the file; "rest" is the whole command
# minus those: start-up, seeds, reporting) and its peak memory; then reading a result back with
# `coxmesh convert` (last table). Fastest of R runs. Builds nothing.
#
#   bench/run_end_to_end.sh [path/to/coxmesh] [runs=3] [threads=1]
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
bin="${1:-${BUILD_DIR:-$here/../build}/src/coxmesh}"
runs="${2:-3}" threads="${3:-1}"
[[ -x "$bin" ]] || { echo "error: coxmesh not found: $bin" >&2; exit 1; }
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

cases=(
  "S2 in R3, 101k simplices|--preset sphere --edge-length 0.0285 -o $work/out.vtu"
  "S2 in R3, 0.56M simplices|--preset sphere --edge-length 0.012 -o $work/out.ply"
  "torus in R3|--preset torus --edge-length 0.02 -o $work/out.vtu"
  "S3 in R4|--preset sphere --m 3 --dim 4 --edge-length 0.12 -o $work/out.vtu"
  "T3 in R6|--function x1^2+x2^2-1;x3^2+x4^2-1;x5^2+x6^2-1 --dim 6 --box -2,-2,-2,-2,-2,-2,2,2,2,2,2,2 --edge-length 0.55 -o $work/out.vtu"
  "SO(3) in R9|--preset so3 --edge-length 1.1 --no-output"
)
echo "date $(date -u +%Y-%m-%dT%H:%MZ), $(nproc) CPUs, load average $(cut -d' ' -f1-3 /proc/loadavg), threads $threads, best of $runs"
echo
echo "| case | simplices | cells | trace s | complex s | topology s | write s | rest s | whole s | topology / (trace + complex) | write / (trace + complex) | peak MiB |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
for c in "${cases[@]}"; do
  name="${c%%|*}" args="${c#*|}"
  best=""
  for ((r = 0; r < runs; r++)); do
    IFS=' ' read -r -a argv <<<"$args"
    start=$(date +%s.%N)
    "$bin" trace "${argv[@]}" --threads "$threads" --json >"$work/summary.json"
    end=$(date +%s.%N)
    line=$(/usr/bin/python3 - "$work/summary.json" "$start" "$end" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
t = s["timings"]
whole = float(sys.argv[3]) - float(sys.argv[2])
tr, cx, tp, wr = t["trace_seconds"], t["cell_complex_seconds"], t["topology_seconds"], t.get("write_seconds", 0.0)
print(f"{whole:.3f}|{s['traced_simplices']}|{sum(s['cells']) + sum(s['boundary_cells'])}|{tr:.3f}|{cx:.3f}|{tp:.3f}|"
      f"{wr:.3f}|{whole - tr - cx - tp - wr:.3f}|{whole:.3f}|{tp / (tr + cx):.2f}|{wr / (tr + cx):.2f}|"
      f"{s['peak_memory_bytes'] / 2**20:.0f}")
PY
)
    if [[ -z "$best" ]] || awk "BEGIN { exit !(${line%%|*} < ${best%%|*}) }"; then best="$line"; fi
  done
  echo "| $name | $(cut -d'|' -f2- <<<"$best" | sed 's/|/ | /g') |"
done

# Reading a traced result back: `convert` of the T³ file above saved as .cxm (305 MB) to .vtu, and
# the reading alone as `check --json` times it. Fastest of R runs.
IFS=' ' read -r -a argv <<<"--function x1^2+x2^2-1;x3^2+x4^2-1;x5^2+x6^2-1 --dim 6 --box -2,-2,-2,-2,-2,-2,2,2,2,2,2,2 --edge-length 0.55"
"$bin" trace "${argv[@]}" --threads 1 -q -o "$work/t3.cxm"
echo
echo "| case | file MB | convert to .vtu s | read s (check) | read MB/s |"
echo "|---|---|---|---|---|"
best_convert="" best_read=""
for ((r = 0; r < runs; r++)); do
  start=$(date +%s.%N)
  "$bin" convert -q "$work/t3.cxm" "$work/t3.vtu"
  end=$(date +%s.%N)
  convert=$(awk "BEGIN { print $end - $start }")
  read=$("$bin" check --json "$work/t3.cxm" | /usr/bin/python3 -c 'import json, sys; print(json.load(sys.stdin)["timings"]["read_seconds"])')
  if [[ -z "$best_convert" ]] || awk "BEGIN { exit !($convert < $best_convert) }"; then best_convert=$convert; fi
  if [[ -z "$best_read" ]] || awk "BEGIN { exit !($read < $best_read) }"; then best_read=$read; fi
done
mb=$(awk "BEGIN { print $(stat -c %s "$work/t3.cxm") / 1e6 }")
awk -v mb="$mb" -v c="$best_convert" -v r="$best_read" \
  'BEGIN { printf "| T3 in R6, .cxm | %.0f | %.3f | %.3f | %.0f |\n", mb, c, r, mb / r }'
