#!/usr/bin/env bash
# End-to-end tests of `coxmesh trace --points` ($COXMESH): topology of sampled manifolds, the
# report, the non-orientability warning, and bad input.
set -euo pipefail
source "$(dirname "$0")/lib.sh"
cd "$tmp"

# Deterministic samples: n points of a Fibonacci spiral on the unit sphere, and their image under
# (x,y,z) -> (xy, xz, y^2 - z^2, 2yz), a projective plane in R^4.
awk 'BEGIN { n = 2000; g = 3.14159265358979 * (3 - sqrt(5));
  for (i = 0; i < n; i++) { z = 1 - 2 * (i + 0.5) / n; r = sqrt(1 - z * z); printf "%.12g %.12g %.12g\n", r * cos(i * g), r * sin(i * g), z } }' > sphere.xyz
awk '{ printf "%.12g %.12g %.12g %.12g\n", $1 * $2, $1 * $3, $2 * $2 - $3 * $3, 2 * $2 * $3 }' sphere.xyz > rp2.txt

json=$("$bin" trace --points sphere.xyz --m 2 --json | tr -d ' \n')
check "points sphere betti" "1" "$(grep -c '"betti":\[1,0,1\]' <<<"$json")"
check "points sphere manifold" "1" "$(grep -c '"is_manifold":true' <<<"$json")"
check "points sphere frames" "1" "$(grep -c '"frames_consistent":true' <<<"$json")"
check "points sphere samples" "1" "$(grep -c '"samples":2000' <<<"$json")"
# Far from the origin (a scan in geographic coordinates): the lattice is centred on the samples.
awk '{ printf "%.17g %.17g %.17g\n", $1 + 3e8, $2 - 5e8, $3 + 1e3 }' sphere.xyz > far.xyz
check "points far from the origin" "1" "$("$bin" trace --points far.xyz --no-output | grep -c 'Betti numbers (Z/2) 1 0 1')"
out=$("$bin" trace --points sphere.xyz)  # m defaults to d - 1; writes sphere.vtu
check "points default m" "1" "$(grep -c 'Betti numbers (Z/2) 1 0 1' <<<"$out")"
check "points report spacing" "1" "$(grep -c 'sample spacing' <<<"$out")"
check "points default output" "yes" "$([[ -s sphere.vtu ]] && echo yes || echo no)"
printf '1.7 1.7 1.7\n-1.8 0.5 1.6\n' | cat sphere.xyz - > outliers.xyz
out=$("$bin" trace --points outliers.xyz --no-output)
check "points outliers" "1 1" "$(grep -c 'Betti numbers (Z/2) 1 0 1' <<<"$out") $(grep -c '2 isolated samples' <<<"$out")"
json=$("$bin" trace --points sphere.xyz --pc-function nearest --tube 4 --edge-length 0.08 --json | tr -d ' \n')
check "points nearest" "1" "$(grep -c '"betti":\[1,0,1\]' <<<"$json")"
check "points edge length given" "1" "$(grep -c '"edge_length":0.08' <<<"$json")"
# The per-simplex local-PCA oracle: its defects in the JSON and in the text; the default has none to report.
json=$("$bin" trace --points sphere.xyz --oracle local-pca --json | tr -d ' \n')
check "points local-pca json" "1 1" "$(grep -c '"oracle":"local-pca"' <<<"$json") $(grep -c '"local_pca_defects":[0-9]' <<<"$json")"
check "points local-pca text" "1" "$("$bin" trace --points sphere.xyz --oracle local-pca --no-output | grep -c '^  local-pca defects  [0-9]')"
json=$("$bin" trace --points sphere.xyz --json | tr -d ' \n')
check "points default oracle" "1 0" "$(grep -c '"oracle":"vertex"' <<<"$json") $(grep -c 'local_pca_defects' <<<"$json")"
fails_with "points local-pca domain" "takes no --domain" "$bin" trace --points sphere.xyz --oracle local-pca --cut 0,0,1,0 --no-output
fails_with "points auto-seed" "automatic seeds do not apply to samples" "$bin" trace --points sphere.xyz --auto-seed --no-output
(cat sphere.xyz; head -5 sphere.xyz) > dup.xyz
check "points duplicates" "1" "$("$bin" trace --points dup.xyz --no-output | grep -c '5 exact duplicates removed')"

# The preparation and the trace run on the workers: the same file, byte for byte, for any --threads.
"$bin" trace --points sphere.xyz --threads 1 -o t1.ply --quiet
"$bin" trace --points sphere.xyz --threads 3 -o t3.ply --quiet
check "points threads same file" "yes" "$(cmp -s t1.ply t3.ply && [[ -s t1.ply ]] && echo yes || echo no)"

# RP^2 and the Klein bottle in R^4 have non-orientable normal bundles: no per-vertex function
# meshes them (--oracle vertex warns, on stderr and in the JSON); by default the winding oracle
# does, with their Z/2 Betti numbers, clean and with a little noise, the same file for any --threads.
err=$("$bin" trace --points rp2.txt --m 2 --oracle vertex --no-output 2>&1 >/dev/null)
check "rp2 vertex warning" "1" "$(grep -c '^coxmesh: warning: .*frustrated\|^coxmesh: warning: .*cannot be trusted' <<<"$err")"
json=$("$bin" trace --points rp2.txt --m 2 --oracle vertex --json 2>/dev/null | tr -d ' \n')
check "rp2 vertex json" "1 1" "$(grep -c '"frames_consistent":false' <<<"$json") $(grep -c '"warnings":' <<<"$json")"
out=$("$bin" trace --points rp2.txt --m 2 --no-output 2>&1)
check "rp2 winding" "1 1 1 0" "$(grep -c 'Betti numbers (Z/2) 1 1 1' <<<"$out") $(grep -c 'manifold check     passed' <<<"$out") \
$(grep -c '^  oracle             winding (chosen because the normal frames look non-orientable): 0 tetrahedra' <<<"$out") \
$(grep -c 'warning' <<<"$out")"
json=$("$bin" trace --points rp2.txt --m 2 --json 2>/dev/null | tr -d ' \n')
check "rp2 winding json" "1 1 1 1 0" "$(grep -c '"betti":\[1,1,1\]' <<<"$json") $(grep -c '"euler_characteristic":1,' <<<"$json") \
$(grep -c '"oracle":"winding","oracle_reason":"chosenbecause' <<<"$json") $(grep -c '"winding_odd_tetrahedra":0' <<<"$json") \
$(grep -c '"warnings":' <<<"$json")"
awk 'BEGIN { n = 2500; pi = 3.14159265358979; g = (sqrt(5) - 1) / 2;
  for (i = 0; i < n; i++) { u = 2 * pi * (i + 0.5) / n; v = 2 * pi * (i * g - int(i * g)); r = 1 + 0.4 * cos(v);
    e = 0.005 * sin(12.9898 * i); f = 0.005 * cos(78.233 * i);
    printf "%.12g %.12g %.12g %.12g\n", r * cos(u) + e, r * sin(u) + f, 0.4 * sin(v) * cos(u / 2) - e, 0.4 * sin(v) * sin(u / 2) + f } }' > klein.txt
awk '{ printf "%.12g %.12g %.12g %.12g\n", $1 + 0.004 * sin(3.7 * NR), $2 + 0.004 * cos(5.3 * NR), $3 - 0.004 * sin(7.1 * NR), $4 + 0.004 * cos(2.9 * NR) }' rp2.txt > rp2-noisy.txt
json=$("$bin" trace --points klein.txt --m 2 --json | tr -d ' \n')
check "klein winding" "1 1 1" "$(grep -c '"betti":\[1,2,1\]' <<<"$json") $(grep -c '"is_manifold":true' <<<"$json") $(grep -c '"oracle":"winding"' <<<"$json")"
json=$("$bin" trace --points rp2-noisy.txt --m 2 --json | tr -d ' \n')
check "rp2 noisy winding" "1 1" "$(grep -c '"betti":\[1,1,1\]' <<<"$json") $(grep -c '"is_manifold":true' <<<"$json")"
"$bin" trace --points rp2.txt --m 2 --threads 1 -o w1.cxm --quiet
"$bin" trace --points rp2.txt --m 2 --threads 3 -o w3.cxm --quiet
check "rp2 threads same file" "yes" "$(cmp -s w1.cxm w3.cxm && [[ -s w1.cxm ]] && echo yes || echo no)"
json=$("$bin" trace --points klein.txt --m 2 --oracle winding --json | tr -d ' \n')
check "klein requested winding" "1" "$(grep -c '"oracle":"winding","oracle_reason":"requested"' <<<"$json")"
fails_with "winding codimension" "codimension 2" "$bin" trace --points sphere.xyz --oracle winding --no-output
fails_with "winding domain" "takes no --domain" "$bin" trace --points rp2.txt --m 2 --oracle winding --cut 0,0,1,0,0 --no-output

# Bad input: one line, non-zero exit.
printf '0 0 0\n1 nan 0\n' > nan.xyz
fails_with "points NaN" "NaN" "$bin" trace --points nan.xyz --no-output
fails_with "points extension" "unknown point file extension" "$bin" trace --points sphere.las --no-output
mkdir folder.xyz
fails_with "points directory" "is a directory" "$bin" trace --points folder.xyz --no-output
fails_with "points missing" "cannot open" "$bin" trace --points none.xyz --no-output
fails_with "points m too big" "between 1 and d" "$bin" trace --points sphere.xyz --m 3 --no-output
fails_with "points preset parameter" "does not apply to --points" "$bin" trace --points sphere.xyz --radius 2 --no-output
fails_with "points no normals" "has no normals" "$bin" trace --points sphere.xyz --use-normals --no-output
fails_with "points wrong dim" "expected R^4" "$bin" trace --points sphere.xyz --dim 4 --no-output
head -3 sphere.xyz > three.xyz
fails_with "points too few" "too few for a 2-manifold" "$bin" trace --points three.xyz --no-output
for i in 1 2 3 4 5 6; do echo "1 2 3"; done > same.xyz
printf '1\n2\n3\n4\n' > line1.xyz
fails_with "points of R^1" "the samples have 1 coordinate each" "$bin" trace --points line1.xyz --no-output
fails_with "points all the same" "6 samples are only 1 distinct point: too few" "$bin" trace --points same.xyz --no-output
printf 'x,y,z\n1,2,3\n4,5\n' > ragged.csv
fails_with "points ragged csv" "line 3 has 2 numbers, line 2 has 3" "$bin" trace --points ragged.csv --no-output
err=$("$bin" trace --points sphere.xyz --function x --no-output 2>&1) && status=0 || status=$?
check "points excludes function" "1 1" "$([[ $status -ne 0 ]] && echo 1) $(grep -c 'excludes' <<<"$err")"
finish
