"""Bad input raises holey.HoleyError (a ValueError) saying what and where;
nothing panics and no input array is modified."""

import numpy as np
import pytest

import holey
from conftest import box


def test_holey_error_is_a_value_error():
    assert issubclass(holey.HoleyError, ValueError)


def test_nan_names_the_vertex():
    V, F = box([0, 0, 0], [1, 1, 1])
    V[5, 1] = np.nan
    for call in [
        lambda: holey.union(V, F, *box([0.5] * 3, [2] * 3)),
        lambda: holey.self_intersections(V, F),
        lambda: holey.topology_change(V, V, F),
        lambda: holey.info(V, F),
    ]:
        with pytest.raises(holey.HoleyError, match="5"):
            call()


def test_bad_indices_name_the_face():
    V, F = box([0, 0, 0], [1, 1, 1])
    F[3, 2] = 8
    with pytest.raises(holey.HoleyError, match="8"):
        holey.resolve(V, F)
    F[3, 2] = -1
    with pytest.raises(holey.HoleyError, match="negative"):
        holey.resolve(V, F)
    with pytest.raises(holey.HoleyError, match="whole number"):
        holey.info(V, np.full((2, 3), 0.5))
    with pytest.raises(holey.HoleyError, match=r"\(m, 3\)"):
        holey.self_intersections(V, F[:, :2])
    with pytest.raises(holey.HoleyError, match=r"\(n, 3\)"):
        holey.self_intersections(V[:, :2], F)
    with pytest.raises(holey.HoleyError, match="numbers"):
        holey.info([["a", "b", "c"]], [[0, 0, 0]])


def test_empty_input():
    empty_v, empty_f = np.zeros((0, 3)), np.zeros((0, 3), dtype=int)
    with pytest.raises(holey.HoleyError, match="no vertices"):
        holey.union(empty_v, empty_f, *box([0] * 3, [1] * 3))
    with pytest.raises(holey.HoleyError, match="pairs"):
        holey.union()
    with pytest.raises(holey.HoleyError, match="pairs"):
        holey.union(*box([0] * 3, [1] * 3), np.zeros((3, 3)))
    assert holey.self_intersections(empty_v, empty_f)["intersecting_pairs"] == 0
    assert holey.info(empty_v, empty_f)["faces"] == 0


def test_options_are_checked():
    V, F = box([0, 0, 0], [1, 1, 1])
    with pytest.raises(holey.HoleyError, match="scheme"):
        holey.topology_change(V, V, F, scheme="vote")
    with pytest.raises(holey.HoleyError, match="method"):
        holey.union(V, F, V + 0.5, F, method="magic")
    with pytest.raises(holey.HoleyError, match="V1 has 4"):
        holey.topology_change(V, V[:4], F)
    with pytest.raises(holey.HoleyError, match="strokes"):
        holey.sculpt(V, F, [{"brush": "teleport", "radius": 1, "path": [[0, 0, 0]]}])
    with pytest.raises(holey.HoleyError, match="thickness"):
        holey.Mesh.primitive("cube").rind(-1.0)
    with pytest.raises(holey.HoleyError, match="nosuch"):
        holey.Mesh.primitive("nosuch")


def test_inputs_are_not_modified():
    V, F = box([0, 0, 0], [2, 2, 2])
    V0, F0 = V.copy(), F.copy()
    holey.union(V, F, V + 0.5, F)
    holey.topology_change(V, V * 1.5, F)
    assert np.array_equal(V, V0) and np.array_equal(F, F0)


def test_any_array_like_is_accepted():
    V, F = box([0, 0, 0], [1, 1, 1])
    as_lists = holey.info(V.tolist(), F.tolist())
    as_other_types = holey.info(V.astype(np.float32), F.astype(np.uint16))
    as_fortran = holey.info(np.asfortranarray(V), np.asfortranarray(F))
    assert as_lists == as_other_types == as_fortran
    assert as_lists["volume"] == pytest.approx(1.0)
