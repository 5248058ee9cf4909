# coxmesh.quality() returns the rows of `coxmesh quality --json`.
import pytest

import coxmesh


def test_rows_equal_the_command_line(cli):
    rows = coxmesh.quality(types=["A", "B"], dim=(3, 4))
    j = cli("quality", "--type", "A,B", "--dim", "3..4", "--json")
    assert [(r["type"], r["dimension"]) for r in rows] == [(r["type"], r["dimension"]) for r in j]
    for mine, theirs in zip(rows, j):
        assert set(mine) == set(theirs)
        for key, value in theirs.items():
            if isinstance(value, float):
                assert mine[key] == pytest.approx(value, rel=1e-14, abs=1e-15), key
            else:
                assert mine[key] == value, key


def test_known_values_and_errors():
    (row,) = coxmesh.quality(types="A", dim=3)
    assert row["thickness"] == pytest.approx(2 ** -0.5)
    assert row["delaunay"] == "yes"
    assert {r["type"] for r in coxmesh.quality(max_dim=4)} == {"A", "B", "C", "D", "F", "G"}
    with pytest.raises(ValueError):
        coxmesh.quality(types="Q")
    with pytest.raises(ValueError):
        coxmesh.quality(types="E", dim=3)
