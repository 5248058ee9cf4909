#!/usr/bin/env bash
# Careless and hostile input: each case once gave a wrong report, a crash, a hang, lost data or an
# unreadable message. Every error is one line "coxmesh: error: ...", exit 2 for usage errors.
set -euo pipefail
source "$(dirname "$0")/lib.sh"
cd "$tmp"
json_get() { python3 -c 'import json,sys; d=json.load(sys.stdin); print(d.get(sys.argv[1], "absent"))' "$1"; }

# Truncated and box-cut runs: the topology of what was written, or none; never a wrong one.
out=$("$bin" trace --preset sphere --max-simplices 100 --no-output)
check "limit: no components line" "0" "$(grep -c 'components' <<<"$out" || true)"
check "limit: topology not computed" "1" "$(grep -c 'topology           not computed' <<<"$out")"
json=$("$bin" trace --preset sphere --max-simplices 100 --json)
# The limit holds with thousands of automatic seeds (each used to add its simplices and a level).
json=$("$bin" trace --function "x1^2+x2^2+x3^2+x4^2-1" --edge-length 0.05 --max-simplices 2000 --json)
check "limit with many seeds: S stops near it" "True" "$(python3 -c 'import json,sys; print(json.load(sys.stdin)["traced_simplices"] < 4000)' <<<"$json")"
check "limit: json incomplete" "False" "$(json_get complete <<<"$json")"
check "limit: json has no betti" "absent" "$(json_get betti <<<"$json")"
check "limit: json not closed" "False" "$(json_get closed <<<"$json")"
genus2="(x*(x-1)^2*(x-2)+y^2)^2+z^2-0.01"  # reaches x = 2.045, past the default box [-2,2]^3
json=$("$bin" trace --function "$genus2" --seed 0,0.1,0 --json)
check "seed without box: whole genus-2 surface" "[1, 4, 1]" "$(json_get betti <<<"$json")"
check "seed without box: manifold" "True" "$(json_get is_manifold <<<"$json")"
json=$("$bin" trace --function "$genus2" --json)
check "default box cuts a closed disk out" "[1, 4, 0]" "$(json_get betti <<<"$json")"
check "default box: manifold with boundary" "True" "$(json_get is_manifold <<<"$json")"
json=$("$bin" trace --preset sphere --box -2,-2,0,2,2,2 --json)
check "box: half sphere is a disk" "[1, 0, 0]" "$(json_get betti <<<"$json")"
check "box: complete" "True" "$(json_get complete <<<"$json")"

# Numbers and options.
exits_with "empty function" 1 "empty" "$bin" trace --function "" --no-output
exits_with "blank function" 1 "empty" "$bin" trace --function "   " --no-output
exits_with "negative count" 2 "not a non-negative integer" "$bin" trace --max-simplices -5 --no-output
exits_with "count past 2^64" 2 "below 2^64" "$bin" trace --max-simplices 18446744073709551616 --no-output
exits_with "negative rotation seed" 2 "not a non-negative integer" "$bin" trace --rotate -1 --no-output
exits_with "bad number" 2 "--edge-length" "$bin" trace --edge-length 1e --no-output
exits_with "threads abc" 2 "--threads" "$bin" trace --threads abc --no-output
exits_with "unknown option" 2 "--bogus" "$bin" trace --bogus
exits_with "unknown subcommand" 2 "bogus" "$bin" bogus
exits_with "repeated preset" 2 "--preset" "$bin" trace --preset sphere --preset torus
exits_with "empty field" 1 "empty field" "$bin" trace --preset sphere --seed 1,,0
exits_with "trailing comma" 1 "empty field" "$bin" locate --point 1,2,
check "subnormal coordinate is a number" "0" "$("$bin" locate --point 1e-320,0.5 >/dev/null; echo $?)"
exits_with "preset ignores --m" 1 "--m does not apply to the preset torus" "$bin" trace --preset torus --m 1
exits_with "preset ignores --center" 1 "--center does not apply" "$bin" trace --preset torus --center 1,2,3
exits_with "preset ignores --dim" 1 "--dim does not apply" "$bin" trace --preset so3 --dim 4
exits_with "domain centre without ball" 1 "--domain-center needs --domain-ball" "$bin" trace --domain-center 1,0,0

# Functions that define no manifold, or are not finite.
exits_with "F = 0" 1 "vanishes identically" "$bin" trace --function 0 --dim 3 --no-output
exits_with "dependent equations" 1 "dependent" "$bin" trace --function "x^2+y^2+z^2-1; 2*(x^2+y^2+z^2)-2" --no-output
exits_with "0/0" 1 "not finite" "$bin" trace --function "0/0+x+y+z" --no-output
exits_with "1/0" 1 "not finite" "$bin" trace --function "1/0+x+y+z" --no-output
long=$(python3 -c 'print("+".join(["x"] * 40000))')
exits_with "expression too long" 1 "too long" "$bin" trace --function "$long" --no-output
exits_with "newline in an expression" 1 "" "$bin" trace --function $'x^2+\ny^2+z^2-1)' --no-output
head -c 300 /dev/urandom > binary.txt
exits_with "binary matrix file" 1 "matrix file" "$bin" trace --matrix binary.txt --no-output
mkdir adir
exits_with "directory as matrix" 1 "is a directory" "$bin" trace --matrix adir --no-output
exits_with "directory as projection" 1 "is a directory" "$bin" trace --preset flat-torus --project adir -o f.off
exits_with "directory as points" 1 "is a directory" "$bin" locate --dim 2 --points adir
exits_with "directory as samples" 1 "is a directory" "$bin" trace --points adir --m 2
exits_with "samples and a function" 2 "excludes" "$bin" trace --points adir --function x

# A zero set that is not a regular level, a domain tangent to M: meshed, with a warning.
err=$("$bin" trace --function "(x^2+y^2+z^2-1)^2" --no-output 2>&1 >/dev/null)
check "square: warning" "1" "$(grep -c 'coxmesh: warning: .*singular' <<<"$err")"
err=$("$bin" trace --function "x^2+y^2+z^2" --no-output 2>&1 >/dev/null)
check "point: warning" "1" "$(grep -c 'coxmesh: warning: .*singular' <<<"$err")"
err=$("$bin" trace --function "x^2+y^2+z^2-1" --domain "x^2+y^2+z^2-1" --no-output 2>&1 >/dev/null)
check "tangent domain: warning" "1" "$(grep -c 'coxmesh: warning: .*tangent' <<<"$err")"
err=$("$bin" trace --function "x^2+y^2+z^2-1" --domain "z" --no-output 2>&1 >/dev/null)
check "regular level: no warning" "" "$err"
json=$("$bin" trace --function "(x^2+y^2+z^2-1)^2" --json)
check "square: warning in json" "1" "$(json_get warnings <<<"$json" | grep -c singular)"

# Paths that are not UTF-8, and what -o points at.
json=$("$bin" trace -o $'lat\xe9.vtu' --json)
check "non-UTF-8 output path: JSON" "True" "$(json_get complete <<<"$json")"
exits_with "non-UTF-8 missing input" 1 "cannot open" "$bin" check $'bad\xff.cxm' --json
echo old > real.off
ln -s real.off link.off
"$bin" trace -q -o link.off
check "symlink stays a link" "real.off" "$(readlink link.off)"
check "symlink target written" "OFF" "$(head -1 real.off)"
mkdir sub && ln -s ../real.off sub/rel.off && echo old > real.off
"$bin" trace -q -o sub/rel.off
check "relative symlink target written" "OFF" "$(head -1 real.off)"
check "no temporary files left" "" "$(ls -A sub | grep -v rel.off || true)"
mkfifo pipe.off
(cat pipe.off > from_pipe.txt) &
"$bin" trace -q -o pipe.off
wait
check "fifo stays a fifo" "yes" "$([[ -p pipe.off ]] && echo yes || echo no)"
check "fifo received the mesh" "OFF" "$(head -1 from_pipe.txt)"
if [[ -w /dev/null && $(id -u) -eq 0 ]]; then
  "$bin" trace -q -o /dev/null --format off
  check "/dev/null stays a device" "yes" "$([[ -c /dev/null ]] && echo yes || echo no)"
fi
out=$("$bin" trace -o - --format off 2>summary.txt)
check "-o -: mesh on standard output" "OFF" "$(head -1 <<<"$out")"
check "-o -: summary on standard error" "1" "$(grep -c 'Betti' summary.txt)"
exits_with "-o - binary" 1 "binary" "$bin" trace -o - --format cxm

# Out of memory is an error line, not an abort.
[[ ${COXMESH_SANITIZED:-0} == 1 ]] ||  # (sanitizers cannot start under a limit on the address space)
  exits_with "out of memory" 1 "out of memory" bash -c "ulimit -v 300000; exec \"$bin\" trace --preset sphere --edge-length 0.004 -q --no-output"

finish
