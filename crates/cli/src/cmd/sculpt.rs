//! `holey sculpt`: headless stroke replay with incidental topology change
//! (Bernstein & Wojtan 2013, §4).

use std::path::{Path, PathBuf};

use anyhow::Result;
use holey_sculpt::{SculptError, Session, StrokeFileError, parse_strokes};
use holey_topo::SurfaceAudit;

use crate::cmd::render::{options as render_options, write_picture};
use crate::error::{bad_input, from_io};
use crate::input::WeldDistance;
use crate::progress::Progress;
use crate::tri::{compact, load_triangles, load_triangles_welded, write_triangles};

#[derive(clap::Args)]
#[command(after_help = "\
Replays the strokes of a JSON file on a triangle mesh (polygons are
fan-triangulated) and writes the result. Brushes: inflate (negative
strength deflates), smooth, grab, move, snake_hook, draw, clay, crease,
flatten, pinch, scrape, scale and layer. Each path point is one frame. All but
grab and move change topology every frame where the surface
collides with itself; grab and move accumulate collisions over the drag
and change topology once, at the end of the stroke, so a drag that comes
back to where it began changes nothing.

STROKES.json:
  {\"remesh\": {\"min_edge\": 0.02, \"max_edge\": 0.06},
   \"strokes\": [
     {\"brush\": \"inflate\", \"radius\": 0.3, \"strength\": 0.02, \"path\": [[0,0,1], [0.1,0,1]]},
     {\"brush\": \"smooth\",  \"radius\": 0.3, \"strength\": 0.5,  \"path\": [[0,0,1]]},
     {\"brush\": \"grab\",    \"radius\": 0.4, \"path\": [[0,0,1], [0,0,0.5], [0,0,-1.5]]},
     {\"brush\": \"move\",    \"path\": [[2,0,0], [1.5,0,0], [1,0,0]]},
     {\"brush\": \"snake_hook\", \"radius\": 0.3, \"path\": [[1,0,0], [1.5,0,0], [1.5,0,1]]},
     {\"brush\": \"crease\", \"radius\": 0.3, \"strength\": 0.01, \"path\": [[0,0,1]],
      \"falloff\": \"sharp\", \"symmetry\": \"x\", \"mask\": {\"sphere\": {\"centre\": [0,0,-1], \"radius\": 0.5}},
      \"pressure\": [0.7]}]}

The sculptor's brushes draw, clay and crease take a strength in world
units per frame like inflate, layer the height of its plateau; flatten, scrape (in [0, 1]), pinch and scale
(in [-1, 1]) a share of the way per frame. Every stroke may give a
\"falloff\" (smooth, sphere, root, sharp, linear, constant, or
{\"custom\": [five values]}), \"symmetry\" (axes among x, y, z) with
\"symmetry_about\" (origin or centre), a \"mask\" ({\"vertices\": [...]} or a
sphere) whose vertices never move, and a \"pressure\" per path point
with \"pressure_drives\" (strength or radius), and \"frames\": how many
consecutive path points each frame paints together (the brush at each,
one topology change and remeshing for all; the modeler records the dabs
it sent in one request that way), one point a frame without it. The
snake hook pulls the part under it along the path and lets go when it
fuses with what it meets.

Strokes are numbered from 0 in errors. The first point of a grab must lie
within its radius of the surface, that of a move within 10% of the
bounding-box diagonal. After every inflate/smooth frame and every grab,
the brushed region is remeshed (splits, collapses, flips; never a
topology change) to edge lengths in \"remesh\", or without it to half to
one and a half times the input's mean edge length; --no-remesh turns
this off. On any error nothing is written to OUT (frames already written
stay).

Examples:
  holey sculpt @sphere:3 strokes.json out.obj
  holey sculpt body.ply strokes.json out.ply --frames frames/ -v")]
pub struct Args {
    /// The mesh to sculpt: a file or a primitive such as @sphere:3. It is
    /// never modified.
    pub input: String,
    /// The stroke file (JSON).
    pub strokes: String,
    /// Output file; its extension names the format.
    pub output: String,
    /// Write a PNG per frame here, named strokeSSS_frameFFFF.png.
    #[arg(long, value_name = "DIR")]
    pub frames: Option<String>,
    /// Picture size of the frames, WIDTHxHEIGHT.
    #[arg(long, default_value = "640x480")]
    pub size: String,
    /// Viewing direction of the frames (as for `holey render`).
    #[arg(long, default_value = "iso", allow_hyphen_values = true)]
    pub view: String,
    /// Print a line per stroke.
    #[arg(short, long)]
    pub verbose: bool,
    /// Do not remesh the brushed region between frames.
    #[arg(long)]
    pub no_remesh: bool,
    /// Measure the surface exactly before and after every stroke (with
    /// -v: every frame): components, boundary, non-manifold and
    /// misoriented edges, pinched vertices, degenerate triangles and intersecting triangle
    /// pairs, and name whatever got worse.
    #[arg(long)]
    pub audit: bool,
    /// Merge vertices closer than this before sculpting (a length, or a
    /// share of the bounding-box diagonal such as 0.01%; 0 merges
    /// identical positions): unwelded patch seams then move as one.
    #[arg(long, value_name = "DIST")]
    pub weld: Option<WeldDistance>,
}

pub fn run(args: Args) -> Result<()> {
    // Everything that can be checked before sculpting is: the output
    // format, the stroke file and the mesh.
    holey_io::Format::from_path(Path::new(&args.output)).map_err(from_io)?;
    let text = std::fs::read_to_string(&args.strokes).map_err(|e| {
        if e.kind() == std::io::ErrorKind::NotFound || e.kind() == std::io::ErrorKind::InvalidData {
            bad_input(format!("{}: {e}", args.strokes))
        } else {
            anyhow::anyhow!("{}: {e}", args.strokes)
        }
    })?;
    let file = parse_strokes(&text)
        .map_err(|e: StrokeFileError| bad_input(format!("{}: {e}", args.strokes)))?;
    let opts = render_options(&args.size, &args.view, "z", false, false)?;
    let mesh = match args.weld {
        Some(d) => load_triangles_welded(&args.input, d)?,
        None => load_triangles(&args.input)?,
    };
    let mut session = Session::new(mesh).map_err(|e| bad_input(format!("{}: {e}", args.input)))?;
    session.set_remeshing(!args.no_remesh);
    let frames_dir = match &args.frames {
        Some(dir) => {
            std::fs::create_dir_all(dir).map_err(|e| anyhow::anyhow!("{dir}: {e}"))?;
            Some(PathBuf::from(dir))
        }
        None => None,
    };
    let audit = |mesh: &holey_topo::TriMesh| {
        SurfaceAudit::of(mesh).map_err(|e| anyhow::anyhow!("audit: {e}"))
    };
    let mut audits = Vec::new();
    if args.audit {
        audits.push(audit(session.mesh())?);
        eprintln!("input: {}", audits[0]);
    }
    let reports = {
        let _p = Progress::start(format!("sculpting {} strokes", file.strokes.len()));
        let mut previous = audits.first().copied();
        session
            .replay(&file, &mut |stroke, frame| {
                if args.audit && args.verbose {
                    let now = SurfaceAudit::of(frame.mesh).map_err(|e| e.to_string())?;
                    // A grab or move changes topology once, at the release
                    // (its last frame): until then the dragged surface may
                    // pass through itself, which the release resolves, so
                    // those frames are shown but not judged, and the
                    // release is judged against the surface before the drag.
                    let dragging = file
                        .strokes
                        .get(stroke)
                        .is_some_and(|s| s.brush.is_drag() && frame.index + 1 < s.path.len());
                    if dragging {
                        eprintln!(
                            "stroke {stroke} frame {} (dragging, before the release): {now}",
                            frame.index
                        );
                    } else {
                        let worse = previous.map(|p| p.regressions(&now)).unwrap_or_default();
                        eprintln!(
                            "stroke {stroke} frame {}: {now}{}",
                            frame.index,
                            if worse.is_empty() {
                                String::new()
                            } else {
                                format!(" [worse: {}]", worse.join(", "))
                            }
                        );
                        previous = Some(now);
                    }
                }
                if let Some(dir) = &frames_dir {
                    let path = dir.join(format!("stroke{stroke:03}_frame{:04}.png", frame.index));
                    write_picture(&path.to_string_lossy(), &compact(frame.mesh), &opts)
                        .map_err(|e| e.to_string())?;
                }
                Ok(())
            })
            .map_err(|e| {
                // A frame that could not be written is the system's fault
                // (status 1); anything else is the input's (status 2).
                let system = matches!(&e, SculptError::Stroke { source, .. }
                    if matches!(**source, SculptError::Observer { .. }));
                if system {
                    anyhow::anyhow!("{}: {e}", args.strokes)
                } else {
                    bad_input(format!("{}: {e}", args.strokes))
                }
            })?
    };
    write_triangles(&args.output, session.mesh())?;
    if args.audit {
        let after = audit(session.mesh())?;
        let worse = audits[0].regressions(&after);
        eprintln!("output: {after}");
        if !worse.is_empty() {
            eprintln!("worse than the input: {}", worse.join(", "));
        }
    }
    if args.verbose {
        for (i, r) in reports.iter().enumerate() {
            let brush = r.brush.map(|b| b.name()).unwrap_or("?");
            eprintln!(
                "stroke {i} ({brush}): {} frame(s), {} engine run(s), {} topology change(s), {} remeshing operation(s), {} guarded frame(s) ({} held whole, {} vertex-frames held), {} sub-frame split(s), {} whole-mesh frame(s), {} speck(s) of debris taken out, {} -> {} triangles, {:.3} s",
                r.frames,
                r.engine_runs,
                r.changes,
                r.remesh_operations,
                r.guarded_frames,
                r.held_frames,
                r.held_vertices,
                r.subframes,
                r.whole_mesh_frames,
                r.specks_removed,
                r.triangles_before,
                r.triangles_after,
                r.seconds
            );
            if !r.held_because.is_empty() {
                eprintln!(
                    "stroke {i} ({brush}) held frames that would have left {}",
                    r.held_because.join(", ")
                );
            }
            if !r.refused.is_empty() {
                eprintln!(
                    "stroke {i} ({brush}) was undone: it would have left {}",
                    r.refused.join(", ")
                );
            }
        }
    }
    Ok(())
}
