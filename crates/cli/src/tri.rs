//! Triangle meshes for the topology-change commands: reading any mesh
//! argument as triangles, writing results compactly, and the JSON report.

use anyhow::Result;
use holey_io::WriteOptions;
use holey_mesh::PolyMesh;
use holey_topo::{Report, TriMesh};
use serde_json::Value;

use crate::error::bad_input;
use crate::input::{Input, WeldDistance, load, weld};

/// Reads a mesh argument as triangles: polygons are fan-triangulated; a
/// `.dlfl` file contributes its non-hole faces.
pub fn load_triangles(arg: &str) -> Result<TriMesh> {
    triangles_of(arg, load_soup(arg)?)
}

/// [`load_triangles`] with the vertices within `distance` welded first.
pub fn load_triangles_welded(arg: &str, distance: WeldDistance) -> Result<TriMesh> {
    triangles_of(arg, weld(arg, &load_soup(arg)?, distance)?)
}

/// A mesh argument as a polygon soup (a `.dlfl` file's non-hole faces).
fn load_soup(arg: &str) -> Result<PolyMesh> {
    let loaded = load(arg)?;
    Ok(match loaded.input {
        Input::Soup(s) => s,
        Input::Dlfl(_) => {
            let kernel = loaded.into_kernel(false)?;
            holey_dlfl::convert::to_poly(&kernel.mesh).poly
        }
    })
}

fn triangles_of(arg: &str, soup: PolyMesh) -> Result<TriMesh> {
    let mesh = soup.triangulated();
    mesh.check().map_err(|e| bad_input(format!("{arg}: {e}")))?;
    Ok(mesh)
}

/// Reads two mesh arguments at once, on two threads (parsing is most of
/// the time a union of two large files spends outside the engine). A's
/// error is reported first when both fail.
pub fn load_triangle_pair(a: &str, b: &str) -> Result<(TriMesh, TriMesh)> {
    let (ra, rb) = std::thread::scope(|s| {
        let hb = s.spawn(|| load_triangles(b));
        let ra = load_triangles(a);
        (ra, hb.join())
    });
    let rb = rb.map_err(|_| anyhow::anyhow!("reading {b} failed unexpectedly"))?;
    Ok((ra?, rb?))
}

/// The mesh without unreferenced vertices, as a polygon soup.
pub fn compact(mesh: &TriMesh) -> PolyMesh {
    PolyMesh::from(mesh.clone().compacted())
}

/// Writes a triangle mesh (unreferenced vertices dropped) atomically.
pub fn write_triangles(path: &str, mesh: &TriMesh) -> Result<()> {
    crate::output::write_soup(path, &compact(mesh), &WriteOptions::default(), true)
}

/// Writes `mesh` as a PLY with one colour per vertex.
pub fn write_colored(path: &str, mesh: &TriMesh, colors: Vec<[u8; 3]>) -> Result<()> {
    let poly = PolyMesh::from(mesh);
    let opts = WriteOptions {
        ascii: false,
        vertex_colors: Some(colors),
    };
    check_parity_path(path)?;
    crate::output::write_soup(path, &poly, &opts, true)
}

/// The parity picture is a PLY file (the one format here with vertex
/// colours).
pub fn check_parity_path(path: &str) -> Result<()> {
    if path.to_ascii_lowercase().ends_with(".ply") {
        Ok(())
    } else {
        Err(bad_input(format!(
            "{path}: the parity picture must be a .ply file"
        )))
    }
}

/// A one-paragraph summary of a report for the terminal.
pub fn report_text(r: &Report) -> String {
    format!(
        "collisions {} ({} tests); odd vertices raw {} corrected {}\n\
         intersections: {} triangle pairs, {} points ({} triple), {} edges, {} curves ({} kept)\n\
         triangles split {}, deleted {}; {:.3} s (collisions {:.3}, intersections {:.3}, correction {:.3}, cut {:.3})\n",
        r.collisions,
        r.collision_tests,
        r.raw_odd_vertices,
        r.corrected_odd_vertices,
        r.intersecting_pairs,
        r.intersection_points,
        r.triple_points,
        r.intersection_edges,
        r.intersection_curves,
        r.cut.curves_kept,
        r.cut.triangles_split,
        r.cut.triangles_deleted,
        r.timings.total,
        r.timings.collisions,
        r.timings.intersections,
        r.timings.correction,
        r.timings.cut,
    )
}

/// Writes JSON atomically.
pub fn write_json(path: &str, value: &Value) -> Result<()> {
    let mut text = serde_json::to_string_pretty(value)?;
    text.push('\n');
    holey_io::write_bytes_atomic(std::path::Path::new(path), text.as_bytes())
        .map_err(crate::error::from_io)
}
