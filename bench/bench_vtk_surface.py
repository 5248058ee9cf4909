"""Surfaces in R^3 as graphics users make them: VTK samples the implicit unit sphere on an n^3 grid
and contours it with Flying Edges, then writes a binary PLY; coxmesh traces the same sphere with
`coxmesh trace --preset sphere --edge-length H -o s.ply`. Whole time of each (VTK: sampling,
contouring, writing; coxmesh: the command, topology included) and polygons per second, at about
equal polygon counts; fastest of the runs. Needs Debian's python3-vtk9.

    python3 bench/bench_vtk_surface.py path/to/coxmesh [runs=3] [threads=1]
"""
import json
import os
import subprocess
import sys
import tempfile
import time

import vtk

# (grid points per side for VTK, edge length for coxmesh): about 0.22, 0.87 and 1.95 M polygons each.
SIZES = [(170, 0.024), (340, 0.012), (510, 0.008)]


def vtk_sphere(n, path, threads):
    vtk.vtkSMPTools.SetBackend("STDThread")
    vtk.vtkSMPTools.Initialize(threads)
    start = time.perf_counter()
    sphere = vtk.vtkSphere()
    sphere.SetRadius(1.0)
    sample = vtk.vtkSampleFunction()
    sample.SetImplicitFunction(sphere)
    sample.SetModelBounds(-1.1, 1.1, -1.1, 1.1, -1.1, 1.1)
    sample.SetSampleDimensions(n, n, n)
    sample.ComputeNormalsOff()
    contour = vtk.vtkFlyingEdges3D()
    contour.SetInputConnection(sample.GetOutputPort())
    contour.SetValue(0, 0.0)  # (vtkSphere is |x - c|^2 - r^2: the sphere is its zero level)
    contour.ComputeNormalsOff()
    contour.ComputeGradientsOff()
    writer = vtk.vtkPLYWriter()
    writer.SetInputConnection(contour.GetOutputPort())
    writer.SetFileName(path)
    writer.SetFileTypeToBinary()
    writer.Write()
    elapsed = time.perf_counter() - start
    return contour.GetOutput().GetNumberOfCells(), elapsed


def coxmesh_sphere(binary, h, path, threads):
    start = time.perf_counter()
    out = subprocess.run([binary, "trace", "--preset", "sphere", "--edge-length", str(h), "--threads", str(threads),
                          "-o", path, "--json"], check=True, capture_output=True, text=True).stdout
    elapsed = time.perf_counter() - start
    return json.loads(out)["cells"][2], elapsed


def main():
    binary = sys.argv[1]
    runs = int(sys.argv[2]) if len(sys.argv) > 2 else 3
    threads = int(sys.argv[3]) if len(sys.argv) > 3 else 1
    print(f"| VTK grid | VTK triangles | VTK s | VTK M polygons/s | coxmesh edge | coxmesh polygons | coxmesh s "
          f"| coxmesh M polygons/s |")
    print("|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for n, h in SIZES:
            v = min((vtk_sphere(n, os.path.join(tmp, "v.ply"), threads) for _ in range(runs)), key=lambda r: r[1])
            c = min((coxmesh_sphere(binary, h, os.path.join(tmp, "c.ply"), threads) for _ in range(runs)),
                    key=lambda r: r[1])
            print(f"| {n}^3 | {v[0]:,} | {v[1]:.2f} | {v[0] / v[1] / 1e6:.2f} | {h} | {c[0]:,} | {c[1]:.2f} "
                  f"| {c[0] / c[1] / 1e6:.2f} |")


if __name__ == "__main__":
    main()
