# coxmesh.trace(points=...): samples of a manifold (thesis Ch. 4) from an array or a file, meshed by
# the library's one call: the topology of sampled manifolds, the oracle chosen for RP² in R⁴, the
# same summary as `coxmesh trace --points FILE --json`, and bad input as InputError.
import json
import subprocess

import numpy as np
import pytest

import coxmesh


def on_sphere(rng, n, dim=3):
    x = rng.normal(size=(n, dim))
    return x / np.linalg.norm(x, axis=1, keepdims=True)


def sphere(n=2000, seed=7):
    return on_sphere(np.random.default_rng(seed), n)


def torus(n=3000, seed=7, R=1.0, r=0.4):
    rng = np.random.default_rng(seed)
    a, b = rng.uniform(0, 2 * np.pi, (2, 3 * n))
    keep = rng.uniform(0, 1 + r / R, 3 * n) < 1 + (r / R) * np.cos(b)  # area-uniform: rejection
    a, b = a[keep][:n], b[keep][:n]
    return np.column_stack([(R + r * np.cos(b)) * np.cos(a), (R + r * np.cos(b)) * np.sin(a), r * np.sin(b)])


def rp2(n=3000, seed=7):
    """The Veronese-type projective plane in R^4: (x, y, z) on S^2 -> (xy, xz, y^2 - z^2, 2yz)."""
    x, y, z = on_sphere(np.random.default_rng(seed), n).T
    return np.column_stack([x * y, x * z, y * y - z * z, 2 * y * z])


def write_rows(path, X):
    np.savetxt(path, X, fmt="%.17g")  # (round-trips every double exactly)
    return str(path)


@pytest.mark.parametrize("samples, betti", [(sphere, [1, 0, 1]), (torus, [1, 2, 1])])
def test_sampled_surfaces_have_their_topology(samples, betti):
    mesh = coxmesh.trace(points=samples(), m=2)
    assert mesh.betti == betti and mesh.is_manifold and mesh.complete
    pc = mesh.summary()["point_cloud"]
    assert pc["oracle"] == "vertex" and pc["frames_consistent"] and pc["file"] is None and pc["format"] == "array"
    assert mesh.source == "points (array)"


def test_rp2_gets_the_winding_oracle():
    mesh = coxmesh.trace(points=rp2(), m=2)
    pc = mesh.summary()["point_cloud"]
    assert pc["oracle"] == "winding" and pc["oracle_reason"].startswith("chosen because")
    assert not pc["frames_consistent"] and "warning" not in pc
    assert mesh.betti == [1, 1, 1] and mesh.euler_characteristic == 1 and mesh.is_manifold
    # Asked for the per-vertex function instead, the frames' warning comes with it.
    vertex = coxmesh.trace(points=rp2(), m=2, oracle="vertex").summary()["point_cloud"]
    assert vertex["oracle"] == "vertex" and "cannot be made consistent" in vertex["warning"]


@pytest.mark.parametrize("samples, options", [(sphere, []), (rp2, ["--m", "2"]),
                                              (torus, ["--oracle", "local-pca", "--tube", "4"])])
def test_summary_matches_the_command_line(cli, tmp_path, samples, options):
    X = samples()
    path = write_rows(tmp_path / "samples.txt", X)
    j = cli("trace", "--points", path, *options, "--json")
    kwargs = {name[2:].replace("-", "_"): value for name, value in zip(options[::2], options[1::2])}
    kwargs = {k: (int(v) if k == "m" else float(v) if k == "tube" else v) for k, v in kwargs.items()}
    by_file = coxmesh.trace(points=path, **kwargs).summary()
    by_array = coxmesh.trace(points=X, **kwargs).summary()
    for key in ("cells", "betti", "traced_simplices", "is_manifold", "function_evaluations", "seeds",
                "automatic_seeds", "complete"):
        assert by_file.get(key) == j.get(key) == by_array.get(key), key  # (no betti when not closed)
    cli_pc = {k: v for k, v in j["point_cloud"].items() if k != "setup_seconds"}
    file_pc = {k: v for k, v in by_file["point_cloud"].items() if k != "setup_seconds"}
    array_pc = {k: v for k, v in by_array["point_cloud"].items() if k != "setup_seconds"}
    assert file_pc == cli_pc
    assert array_pc == dict(cli_pc, file=None, format="array")


def test_cxm_file_is_the_command_lines(cli, tmp_path):
    X = sphere(800)
    path = write_rows(tmp_path / "s.txt", X)
    subprocess.run([cli.path, "trace", "--points", path, "-o", str(tmp_path / "cli.cxm"), "--quiet"], check=True)
    coxmesh.trace(points=path).write(str(tmp_path / "py.cxm"))
    assert (tmp_path / "cli.cxm").read_bytes() == (tmp_path / "py.cxm").read_bytes()


def test_duplicates_normals_and_options():
    X = sphere(1500)
    mesh = coxmesh.trace(points=np.vstack([X, X[:5]]), normals=np.vstack([X, X[:5]]),
                         pc_function="nearest", tube=4, edge_length=0.15, threads=2)
    pc = mesh.summary()["point_cloud"]
    assert (pc["samples_read"], pc["duplicates_removed"], pc["samples"]) == (1505, 5, 1500)
    assert pc["function"] == "nearest" and pc["edge_length"] == 0.15
    assert mesh.betti == [1, 0, 1]


def test_bad_input_raises_input_error_with_the_library_message(tmp_path):
    X = sphere(200)
    bad = X.copy()
    bad[3, 1] = np.nan
    with pytest.raises(coxmesh.InputError, match="NaN"):
        coxmesh.trace(points=bad)
    with pytest.raises(coxmesh.InputError, match=r"\(n, d\) array"):
        coxmesh.trace(points=[[0, 0, 0], [1, 1]])
    with pytest.raises(coxmesh.InputError, match="too few for a 2-manifold"):
        coxmesh.trace(points=X[:3], m=2)
    with pytest.raises(coxmesh.InputError, match="between 1 and d − 1 = 2"):
        coxmesh.trace(points=X, m=3)
    with pytest.raises(coxmesh.InputError, match="codimension 2"):
        coxmesh.trace(points=X, oracle="winding")
    with pytest.raises(coxmesh.InputError, match="oracle must be auto"):
        coxmesh.trace(points=X, oracle="nearest")
    with pytest.raises(coxmesh.InputError, match="no normals"):
        coxmesh.trace(points=X, use_normals=True)
    with pytest.raises(coxmesh.InputError, match="does not apply to points"):
        coxmesh.trace(points=X, box=[-1, -1, -1, 1, 1, 1])
    with pytest.raises(coxmesh.InputError, match="one of them"):
        coxmesh.trace(points=X, preset="sphere")
    with pytest.raises(coxmesh.InputError, match="expected R\\^4"):
        coxmesh.trace(points=X, dim=4)
    with pytest.raises(coxmesh.InputError, match="unknown point file extension"):
        coxmesh.trace(points=str(tmp_path / "samples.las"))
    with pytest.raises(coxmesh.InputError, match="cannot open"):
        coxmesh.trace(points=str(tmp_path / "missing.xyz"))
