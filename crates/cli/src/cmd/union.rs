//! `holey union`: the Boolean union of two solids by Theorem 5.2 of
//! Bernstein & Wojtan 2013: move one solid into the other and let the
//! topology change delete what ends up inside.

use anyhow::Result;
use glam::DVec3;
use holey_topo::union::{NUDGES, nudge};
use holey_topo::{Operation, TriMesh, UnionError};

use crate::cmd::topo::{EngineArgs, write_outcome};
use crate::cmd::winding;
use crate::error::bad_input;
use crate::progress::Progress;
use crate::tri::{load_triangle_pair, load_triangles};

/// The default direction B arrives from: generic, so that B's vertices
/// travel along lines that pass through none of the vertices and edges of
/// a mesh built on an axis-aligned lattice (a union of two copies of one
/// mesh shifted along an axis is the common case, and an axis-aligned
/// approach would make every collision degenerate).
const DEFAULT_DIRECTION: [f64; 3] = [1.0, 0.3127, 0.1731];

#[derive(clap::Args)]
#[command(after_help = "\
What is inside: a point is inside a solid when the solid's winding number
there is at least 1/2 (for a closed surface, an integer: the number of
times the surface wraps around the point). The union is everything inside
any input.

Which computation: with one input, or three and more, and whenever an
input crosses itself (checked exactly first), or with --winding: the
winding-number arrangement. Every triangle of every input is intersected
with every other, the surfaces are cut and glued along the curves, and
each region between curves gets its inputs' winding numbers on both sides
from one exact ray (simulation of simplicity); the regions with inside on
one side and outside on the other are kept, facing out. One input alone
gives the solid its surface encloses: self-intersections and inner shells
removed. Every input must be closed. The output is checked for crossing
triangles; if it has any (coplanar faces that touch), a warning says so.

Otherwise, for two solids that do not cross themselves, the union of
Theorem 5.2 below.

The motion (Theorem 5.2): B is first translated by s·d, where d is the
unit vector along --direction and s is the distance that puts B's shadow
on d wholly beyond A's plus 10% of the two shadows' combined length (so
B starts well clear of A's bounding box), and then moves in a straight
line back to its given position in one frame. A vertex of either solid
that ends inside the other hits the other's surface an odd number of
times, so the topology change deletes exactly the parts inside: the
union.

How it is computed: when A and B are both closed (every edge shared by
an even number of triangles), the parity that motion gives each vertex
is its containment in the other solid, so it is computed without
simulating the motion: the intersections of A with B only, then one
exact ray per region of vertices between the intersection curves (the
report counts the rays; it has no collisions). --via-motion runs the
synthesized frame through the whole pipeline of `holey topo` instead
(collisions, intersections, error correction), as it does by itself
for open input and for a solid that intersects itself where it meets
the other. A solid's own self-intersections elsewhere are kept as they
are, except by --via-motion.

Degenerate contact (faces of A and B coplanar, vertices or edges
coinciding: a copy of a mesh shifted by a lattice step) is resolved by
symbolic perturbation. Where coplanar faces of A and B overlap, the
perturbed result, placed at the exact coordinates, can have duplicate
triangles or cracks; so if A and B are closed 2-manifolds and the union
is not, the run is retried with B moved by a deterministic,
scale-relative nudge: 2^-30 of the scene's diagonal along a fixed
generic direction (about 1e-9 relative, far below any modelling
precision), then 16 and 256 times that along other directions. The
report counts the retries. Faces that merely touch from opposite sides
come out exact on the first try (the wall between them is removed).
--exact makes the first attempt the only one.

The default direction is generic (not along an axis) so that the paths
of B's vertices avoid A's vertices and edges even when A and B are
copies of one lattice-built mesh.

Examples:
  holey union a.obj b.obj union.obj
  holey union scan.stl repaired.stl        (one input: its enclosed solid)
  holey union a.obj b.obj c.obj all.obj --report r.json
  holey union @sphere:4 b.ply u.ply --via-motion --direction 0,0,1 --report r.json")]
pub struct Args {
    /// The first solid; it stays in place.
    pub a: String,
    /// The other solids (none, one, or more), then the output file, whose
    /// extension names the format.
    #[arg(required = true, num_args = 1.., value_name = "B... OUT")]
    pub rest: Vec<String>,
    /// Use the winding-number arrangement even for two solids that do
    /// not cross themselves (see below).
    #[arg(long, conflicts_with = "via_motion")]
    pub winding: bool,
    /// Skip the exact check that the two solids are closed 2-manifolds
    /// that do not cross themselves (about the time of `holey selfint` on
    /// both): for inputs known to be such solids. If one does cross
    /// itself, the result keeps its crossings.
    #[arg(long, conflicts_with = "winding")]
    pub no_check: bool,
    /// Direction B arrives from, as x,y,z.
    #[arg(long, value_name = "X,Y,Z")]
    pub direction: Option<String>,
    /// Do not perturb B's final position (see below).
    #[arg(long)]
    pub exact: bool,
    /// Run the synthesized motion through the whole pipeline even when
    /// both solids are closed (see below).
    #[arg(long)]
    pub via_motion: bool,
    #[command(flatten)]
    pub engine: EngineArgs,
}

fn parse_direction(s: &str) -> Result<DVec3> {
    let parts: Vec<f64> = s
        .split(',')
        .map(|t| t.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|_| bad_input(format!("--direction {s:?} is not three numbers x,y,z")))?;
    let [x, y, z] = parts[..] else {
        return Err(bad_input(format!(
            "--direction {s:?} is not three numbers x,y,z"
        )));
    };
    let d = DVec3::new(x, y, z);
    let len = d.length();
    if !len.is_finite() || len == 0.0 {
        return Err(bad_input(format!(
            "--direction {s:?} must be a finite, non-zero vector"
        )));
    }
    Ok(d / len)
}

/// The start positions of `a` joined with `b` moved away along `d`.
pub fn synthesize(a: &TriMesh, b: &TriMesh, d: DVec3) -> (TriMesh, Vec<DVec3>) {
    let shadow = |m: &TriMesh| {
        m.positions
            .iter()
            .map(|p| p.dot(d))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
                (lo.min(x), hi.max(x))
            })
    };
    let (alo, ahi) = shadow(a);
    let (blo, bhi) = shadow(b);
    let (alen, blen) = ((ahi - alo).max(0.0), (bhi - blo).max(0.0));
    let s = (ahi - blo).max(0.0) + 0.1 * (alen + blen) + f64::MIN_POSITIVE;
    let start = joined(a, b, d * s);
    let end: Vec<DVec3> = a.positions.iter().chain(&b.positions).copied().collect();
    (start, end)
}

/// `a` and `b` as one mesh, `b` moved by `offset` (A's vertices first).
pub(crate) fn joined(a: &TriMesh, b: &TriMesh, offset: DVec3) -> TriMesh {
    let n = a.positions.len() as u32;
    let mut both = a.clone();
    both.positions
        .extend(b.positions.iter().map(|p| *p + offset));
    both.triangles
        .extend(b.triangles.iter().map(|t| t.map(|v| v + n)));
    both
}

pub fn run(args: Args) -> Result<()> {
    args.engine.check_outputs()?;
    let Some((output, others)) = args.rest.split_last() else {
        return Err(bad_input("union needs an output file"));
    };
    if others.len() != 1 {
        if args.via_motion {
            return Err(bad_input("--via-motion unites exactly two solids"));
        }
        let names: Vec<&str> = std::iter::once(args.a.as_str())
            .chain(others.iter().map(String::as_str))
            .collect();
        let inputs = names
            .iter()
            .map(|n| load_triangles(n))
            .collect::<Result<Vec<_>>>()?;
        let _p = Progress::start("uniting");
        return winding::run(
            &inputs,
            &names,
            Operation::Union,
            output,
            &args.engine,
            args.exact,
        );
    }
    let (a, b) = load_triangle_pair(&args.a, &others[0])?;
    if a.positions.is_empty() || b.positions.is_empty() {
        return Err(bad_input("both solids must have vertices"));
    }
    if a.positions.len() + b.positions.len() >= u32::MAX as usize / 2 {
        return Err(bad_input("the two meshes together have too many vertices"));
    }
    let d = match &args.direction {
        Some(s) => parse_direction(s)?,
        None => DVec3::from_array(DEFAULT_DIRECTION).normalize(),
    };
    let _p = Progress::start("uniting");
    let checked = std::time::Instant::now();
    if !args.via_motion && (args.winding || (!args.no_check && winding::needs_winding(&a, &b)?)) {
        let names = [args.a.as_str(), others[0].as_str()];
        return winding::run(
            &[a, b],
            &names,
            Operation::Union,
            output,
            &args.engine,
            args.exact,
        );
    }
    let options = args.engine.options();
    let direct = if args.via_motion {
        None
    } else {
        let result = if args.exact {
            holey_topo::union(&a, &b, &options)
        } else {
            holey_topo::union_robust(&a, &b, &options)
        };
        match result {
            Ok(out) => Some(out),
            Err(UnionError::NotClosed(_) | UnionError::SelfIntersecting(_)) => None,
            Err(e) => return Err(bad_input(e.to_string())),
        }
    };
    let (out, picture) = match direct {
        Some(out) => {
            let retries = out.report.perturbation_retries;
            (out, Picture::Direct(retries))
        }
        None => via_motion(&a, &b, d, &args, &options)?,
    };
    let mut out = out;
    // The engine's total includes the check that sent the pair here.
    out.report.timings.total = checked.elapsed().as_secs_f64();
    write_outcome(&out, output, &args.engine, || match picture {
        Picture::Direct(retries) => joined(&a, &b, nudge(&a, &b, retries)),
        Picture::Motion(start, end) => TriMesh {
            positions: end,
            triangles: start.triangles,
        },
    })
}

/// What the parity picture shows: A and B at their final positions.
enum Picture {
    /// The direct union, after this many nudges of B.
    Direct(usize),
    /// The motion: its start mesh and end positions.
    Motion(TriMesh, Vec<DVec3>),
}

/// `b` translated by `d`.
fn moved(b: &TriMesh, d: DVec3) -> TriMesh {
    TriMesh {
        positions: b.positions.iter().map(|p| *p + d).collect(),
        triangles: b.triangles.clone(),
    }
}

/// The synthesized motion through the whole pipeline, B nudged as
/// [`holey_topo::union::NUDGES`] says from the first nonzero nudge on,
/// while A and B are closed 2-manifolds and the result is not; with
/// `--exact`, B unmoved only. The motion starts nudged, unlike the direct
/// union: on lattice-aligned copies its vertex parity misses overlaps
/// whose vertices all lie on the other's faces (§3.5 drops a curve
/// between even vertices), leaving both solids whole, which is closed
/// and so would not be retried.
fn via_motion(
    a: &TriMesh,
    b: &TriMesh,
    d: DVec3,
    args: &Args,
    options: &holey_topo::Options,
) -> Result<(holey_topo::Outcome, Picture)> {
    let both_closed = a.is_closed_manifold() && b.is_closed_manifold();
    let attempts = if args.exact { 0..1 } else { 1..NUDGES.len() };
    let mut last = None;
    for k in attempts {
        let b = moved(b, nudge(a, b, k));
        let (start, end) = synthesize(a, &b, d);
        if start.positions.iter().any(|p| !p.is_finite()) {
            return Err(bad_input(
                "B's start position overflows: the coordinates are too large",
            ));
        }
        let mut out = holey_topo::topology_change(&start, &end, options)
            .map_err(|e| bad_input(e.to_string()))?;
        out.report.perturbation_retries = k;
        let good = !both_closed || out.mesh.is_closed_manifold();
        last = Some((out, Picture::Motion(start, end)));
        if good {
            break;
        }
    }
    last.ok_or_else(|| bad_input("no attempt was made"))
}
