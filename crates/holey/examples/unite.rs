//! Unites solids and writes the result: by containment parity
//! (Theorem 5.2) when both are clean closed solids, by the winding number
//! when either is open or crosses itself.
//!
//! ```text
//! cargo run --release -p holey --example unite -- [A B] [OUT.obj]
//! ```
//!
//! Without arguments it unites two overlapping icospheres.

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
    let (a, mut b, out) = match args.as_slice() {
        [a, b, out] => (load(a)?, load(b)?, out.clone()),
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
    let options = topo::Options::default();
    let mesh = if topo::needs_arrangement(&a, &b)? {
        let out = topo::boolean_by_winding_robust(&[&a, &b], topo::Operation::Union, &options)?;
        println!("by the winding number: {} cells", out.report.regions);
        out.mesh
    } else {
        let out = topo::union_robust(&a, &b, &options)?;
        println!(
            "by containment parity: {} intersecting pairs, {} curves",
            out.report.intersecting_pairs, out.report.intersection_curves
        );
        out.mesh
    };
    let poly = PolyMesh::from_faces(mesh.positions.clone(), mesh.triangles.iter());
    io::write_poly(
        std::path::Path::new(&out),
        &poly,
        &io::WriteOptions::default(),
    )?;
    println!(
        "{out}: {} triangles, closed: {}",
        mesh.triangles.len(),
        mesh.is_closed_manifold()
    );
    Ok(())
}
