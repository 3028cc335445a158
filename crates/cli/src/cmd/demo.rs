//! `holey demo`: the main job on built-in defaults. It builds a gallery of
//! models from the built-in primitives, writes each one, and prints a table.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, Result};
use holey_dlfl::Mesh;
use holey_io::WriteOptions;
use holey_mesh::convert::{ImportOptions, to_dlfl};

use crate::error::bad_input;
use crate::output::write_kernel;

#[derive(clap::Args)]
#[command(after_help = "\
Writes each model as .obj and .dlfl into the output folder and prints a
table of V/E/F, genus and the time each took.

Examples:
  holey demo
  holey demo --out /tmp/gallery")]
pub struct Args {
    /// Folder to write the gallery into (created if missing).
    #[arg(long, default_value = "holey-demo")]
    pub out: PathBuf,
}

/// One model of the gallery.
struct Model {
    name: &'static str,
    what: &'static str,
    build: fn() -> Result<Mesh>,
}

fn primitive(spec: &str) -> Result<Mesh> {
    let soup =
        holey_shapes::parse_primitive(spec).map_err(|e| bad_input(format!("{spec}: {e}")))?;
    let imported =
        to_dlfl(&soup, ImportOptions::default()).map_err(|e| bad_input(format!("{spec}: {e}")))?;
    Ok(imported.mesh)
}

fn models() -> Vec<Model> {
    vec![
        Model {
            name: "tetrahedron",
            what: "@tetrahedron",
            build: || primitive("@tetrahedron"),
        },
        Model {
            name: "cube",
            what: "@cube",
            build: || primitive("@cube"),
        },
        Model {
            name: "octahedron",
            what: "@octahedron",
            build: || primitive("@octahedron"),
        },
        Model {
            name: "dodecahedron",
            what: "@dodecahedron",
            build: || primitive("@dodecahedron"),
        },
        Model {
            name: "icosahedron",
            what: "@icosahedron",
            build: || primitive("@icosahedron"),
        },
        Model {
            name: "sphere",
            what: "@sphere:3",
            build: || primitive("@sphere:3"),
        },
        Model {
            name: "torus",
            what: "@torus",
            build: || primitive("@torus"),
        },
        Model {
            name: "cylinder",
            what: "@cylinder",
            build: || primitive("@cylinder"),
        },
        Model {
            name: "plane",
            what: "@plane (open: one hole face)",
            build: || primitive("@plane"),
        },
    ]
}

/// A row of the printed table.
struct Row {
    name: &'static str,
    what: &'static str,
    v: usize,
    e: usize,
    f: usize,
    genus: i64,
    ms: f64,
}

pub fn run(args: Args) -> Result<()> {
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("creating {}", args.out.display()))?;
    let mut rows = Vec::new();
    let total = Instant::now();
    for model in models() {
        let start = Instant::now();
        let mesh = (model.build)()?;
        let ms = start.elapsed().as_secs_f64() * 1e3;
        mesh.validate()
            .with_context(|| format!("{} is not a valid DLFL", model.name))?;
        write_model(&args.out, model.name, &mesh)?;
        let t = mesh.topology();
        rows.push(Row {
            name: model.name,
            what: model.what,
            v: mesh.vertex_count(),
            e: mesh.edge_count(),
            f: mesh.face_count() - mesh.hole_count(),
            genus: t.genus(),
            ms,
        });
    }
    println!(
        "{:<14} {:>8} {:>8} {:>8} {:>6} {:>9}  made from",
        "model", "V", "E", "F", "genus", "ms"
    );
    for r in &rows {
        println!(
            "{:<14} {:>8} {:>8} {:>8} {:>6} {:>9.2}  {}",
            r.name, r.v, r.e, r.f, r.genus, r.ms, r.what
        );
    }
    eprintln!(
        "wrote {} models to {} in {:.2} s",
        rows.len(),
        args.out.display(),
        total.elapsed().as_secs_f64()
    );
    Ok(())
}

fn write_model(dir: &Path, name: &str, mesh: &Mesh) -> Result<()> {
    for ext in ["obj", "dlfl"] {
        let path = dir.join(format!("{name}.{ext}"));
        let path = path.to_str().context("output path is not UTF-8")?;
        write_kernel(path, mesh, &WriteOptions::default())?;
    }
    Ok(())
}
