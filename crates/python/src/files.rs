//! Mesh files: OBJ, OFF, PLY, STL, glTF, 3MF and `.dlfl`, by extension (holey's
//! readers and atomic writers).

use std::path::Path;

use holey::dlfl::Mesh;
use holey::dlfl::convert::{ImportOptions, infer_edges, to_dlfl, to_poly};
use holey::io::{MeshFile, WriteOptions};
use holey::mesh::PolyMesh;
use pyo3::prelude::*;
use pyo3::types::PyBytes;

use crate::arrays::{index_bytes, poly_mesh, position_bytes};
use crate::errors::{bad, io};

/// A polygon mesh as `(V, flat indices, offsets)` buffers.
pub type PolyArrays<'py> = (
    Bound<'py, PyBytes>,
    Bound<'py, PyBytes>,
    Bound<'py, PyBytes>,
);

/// The buffers of a polygon mesh, every vertex kept.
pub fn poly_arrays<'py>(py: Python<'py>, mesh: &PolyMesh) -> PolyArrays<'py> {
    let offsets: Vec<u32> = if mesh.face_offsets.is_empty() {
        vec![0]
    } else {
        mesh.face_offsets.clone()
    };
    (
        position_bytes(py, &mesh.positions),
        index_bytes(py, mesh.face_indices.iter().copied()),
        index_bytes(py, offsets.into_iter()),
    )
}

/// The kernel's mesh of a `.dlfl` file's contents: the edges inferred
/// from the face lists when the file lists none, as `holey` does.
pub fn kernel_of_raw(mut raw: holey::dlfl::RawMesh, path: &str) -> PyResult<Mesh> {
    if raw.edges.is_empty() && raw.face_vertices.len() > raw.face_count() {
        infer_edges(&mut raw).map_err(|e| bad(format!("{path}: {e}")))?;
    }
    Mesh::from_raw(&raw).map_err(|e| bad(format!("{path}: {e}")))
}

/// Reads a mesh file as a polygon mesh: its vertices and faces as stored
/// (a `.dlfl` file: its non-hole faces). Returns the buffers.
#[pyfunction]
pub fn read<'py>(py: Python<'py>, path: &str) -> PyResult<PolyArrays<'py>> {
    let mesh = match holey::io::read_path(Path::new(path)).map_err(io)? {
        MeshFile::Poly(p) => p,
        MeshFile::Dlfl(raw) => to_poly(&kernel_of_raw(raw, path)?).poly,
    };
    Ok(poly_arrays(py, &mesh))
}

/// Writes a polygon mesh atomically; the format comes from the
/// extension (`.dlfl` converts it to the kernel first, which needs an
/// orientable 2-manifold). `ascii` chooses ascii PLY and STL (exact
/// decimals; binary STL stores float32).
#[pyfunction]
#[pyo3(signature = (path, v, flat, offsets, *, ascii=false))]
pub fn write(path: &str, v: &[u8], flat: &[u8], offsets: &[u8], ascii: bool) -> PyResult<()> {
    let mesh = poly_mesh(v, flat, offsets, path)?;
    let target = Path::new(path);
    if holey::io::Format::from_path(target).map_err(io)? == holey::io::Format::Dlfl {
        let kernel =
            to_dlfl(&mesh, ImportOptions::default()).map_err(|e| bad(format!("{path}: {e}")))?;
        return holey::io::write_dlfl(target, &kernel.mesh.to_raw()).map_err(io);
    }
    let options = WriteOptions {
        ascii,
        vertex_colors: None,
    };
    holey::io::write_poly(target, &mesh, &options).map_err(io)
}
