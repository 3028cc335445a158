//! `holey render`: a picture of a mesh.

use std::path::Path;

use anyhow::Result;
use holey_dlfl::Mesh;
use holey_dlfl::convert::to_poly;
use holey_mesh::PolyMesh;
use holey_render::{RenderOptions, Up, View, parse_size, render};

use crate::error::{bad_input, from_io};
use crate::input::{Input, load};
use crate::progress::Progress;

#[derive(clap::Args)]
#[command(after_help = "\
Draws the mesh with a CPU rasterizer (z-buffer, faceted or smooth
shading, anti-aliased), framed automatically. Back faces are tinted so
holes and inside-out regions read. The same input always gives the same
picture, byte for byte.

Views: iso (default), front, back, left, right, top, bottom, or a
direction x,y,z from the model towards the camera. --up y suits files
modelled y-up (most OBJ characters); the default is z-up.

Examples:
  holey render @torus torus.png --edges
  holey render bunny.obj bunny.png --up y --smooth --size 1024x768
  holey render sponge.obj sponge.png --view 1,1,1")]
pub struct Args {
    /// The mesh: a file or a primitive such as @torus.
    pub mesh: String,
    /// The PNG to write.
    pub output: String,
    /// Picture size, WIDTHxHEIGHT.
    #[arg(long, default_value = "800x600")]
    pub size: String,
    /// Viewing direction.
    #[arg(long, default_value = "iso", allow_hyphen_values = true)]
    pub view: String,
    /// Which axis points up: z or y.
    #[arg(long, default_value = "z")]
    pub up: String,
    /// Draw polygon edges.
    #[arg(long)]
    pub edges: bool,
    /// Smooth shading instead of faceted.
    #[arg(long)]
    pub smooth: bool,
}

/// The rendering options of the command line's flags.
pub fn options(
    size: &str,
    view: &str,
    up: &str,
    edges: bool,
    smooth: bool,
) -> Result<RenderOptions> {
    let (width, height) = parse_size(size).map_err(|e| bad_input(e.to_string()))?;
    Ok(RenderOptions {
        width,
        height,
        view: View::parse(view).map_err(|e| bad_input(e.to_string()))?,
        up: up.parse::<Up>().map_err(|e| bad_input(e.to_string()))?,
        edges,
        smooth,
        ..RenderOptions::default()
    })
}

/// Renders a soup and writes the PNG atomically.
pub fn write_picture(path: &str, soup: &PolyMesh, opts: &RenderOptions) -> Result<()> {
    let image = render(soup, opts).map_err(|e| bad_input(format!("{path}: {e}")))?;
    let bytes = image
        .encode_png()
        .map_err(|e| anyhow::anyhow!("{path}: {e}"))?;
    holey_io::write_bytes_atomic(Path::new(path), &bytes).map_err(from_io)
}

/// Renders a DLFL as its written soup (self-loops dropped).
pub fn write_kernel_picture(path: &str, mesh: &Mesh, opts: &RenderOptions) -> Result<()> {
    write_picture(path, &to_poly(mesh).poly, opts)
}

pub fn run(args: Args) -> Result<()> {
    if !args.output.to_ascii_lowercase().ends_with(".png") {
        return Err(bad_input(format!(
            "{}: the picture must be a .png file",
            args.output
        )));
    }
    let opts = options(&args.size, &args.view, &args.up, args.edges, args.smooth)?;
    let loaded = load(&args.mesh)?;
    let _p = Progress::start(format!("rendering {}", args.mesh));
    match loaded.input {
        Input::Soup(ref soup) => write_picture(&args.output, soup, &opts),
        Input::Dlfl(_) => {
            let kernel = loaded.into_kernel(false)?;
            write_kernel_picture(&args.output, &kernel.mesh, &opts)
        }
    }
}
