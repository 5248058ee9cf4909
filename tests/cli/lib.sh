# Shared by the CLI test scripts, sourced after `set -euo pipefail`: $bin (the absolute path of
# $COXMESH), $tmp (a directory removed on exit), the checks, and `finish` (the closing count line).
bin=${COXMESH:?set COXMESH to the coxmesh binary}
bin=$(cd "$(dirname "$bin")" && pwd)/$(basename "$bin")
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fails=0 passes=0
check() {  # check NAME EXPECTED ACTUAL
  if [[ "$2" == "$3" ]]; then echo "ok   $1"; passes=$((passes + 1)); else echo "FAIL $1: expected [$2] got [$3]"; fails=$((fails + 1)); fi
}
fails_with() {  # fails_with NAME PATTERN CMD...: non-zero exit and one error line matching PATTERN
  local name=$1 pattern=$2; shift 2
  local err status=0
  err=$("$@" 2>&1 >/dev/null) || status=$?
  if [[ $status -ne 0 && "$err" == *"$pattern"* && $(printf '%s\n' "$err" | wc -l) -eq 1 ]]; then echo "ok   $name"; passes=$((passes + 1))
  else echo "FAIL $name: status $status, stderr [$err]"; fails=$((fails + 1)); fi
}
finish() {
  echo "$passes passed, $fails failed"
  [[ $fails -eq 0 ]]
}
exits_with() {  # exits_with NAME STATUS PATTERN CMD...: exit status STATUS and one error line matching PATTERN
  local name=$1 want=$2 pattern=$3; shift 3
  local err status=0
  err=$("$@" 2>&1 >/dev/null) || status=$?
  if [[ $status -eq $want && "$err" == "coxmesh: error: "*"$pattern"* && $(printf '%s\n' "$err" | wc -l) -eq 1 ]]; then
    echo "ok   $name"; passes=$((passes + 1))
  else echo "FAIL $name: status $status (expected $want), stderr [$err]"; fails=$((fails + 1)); fi
}
require_vtk() {  # VTK's Python module must be there (Debian python3-vtk9): missing is a failure, not a skip
  if ! /usr/bin/python3 -c 'import vtk' 2>/dev/null; then
    echo "FAIL: /usr/bin/python3 cannot import vtk (install the Debian package python3-vtk9)"; exit 1
  fi
}
