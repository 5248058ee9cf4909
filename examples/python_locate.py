"""Locating a million points in the Coxeter triangulation of R^3 in one call.

    PYTHONPATH=build/python python3 examples/python_locate.py
"""
import time

import numpy as np

import coxmesh

T = coxmesh.Triangulation.coxeter(3).with_longest_edge(0.1)
X = np.random.default_rng(1).uniform(-1, 1, size=(1_000_000, 3))
start = time.perf_counter()
vertex, blocks, barycentric = T.locate(X)  # one C++ loop, without the GIL
print(f"{len(X)} points located in {time.perf_counter() - start:.3f} s")

# Row i: the simplex with minimal vertex vertex[i] and blocks blocks[i] (blocks[i, 3] = its dimension).
s = T.simplex_at(X[0])
print("the first point lies in", s, "with barycentric coordinates", barycentric[0])
print("rebuilt from the vertices:", barycentric[0] @ T.vertices(s), "=", X[0])
print("two of the 3-simplices around its first edge:", T.cofaces(s.faces(1)[0], 3)[:2])
print("points by the dimension of their simplex:", np.bincount(blocks[:, 3]))
