//! `holey remesh`: TopMod's remeshing schemes (issue 18), every scheme of
//! `holey_subdiv::remesh` by its kebab-case name.

use anyhow::Result;
use holey_io::WriteOptions;
use holey_subdiv::{RemeshParams, RemeshScheme, SubdivError, remesh};

use crate::error::bad_input;
use crate::input::load;
use crate::output::write_kernel;
use crate::progress::Progress;

#[derive(clap::Args)]
#[command(after_help = "\
Schemes (TopMod's remeshing menu); V, E, F, C are the input's vertices,
edges, faces and corners (C = 2E on a closed mesh):
  dual                      V'=F  E'=E  F'=V (closed meshes only)
  triangulate               non-triangles fanned from their centroid
  sqrt3 (root-3)            Kobbelt's √3, smoothed: V+F, E+C, C
  dual-vertex-truncation    √3's connectivity, unsmoothed: V+F, E+C, C
  stellate                  every face fanned: V+F, E+C, C
  double-stellate           stellate twice: V+F+C, E+4C, 3C     [--offset]
  stellate-edge-removal     stellate, old edges deleted: V+F, C, E
  modified-double-stellate  V+F+C, 2E+2C, E+C           [--height --curve]
  loop                      Loop: V+E, 2E+C, F+C (triangles: 4F)
  loop-style                Loop's connectivity, midpoints      [--length]
  dual-loop                 V+C, 2C, F+E (closed only)
  root4                     V+C, 2C, F+E: hexagons stay hexagons [--weight --twist]
  hexagon-preserving        the same operator as root4     [--weight --twist]
  dual-hexagon-preserving   V+E, 2C, F+C (closed only) [--weight --twist]
  linear-vertex-insertion   quads, linear: V+E+F, 2E+C, C
  subdivide-face            linear-vertex-insertion, or stellate with --triangles
  catmull-clark             V+E+F, 2E+C, C
  vertex-truncation         corners cut: 2E, E+C, F+V           [--offset]
  simplest                  Peters–Reif: E, C, F+V
  corner-cutting            Doo–Sabin connectivity: C, 2C, F+E+V [--alpha]
  modified-corner-cutting   faces inset: C, 2C, F+E+V        [--thickness]
  doo-sabin                 C, 2C, F+E+V
  doo-sabin-bc              2C, 4C-E, V+2E+F
  doo-sabin-bc-new          old vertices kept: V+2C, 4C-E, F+2E [--scale --length]
  honeycomb                 C, E+C, F+V
  12.6.4                    barycentric: V+E+F, 3C, 2C (closed only) [--scale]
  dual-12.6.4               omnitruncation: 2C, 2E+2C, F+E+V     [--scale]
  pentagonalization         n-gon to n pentagons: V+2E+F, 3E+C, C [--offset]
  cubic-pentagonalization   same counts, averaged (closed only)  [--offset]
  dual-pentagonalization    C, 3E+C, V+2E+F (closed only)        [--offset]
  pentagon-preserving       V+E+C, 2E+2C, F+C                     [--scale]
  dual-pentagon-preserving  V+C, 2E+2C, F+E+C (closed only)       [--scale]
  checkerboard              V+2E+C, 3E+3C, F+2C               [--thickness]
  dual-checkerboard         V+2C, 3E+3C, F+2E+C (closed only) [--thickness]
  global-extrude            every face extruded: V+C, E+2C, F+C [--length --scale]
  dual-global-extrude       the same on the dual (closed only) [--length --scale]
  dome                      V+3E+28C, 4E+56C, F+28C        [--length --scale]
  fractal                   V+E+F, 2E+2C, 2C                    [--offset]

A scheme option given to a scheme that does not read it is refused, and
so is a value out of its range (NaN, or --offset outside (0, 0.5] for
vertex-truncation, --thickness outside [0, 0.5] for checkerboard). Every
scheme keeps the genus and the boundary loops; the schemes marked closed
only refuse a mesh with a boundary. `holey subdivide` runs Catmull–Clark
and Doo–Sabin too.

Examples:
  holey remesh @cube dual.obj --scheme dual
  holey remesh @tetrahedron s.obj --scheme sqrt3 -n 3
  holey remesh @sphere:1 honey.obj --scheme honeycomb
  holey remesh @cube cc.obj --scheme corner-cutting --alpha 0.7 -n 2
  holey remesh @icosahedron t.obj --scheme 12.6.4")]
pub struct Args {
    /// Input mesh (a file or a primitive).
    pub input: String,
    /// Output file; its extension names the format.
    pub output: String,
    #[command(flatten)]
    pub options: Options,
}

/// The options besides the two files, which `holey batch remesh` shares.
#[derive(clap::Args)]
pub struct Options {
    /// The scheme (listed below), e.g. dual, sqrt3, loop, 12.6.4.
    #[arg(long, value_parser = parse_scheme)]
    pub scheme: RemeshScheme,
    /// Number of levels.
    #[arg(short = 'n', long = "levels", default_value_t = 1)]
    pub levels: usize,
    /// corner-cutting: the tension α, the weight of a corner's own vertex [default: 0.5625].
    #[arg(long, allow_hyphen_values = true)]
    pub alpha: Option<f64>,
    /// modified-corner-cutting: twice the inset distance [default: 0.25];
    /// checkerboard, dual-checkerboard: the fraction cut off each edge end [default: 0.33].
    #[arg(long, allow_hyphen_values = true)]
    pub thickness: Option<f64>,
    /// vertex-truncation: fraction of each edge cut off [default: 0.25];
    /// pentagonalization (and its variants): pull towards the centroid [default: 0];
    /// double-stellate: lift of the centres [default: 0]; fractal: apex factor [default: 1].
    #[arg(long, allow_hyphen_values = true)]
    pub offset: Option<f64>,
    /// pentagon-preserving: inner face scale [default: 0.75]; 12.6.4, dual-12.6.4:
    /// face scale [default: 0.7]; global-extrude: top scale [default: 1]; dome [default: 1];
    /// doo-sabin-bc-new: face copy scale (TopMod's sf) [default: 1].
    #[arg(long, allow_hyphen_values = true)]
    pub scale: Option<f64>,
    /// global-extrude, dual-global-extrude, dome: height in units of each face's
    /// size √(area) [default: 1]; loop-style, doo-sabin-bc-new: old vertex weight [default: 1].
    #[arg(long, allow_hyphen_values = true)]
    pub length: Option<f64>,
    /// root4, hexagon-preserving, dual-hexagon-preserving: smoothing weight [default: 0].
    #[arg(long, allow_hyphen_values = true)]
    pub weight: Option<f64>,
    /// root4, hexagon-preserving, dual-hexagon-preserving: twist along edges [default: 0].
    #[arg(long, allow_hyphen_values = true)]
    pub twist: Option<f64>,
    /// modified-double-stellate: lift of the first centres [default: 0].
    #[arg(long, allow_hyphen_values = true)]
    pub height: Option<f64>,
    /// modified-double-stellate: lift of the second centres [default: 0].
    #[arg(long, allow_hyphen_values = true)]
    pub curve: Option<f64>,
    /// subdivide-face: triangles (stellate) instead of quads.
    #[arg(long)]
    pub triangles: bool,
    /// Cut non-manifold edges and split non-manifold vertices of the input.
    #[arg(long)]
    pub split_nonmanifold: bool,
}

/// A scheme name: the library's kebab-case names (`12.6.4` and
/// `dual-12.6.4` included) and a few of TopMod's menu spellings.
pub fn parse_scheme(s: &str) -> std::result::Result<RemeshScheme, String> {
    let alias = match s.trim().to_ascii_lowercase().replace('_', "-").as_str() {
        "root3" | "root-3" | "sqrt-3" => Some(RemeshScheme::Sqrt3),
        "root-4" => Some(RemeshScheme::Root4),
        "1264" => Some(RemeshScheme::TwelveSixFour),
        "dual-1264" => Some(RemeshScheme::Dual12_6_4),
        _ => None,
    };
    match alias {
        Some(scheme) => Ok(scheme),
        None => s
            .parse()
            .map_err(|e: holey_subdiv::SubdivError| e.to_string()),
    }
}

impl Options {
    /// The library's parameters: TopMod's defaults with the options given.
    pub fn params(&self) -> Result<RemeshParams> {
        let scheme = self.scheme;
        let mut p = RemeshParams::default();
        let given = [
            ("alpha", self.alpha),
            ("thickness", self.thickness),
            ("offset", self.offset),
            ("scale", self.scale),
            ("length", self.length),
            ("weight", self.weight),
            ("twist", self.twist),
            ("height", self.height),
            ("curve", self.curve),
        ];
        for (flag, value) in given {
            let Some(value) = value else { continue };
            p.set(scheme, flag, value).map_err(|e| match e {
                SubdivError::UnknownOption { .. } => bad_input(format!(
                    "--{flag} does not apply to --scheme {scheme} (see `holey remesh --help` for what each scheme reads)"
                )),
                e => bad_input(e.to_string()),
            })?;
        }
        if self.triangles {
            if scheme != RemeshScheme::SubdivideFace {
                return Err(bad_input(format!(
                    "--triangles applies to --scheme subdivide-face only, not {scheme}"
                )));
            }
            p.subdivide_face_quads = false;
        }
        Ok(p)
    }
}

pub fn run(args: Args) -> Result<()> {
    run_file(&args.input, &args.output, &args.options)
}

/// Remeshes the mesh `input` names into the file `output`.
pub fn run_file(input: &str, output: &str, options: &Options) -> Result<()> {
    let params = options
        .params()
        .map_err(|e| bad_input(format!("{input}: {e}")))?;
    let kernel = load(input)?.into_kernel(options.split_nonmanifold)?;
    let _p = Progress::start(format!(
        "remeshing ({}), {} level(s)",
        options.scheme, options.levels
    ));
    let out = remesh(&kernel.mesh, options.scheme, &params, options.levels)
        .map_err(|e| bad_input(format!("{input}: {e}")))?;
    write_kernel(output, &out, &WriteOptions::default())
}
