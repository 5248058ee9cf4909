"""The unit sphere in R^3 from a numpy function, meshed, checked and written.

    PYTHONPATH=build/python python3 examples/python_sphere.py
"""
import numpy as np

import coxmesh

# F(X) for many points at once: X is an (n, 3) array, the result (n,) values.
mesh = coxmesh.trace(function=lambda X: (X ** 2).sum(axis=1) - 1, dim=3, seeds=[[1, 0, 0]], edge_length=0.1)
print(mesh)
print("Euler characteristic", mesh.euler_characteristic, "Betti numbers", mesh.betti)
print(mesh.function_evaluations, "evaluations of F, one per lattice vertex met")

# The intersection points lie on the sphere up to the linear interpolation inside each edge.
radii = np.linalg.norm(mesh.points, axis=1)
print(f"|x| between {radii.min():.4f} and {radii.max():.4f}")

mesh.write("sphere.vtu")  # open it in ParaView; .off .ply .obj .mesh .cxm work too
V, T = mesh.triangles()  # for matplotlib: ax.plot_trisurf(V[:, 0], V[:, 1], V[:, 2], triangles=T)
print(len(T), "triangles written to sphere.vtu as", mesh.cells[2], "polygons")
