# Type stubs of the native module holey._holey (crates/python). Arrays
# cross as little-endian bytes: positions float64 xyz, indices uint32 in
# and int64 out; reports as JSON text. Use the package `holey`, which
# converts numpy arrays and parses the reports.
from typing import List, Optional, Tuple

__version__: str

class HoleyError(ValueError): ...

def boolean(
    op: str,
    meshes: List[Tuple[bytes, bytes]],
    *,
    method: Optional[str] = ...,
    exact: bool = ...,
    check: bool = ...,
    threads: Optional[int] = ...,
) -> Tuple[bytes, bytes, str]: ...
def topology_change(
    v0: bytes,
    v1: bytes,
    f: bytes,
    *,
    scheme: str = ...,
    solid_guard: bool = ...,
    float_ccd: bool = ...,
    orient: bool = ...,
    refine: bool = ...,
    threads: Optional[int] = ...,
) -> Tuple[bytes, bytes, str]: ...
def self_intersections(
    v: bytes, f: bytes, *, threads: Optional[int] = ...
) -> Tuple[str, bytes, bytes, bytes, bytes]: ...
def resolve(v: bytes, f: bytes, *, threads: Optional[int] = ...) -> Tuple[bytes, bytes, str]: ...
def info(v: bytes, flat: bytes, offsets: bytes) -> str: ...
def sculpt(
    v: bytes, f: bytes, strokes: str, *, remesh: bool = ..., threads: Optional[int] = ...
) -> Tuple[bytes, bytes, str]: ...
def read(path: str) -> Tuple[bytes, bytes, bytes]: ...
def write(path: str, v: bytes, flat: bytes, offsets: bytes, *, ascii: bool = ...) -> None: ...

class Mesh:
    @staticmethod
    def primitive(spec: str) -> Mesh: ...
    @staticmethod
    def from_arrays(v: bytes, flat: bytes, offsets: bytes) -> Mesh: ...
    @staticmethod
    def read(path: str) -> Mesh: ...
    def write(self, path: str) -> None: ...
    def to_arrays(self) -> Tuple[bytes, bytes, bytes]: ...
    def info(self) -> str: ...
    def sierpinski(self, iterations: int) -> Mesh: ...
    def menger(
        self,
        iterations: int,
        *,
        exact: bool = ...,
        thickness: Optional[float] = ...,
        ratio: Optional[float] = ...,
        collapse_angle: float = ...,
    ) -> Mesh: ...
    def subdivide(self, scheme: str, levels: int) -> Mesh: ...
    def handle(
        self,
        faces: Tuple[int, int],
        corners: Tuple[int, int] = ...,
        *,
        segments: int = ...,
        w1: float = ...,
        w2: float = ...,
        curve: str = ...,
    ) -> Mesh: ...
    def multi_face_handle(
        self,
        faces: List[int],
        *,
        segments: int = ...,
        w1: float = ...,
        w2: float = ...,
        curve: str = ...,
        hub_scale: float = ...,
    ) -> Mesh: ...
    def rind(
        self, thickness: float, *, punch: List[int] = ..., peel: List[int] = ...
    ) -> Tuple[Mesh, List[str]]: ...
    def remesh(
        self,
        scheme: str,
        levels: int = ...,
        *,
        options: List[Tuple[str, float]] = ...,
        triangles: bool = ...,
    ) -> Mesh: ...
    def extrude(
        self,
        faces: List[int],
        *,
        kind: str = ...,
        distance: Optional[float] = ...,
        scale: Optional[float] = ...,
        rotation: Optional[float] = ...,
        twist: Optional[float] = ...,
        height: Optional[float] = ...,
        count: Optional[int] = ...,
        together: bool = ...,
        vertex_normals: bool = ...,
    ) -> Mesh: ...
    def wireframe(self, thickness: float, *, columns: Optional[int] = ...) -> Mesh: ...
    def cut(
        self,
        *,
        vertices: List[int] = ...,
        edges: List[Tuple[int, int]] = ...,
        faces: List[int] = ...,
        offset: Optional[float] = ...,
        fraction: Optional[float] = ...,
        vertex_offset: Optional[float] = ...,
        vertex_fraction: Optional[float] = ...,
    ) -> Mesh: ...
    def truncate(
        self,
        fraction: float,
        *,
        vertices: Optional[List[int]] = ...,
        edges: Optional[List[Tuple[int, int]]] = ...,
    ) -> Mesh: ...
    def convex_hull(self) -> Mesh: ...
    def dual_convex_hull(self) -> Mesh: ...
    def validate(self) -> None: ...
