#!/usr/bin/env bash
# End-to-end tests of `mpirun -n P coxmesh trace` ($COXMESH = the binary, $MPIEXEC = mpirun): for
# P = 1, 2, 3 on this machine, the file and the JSON summary (timings, memory and the file's name
# aside) are byte for byte those of one process with one thread, F evaluations included (a .cxm
# written in pieces, merged by `coxmesh convert`; the topology computed without gathering the
# complex); a failure
# of F on one rank stops every rank with one error line and a non-zero status; --refine with pieces
# (each rank refines its vertices); manifolds with corners (rank 0 meshes them as one process does).
set -euo pipefail
source "$(dirname "$0")/lib.sh"
mpiexec=${MPIEXEC:?set MPIEXEC to mpirun}
cd "$tmp"
# (root in containers; more ranks than cores; no network but this machine)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl=self,vader OMPI_MCA_rmaps_base_oversubscribe=1
mpi() {  # mpi P ARGS...: coxmesh ARGS on P processes, ended after 120 s (a hang is a failure)
  local n=$1; shift
  timeout 120 "$mpiexec" --oversubscribe -n "$n" "$bin" "$@"
}
stable() { grep -v -E '"(path|[a-z_]*seconds|peak_memory_bytes|cell_complex_bytes)"' "$1"; }

same_as_one_process() {  # same_as_one_process NAME TRACE-ARGS...
  local name=$1; shift
  "$bin" trace "$@" --threads 1 --json -o "$name.cxm" > "$name.json"
  for n in 1 2 3; do
    local status=0
    # (one process is today's tool, whose oracle call count depends on its threads; several
    # processes walk with one thread each, whatever --threads says)
    local threads=()
    [[ $n -eq 1 ]] && threads=(--threads 1)
    mpi "$n" trace "$@" "${threads[@]}" --json -o "$name.$n.cxm" > "$name.$n.json" 2> "$name.$n.err" || status=$?
    check "$name, $n processes: exit status" 0 "$status"
    # (several processes write a piece each and a manifest; convert merges them into one file)
    local merged=$name.$n.cxm
    if [[ $n -gt 1 ]]; then
      check "$name, $n processes: one piece per process" "$n" "$(ls "$name.$n"_*.cxm | wc -l)"
      merged=$name.$n.merged.cxm
      "$bin" convert -q "$name.$n.cxm" "$merged"
    fi
    check "$name, $n processes: the same file" "same" "$(cmp -s "$name.cxm" "$merged" && echo same || echo different)"
    check "$name, $n processes: the same summary" "$(stable "$name.json")" "$(stable "$name.$n.json")"
    if [[ $n -gt 1 ]]; then  # (the topology computed by the ranks: rank 0 gets part of the cells)
      check "$name, $n processes: rank 0 gets part of the cells" yes "$(sed -n 's/.*topology: \([0-9]*\) of \([0-9]*\) cells.*/\1 \2/p' "$name.$n.err" |
        awk '{ print ($1 < $2 ? "yes" : "no") }')"
    fi
  done
  # F once per lattice vertex in the whole job: the count is that of one process.
  check "$name: F evaluations" "$(grep function_evaluations "$name.json")" "$(grep function_evaluations "$name.3.json")"
}

same_as_one_process curve --preset moment-curve
same_as_one_process surface --preset torus
same_as_one_process three-manifold --preset sphere --m 3 --dim 4 --edge-length 0.3
same_as_one_process box --preset torus --box -2,-2,-0.1,2,2,2
same_as_one_process two-components --function "(x^2+y^2+z^2-1)*((x-3)^2+y^2+z^2-1)" --seed 1,0,0 --seed 4,0,0
same_as_one_process limit --preset torus --max-simplices 3000
# Without a file the ranks build and analyse their parts as for pieces (no process gathers the
# complex) and write nothing: the summary is one process's.
"$bin" trace --preset sphere --m 3 --dim 4 --edge-length 0.3 --threads 1 --json > no-file.json
mpi 2 trace --preset sphere --m 3 --dim 4 --edge-length 0.3 --json > no-file.2.json 2> no-file.2.err
check "no file, 2 processes: the same summary" "$(stable no-file.json)" "$(stable no-file.2.json)"
check "no file, 2 processes: rank 0 gets part of the cells" yes "$(sed -n 's/.*topology: \([0-9]*\) of \([0-9]*\) cells.*/\1 \2/p' no-file.2.err |
  awk '{ print ($1 < $2 ? "yes" : "no") }')"
check "no file, 2 processes: no file written" 0 "$(ls | grep -c -v -E '[.](json|err|cxm)$' || true)"
# (a boundary too, on 3 processes: each rank's levels are left as their cells arrived)
"$bin" trace --preset torus --box -2,-2,-0.1,2,2,2 --threads 1 --json > no-file-box.json
mpi 3 trace --preset torus --box -2,-2,-0.1,2,2,2 --json > no-file-box.3.json 2> no-file-box.3.err
check "no file with a boundary, 3 processes: the same summary" "$(stable no-file-box.json)" "$(stable no-file-box.3.json)"
# The summary of pieces (no process holds the complex) still counts the traced simplices.
summary=$(mpi 2 trace --preset torus -o rate.cxm)
check "pieces: the summary's simplex rate" "0 1" "$(grep -c '(0 simplices/s)' <<<"$summary") $(grep -c '^  traced simplices   [1-9]' <<<"$summary")"
check "limit: stopped by it" '  "complete": false,' "$(grep '"complete"' limit.2.json)"
check "two components" '  "components": 2,' "$(grep '"components"' two-components.2.json)"
check "box: a boundary" 1 "$(grep -c '"boundary_simplices": [1-9]' box.3.json)"

# F is not finite for x < -0.5: the rank that meets it first stops every rank with its error.
for n in 2 3; do
  status=0
  mpi "$n" trace --function "x^2+y^2+z^2-1+sqrt(x+0.5)-sqrt(x+0.5)" --seed 1,0,0 --json -o nan.cxm \
    > nan.out 2> nan.err || status=$?
  check "NaN on one rank, $n processes: non-zero status" 1 "$((status != 0))"
  check "NaN, $n processes: one error line" 1 "$(grep -c '^coxmesh: error: the function is not finite' nan.err)"
  check "NaN, $n processes: nothing on stdout, no file" "0 no" "$(wc -c < nan.out) $([ -e nan.cxm ] && echo yes || echo no)"
done
# Other formats: rank 0 writes the whole file, the one of one process.
"$bin" trace --preset torus --threads 1 -q -o torus.vtu
mpi 2 trace --preset torus -q -o torus.2.vtu
check "vtu, 2 processes: the same file" same "$(cmp -s torus.vtu torus.2.vtu && echo same || echo different)"
# .pvtu: a .vtu piece per process and the manifest. Read back (with python3's vtk, when installed),
# the pieces hold each cell of one process's .vtu once (the same vertices, by their global ids).
vtk_python=
for p in python3 /usr/bin/python3; do
  if "$p" -c "import vtk" 2> /dev/null; then vtk_python=$p; break; fi
done
same_cells_as_one_process() {  # NAME TRACE-ARGS...
  local name=$1; shift
  "$bin" trace "$@" --threads 1 -q -o "$name.vtu"
  local status=0
  mpi 3 trace "$@" -q -o "$name.pvtu" 2> "$name.pvtu.err" || status=$?
  check "$name .pvtu, 3 processes: exit status and pieces" "0 3" "$status $(ls "$name"_*.vtu | wc -l)"
  if [[ -n $vtk_python ]]; then
    check "$name .pvtu: the cells of one process" same "$("$vtk_python" - "$name" << 'EOF'
import sys, vtk
from vtk.util.numpy_support import vtk_to_numpy
def cells(grid, ids):
    out = []
    for c in range(grid.GetNumberOfCells()):
        points = grid.GetCell(c).GetPointIds()
        out.append(tuple(sorted(int(ids[points.GetId(i)]) for i in range(points.GetNumberOfIds()))))
    return sorted(out)
def read(reader, name):
    reader.SetFileName(name)
    reader.Update()
    return reader.GetOutput()
one = read(vtk.vtkXMLUnstructuredGridReader(), sys.argv[1] + ".vtu")
pieces = read(vtk.vtkXMLPUnstructuredGridReader(), sys.argv[1] + ".pvtu")
ids = vtk_to_numpy(pieces.GetPointData().GetArray("global_id"))
xs, ys = vtk_to_numpy(pieces.GetPoints().GetData()), vtk_to_numpy(one.GetPoints().GetData())
same = cells(one, range(one.GetNumberOfPoints())) == cells(pieces, ids) and (xs == ys[ids]).all()
print("same" if same else "different")
EOF
)"
  fi
}
same_cells_as_one_process curve-pieces --preset moment-curve
same_cells_as_one_process surface-pieces --preset torus --box -2,-2,-0.1,2,2,2
same_cells_as_one_process solid-pieces --preset sphere --m 3 --dim 4 --edge-length 0.3
status=0
"$bin" trace --preset torus -q -o one-process.pvtu 2> pvtu.err || status=$?
check ".pvtu without mpirun: refused with one error line" "1 1" "$((status != 0)) $(grep -c '^coxmesh: error:' pvtu.err)"
# A piece that cannot be written (rank 1's name is a directory): every rank stops, no manifest.
mkdir fail_1.cxm
status=0
mpi 2 trace --preset torus -q -o fail.cxm > fail.out 2> fail.err || status=$?
check "a piece not written: non-zero status, one error line, no manifest" "1 1 no" \
  "$((status != 0)) $(grep -c '^coxmesh: error:' fail.err) $([ -e fail.cxm ] && echo yes || echo no)"
# Bad input: every rank meets it at once; rank 0 says it.
status=0
mpi 2 trace --function "x^2+" --json > bad.out 2> bad.err || status=$?
check "bad expression: non-zero status, one error line" "1 1" "$((status != 0)) $(grep -c '^coxmesh: error:' bad.err)"
# Samples (a torus, quasi-random by the golden ratios): every rank prepares the same problem from
# them, and the per-vertex function is traced like any F.
awk 'BEGIN { pi = atan2(0, -1); for (i = 0; i < 3000; i++) { a = 2 * pi * ((i * 0.6180339887) % 1);
  b = 2 * pi * ((i * 0.7548776662) % 1); r = 1 + 0.4 * cos(b); printf "%.9f %.9f %.9f\n", r * cos(a), r * sin(a), 0.4 * sin(b) } }' > torus.xyz
same_as_one_process cloud --points torus.xyz --m 2
# RP^2 in R^4 (a Fibonacci sphere through the Veronese map): its frames ask for the winding oracle,
# which one process runs: refused with one error line.
awk 'BEGIN { for (i = 0; i < 2000; i++) { z = 1 - 2 * (i + 0.5) / 2000; r = sqrt(1 - z * z); p = 2.399963 * i;
  x = r * cos(p); y = r * sin(p); printf "%.9f %.9f %.9f %.9f\n", x * y, x * z, y * y - z * z, 2 * y * z } }' > rp2.xyz
status=0
mpi 2 trace --points rp2.xyz --m 2 -q --no-output 2> rp2.err || status=$?
check "the winding oracle under mpirun: refused with one error line" "1 1" \
  "$((status != 0)) $(grep -c '^coxmesh: error: the winding oracle of point clouds is not traced by several processes' rp2.err)"
# Manifolds with corners (several domains) are meshed by rank 0 as one process does, the other
# ranks waiting: the files (a .cxm whole, no pieces) and the summary are one process's.
same_whole_as_one_process() {  # NAME "EXTENSIONS" TRACE-ARGS... (the formats written by rank 0, besides .cxm)
  local name=$1 extensions=$2; shift 2
  "$bin" trace "$@" --threads 1 --json -o "$name.cxm" > "$name.json"
  for ext in $extensions; do "$bin" trace "$@" --threads 1 -q -o "$name.$ext"; done
  for n in 2 3; do
    local status=0
    mpi "$n" trace "$@" --json -o "$name.$n.cxm" > "$name.$n.json" 2> "$name.$n.err" || status=$?
    check "$name, $n processes: exit status, no pieces" "0 0" "$status $(ls "$name.$n"_*.cxm 2> /dev/null | wc -l)"
    check "$name, $n processes: the same file" same "$(cmp -s "$name.cxm" "$name.$n.cxm" && echo same || echo different)"
    "$bin" convert -q "$name.$n.cxm" "$name.$n.merged.cxm"
    check "$name, $n processes: converted, the same file" same \
      "$(cmp -s "$name.cxm" "$name.$n.merged.cxm" && echo same || echo different)"
    check "$name, $n processes: the same summary" "$(stable "$name.json")" "$(stable "$name.$n.json")"
    check "$name, $n processes: said on standard error" 1 "$(grep -c 'meshed by rank 0 alone' "$name.$n.err")"
    for ext in $extensions; do
      status=0
      mpi "$n" trace "$@" -q -o "$name.$n.$ext" || status=$?
      check "$name, $n processes: the same .$ext" "0 same" \
        "$status $(cmp -s "$name.$ext" "$name.$n.$ext" && echo same || echo different)"
    done
  done
}
same_whole_as_one_process sphere-two-domains "vtu ply" --preset sphere --domain=-x --domain=-y
same_whole_as_one_process octant "vtu ply" --preset sphere --domain=-x --domain=-y --cut 0,0,-1,0 --edge-length 0.15
same_whole_as_one_process arc vtu --function "x^2+y^2+z^2-1; z" --domain=-x --domain "y-0.5" --edge-length 0.1
same_whole_as_one_process octant-refined "vtu obj" --preset sphere --domain=-x --domain=-y --cut 0,0,-1,0 --edge-length 0.15 --refine
check "octant: three corners" '  "corners": 3,' "$(grep '"corners"' octant.3.json)"
check "octant, refined: refined" 1 "$(grep -c '"max_abs_f_after"' octant-refined.2.json)"
status=0
mpi 2 trace --preset sphere --domain=-x --domain=-y -q -o corners.pvtu 2> corners.err || status=$?
check "corners to a .pvtu: refused with one error line, no file" "1 1 no" \
  "$((status != 0)) $(grep -c '^coxmesh: error: .*corners is meshed by one process, not in pieces' corners.err) $([ -e corners.pvtu ] && echo yes || echo no)"
# --refine with pieces: each rank refines the vertices of its cells before writing its piece.
# (the torus at 3 processes: the largest |F| before refinement is not on rank 0)
same_as_one_process refined --preset torus --refine
same_as_one_process refined-cut --preset torus --box -2,-2,-0.1,2,2,2 --edge-length 0.3 --refine
check "refined: max |F| after below before" yes "$(python3 -c 'import json, sys; r = json.load(open(sys.argv[1]))["refinement"]
print("yes" if r["max_abs_f_after"] < r["max_abs_f_before"] and r["vertices"] > 0 else "no")' refined-cut.3.json)"
same_cells_as_one_process refined-pieces --preset torus --box -2,-2,-0.1,2,2,2 --edge-length 0.3 --refine
"$bin" trace --preset torus --box -2,-2,-0.1,2,2,2 --edge-length 0.3 --refine --threads 1 --json -o refined-one.vtu > refined-one.json
mpi 2 trace --preset torus --box -2,-2,-0.1,2,2,2 --edge-length 0.3 --refine --json -o refined-two.pvtu > refined-two.json
check "refined .pvtu, 2 processes: the summary's refinement" "$(grep -A4 '"refinement"' refined-one.json)" \
  "$(grep -A4 '"refinement"' refined-two.json)"
finish
