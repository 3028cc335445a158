"""Reading and writing every format: exact round trips where the format
stores float64 or shortest decimals, float32 where binary STL does."""

import numpy as np
import pytest

import holey

FORMATS = ["obj", "off", "ply", "stl", "dlfl"]


def awkward_mesh():
    # Coordinates no short decimal holds exactly, and an octahedron so that
    # .dlfl (a 2-manifold) can store it too.
    V = np.array(
        [[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]], dtype=float
    ) * (1 / 3) + [0.1, 1e-300, 12345.678901234567]
    F = np.array(
        [[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]]
    )
    return V, F


@pytest.mark.parametrize("ext", ["obj", "off", "ply", "dlfl"])
@pytest.mark.parametrize("ascii", [False, True])
def test_round_trip_is_exact(tmp_path, ext, ascii):
    V, F = awkward_mesh()
    path = tmp_path / f"m.{ext}"
    holey.write(path, V, F, ascii=ascii)
    W, G = holey.read(path)
    assert np.array_equal(W, V) and np.array_equal(G, F)


def first_use_order(V, F):
    """STL stores triangles of positions: reading numbers the vertices in
    order of first appearance. The mesh renumbered so."""
    flat = F.reshape(-1)
    _, first = np.unique(flat, return_index=True)
    order = flat[np.sort(first)]
    rank = np.empty(len(V), dtype=np.int64)
    rank[order] = np.arange(len(order))
    return V[order], rank[F]


def test_ascii_stl_is_exact_and_binary_stl_is_float32(tmp_path):
    V, F = first_use_order(*awkward_mesh())
    holey.write(tmp_path / "a.stl", V, F, ascii=True)
    W, G = holey.read(tmp_path / "a.stl")
    assert np.array_equal(W, V) and np.array_equal(G, F)
    holey.write(tmp_path / "b.stl", V, F)
    W, G = holey.read(tmp_path / "b.stl")
    assert np.array_equal(W, V.astype(np.float32).astype(np.float64)) and np.array_equal(G, F)


def test_polygons_and_unused_vertices_survive(tmp_path):
    V = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0.5, 0.5, 1], [9, 9, 9]], dtype=float)
    faces = [[0, 3, 2, 1], [0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]]
    for ext in ["obj", "off", "ply"]:
        path = tmp_path / f"p.{ext}"
        holey.write(path, V, faces)
        W, G = holey.read(path, triangulate=False)
        assert np.array_equal(W, V)
        assert [list(g) for g in G] == faces
        W, T = holey.read(path)
        assert T.shape == (6, 3) and np.array_equal(T[:2], [[0, 3, 2], [0, 2, 1]])


def test_a_failed_write_leaves_nothing(tmp_path):
    V, F = awkward_mesh()
    path = tmp_path / "bad.obj"
    with pytest.raises(holey.HoleyError):
        holey.write(path, V, F + 100)
    assert not path.exists()
    with pytest.raises(holey.HoleyError, match="format|extension"):
        holey.write(tmp_path / "m.xyz", V, F)
    assert list(tmp_path.iterdir()) == []


def test_malformed_files_say_where(tmp_path):
    path = tmp_path / "broken.obj"
    path.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n")
    with pytest.raises(holey.HoleyError, match="broken.obj"):
        holey.read(path)
    path.write_text("v 0 0 zero\n")
    with pytest.raises(holey.HoleyError, match="broken.obj:1"):
        holey.read(path)
    with pytest.raises(FileNotFoundError):
        holey.read(tmp_path / "absent.obj")


def test_mesh_files_keep_the_dlfl(tmp_path):
    m = holey.Mesh.primitive("torus")
    m.write(tmp_path / "t.dlfl")
    back = holey.Mesh.read(tmp_path / "t.dlfl")
    assert back.info() == m.info()
    V, faces = back.to_arrays()
    W, G = m.to_arrays()
    assert np.array_equal(V, W) and np.array_equal(faces, G)
