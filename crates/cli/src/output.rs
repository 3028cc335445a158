//! Writing meshes in the format the output file's extension names.

use std::path::Path;

use anyhow::Result;
use holey_dlfl::Mesh;
use holey_dlfl::convert::to_poly;
use holey_io::{Format, WriteOptions};
use holey_mesh::PolyMesh;

use crate::error::from_io;

/// Writes `text` to standard output and flushes it. A closed pipe
/// (`holey selfint x.obj --json | head -1`) is an error saying so, not a
/// panic as `print!` would make it.
pub fn print_stdout(text: &str) -> Result<()> {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    out.write_all(text.as_bytes())
        .and_then(|()| out.flush())
        .map_err(|e| anyhow::Error::new(e).context("cannot write to stdout"))
}

/// [`print_stdout`] of a line, as `println!` takes one.
macro_rules! outln {
    ($($arg:tt)*) => {
        $crate::output::print_stdout(&format!("{}\n", format_args!($($arg)*)))
    };
}

pub(crate) use outln;

/// Writes a DLFL: exactly as `.dlfl`, otherwise as a soup of its non-hole
/// faces with self-loops dropped (see `holey_dlfl::convert::to_poly`).
pub fn write_kernel(path: &str, mesh: &Mesh, opts: &WriteOptions) -> Result<()> {
    let p = Path::new(path);
    match Format::from_path(p).map_err(from_io)? {
        Format::Dlfl => holey_io::write_dlfl(p, &mesh.to_raw()).map_err(from_io),
        _ => {
            let out = to_poly(mesh);
            if out.dropped_faces > 0 {
                eprintln!(
                    "note: {path}: {} face(s) with fewer than 3 corners (two-gons, point-spheres) are not written; .dlfl keeps them",
                    out.dropped_faces
                );
            }
            holey_io::write_poly(p, &out.poly, opts).map_err(from_io)
        }
    }
}

/// Writes a soup. For `.dlfl` it is imported into the kernel first, so it
/// must be a 2-manifold (or `split_nonmanifold` set).
pub fn write_soup(
    path: &str,
    soup: &PolyMesh,
    opts: &WriteOptions,
    split_nonmanifold: bool,
) -> Result<()> {
    let p = Path::new(path);
    match Format::from_path(p).map_err(from_io)? {
        Format::Dlfl => {
            let imported = holey_dlfl::convert::to_dlfl(
                soup,
                holey_dlfl::convert::ImportOptions { split_nonmanifold },
            )
            .map_err(|e| crate::error::bad_input(format!("cannot write {path} as a DLFL: {e}")))?;
            holey_io::write_dlfl(p, &imported.mesh.to_raw()).map_err(from_io)
        }
        _ => holey_io::write_poly(p, soup, opts).map_err(from_io),
    }
}
