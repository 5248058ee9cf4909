# Mesh.write in every format and coxmesh.read of .cxm files.
import os

import numpy as np
import pytest

import coxmesh


def test_cxm_round_trip(tmp_path, cli):
    mesh = coxmesh.trace(preset="flat-torus", edge_length=0.4, seeds=[[-1, 0, 1, 0]])
    path = str(tmp_path / "flat.cxm")
    written = mesh.write(path)
    assert written["format"] == "cxm"
    back = coxmesh.read(path)
    np.testing.assert_array_equal(back.points, mesh.points)
    for j in range(1, mesh.manifold_dimension + 1):
        for a, b in zip(back.facets(j), mesh.facets(j)):
            np.testing.assert_array_equal(a, b)
        for c in (0, mesh.cells[j] - 1):
            assert back.simplex(j, c) == mesh.simplex(j, c)
    for key in ("cells", "betti", "euler_characteristic", "is_manifold", "function_evaluations", "complete"):
        assert getattr(back, key) == getattr(mesh, key), key
    assert back.source == "preset flat-torus"
    # The command line reads what Python wrote.
    check = cli("check", path, "--json")
    assert check["betti"] == mesh.betti and check["cells"] == mesh.cells


@pytest.mark.parametrize("name,fmt", [("s.vtu", None), ("s.off", None), ("s.ply", None), ("s.obj", None),
                                      ("s.mesh", None), ("s.data", "ply"), ("s.stl", None), ("s.msh", None)])
def test_every_format_is_written(tmp_path, name, fmt):
    mesh = coxmesh.trace(preset="sphere")
    path = tmp_path / name
    counts = mesh.write(str(path), format=fmt)
    assert path.stat().st_size > 0
    assert counts["points"] == mesh.traced_simplices


def test_projection_and_errors(tmp_path):
    mesh = coxmesh.trace(preset="sphere", m=2, dim=4, edge_length=0.3)
    mesh.write(str(tmp_path / "p.ply"), project="pca")
    with pytest.raises(ValueError):
        mesh.write(str(tmp_path / "p.ply"), project="1,2,9")
    with pytest.raises(ValueError):
        mesh.write(str(tmp_path / "p.xyz"))
    with pytest.raises(ValueError):
        coxmesh.read(str(tmp_path / "missing.cxm"))
    (tmp_path / "bad.cxm").write_bytes(b"not a cxm file\n")
    with pytest.raises(ValueError):
        coxmesh.read(str(tmp_path / "bad.cxm"))
    assert not os.path.exists(tmp_path / "p.xyz")


def test_simplices(tmp_path):
    mesh = coxmesh.trace(preset="torus")
    V, T = mesh.triangles()
    off = tmp_path / "t.off"
    counts = mesh.write(str(off), simplices=True)
    assert counts["cells"] == len(T)
    faces = off.read_text().split("\n")[2 + len(V):2 + len(V) + len(T)]
    assert all(f.split()[0] == "3" for f in faces)
    # the same triangles, in the same order and orientation
    np.testing.assert_array_equal(np.array([[int(x) for x in f.split()[1:]] for f in faces]), T)
    with pytest.raises(ValueError):
        mesh.write(str(tmp_path / "t.cxm"), simplices=True)
