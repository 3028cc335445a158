//! `holey cut` and `holey truncate`: TopMod's conical tools (issue 18).

use anyhow::Result;
use holey_io::WriteOptions;
use holey_model::cut::{CutOffset, CutTarget, cut_each, offsets_by_kind};
use holey_model::numbering::{parse_edge_list, parse_index_list};

use crate::error::bad_input;
use crate::input::{Kernel, load};
use crate::output::write_kernel;

#[derive(clap::Args)]
#[command(group(clap::ArgGroup::new("target").required(true).multiple(true).args(["vertex", "edge", "face"])))]
#[command(after_help = "\
Cuts a small neighbourhood of each target off the mesh and closes the
wound with one new face: each edge leaving the target (a spoke) is cut
at --offset model units (or --fraction of its length) from the target,
the cut points are joined across the faces around it, and the target
goes. Vertices are numbered in file order, faces as `holey info` counts
them; an edge is U-W (the edge between vertices U and W) or F:C (the
edge leaving corner C of face F). Counts:
  vertex of valence k         +(k-1) vertices, +k edges, +1 face (a k-gon)
  edge between valences a, b  +(a+b-4), +(a+b-3), +1
  face with s spokes, d sides +(s-d), +(s-d), +0 (the face moves in)
A cube corner: 8/12/6 -> 10/15/7. Several targets are cut at once (no
two may share a vertex); --vertex with --edge is TopMod's edge-vertex cut,
and --vertex-offset (or --vertex-fraction) gives the vertices an offset of
their own, TopMod's Offset (Vertex) beside the edges' Offset (Edge).

Refused (nothing written): an offset that is not positive and finite or
reaches the middle of a spoke, a target whose neighbourhood is not a
disk or is a whole component, a hole face, self-loops, two targets
sharing a vertex.

Examples:
  holey cut @cube corner.obj --vertex 0 --offset 0.5
  holey cut @cube wedge.obj --edge 0-1 --fraction 0.25
  holey cut @octahedron c.obj --vertex 0 --edge 1-2 --offset 0.3
  holey cut @cube ev.obj --edge 0-1 --vertex 6 --offset 0.3 --vertex-offset 0.7")]
pub struct Args {
    /// Input mesh (a file or a primitive).
    pub input: String,
    /// Output file; its extension names the format.
    pub output: String,
    /// Vertices to cut off, comma-separated (file order).
    #[arg(long, value_name = "V[,V...]")]
    pub vertex: Option<String>,
    /// Edges to cut off, comma-separated, each U-W or F:C.
    #[arg(long, value_name = "E[,E...]")]
    pub edge: Option<String>,
    /// Faces to cut off, comma-separated (file order).
    #[arg(long, value_name = "F[,F...]")]
    pub face: Option<String>,
    /// Distance of the cut along each spoke, in model units [default: --fraction 0.25].
    #[arg(long, conflicts_with = "fraction", allow_hyphen_values = true)]
    pub offset: Option<f64>,
    /// Distance of the cut along each spoke, as a fraction of its length (below 0.5).
    #[arg(long, allow_hyphen_values = true)]
    pub fraction: Option<f64>,
    /// The vertices' own offset in model units [default: as the others].
    #[arg(
        long,
        requires = "vertex",
        conflicts_with = "vertex_fraction",
        allow_hyphen_values = true
    )]
    pub vertex_offset: Option<f64>,
    /// The vertices' own offset as a fraction of each spoke's length.
    #[arg(long, requires = "vertex", allow_hyphen_values = true)]
    pub vertex_fraction: Option<f64>,
}

#[derive(clap::Args)]
#[command(after_help = "\
Truncation is the conical cut of `holey cut` with the offset a fraction
of each edge's length, so it scales with the mesh. Truncating every
vertex (--all) of a closed mesh gives 2E vertices, 3E edges and F + V
faces, each vertex of valence k becoming a k-gon: a cube 8/12/6 ->
24/36/14 (the truncated cube), an icosahedron at 1/3 -> 60/90/32 (the
soccer ball). Truncating an edge between valences a and b adds a+b-4
vertices, a+b-3 edges and one face. Vertices are numbered in file order;
an edge is U-W (between vertices U and W) or F:C (leaving corner C of
face F). The fraction must lie strictly between 0 and 0.5.

Examples:
  holey truncate @cube tcube.obj --all
  holey truncate @icosahedron ball.obj --all --fraction 0.3333333333333333
  holey truncate @cube t.obj --vertex 0,7 --fraction 0.2
  holey truncate @cube e.obj --edge 0-1,6-7")]
pub struct TruncateArgs {
    /// Input mesh (a file or a primitive).
    pub input: String,
    /// Output file; its extension names the format.
    pub output: String,
    #[command(flatten)]
    pub options: TruncateOptions,
}

/// The options besides the two files, which `holey batch truncate` shares.
#[derive(clap::Args)]
#[command(group(clap::ArgGroup::new("target").required(true).args(["vertex", "edge", "all"])))]
pub struct TruncateOptions {
    /// Vertices to truncate, comma-separated (file order).
    #[arg(long, value_name = "V[,V...]")]
    pub vertex: Option<String>,
    /// Edges to truncate, comma-separated, each U-W or F:C; no two may share a vertex.
    #[arg(long, value_name = "E[,E...]")]
    pub edge: Option<String>,
    /// Truncate every vertex that has an edge.
    #[arg(long)]
    pub all: bool,
    /// Where each edge is cut, as a fraction of its length from the truncated end.
    #[arg(long, default_value_t = 1.0 / 3.0, allow_hyphen_values = true)]
    pub fraction: f64,
}

/// The targets the comma-separated lists name, in the order given.
fn targets(
    kernel: &Kernel,
    vertices: Option<&str>,
    edges: Option<&str>,
    faces: Option<&str>,
) -> Result<Vec<CutTarget>> {
    let numbers =
        |list: Option<&str>, what| list.map_or(Ok(Vec::new()), |s| parse_index_list(s, what));
    let vertices = numbers(vertices, "vertex").map_err(bad_input)?;
    let edges = edges
        .map_or(Ok(Vec::new()), parse_edge_list)
        .map_err(bad_input)?;
    let faces = numbers(faces, "face").map_err(bad_input)?;
    let out = kernel
        .numbering
        .cut_targets(&kernel.mesh, &vertices, &edges, &faces)
        .map_err(bad_input)?;
    if out.is_empty() {
        return Err(bad_input("no vertex, edge or face was named to cut"));
    }
    Ok(out)
}

/// Cuts `targets` off `kernel`, each at its own offset, and writes it to
/// `output`.
fn cut_and_write(
    input: &str,
    output: &str,
    mut kernel: Kernel,
    targets: &[(CutTarget, CutOffset)],
) -> Result<()> {
    // A refused cut leaves the mesh unchanged, so its ids still describe it.
    cut_each(&mut kernel.mesh, targets).map_err(|e| {
        let why = kernel.numbering.describe_cut(&kernel.mesh, &e);
        bad_input(format!("{input}: {why}"))
    })?;
    write_kernel(output, &kernel.mesh, &WriteOptions::default())
}

pub fn run(args: Args) -> Result<()> {
    let offset = match (args.offset, args.fraction) {
        (Some(x), _) => CutOffset::Distance(x),
        (None, Some(t)) => CutOffset::Fraction(t),
        (None, None) => CutOffset::Fraction(0.25),
    };
    let kernel = load(&args.input)?.into_kernel(false)?;
    let targets = targets(
        &kernel,
        args.vertex.as_deref(),
        args.edge.as_deref(),
        args.face.as_deref(),
    )
    .map_err(|e| bad_input(format!("{}: {e}", args.input)))?;
    let vertex_offset = match (args.vertex_offset, args.vertex_fraction) {
        (Some(x), _) => CutOffset::Distance(x),
        (None, Some(t)) => CutOffset::Fraction(t),
        (None, None) => offset,
    };
    let each = offsets_by_kind(targets, vertex_offset, offset);
    cut_and_write(&args.input, &args.output, kernel, &each)
}

pub fn run_truncate(args: TruncateArgs) -> Result<()> {
    run_truncate_file(&args.input, &args.output, &args.options)
}

/// Truncates the mesh `input` names into the file `output`.
pub fn run_truncate_file(input: &str, output: &str, o: &TruncateOptions) -> Result<()> {
    if !(o.fraction > 0.0 && o.fraction < 0.5) {
        return Err(bad_input(format!(
            "--fraction must lie strictly between 0 and 0.5, got {}",
            o.fraction
        )));
    }
    let kernel = load(input)?.into_kernel(false)?;
    let targets = if o.all {
        let mut all = Vec::new();
        for v in kernel.mesh.vertices() {
            if kernel
                .mesh
                .valence(v)
                .map_err(|e| bad_input(e.to_string()))?
                > 0
            {
                all.push(CutTarget::Vertex(v));
            }
        }
        if all.is_empty() {
            return Err(bad_input(format!(
                "{input}: the mesh has no edges to truncate"
            )));
        }
        all
    } else {
        targets(&kernel, o.vertex.as_deref(), o.edge.as_deref(), None)
            .map_err(|e| bad_input(format!("{input}: {e}")))?
    };
    let each: Vec<(CutTarget, CutOffset)> = targets
        .into_iter()
        .map(|t| (t, CutOffset::Fraction(o.fraction)))
        .collect();
    cut_and_write(input, output, kernel, &each)
}
