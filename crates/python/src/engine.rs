//! The triangle-mesh engine: Booleans, one frame of topology change,
//! self-intersections, their resolution, measurements and stroke replay
//! (Bernstein & Wojtan 2013).

use holey::mesh::PolyMesh;
use holey::mesh::analysis::analyze;
use holey::sculpt::{Session, parse_strokes};
use holey::topo::intersect::Node;
use holey::topo::solids::{BooleanOptions, Method};
use holey::topo::{Operation, Options, Scheme, TriMesh};
use pyo3::prelude::*;
use pyo3::types::PyBytes;
use serde_json::{Value, json};

use crate::arrays::{index_bytes, position_bytes, positions, tri_arrays, tri_mesh};
use crate::errors::bad;

/// Runs `work` with the GIL released, on a local rayon pool of `threads`
/// threads when given (0 or none: rayon's global pool, one thread per
/// core).
pub fn detached<T: Send>(
    py: Python<'_>,
    threads: Option<usize>,
    work: impl FnOnce() -> T + Send,
) -> PyResult<T> {
    py.detach(|| match threads {
        None | Some(0) => Ok(work()),
        Some(n) => rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .map(|pool| pool.install(work))
            .map_err(|e| format!("cannot start {n} threads: {e}")),
    })
    .map_err(pyo3::exceptions::PyRuntimeError::new_err)
}

/// The engine's options from the keyword arguments the Python half
/// passes through.
fn engine_options(
    scheme: &str,
    solid_guard: bool,
    float_ccd: bool,
    orient: bool,
    refine: bool,
) -> PyResult<Options> {
    let scheme = match scheme {
        "partition" => Scheme::Partition,
        "majority" => Scheme::Majority,
        other => {
            return Err(bad(format!(
                "scheme {other:?} is not known: use \"partition\" or \"majority\""
            )));
        }
    };
    Ok(Options {
        scheme,
        float_ccd,
        orient,
        refine,
        solid_guard,
        ..Options::default()
    })
}

/// A Boolean of closed solids by the winding-number rule: `op` is
/// `union`, `intersection` or `difference` (the first minus the others);
/// `method` forces `containment`, `winding` or `motion`. Returns the
/// result's buffers (unused vertices dropped) and its report as JSON.
#[pyfunction]
#[pyo3(signature = (op, meshes, *, method=None, exact=false, check=true, threads=None))]
pub fn boolean<'py>(
    py: Python<'py>,
    op: &str,
    meshes: Vec<(Bound<'py, PyBytes>, Bound<'py, PyBytes>)>,
    method: Option<&str>,
    exact: bool,
    check: bool,
    threads: Option<usize>,
) -> PyResult<(Bound<'py, PyBytes>, Bound<'py, PyBytes>, String)> {
    let op = match op {
        "union" => Operation::Union,
        "intersection" => Operation::Intersection,
        "difference" => Operation::Difference,
        other => return Err(bad(format!("{other:?} is not a Boolean operation"))),
    };
    let method = match method {
        None => None,
        Some("containment") => Some(Method::Containment),
        Some("winding") => Some(Method::Winding),
        Some("motion") => Some(Method::Motion),
        Some(other) => {
            return Err(bad(format!(
                "method {other:?} is not known: use \"containment\", \"winding\" or \"motion\""
            )));
        }
    };
    let inputs = meshes
        .iter()
        .enumerate()
        .map(|(i, (v, f))| tri_mesh(v.as_bytes(), f.as_bytes(), &format!("mesh {i}")))
        .collect::<PyResult<Vec<TriMesh>>>()?;
    let options = BooleanOptions {
        exact,
        check,
        method,
        ..BooleanOptions::default()
    };
    let out = detached(py, threads, || {
        let refs: Vec<&TriMesh> = inputs.iter().collect();
        holey::topo::solid_boolean(&refs, op, &options)
            .map(|out| (out.report_json(), out.into_mesh()))
    })?
    .map_err(bad)?;
    let (report, mesh) = out;
    let (v, f) = tri_arrays(py, &mesh.compacted());
    Ok((v, f, report.to_string()))
}

/// One frame of topology change (§3): the mesh `f` moves from `v0` to
/// `v1`; returns the result's buffers and the report as JSON.
#[pyfunction]
#[pyo3(signature = (v0, v1, f, *, scheme="partition", solid_guard=true, float_ccd=false, orient=true, refine=true, threads=None))]
#[allow(clippy::too_many_arguments)]
pub fn topology_change<'py>(
    py: Python<'py>,
    v0: &[u8],
    v1: &[u8],
    f: &[u8],
    scheme: &str,
    solid_guard: bool,
    float_ccd: bool,
    orient: bool,
    refine: bool,
    threads: Option<usize>,
) -> PyResult<(Bound<'py, PyBytes>, Bound<'py, PyBytes>, String)> {
    let options = engine_options(scheme, solid_guard, float_ccd, orient, refine)?;
    let mesh = tri_mesh(v0, f, "V0")?;
    let end = positions(v1, "V1")?;
    if end.len() != mesh.positions.len() {
        return Err(bad(format!(
            "V0 has {} vertices but V1 has {}: they must be the same mesh at the start and the end of the frame",
            mesh.positions.len(),
            end.len()
        )));
    }
    let out = detached(py, threads, || {
        holey::topo::topology_change(&mesh, &end, &options)
    })?
    .map_err(bad)?;
    let (v, f) = tri_arrays(py, &out.mesh.compacted());
    Ok((v, f, out.report.to_json().to_string()))
}

/// The exact self-intersections of a triangle mesh (§3.3): the counts as
/// JSON, the intersecting pairs (int64 pairs), the intersection points
/// (float64 xyz), the intersection edges as segments (float64, two
/// points each) and the curve each edge belongs to (int64).
#[pyfunction]
#[pyo3(signature = (v, f, *, threads=None))]
#[allow(clippy::type_complexity)]
pub fn self_intersections<'py>(
    py: Python<'py>,
    v: &[u8],
    f: &[u8],
    threads: Option<usize>,
) -> PyResult<(
    String,
    Bound<'py, PyBytes>,
    Bound<'py, PyBytes>,
    Bound<'py, PyBytes>,
    Bound<'py, PyBytes>,
)> {
    let mesh = tri_mesh(v, f, "mesh")?;
    let started = std::time::Instant::now();
    let x = detached(py, threads, || holey::topo::self_intersections(&mesh))?.map_err(bad)?;
    let counts = x.counts_json(mesh.triangles.len(), started.elapsed().as_secs_f64());
    let point = |n: Node| match n {
        Node::Point(i) => x.points.get(i as usize).map(|p| p.position),
        Node::Shared(id) => mesh.positions.get(id as usize).copied(),
    };
    let segments: Vec<_> = x
        .pieces
        .iter()
        .flat_map(|p| p.ends.map(|n| point(n).unwrap_or(holey::DVec3::NAN)))
        .collect();
    let points: Vec<_> = x.points.iter().map(|p| p.position).collect();
    Ok((
        counts.to_string(),
        index_bytes(py, x.pairs.iter().flat_map(|&(a, b)| [a, b])),
        position_bytes(py, &points),
        position_bytes(py, &segments),
        index_bytes(py, x.curve_of_piece.iter().copied()),
    ))
}

/// The arrangement of a self-intersecting surface: cut along every
/// intersection curve and glued there, nothing deleted. Returns the
/// buffers and a report as JSON.
#[pyfunction]
#[pyo3(signature = (v, f, *, threads=None))]
pub fn resolve<'py>(
    py: Python<'py>,
    v: &[u8],
    f: &[u8],
    threads: Option<usize>,
) -> PyResult<(Bound<'py, PyBytes>, Bound<'py, PyBytes>, String)> {
    let mesh = tri_mesh(v, f, "mesh")?;
    let (out, x, cut) = detached(py, threads, || holey::topo::resolve(&mesh))?.map_err(bad)?;
    let report = json!({
        "intersecting_pairs": x.pairs.len(),
        "intersection_curves": x.curve_count,
        "triangles_split": cut.triangles_split,
        "points_welded": cut.points_welded,
        "coplanar_groups_merged": cut.coplanar_groups_merged,
        "coplanar_groups_left": cut.coplanar_groups_left,
        "output_triangles": out.triangles.len(),
    });
    let (v, f) = tri_arrays(py, &out);
    Ok((v, f, report.to_string()))
}

/// The measurements `holey info --json` prints, of a polygon mesh given
/// as positions, flat indices and face offsets.
#[pyfunction]
pub fn info(v: &[u8], flat: &[u8], offsets: &[u8]) -> PyResult<String> {
    let mesh: PolyMesh = crate::arrays::poly_mesh(v, flat, offsets, "mesh")?;
    serde_json::to_string(&analyze(&mesh)).map_err(bad)
}

/// Replays the strokes of a stroke file (the JSON `holey sculpt` reads)
/// on a triangle mesh; returns the result's buffers and one report per
/// stroke as JSON. On an error nothing is returned.
#[pyfunction]
#[pyo3(signature = (v, f, strokes, *, remesh=true, threads=None))]
pub fn sculpt<'py>(
    py: Python<'py>,
    v: &[u8],
    f: &[u8],
    strokes: &str,
    remesh: bool,
    threads: Option<usize>,
) -> PyResult<(Bound<'py, PyBytes>, Bound<'py, PyBytes>, String)> {
    let mesh = tri_mesh(v, f, "mesh")?;
    let file = parse_strokes(strokes).map_err(|e| bad(format!("strokes: {e}")))?;
    let replayed = detached(py, threads, || {
        let mut session = Session::new(mesh)?;
        session.set_remeshing(remesh);
        let reports = session.replay(&file, &mut |_, _| Ok(()))?;
        Ok::<_, holey::sculpt::SculptError>((session.mesh().clone().compacted(), reports))
    })?;
    let (out, reports) = replayed.map_err(bad)?;
    let (v, f) = tri_arrays(py, &out);
    Ok((v, f, stroke_reports(&reports).to_string()))
}

fn stroke_reports(reports: &[holey::sculpt::StrokeReport]) -> Value {
    Value::Array(
        reports
            .iter()
            .map(|r| {
                json!({
                    "brush": r.brush.map(|b| b.name()),
                    "frames": r.frames,
                    "engine_runs": r.engine_runs,
                    "topology_changes": r.changes,
                    "raw_odd_vertices": r.raw_odd_vertices,
                    "corrected_odd_vertices": r.corrected_odd_vertices,
                    "triangles_before": r.triangles_before,
                    "triangles_after": r.triangles_after,
                    "remesh_operations": r.remesh_operations,
                    "guarded_frames": r.guarded_frames,
                    "held_frames": r.held_frames,
                    "held_vertices": r.held_vertices,
                    "subframes": r.subframes,
                    "whole_mesh_frames": r.whole_mesh_frames,
                    "specks_removed": r.specks_removed,
                    "refused": r.refused,
                    "held_because": r.held_because,
                    "seconds": r.seconds,
                })
            })
            .collect(),
    )
}
