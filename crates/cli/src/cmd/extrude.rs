//! `holey extrude`: TopMod's extrusions (issue 18) of one face or several.

use anyhow::Result;
use clap::ValueEnum;
use holey_dlfl::FaceId;
use holey_io::WriteOptions;
use holey_model::extrude::{
    self, DomeParams, DooSabinParams, ExtrudeParams, MultiExtrudeParams, RegionDirection,
};
use holey_model::numbering::parse_index_list;

use crate::error::bad_input;
use crate::input::load;
use crate::output::write_kernel;

/// The kind of extrusion.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Kind {
    /// Lift the face along its normal, turn and scale it, join it by quads.
    Plain,
    /// Plain, by --height times the face's mean edge length (cubes on squares).
    Cubical,
    /// Two rings of pentagons: a regular dodecahedron on a regular pentagon.
    Dodecahedral,
    /// Triangles and pentagon fans: a regular icosahedron on a triangle.
    Icosahedral,
    /// The face turned half a step and joined by triangles (an octahedron).
    Octahedral,
    /// Plain, each new ring smoothed by the Doo–Sabin face mask.
    DooSabin,
    /// Rings of quads closing over the face, finished by a cone.
    Dome,
    /// A cone: a vertex over the centroid joined to every corner.
    Stellate,
    /// A cone whose triangles are stellated again.
    DoubleStellate,
}

impl Kind {
    fn name(self) -> &'static str {
        match self {
            Kind::Plain => "plain",
            Kind::Cubical => "cubical",
            Kind::Dodecahedral => "dodecahedral",
            Kind::Icosahedral => "icosahedral",
            Kind::Octahedral => "octahedral",
            Kind::DooSabin => "doo-sabin",
            Kind::Dome => "dome",
            Kind::Stellate => "stellate",
            Kind::DoubleStellate => "double-stellate",
        }
    }

    /// The options this kind reads (besides --faces and --kind).
    fn reads(self, flag: &str) -> bool {
        match self {
            Kind::Plain => matches!(flag, "distance" | "scale" | "rotation" | "count"),
            Kind::DooSabin => matches!(flag, "distance" | "scale" | "twist" | "count"),
            Kind::Cubical => matches!(flag, "height" | "count"),
            Kind::Dome => matches!(flag, "height" | "count"),
            Kind::Dodecahedral | Kind::Icosahedral | Kind::Octahedral => flag == "height",
            Kind::Stellate | Kind::DoubleStellate => flag == "distance",
        }
    }
}

#[derive(clap::Args)]
#[command(after_help = "\
Extrudes each face of --faces (numbered in file order, as `holey info`
counts them) one after the other, or, with --together, lifts the faces
as one region so that neighbouring selected faces keep their shared
edges. Counts for a d-gon (genus and components unchanged):
  plain, doo-sabin, cubical, k times   +kd vertices, +2kd edges, +kd faces
  octahedral                           +d, +3d, +2d
  dodecahedral                         +3d, +5d, +2d
  icosahedral                          +3d, +9d, +6d
  stellate                             +1, +d, +d-1
  double-stellate                      +d+1, +4d, +3d-1
  dome of k rings                      +kd+1, +2kd+d, +kd+d-1
  --together, b boundary sides         +b, +2b, +b per repetition
So one plain extrusion of a quad adds 4/8/4.

Options per kind: plain reads --distance (default 1), --scale (1),
--rotation (degrees, 0) and --count (1); doo-sabin --distance, --scale,
--twist (0) and --count; cubical --height (times the mean edge, 1) and
--count; dome --height (times the circumradius, 1) and --count (rings,
5); dodecahedral, icosahedral and octahedral --height (1 is regular);
stellate and double-stellate --distance (the apex's lift, 0). --together
takes plain's --distance and --count, and --vertex-normals. An option
the kind does not read is refused, and so are NaN or infinite values.
A hole face, a face with a self-loop or of zero area is refused.

Examples:
  holey extrude @cube tower.obj --faces 0 --distance 1 --count 3 --scale 0.8 --rotation 15
  holey extrude @cube spikes.obj --faces 0,1,2,3,4,5 --kind stellate --distance 1
  holey extrude @dodecahedron d.obj --faces 0 --kind dodecahedral
  holey extrude @plane:4:4 slab.obj --faces 5,6,9,10 --together --distance 0.5")]
pub struct Args {
    /// Input mesh (a file or a primitive).
    pub input: String,
    /// Output file; its extension names the format.
    pub output: String,
    #[command(flatten)]
    pub options: Options,
}

/// The options besides the two files.
#[derive(clap::Args)]
pub struct Options {
    /// Faces to extrude, comma-separated, in file order.
    #[arg(long, value_name = "F[,F...]")]
    pub faces: String,
    /// The kind of extrusion.
    #[arg(long, value_enum, default_value_t = Kind::Plain)]
    pub kind: Kind,
    /// How far each repetition moves the face along its normal (plain,
    /// doo-sabin, --together); the apex's lift (stellate, double-stellate).
    #[arg(long, allow_hyphen_values = true)]
    pub distance: Option<f64>,
    /// Size of each new face relative to the one before (plain, doo-sabin).
    #[arg(long, allow_hyphen_values = true)]
    pub scale: Option<f64>,
    /// Turn of each repetition about the normal, degrees (plain).
    #[arg(long, allow_hyphen_values = true)]
    pub rotation: Option<f64>,
    /// Slide of each corner towards the next, a fraction of the edge (doo-sabin).
    #[arg(long, allow_hyphen_values = true)]
    pub twist: Option<f64>,
    /// Height as a multiple of the face's size (cubical, dome, dodecahedral,
    /// icosahedral, octahedral).
    #[arg(long, allow_hyphen_values = true)]
    pub height: Option<f64>,
    /// Repetitions (plain, doo-sabin, cubical, --together); rings (dome).
    #[arg(long)]
    pub count: Option<usize>,
    /// Lift the faces together as one region (plain only).
    #[arg(long)]
    pub together: bool,
    /// With --together: move each vertex along its own normal instead of
    /// the selection's average normal.
    #[arg(long, requires = "together")]
    pub vertex_normals: bool,
}

impl Options {
    /// Refuses options the kind does not read, before anything is done.
    fn check(&self) -> Result<()> {
        let given = [
            ("distance", self.distance.is_some()),
            ("scale", self.scale.is_some()),
            ("rotation", self.rotation.is_some()),
            ("twist", self.twist.is_some()),
            ("height", self.height.is_some()),
            ("count", self.count.is_some()),
        ];
        if self.together {
            if self.kind != Kind::Plain {
                return Err(bad_input(format!(
                    "--together extrudes plainly; it does not take --kind {}",
                    self.kind.name()
                )));
            }
            for (flag, set) in given {
                if set && !matches!(flag, "distance" | "count") {
                    return Err(bad_input(format!(
                        "--{flag} does not apply to --together (it takes --distance, --count and --vertex-normals)"
                    )));
                }
            }
            return Ok(());
        }
        for (flag, set) in given {
            if set && !self.kind.reads(flag) {
                return Err(bad_input(format!(
                    "--{flag} does not apply to --kind {} (see `holey extrude --help`)",
                    self.kind.name()
                )));
            }
        }
        Ok(())
    }
}

pub fn run(args: Args) -> Result<()> {
    run_file(&args.input, &args.output, &args.options)
}

/// Extrudes the faces of the mesh `input` names into the file `output`.
pub fn run_file(input: &str, output: &str, o: &Options) -> Result<()> {
    o.check()?;
    let numbers = parse_index_list(&o.faces, "face").map_err(bad_input)?;
    if numbers.is_empty() {
        return Err(bad_input("--faces names no face"));
    }
    let mut kernel = load(input)?.into_kernel(false)?;
    // Every id is resolved before the first extrusion, so the numbers
    // are those of the input whatever the earlier extrusions made.
    let faces = kernel
        .numbering
        .faces(&numbers)
        .map_err(|e| bad_input(format!("{input}: --faces: {e}")))?;
    if o.together {
        let params = MultiExtrudeParams {
            distance: o.distance.unwrap_or(1.0),
            direction: if o.vertex_normals {
                RegionDirection::VertexNormals
            } else {
                RegionDirection::Average
            },
            count: o.count.unwrap_or(1),
        };
        let ids: Vec<FaceId> = faces.iter().map(|&(_, f)| f).collect();
        extrude::extrude_faces(&mut kernel.mesh, &ids, &params).map_err(|e| {
            bad_input(format!(
                "{input}: faces {}: {}",
                o.faces,
                kernel.numbering.describe_extrude(&kernel.mesh, &e)
            ))
        })?;
        return write_kernel(output, &kernel.mesh, &WriteOptions::default());
    }
    for &(n, face) in &faces {
        let mesh = &mut kernel.mesh;
        let done = match o.kind {
            Kind::Plain => extrude::extrude_face(
                mesh,
                face,
                &ExtrudeParams {
                    distance: o.distance.unwrap_or(1.0),
                    rotation_deg: o.rotation.unwrap_or(0.0),
                    scale: o.scale.unwrap_or(1.0),
                    count: o.count.unwrap_or(1),
                },
            ),
            Kind::DooSabin => extrude::extrude_face_doo_sabin(
                mesh,
                face,
                &DooSabinParams {
                    distance: o.distance.unwrap_or(1.0),
                    twist: o.twist.unwrap_or(0.0),
                    scale: o.scale.unwrap_or(1.0),
                    count: o.count.unwrap_or(1),
                },
            ),
            Kind::Cubical => extrude::extrude_face_cubical(
                mesh,
                face,
                o.height.unwrap_or(1.0),
                o.count.unwrap_or(1),
            ),
            Kind::Dome => extrude::extrude_face_dome(
                mesh,
                face,
                &DomeParams {
                    height_factor: o.height.unwrap_or(1.0),
                    rings: o.count.unwrap_or(DomeParams::default().rings),
                },
            ),
            Kind::Dodecahedral => {
                extrude::extrude_face_dodecahedral(mesh, face, o.height.unwrap_or(1.0))
            }
            Kind::Icosahedral => {
                extrude::extrude_face_icosahedral(mesh, face, o.height.unwrap_or(1.0))
            }
            Kind::Octahedral => {
                extrude::extrude_face_octahedral(mesh, face, o.height.unwrap_or(1.0))
            }
            Kind::Stellate => extrude::stellate_face(mesh, face, o.distance.unwrap_or(0.0)),
            Kind::DoubleStellate => {
                extrude::double_stellate_face(mesh, face, o.distance.unwrap_or(0.0))
            }
        };
        // A refused extrusion leaves the mesh unchanged; the faces before
        // it are done, but nothing is written.
        done.map_err(|e| {
            let why = kernel.numbering.describe_extrude(&kernel.mesh, &e);
            bad_input(format!("{input}: face {n}: {why}"))
        })?;
    }
    write_kernel(output, &kernel.mesh, &WriteOptions::default())
}
