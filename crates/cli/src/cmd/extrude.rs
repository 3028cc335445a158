//! `holey extrude`: TopMod's extrusions (issue 18) of one face or several.

use anyhow::Result;
use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
use holey_io::WriteOptions;
use holey_model::extrude::{
    ExtrudeError, ExtrudeKind, ExtrudeOptions, RegionDirection, extrude_selection,
};
use holey_model::numbering::parse_index_list;

use crate::cmd::{FileArgs, MeshToFile};
use crate::error::bad_input;
use crate::input::load;
use crate::output::write_kernel;

/// `--kind`: the library's kinds, with their names and summaries.
fn kind_parser() -> impl TypedValueParser<Value = ExtrudeKind> {
    PossibleValuesParser::new(
        ExtrudeKind::ALL.map(|k| PossibleValue::new(k.name()).help(k.summary())),
    )
    .try_map(|name| name.parse::<ExtrudeKind>())
}

const AFTER_HELP: &str = "\
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
  holey extrude @plane:4:4 slab.obj --faces 5,6,9,10 --together --distance 0.5";

pub type Args = FileArgs<Options>;

/// The options besides the two files.
#[derive(clap::Args)]
pub struct Options {
    /// Faces to extrude, comma-separated, in file order.
    #[arg(long, value_name = "F[,F...]")]
    pub faces: String,
    /// The kind of extrusion.
    #[arg(long, value_parser = kind_parser(), default_value = "plain")]
    pub kind: ExtrudeKind,
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
    /// The options as the library takes them.
    fn library(&self) -> ExtrudeOptions {
        ExtrudeOptions {
            distance: self.distance,
            scale: self.scale,
            rotation_deg: self.rotation,
            twist: self.twist,
            height: self.height,
            count: self.count,
            together: self
                .together
                .then_some(RegionDirection::from_vertex_normals(self.vertex_normals)),
        }
    }
}

/// An option refusal in the words of this command's flags; `None` for
/// any other refusal.
fn flag_refusal(e: &ExtrudeError) -> Option<String> {
    Some(match e {
        ExtrudeError::TogetherNotPlain(kind) => {
            format!("--together extrudes plainly; it does not take --kind {kind}")
        }
        ExtrudeError::UnreadTogether { option } => format!(
            "--{option} does not apply to --together (it takes --distance, --count and --vertex-normals)"
        ),
        ExtrudeError::Unread { option, kind } => {
            format!("--{option} does not apply to --kind {kind} (see `holey extrude --help`)")
        }
        _ => return None,
    })
}

impl MeshToFile for Options {
    /// Extrudes the faces of the mesh `input` names into the file `output`.
    fn run_file(&self, input: &str, output: &str) -> Result<()> {
        let options = self.library();
        // Refused before the input is read.
        options
            .check(self.kind)
            .map_err(|e| bad_input(flag_refusal(&e).unwrap_or_else(|| e.to_string())))?;
        let numbers = parse_index_list(&self.faces, "face").map_err(bad_input)?;
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
        let ids: Vec<_> = faces.iter().map(|&(_, f)| f).collect();
        // A refusal leaves the mesh unchanged, and nothing is written; one by
        // one, it names the face refused.
        extrude_selection(&mut kernel.mesh, &ids, self.kind, &options).map_err(|e| {
            let why = kernel.numbering.describe_extrude(&kernel.mesh, &e);
            if self.together {
                bad_input(format!("{input}: faces {}: {why}", self.faces))
            } else {
                bad_input(format!("{input}: {why}"))
            }
        })?;
        write_kernel(output, &kernel.mesh, &WriteOptions::default())
    }

    const INPUT: &str = "Input mesh (a file or a primitive)";
    const AFTER_HELP: &str = AFTER_HELP;
}
