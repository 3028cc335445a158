//! `holey`: change the topology of meshes.

mod cmd;
mod error;
mod input;
mod output;
mod progress;
mod tri;

use clap::{Parser, Subcommand};

/// mimalloc keeps freed pages for reuse: the engine allocates and drops
/// several buffers of tens of megabytes per run, and with the system
/// allocator each came back as fresh pages (page faults were 15% of a
/// 524k-triangle union; see BENCHMARKS.md). Built without asking for
/// transparent huge pages (`no_thp`): each first touch of one cleared
/// 2 MB, which about doubled the resident size of mid-sized runs and made
/// their times swing by 3x, for at most a tenth saved elsewhere.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

const ABOUT: &str = "holey changes the topology of meshes: it punches holes, joins parts, grows handles and builds very high-genus shapes.";

const AFTER_HELP: &str = "\
Meshes: every argument naming an input mesh takes a file (.obj, .off, .ply,
.stl, .gltf, .glb, .3mf, .dlfl) or a built-in primitive written @name, e.g. @cube, @torus,
@sphere:3 (run `holey primitives` for the list and their parameters).
Outputs are written in the format their file extension names, atomically.

Faces and corners are numbered in file order: face i is the i-th face read
from (or written to) the file, from 0, and corner j is its j-th vertex.

Exit status: 0 on success, 2 on bad input (a malformed file, a wrong id,
a mesh the command cannot take), 1 when the system fails (disk, permissions).";

#[derive(Parser)]
#[command(name = "holey", version, about = ABOUT, after_help = AFTER_HELP)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// The main job: build a gallery of models on built-in defaults.
    Demo(cmd::demo::Args),
    /// Measure a mesh: counts, boundary, manifoldness, genus, volume.
    Info(cmd::info::Args),
    /// Convert a mesh between file formats.
    Convert(cmd::convert::Args),
    /// Write a built-in primitive to a file.
    Primitive(cmd::primitive::Args),
    /// List the built-in primitives and their parameters.
    Primitives,
    /// Generalized Sierpinski polyhedra (thesis chapter VI).
    Sierpinski(cmd::sierpinski::Args),
    /// Generalized Menger sponges (thesis chapter VII).
    Menger(cmd::menger::Args),
    /// A multi-segment curved handle between two faces (thesis chapter IV).
    Handle(cmd::handle::Args),
    /// Catmull–Clark or Doo–Sabin smoothing.
    Subdivide(cmd::subdivide::Args),
    /// TopMod's remeshing schemes: dual, √3, Loop, truncations, honeycomb, 12.6.4, …
    Remesh(cmd::remesh::Args),
    /// Extrude faces: plain, cubical, polyhedral, Doo–Sabin, dome, stellations.
    Extrude(cmd::extrude::Args),
    /// Wireframe and column modeling: a tube along every edge.
    Wireframe(cmd::wireframe::Args),
    /// Cut a vertex, edge or face off with a plane-like cut (conical tools).
    Cut(cmd::cut::Args),
    /// Truncate vertices or edges (a cut at a fraction of each edge).
    Truncate(cmd::cut::TruncateArgs),
    /// The convex hull of a mesh's vertices, or TopMod's dual convex hull.
    Hull(cmd::hull::Args),
    /// Draw a mesh to a PNG picture.
    Render(cmd::render::Args),
    /// Rind modeling: a crust with punched and peeled holes (thesis chapter V).
    Rind(cmd::rind::Args),
    /// Topology change for one frame of motion (Bernstein & Wojtan 2013).
    Topo(cmd::topo::Args),
    /// Boolean union of two solids by moving one into the other (Theorem 5.2).
    Union(cmd::union::Args),
    /// Boolean intersection A ∩ B of two closed solids.
    Intersection(cmd::boolean::Args),
    /// Boolean difference A − B of two closed solids.
    Difference(cmd::boolean::Args),
    /// Exact self-intersections: pairs, points, edges and curves.
    Selfint(cmd::selfint::Args),
    /// Cut and glue a surface along its self-intersections (the arrangement).
    Resolve(cmd::resolve::Args),
    /// Replay sculpting strokes with incidental topology change (Bernstein & Wojtan 2013, §4).
    Sculpt(cmd::sculpt::Args),
    /// The interactive modeler in the browser (model and sculpt workspaces).
    Serve(cmd::serve::Args),
    /// Run one command on many files at once: folders, glob patterns, lists.
    Batch(cmd::batch::Args),
}

fn main() {
    holey_topo::hide_caught_triangulation_panics();
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Demo(a) => cmd::demo::run(a),
        Command::Info(a) => a.run(),
        Command::Convert(a) => a.run(),
        Command::Primitive(a) => cmd::primitive::run(a),
        Command::Sierpinski(a) => a.run(),
        Command::Menger(a) => a.run(),
        Command::Handle(a) => cmd::handle::run(a),
        Command::Rind(a) => cmd::rind::run(a),
        Command::Render(a) => cmd::render::run(a),
        Command::Subdivide(a) => a.run(),
        Command::Remesh(a) => cmd::remesh::run(a),
        Command::Extrude(a) => a.run(),
        Command::Wireframe(a) => a.run(),
        Command::Cut(a) => cmd::cut::run(a),
        Command::Truncate(a) => cmd::cut::run_truncate(a),
        Command::Hull(a) => cmd::hull::run(a),
        Command::Topo(a) => cmd::topo::run(a),
        Command::Union(a) => cmd::union::run(a),
        Command::Intersection(a) => cmd::boolean::run(a, holey_topo::Operation::Intersection),
        Command::Difference(a) => cmd::boolean::run(a, holey_topo::Operation::Difference),
        Command::Selfint(a) => a.run(),
        Command::Resolve(a) => cmd::resolve::run(a),
        Command::Sculpt(a) => cmd::sculpt::run(a),
        Command::Serve(a) => cmd::serve::run(a),
        Command::Batch(a) => cmd::batch::run(a),
        Command::Primitives => output::print_stdout(holey_shapes::primitive_help()),
    };
    if let Err(e) = result {
        eprintln!("error: {e:#}");
        std::process::exit(error::exit_status(&e));
    }
}
