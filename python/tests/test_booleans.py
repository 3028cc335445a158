"""Booleans of solids: closed forms for boxes, manifold3d's recorded
figures for spheres, libigl's for the shared self-intersecting pair."""

import numpy as np
import pytest

import holey
from conftest import box

# manifold3d 3.x (Mesh64, float64) on holey.primitive("sphere", 3) and its
# copy moved by (0.7, 0.2, 0.1), measured once and recorded here.
MANIFOLD_SPHERES = {
    "union": 6.344190045550977,
    "intersection": 1.961291588635138,
    "difference": 2.1914492284579192,
}


def closed_genus0(V, F):
    i = holey.info(V, F)
    return i["closed"] and i["manifold"] and i["genus"] == 0 and i["components"] == 1


@pytest.mark.parametrize(
    "op, expected",
    [
        (holey.union, 2 * 8.0 - 1.5**3),
        (holey.intersection, 1.5**3),
        (holey.difference, 8.0 - 1.5**3),
    ],
)
def test_boxes_closed_form(op, expected):
    a = box([0, 0, 0], [2, 2, 2])
    b = box([0.5, 0.5, 0.5], [2.5, 2.5, 2.5])
    V, F = op(*a, *b)
    assert F.dtype == np.int64 and V.dtype == np.float64
    assert holey.volume(V, F) == pytest.approx(expected, rel=1e-12)
    assert closed_genus0(V, F)


@pytest.mark.parametrize("name", sorted(MANIFOLD_SPHERES))
def test_spheres_match_manifold3d(name):
    V, F = holey.primitive("sphere", 3)
    op = getattr(holey, name)
    W, G, report = op(V, F, V + [0.7, 0.2, 0.1], F, report=True)
    assert report["method"] == "containment"
    assert holey.volume(W, G) == pytest.approx(MANIFOLD_SPHERES[name], rel=1e-12)
    assert closed_genus0(W, G)


def test_one_mesh_union_removes_its_overlap():
    # Two overlapping boxes in one mesh: a solid that crosses itself.
    # Its union is the region of winding number >= 1/2: one closed box pair.
    a, b = box([0, 0, 0], [2, 2, 2]), box([1, 1, 1], [3, 3, 3])
    V = np.vstack([a[0], b[0]])
    F = np.vstack([a[1], b[1] + 8])
    assert holey.self_intersections(V, F)["intersecting_pairs"] > 0
    W, G, report = holey.union(V, F, report=True)
    assert report["method"] == "winding"
    assert holey.volume(W, G) == pytest.approx(16.0 - 1.0, rel=1e-12)
    assert closed_genus0(W, G)
    assert holey.self_intersections(W, G)["intersecting_pairs"] == 0


def test_nested_shell_is_a_cavity_only_when_it_faces_inward():
    # Winding numbers add within one mesh: an inward shell inside an
    # outward one has w = 1 - 1 = 0 there, a cavity. As an input of its
    # own an inward shell encloses nothing (w = -1 < 1/2).
    outer = box([0, 0, 0], [4, 4, 4])
    inner = box([1, 1, 1], [2, 2, 2])
    V = np.vstack([outer[0], inner[0]])
    F = np.vstack([outer[1], inner[1][:, ::-1] + 8])
    W, G = holey.union(V, F)
    assert holey.volume(W, G) == pytest.approx(64.0 - 1.0, rel=1e-12)
    assert holey.info(W, G)["components"] == 2
    W, G = holey.union(*outer, inner[0], inner[1][:, ::-1])
    assert holey.volume(W, G) == pytest.approx(64.0, rel=1e-12)
    # An outward inner shell only doubles what is inside: the union drops it.
    W, G = holey.union(*outer, *inner)
    assert holey.volume(W, G) == pytest.approx(64.0, rel=1e-12)
    assert holey.info(W, G)["components"] == 1


def test_three_inputs():
    boxes = [box([i, 0, 0], [i + 1.5, 1, 1]) for i in range(3)]
    arrays = [a for b in boxes for a in b]
    V, F = holey.union(*arrays)
    assert holey.volume(V, F) == pytest.approx(3.5, rel=1e-12)
    V, F = holey.intersection(*arrays)
    assert len(F) == 0  # the first and the third do not meet


def test_threads_give_the_same_result():
    V, F = holey.primitive("sphere", 3)
    one = holey.union(V, F, V + 0.3, F, threads=1)
    two = holey.union(V, F, V + 0.3, F, threads=2)
    assert np.array_equal(one[0], two[0]) and np.array_equal(one[1], two[1])


def test_self_intersecting_pair_matches_libigl(shared):
    # libigl 2.5's exact mesh_boolean (CGAL) on the shared pair: 0.2767855
    # with genus 2 (meshes/README.md; manifold3d gives genus 1, 0.28723).
    A = holey.read(shared / "self_intersectA.obj")
    B = holey.read(shared / "self_intersectB.obj")
    V, F, report = holey.union(*A, *B, report=True)
    assert report["method"] == "winding"
    assert holey.volume(V, F) == pytest.approx(0.2767855, rel=1e-6)
    info = holey.info(V, F)
    assert info["closed"] and info["manifold"] and info["genus"] == 2
    assert holey.self_intersections(V, F)["intersecting_pairs"] == 0


def test_bunny_oded_union_matches_the_peers(shared):
    # meshes/README.md: every exact peer gives V=5763, F=11522, closed,
    # manifold, genus 0, volume 1.23335 for this shift of 0.4 x-extents.
    V, F = holey.read(shared / "bunny_oded.obj")
    shift = 0.4 * (V[:, 0].max() - V[:, 0].min())
    assert shift == pytest.approx(0.620760, abs=1e-6)
    W, G = holey.union(V, F, V + [shift, 0, 0], F)
    info = holey.info(W, G)
    assert (len(W), len(G)) == (5763, 11522)
    assert info["closed"] and info["manifold"] and info["genus"] == 0
    assert holey.volume(W, G) == pytest.approx(1.23335, abs=5e-6)


def test_self_intersect_a_alone_is_the_peers_outer_shell(shared):
    # meshes/README.md: libigl, trueform's outer_shell and pymeshlab all
    # give V=8474, F=16948, closed manifold, genus 1, volume 0.14266215546792.
    V, F = holey.union(*holey.read(shared / "self_intersectA.obj"))
    info = holey.info(V, F)
    assert (len(V), len(F)) == (8474, 16948)
    assert info["closed"] and info["manifold"] and info["genus"] == 1
    assert holey.volume(V, F) == pytest.approx(0.14266215546792, rel=1e-9)
