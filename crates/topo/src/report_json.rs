//! The engine's reports as JSON objects: one shape for every front end
//! (the CLI's `--report` files, the Python package's report dicts), so a
//! key means the same thing wherever it is read.

use serde_json::{Value, json};

use crate::engine::Report;
use crate::intersect::Intersections;
use crate::solids::{BooleanOutcome, Computed};
use crate::winding_boolean::WindingOutcome;

impl Report {
    /// The report as one JSON object: the counts of every stage (keys as
    /// the fields, the cut's flattened in) and `seconds` per stage.
    pub fn to_json(&self) -> Value {
        let (r, c) = (self, &self.cut);
        let mut report = json!({
            "collisions": r.collisions,
            "collision_tests": r.collision_tests,
            "containment_rays": r.containment_rays,
            "raw_odd_vertices": r.raw_odd_vertices,
            "corrected_odd_vertices": r.corrected_odd_vertices,
            "intersecting_pairs": r.intersecting_pairs,
            "intersection_points": r.intersection_points,
            "triple_points": r.triple_points,
            "intersection_edges": r.intersection_edges,
            "intersection_curves": r.intersection_curves,
            "curves_kept": c.curves_kept,
            "curves_dropped": c.curves_dropped,
            "false_vertices": c.false_vertices,
            "false_edges": c.false_edges,
            "triangles_split": c.triangles_split,
            "triangles_deleted": c.triangles_deleted,
            "diffused_triangles": c.diffused,
            "undecided_triangles": c.undecided,
            "dropped_constraints": c.dropped_constraints,
            "sampled_regions": c.sampled_regions,
            "junctions_repaired": c.junctions_repaired,
            "crossings_reconnected": c.crossings_reconnected,
            "opposite_pairs_cancelled": c.opposite_pairs_cancelled,
            "pinches_split": c.pinches_split,
            "solid_relabelled": c.solid_relabelled,
            "conflicting_triangles": c.conflicting,
            "constraint_splits": c.constraint_splits,
            "merged_points": c.merged_points,
            "solved_components": r.solved_components,
            "unsolved_components": r.unsolved_components,
            "perturbation_retries": r.perturbation_retries,
            "output_intersecting_pairs": r.output_intersecting_pairs,
            "solid_input": r.solid_input,
            "zero_area_removed": r.zero_area_removed,
            "orientation_flips": r.orientation_flips,
            "seconds": {
                "collisions": r.timings.collisions,
                "intersections": r.timings.intersections,
                "correction": r.timings.correction,
                "cut": r.timings.cut,
                "total": r.timings.total,
            },
        });
        // One more key than `json!` expands in one go.
        report["specks_removed"] = json!(c.specks_removed);
        report
    }
}

impl WindingOutcome {
    /// The winding-number Boolean's report as one JSON object, with
    /// `crossing`, the triangle pairs of the result that cross (the
    /// report's own count where it has one).
    pub fn report_json(&self, crossing: usize) -> Value {
        let r = &self.report;
        json!({
            "method": "winding",
            "inputs_closed": r.inputs_closed,
            "intersecting_pairs": r.intersecting_pairs,
            "intersection_points": r.intersection_points,
            "triple_points": r.triple_points,
            "intersection_curves": r.intersection_curves,
            "arrangement_triangles": r.arrangement_triangles,
            "cells": r.regions,
            "coincident_groups": r.coincident_groups,
            "rays": r.rays,
            "snapped_points": r.welded_points,
            "t_junctions_repaired": r.t_junctions_repaired,
            "coplanar_walls_merged": r.coplanar_walls_merged,
            "zero_area_removed": r.zero_area_removed,
            "unzipped_edges": r.unzipped_edges,
            "split_vertices": r.split_vertices,
            "unsampled_regions": r.unsampled_regions,
            "perturbation_retries": r.perturbation_retries,
            "snap_rounding": r.snap_rounding.map(|s| json!({
                "grid": s.grid,
                "moved_points": s.moved_points,
                "grids_tried": s.grids_tried,
                "rounds": s.rounds,
                "seconds": s.seconds,
            })),
            "unpaired_edges": r.unpaired_edges,
            "nonmanifold_edges": r.nonmanifold_edges,
            "pinched_vertices": r.pinched_vertices,
            "output_triangles": self.mesh.triangles.len(),
            "output_intersecting_pairs": crossing,
            "seconds": {
                "intersections": r.seconds.intersections,
                "cut": r.seconds.cut,
                "classify": r.seconds.classify,
                "total": r.seconds.total,
            },
        })
    }
}

impl BooleanOutcome {
    /// The report of whichever engine computed the result, with the
    /// `method` that did and the `seconds` of the whole call (the check
    /// that chose the method included) as `seconds.total`. A
    /// winding-number result whose crossings were not counted (the exact
    /// path) has them counted here, exactly; an error in that count
    /// leaves `output_intersecting_pairs` null.
    pub fn report_json(&self) -> Value {
        let mut json = match &self.computed {
            Computed::Parity(o) => o.report.to_json(),
            Computed::Winding(w) => {
                let crossing = w.report.output_intersecting_pairs.or_else(|| {
                    crate::engine::self_intersections(&w.mesh)
                        .ok()
                        .map(|x| x.pairs.len())
                });
                let mut json = w.report_json(crossing.unwrap_or(0));
                if crossing.is_none() {
                    json["output_intersecting_pairs"] = Value::Null;
                }
                json
            }
        };
        json["method"] = self.method.name().into();
        json["seconds"]["total"] = self.seconds.into();
        json
    }
}

impl Intersections {
    /// The counts of a self-intersection search of a mesh of `triangles`
    /// triangles that took `seconds`, as one JSON object: the CLI's
    /// `selfint --json` and the Python package's `self_intersections`
    /// counts.
    pub fn counts_json(&self, triangles: usize, seconds: f64) -> Value {
        json!({
            "triangles": triangles,
            "intersecting_pairs": self.pairs.len(),
            "intersection_points": self.points.len(),
            "triple_points": self.triple_points(),
            "intersection_edges": self.pieces.len(),
            "intersection_curves": self.curve_count,
            "seconds": seconds,
        })
    }
}
