#!/usr/bin/env bash
# End-to-end tests of the coxmesh binary ($COXMESH): outputs, JSON keys, errors and exit codes.
set -euo pipefail
source "$(dirname "$0")/lib.sh"
cd "$tmp"  # `coxmesh trace` writes NAME.vtu in the current directory

# locate: worked examples computed with GUDHI.
check "locate FK" "(3,-2,0) [{0},{2},{1},{3}]" "$("$bin" locate --triangulation freudenthal --point 3.5,-1.8,0.3 | cut -d' ' -f1-2)"
json=$("$bin" locate --triangulation freudenthal --point 0.3,0.7 --json)
check "locate json" '{"cartesian":[[0.0,0.0],[0.0,1.0],[1.0,1.0]],"dimension":2,"partition":[[1],[0],[2]],"vertex":[0,0]}' "$json"
printf '0 1.0000000000000002\n1.1547005383792517 -0.57735026918962584\n' > "$tmp/m.txt"
check "locate --matrix" "(1,-1) [{1},{0},{2}]" "$("$bin" locate --matrix "$tmp/m.txt" --point -0.2,1.5 | cut -d' ' -f1-2)"
printf '0.3 0.7\n# comment\n\n0.7,0.3\n' > "$tmp/pts.txt"
check "locate --points" "2" "$("$bin" locate --dim 2 --points "$tmp/pts.txt" --triangulation freudenthal | wc -l)"
check "locate stdin json" "2" "$(printf '0 0\n0.5 0.5\n' | "$bin" locate --dim 2 --points - --json | grep -c '"dimension"')"
check "locate offset" "(0,0) [{0,1,2}]" "$("$bin" locate --triangulation freudenthal --offset 0.5,0.5 --point 0.5,0.5 | cut -d' ' -f1-2)"

# faces / cofaces.
check "cofaces count" "6" "$("$bin" cofaces --simplex "(0,0) [{0,1,2}]" --dim 2 | wc -l)"
check "faces edges" "6" "$("$bin" faces --simplex "(0,0,0) [{0},{1},{2},{3}]" --dim 1 | wc -l)"
check "faces json" "4" "$("$bin" faces --simplex "(0,0,0) [{0},{1},{2},{3}]" --dim 2 --json | grep -o '"dimension":2' | wc -l)"

# Errors: one line, non-zero exit.
fails_with "wrong coordinate count" "coordinates, expected 3" "$bin" locate --dim 3 --point 1,2
fails_with "NaN" "NaN" "$bin" locate --point 1,nan
fails_with "Inf" "infinite" "$bin" locate --point 1,inf
fails_with "garbage" "not a number" "$bin" locate --point 1,2x
printf '1 2\n2 4\n' > "$tmp/sing.txt"
fails_with "singular matrix" "singular" "$bin" locate --matrix "$tmp/sing.txt" --point 1,2
printf '1 2 3\n2 4 5\n' > "$tmp/rect.txt"
fails_with "non-square matrix" "square" "$bin" locate --matrix "$tmp/rect.txt" --point 1,2
fails_with "missing matrix" "cannot open" "$bin" locate --matrix "$tmp/none.txt" --point 1,2
fails_with "unsorted block" "strictly increasing" "$bin" faces --simplex "(0,0) [{1,0},{2}]"
fails_with "overlapping blocks" "two blocks" "$bin" faces --simplex "(0,0) [{0,1},{1,2}]"
fails_with "d not last" "last block" "$bin" faces --simplex "(0,0) [{0,2},{1}]"
fails_with "overflow" "out of range" "$bin" faces --simplex "(0,99999999999) [{0,1,2}]"
fails_with "far point" "exceeds 2^30" "$bin" locate --point 1e12,0
fails_with "d too large" "not supported" "$bin" locate --point "$(seq -s, 1 40)"
fails_with "bad face dim" "outside" "$bin" faces --simplex "(0,0) [{0},{1,2}]" --dim 3

# trace: the default torus, JSON keys, presets, boundary, errors.
out=$("$bin" trace)
check "trace default torus" "1" "$(grep -c 'Euler characteristic 0, Betti numbers (Z/2) 1 2 1' <<<"$out")"
json=$("$bin" trace --preset sphere --json)
for key in ambient_dimension manifold_dimension traced_simplices boundary_simplices cells boundary_cells \
           euler_characteristic betti is_manifold function_evaluations timings corners strata; do
  check "trace json has $key" "1" "$(grep -c "^  \"$key\"" <<<"$json")"  # (top level: 2 spaces)
done
check "trace sphere chi" "1" "$(tr -d ' \n' <<<"$json" | grep -c '"euler_characteristic":2')"
json=$("$bin" trace --preset sphere --domain-ball 0.5 --domain-center 1,0,0 --json | tr -d ' \n')
check "trace cap chi" "1" "$(grep -c '"euler_characteristic":1' <<<"$json")"
check "trace cap manifold" "1" "$(grep -c '"is_manifold":true' <<<"$json")"
check "presets lists torus" "1" "$("$bin" presets | grep -c '^torus')"
json=$("$bin" trace --preset moment-curve --dim 4 --domain-ball 100 --max-simplices 500 --json | tr -d ' \n')
check "trace limit" "1" "$(grep -c '"complete":false' <<<"$json")"
fails_with "trace seed far" "meets the manifold" "$bin" trace --preset sphere --seed 0,0,0
fails_with "trace seed dims" "coordinates, expected 3" "$bin" trace --preset sphere --seed 1,0
fails_with "trace unknown preset" "unknown preset" "$bin" trace --preset nope
fails_with "trace seed outside domain" "outside the domain" "$bin" trace --preset sphere --domain-ball 0.3 --domain-center -1,0,0
fails_with "trace bad box" "2d = 6" "$bin" trace --preset sphere --box 0,0,1

finish
