//! `holey selfint`: the exact self-intersections of a mesh (§3.3).

use crate::output::print_stdout;
use anyhow::Result;
use holey_topo::self_intersections;
use serde_json::json;

use crate::cmd::{MeshReport, ReportArgs};
use crate::error::bad_input;
use crate::progress::Progress;
use crate::tri::load_triangles;

const AFTER_HELP: &str = "\
Counts the pairs of triangles that intersect along a segment, decided by
exact predicates with simulation of simplicity: triangles that only touch
(share a vertex or an edge, or meet at a point of their boundaries in a
degenerate way) are resolved symbolically, consistently for the whole
mesh. Also counts the intersection points (edge crosses triangle, and
triple points where three triangles meet), the intersection edges between
them and the closed or open curves they form. Polygons are
fan-triangulated; vertices with equal positions are the same point.

Examples:
  holey selfint teapot.obj
  holey selfint soup.stl --json
  holey selfint teapot.obj --curves curves.obj";

pub type Args = ReportArgs<Options>;

/// The options besides the mesh, which `holey batch selfint` shares.
#[derive(clap::Args)]
pub struct Options {
    /// Print one JSON object instead of text; with --pairs, list the pairs.
    #[arg(long)]
    pub json: bool,
    /// Also list the intersecting triangle pairs (triangle indices after
    /// fan triangulation).
    #[arg(long)]
    pub pairs: bool,
    /// Write the intersection curves as an OBJ of points and line
    /// segments, one group per curve (`g curve0`, ...), for viewing them.
    #[arg(long, value_name = "CURVES.obj")]
    pub curves: Option<String>,
    /// Also count the pairs of triangles that lie in one plane and
    /// overlap there (exact). Simulation of simplicity keeps coplanar
    /// triangles apart, so such overlaps are not intersecting pairs.
    #[arg(long)]
    pub overlaps: bool,
}

impl MeshReport for Options {
    fn report(&self, name: &str) -> Result<()> {
        if let Some(path) = &self.curves
            && !path.to_ascii_lowercase().ends_with(".obj")
        {
            return Err(bad_input(format!("{path}: the curves are written as .obj")));
        }
        let found = find(name)?;
        let Found { mesh, x, .. } = &found;
        if let Some(path) = &self.curves {
            holey_io::write_bytes_atomic(
                std::path::Path::new(path),
                curves_obj(mesh, x).as_bytes(),
            )
            .map_err(crate::error::from_io)?;
        }
        let triple = x.triple_points();
        let overlaps = self.overlaps.then(|| holey_topo::coplanar_overlaps(mesh));
        if self.json {
            let mut v = report_json(name, &found, self.pairs);
            if let Some(n) = overlaps {
                v["coplanar_overlaps"] = json!(n);
            }
            print_stdout(&(serde_json::to_string_pretty(&v)? + "\n"))?;
        } else {
            // One write: `--pairs` can list a great many lines.
            let mut text = format!(
                "mesh                {name}\ntriangles           {}\nintersecting pairs  {}\npoints              {} ({} triple)\nedges               {}\ncurves              {}\n",
                mesh.triangles.len(),
                x.pairs.len(),
                x.points.len(),
                triple,
                x.pieces.len(),
                x.curve_count
            );
            if let Some(n) = overlaps {
                text += &format!("coplanar overlaps   {n}\n");
            }
            if self.pairs {
                for (a, b) in &x.pairs {
                    text += &format!("pair {a} {b}\n");
                }
            }
            print_stdout(&text)?;
        }
        Ok(())
    }

    const MESH: &str = "The mesh";
    const AFTER_HELP: &str = AFTER_HELP;
}

/// A mesh's self-intersections, and the seconds finding them took.
pub struct Found {
    pub mesh: holey_topo::TriMesh,
    pub x: holey_topo::intersect::Intersections,
    pub seconds: f64,
}

/// The self-intersections of the mesh `name` names (read as triangles).
pub fn find(name: &str) -> Result<Found> {
    let mesh = load_triangles(name)?;
    let t = std::time::Instant::now();
    let x = {
        let _p = Progress::start("finding self-intersections");
        self_intersections(&mesh).map_err(|e| bad_input(format!("{name}: {e}")))?
    };
    let seconds = t.elapsed().as_secs_f64();
    Ok(Found { mesh, x, seconds })
}

/// The JSON object `--json` prints, with the pairs listed when `pairs`.
pub fn report_json(name: &str, found: &Found, pairs: bool) -> serde_json::Value {
    let Found { mesh, x, seconds } = found;
    let mut v = x.counts_json(mesh.triangles.len(), *seconds);
    v["mesh"] = json!(name);
    if pairs {
        v["pairs"] = json!(x.pairs);
    }
    v
}

/// The curves as OBJ text: every intersection point and every vertex a
/// curve passes through as a `v` line, every intersection edge as an `l`
/// line, grouped by curve.
fn curves_obj(mesh: &holey_topo::TriMesh, x: &holey_topo::intersect::Intersections) -> String {
    use holey_topo::intersect::Node;
    use std::fmt::Write;
    let mut text = String::from("# intersection curves written by holey selfint\n");
    let n = x.points.len();
    for p in &x.points {
        let q = p.position;
        let _ = writeln!(text, "v {} {} {}", q.x, q.y, q.z);
    }
    // Vertices shared by the two triangles of a piece, numbered after the
    // points in order of first use.
    let mut shared: std::collections::HashMap<u32, usize> = std::collections::HashMap::new();
    let mut index = |node: Node, text: &mut String| -> usize {
        match node {
            Node::Point(i) => i as usize + 1,
            Node::Shared(id) => {
                let next = n + shared.len() + 1;
                *shared.entry(id).or_insert_with(|| {
                    let q = mesh.positions.get(id as usize).copied().unwrap_or_default();
                    let _ = writeln!(text, "v {} {} {}", q.x, q.y, q.z);
                    next
                })
            }
        }
    };
    let mut by_curve: Vec<Vec<usize>> = vec![Vec::new(); x.curve_count];
    for (k, &c) in x.curve_of_piece.iter().enumerate() {
        if let Some(list) = by_curve.get_mut(c as usize) {
            list.push(k);
        }
    }
    let mut lines = String::new();
    for (c, pieces) in by_curve.iter().enumerate() {
        let _ = writeln!(lines, "g curve{c}");
        for &k in pieces {
            let [a, b] = x.pieces[k].ends;
            let (a, b) = (index(a, &mut text), index(b, &mut text));
            let _ = writeln!(lines, "l {a} {b}");
        }
    }
    text.push_str(&lines);
    text
}
