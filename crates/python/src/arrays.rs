//! Buffers in, buffers out: the meshes the Python half hands over as
//! little-endian bytes (`float64` xyz triples, `uint32` indices), and the
//! results handed back the same way (indices as `int64`, numpy's default
//! integer, so that the caller gets the dtype trimesh and libigl use).

use holey::DVec3;
use holey::mesh::PolyMesh;
use holey::topo::TriMesh;
use pyo3::prelude::*;
use pyo3::types::PyBytes;

use crate::errors::bad;

/// `bytes` cut into rows of `size` bytes, or an error naming the input,
/// `what`, when the length is not a whole number of rows (`noun` names
/// them). Positions and indices refuse a ragged buffer the same way.
fn rows<'b>(
    bytes: &'b [u8],
    size: usize,
    what: &str,
    noun: &str,
) -> PyResult<std::slice::ChunksExact<'b, u8>> {
    if !bytes.len().is_multiple_of(size) {
        return Err(bad(format!(
            "{what}: {} bytes is not a whole number of {noun}",
            bytes.len()
        )));
    }
    Ok(bytes.chunks_exact(size))
}

/// Positions from `float64` triples.
pub fn positions(bytes: &[u8], what: &str) -> PyResult<Vec<DVec3>> {
    Ok(rows(bytes, 24, what, "float64 (x, y, z) rows")?
        .map(|row| {
            let c = |i: usize| {
                let mut b = [0u8; 8];
                b.copy_from_slice(&row[8 * i..8 * i + 8]);
                f64::from_le_bytes(b)
            };
            DVec3::new(c(0), c(1), c(2))
        })
        .collect())
}

/// Indices from `uint32` values.
pub fn indices(bytes: &[u8], what: &str) -> PyResult<Vec<u32>> {
    Ok(rows(bytes, 4, what, "uint32 indices")?
        .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
        .collect())
}

/// A triangle mesh, checked (finite coordinates, indices in range): the
/// error names the input, `what`, and the first offending vertex or face.
pub fn tri_mesh(v: &[u8], f: &[u8], what: &str) -> PyResult<TriMesh> {
    let flat = indices(f, what)?;
    if !flat.len().is_multiple_of(3) {
        return Err(bad(format!("{what}: the faces are not triangles")));
    }
    let mesh = TriMesh {
        positions: positions(v, what)?,
        triangles: flat.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect(),
    };
    mesh.check().map_err(|e| bad(format!("{what}: {e}")))?;
    Ok(mesh)
}

/// A polygon mesh from flat indices and the offset where each face
/// starts (plus the end), checked like [`tri_mesh`].
pub fn poly_mesh(v: &[u8], flat: &[u8], offsets: &[u8], what: &str) -> PyResult<PolyMesh> {
    let mesh = PolyMesh {
        positions: positions(v, what)?,
        face_indices: indices(flat, what)?,
        face_offsets: indices(offsets, what)?,
    };
    mesh.check().map_err(|e| bad(format!("{what}: {e}")))?;
    Ok(mesh)
}

/// `float64` bytes of positions.
pub fn position_bytes<'py>(py: Python<'py>, positions: &[DVec3]) -> Bound<'py, PyBytes> {
    let mut out = Vec::with_capacity(positions.len() * 24);
    for p in positions {
        for c in [p.x, p.y, p.z] {
            out.extend_from_slice(&c.to_le_bytes());
        }
    }
    PyBytes::new(py, &out)
}

/// `int64` bytes of indices.
pub fn index_bytes<'py>(
    py: Python<'py>,
    indices: impl Iterator<Item = u32>,
) -> Bound<'py, PyBytes> {
    let mut out = Vec::new();
    for i in indices {
        out.extend_from_slice(&i64::from(i).to_le_bytes());
    }
    PyBytes::new(py, &out)
}

/// A triangle mesh as `(V bytes, F bytes)`.
pub type Arrays<'py> = (Bound<'py, PyBytes>, Bound<'py, PyBytes>);

/// The buffers of a triangle mesh, as it is (no vertex dropped).
pub fn tri_arrays<'py>(py: Python<'py>, mesh: &TriMesh) -> Arrays<'py> {
    (
        position_bytes(py, &mesh.positions),
        index_bytes(py, mesh.triangles.iter().flatten().copied()),
    )
}
