//! `holey handle`: a multi-segment curved handle (thesis chapter IV).

use anyhow::Result;
use holey_io::WriteOptions;
use holey_model::handle::{
    HandleCurve, HandleParams, MultiHandleParams, create_handle, create_multi_face_handle,
};
use holey_model::numbering::{parse_face_corner, parse_index_list};

use crate::error::bad_input;
use crate::input::load;
use crate::output::write_kernel;

#[derive(clap::Args)]
#[command(after_help = "\
Joins two faces with a handle of K segments along a Hermite curve that
leaves the first face's centroid along its normal (weight w1) and arrives
at the second's against its normal (weight w2). Negative weights make a
hole through the mesh instead. Faces in one component: genus rises by 1;
in two components: they join. The corners (F:C, face F in file order as
`holey info` counts, corner C its C-th vertex) are matched, so choosing
other corners twists the handle. Between two d-gons a handle of s
segments adds d(s-1) vertices, d(2s-1) edges and ds-2 faces.
--curve bezier takes TopMod's cubic Bézier instead, with control points
w1 and w2 above the faces along their normals (the Hermite curve with
three times the weights).
--faces F,F,F,F[,...] instead joins four or more faces through a hub (a
multi-face handle, TopMod's): the dual convex hull of points in the
faces' directions from a centre that every face sees from outside and
that has faces all around it, --hub-scale times the nearest centroid's
distance, one handle from each face to its hub face. Genus rises by
k - m for k faces in m pieces. Faces with no such centre (all around one
body, looking outward), a face whose view of it is blocked, and handles
that would cross anything (checked exactly, as holey selfint counts) are
refused, naming the faces.

Examples:
  holey handle @torus out.obj --from 0:0 --to 150:2 --segments 6 --w1 2 --w2 2
  holey handle @cube tunnel.obj --from 0:0 --to 5:0 --segments 4 --w1 -1 --w2 -1
  holey handle @cube arch.obj --from 0:0 --to 2:0 --segments 6 --curve bezier
  holey handle six_cubes.obj star.obj --faces 0,11,22,33,44,55 --hub-scale 0.5
  holey handle @torus:64:32 wheel.obj --faces 14,336,686,1008,1358,1712 --segments 4 --hub-scale 0.2 --w1 0.2 --w2 0.2")]
pub struct Args {
    /// Input mesh (a file or a primitive).
    pub input: String,
    /// Output file; its extension names the format.
    pub output: String,
    /// The first face and corner, as FACE:CORNER.
    #[arg(long, required_unless_present = "faces", conflicts_with = "faces")]
    pub from: Option<String>,
    /// The second face and corner, as FACE:CORNER.
    #[arg(long, required_unless_present = "faces", conflicts_with = "faces")]
    pub to: Option<String>,
    /// Four or more faces, comma-separated, joined through a hub.
    #[arg(long)]
    pub faces: Option<String>,
    /// The hub's size, as a share of the nearest face centroid's distance
    /// from the centre of the selected faces (with --faces).
    #[arg(long, default_value_t = 0.5, requires = "faces")]
    pub hub_scale: f64,
    /// Number of segments.
    #[arg(long, default_value_t = 4)]
    pub segments: usize,
    /// Weight of the first face's normal (negative: a hole).
    #[arg(long, default_value_t = 1.0, allow_hyphen_values = true)]
    pub w1: f64,
    /// Weight of the second face's normal (negative: a hole).
    #[arg(long, default_value_t = 1.0, allow_hyphen_values = true)]
    pub w2: f64,
    /// The handle's centre curve: hermite (the thesis's, §IV.2) or bezier.
    #[arg(long, default_value = "hermite")]
    pub curve: String,
}

pub fn run(args: Args) -> Result<()> {
    let curve: HandleCurve = args.curve.parse().map_err(bad_input)?;
    let params = HandleParams::new(args.segments, args.w1, args.w2).with_curve(curve);
    let (Some(from), Some(to)) = (&args.from, &args.to) else {
        return run_multi(&args, params);
    };
    let (f1, c1) = parse_face_corner(from).map_err(bad_input)?;
    let (f2, c2) = parse_face_corner(to).map_err(bad_input)?;
    let mut kernel = load(&args.input)?.into_kernel(false)?;
    let corner = |f, c| {
        kernel
            .numbering
            .corner(&kernel.mesh, f, c)
            .map_err(bad_input)
    };
    let (a, b) = (corner(f1, c1)?, corner(f2, c2)?);
    create_handle(&mut kernel.mesh, a, b, &params)
        .map_err(|e| bad_input(format!("{}: {e}", args.input)))?;
    write_kernel(&args.output, &kernel.mesh, &WriteOptions::default())
}

/// `--faces`: a multi-face handle through a hub.
fn run_multi(args: &Args, handle: HandleParams) -> Result<()> {
    let list = args.faces.as_deref().unwrap_or_default();
    let numbers = parse_index_list(list, "face").map_err(bad_input)?;
    let mut kernel = load(&args.input)?.into_kernel(false)?;
    let faces: Vec<_> = numbers
        .iter()
        .map(|&n| kernel.numbering.face(n).map_err(bad_input))
        .collect::<Result<_>>()?;
    let params = MultiHandleParams::new(handle, args.hub_scale);
    if let Err(e) = create_multi_face_handle(&mut kernel.mesh, &faces, &params) {
        let why = kernel.numbering.describe_multi_handle(&kernel.mesh, &e);
        return Err(bad_input(format!("{}: {why}", args.input)));
    }
    write_kernel(&args.output, &kernel.mesh, &WriteOptions::default())
}
