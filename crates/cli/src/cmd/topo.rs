//! `holey topo`: one frame of topology change (Bernstein & Wojtan 2013, §3).

use anyhow::Result;
use clap::ValueEnum;
use holey_topo::{Options, Scheme, TriMesh, topology_change};

use crate::error::bad_input;
use crate::progress::Progress;
use crate::tri::{load_triangle_pair, report_text, write_colored, write_json, write_triangles};

/// The error-correction scheme (§3.4).
#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum SchemeArg {
    /// Graph partitioning: a quadratic energy, then a sweep cut (appendix B).
    Partition,
    /// Majority vote per intersection-bounded region (the paper's first scheme).
    Majority,
}

impl From<SchemeArg> for Scheme {
    fn from(s: SchemeArg) -> Scheme {
        match s {
            SchemeArg::Partition => Scheme::Partition,
            SchemeArg::Majority => Scheme::Majority,
        }
    }
}

/// Options shared by `topo` and `union`.
#[derive(clap::Args)]
pub struct EngineArgs {
    /// Write the report as JSON here.
    #[arg(long, value_name = "R.json")]
    pub report: Option<String>,
    /// Error-correction scheme.
    #[arg(long, value_enum, default_value_t = SchemeArg::Partition)]
    pub scheme: SchemeArg,
    /// Use the paper's floating-point coplanarity cubic instead of the exact
    /// root-parity collision test.
    #[arg(long)]
    pub float_ccd: bool,
    /// Leave triangle orientations as they come instead of making them
    /// consistent.
    #[arg(long)]
    pub keep_orientation: bool,
    /// Keep regions cut off by intersection curves that contain no vertex,
    /// as the paper does (its Figure 13 failure), instead of sampling
    /// their parity at a new point.
    #[arg(long)]
    pub no_refine: bool,
    /// Keep the parity result of a solid input even when it is not closed,
    /// as the paper does, instead of labelling the cut surface by
    /// containment number (motions that fold the surface).
    #[arg(long)]
    pub no_solid_guard: bool,
    /// Write the input at its end positions coloured by parity (PLY):
    /// grey even, red odd, yellow odd only before correction, blue odd only
    /// after it.
    #[arg(long, value_name = "P.ply")]
    pub parity: Option<String>,
    /// Print the report summary.
    #[arg(short, long)]
    pub verbose: bool,
}

impl EngineArgs {
    /// Refuses an output the run could only fail to write at its end
    /// (after the result had been written): checked before any work.
    pub fn check_outputs(&self) -> Result<()> {
        if let Some(path) = &self.parity {
            crate::tri::check_parity_path(path)?;
        }
        Ok(())
    }

    pub fn options(&self) -> Options {
        Options {
            scheme: self.scheme.into(),
            float_ccd: self.float_ccd,
            orient: !self.keep_orientation,
            refine: !self.no_refine,
            solid_guard: !self.no_solid_guard,
            ..Options::default()
        }
    }
}

#[derive(clap::Args)]
#[command(after_help = "\
BEFORE and AFTER are the same triangle mesh (same faces, same vertex
count) at the start and the end of a frame; every vertex moves in a
straight line from one to the other. The mesh may be open, non-manifold,
self-intersecting, disconnected or an unwelded soup. Polygons are
fan-triangulated.

Vertices that hit the moving surface an odd number of times are odd; the
parity field is corrected against the intersection curves at the end
positions, the surface is cut along those curves, the odd part is deleted
and the rest glued.

Examples:
  holey topo before.obj after.obj out.obj --report r.json
  holey topo before.ply after.ply out.ply --parity parity.ply --scheme majority")]
pub struct Args {
    /// The mesh at the start of the frame.
    pub before: String,
    /// The same mesh at the end of the frame.
    pub after: String,
    /// Output file; its extension names the format.
    pub output: String,
    #[command(flatten)]
    pub engine: EngineArgs,
}

pub fn run(args: Args) -> Result<()> {
    args.engine.check_outputs()?;
    let (before, after) = load_triangle_pair(&args.before, &args.after)?;
    if before.positions.len() != after.positions.len() {
        return Err(bad_input(format!(
            "{} has {} vertices but {} has {}: BEFORE and AFTER must be the same mesh",
            args.before,
            before.positions.len(),
            args.after,
            after.positions.len()
        )));
    }
    if let Some(t) = (0..before.triangles.len().max(after.triangles.len()))
        .find(|&t| before.triangles.get(t) != after.triangles.get(t))
    {
        return Err(bad_input(format!(
            "the faces of {} and {} differ (first at triangle {t}; {} and {} triangles): BEFORE and AFTER must be the same mesh",
            args.before,
            args.after,
            before.triangles.len(),
            after.triangles.len()
        )));
    }
    run_engine(&before, &after.positions, &args.output, &args.engine)
}

/// Runs the engine and writes the result, the report and the parity picture.
pub fn run_engine(
    mesh: &TriMesh,
    end: &[glam::DVec3],
    output: &str,
    args: &EngineArgs,
) -> Result<()> {
    let out = {
        let _p = Progress::start("changing topology");
        topology_change(mesh, end, &args.options()).map_err(|e| bad_input(e.to_string()))?
    };
    write_outcome(&out, output, args, None, || TriMesh {
        positions: end.to_vec(),
        triangles: mesh.triangles.clone(),
    })
}

/// Writes an outcome: the mesh, the report and the parity picture (of
/// the input at its end positions, made by `at_end` only when asked for).
pub fn write_outcome(
    out: &holey_topo::Outcome,
    output: &str,
    args: &EngineArgs,
    method: Option<&str>,
    at_end: impl FnOnce() -> TriMesh,
) -> Result<()> {
    write_triangles(output, &out.mesh)?;
    if let Some(path) = &args.report {
        let mut json = out.report.to_json();
        if let (Some(m), Some(fields)) = (method, json.as_object_mut()) {
            fields.insert("method".into(), m.into());
        }
        write_json(path, &json)?;
    }
    if let Some(path) = &args.parity {
        let colors = out
            .raw_odd
            .iter()
            .zip(&out.corrected_odd)
            .map(|(&raw, &fixed)| match (raw, fixed) {
                (false, false) => [170, 170, 170],
                (true, true) => [220, 40, 40],
                (true, false) => [240, 200, 30],
                (false, true) => [40, 90, 230],
            })
            .collect();
        write_colored(path, &at_end(), colors)?;
    }
    if args.verbose {
        eprint!("{}", report_text(&out.report));
    }
    if let Some(crossing) = out.report.output_intersecting_pairs.filter(|&n| n > 0) {
        eprintln!(
            "warning: {crossing} triangle pairs of the result cross: B was nudged off coplanar contact (nudge {}), and points of the slivers that left were rounded past a sheet; `--winding` merges coplanar faces instead, more slowly",
            out.report.perturbation_retries
        );
    }
    Ok(())
}
