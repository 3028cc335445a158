//! Triangle meshes for the topology-change commands: reading any mesh
//! argument as triangles, writing results compactly, and the JSON report.

use anyhow::Result;
use holey_io::WriteOptions;
use holey_mesh::PolyMesh;
use holey_topo::{Report, TriMesh};
use serde_json::{Value, json};

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

/// The engine's report as JSON.
pub fn report_json(r: &Report) -> Value {
    json!({
        "collisions": r.collisions,
        "collision_tests": r.collision_tests,
        "containment_rays": r.containment_rays,
        "raw_odd_vertices": r.raw_odd_vertices,
        "corrected_odd_vertices": r.corrected_odd_vertices,
        "intersecting_pairs": r.intersecting_pairs,
        "intersection_points": r.intersection_points,
        "triple_points": r.triple_points,
        "intersection_edges": r.intersection_edges,
        "intersection_curves": r.intersection_curves,
        "curves_kept": r.cut.curves_kept,
        "curves_dropped": r.cut.curves_dropped,
        "false_vertices": r.cut.false_vertices,
        "false_edges": r.cut.false_edges,
        "triangles_split": r.cut.triangles_split,
        "triangles_deleted": r.cut.triangles_deleted,
        "diffused_triangles": r.cut.diffused,
        "undecided_triangles": r.cut.undecided,
        "dropped_constraints": r.cut.dropped_constraints,
        "sampled_regions": r.cut.sampled_regions,
        "junctions_repaired": r.cut.junctions_repaired,
        "pinches_split": r.cut.pinches_split,
        "solid_relabelled": r.cut.solid_relabelled,
        "conflicting_triangles": r.cut.conflicting,
        "constraint_splits": r.cut.constraint_splits,
        "merged_points": r.cut.merged_points,
        "solved_components": r.solved_components,
        "unsolved_components": r.unsolved_components,
        "perturbation_retries": r.perturbation_retries,
        "solid_input": r.solid_input,
        "orientation_flips": r.orientation_flips,
        "seconds": {
            "collisions": r.timings.collisions,
            "intersections": r.timings.intersections,
            "correction": r.timings.correction,
            "cut": r.timings.cut,
            "total": r.timings.total,
        },
    })
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
