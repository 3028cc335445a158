"""holey.Mesh's TopMod toolbox (issue 18): remeshing schemes, extrusions,
wireframes, cuts and truncations. Every expected count is worked out here
from the input's counts, the operator's definition and Euler's formula."""

import math

import pytest

import holey


def counts(m):
    i = m.info()
    return i["vertices"], i["edges"], i["faces"]


def topology(m):
    i = m.info()
    return i["genus"], i["components"], i["boundary_loops"]


def test_dual_of_a_cube():
    cube = holey.Mesh.primitive("cube")
    V, E, F = counts(cube)
    dual = cube.remesh("dual")
    dual.validate()
    assert counts(dual) == (F, E, V) == (6, 12, 8)
    assert counts(cube) == (8, 12, 6)  # a new mesh; the cube is unchanged


def test_sqrt3_and_loop():
    t = holey.Mesh.primitive("tetrahedron")
    V, E, F = counts(t)
    C = 2 * E
    assert counts(t.remesh("sqrt3")) == (V + F, E + C, C) == (8, 18, 12)
    ico = holey.Mesh.primitive("icosahedron")
    V, E, F = counts(ico)
    loop = ico.remesh("loop", 2)
    # Loop twice: (V, E, F) -> (V + E, 2E + 3F, 4F), applied two times.
    V1, E1, F1 = V + E, 2 * E + 3 * F, 4 * F
    assert counts(loop) == (V1 + E1, 2 * E1 + 3 * F1, 4 * F1)


def test_truncation_stellation_corner_cutting_of_a_cube():
    cube = holey.Mesh.primitive("cube")
    V, E, F = counts(cube)
    C = 2 * E
    assert counts(cube.remesh("vertex-truncation", offset=0.3)) == (2 * E, E + C, F + V) == (24, 36, 14)
    assert counts(cube.remesh("stellate")) == (V + F, E + C, C) == (14, 36, 24)
    assert counts(cube.remesh("corner-cutting", alpha=0.6)) == (C, 2 * C, F + E + V) == (24, 48, 26)
    assert counts(cube.remesh("12.6.4")) == (V + E + F, 3 * C, 2 * C)
    assert counts(cube.remesh("dual-12.6.4")) == (2 * C, 2 * E + 2 * C, F + E + V)


def test_options_reach_their_parameters():
    cube = holey.Mesh.primitive("cube")
    V, E, F = counts(cube)
    # Truncation at half of every edge is the simplest scheme: E, 2E, F + V.
    assert counts(cube.remesh("vertex-truncation", offset=0.5)) == (E, 2 * E, F + V)
    assert counts(cube.remesh("subdivide-face", triangles=True)) == (V + F, 3 * E, 2 * E)


def test_every_scheme_keeps_a_torus_a_torus():
    torus = holey.Mesh.primitive("torus", 8, 4)
    schemes = [
        "dual", "triangulate", "sqrt3", "loop", "root4", "linear-vertex-insertion",
        "vertex-truncation", "dual-vertex-truncation", "stellate", "double-stellate",
        "corner-cutting", "modified-corner-cutting", "simplest", "honeycomb", "12.6.4",
        "dual-12.6.4", "pentagonalization", "dual-pentagonalization", "checkerboard",
        "dual-checkerboard", "global-extrude", "dual-global-extrude", "dome", "fractal",
        "doo-sabin-bc", "doo-sabin-bc-new",
    ]
    for scheme in schemes:
        r = torus.remesh(scheme)
        r.validate()
        V, E, F = counts(r)
        assert V - E + F == 0, scheme  # Euler: genus 1
        assert topology(r) == (1, 1, 0), scheme


def test_remesh_refusals():
    cube = holey.Mesh.primitive("cube")
    with pytest.raises(holey.HoleyError, match="no-such-scheme"):
        cube.remesh("no-such-scheme")
    with pytest.raises(holey.HoleyError, match="NaN"):
        cube.remesh("corner-cutting", alpha=float("nan"))
    with pytest.raises(holey.HoleyError, match="alpha"):
        cube.remesh("dual", alpha=0.5)
    with pytest.raises(holey.HoleyError, match="boundary"):
        holey.Mesh.primitive("plane", 3, 3).remesh("dual")
    with pytest.raises(ValueError):  # HoleyError is a ValueError
        cube.remesh("sqrt3", offset="big")


def test_extrusions_of_a_quad():
    cube = holey.Mesh.primitive("cube")
    V, E, F = counts(cube)
    d = 4  # every face of the cube is a quad

    def delta(m):
        m.validate()
        v, e, f = counts(m)
        return v - V, e - E, f - F

    assert delta(cube.extrude(0)) == (d, 2 * d, d) == (4, 8, 4)
    k = 3
    assert delta(cube.extrude([0], distance=0.5, scale=0.8, rotation=10, count=k)) == (k * d, 2 * k * d, k * d)
    assert delta(cube.extrude(0, kind="octahedral")) == (d, 3 * d, 2 * d)
    assert delta(cube.extrude(0, kind="dodecahedral")) == (3 * d, 5 * d, 2 * d)
    assert delta(cube.extrude(0, kind="icosahedral")) == (3 * d, 9 * d, 6 * d)
    assert delta(cube.extrude(0, kind="double-stellate")) == (d + 1, 4 * d, 3 * d - 1)
    # Every face stellated: 14/36/24.
    spiky = cube.extrude(range(6), kind="stellate", distance=1.0)
    assert counts(spiky) == (V + F, E + d * F, d * F) == (14, 36, 24)


def test_extruding_a_block_together():
    grid = holey.Mesh.primitive("plane", 4, 4)
    V, E, F = counts(grid)
    # The middle 2x2 block of quads has 8 boundary sides: +8, +16, +8.
    block = grid.extrude([5, 6, 9, 10], together=True, distance=0.5)
    assert counts(block) == (V + 8, E + 16, F + 8)


def test_extrude_refusals():
    cube = holey.Mesh.primitive("cube")
    with pytest.raises(holey.HoleyError, match="face 6 does not exist"):
        cube.extrude(6)
    with pytest.raises(holey.HoleyError, match="NaN"):
        cube.extrude(0, distance=math.nan)
    with pytest.raises(holey.HoleyError, match="rotation"):
        cube.extrude(0, kind="cubical", rotation=5)
    with pytest.raises(holey.HoleyError, match="pyramid"):
        cube.extrude(0, kind="pyramid")
    # The second ring overflows: the message says which point.
    with pytest.raises(holey.HoleyError, match=r"face 2: .*\(new point 4 has a non-finite"):
        cube.extrude([2], distance=1e308, count=3)


def test_wireframe_genus_is_the_cycle_rank():
    for mesh in [holey.Mesh.primitive("cube"), holey.Mesh.primitive("dodecahedron")]:
        V, E, F = counts(mesh)
        w = mesh.wireframe(0.05)
        w.validate()
        # Every vertex has valence 3 or more: E' = 10E, F' = 4E + 2V.
        assert counts(w) == (4 * E, 10 * E, 4 * E + 2 * V)
        assert topology(w) == (E - V + 1, 1, 0)
    cube = holey.Mesh.primitive("cube")
    cols = cube.wireframe(0.1, columns=5)
    n, (V, E, F) = 5, counts(cube)
    # Valence 3 everywhere: 2nE, 3nE + 6V, nE + 5V.
    assert counts(cols) == (2 * n * E, 3 * n * E + 6 * V, n * E + 5 * V)
    with pytest.raises(holey.HoleyError, match="thickness"):
        cube.wireframe(float("nan"))
    with pytest.raises(holey.HoleyError, match="face 0 turns over"):
        cube.wireframe(5.0)
    with pytest.raises(holey.HoleyError, match="3 sides"):
        cube.wireframe(0.1, columns=2)


def test_cut_and_truncate():
    cube = holey.Mesh.primitive("cube")
    V, E, F = counts(cube)
    # A vertex of valence 3: +2, +3, +1; an edge between two of them too.
    assert counts(cube.cut(vertices=[0], offset=0.5)) == (V + 2, E + 3, F + 1)
    assert counts(cube.cut(edges=[(0, 1)], fraction=0.25)) == (V + 2, E + 3, F + 1)
    assert counts(cube.cut(faces=[0])) == (V, E, F)
    assert counts(cube.truncate()) == (2 * E, 3 * E, F + V) == (24, 36, 14)
    ico = holey.Mesh.primitive("icosahedron")
    V, E, F = counts(ico)
    ball = ico.truncate(1 / 3)
    ball.validate()
    assert counts(ball) == (2 * E, 3 * E, F + V) == (60, 90, 32)
    assert counts(ball) == counts(holey.Mesh.primitive("soccerball"))
    assert ball.info()["face_sizes"] == {"5": 12, "6": 20}
    with pytest.raises(holey.HoleyError, match="not joined"):
        cube.cut(edges=[(0, 7)])
    with pytest.raises(holey.HoleyError, match="vertex 8 does not exist"):
        cube.cut(vertices=[8])
    with pytest.raises(holey.HoleyError, match=r"middle of edge \(0, \d\)"):
        cube.cut(vertices=[0], offset=5.0)
    with pytest.raises(holey.HoleyError, match="share vertex 1"):
        cube.cut(vertices=[1], edges=[(0, 1)])
    with pytest.raises(holey.HoleyError, match="0.5"):
        cube.truncate(0.5)


def test_convex_hull_and_dual_convex_hull():
    # A cube is its own hull; its dual convex hull is the octahedron
    # (the cube's F, E, V).
    cube = holey.Mesh.primitive("cube")
    V, E, F = counts(cube)
    h = cube.convex_hull()
    h.validate()
    assert counts(h) == (V, E, F)
    d = cube.dual_convex_hull()
    d.validate()
    assert counts(d) == (F, E, V)
    assert topology(d) == (0, 1, 0)
    # A torus's hull: genus 0, closed, Euler's formula; its dual has one
    # face per corner of the hull.
    torus = holey.Mesh.primitive("torus")
    t = torus.convex_hull()
    tv, te, tf = counts(t)
    assert topology(t) == (0, 1, 0) and tv - te + tf == 2
    assert counts(torus.dual_convex_hull())[2] == tv
    # A 3 x 3 grid on z = 0 closed by eight triangles to a point 1e-17
    # above its middle: the hull is the pyramid over the square (5/8/5);
    # with the point exactly on the grid it is flat.
    grid = [(float(i), float(j), 0.0) for j in range(3) for i in range(3)]
    base = [[0, 3, 4, 1], [1, 4, 5, 2], [3, 6, 7, 4], [4, 7, 8, 5]]
    rim = [0, 1, 2, 5, 8, 7, 6, 3]
    sides = [[a, b, 9] for a, b in zip(rim, rim[1:] + rim[:1])]
    for z, pyramid in [(1e-17, True), (0.0, False)]:
        m = holey.Mesh.from_polygons(grid + [(1.0, 1.0, z)], base + sides)
        if pyramid:
            assert counts(m.convex_hull()) == (5, 8, 5)
        else:
            with pytest.raises(holey.HoleyError, match="one plane"):
                m.convex_hull()
            with pytest.raises(holey.HoleyError, match="one plane"):
                m.dual_convex_hull()


def test_multi_face_handle_on_spot(shared):
    # The finer cow: six quads around a point above its head (a horn, both
    # ears, the head, the neck, the back) joined through a hub. One closed
    # piece before and after, genus 0 + 6 - 1, and no crossing pair by the
    # exact self-intersection count of the fan triangles.
    spot = holey.Mesh.read(str(shared / "spot_quadrangulated.obj"))
    V, F = spot.to_arrays(triangulate=True)
    assert holey.self_intersections(V, F)["intersecting_pairs"] == 0
    m = spot.multi_face_handle(
        [609, 2067, 2676, 651, 2136, 933], segments=4, w1=0.2, w2=0.2, hub_scale=0.3
    )
    m.validate()
    assert topology(m) == (5, 1, 0)
    V, F = m.to_arrays(triangulate=True)
    assert holey.self_intersections(V, F)["intersecting_pairs"] == 0
    # The faces of the coarse cow look outward all around it: a
    # hub would sit inside. Refused, naming faces of the selection in the
    # same numbers.
    coarse = holey.Mesh.read(str(shared / "spot_control_mesh.obj"))
    with pytest.raises(holey.HoleyError, match="look away from each other") as e:
        coarse.multi_face_handle([39, 129, 59, 26, 89, 56], segments=3, hub_scale=0.3)
    named = [int(n) for n in e.value.args[0].split(" look away")[0].replace("faces ", "").replace(" and", ",").split(",")]
    assert 2 <= len(named) <= 4 and set(named) <= {39, 129, 59, 26, 89, 56}


def test_multi_face_handle_counts_and_refusals():
    # Six cubes (side 2) at distance 4 on the axes, the face of each that
    # looks at the origin joined through a hub: the six directions are the
    # octahedron's, so the hub is a cube (8 / 12 / 6), each handle of s
    # segments between squares adds 4(s - 1) / 4(2s - 1) / 4s - 2, and
    # seven pieces become one sphere.
    import numpy as np

    cube = holey.Mesh.primitive("cube")
    cv, cf = cube.to_arrays()
    axes = [np.array(a, float) for a in [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)]]
    V = np.concatenate([cv + 4 * a for a in axes])
    F = np.concatenate([cf + 8 * k for k in range(6)])
    six = holey.Mesh.from_polygons(V, F)
    faces = []
    for k, a in enumerate(axes):
        for j, f in enumerate(cf):
            p = cv[f]
            n = np.cross(p[1] - p[0], p[2] - p[0])
            if np.dot(n / np.linalg.norm(n), -a) > 0.999:
                faces.append(6 * k + j)
    assert len(faces) == 6
    v, e, f = counts(six)
    s, k = 3, 6
    m = six.multi_face_handle(faces, segments=s, hub_scale=0.5, curve="bezier")
    m.validate()
    assert counts(m) == (v + 8 + k * 4 * (s - 1), e + 12 + k * 4 * (2 * s - 1), f + 6 + k * (4 * s - 2))
    assert topology(m) == (0, 1, 0)
    # Refusals: too few faces, a face twice, a face that does not exist,
    # a bad curve or hub scale; each a HoleyError (a ValueError).
    with pytest.raises(holey.HoleyError, match="at least four"):
        six.multi_face_handle(faces[:3])
    with pytest.raises(holey.HoleyError, match=f"face {faces[0]} is selected twice"):
        six.multi_face_handle([faces[0]] + faces[:3])
    with pytest.raises(ValueError, match="does not exist"):
        six.multi_face_handle(faces[:5] + [999])
    with pytest.raises(holey.HoleyError, match="curve"):
        six.multi_face_handle(faces, curve="spline")
    with pytest.raises(holey.HoleyError, match="hub scale"):
        six.multi_face_handle(faces, hub_scale=-1.0)
    # The six faces of one cube look away from each other.
    with pytest.raises(holey.HoleyError, match="look away from each other"):
        cube.multi_face_handle([0, 1, 2, 3, 4, 5])


def test_cut_by_edge_vertex_with_an_offset_each():
    # TopMod's cut by edge-vertex: edge 0-1 of the cube (side 2) at 0.3,
    # the far corner 7 at 0.7. Each cut alone adds 2 / 3 / 1; every new
    # point lies on a cube edge at its own target's offset from the corner
    # it replaced.
    import numpy as np

    cube = holey.Mesh.primitive("cube")
    V0, _ = cube.to_arrays()
    v, e, f = counts(cube)
    m = cube.cut(edges=[(0, 1)], vertices=[7], offset=0.3, vertex_offset=0.7)
    m.validate()
    assert counts(m) == (v + 4, e + 6, f + 2)
    V, _ = m.to_arrays()
    d = sorted(np.min(np.linalg.norm(V[:, None, :] - V0[None, :, :], axis=2), axis=1))
    assert np.allclose(d, [0] * 5 + [0.3] * 4 + [0.7] * 3)
    with pytest.raises(holey.HoleyError, match="vertex_offset or vertex_fraction"):
        cube.cut(vertices=[7], vertex_offset=0.3, vertex_fraction=0.2)
    with pytest.raises(holey.HoleyError, match="middle"):
        cube.cut(edges=[(0, 1)], vertices=[7], offset=0.3, vertex_offset=1.0)
