//! `holey primitive`: write a built-in primitive.

use anyhow::Result;
use holey_io::WriteOptions;

use crate::error::bad_input;
use crate::output::write_soup;

#[derive(clap::Args)]
#[command(after_help = "\
Every command that reads a mesh also accepts a primitive in its place,
written @name (for example `holey info @torus`).

Examples:
  holey primitive cube cube.obj
  holey primitive @sphere:4 sphere.ply
  holey primitive torus:32:16 torus.dlfl")]
pub struct Args {
    /// The primitive, with or without the leading @ (see `holey primitives`).
    pub name: String,
    /// Output file; its extension names the format.
    pub output: String,
    /// Write PLY or STL as text instead of binary.
    #[arg(long)]
    pub ascii: bool,
}

pub fn run(args: Args) -> Result<()> {
    let spec = if args.name.starts_with('@') {
        args.name.clone()
    } else {
        format!("@{}", args.name)
    };
    let soup =
        holey_shapes::parse_primitive(&spec).map_err(|e| bad_input(format!("{spec}: {e}")))?;
    let opts = WriteOptions {
        ascii: args.ascii,
        ..WriteOptions::default()
    };
    write_soup(&args.output, &soup, &opts, false)
}
