# Triangulation.locate in bulk equals point-by-point location; simplices print as the command line
# prints them; faces and cofaces.
import numpy as np
import pytest

import coxmesh


def test_bulk_locate_equals_point_by_point():
    T = coxmesh.Triangulation.coxeter(4).with_longest_edge(0.37).with_offset([0.1, -0.2, 0.3, 0.05])
    rng = np.random.default_rng(7)
    X = rng.uniform(-3, 3, size=(100_000, 4))
    vertex, blocks, bary = T.locate(X)
    assert vertex.shape == (100_000, 4) and vertex.dtype == np.int32
    assert blocks.shape == (100_000, 5) and bary.shape == (100_000, 5)
    for i in range(0, 100_000, 97):  # the scalar path on a sample of a thousand
        s = T.simplex_at(X[i])
        assert tuple(vertex[i]) == s.vertex
        partition = [[j for j in range(5) if blocks[i, j] == b] for b in range(blocks[i, 4] + 1)]
        assert partition == s.partition
    # The barycentric coordinates rebuild the point from the simplex's vertices.
    for i in range(0, 100_000, 997):
        s = T.simplex_at(X[i])
        np.testing.assert_allclose(bary[i, : s.dimension + 1] @ T.vertices(s), X[i], atol=1e-12)
    assert (bary >= -1e-12).all() and np.allclose(bary.sum(axis=1), 1)


def test_locate_matches_the_command_line(cli):
    T = coxmesh.Triangulation.coxeter(2)
    for p in ([0.3, 0.7], [0.0, 0.0], [-1.25, 2.5], [0.5, 0.28867513459481287]):
        j = cli("locate", "--point", ",".join(repr(x) for x in p), "--json")
        vertex, blocks, bary = T.locate(p)
        assert list(vertex) == j["vertex"]
        s = T.simplex_at(p)
        assert s.partition == j["partition"] and s.dimension == j["dimension"]
        np.testing.assert_allclose(T.vertices(s), j["cartesian"], atol=1e-12)


def test_simplex_text_faces_and_cofaces():
    s = coxmesh.Simplex([0, 0], [[0], [1], [2]])
    assert repr(s) == "(0,0) [{0},{1},{2}]"
    assert coxmesh.Simplex.parse(repr(s)) == s
    assert len(s.faces(1)) == 3 and len(s.faces(0)) == 3
    edge = s.faces(1)[0]
    assert len(coxmesh.Triangulation.coxeter(2).cofaces(edge, 2)) == 2
    assert s in edge.cofaces(2)
    assert s.vertices().tolist() == [[0, 0], [1, 0], [1, 1]] or s.vertices().shape == (3, 2)
    assert len({s, coxmesh.Simplex.parse("(0,0) [{0},{1},{2}]")}) == 1
    with pytest.raises(ValueError):
        coxmesh.Simplex([0, 0], [[0], [2]])
    with pytest.raises(ValueError):
        s.cofaces(5)


def test_triangulation_construction_and_errors():
    T = coxmesh.Triangulation(np.eye(3) * 2, [1, 2, 3])
    np.testing.assert_array_equal(T.matrix, np.eye(3) * 2)
    np.testing.assert_array_equal(T.offset, [1, 2, 3])
    assert T.dimension == 3
    assert abs(coxmesh.Triangulation.coxeter(3).with_longest_edge(0.5).longest_edge() - 0.5) < 1e-12
    with pytest.raises(ValueError):
        coxmesh.Triangulation(np.zeros((3, 3)))
    with pytest.raises(ValueError):
        coxmesh.Triangulation(np.eye(3), [1, 2])
    plane = coxmesh.Triangulation.coxeter(2)
    with pytest.raises(ValueError, match="NaN|finite"):
        plane.locate([[0.1, float("nan")]])
    with pytest.raises(ValueError, match="shape"):
        plane.locate(np.zeros((4, 3)))
