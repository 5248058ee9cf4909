#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, ASan + UBSan, in build-fuzz/) if needed and runs each for
# SECONDS (default 20) on a copy of its seed corpus in a temporary directory, one target a core at a
# time. Fails if any target finds a crash, a sanitizer report, a leak, a hang (> 5 s on one input,
# 30 s for the CLI) or runs out of memory; the input that did it is kept in build-fuzz/fuzz-artifacts/.
#   fuzz/run.sh [SECONDS] [TARGET...]      e.g. fuzz/run.sh 60 cxm cli
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-20}
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(cxm expression simplex number_rows cli)
build=${COXMESH_FUZZ_BUILD_DIR:-build-fuzz}
if [ ! -f "$build/CMakeCache.txt" ]; then
  CC=clang CXX=clang++ cmake -S . -B "$build" -DCOXMESH_FUZZ=ON -DCOXMESH_TESTS=OFF -DCOXMESH_BENCHMARKS=OFF \
    -DCOXMESH_GUDHI=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo
fi
cmake --build "$build" -j "$(nproc)" --target "${targets[@]/#/fuzz_}"

root=$(pwd)
artifacts="$root/$build/fuzz-artifacts"
mkdir -p "$artifacts"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fuzz() {  # fuzz TARGET: its log in $work/TARGET.log, its exit status in $work/TARGET.status
  local t=$1 timeout=5
  cp -r "fuzz/corpus/$t" "$work/$t"
  # 5 s an input; the CLI 30 s: its automatic seed search (2000 Newton projections) takes 0.1 s in
  # Release and up to 50 times that instrumented, on a busy machine.
  [ "$t" = cli ] && timeout=30
  # Run inside the temporary directory (with TMPDIR there too): nothing lands elsewhere.
  local status=0
  (cd "$work" && TMPDIR="$work" "$root/$build/fuzz/fuzz_$t" "$work/$t" -max_total_time="$seconds" -timeout="$timeout" \
      -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$artifacts/$t-" >"$work/$t.log" 2>&1) || status=$?
  echo "$status" >"$work/$t.status"
}
# One target a core (each libFuzzer process is single-threaded); the logs are printed in order.
for t in "${targets[@]}"; do
  while [ "$(jobs -rp | wc -l)" -ge "$(nproc)" ]; do wait -n || true; done
  fuzz "$t" &
done
wait
failed=()
for t in "${targets[@]}"; do
  echo "== fuzz_$t: ${seconds} s"
  if [ "$(cat "$work/$t.status")" = 0 ]; then
    grep -E '^#[0-9]+.*DONE|stat::number_of_executed_units|stat::average_exec_per_sec' "$work/$t.log" || true
  else
    failed+=("$t")
    tail -n 60 "$work/$t.log"
  fi
done
if [ ${#failed[@]} -gt 0 ]; then
  echo "fuzzing failed: ${failed[*]} (inputs in $build/fuzz-artifacts/)" >&2
  exit 1
fi
echo "fuzzing: no failures"
