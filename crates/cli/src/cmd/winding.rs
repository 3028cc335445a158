//! The output of the winding-number Booleans behind `holey union`,
//! `intersection` and `difference` (the library's choice,
//! [`holey_topo::solid_boolean`], when an input crosses itself, when there
//! are more than two inputs or one, or with `--winding`), its result
//! checked for crossings (a result that crosses itself is written, but
//! never silently).

use anyhow::Result;
use holey_topo::WindingOutcome;

use crate::cmd::topo::EngineArgs;
use crate::error::bad_input;
use crate::tri::{write_json, write_triangles};

/// Writes the winding-number Boolean `out` of the inputs `names` to
/// `output`, the report where `engine` says, with a note for each open
/// input and a warning for an open or self-crossing result.
pub fn write(
    out: &WindingOutcome,
    names: &[&str],
    output: &str,
    engine: &EngineArgs,
) -> Result<()> {
    for (name, closed) in names.iter().zip(&out.report.inputs_closed) {
        if !closed {
            eprintln!(
                "note: {name} is not closed: inside it means a generalized winding number of at least 1/2 (Jacobson et al. 2013)"
            );
        }
    }
    let crossing = match out.report.output_intersecting_pairs {
        Some(n) => n,
        None => holey_topo::self_intersections(&out.mesh)
            .map(|x| x.pairs.len())
            .map_err(|e| bad_input(e.to_string()))?,
    };
    write_triangles(output, &out.mesh)?;
    if let Some(path) = &engine.report {
        write_json(path, &out.report_json(crossing))?;
    }
    if engine.verbose {
        eprint!("{}", report_text(out, crossing));
    }
    if out.report.unpaired_edges > 0 && out.report.inputs_closed.iter().all(|&c| c) {
        eprintln!(
            "warning: the result is not closed: {} edges have no partner (constructed points that should meet an input vertex rounded a few ulps from it)",
            out.report.unpaired_edges
        );
    }
    if crossing > 0 {
        eprintln!(
            "warning: {crossing} triangle pairs of the result cross (coplanar faces that touch kept as a wall of no thickness, or points rounded past a sheet); its volume and inside are still the winding-number rule's"
        );
    }
    Ok(())
}

fn report_text(out: &WindingOutcome, crossing: usize) -> String {
    let r = &out.report;
    let snapped = r.snap_rounding.map_or(String::new(), |s| {
        format!(
            "snap-rounded: {} points moved onto a grid of {:e} ({} grids, {} rounds on the last; {:.3} s)\n",
            s.moved_points, s.grid, s.grids_tried, s.rounds, s.seconds
        )
    });
    snapped
        + &format!(
            "winding-number arrangement: {} intersecting pairs, {} curves, {} triangles in {} cells ({} coincident groups), {} rays\n\
         result: {} triangles, {} unpaired edges, {} crossing pairs; {:.3} s (intersections {:.3}, cut {:.3}, classify {:.3})\n",
            r.intersecting_pairs,
            r.intersection_curves,
            r.arrangement_triangles,
            r.regions,
            r.coincident_groups,
            r.rays,
            out.mesh.triangles.len(),
            r.unpaired_edges,
            crossing,
            r.seconds.total,
            r.seconds.intersections,
            r.seconds.cut,
            r.seconds.classify,
        )
}
