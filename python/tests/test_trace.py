# coxmesh.trace(): callables, expressions and presets agree; a callable is evaluated once per
# lattice vertex, in batches; errors keep their type; the summary matches the command line's.
import numpy as np
import pytest

import coxmesh


def sphere_numpy(X):
    return X[:, 0] ** 2 + X[:, 1] ** 2 + X[:, 2] ** 2 - 1


SEED = [[0.577, 0.577, 0.578]]  # near S^2, and no lattice vertex


def test_callable_expression_and_preset_agree():
    by_callable = coxmesh.trace(function=sphere_numpy, dim=3, edge_length=0.2, seeds=SEED)
    by_text = coxmesh.trace(function="x^2+y^2+z^2-1", edge_length=0.2, seeds=SEED)
    by_preset = coxmesh.trace(preset="sphere", edge_length=0.2, seeds=SEED)
    for mesh in (by_callable, by_text, by_preset):
        assert mesh.betti == [1, 0, 1]
        assert mesh.euler_characteristic == 2
        assert mesh.is_manifold and mesh.complete
    assert by_callable.cells == by_text.cells == by_preset.cells
    assert by_callable.points.shape == (by_callable.traced_simplices, 3)
    # The same simplices in the same order: the points agree up to rounding in F.
    np.testing.assert_allclose(by_callable.points, by_text.points, rtol=0, atol=1e-12)
    np.testing.assert_allclose(by_callable.points, by_preset.points, rtol=0, atol=1e-12)
    assert by_callable.function_evaluations == by_text.function_evaluations == by_preset.function_evaluations
    for j in (1, 2):
        for a, b in zip(by_callable.facets(j), by_text.facets(j)):
            np.testing.assert_array_equal(a, b)


def test_callable_is_evaluated_once_per_lattice_vertex_in_batches():
    calls = []

    def f(X):
        calls.append(X.copy())
        return sphere_numpy(X)

    mesh = coxmesh.trace(function=f, dim=3, edge_length=0.1, seeds=SEED)
    rows = np.concatenate(calls)
    # Lattice vertices locate as 0-simplices; the other rows are the probe and the seed's projection.
    T = coxmesh.Triangulation.coxeter(3).with_longest_edge(0.1)
    _, blocks, _ = T.locate(rows)
    vertices = rows[blocks[:, 3] == 0]
    assert len(vertices) == mesh.function_evaluations
    assert len(np.unique(vertices, axis=0)) == len(vertices), "a lattice vertex was evaluated twice"
    text = coxmesh.trace(function="x^2+y^2+z^2-1", edge_length=0.1, seeds=SEED)
    assert mesh.function_evaluations == text.function_evaluations
    assert mesh.cells == text.cells
    # Batches: one call per breadth-first level, many vertices each.
    batched = [c for c in calls if len(c) > 1]
    assert sum(len(c) for c in batched) > 0.9 * mesh.function_evaluations
    assert len(calls) < mesh.function_evaluations / 20


def test_callable_with_several_equations_and_a_callable_domain():
    # The flat torus S^1 x S^1 in R^4, cut by <(1,1,0,0), x> < 0.5 given three ways.
    def flat(X):
        return np.stack([X[:, 0] ** 2 + X[:, 1] ** 2 - 1, X[:, 2] ** 2 + X[:, 3] ** 2 - 1], axis=1)

    common = dict(edge_length=0.3, seeds=[[-1, 0, 1, 0]], box=([-2] * 4, [2] * 4))
    by_callable = coxmesh.trace(function=flat, domain=lambda X: X[:, 0] + X[:, 1] - 0.5, **common)
    by_text = coxmesh.trace(function="x^2+y^2-1; z^2+w^2-1", domain="x+y-0.5", **common)
    mixed = coxmesh.trace(function=flat, domain=["x+y-0.5", lambda X: X[:, 3] - 5], **common)
    assert by_callable.boundary_simplices > 0
    # Two domains: a manifold with corners; w < 5 and the box cut nothing, so one boundary stratum.
    assert mixed.cells == by_callable.cells
    assert mixed.boundary_cells == by_callable.boundary_cells
    assert [s["domains"] for s in mixed.summary()["strata"]] == [[], [1]]
    assert mixed.summary()["corners"] == 0
    for mesh in (by_text,):
        assert mesh.cells == by_callable.cells
        assert mesh.boundary_cells == by_callable.boundary_cells
        assert mesh.function_evaluations == by_callable.function_evaluations
        np.testing.assert_allclose(mesh.boundary_points, by_callable.boundary_points, atol=1e-12)
    assert by_callable.euler_characteristic == 0  # a cylinder
    assert by_callable.boundary_cells[0] > 0


class Boom(Exception):
    pass


def test_exception_from_the_callable_propagates_unchanged():
    raised = Boom("from the callable")
    count = [0]

    def f(X):
        count[0] += 1
        if count[0] == 5:
            raise raised
        return sphere_numpy(X)

    with pytest.raises(Boom) as info:
        coxmesh.trace(function=f, dim=3, edge_length=0.05, seeds=SEED)
    assert info.value is raised
    assert count[0] == 5, "the trace went on after the exception"


def test_bad_input_raises_value_error_with_the_library_message():
    with pytest.raises(ValueError, match="unknown preset 'cube'"):
        coxmesh.trace(preset="cube")
    with pytest.raises(coxmesh.InputError):
        coxmesh.trace(function="x^2+y^2+", dim=3)
    with pytest.raises(ValueError, match="give dim"):
        coxmesh.trace(function=sphere_numpy)
    with pytest.raises(ValueError, match="shape"):
        coxmesh.trace(function=lambda X: np.zeros((len(X) + 1,)), dim=3, seeds=SEED)
    with pytest.raises(ValueError, match="values per point"):
        coxmesh.trace(function=lambda X: np.zeros((len(X), 3)), dim=3, seeds=SEED)
    with pytest.raises(ValueError, match="preset parameter"):
        coxmesh.trace(function="x^2+y^2+z^2-1", radius=2)
    with pytest.raises(ValueError, match="coordinates"):
        coxmesh.trace(preset="sphere", seeds=[[1, 0]])
    with pytest.raises(ValueError, match="lo must be below hi"):
        coxmesh.trace(function="x^2+y^2+z^2-1", box=([0, 0, 0], [1, -1, 1]))
    with pytest.raises(ValueError, match="triangulation"):
        coxmesh.trace(preset="sphere", triangulation="cubic")
    with pytest.raises(coxmesh.EvaluationError, match="not finite"):
        coxmesh.trace(function=lambda X: np.where(X[:, 2] > 0.5, np.nan, sphere_numpy(X)), dim=3, seeds=SEED)
    with pytest.raises(coxmesh.SeedError, match="outside the domain"):
        coxmesh.trace(function="x^2+y^2+z^2-1", domain="z", seeds=[[0, 0, 1]])
    with pytest.raises(ValueError, match="scale or edge_length"):
        coxmesh.trace(preset="sphere", scale=1, edge_length=1)
    assert issubclass(coxmesh.SeedError, ValueError) and issubclass(coxmesh.EvaluationError, ValueError)


def test_summary_matches_the_command_line(cli):
    mesh = coxmesh.trace(preset="sphere", m=2, dim=4, threads=2)
    j = cli("trace", "--preset", "sphere", "--m", "2", "--dim", "4", "--json")
    summary = mesh.summary()
    for key in ("ambient_dimension", "manifold_dimension", "traced_simplices", "boundary_simplices", "cells",
                "boundary_cells", "euler_characteristic", "betti", "components", "is_manifold",
                "function_evaluations", "complete", "seeds", "preset"):
        assert summary[key] == j[key], key
        assert getattr(mesh, key, summary[key]) == j[key], key
    assert set(summary["timings"]) == {"trace_seconds", "cell_complex_seconds", "topology_seconds"}


def test_max_simplices_stops_with_a_message():
    mesh = coxmesh.trace(preset="sphere", edge_length=0.05, max_simplices=1000)
    assert not mesh.complete
    assert "limit of 1000" in mesh.message
    # open at its front: no topology rather than a wrong one
    assert not mesh.closed and mesh.betti is None and mesh.components is None
    assert "betti" not in mesh.summary()


def test_box_is_a_domain_and_seeds_trace_whole_components():
    genus2 = "(x*(x-1)^2*(x-2)+y^2)^2+z^2-0.01"  # reaches x = 2.045, past the default box
    assert coxmesh.trace(function=genus2, seeds=[[0, 0.1, 0]]).betti == [1, 4, 1]
    cut = coxmesh.trace(function=genus2)
    assert cut.betti == [1, 4, 0] and cut.is_manifold and cut.boundary_simplices > 0
    assert coxmesh.trace(preset="sphere", box=[-2, -2, 0, 2, 2, 2]).betti == [1, 0, 0]


def test_points_are_a_read_only_view():
    mesh = coxmesh.trace(preset="torus")
    p = mesh.points
    assert not p.flags.writeable and not p.flags.owndata
    assert p.base is not None
    del mesh  # the array keeps the mesh alive
    assert np.isfinite(p).all() and p.shape[1] == 3


def test_triangles_cover_the_surface():
    mesh = coxmesh.trace(preset="sphere")
    V, T = mesh.triangles()
    assert V.shape == (mesh.traced_simplices, 3) and T.shape[1] == 3
    # Every polygon with n sides gives n - 2 triangles; a closed surface: each edge in 2 triangles.
    offsets, _ = mesh.facets(2)
    assert len(T) == int((np.diff(offsets) - 2).sum())
    edges = np.sort(np.concatenate([T[:, [0, 1]], T[:, [1, 2]], T[:, [2, 0]]]), axis=1)
    _, counts = np.unique(edges, axis=0, return_counts=True)
    assert (counts == 2).all()
    # Outward orientation: positive volume 1/6 sum det(a, b, c) close to 4/3 pi.
    a, b, c = V[T[:, 0]], V[T[:, 1]], V[T[:, 2]]
    volume = np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6
    assert 0.9 * 4 / 3 * np.pi < volume < 4 / 3 * np.pi
    circle = coxmesh.trace(preset="sphere", m=1, dim=2)
    with pytest.raises(ValueError, match="surface"):
        circle.triangles()


def test_a_list_of_domains_makes_a_manifold_with_corners():
    # The octant x, y, z > 0 of the unit sphere: a disk with three corners and three boundary arcs.
    mesh = coxmesh.trace(preset="sphere", domain=["-x", "-y", lambda X: -X[:, 2]], seeds=[[0.6, 0.6, 0.6]],
                         edge_length=0.15)
    s = mesh.summary()
    assert s["corners"] == 3
    assert sorted(x["domains"] for x in s["strata"]) == [[], [1], [1, 2], [1, 3], [2], [2, 3], [3]]
    assert s["euler_characteristic"] == 1 and s["betti"] == [1, 0, 0] and s["is_manifold"]
    masks = mesh.domains(0)
    assert len(masks) == len(mesh.points)
    assert sorted(m for m in masks if bin(m).count("1") == 2) == [3, 5, 6]
    assert len(mesh.domains(2)) > 0 and not mesh.domains(2).any()  # 2-cells are all interior
    assert len(coxmesh.trace(preset="sphere", domain=["-x"], edge_length=0.15).domains(0)) == 0


def test_vertex_domains_find_the_boundary_and_the_corners_and_refine_moves_them():
    octant = dict(preset="sphere", domain=["-x", "-y", "-z"], seeds=[[0.6, 0.6, 0.6]], edge_length=0.15)
    plain, refined = coxmesh.trace(**octant), coxmesh.trace(refine=True, **octant)
    masks = refined.vertex_domains
    assert masks.dtype == np.uint64 and len(masks) == len(refined.points) and not masks.flags.writeable
    np.testing.assert_array_equal(masks, refined.domains(0))
    np.testing.assert_array_equal(masks, plain.vertex_domains)
    bits = np.array([bin(int(m)).count("1") for m in masks])
    assert sorted(masks[bits == 2]) == [3, 5, 6]  # the corners
    assert (bits == 1).sum() > 0 and (bits == 0).sum() > 0
    # Each boundary vertex lies on the planes of its bits, inside the others; the corners at e_1, e_2, e_3.
    x = refined.points
    on = (masks[:, None] >> np.arange(3, dtype=np.uint64)) & np.uint64(1) == 1
    assert np.abs(x[on]).max() <= 1e-12 and (x[~on] > 0).all()
    assert np.abs(np.linalg.norm(x, axis=1) - 1).max() <= 1e-12
    np.testing.assert_allclose(x[bits == 2][np.argsort(masks[bits == 2])], [[0, 0, 1], [0, 1, 0], [1, 0, 0]],
                               atol=1e-12)
    r = refined.refinement
    assert r["not_refined"] == 0 and r["vertices"] == len(x) and r["max_abs_f_before"] > 1e-4
    assert np.abs(plain.points[on]).max() > 1e-4 or np.abs(np.linalg.norm(plain.points, axis=1) - 1).max() > 1e-4
    assert refined.summary()["strata"] == plain.summary()["strata"]
    # Without corners: no vertex of `points` is on a boundary; the boundary ones are boundary_points.
    cut = coxmesh.trace(preset="sphere", domain="z", edge_length=0.15)
    assert len(cut.vertex_domains) == len(cut.points) and not cut.vertex_domains.any()
    assert len(cut.boundary_points) > 0


def test_refine_moves_the_vertices_onto_the_manifold(cli):
    plain = coxmesh.trace(preset="torus", edge_length=0.2)
    refined = coxmesh.trace(preset="torus", edge_length=0.2, refine=True)
    assert plain.refinement is None and "refinement" not in plain.summary()
    r = refined.refinement
    assert r["vertices"] == refined.traced_simplices and r["not_refined"] == 0
    assert r["max_abs_f_after"] <= 1e-10 < r["max_abs_f_before"]
    # The torus of radii 1 and 0.4 (the preset's): the distance to the core circle is 0.4.
    def distance_error(mesh):
        P = mesh.points
        return np.abs(np.hypot(np.hypot(P[:, 0], P[:, 1]) - 1, P[:, 2]) - 0.4).max()
    assert distance_error(refined) < 1e-9 < distance_error(plain) / 10
    # Same cells and topology; the same report as the command line's.
    assert refined.cells == plain.cells and refined.betti == plain.betti == [1, 2, 1]
    j = cli("trace", "--preset", "torus", "--edge-length", "0.2", "--refine", "--json")
    assert refined.summary()["refinement"] == j["refinement"]
    assert "refine_seconds" in refined.timings
