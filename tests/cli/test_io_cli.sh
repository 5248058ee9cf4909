#!/usr/bin/env bash
# End-to-end tests of coxmesh's files and expressions ($COXMESH = the binary): expressions against
# the equivalent presets, automatic seeding, every writer's file read back (VTU with VTK's own
# reader from Debian python3-vtk9 under /usr/bin/python3), convert and check, progress output, and
# errors (one line, non-zero exit, existing output files untouched).
set -euo pipefail
source "$(dirname "$0")/lib.sh"
py=/usr/bin/python3
cd "$tmp"

require_vtk

# The summary without what legitimately differs between two runs (timings, memory, names, files).
stable() {
  "$py" -c 'import json, sys
j = json.load(sys.stdin)
# oracle_calls: the walk tests extra simplices where its door-in/door-out guess meets a near-tie,
# which depends on the last bits of F (an expression and a preset round differently).
for k in ("timings", "peak_memory_bytes", "preset", "function", "output", "cell_complex_bytes", "seeds", "automatic_seeds",
          "file", "source", "oracle_calls"): j.pop(k, None)
print(json.dumps(j, sort_keys=True))'
}
jget() {  # jget FILE EXPR: a value of a JSON file, e.g. jget s.json 'j["cells"][2]'
  "$py" -c "import json; j = json.load(open('$1')); print($2)"
}

# ---- Expressions give the same results as the equivalent presets ----
a=$("$bin" trace --function "x^2+y^2+z^2-1" --edge-length 0.2 --seed 1,0,0 --json | stable)
b=$("$bin" trace --preset sphere --edge-length 0.2 --seed 1,0,0 --json | stable)
check "sphere: expression = preset" "$b" "$a"
a=$("$bin" trace --function "(sqrt(x^2+y^2)-1)^2+z^2-0.4^2" --edge-length 0.1 --seed 1.4,0,0 --json | stable)
b=$("$bin" trace --preset torus --edge-length 0.1 --seed 1.4,0,0 --json | stable)
check "torus: expression = preset" "$b" "$a"
a=$("$bin" trace --function "x1^2+x2^2+x3^2-1; x4" --edge-length 0.4 --seed 1,0,0,0 --json | stable)
b=$("$bin" trace --preset sphere --m 2 --dim 4 --edge-length 0.4 --seed 1,0,0,0 --json | stable)
check "S^2 in R^4 (two equations): expression = preset" "$b" "$a"
a=$("$bin" trace --function "x^2+y^2+z^2 = 1" --domain "x-0.5" --edge-length 0.2 --seed 0,0,1 --json | stable)
b=$("$bin" trace --preset sphere --cut 1,0,0,0.5 --edge-length 0.2 --seed 0,0,1 --json | stable)
check "cut sphere: --domain expression = --cut" "$b" "$a"
strip_human() { grep -v -e '^  time' -e '^  peak memory' -e '^  output' -e ':.*-manifold in' | sed 's/ ([0-9]* oracle calls)//' ; }
a=$("$bin" trace --function "x^2+y^2+z^2-1" --edge-length 0.2 --seed 1,0,0 --no-output | strip_human)
b=$("$bin" trace --preset sphere --edge-length 0.2 --seed 1,0,0 --no-output | strip_human)
check "sphere: human summaries agree" "$b" "$a"

# ---- Automatic seeding: every component in the box, reported ----
"$bin" trace --function "(x^2+y^2+z^2-1)*((x-3)^2+y^2+z^2-1)" --box -2,-2,-2,5,2,2 --edge-length 0.2 --json > two.json
check "two spheres found automatically" "2" "$(jget two.json 'j["components"]')"
check "two spheres: betti" "[2, 0, 2]" "$(jget two.json 'j["betti"]')"
check "two spheres: complete" "True" "$(jget two.json 'j["complete"]')"
out=$("$bin" trace --function "(x^2+y^2+z^2-1)*((x-3)^2+y^2+z^2-1)" --box -2,-2,-2,5,2,2 --edge-length 0.2 --no-output)
check "human report of components" "1" "$(grep -c '^  components         2$' <<<"$out")"
check "human report of automatic seeds" "1" "$(grep -c 'found automatically' <<<"$out")"
"$bin" trace --function "x^2+y^2-1" --json > circle.json   # d = 2 inferred, default box and scale
check "circle: d inferred" "2 1" "$(jget circle.json 'j["ambient_dimension"], j["manifold_dimension"]' | tr -d '(),')"
check "circle: betti" "[1, 1]" "$(jget circle.json 'j["betti"]')"

# ---- The default run: the torus, written to torus.vtu in the current directory ----
mkdir default && (cd default && "$bin" trace > summary.txt)
check "default writes torus.vtu" "1" "$(ls default | grep -c '^torus.vtu$')"
check "default summary names it" "1" "$(grep -c 'output             torus.vtu (vtu' default/summary.txt)"
check "default summary topology" "1" "$(grep -c 'Euler characteristic 0, Betti numbers (Z/2) 1 2 1' default/summary.txt)"

# ---- Every writer, read back ----
vtk_counts() {  # points, cells, and the names of the point and cell arrays of a VTU file, via VTK
  "$py" - "$1" <<'PY'
import sys, vtk
r = vtk.vtkXMLUnstructuredGridReader()
r.SetFileName(sys.argv[1])
r.Update()
if r.GetErrorCode() != 0: sys.exit("vtk could not read " + sys.argv[1])
g = r.GetOutput()
pd, cd = g.GetPointData(), g.GetCellData()
types = sorted({g.GetCellType(i) for i in range(g.GetNumberOfCells())})
arrays = [pd.GetArrayName(i) + ":" + str(pd.GetArray(i).GetNumberOfComponents()) for i in range(pd.GetNumberOfArrays())]
arrays += [cd.GetArrayName(i) for i in range(cd.GetNumberOfArrays())]
print(g.GetNumberOfPoints(), g.GetNumberOfCells(), ",".join(map(str, types)), " ".join(arrays))
PY
}
vtk_polyhedra() {  # polyhedra that VTK reads back as closed surfaces on their own points, and the others
  "$py" - "$1" <<'PY'
import sys, vtk
r = vtk.vtkXMLUnstructuredGridReader()
r.SetFileName(sys.argv[1])
r.Update()
g, stream, points = r.GetOutput(), vtk.vtkIdList(), vtk.vtkIdList()
good = bad = 0
for c in range(g.GetNumberOfCells()):
    if g.GetCellType(c) != 42: continue
    g.GetFaceStream(c, stream)
    g.GetCellPoints(c, points)
    s = [stream.GetId(i) for i in range(stream.GetNumberOfIds())]
    own = {points.GetId(i) for i in range(points.GetNumberOfIds())}
    k, edges, ok = 1, {}, True
    for _ in range(s[0]):
        face = s[k + 1:k + 1 + s[k]]
        k += 1 + s[k]
        ok &= set(face) <= own
        for a, b in zip(face, face[1:] + face[:1]):
            edges[min(a, b), max(a, b)] = edges.get((min(a, b), max(a, b)), 0) + 1
    ok &= k == len(s) and all(n == 2 for n in edges.values())
    good, bad = good + ok, bad + (not ok)
print(good, bad)
PY
}
file_counts() {  # points and elements of an OFF, PLY, OBJ or medit file, parsed independently
  "$py" - "$1" <<'PY'
import struct, sys
path = sys.argv[1]
data = open(path, "rb").read()
if path.endswith(".off"):
    t = data.decode().split()
    i = 0
    if t[0] == "nOFF": dim, i = int(t[1]), 2
    else: dim, i = 3, 1
    nv, nf = int(t[i]), int(t[i + 1]); i += 3 + nv * dim
    for _ in range(nf):
        n = int(t[i]); ids = [int(x) for x in t[i + 1:i + 1 + n]]; i += 1 + n
        assert n >= 3 and all(0 <= v < nv for v in ids)
    assert i == len(t)
    print(nv, nf)
elif path.endswith(".ply"):
    end = data.index(b"end_header\n") + 11
    head = data[:end].decode().split("\n")
    assert head[1] == "format binary_little_endian 1.0"
    nv = int([l for l in head if l.startswith("element vertex")][0].split()[2])
    nf = int([l for l in head if l.startswith("element face")][0].split()[2])
    pos = end + 24 * nv
    for _ in range(nf):
        n = data[pos]; ids = struct.unpack_from("<%di" % n, data, pos + 1); pos += 1 + 4 * n
        assert n >= 3 and all(0 <= v < nv for v in ids)
    assert pos == len(data)
    print(nv, nf)
elif path.endswith(".obj"):
    lines = data.decode().splitlines()
    nv = sum(l.startswith("v ") for l in lines)
    el = [l.split()[1:] for l in lines if l[:2] in ("f ", "l ")]
    assert all(1 <= int(v) <= nv for e in el for v in e)
    print(nv, len(el))
else:  # medit
    t = data.decode().split()
    sections, i = {}, 0
    while i < len(t):
        if t[i] in ("Vertices", "Edges", "Triangles", "Tetrahedra"):
            name, n = t[i], int(t[i + 1]); arity = {"Vertices": 3, "Edges": 2, "Triangles": 3, "Tetrahedra": 4}[name]
            rows = [t[i + 2 + r * (arity + 1): i + 2 + (r + 1) * (arity + 1)] for r in range(n)]
            if name != "Vertices": assert all(1 <= int(v) <= sections["Vertices"] for row in rows for v in row[:arity])
            sections[name] = n; i += 2 + n * (arity + 1)
        else: i += 1
    assert t[-1] == "End"
    print(sections.get("Vertices", 0), sections.get("Edges", 0), sections.get("Triangles", 0), sections.get("Tetrahedra", 0))
PY
}

# A torus (closed surface), a cap (surface with boundary), S^3 in R^4 (polyhedra), a 3-ball with boundary.
"$bin" trace --preset torus --json -o torus.cxm > torus.json
"$bin" trace --function "x^2+y^2+z^2-1" --domain "(x-1)^2+y^2+z^2-0.8" --edge-length 0.2 --seed 1,0,0 --json -o cap.cxm > cap.json
"$bin" trace --preset sphere --m 3 --dim 4 --edge-length 0.6 --json -o s3.cxm > s3.json
"$bin" trace --function "x4" --domain "x1^2+x2^2+x3^2-1" --dim 4 --edge-length 0.4 --seed 0.1,0.2,0.3,0 --json -o ball.cxm > ball.json
for name in torus cap s3 ball; do
  check "check $name.cxm = trace summary" "$(stable < $name.json | "$py" -c 'import json,sys; j=json.load(sys.stdin); print(json.dumps({k: j[k] for k in sorted(j)}))')" \
        "$("$bin" check $name.cxm --json | stable)"
done
check "check human" "1" "$("$bin" check torus.cxm | grep -c 'Euler characteristic 0, Betti numbers (Z/2) 1 2 1')"
"$bin" convert torus.cxm again.cxm > /dev/null
check "convert cxm -> cxm is byte-identical" "same" "$(cmp -s torus.cxm again.cxm && echo same || echo differ)"

# VTU: points = all vertex cells; cells = top cells (polygons / polyhedra) + boundary cells one dimension down.
c() { jget "$1.json" "$2"; }
"$bin" convert torus.cxm torus.vtu > /dev/null
check "vtu torus (VTK reader)" "$(c torus 'j["cells"][0]') $(c torus 'j["cells"][2]') 7 on_boundary:1 dimension is_boundary domains" "$(vtk_counts torus.vtu)"
"$bin" convert cap.cxm cap.vtu > /dev/null
check "vtu cap with boundary lines" \
  "$(c cap 'j["cells"][0] + j["boundary_cells"][0]') $(c cap 'j["cells"][2] + j["boundary_cells"][1]') 3,7 on_boundary:1 dimension is_boundary domains" \
  "$(vtk_counts cap.vtu)"
"$bin" convert s3.cxm s3.vtu --project pca > /dev/null
check "vtu S^3 polyhedra, R^4 coordinates kept" "$(c s3 'j["cells"][0]') $(c s3 'j["cells"][3]') 42 on_boundary:1 coordinates:4 dimension is_boundary domains" "$(vtk_counts s3.vtu)"
check "vtu S^3: VTK reads every polyhedron as a closed surface" "$(c s3 'j["cells"][3]') 0" "$(vtk_polyhedra s3.vtu)"
"$bin" convert ball.cxm ball.vtu > /dev/null
check "vtu 3-ball: polyhedra and boundary polygons" \
  "$(c ball 'j["cells"][0] + j["boundary_cells"][0]') $(c ball 'j["cells"][3] + j["boundary_cells"][2]') 7,42 on_boundary:1 coordinates:4 dimension is_boundary domains" \
  "$(vtk_counts ball.vtu)"
check "vtu 3-ball: VTK reads every polyhedron as a closed surface" "$(c ball 'j["cells"][3]') 0" "$(vtk_polyhedra ball.vtu)"
"$bin" trace --preset sphere --m 4 --dim 5 --edge-length 0.9 --domain-ball 1 --domain-center 1,0,0,0,0 --json -o s4.vtu > s4.json
check "vtu 4-manifold with boundary: the 3-skeleton" \
  "$(c s4 'j["cells"][0] + j["boundary_cells"][0]') $(c s4 'j["cells"][3] + j["boundary_cells"][3]') 42 on_boundary:1 coordinates:5 dimension is_boundary domains" \
  "$(vtk_counts s4.vtu)"
"$bin" trace --function "x^2+y^2-1" --edge-length 0.2 -o circle.vtu --quiet
check "vtu curve: lines" "1" "$(vtk_counts circle.vtu | grep -c '^[0-9]* [0-9]* 3 ')"

# OFF / nOFF / PLY / OBJ / medit, parsed independently.
for f in torus.off torus.ply torus.obj; do
  "$bin" convert torus.cxm $f > /dev/null
  check "$f read back" "$(c torus 'j["cells"][0]') $(c torus 'j["cells"][2]')" "$(file_counts $f)"
done
"$bin" convert cap.cxm cap.off > /dev/null
check "cap.off read back" "$(c cap 'j["cells"][0] + j["boundary_cells"][0]') $(c cap 'j["cells"][2]')" "$(file_counts cap.off)"
"$bin" convert s3.cxm s3.off > /dev/null
check "nOFF header for d = 4" "nOFF 4" "$(head -2 s3.off | tr '\n' ' ' | sed 's/ $//')"
check "nOFF 2-skeleton read back" "$(c s3 'j["cells"][0]') $(c s3 'j["cells"][2]')" "$(file_counts s3.off)"
"$bin" convert torus.cxm torus.mesh > /dev/null
read -r mv me mt mtet <<<"$(file_counts torus.mesh)"
check "medit torus vertices" "$(c torus 'j["cells"][0]')" "$mv"
check "medit torus triangles >= polygons" "1" "$(( mt >= $(c torus 'j["cells"][2]') ? 1 : 0 ))"
check "medit torus has no tetrahedra" "0" "$mtet"
"$bin" convert ball.cxm ball.mesh > /dev/null
read -r mv me mt mtet <<<"$(file_counts ball.mesh)"
check "medit 3-ball vertices" "$(c ball 'j["cells"][0] + j["boundary_cells"][0]')" "$mv"
check "medit 3-ball tetrahedra >= 3-cells" "1" "$(( mtet >= $(c ball 'j["cells"][3]') ? 1 : 0 ))"
check "medit 3-ball boundary triangles >= boundary polygons" "1" "$(( mt >= $(c ball 'j["boundary_cells"][2]') ? 1 : 0 ))"
tet_volume=$("$py" - ball.mesh <<'PY'
import sys
t = open(sys.argv[1]).read().split()
v = t.index("Vertices"); nv = int(t[v + 1]); P = [tuple(map(float, t[v + 2 + 4 * i: v + 5 + 4 * i])) for i in range(nv)]
k = t.index("Tetrahedra"); n = int(t[k + 1]); total = 0; negative = 0
for r in range(n):
    a, b, c, d = [P[int(x) - 1] for x in t[k + 2 + 5 * r: k + 6 + 5 * r]]
    u = [b[i] - a[i] for i in range(3)]; w = [c[i] - a[i] for i in range(3)]; z = [d[i] - a[i] for i in range(3)]
    vol = (u[0] * (w[1] * z[2] - w[2] * z[1]) - u[1] * (w[0] * z[2] - w[2] * z[0]) + u[2] * (w[0] * z[1] - w[1] * z[0])) / 6
    total += vol; negative += vol < -1e-15
print("ok" if negative == 0 and abs(total - 4.18879) < 0.3 else "bad %g %d" % (total, negative))
PY
)
check "medit 3-ball: tetrahedra positive, volume of the unit ball" "ok" "$tet_volume"
"$bin" trace --preset flat-torus --edge-length 0.5 --format ply -o flat.data --project 1,2,3 --quiet
check "--format overrides the extension" "ply" "$(head -1 flat.data)"

# ---- Progress: stderr stays empty with --json and --quiet; plain lines (no \r) when not a terminal ----
check "no progress with --json" "" "$("$bin" trace --preset sphere --edge-length 0.03 --json 2>&1 >/dev/null)"
check "nothing at all with --quiet" "" "$("$bin" trace --preset sphere --edge-length 0.03 --no-output --quiet 2>&1)"
"$bin" trace --preset sphere --edge-length 0.015 --no-output > long.txt 2> progress.txt
check "progress lines are plain" "0" "$(grep -c $'\r' progress.txt || true)"
if "$py" -c "import sys; sys.exit(0 if float(open('long.txt').read().split('trace ')[1].split()[0]) > 2 else 1)"; then
  check "progress lines on a long run" "1" "$(( $(grep -c '^coxmesh: tracing: [0-9]* simplices' progress.txt) >= 1 ? 1 : 0 ))"
else
  echo "ok   (trace shorter than 2 s: progress lines not required)"
fi

# ---- Errors: one line, non-zero exit, existing output untouched ----
echo previous > keep.vtu
fails_with "unparsable expression shows the position" "at position 5" "$bin" trace --function "x^2+*y" -o keep.vtu
fails_with "missing parenthesis" "marked:" "$bin" trace --function "sin(x+y" -o keep.vtu
fails_with "unknown variable" "unknown variable 'foo'" "$bin" trace --function "x^2+foo" -o keep.vtu
fails_with "too many equations" "fewer equations than the dimension" "$bin" trace --function "x; y; z" -o keep.vtu
# ---- Any number of threads writes the same bytes ----
same_files() {  # same_files NAME EXT TRACE-ARGS...: files for 1, 2, 3 and 4 threads are identical
  local name=$1 ext=$2; shift 2
  for t in 1 2 3 4; do "$bin" trace "$@" --threads "$t" -q -o "threads$t.$ext"; done
  local same=yes
  for t in 2 3 4; do cmp -s threads1."$ext" threads"$t"."$ext" || same=no; done
  check "$name: identical $ext files for 1-4 threads" "yes" "$same"
}
same_files "torus" cxm --preset torus --edge-length 0.05
same_files "torus" vtu --preset torus --edge-length 0.05
same_files "S^3 in R^5, cut" cxm --preset sphere --m 3 --dim 5 --edge-length 0.5 --cut 1,1,0,0,0,0.3 --seed -1,0,0,0,0
# (24,736 polyhedra: several ranges of 3-cells per worker, put together in order)
same_files "S^3 in R^5, cut" vtu --preset sphere --m 3 --dim 5 --edge-length 0.5 --cut 1,1,0,0,0,0.3 --seed -1,0,0,0,0
same_files "flat torus, cut" mesh --preset flat-torus --cut 1,1,0,0,0.5 --seed -1,0,1,0 --edge-length 0.1
same_files "function, automatic seeds" ply --function "x^4+y^4+z^4-1" --domain "z-0.2" --edge-length 0.05

fails_with "domain with two equations" "2 expressions" "$bin" trace --function "x^2+y^2+z^2-1" --domain "x; y" -o keep.vtu
fails_with "domain beyond d" "beyond the dimension d = 3" "$bin" trace --function "x^2+y^2+z^2-1" --domain "x4" -o keep.vtu
fails_with "preset parameter with --function" "does not apply to --function" "$bin" trace --function "x^2+y^2+z^2-1" --radius 2
fails_with "no seed in the box" "no point of the manifold found" "$bin" trace --function "x^2+y^2+z^2-100" -o keep.vtu
echo notadir > file.txt
fails_with "unwritable path (parent is a file)" "cannot write file.txt/out.vtu" "$bin" trace --preset sphere -o file.txt/out.vtu
fails_with "unwritable path (no directory)" "cannot write nodir/out.vtu" "$bin" trace --preset sphere -o nodir/out.vtu
fails_with "unknown extension" "cannot tell the format" "$bin" trace --preset sphere -o out.step
fails_with "unknown format" "unknown format 'step'" "$bin" trace --preset sphere -o keep.vtu --format step
fails_with "projection beyond d" "outside 1..4" "$bin" trace --preset flat-torus -o keep.vtu --project 1,2,5
printf '1 0 0\n0 1 0\n0 0 1\n' > p3.txt
fails_with "projection matrix of the wrong shape" "expected d = 4" "$bin" convert s3.cxm keep.vtu --project p3.txt
fails_with "OFF of a curve" "holds polygons" "$bin" trace --function "x^2+y^2-1" -o keep.off
fails_with "convert a non-cxm file" "not a .cxm file" "$bin" convert keep.vtu out.vtu
fails_with "check a missing file" "cannot open" "$bin" check missing.cxm
fails_with "convert to an unwritable path" "cannot write" "$bin" convert torus.cxm nodir/x.vtu
check "existing output untouched" "previous" "$(cat keep.vtu)"
check "no temporary files left" "0" "$(ls -A | grep -c '\.tmp-' || true)"

finish
