//! `holey info`: measure a mesh.

use crate::output::print_stdout;
use anyhow::Result;
use holey_dlfl::dlfl_info;
use holey_mesh::analysis::{MeshInfo, analyze, weld_exact};

use crate::cmd::{MeshReport, ReportArgs};
use crate::input::{Input, load};

const AFTER_HELP: &str = "\
Counts are of the mesh as stored: vertex indices as in the file, and
unreferenced vertices not counted. For a .dlfl file they are of the DLFL
structure itself: every edge record (self-loops and multiple edges
included), faces without the holes, and holes as boundary loops.

genus is the sum over components of (2 - χᵢ - bᵢ)/2, given only for a
manifold, consistently oriented mesh; volume only for a closed one.

Examples:
  holey info bunny.obj
  holey info scene.glb            # the default scene's meshes, placed
  holey info --json @torus
  holey info --weld soup.stl      # measure after merging identical positions";

pub type Args = ReportArgs<Options>;

/// The options besides the mesh, which `holey batch info` shares.
#[derive(clap::Args)]
pub struct Options {
    /// Print one JSON object instead of text.
    #[arg(long)]
    pub json: bool,
    /// Merge vertices with bit-identical positions before measuring.
    #[arg(long)]
    pub weld: bool,
}

impl MeshReport for Options {
    fn report(&self, mesh: &str) -> Result<()> {
        let info = measure(mesh, self)?;
        if self.json {
            print_stdout(&(serde_json::to_string_pretty(&info)? + "\n"))?;
        } else {
            print_stdout(&render_text(mesh, &info))?;
        }
        Ok(())
    }

    const MESH: &str = "The mesh: a file (OBJ, OFF, PLY, STL, glTF .gltf/.glb, 3MF, .dlfl) or a primitive such as @cube";
    const AFTER_HELP: &str = AFTER_HELP;
}

/// What `holey info` prints of the mesh `mesh` names.
pub fn measure(mesh: &str, options: &Options) -> Result<MeshInfo> {
    let loaded = load(mesh)?;
    Ok(match &loaded.input {
        Input::Soup(soup) if options.weld => analyze(&weld_exact(soup)),
        Input::Soup(soup) => analyze(soup),
        Input::Dlfl(_) => dlfl_info(&loaded.into_kernel(false)?.mesh),
    })
}

fn yes(b: bool) -> &'static str {
    if b { "yes" } else { "no" }
}

/// A measure, or a dash and why the mesh has none.
fn or_why(value: Option<impl ToString>, why: &str) -> String {
    value.map_or_else(|| format!("- ({why})"), |v| v.to_string())
}

/// The human-readable report.
pub fn render_text(name: &str, i: &MeshInfo) -> String {
    let sizes: Vec<String> = i
        .face_sizes
        .iter()
        .map(|(k, v)| format!("{k}-gons: {v}"))
        .collect();
    let mut s = String::new();
    s += &format!("mesh:          {name}\n");
    s += &format!("vertices:      {}", i.vertices);
    if i.unreferenced_vertices > 0 {
        s += &format!(" (+{} unreferenced)", i.unreferenced_vertices);
    }
    s += "\n";
    s += &format!("edges:         {}\n", i.edges);
    s += &format!("faces:         {} ({})\n", i.faces, sizes.join(", "));
    s += &format!("components:    {}\n", i.components);
    s += &format!(
        "closed:        {} ({} boundary edges in {} loops)\n",
        yes(i.closed),
        i.boundary_edges,
        i.boundary_loops
    );
    s += &format!(
        "manifold:      {} ({} non-manifold edges, {} non-manifold vertices)\n",
        yes(i.manifold),
        i.nonmanifold_edges,
        i.nonmanifold_vertices
    );
    s += &format!(
        "oriented:      {} ({} misoriented edges)\n",
        yes(i.oriented),
        i.misoriented_edges
    );
    s += &format!("euler:         {}\n", i.euler);
    let genus = or_why(i.genus, "needs a manifold, oriented mesh");
    s += &format!("genus:         {genus}\n");
    s += &format!(
        "degenerate:    {} self-loops, {} two-gons, {} point-spheres\n",
        i.self_loops, i.two_gons, i.point_spheres
    );
    if let Some([lo, hi]) = i.bbox {
        s += &format!(
            "bbox:          [{}, {}, {}] .. [{}, {}, {}]\n",
            lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]
        );
    }
    s += &format!("area:          {}\n", i.area);
    let volume = or_why(i.volume, "needs a closed, oriented mesh");
    s += &format!("volume:        {volume}\n");
    s
}
