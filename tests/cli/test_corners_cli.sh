#!/usr/bin/env bash
# End-to-end tests of manifolds with corners ($COXMESH = the binary): repeated --domain/--cut each
# their own face; the strata and corners in the summary, the same for 1 and 2 threads; the bitmasks
# in .cxm (read back and validated by check; version 1 files still read) and in .vtu (VTK's own
# reader); errors.
set -euo pipefail
source "$(dirname "$0")/lib.sh"
py=/usr/bin/python3
corpus=$(cd "$(dirname "$0")/../../fuzz/corpus/cxm" && pwd)
cd "$tmp"
require_vtk

# corners, the strata (domains: cells), χ, Betti numbers, the manifold check.
strata() {
  "$py" -c 'import json, sys
j = json.load(sys.stdin)
print(j["corners"], " ".join("%s:%s" % (",".join(map(str, s["domains"])), "/".join(map(str, s["cells"]))) for s in j["strata"]),
      j.get("euler_characteristic"), j.get("betti"), j["is_manifold"])'
}
shape() {  # corners, then the number of strata per dimension, χ, Betti, manifold
  "$py" -c 'import json, sys, collections
j = json.load(sys.stdin)
n = collections.Counter(s["dimension"] for s in j["strata"])
print(j["corners"], [n[i] for i in sorted(n)], j.get("euler_characteristic"), j.get("betti"), j["is_manifold"])'
}

octant=(trace --preset sphere --domain=-x --domain=-y --cut 0,0,-1,0 --edge-length 0.15)
check "octant: 3 corners, 3 arcs, a disk" "3 [3, 3, 1] 1 [1, 0, 0] True" "$("$bin" "${octant[@]}" --json | shape)"
a=$("$bin" "${octant[@]}" --json --threads 1 | strata)
b=$("$bin" "${octant[@]}" --json --threads 2 | strata)
check "octant: same strata for 1 and 2 threads" "$a" "$b"
lines=$("$bin" "${octant[@]}" --no-output)
check "octant: strata line" "1" "$(grep -c '^  strata .*3 corners$' <<<"$lines")"
cube=(trace --function "w" --dim 4 --cut 1,0,0,0,0.5 --cut=-1,0,0,0,0.5 --cut 0,1,0,0,0.5 --cut 0,-1,0,0,0.5
      --cut 0,0,1,0,0.5 --cut 0,0,-1,0,0.5 --seed 0,0,0,0 --edge-length 0.25)
check "solid cube: 8 corners, 12 edges, 6 faces, a ball" "8 [8, 12, 6, 1] 1 [1, 0, 0, 0] True" \
  "$("$bin" "${cube[@]}" --json | shape)"
check "torus cut by two planes: 4 corners" "4 [1, 2, 1]" \
  "$("$bin" trace --preset torus --cut 1,0,0,0.3 --cut 0,0,1,0.1 --seed=-1.4,0,0 --json | shape | cut -d' ' -f1-4)"
# Corners on lattice vertices: Freudenthal–Kuhn at scale 1/8 has vertices all over x = 0, y = 0 and
# z = 0, so F and two domain functions vanish together at the corner (0, 0, 0).
check "degenerate corners: a quarter disk" "3 [3, 3, 1] 1 [1, 0, 0] True" \
  "$("$bin" trace --function "z" --triangulation freudenthal --scale 0.125 --cut 1,0,0,0 --cut 0,1,0,0 \
     --domain "x^2+y^2-1" --seed=-0.5,-0.5,0 --json | shape)"
check "one domain: interior and boundary strata" "0 [1, 1] 1 [1, 0, 0] True" \
  "$("$bin" trace --preset sphere --domain "z" --json | shape)"

# Files: .cxm keeps the bitmasks (check reports the same strata); .vtu has them as cell data.
"$bin" "${octant[@]}" --json -o octant.cxm | strata > traced.txt
check "cxm: check reads the strata back" "$(cat traced.txt)" "$("$bin" check octant.cxm --json | strata)"
check "cxm: version 2" "2" "$(head -1 octant.cxm | "$py" -c 'import json, sys; print(json.load(sys.stdin)["version"])')"
"$bin" convert octant.cxm again.cxm
check "cxm: convert cxm -> cxm is byte-identical" "same" "$(cmp -s octant.cxm again.cxm && echo same || echo different)"
"$bin" convert octant.cxm octant.vtu
check "vtu: corners and boundary arcs with their domains" "3 [3, 5, 6] 3" "$("$py" -c '
import vtk
from vtk.util.numpy_support import vtk_to_numpy
r = vtk.vtkXMLUnstructuredGridReader(); r.SetFileName("octant.vtu"); r.Update()
g = r.GetOutput(); masks = vtk_to_numpy(g.GetCellData().GetArray("domains")); dims = vtk_to_numpy(g.GetCellData().GetArray("dimension"))
corners = sorted(int(m) for m, d in zip(masks, dims) if d == 0)
print(len(corners), corners, len(set(int(m) for m, d in zip(masks, dims) if d == 1)))')"
"$bin" "${cube[@]}" -q -o cube.vtu
check "vtu: the cube's corners, edges, faces and inside by their domains" "8 12 6 1" "$("$py" -c '
import vtk
from vtk.util.numpy_support import vtk_to_numpy
r = vtk.vtkXMLUnstructuredGridReader(); r.SetFileName("cube.vtu"); r.Update()
g = r.GetOutput(); masks = vtk_to_numpy(g.GetCellData().GetArray("domains")); dims = vtk_to_numpy(g.GetCellData().GetArray("dimension"))
print(*(len(set(int(m) for m, d in zip(masks, dims) if d == j)) for j in range(4)))')"
check "cxm version 1 still reads" "True" "$("$bin" check "$corpus/circle" --json | "$py" -c 'import json, sys; print(json.load(sys.stdin)["is_manifold"])')"
"$py" -c '
data = open("octant.cxm", "rb").read()
open("fewer.cxm", "wb").write(data.replace(b"\"domains\":3", b"\"domains\":1", 1))'
fails_with "cxm: bitmasks naming missing domains" "domains that do not exist" "$bin" check fewer.cxm

# --refine: every vertex onto the sphere and the planes of its stratum, the corners exactly at the
# unit points; the strata unchanged; the same for 1 and 2 threads.
"$bin" "${octant[@]}" --refine --json -o refined.off > refined.json
check "refine: the report" "0 True" "$("$py" -c '
import json; r = json.load(open("refined.json"))["refinement"]
print(r["not_refined"], r["max_abs_f_after"] <= 1e-10 * r["max_abs_f_before"] and r["max_abs_f_before"] > 1e-4)')"
check "refine: strata unchanged" "$a" "$(strata < refined.json)"
check "refine: vertices on the sphere inside the octant, corners at the unit points" "True [True, True, True]" \
  "$("$py" -c '
import numpy as np
lines = open("refined.off").read().split("\n"); n = int(lines[1].split()[0])
x = np.array([[float(v) for v in l.split()] for l in lines[2:2 + n]])
print(bool(np.all(np.abs(np.linalg.norm(x, axis=1) - 1) < 1e-12) and np.all(x > -1e-12)),
      [bool(np.min(np.linalg.norm(x - e, axis=1)) < 1e-10) for e in np.eye(3)])')"
check "refine: same for 1 and 2 threads" "same" \
  "$("$bin" "${octant[@]}" --refine --threads 2 -q -o refined2.off && cmp -s refined.off refined2.off && echo same || echo different)"

# Errors: one line each.
too_many=()
for i in $(seq 65); do too_many+=(--cut "0,0,1,$i"); done
exits_with "more than 64 domains" 1 "at most 64 domains" "$bin" trace --preset sphere "${too_many[@]}" --no-output
exits_with "seed outside the domains" 1 "inside the domains" "$bin" trace --preset sphere --cut 1,0,0,0 --cut 0,1,0,0 --seed 1,0,0 --no-output
exits_with "3-manifold with corners to stl" 1 "cannot hold this manifold with corners" "$bin" "${cube[@]}" --project 1,2,3 -o cube.stl
check "surface with corners to off" "OFF" "$("$bin" "${octant[@]}" -q -o octant.off && head -1 octant.off)"
finish
