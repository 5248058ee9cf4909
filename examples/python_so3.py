"""The rotation group SO(3) as a 3-manifold in R^9 (matrices M with M^T M = I), from a numpy
function of 6 equations; Z/2 homology of RP^3: Betti numbers 1 1 1 1.

    PYTHONPATH=build/python python3 examples/python_so3.py
"""
import numpy as np

import coxmesh


def orthonormal_columns(X):
    """<c_i, c_j> - delta_ij for i <= j, for each row of X (a 3x3 matrix, row-major)."""
    M = X.reshape(-1, 3, 3)
    gram = np.einsum("nki,nkj->nij", M, M) - np.eye(3)
    i, j = np.triu_indices(3)
    return gram[:, i, j]  # (n, 6)


mesh = coxmesh.trace(function=orthonormal_columns, dim=9, seeds=[np.eye(3).ravel()], edge_length=1.5,
                     box=([-1.5] * 9, [1.5] * 9))
print(mesh)
print("Betti numbers (Z/2)", mesh.betti, "- expected 1 1 1 1 for RP^3")
print("F evaluated", mesh.function_evaluations, "times, in", mesh.timings["trace_seconds"], "s of tracing")
# The same manifold built in: identical cells.
builtin = coxmesh.trace(preset="so3", edge_length=1.5, box=([-1.5] * 9, [1.5] * 9))
print("the built-in preset gives the same cells:", builtin.cells == mesh.cells)
