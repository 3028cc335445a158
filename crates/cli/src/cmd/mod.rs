//! One module per command.

pub mod batch;
pub mod boolean;
pub mod convert;
pub mod cut;
pub mod demo;
pub mod extrude;
pub mod handle;
pub mod hull;
pub mod info;
pub mod menger;
pub mod primitive;
pub mod remesh;
pub mod render;
pub mod resolve;
pub mod rind;
pub mod sculpt;
pub mod selfint;
pub mod serve;
pub mod sierpinski;
pub mod subdivide;
pub mod topo;
pub mod union;
pub mod winding;
pub mod wireframe;

/// A command that reads one mesh and writes one file, and that `holey
/// batch` can run on many files: its options are the clap struct that
/// implements this, flattened both into the command run alone
/// ([`FileArgs`]) and into its batch subcommand, so both parse the same
/// flags and run the same [`MeshToFile::run_file`].
pub trait MeshToFile: clap::Args {
    /// The input argument's help: what kind of mesh the command takes.
    const INPUT: &'static str;
    /// What `--help` prints after the options: what the command does,
    /// what it refuses, examples.
    const AFTER_HELP: &'static str;
    /// Runs on the mesh `input` names and writes the result to `output`.
    fn run_file(&self, input: &str, output: &str) -> anyhow::Result<()>;
}

/// The arguments of a [`MeshToFile`] command run alone: the two files,
/// then the command's options.
#[derive(clap::Args)]
#[command(after_help = O::AFTER_HELP)]
pub struct FileArgs<O: MeshToFile> {
    #[arg(help = O::INPUT)]
    pub input: String,
    /// Output file; its extension names the format.
    pub output: String,
    #[command(flatten)]
    pub options: O,
}

impl<O: MeshToFile> FileArgs<O> {
    pub fn run(self) -> anyhow::Result<()> {
        self.options.run_file(&self.input, &self.output)
    }
}

/// A command that reads one mesh and prints what it finds, and that
/// `holey batch` can run on many files (printing JSON lines instead): its
/// options are the clap struct that implements this, flattened into the
/// command run alone ([`ReportArgs`]) and into its batch subcommand.
pub trait MeshReport: clap::Args {
    /// The mesh argument's help.
    const MESH: &'static str;
    /// What `--help` prints after the options.
    const AFTER_HELP: &'static str;
    /// Prints the report on the mesh `mesh` names.
    fn report(&self, mesh: &str) -> anyhow::Result<()>;
}

/// The arguments of a [`MeshReport`] command run alone: the mesh, then the
/// command's options.
#[derive(clap::Args)]
#[command(after_help = O::AFTER_HELP)]
pub struct ReportArgs<O: MeshReport> {
    #[arg(help = O::MESH)]
    pub mesh: String,
    #[command(flatten)]
    pub options: O,
}

impl<O: MeshReport> ReportArgs<O> {
    pub fn run(self) -> anyhow::Result<()> {
        self.options.report(&self.mesh)
    }
}
