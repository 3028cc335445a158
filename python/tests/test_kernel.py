"""holey.Mesh: the DLFL kernel and the thesis's tools, checked against
the thesis's counts and closed forms."""

import numpy as np
import pytest

import holey

CUBE_V = [[i & 1, i >> 1 & 1, i >> 2 & 1] for i in range(8)]
CUBE_F = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]]


def counts(m):
    i = m.info()
    return i["vertices"], i["edges"], i["faces"], i["genus"]


def test_from_polygons_and_to_arrays():
    m = holey.Mesh.from_polygons(CUBE_V, CUBE_F)
    m.validate()
    assert counts(m) == (8, 12, 6, 0)
    V, faces = m.to_arrays()
    assert np.array_equal(V, np.asarray(CUBE_V, float)) and np.array_equal(faces, CUBE_F)
    V, T = m.to_arrays(triangulate=True)
    assert T.shape == (12, 3)
    assert holey.volume(V, T) == pytest.approx(1.0, rel=1e-15)
    with pytest.raises(holey.HoleyError, match="face"):
        holey.Mesh.from_polygons(CUBE_V, CUBE_F + [[0, 2, 3, 1]])


def test_sierpinski_tetrahedron_figure_39():
    m = holey.Mesh.primitive("tetrahedron")
    t = m.sierpinski(2)
    t.validate()
    assert counts(t) == (34, 126, 64, 15)
    assert counts(m) == (4, 6, 4, 0)  # the operator returned a new mesh


def test_true_menger_sponge_closed_form():
    # Level n keeps 20**n of the 27**n subcubes: volume 8 * (20/27)**n for
    # the 2-unit cube; a level-1 sponge is a cube with three crossing
    # tunnels, genus 5; level 2 has genus 81.
    cube = holey.Mesh.primitive("cube")
    for n, genus in [(1, 5), (2, 81)]:
        s = cube.menger(n, exact=True)
        s.validate()
        i = s.info()
        assert i["genus"] == genus and i["closed"]
        assert i["volume"] == pytest.approx(8 * (20 / 27) ** n, rel=1e-12)


def test_menger_level_3_matches_manifolds_sponge(shared):
    # meshes/README.md: Manifold's level-3 sponge is closed, genus 1409,
    # volume 0.406442 for a unit cube.
    theirs = holey.info(*holey.read(shared / "menger_sponge_level3.obj"))
    ours = holey.Mesh.primitive("cube").menger(3, exact=True).info()
    assert theirs["genus"] == ours["genus"] == 1409
    assert ours["volume"] / 8 == pytest.approx(theirs["volume"], rel=1e-5)


def test_catmull_clark_and_doo_sabin_counts():
    cube = holey.Mesh.primitive("cube")
    # One Catmull-Clark level: a vertex per old vertex, edge and face.
    assert counts(cube.subdivide("catmull-clark", 1)) == (26, 48, 24, 0)
    # Doo-Sabin: a vertex per corner, a face per old vertex, edge and face.
    assert counts(cube.subdivide("doo-sabin", 1)) == (24, 48, 26, 0)
    with pytest.raises(holey.HoleyError, match="loop"):
        cube.subdivide("loop", 1)


def test_spot_catmull_clark_reproduces_the_quadrangulated_mesh(shared):
    # meshes/README.md: two textbook Catmull-Clark steps of the control
    # mesh give spot_quadrangulated.obj to within 6.7e-6.
    V, faces = holey.Mesh.read(shared / "spot_control_mesh.obj").subdivide("catmull-clark", 2).to_arrays()
    Q, quads = holey.read(shared / "spot_quadrangulated.obj", triangulate=False)
    assert V.shape == Q.shape and np.shape(faces) == np.shape(quads) == (2928, 4)
    nearest = np.sqrt(((V[:, None, :] - Q[None, :, :]) ** 2).sum(-1)).min(axis=1)
    assert nearest.max() < 1e-5


def test_handle_through_a_cube_makes_genus_one():
    m = holey.Mesh.primitive("cube", 3)
    V, faces = m.to_arrays()
    height = V[faces].mean(axis=1)[:, 2]
    top, bottom = int(np.argmax(height)), int(np.argmin(height))
    tunnel = m.handle((top, bottom), segments=6, w1=-1.0, w2=-1.0)
    tunnel.validate()
    assert tunnel.info()["genus"] == 1 and tunnel.info()["components"] == 1
    # Between two d-gons a handle of s segments adds d(s-1) vertices,
    # d(2s-1) edges and ds-2 faces.
    (v, e, f, _), d, s = counts(m), 4, 6
    assert counts(tunnel)[:3] == (v + d * (s - 1), e + d * (2 * s - 1), f + d * s - 2)
    with pytest.raises(holey.HoleyError, match="face 9999"):
        m.handle((9999, 0))
    # TopMod's Bézier curve: the same counts along another curve.
    arch = m.handle((top, bottom), segments=6, w1=-1.0, w2=-1.0, curve="bezier")
    arch.validate()
    assert counts(arch)[:3] == counts(tunnel)[:3] and arch.info()["genus"] == 1
    assert not np.array_equal(arch.to_arrays()[0], tunnel.to_arrays()[0])
    with pytest.raises(holey.HoleyError, match="spline"):
        m.handle((top, bottom), curve="spline")


def test_rind_punches_join_the_shells_then_grow_handles():
    sphere = holey.Mesh.primitive("sphere", 1)
    crust = sphere.rind(0.1)
    assert crust.info()["components"] == 2
    one = sphere.rind(0.1, punch=[0])
    assert (one.info()["components"], one.info()["genus"]) == (1, 0)
    # k holes in a genus-0 crust give genus k - 1.
    three = sphere.rind(0.1, punch=[0, 7, 30])
    three.validate()
    assert three.info()["genus"] == 2
    with pytest.warns(UserWarning, match="not punched"):
        sphere.rind(0.1, punch=[0, 0])
