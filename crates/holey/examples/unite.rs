//! Unites two solids and writes the result, by the method
//! [`holey::topo::solid_boolean`] chooses: containment parity
//! (Theorem 5.2) when both are clean closed solids, the winding number
//! when either is open, crosses itself or has nested shells.
//!
//! ```text
//! cargo run --release -p holey --example unite -- [A B] [OUT.obj]
//! ```
//!
//! Without arguments it unites two overlapping icospheres.

use std::path::Path;

use holey::prelude::*;

fn load(name: &str) -> Result<TriMesh, Box<dyn std::error::Error>> {
    let soup = if let Some(spec) = name.strip_prefix('@') {
        shapes::parse_primitive(&format!("@{spec}"))?
    } else {
        match io::read_path(std::path::Path::new(name))? {
            io::MeshFile::Poly(p) => p,
            io::MeshFile::Dlfl(_) => {
                return Err(format!("{name}: a .dlfl file; export it as polygons").into());
            }
        }
    };
    Ok(triangles(&soup))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (a, mut b, path) = match args.as_slice() {
        [a, b, path] => (load(a)?, load(b)?, path.clone()),
        [] => (
            load("@sphere:4")?,
            load("@sphere:4")?,
            "union.obj".to_string(),
        ),
        _ => return Err("usage: unite [A B OUT]".into()),
    };
    if args.is_empty() {
        for p in &mut b.positions {
            *p += DVec3::new(0.9, 0.3, 0.2);
        }
    }
    // The library chooses: containment parity for clean solids, the
    // winding number for anything else.
    let out = topo::solid_boolean(&[&a, &b], topo::Operation::Union, &Default::default())?;
    println!(
        "by {}: {:.3} s, {} nudges",
        out.method.name(),
        out.seconds,
        out.perturbation_retries()
    );
    let mesh = out.into_mesh();
    let options = io::WriteOptions::default();
    io::write_poly(Path::new(&path), &PolyMesh::from(&mesh), &options)?;
    println!(
        "{path}: {} triangles, closed: {}",
        mesh.triangles.len(),
        mesh.is_closed_manifold()
    );
    Ok(())
}
