//! `holey selfint`: the exact self-intersections of a mesh (§3.3).

use anyhow::Result;
use holey_topo::self_intersections;
use serde_json::json;

use crate::error::bad_input;
use crate::progress::Progress;
use crate::tri::load_triangles;

#[derive(clap::Args)]
#[command(after_help = "\
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
  holey selfint soup.stl --json")]
pub struct Args {
    /// The mesh.
    pub mesh: String,
    /// Print one JSON object instead of text; with --pairs, list the pairs.
    #[arg(long)]
    pub json: bool,
    /// Also list the intersecting triangle pairs (triangle indices after
    /// fan triangulation).
    #[arg(long)]
    pub pairs: bool,
}

pub fn run(args: Args) -> Result<()> {
    let mesh = load_triangles(&args.mesh)?;
    let t = std::time::Instant::now();
    let x = {
        let _p = Progress::start("finding self-intersections");
        self_intersections(&mesh).map_err(|e| bad_input(format!("{}: {e}", args.mesh)))?
    };
    let seconds = t.elapsed().as_secs_f64();
    let triple = x.triple_points();
    if args.json {
        let mut v = json!({
            "mesh": args.mesh,
            "triangles": mesh.triangles.len(),
            "intersecting_pairs": x.pairs.len(),
            "intersection_points": x.points.len(),
            "triple_points": triple,
            "intersection_edges": x.pieces.len(),
            "intersection_curves": x.curve_count,
            "seconds": seconds,
        });
        if args.pairs {
            v["pairs"] = json!(x.pairs);
        }
        println!("{}", serde_json::to_string_pretty(&v)?);
    } else {
        println!("mesh                {}", args.mesh);
        println!("triangles           {}", mesh.triangles.len());
        println!("intersecting pairs  {}", x.pairs.len());
        println!("points              {} ({} triple)", x.points.len(), triple);
        println!("edges               {}", x.pieces.len());
        println!("curves              {}", x.curve_count);
        if args.pairs {
            for (a, b) in &x.pairs {
                println!("pair {a} {b}");
            }
        }
    }
    Ok(())
}
