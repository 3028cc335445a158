"""holey: change the topology of meshes, numpy in and numpy out.

Two papers stand behind it:

- Bernstein & Wojtan, *Putting Holes in Holey Geometry* (SIGGRAPH 2013):
  topology change for arbitrary triangle meshes during deformation
  (:func:`topology_change`), exact self-intersections
  (:func:`self_intersections`, :func:`resolve`), Booleans of solids by the
  winding-number rule (:func:`union`, :func:`intersection`,
  :func:`difference`) and sculpting whose brushes change topology
  (:func:`sculpt`);
- Srinivasan, *Modeling High-Genus Surfaces* (2004): the doubly linked
  face list and its tools, in :class:`Mesh` (handles, rinds, Sierpinski
  polyhedra, Menger sponges, Catmull-Clark and Doo-Sabin), with TopMod's
  toolbox: remeshing schemes, extrusions, wireframes, cuts and
  truncations.

A triangle mesh is a pair ``(V, F)``: ``V`` an ``(n, 3)`` array of
positions and ``F`` an ``(m, 3)`` array of vertex indices. Any array-like
is accepted and converted (to float64 and to 32-bit indices); results
come back as ``float64`` and ``int64`` arrays. Bad input raises
:class:`HoleyError`, a subclass of ``ValueError`` whose message says what
and where; a file the system cannot read or write raises ``OSError``.

Every engine call releases the GIL. ``threads=N`` runs it on a local pool
of ``N`` threads (default: one per core).

>>> import holey
>>> V, F = holey.primitive("cube")             # 2 units a side
>>> W, G = holey.union(V, F, V + 0.5, F)
>>> holey.volume(W, G) == 2 * 8 - 1.5**3
True
"""

from __future__ import annotations

import json
import numbers
import os
import warnings
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

from . import _holey
from ._holey import HoleyError

__all__ = [
    "HoleyError",
    "Mesh",
    "difference",
    "info",
    "intersection",
    "primitive",
    "read",
    "resolve",
    "sculpt",
    "self_intersections",
    "topology_change",
    "union",
    "volume",
    "write",
]

__version__: str = _holey.__version__

ArrayLike = Any
Arrays = Tuple[np.ndarray, np.ndarray]


# ---------------------------------------------------------------- arrays


def _positions(V: ArrayLike, name: str = "V") -> np.ndarray:
    """``V`` as a contiguous little-endian ``(n, 3)`` float64 array."""
    try:
        array = np.asarray(V, dtype="<f8")
    except (TypeError, ValueError) as e:
        raise HoleyError(f"{name}: not an array of numbers ({e})") from None
    if array.ndim != 2 or array.shape[1] != 3:
        raise HoleyError(f"{name}: expected an (n, 3) array of positions, got shape {array.shape}")
    return np.ascontiguousarray(array)


def _integers(F: ArrayLike, name: str) -> np.ndarray:
    """``F`` as int64 values, refusing fractions and negative indices."""
    array = np.asarray(F)
    if array.size == 0:
        return array.astype(np.int64).reshape(array.shape)
    if array.dtype.kind == "f":
        if not np.all(np.isfinite(array)) or np.any(array != np.floor(array)):
            bad = np.argwhere(~np.isfinite(array) | (array != np.floor(array)))[0]
            raise HoleyError(f"{name}: entry {tuple(int(i) for i in bad)} is not a whole number")
    elif array.dtype.kind not in "iub":
        raise HoleyError(f"{name}: expected integer vertex indices, got dtype {array.dtype}")
    values = array.astype(np.int64)
    if values.min() < 0:
        where = tuple(int(i) for i in np.argwhere(values < 0)[0])
        raise HoleyError(f"{name}: index {int(values[where])} at {where} is negative")
    if values.max() >= 2**32 - 1:
        raise HoleyError(f"{name}: index {int(values.max())} does not fit 32 bits")
    return values


def _triangles(F: ArrayLike, name: str = "F") -> np.ndarray:
    """``F`` as a contiguous little-endian ``(m, 3)`` uint32 array."""
    values = _integers(F, name)
    if values.ndim != 2 or values.shape[1] != 3:
        if values.size == 0:
            return np.zeros((0, 3), dtype="<u4")
        raise HoleyError(f"{name}: expected an (m, 3) array of triangles, got shape {values.shape}")
    return np.ascontiguousarray(values, dtype="<u4")


def _polygons(faces: ArrayLike, name: str = "faces") -> Tuple[bytes, bytes]:
    """Faces (an ``(m, k)`` array or a sequence of index sequences) as the
    flat indices and the offsets where each face starts, plus the end."""
    if isinstance(faces, np.ndarray) and faces.ndim == 2 or _is_rectangular(faces):
        values = _integers(faces, name)
        if values.size == 0:
            return b"", np.zeros(1, dtype="<u4").tobytes()
        if values.ndim != 2:
            raise HoleyError(f"{name}: expected an (m, k) array or a list of faces, got shape {values.shape}")
        m, k = values.shape
        offsets = np.arange(0, m * k + 1, k, dtype="<u4") if k else np.zeros(1, dtype="<u4")
        return values.astype("<u4").tobytes(), offsets.tobytes()
    flat: List[np.ndarray] = []
    offsets = [0]
    for i, face in enumerate(faces):
        values = _integers(face, f"{name}[{i}]").reshape(-1)
        flat.append(values)
        offsets.append(offsets[-1] + len(values))
    indices = np.concatenate(flat) if flat else np.zeros(0, dtype=np.int64)
    return indices.astype("<u4").tobytes(), np.asarray(offsets, dtype="<u4").tobytes()


def _is_rectangular(faces: ArrayLike) -> bool:
    try:
        lengths = {len(f) for f in faces}
    except TypeError:
        return False
    return len(lengths) <= 1


def _vertices_out(buffer: bytes) -> np.ndarray:
    return np.frombuffer(buffer, dtype="<f8").reshape(-1, 3).astype(np.float64)


def _indices_out(buffer: bytes, width: int = 3) -> np.ndarray:
    return np.frombuffer(buffer, dtype="<i8").reshape(-1, width).astype(np.int64)


def _faces_out(flat: bytes, offsets: bytes, triangulate: bool) -> Union[np.ndarray, List[np.ndarray]]:
    """Flat faces back as an ``(m, k)`` array when they all have ``k``
    corners, else a list of arrays; or fan triangles if ``triangulate``."""
    indices = np.frombuffer(flat, dtype="<i8").astype(np.int64)
    starts = np.frombuffer(offsets, dtype="<i8").astype(np.int64)
    sizes = np.diff(starts)
    if len(sizes) == 0:
        return np.zeros((0, 3), dtype=np.int64)
    if triangulate:
        rows = [
            (indices[s], indices[s + j], indices[s + j + 1])
            for s, n in zip(starts[:-1], sizes)
            for j in range(1, n - 1)
        ]
        return np.asarray(rows, dtype=np.int64).reshape(-1, 3)
    if np.all(sizes == sizes[0]):
        return indices.reshape(-1, int(sizes[0]))
    return [indices[s : s + n] for s, n in zip(starts[:-1], sizes)]


def _mesh(V: ArrayLike, F: ArrayLike, name: str = "") -> Tuple[bytes, bytes]:
    v = _positions(V, f"{name}V" if name else "V")
    f = _triangles(F, f"{name}F" if name else "F")
    return v.tobytes(), f.tobytes()


def _pairs(arrays: Sequence[ArrayLike]) -> List[Tuple[bytes, bytes]]:
    if len(arrays) == 0 or len(arrays) % 2:
        raise HoleyError(f"expected meshes as V, F pairs, got {len(arrays)} arrays")
    return [_mesh(arrays[i], arrays[i + 1], f"mesh {i // 2}: ") for i in range(0, len(arrays), 2)]


# ---------------------------------------------------------------- engine


def _boolean(op: str, arrays: Sequence[ArrayLike], method, exact, check, threads, report):
    v, f, text = _holey.boolean(
        op, _pairs(arrays), method=method, exact=exact, check=check, threads=threads
    )
    out = (_vertices_out(v), _indices_out(f))
    return out + (json.loads(text),) if report else out


def union(
    *meshes: ArrayLike,
    method: Optional[str] = None,
    exact: bool = False,
    check: bool = True,
    threads: Optional[int] = None,
    report: bool = False,
):
    """The union of closed solids: what is inside any of them.

    ``union(Va, Fa, Vb, Fb, ...)`` takes one or more meshes as ``V, F``
    pairs. A point is inside a mesh where its winding number is at least
    1/2, so solids may cross themselves, hold several or nested shells and
    overlap. With one mesh, the result is the boundary of the solid it
    encloses, free of its self-intersections and inner shells (the repair
    a 3D print needs).

    Two solids that do not cross themselves are united by exact
    containment (Bernstein & Wojtan, Theorem 5.2); otherwise by the exact
    arrangement of all the meshes. ``method`` forces ``"containment"``,
    ``"winding"`` or ``"motion"``; ``exact=True`` keeps the exactly placed
    result where overlapping coplanar faces would have the solids nudged;
    ``check=False`` skips the exact check that the inputs do not cross
    themselves. Returns ``(V, F)``, and the report as a dict as well when
    ``report=True``.
    """
    return _boolean("union", meshes, method, exact, check, threads, report)


def intersection(
    *meshes: ArrayLike,
    method: Optional[str] = None,
    exact: bool = False,
    check: bool = True,
    threads: Optional[int] = None,
    report: bool = False,
):
    """The intersection of closed solids: what is inside all of them.
    Arguments as for :func:`union`."""
    return _boolean("intersection", meshes, method, exact, check, threads, report)


def difference(
    *meshes: ArrayLike,
    method: Optional[str] = None,
    exact: bool = False,
    check: bool = True,
    threads: Optional[int] = None,
    report: bool = False,
):
    """The first solid minus the others: what is inside the first and
    inside none of the others. Arguments as for :func:`union`."""
    return _boolean("difference", meshes, method, exact, check, threads, report)


def topology_change(
    V0: ArrayLike,
    V1: ArrayLike,
    F: ArrayLike,
    scheme: str = "partition",
    solid_guard: bool = True,
    *,
    float_ccd: bool = False,
    orient: bool = True,
    refine: bool = True,
    threads: Optional[int] = None,
) -> Tuple[np.ndarray, np.ndarray, Dict[str, Any]]:
    """One frame of topology change (Bernstein & Wojtan 2013, section 3).

    The triangle mesh ``F`` moves in a straight line from ``V0`` to ``V1``.
    Vertices that hit the moving surface an odd number of times are odd;
    the parity is corrected against the intersection curves (``scheme``:
    ``"partition"``, the paper's graph cut, or ``"majority"``), the
    surface is cut along the curves, the odd part deleted and the rest
    glued. The mesh may be open, non-manifold, self-intersecting or a
    soup. ``solid_guard`` relabels a closed input's cut surface by
    containment where the motion folds it. Returns ``(V, F, report)``.
    """
    v0 = _positions(V0, "V0")
    v1 = _positions(V1, "V1")
    f = _triangles(F)
    v, g, text = _holey.topology_change(
        v0.tobytes(),
        v1.tobytes(),
        f.tobytes(),
        scheme=scheme,
        solid_guard=solid_guard,
        float_ccd=float_ccd,
        orient=orient,
        refine=refine,
        threads=threads,
    )
    return _vertices_out(v), _indices_out(g), json.loads(text)


def self_intersections(V: ArrayLike, F: ArrayLike, threads: Optional[int] = None) -> Dict[str, Any]:
    """The exact self-intersections of a triangle mesh.

    Triangles that only touch (share a vertex or an edge) are resolved by
    simulation of simplicity. Returns a dict with the counts
    ``triangles``, ``intersecting_pairs``, ``intersection_points``,
    ``triple_points``, ``intersection_edges``, ``intersection_curves`` and
    ``seconds``, and the arrays ``pairs`` (``(k, 2)`` triangle indices),
    ``points`` (``(p, 3)``), ``segments`` (``(e, 2, 3)``, each intersection
    edge's two ends), ``curve_of_segment`` (``(e,)``) and ``curves`` (one
    ``(s, 2, 3)`` array of segments per curve).
    """
    text, pairs, points, segments, curve_of = _holey.self_intersections(*_mesh(V, F), threads=threads)
    out: Dict[str, Any] = json.loads(text)
    out["pairs"] = _indices_out(pairs, 2)
    out["points"] = _vertices_out(points)
    out["segments"] = _vertices_out(segments).reshape(-1, 2, 3)
    out["curve_of_segment"] = np.frombuffer(curve_of, dtype="<i8").astype(np.int64)
    out["curves"] = [out["segments"][out["curve_of_segment"] == c] for c in range(out["intersection_curves"])]
    return out


def resolve(V: ArrayLike, F: ArrayLike, threads: Optional[int] = None, report: bool = False):
    """The arrangement of a self-intersecting surface: cut along all its
    intersection curves and glued there, nothing deleted, so that no
    triangle crosses another. Returns ``(V, F)`` (and a report dict when
    ``report=True``)."""
    v, f, text = _holey.resolve(*_mesh(V, F), threads=threads)
    out = (_vertices_out(v), _indices_out(f))
    return out + (json.loads(text),) if report else out


def info(V: ArrayLike, F: ArrayLike) -> Dict[str, Any]:
    """Measurements of a polygon mesh, with the keys of ``holey info
    --json``: counts, components, boundary loops, manifoldness,
    orientation, Euler characteristic, genus, bounding box, area, volume.
    ``F`` may be an ``(m, k)`` array or a list of faces of any sizes."""
    flat, offsets = _polygons(F, "F")
    return json.loads(_holey.info(_positions(V).tobytes(), flat, offsets))


def sculpt(
    V: ArrayLike,
    F: ArrayLike,
    strokes: Union[Dict[str, Any], List[Dict[str, Any]], str, "os.PathLike[str]"],
    remesh: bool = True,
    threads: Optional[int] = None,
    report: bool = False,
):
    """Replays sculpting strokes on a triangle mesh (Bernstein & Wojtan
    2013, section 4): the brushes move the surface and the engine changes
    its topology wherever it collides with itself.

    ``strokes`` is the stroke file ``holey sculpt`` reads, as a dict
    (``{"strokes": [...], "remesh": {...}}``), a list of strokes (each
    ``{"brush": "inflate", "radius": 0.3, "strength": 0.02, "path":
    [[x, y, z], ...]}``) or the path of a JSON file. The brushes are
    inflate, smooth, grab, move, snake_hook, draw, clay, crease, flatten,
    pinch, scrape, scale and layer; a stroke may add ``falloff``, ``symmetry``
    (``"x"``, ``"xz"``, ...), ``symmetry_about``, ``mask`` (``{"vertices":
    [...]}`` or ``{"sphere": {"centre": [...], "radius": r}}``) and a
    ``pressure`` per path point (see ``holey sculpt --help``). ``remesh``
    remeshes the brushed region between frames. Returns ``(V, F)`` (and
    one report dict per stroke when ``report=True``).
    """
    if isinstance(strokes, (str, os.PathLike)):
        with open(strokes, encoding="utf-8") as handle:
            text = handle.read()
    else:
        spec = {"strokes": strokes} if isinstance(strokes, list) else strokes
        try:
            text = json.dumps(spec)
        except (TypeError, ValueError) as e:
            raise HoleyError(f"strokes: not JSON data ({e})") from None
    v, f, reports = _holey.sculpt(*_mesh(V, F), text, remesh=remesh, threads=threads)
    out = (_vertices_out(v), _indices_out(f))
    return out + (json.loads(reports),) if report else out


def volume(V: ArrayLike, F: ArrayLike) -> float:
    """The signed volume a closed, outward-oriented triangle mesh encloses
    (the divergence theorem, summed in float64)."""
    v = _positions(V)
    f = _triangles(F).astype(np.int64)
    if len(f) and f.max() >= len(v):
        raise HoleyError(f"F: index {int(f.max())} is out of range for {len(v)} vertices")
    a, b, c = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)


# ---------------------------------------------------------------- files


def read(path: Union[str, "os.PathLike[str]"], triangulate: bool = True):
    """Reads a mesh file: OBJ, OFF, PLY, STL, glTF (``.gltf``, ``.glb``), 3MF
    or ``.dlfl``, by extension.

    Returns ``(V, F)``. Polygons are fan-triangulated from their first
    corner unless ``triangulate=False``, which gives ``F`` as an ``(m, k)``
    array when every face has ``k`` corners and as a list of arrays
    otherwise. Vertices keep file order, unused ones included, so
    ``read(write(path, V, F))`` gives back ``V`` and ``F`` exactly (binary
    STL stores float32 and does not store which vertices are shared)."""
    v, flat, offsets = _holey.read(os.fspath(path))
    return _vertices_out(v), _faces_out(flat, offsets, triangulate)


def write(path: Union[str, "os.PathLike[str]"], V: ArrayLike, F: ArrayLike, ascii: bool = False) -> None:
    """Writes a mesh atomically (nothing is left at ``path`` unless the
    whole file was written), the format from the extension. ``F`` may be
    triangles or polygons. OBJ, OFF and ascii STL write shortest
    round-trip decimals and PLY float64, so they are exact. ``ascii``
    chooses ascii PLY and STL."""
    flat, offsets = _polygons(F, "F")
    _holey.write(os.fspath(path), _positions(V).tobytes(), flat, offsets, ascii=ascii)


def primitive(name: str, *args: Union[int, float]) -> Arrays:
    """A built-in primitive as triangles, e.g. ``primitive("sphere", 3)``
    (``holey primitives`` lists them)."""
    return Mesh.primitive(name, *args).to_arrays(triangulate=True)


# ---------------------------------------------------------------- kernel


class Mesh:
    """A polygon mesh in the doubly linked face list of Srinivasan's
    thesis: an orientable 2-manifold, possibly with boundary. Its tools
    build high-genus surfaces; each returns a new :class:`Mesh` and
    leaves this one unchanged.

    Faces are numbered as :meth:`to_arrays` lists them (for a mesh from
    :meth:`from_polygons`, the order of the polygons given), and a face's
    corners from its first.

    >>> import holey
    >>> t = holey.Mesh.primitive("tetrahedron").sierpinski(2)
    >>> t.info()["genus"]
    15
    """

    __slots__ = ("_native",)

    def __init__(self, native: "_holey.Mesh") -> None:
        self._native = native

    @staticmethod
    def primitive(name: str, *args: Union[int, float]) -> "Mesh":
        """A built-in primitive: ``Mesh.primitive("torus", 32, 16)``."""
        spec = name if name.startswith("@") else "@" + name
        spec = ":".join([spec, *(str(a) for a in args)])
        return Mesh(_holey.Mesh.primitive(spec))

    @staticmethod
    def from_polygons(V: ArrayLike, faces: ArrayLike) -> "Mesh":
        """The mesh of polygons: ``faces`` an ``(m, k)`` array or a list
        of index sequences, each counter-clockwise seen from outside.
        Edges used twice the same way, or by three faces, are refused with
        the face that does not fit."""
        flat, offsets = _polygons(faces)
        return Mesh(_holey.Mesh.from_arrays(_positions(V).tobytes(), flat, offsets))

    @staticmethod
    def read(path: Union[str, "os.PathLike[str]"]) -> "Mesh":
        """Reads a mesh file (a ``.dlfl`` file as the DLFL it stores)."""
        return Mesh(_holey.Mesh.read(os.fspath(path)))

    def write(self, path: Union[str, "os.PathLike[str]"]) -> None:
        """Writes the mesh atomically; ``.dlfl`` keeps the holes and the
        exact structure."""
        self._native.write(os.fspath(path))

    def sierpinski(self, iterations: int = 1) -> "Mesh":
        """The Sierpinski polyhedron of ``iterations`` levels (thesis
        chapter VI): every face shrinks towards its corners and the holes
        between them become tunnels (figure 39: a tetrahedron at level 2
        has 34 vertices, 126 edges, 64 faces and genus 15)."""
        return Mesh(self._native.sierpinski(iterations))

    def menger(
        self,
        iterations: int = 1,
        exact: bool = False,
        thickness: Optional[float] = None,
        ratio: Optional[float] = None,
    ) -> "Mesh":
        """The Menger sponge of ``iterations`` levels (thesis chapter VII).
        ``exact=True`` builds the true sponge of a parallelepiped; the
        wall thickness is ``thickness`` in model units or ``ratio`` times
        the mean edge length (default 1/3)."""
        return Mesh(self._native.menger(iterations, exact=exact, thickness=thickness, ratio=ratio))

    def subdivide(self, scheme: str = "catmull-clark", levels: int = 1) -> "Mesh":
        """``levels`` of ``"catmull-clark"`` or ``"doo-sabin"``."""
        return Mesh(self._native.subdivide(scheme, levels))

    def handle(
        self,
        faces: Tuple[int, int],
        corners: Tuple[int, int] = (0, 0),
        segments: int = 4,
        w1: float = 1.0,
        w2: float = 1.0,
        curve: str = "hermite",
    ) -> "Mesh":
        """A handle of ``segments`` segments from face ``faces[0]`` to
        face ``faces[1]`` along a Hermite curve (thesis chapter IV), or
        with ``curve="bezier"`` TopMod's cubic Bézier whose control points
        stand ``w1`` and ``w2`` above the faces; the corners matched are
        ``corners``, so other corners twist it. Negative weights make a
        tunnel through the mesh. In one component the genus rises by 1;
        between two components they join."""
        return Mesh(
            self._native.handle(tuple(faces), tuple(corners), segments=segments, w1=w1, w2=w2, curve=curve)
        )

    def multi_face_handle(
        self,
        faces: Sequence[int],
        segments: int = 4,
        w1: float = 1.0,
        w2: float = 1.0,
        curve: str = "hermite",
        hub_scale: float = 0.5,
    ) -> "Mesh":
        """Joins four or more ``faces`` (numbered as :meth:`to_arrays`
        lists them) through a hub, one handle of ``segments`` segments from
        each (TopMod's multi-face handle, ``holey handle --faces``): the
        hub touches the sphere of ``hub_scale`` times the nearest face's
        distance about a centre that every face sees from outside, with
        one face turned to each selected face. ``k`` faces in ``m`` pieces
        raise the genus by ``k - m``. Faces with no such centre (all round
        one body, looking outward), a face whose view of it is blocked, and
        handles that would cross anything (an exact check, as ``holey
        selfint`` counts) raise ``ValueError`` naming the faces."""
        return Mesh(
            self._native.multi_face_handle(
                [int(f) for f in faces],
                segments=segments,
                w1=w1,
                w2=w2,
                curve=curve,
                hub_scale=hub_scale,
            )
        )

    def rind(self, thickness: float, punch: Sequence[int] = (), peel: Sequence[int] = ()) -> "Mesh":
        """A crust of ``thickness`` (thesis chapter V): two shells; each
        face in ``punch`` becomes a pipe from the outer shell to the inner,
        and ``peel`` also removes the thin walls between neighbouring
        holes. ``k`` holes in a genus-``g`` crust give genus ``2g + k - 1``.
        A face that could not be punched gives a warning."""
        native, notes = self._native.rind(thickness, punch=list(punch), peel=list(peel))
        for note in notes:
            warnings.warn(note, stacklevel=2)
        return Mesh(native)

    def remesh(self, scheme: str, n: int = 1, **opts: Union[float, bool]) -> "Mesh":
        """``n`` levels of one of TopMod's remeshing schemes, by the names
        of ``holey remesh``: ``"dual"``, ``"sqrt3"``, ``"loop"``,
        ``"vertex-truncation"``, ``"stellate"``, ``"corner-cutting"``,
        ``"honeycomb"``, ``"12.6.4"``, ``"dual-12.6.4"``,
        ``"pentagonalization"``, ``"checkerboard"``, ``"global-extrude"``,
        ``"dome"``, ``"fractal"`` and the others ``holey remesh --help``
        lists with their counts.

        Options, each read by the schemes ``holey remesh --help`` names
        (any other is refused): ``alpha`` (corner-cutting's tension),
        ``thickness``, ``offset``, ``scale``, ``length``, ``weight``,
        ``twist``, ``height``, ``curve`` and ``triangles=True``
        (subdivide-face). Every scheme keeps the genus; those built from
        the dual refuse a mesh with a boundary.

        >>> import holey
        >>> holey.Mesh.primitive("cube").remesh("dual").info()["faces"]
        8
        """
        triangles = opts.pop("triangles", False)
        if not isinstance(triangles, bool):
            raise HoleyError(f"remesh option triangles={triangles!r}: expected True or False")
        options = []
        for name, value in opts.items():
            if isinstance(value, bool) or not isinstance(value, numbers.Real):
                raise HoleyError(f"remesh option {name}={value!r}: expected a number")
            options.append((name, float(value)))
        return Mesh(self._native.remesh(scheme, n, options=options, triangles=triangles))

    def extrude(
        self,
        faces: Union[int, Sequence[int]],
        kind: str = "plain",
        distance: Optional[float] = None,
        scale: Optional[float] = None,
        rotation: Optional[float] = None,
        twist: Optional[float] = None,
        height: Optional[float] = None,
        count: Optional[int] = None,
        together: bool = False,
        vertex_normals: bool = False,
    ) -> "Mesh":
        """Extrudes each of ``faces`` (numbered as :meth:`to_arrays` lists
        them), one after the other, as ``holey extrude`` does.

        ``kind``: ``"plain"`` (``distance`` 1, ``scale`` 1, ``rotation``
        in degrees 0, ``count`` 1), ``"doo-sabin"`` (``distance``,
        ``scale``, ``twist``, ``count``), ``"cubical"`` (``height`` times
        the mean edge, ``count``), ``"dome"`` (``height``, ``count`` rings,
        default 5), ``"dodecahedral"``, ``"icosahedral"``,
        ``"octahedral"`` (``height``, 1 is regular), ``"stellate"`` and
        ``"double-stellate"`` (``distance``: the apex's lift, 0). An
        option the kind does not read is refused. ``together=True`` lifts
        the faces as one region (plain; ``distance``, ``count``,
        ``vertex_normals``). For a ``d``-gon, a plain extrusion adds ``d``
        vertices, ``2d`` edges and ``d`` faces per repetition.
        """
        if isinstance(faces, numbers.Integral):
            faces = [faces]
        return Mesh(
            self._native.extrude(
                [int(f) for f in faces],
                kind=kind,
                distance=distance,
                scale=scale,
                rotation=rotation,
                twist=twist,
                height=height,
                count=count,
                together=together,
                vertex_normals=vertex_normals,
            )
        )

    def wireframe(self, thickness: float, columns: Optional[int] = None) -> "Mesh":
        """Every edge a tube and every vertex a joint: the surface of the
        thickened edge graph, of genus ``E - V + 1`` per component. Without
        ``columns``, TopMod's wireframe (four-sided tubes ``thickness``
        wide: ``4E`` vertices, ``10E - 2(V1 + V2)`` edges and
        ``4E + 2 V3`` faces, ``Vk`` the vertices of valence ``k`` and
        ``V3`` those of valence 3 or more: no joint where one or two edges
        meet); with ``columns=n``, ``n``-sided columns of radius
        ``thickness``."""
        return Mesh(self._native.wireframe(thickness, columns=columns))

    def cut(
        self,
        vertices: Sequence[int] = (),
        edges: Sequence[Tuple[int, int]] = (),
        faces: Sequence[int] = (),
        offset: Optional[float] = None,
        fraction: Optional[float] = None,
        vertex_offset: Optional[float] = None,
        vertex_fraction: Optional[float] = None,
    ) -> "Mesh":
        """Cuts each vertex, edge and face off with one new face (TopMod's
        conical cuts, ``holey cut``): every edge leaving the target is cut
        at ``offset`` model units or at ``fraction`` of its length (default
        ``fraction=0.25``) and the cut points joined. Vertices and faces
        are numbered as :meth:`to_arrays` lists them; an edge is a pair of
        vertex numbers. A vertex of valence ``k`` adds ``k - 1`` vertices,
        ``k`` edges and one face. ``vertex_offset`` or ``vertex_fraction``
        gives the vertices an offset of their own (TopMod's cut by
        edge-vertex: edges at one offset, vertices at another)."""
        return Mesh(
            self._native.cut(
                vertices=[int(v) for v in vertices],
                edges=[(int(a), int(b)) for a, b in edges],
                faces=[int(f) for f in faces],
                offset=offset,
                fraction=fraction,
                vertex_offset=vertex_offset,
                vertex_fraction=vertex_fraction,
            )
        )

    def truncate(
        self,
        fraction: float = 1 / 3,
        vertices: Optional[Sequence[int]] = None,
        edges: Optional[Sequence[Tuple[int, int]]] = None,
    ) -> "Mesh":
        """Truncates vertices (every vertex when neither ``vertices`` nor
        ``edges`` is given) or edges at ``fraction`` of each edge, in
        ``(0, 0.5)``. Every vertex of a closed mesh: ``2E`` vertices,
        ``3E`` edges, ``F + V`` faces; an icosahedron at 1/3 is the soccer
        ball (60/90/32)."""
        return Mesh(
            self._native.truncate(
                fraction,
                vertices=None if vertices is None else [int(v) for v in vertices],
                edges=None if edges is None else [(int(a), int(b)) for a, b in edges],
            )
        )

    def convex_hull(self) -> "Mesh":
        """The convex hull of the vertices (``holey hull``): a convex
        polyhedron of genus 0, its faces the hull's planar facets and its
        vertices the corners (points inside, on a face or on a straight
        edge dropped); ``V - E + F = 2``, and ``F = 2V - 4`` when every
        face is a triangle. Decided exactly, with no tolerance: a point
        ``1e-17`` outside a face is a corner. Raises :class:`HoleyError`
        when the points lie on one plane."""
        return Mesh(self._native.convex_hull())

    def dual_convex_hull(self) -> "Mesh":
        """TopMod's dual convex hull (``holey hull --dual``): the solid
        bounded by the plane through each corner of the convex hull
        perpendicular to its normal, one face per corner; a cube gives
        the octahedron (6/12/8). Raises :class:`HoleyError` when the
        points lie on one plane."""
        return Mesh(self._native.dual_convex_hull())

    def info(self) -> Dict[str, Any]:
        """The measurements of ``holey info --json`` for a ``.dlfl``:
        ``vertices``, ``edges``, ``faces``, ``genus``, ``components``,
        ``closed`` and the rest (every edge record counted; holes as
        boundary loops)."""
        return json.loads(self._native.info())

    def to_arrays(self, triangulate: bool = False):
        """``(V, faces)``: the positions and the non-hole faces, as an
        ``(m, k)`` array when every face has ``k`` corners, else a list of
        arrays; fan triangles ``(m, 3)`` when ``triangulate=True``."""
        v, flat, offsets = self._native.to_arrays()
        return _vertices_out(v), _faces_out(flat, offsets, triangulate)

    def validate(self) -> None:
        """Checks every invariant of the DLFL; raises :class:`HoleyError`
        naming the first broken one."""
        self._native.validate()

    def __repr__(self) -> str:
        return repr(self._native)
