#!/usr/bin/env bash
# Runs bench_triangulation (coxmesh vs GUDHI, same inputs) and prints a Markdown table of the
# medians over 5 repetitions and the GUDHI/coxmesh ratio per case.
#
#   bench/run_triangulation.sh [path/to/bench_triangulation] [extra benchmark flags...]
#
# Default binary: $BUILD_DIR/bench/bench_triangulation, BUILD_DIR defaulting to build/ in the
# repository. Times are CPU time per iteration (less sensitive than wall time to other processes on
# a shared machine); repetitions are randomly interleaved for the same reason.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
bin="${1:-${BUILD_DIR:-$here/../build}/bench/bench_triangulation}"
shift || true
if [[ ! -x "$bin" ]]; then
  echo "error: benchmark binary not found: $bin (build the target bench_triangulation first)" >&2
  exit 1
fi

json="$(mktemp)"
trap 'rm -f "$json"' EXIT
"$bin" --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
  --benchmark_enable_random_interleaving=true \
  --benchmark_out="$json" --benchmark_out_format=json "$@" >&2

/usr/bin/python3 - "$json" <<'EOF'
import json
import sys

data = json.load(open(sys.argv[1]))
ctx = data["context"]
med = {}
order = []
for b in data["benchmarks"]:
    if b.get("aggregate_name") != "median":
        continue
    case, _, impl = b["run_name"].rpartition("/")
    if case not in order:
        order.append(case)
    scale = {"ns": 1.0, "us": 1e3, "ms": 1e6, "s": 1e9}[b["time_unit"]]
    med[(case, impl)] = (b["cpu_time"] * scale, b)

def case_key(case):
    # locate first, then cofacets; numerically by d and k.
    parts = case.split("/")
    nums = [int(p.split("=")[1]) for p in parts if "=" in p]
    return (parts[0] != "locate", parts[0], nums)

order.sort(key=case_key)

def fmt(ns):
    if ns >= 1e6:
        return f"{ns / 1e6:.2f} ms"
    if ns >= 1e3:
        return f"{ns / 1e3:.2f} µs"
    return f"{ns:.1f} ns"

print(f"host: {ctx.get('host_name', '?')}, {ctx.get('num_cpus', '?')} CPUs @ {ctx.get('mhz_per_cpu', '?')} MHz, "
      f"load average {', '.join(f'{x:.2f}' for x in ctx.get('load_avg', []))}, date {ctx.get('date', '?')}")
print()
print("| case | coxmesh | GUDHI | GUDHI/coxmesh | per item (coxmesh / GUDHI) |")
print("|---|---:|---:|---:|---:|")
for case in order:
    if (case, "coxmesh") not in med or (case, "gudhi") not in med:
        continue
    c, cb = med[(case, "coxmesh")]
    g, _ = med[(case, "gudhi")]
    per = ""
    n = cb.get("cofacets_per_pass")
    if n:
        per = f"{c / n:.1f} ns / {g / n:.1f} ns per cofacet ({int(n)} per pass)"
    print(f"| {case} | {fmt(c)} | {fmt(g)} | {g / c:.1f}× | {per} |")
EOF
