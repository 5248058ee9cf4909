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
    assert not pc["frames_consistent"] and "warnings" not in pc
    assert mesh.betti == [1, 1, 1] and mesh.euler_characteristic == 1 and mesh.is_manifold
    # Asked for the per-vertex function instead, the frames' warning comes with it.
    vertex_mesh = coxmesh.trace(points=rp2(), m=2, oracle="vertex")
    vertex = vertex_mesh.summary()["point_cloud"]
    assert vertex["oracle"] == "vertex" and any("cannot be made consistent" in w for w in vertex["warnings"])
    assert vertex_mesh.warnings[: len(vertex["warnings"])] == vertex["warnings"]
    # A bound besides the tube needs the per-vertex function: auto keeps to it, winding refuses it.
    boxed = coxmesh.trace(points=rp2(), m=2, box=[-1] * 4 + [1] * 4).summary()["point_cloud"]
    assert boxed["oracle"] == "vertex" and not boxed["frames_consistent"]
    with pytest.raises(coxmesh.InputError, match="oracle winding takes no domain or box"):
        coxmesh.trace(points=rp2(), m=2, oracle="winding", domain="x")


def test_a_curve_given_as_a_surface_is_flagged():
    t = np.random.default_rng(3).uniform(0, 2 * np.pi, 2000)
    trefoil = np.stack([np.sin(t) + 2 * np.sin(2 * t), np.cos(t) - 2 * np.cos(2 * t), -np.sin(3 * t)], axis=1)
    mesh = coxmesh.trace(points=trefoil)  # m = d - 1 = 2 by default
    pc = mesh.summary()["point_cloud"]
    assert pc["apparent_dimension"] == 1
    assert any("look 1-dimensional, not 2-dimensional" in w for w in mesh.warnings)
    curve = coxmesh.trace(points=trefoil, m=1)
    assert curve.warnings == [] and curve.betti == [1, 1]


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
    with pytest.raises(coxmesh.InputError, match="radius is a preset parameter; it does not apply to points"):
        coxmesh.trace(points=X, radius=2)
    with pytest.raises(coxmesh.InputError, match="auto_seed does not apply to points"):
        coxmesh.trace(points=X, auto_seed=True)
    with pytest.raises(coxmesh.InputError, match="oracle local-pca takes no domain or box"):
        coxmesh.trace(points=X, oracle="local-pca", domain="z")
    with pytest.raises(coxmesh.InputError, match="oracle local-pca takes no domain or box"):
        coxmesh.trace(points=X, oracle="local-pca", box=[-2, -2, 0, 2, 2, 2])
    with pytest.raises(coxmesh.InputError, match="refine needs the function F; oracle local-pca has none"):
        coxmesh.trace(points=X, oracle="local-pca", refine=True)
    with pytest.raises(coxmesh.InputError, match="takes no domain, box, seeds"):
        coxmesh.trace(points=X, oracle="local-pca", seeds=[[0, 0, 1]])
    with pytest.raises(coxmesh.InputError, match="box needs 2d = 6 numbers"):
        coxmesh.trace(points=X, box=[-1, 1])
    with pytest.raises(coxmesh.InputError, match="coordinates"):
        coxmesh.trace(points=X, seeds=[[0, 1]])
    with pytest.raises(coxmesh.InputError):
        coxmesh.trace(points=X, domain="z+")
    with pytest.raises(coxmesh.InputError, match="one of them"):
        coxmesh.trace(points=X, preset="sphere")
    with pytest.raises(coxmesh.InputError, match="expected R\\^4"):
        coxmesh.trace(points=X, dim=4)
    with pytest.raises(coxmesh.InputError, match="unknown point file extension"):
        coxmesh.trace(points=str(tmp_path / "samples.las"))
    with pytest.raises(coxmesh.InputError, match="cannot open"):
        coxmesh.trace(points=str(tmp_path / "missing.xyz"))


# domain, box, seeds and refine with samples mean what they mean for `coxmesh trace --points`: the
# tube still bounds the walk, each domain is a further face (two: corners), a box bounds it too,
# seeds join the samples, refine moves the vertices onto the blended F = 0.
BOUNDED = [
    (dict(domain="z - 0.3"), ["--domain", "z - 0.3"]),
    (dict(domain=["z - 0.3", "x"]), ["--domain", "z - 0.3", "--domain", "x"]),
    (dict(box=[-2, -2, -0.5, 2, 2, 2]), ["--box", "-2,-2,-0.5,2,2,2"]),
    (dict(seeds=[[0, 0, 1.02], [0.6, 0, -0.8]]), ["--seed", "0,0,1.02", "--seed", "0.6,0,-0.8"]),
    (dict(refine=True), ["--refine"]),
]


@pytest.mark.parametrize("kwargs, options", BOUNDED, ids=["domain", "corners", "box", "seeds", "refine"])
def test_bounds_mean_what_they_mean_on_the_command_line(cli, tmp_path, kwargs, options):
    X = sphere()
    j = cli("trace", "--points", write_rows(tmp_path / "samples.txt", X), *options, "--json")
    mesh = coxmesh.trace(points=X, **kwargs)
    s = mesh.summary()
    for key in ("cells", "boundary_cells", "betti", "euler_characteristic", "corners", "strata", "traced_simplices",
                "is_manifold", "function_evaluations", "seeds", "automatic_seeds", "complete", "refinement"):
        assert s.get(key) == j.get(key), key
    assert s["point_cloud"]["oracle"] == j["point_cloud"]["oracle"] == "vertex"
    if "domain" in kwargs or "box" in kwargs:  # a disc: the cap z < 0.3 (or z > -0.5), or its half x < 0
        assert s["betti"] == [1, 0, 0] and s["boundary_cells"][0] > 0 and s["is_manifold"]
        assert s["corners"] == (2 if isinstance(kwargs.get("domain"), list) else 0)
        if s["corners"]:  # (the tube is domain 1)
            assert sorted(x["domains"] for x in s["strata"]) == [[], [2], [2, 3], [3]]
        assert mesh.points[:, 2].max() < 0.3 + 0.1 if "domain" in kwargs else mesh.points[:, 2].min() > -0.5 - 0.1
    else:
        assert s["betti"] == [1, 0, 1] and s["boundary_cells"] == [0, 0]
    if "domain" in kwargs:
        texts = kwargs["domain"] if isinstance(kwargs["domain"], list) else [kwargs["domain"]]
        assert mesh.source == "points (array)" + "".join("; domain " + t for t in texts)
    if "seeds" in kwargs:
        assert s["seeds"] == s["automatic_seeds"] + 2
    if "refine" in kwargs:
        r = mesh.refinement
        assert set(r) == {"max_abs_f_before", "max_abs_f_after", "vertices", "not_refined"}
        assert r["max_abs_f_after"] < r["max_abs_f_before"] / 100 and r["vertices"] == s["cells"][0]
        assert "refine_seconds" in mesh.timings and mesh.cells == coxmesh.trace(points=X).cells
    else:
        assert mesh.refinement is None


def test_a_callable_domain_is_an_expression_domain():
    X = sphere()
    by_text = coxmesh.trace(points=X, domain=["z - 0.3", "x"])
    by_callable = coxmesh.trace(points=X, domain=[lambda P: P[:, 2] - 0.3, "x"], threads=2)
    assert by_callable.cells == by_text.cells and by_callable.summary()["strata"] == by_text.summary()["strata"]
    assert by_callable.source == "points (array); domain (python function); domain x"
