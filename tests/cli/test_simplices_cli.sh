#!/usr/bin/env bash
# End-to-end tests of the simplicial output ($COXMESH = the binary): --simplices in VTU (read back
# with VTK's reader from Debian python3-vtk9) and OFF, binary STL and Gmsh .msh files read back,
# --project stereographic, --refine, and the error lines of formats and options that cannot apply.
set -euo pipefail
source "$(dirname "$0")/lib.sh"
py=/usr/bin/python3
cd "$tmp"

require_vtk

# The torus as polygons (OFF) gives the expected triangle count: the sum of (sides - 2).
"$bin" trace --preset torus --edge-length 0.1 -o poly.off -q
fan=$(awk 'NR == 2 { nv = $1; nf = $2 } NR > 2 + nv && NR <= 2 + nv + nf { t += $1 - 2 } END { print t }' poly.off)
"$bin" trace --preset torus --edge-length 0.1 -o tri.off --simplices -q
check "OFF --simplices: sum of (sides - 2) triangles" "$fan" "$(awk 'NR == 2 { print $2 }' tri.off)"
check "OFF --simplices: only triangles" "0" "$(awk 'NR == 2 { nv = $1 } NR > 2 + nv && $1 != 3' tri.off | wc -l)"

# VTU --simplices: VTK reads triangles only, as many; a 3-manifold gives tetrahedra.
"$bin" trace --preset torus --edge-length 0.1 -o tri.vtu --simplices -q
"$bin" trace --preset sphere --m 3 --dim 4 --edge-length 0.5 --project 1,2,3 -o s3.vtu --simplices -q
vtk_types() {
  "$py" -c 'import sys, vtk, collections
r = vtk.vtkXMLUnstructuredGridReader(); r.SetFileName(sys.argv[1]); r.Update(); g = r.GetOutput()
c = collections.Counter(g.GetCellType(i) for i in range(g.GetNumberOfCells()))
print(" ".join(f"{t}:{n}" for t, n in sorted(c.items())))' "$1"
}
check "VTU --simplices of a surface: VTK_TRIANGLE only" "5:$fan" "$(vtk_types tri.vtu)"
check "VTU --simplices of S^3: VTK_TETRA only" "10" "$(vtk_types s3.vtu | cut -d: -f1)"

# Binary STL: 84 + 50 bytes per triangle, the count in the header; the sphere's normals point out
# (triangles with coincident vertices, where M passes through a lattice vertex, have no direction:
# skipped).
"$bin" trace --preset sphere --edge-length 0.2 -o s.stl --json > s.json
stl=$("$py" -c 'import struct, sys
b = open("s.stl", "rb").read(); n = struct.unpack_from("<I", b, 80)[0]
out = 0
for t in range(n):
    r = struct.unpack_from("<12f", b, 84 + 50 * t)
    c = [(r[3 + i] + r[6 + i] + r[9 + i]) / 3 for i in range(3)]
    u = [r[6 + i] - r[3 + i] for i in range(3)]; v = [r[9 + i] - r[3 + i] for i in range(3)]
    area = sum((u[(i + 1) % 3] * v[(i + 2) % 3] - u[(i + 2) % 3] * v[(i + 1) % 3]) ** 2 for i in range(3)) ** 0.5
    out += area > 1e-9 and sum(r[i] * c[i] for i in range(3)) <= 0
print(n, len(b) == 84 + 50 * n, out)')
# (VTK merges coincident points by default and then drops the triangles that collapse)
check "STL read by VTK's reader" "$("$py" -c 'import json; print(json.load(open("s.json"))["output"]["cells"])')" "$("$py" -c 'import vtk
r = vtk.vtkSTLReader(); r.SetFileName("s.stl"); r.MergingOff(); r.Update(); print(r.GetOutput().GetNumberOfCells())')"
check "STL: count, size, outward normals" "$("$py" -c 'import json; print(json.load(open("s.json"))["output"]["cells"])') True 0" "$stl"

# Gmsh: the cap of the sphere has triangles (type 2) and boundary lines (type 1).
"$bin" trace --preset sphere --edge-length 0.2 --domain-ball 0.9 --domain-center 1,0,0 -o cap.msh --json > cap.json
msh=$("$py" -c 'lines = open("cap.msh").read().split("\n")
i = lines.index("$Nodes"); nodes = int(lines[i + 1].split()[1])
i = lines.index("$Elements"); blocks, total = map(int, lines[i + 1].split()[:2])
j = i + 2; kinds = []
for b in range(blocks):
    dim, tag, typ, n = map(int, lines[j].split()); kinds.append(f"{dim}/{typ}")
    assert all(len(lines[j + 1 + k].split()) == 2 + dim for k in range(n)); j += 1 + n
assert lines[j] == "$EndElements"
print(nodes, total, " ".join(kinds))')
check "Gmsh: nodes, elements, blocks" "$(jget() { "$py" -c "import json; j = json.load(open('cap.json')); print($1)"; }; jget 'j["output"]["points"], j["output"]["cells"]' | tr -d '(),') 2/2 1/1" "$msh"

# --project stereographic: the flat torus of R^4 in R^3 (VTU keeps the R^4 coordinates as point
# data); the image of the sphere S^2 of R^3 is a plane (z = 0).
"$bin" trace --preset flat-torus --edge-length 0.2 --project stereographic -o ft.vtu -q
check "stereographic VTU keeps the R^4 coordinates" "4 1" "$("$py" -c 'import vtk
r = vtk.vtkXMLUnstructuredGridReader(); r.SetFileName("ft.vtu"); r.Update(); g = r.GetOutput()
c = g.GetPointData().GetArray("coordinates"); p = g.GetPoints()
# the image spans three dimensions (the default projection to x1, x2, x3 does too, but flattened)
b = [min(p.GetPoint(i)[k] for i in range(p.GetNumberOfPoints())) for k in range(3)]
B = [max(p.GetPoint(i)[k] for i in range(p.GetNumberOfPoints())) for k in range(3)]
print(c.GetNumberOfComponents(), int(all(B[k] - b[k] > 1 for k in range(3))))')"
"$bin" trace --preset flat-torus --edge-length 0.2 --project stereographic --pole 0.9,0.3,0.2,1.07 -o ft.stl -q
check "stereographic STL with a pole" "yes" "$([[ -s ft.stl ]] && echo yes)"
"$bin" trace --preset sphere --edge-length 0.2 --project stereographic -o plane.obj -q
check "stereographic image of S^2 is planar" "0" "$(awk '$1 == "v" && $4 != 0' plane.obj | wc -l)"
fails_with "--pole of the wrong size" "--pole has 3 coordinates, expected d = 4" "$bin" trace --preset flat-torus --project stereographic --pole 1,1,1 -o p.vtu
fails_with "--pole without stereographic" "does not apply to --project pca" "$bin" trace --preset flat-torus --project pca --pole 1,1,1,1 -o p.vtu
"$py" -c 'import math
for i in range(400):
    z = -1 + (i + 0.5) / 200; r = math.sqrt(1 - z * z); a = 2.399963 * i
    print(r * math.cos(a), r * math.sin(a), z)' > cloud.xyz
fails_with "--refine with the local-PCA oracle" "--refine needs the function F" "$bin" trace --points cloud.xyz --oracle local-pca --refine --no-output
fails_with "--pole without output" "--pole applies to the output file" "$bin" trace --preset flat-torus --pole 1,1,1,1 --no-output

# --refine: the vertices on M (JSON report), the same complex; text line; with a domain.
"$bin" trace --preset torus --edge-length 0.1 --json --no-output > plain.json
"$bin" trace --preset torus --edge-length 0.1 --json --no-output --refine --threads 2 > refined.json
check "--refine: report" "True True 0 True" "$("$py" -c 'import json
p = json.load(open("plain.json")); r = json.load(open("refined.json")); f = r["refinement"]
print(f["max_abs_f_before"] > 1e-4, f["max_abs_f_after"] < 1e-12, f["not_refined"], r["cells"] == p["cells"] and r["betti"] == p["betti"])')"
check "--refine: text summary" "1" "$("$bin" trace --preset sphere --refine --no-output | grep -c '^  refinement         max |F| ')"
check "--refine with a domain" "True 0" "$("$bin" trace --preset sphere --domain-ball 0.9 --domain-center 1,0,0 --refine --json | "$py" -c 'import json, sys
f = json.load(sys.stdin)["refinement"]; print(f["max_abs_f_after"] < 1e-12, f["not_refined"])')"
check "--refine: written vertices on the sphere" "1" "$("$bin" trace --preset sphere --refine -o r.obj -q && awk '$1 == "v" { e = sqrt($2 * $2 + $3 * $3 + $4 * $4) - 1; if (e < 0) e = -e; if (e > m) m = e } END { print (m < 1e-12) }' r.obj)"

# Formats that cannot hold the mesh: one error line, before tracing, no file.
fails_with "STL of a curve" "stl holds triangles, but this is a 1-manifold" "$bin" trace --function "x^2+y^2-1" -o c.stl
fails_with "STL in R^4 without a projection" "give --project" "$bin" trace --preset flat-torus -o f.stl
fails_with "msh of a 4-manifold" "msh holds lines, triangles and tetrahedra" "$bin" trace --preset sphere --m 4 --dim 5 -o s4.msh
fails_with "--simplices of a 4-manifold" "--simplices: only curves" "$bin" trace --preset sphere --m 4 --dim 5 -o s4.vtu --simplices
fails_with "--simplices in .cxm" "native format .cxm stores the cells" "$bin" trace --preset sphere -o s.cxm --simplices
fails_with "--simplices without output" "there is none" "$bin" trace --preset sphere --no-output --simplices
check "no files left by the errors" "0" "$(ls c.stl f.stl s4.msh s4.vtu s.cxm p.vtu 2>/dev/null | wc -l)"

finish
