//! The thesis's high-genus shapes, with their counts: a Sierpinski
//! tetrahedron (chapter VI) smoothed by Doo–Sabin, and a Menger sponge
//! (chapter VII) smoothed by Catmull–Clark, written as OBJ files.
//!
//! ```text
//! cargo run --release -p holey --example high_genus -- [LEVEL]
//! ```

use holey::model::menger::{MengerParams, menger};
use holey::model::sierpinski::sierpinski;
use holey::prelude::*;

fn write(name: &str, m: &Mesh) -> Result<(), Box<dyn std::error::Error>> {
    let poly = holey::dlfl::convert::to_poly(m).poly;
    io::write_poly(
        std::path::Path::new(name),
        &poly,
        &io::WriteOptions::default(),
    )?;
    println!(
        "{name}: V {} E {} F {}, genus {}",
        m.vertex_count(),
        m.edge_count(),
        m.face_count(),
        m.genus()
    );
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let level: usize = match std::env::args().nth(1) {
        Some(s) => s.parse().map_err(|_| format!("{s:?} is not a level"))?,
        None => 3,
    };
    let mut t = to_dlfl(&shapes::parse_primitive("@tetrahedron")?)?;
    sierpinski(&mut t, level)?;
    write("sierpinski.obj", &t)?;
    write("sierpinski-smooth.obj", &subdiv::doo_sabin(&t, 2)?)?;
    let mut cube = to_dlfl(&shapes::parse_primitive("@cube")?)?;
    menger(
        &mut cube,
        &MengerParams {
            iterations: level.min(2),
            ..MengerParams::default()
        },
    )?;
    write("menger.obj", &cube)?;
    write("menger-smooth.obj", &subdiv::catmull_clark(&cube, 1)?)?;
    Ok(())
}
