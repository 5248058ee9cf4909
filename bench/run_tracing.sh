#!/usr/bin/env bash
# Runs bench_tracing (manifold tracing and cell complex, coxmesh vs GUDHI, same triangulation,
# manifold and seed, single thread) and prints its Markdown tables. Builds nothing.
#
#   bench/run_tracing.sh [path/to/bench_tracing] [runs=3] [case-name-substring]
#
# Default binary: $BUILD_DIR/bench/bench_tracing, BUILD_DIR defaulting to build/ in the repository.
# Times are thread CPU time (less sensitive than wall time to other processes on a shared machine);
# the wall-time medians go to stderr with the progress lines. Several minutes for the whole suite.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
bin="${1:-${BUILD_DIR:-$here/../build}/bench/bench_tracing}"
shift || true
if [[ ! -x "$bin" ]]; then
  echo "error: benchmark binary not found: $bin (build the target bench_tracing first)" >&2
  exit 1
fi

echo "date $(date -u +%Y-%m-%dT%H:%MZ), $(nproc) CPUs, load average $(cut -d' ' -f1-3 /proc/loadavg)"
echo
"$bin" "$@"
