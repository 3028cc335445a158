//! # holey-topo: topology change for arbitrary triangle meshes
//!
//! Bernstein & Wojtan, *Putting Holes in Holey Geometry* (SIGGRAPH 2013),
//! section 3 and appendices A–C.

#![warn(missing_docs)]

mod accumulate;
pub mod audit;
pub mod clean_solids;
mod containment;
mod coplanar;
mod correct;
mod cut;
mod drag_path;
mod engine;
mod far_field;
mod guard;
mod hidden;
pub mod internals;
pub mod intersect;
mod local;
pub mod mesh;
mod on_side;
mod orient;
mod overlaps;
mod report_json;
mod side_crossings;
pub mod snap_round;
mod solid;
pub mod solids;
#[cfg(test)]
mod test_meshes;
pub mod union;
mod union_find;
mod unzip;
mod weights;
pub mod winding;
pub mod winding_boolean;
pub mod window;
pub mod zero_area;

pub use accumulate::{Accumulator, Release};
pub use audit::SurfaceAudit;
pub use clean_solids::needs_arrangement;
pub use correct::Scheme;
pub use cut::CutReport;
pub use engine::{
    Options, Outcome, Report, Timings, TopoError, crosses_itself, resolve, self_intersections,
    topology_change,
};
pub use far_field::{EVERY_ASK_FROM, FarField};
pub use guard::{
    GuardedReport, topology_change_guarded, topology_change_guarded_holding,
    topology_change_guarded_holding_in, topology_change_guarded_if_sure,
    topology_change_guarded_if_sure_in,
};
pub use hidden::is_one_piece;
pub use intersect::{IntersectError, Intersections};
pub use local::{LocalReport, topology_change_local};
pub use mesh::{MeshError, TriMesh};
pub use overlaps::coplanar_overlaps;
pub use snap_round::SnapRounding;
pub use solids::{BooleanError, BooleanOptions, BooleanOutcome, Computed, Method, solid_boolean};
pub use union::{
    Operation, PreparedSolid, UnionError, boolean, boolean_robust, difference, intersection, union,
    union_prepared, union_robust,
};
pub use winding_boolean::{
    WindingError, WindingOutcome, WindingReport, boolean_by_winding, boolean_by_winding_robust,
};
pub use window::Window;

/// Installs a panic hook that does not print the panics holey-topo
/// raises and catches itself, and prints every other panic as the hook
/// before it did. spade's splitting constraint insertion can panic on
/// near-degenerate input; the cut stage and the coplanar overlay catch
/// that and carry on (`std::panic::catch_unwind`), but the default hook
/// would still print it as if the program had crashed. For programs
/// (the CLI, the Python module); a library leaves the hook alone.
pub fn hide_caught_triangulation_panics() {
    let previous = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let in_spade = info
            .location()
            .is_some_and(|l| l.file().contains("/spade-"));
        if !in_spade {
            previous(info);
        }
    }));
}
