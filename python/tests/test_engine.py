"""Topology change, self-intersections, their resolution, measurements
and sculpting, checked against figures computed here."""

import threading

import numpy as np
import pytest

import holey
from conftest import box


def area(V, F):
    a, b, c = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    return 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1).sum()


def on_box_surface(p, lo, hi, tol=1e-9):
    inside = np.all(p >= np.asarray(lo) - tol) and np.all(p <= np.asarray(hi) + tol)
    on_face = np.any(np.isclose(p, lo, atol=tol)) or np.any(np.isclose(p, hi, atol=tol))
    return inside and on_face


def two_boxes():
    a, b = box([0, 0, 0], [2, 2, 2]), box([1, 1, 1], [3, 3, 3])
    return np.vstack([a[0], b[0]]), np.vstack([a[1], b[1] + 8])


def test_topology_change_unites_a_box_moved_into_another():
    # Theorem 5.2: a solid moved in from far away in one frame leaves the
    # union of the two at the end of the frame.
    a, b = box([0, 0, 0], [2, 2, 2]), box([0, 0, 0], [2, 2, 2])
    F = np.vstack([a[1], b[1] + 8])
    V0 = np.vstack([a[0], b[0] + [9.0, 0.5, 0.5]])
    V1 = np.vstack([a[0], b[0] + [0.5, 0.5, 0.5]])
    V, G, report = holey.topology_change(V0, V1, F)
    assert report["collisions"] > 0 and report["intersecting_pairs"] > 0
    assert holey.volume(V, G) == pytest.approx(16.0 - 1.5**3, rel=1e-12)
    info = holey.info(V, G)
    assert info["closed"] and info["components"] == 1 and info["genus"] == 0


def test_topology_change_without_collision_changes_nothing():
    V0, F = holey.primitive("sphere", 2)
    V, G, report = holey.topology_change(V0, V0 * 1.1, F, scheme="majority")
    assert report["collisions"] == 0
    assert len(V) == len(V0) and np.array_equal(np.sort(G, axis=None), np.sort(F, axis=None))
    assert holey.volume(V, G) == pytest.approx(holey.volume(V0, F) * 1.1**3, rel=1e-12)


def test_self_intersections_of_two_crossing_boxes():
    V, F = two_boxes()
    x = holey.self_intersections(V, F)
    assert x["intersecting_pairs"] == len(x["pairs"]) > 0
    assert x["intersection_curves"] == 1 and len(x["curves"]) == 1
    assert x["segments"].shape == (x["intersection_edges"], 2, 3)
    # Every pair is one triangle of each box, and every end of every
    # intersection edge lies on both boxes' surfaces.
    assert np.all((x["pairs"] < 12).sum(axis=1) == 1)
    for p in x["segments"].reshape(-1, 3):
        assert on_box_surface(p, [0, 0, 0], [2, 2, 2]) and on_box_surface(p, [1, 1, 1], [3, 3, 3])
    assert holey.self_intersections(*box([0, 0, 0], [1, 1, 1]))["intersecting_pairs"] == 0


def test_resolve_cuts_along_every_curve_and_keeps_the_area():
    V, F = two_boxes()
    W, G, report = holey.resolve(V, F, report=True)
    assert report["intersecting_pairs"] > 0 and len(G) > len(F)
    # The boxes' crossing points are exact at these coordinates: none is
    # a rounding away from a corner, so none is welded.
    assert report["points_welded"] == 0
    assert area(W, G) == pytest.approx(area(V, F), rel=1e-12)
    assert holey.self_intersections(W, G)["intersecting_pairs"] == 0


def test_info_counts_of_primitives_and_polygons():
    V, F = holey.primitive("torus")
    i = holey.info(V, F)
    assert (i["euler"], i["genus"], i["closed"], i["components"]) == (0, 1, True, 1)
    # A square pyramid given as one quad and four triangles.
    V = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0.5, 0.5, 1]]
    faces = [[0, 3, 2, 1], [0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]]
    i = holey.info(V, faces)
    assert (i["vertices"], i["edges"], i["faces"], i["genus"]) == (5, 8, 5, 0)
    assert i["volume"] == pytest.approx(1 / 3, rel=1e-12)


def test_stanford_bunny_info_matches_the_readme(shared):
    # meshes/README.md: 34834 vertices (+1113 unreferenced), 69451
    # triangles, open with 223 boundary edges in 5 loops, euler -3.
    i = holey.info(*holey.read(shared / "stanford-bunny.obj"))
    assert (i["vertices"], i["unreferenced_vertices"], i["faces"]) == (34834, 1113, 69451)
    assert (i["boundary_edges"], i["boundary_loops"], i["euler"]) == (223, 5, -3)


def test_sculpt_inflate_grows_a_sphere_and_reports_each_stroke():
    V, F = holey.primitive("sphere", 3)
    strokes = [{"brush": "inflate", "radius": 0.5, "strength": 0.05, "path": [[0, 0, 1]] * 4}]
    W, G, reports = holey.sculpt(V, F, strokes, report=True)
    assert len(reports) == 1 and reports[0]["brush"] == "inflate" and reports[0]["frames"] == 4
    assert holey.volume(W, G) > holey.volume(V, F)
    i = holey.info(W, G)
    assert i["closed"] and i["components"] == 1 and i["genus"] == 0
    # The input arrays are never modified.
    assert np.array_equal(V, holey.primitive("sphere", 3)[0])


def test_sculpt_inflate_closes_the_hole_of_a_torus():
    # An inflate brush centred in the hole of a torus pushes the inner rim
    # inwards from all sides until it meets itself: the engine fuses it
    # (the paper's incidental topology change), genus 1 becomes 0.
    V, F = holey.primitive("torus")
    assert holey.info(V, F)["genus"] == 1
    strokes = [{"brush": "inflate", "radius": 0.9, "strength": 0.1, "path": [[0, 0, 0]] * 16}]
    W, G, reports = holey.sculpt(V, F, strokes, report=True)
    assert reports[0]["topology_changes"] >= 1 and reports[0]["refused"] == []
    i = holey.info(W, G)
    assert i["closed"] and i["manifold"] and i["components"] == 1 and i["genus"] == 0
    assert holey.self_intersections(W, G)["intersecting_pairs"] == 0


def test_sculpt_snake_hook_through_a_sphere_makes_a_tunnel():
    # Issue 19: hooked at the top and pulled down through the inside and
    # out of the bottom, the dent meets the far side and opens: genus 1.
    V, F = holey.primitive("sphere", 3)
    path = [[0, 0, 1 - 2.4 * k / 20] for k in range(21)]
    strokes = [{"brush": "snake_hook", "radius": 0.45, "path": path}]
    W, G, reports = holey.sculpt(V, F, strokes, report=True)
    assert reports[0]["topology_changes"] >= 1
    i = holey.info(W, G)
    assert i["closed"] and i["manifold"] and i["components"] == 1 and i["genus"] == 1


def test_sculpt_symmetry_x_leaves_a_mirror_image():
    # A draw stroke on one side with symmetry in x, on a sphere symmetric
    # in x: every vertex has its mirror image among the vertices.
    V, F = holey.primitive("sphere", 3)
    strokes = [{"brush": "draw", "radius": 0.4, "strength": 0.02,
                "path": [[0.6, 0.3, 0.74], [0.62, 0.25, 0.74]], "symmetry": "x"}]
    W, G = holey.sculpt(V, F, strokes, remesh=False)
    mirrored = W * np.array([-1.0, 1.0, 1.0])
    nearest = np.min(np.linalg.norm(W[:, None, :] - mirrored[None, :, :], axis=2), axis=1)
    assert nearest.max() < 1e-9
    moved = np.linalg.norm(W - V, axis=1) > 0
    assert moved[V[:, 0] > 0].any() and moved[V[:, 0] < 0].any()


def test_the_gil_is_released_during_engine_calls():
    # While one thread runs a long exact computation, the main thread
    # keeps running Python: with the GIL held it could not run at all.
    V, F = holey.primitive("sphere", 6)
    done = threading.Event()

    def work():
        for _ in range(3):
            holey.self_intersections(V, F, threads=1)
        done.set()

    worker = threading.Thread(target=work)
    ticks = 0
    worker.start()
    while not done.is_set():
        ticks += 1
    worker.join()
    assert ticks > 1000
