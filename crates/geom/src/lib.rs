//! Exact geometry under holey's topology-change engine (Bernstein & Wojtan
//! 2013, *Putting Holes in Holey Geometry*, §3.2–3.3 and appendix A).
//!
//! Everything here answers questions about **one perturbed world**: every
//! input point carries an identity ([`SymPoint`]), points are perturbed
//! symbolically by simulation of simplicity (Edelsbrunner & Mücke 1990,
//! [`sos`]), and every predicate is the exact sign of a polynomial in that
//! world. There is no epsilon anywhere: large, tiny and offset coordinates
//! behave alike (the paper's prototype perturbs by an absolute 10⁻⁵, which
//! fails once coordinates reach 4096 on its 30-bit grid).
//!
//! | module | what |
//! |---|---|
//! | [`orient`] | `orient2d`/`orient3d` exact (Shewchuk's adaptive filters via `robust`) and with SoS (the derived 14-term sequence) |
//! | [`identity`] | identities by exact position class (welded in the perturbed world) or by index |
//! | [`intersect`] | segment × triangle, triangle × triangle segment, triple points, order of crossings along a segment |
//! | [`construct`] | coordinates and barycentric coordinates of edge × triangle and triple points, correctly rounded from exact values |
//! | [`distance`] | floating-point point–segment distance, for brushes and for filters in front of the exact tests |
//! | [`dd`] | double-double values with error bounds: the certified fast path of the constructions (bit-identical results, exact fallback) |
//! | [`bvh`] | median-split BVH: box queries, streamed batches, self-overlap, refit |
//! | [`frame`] | the frame in which a turned CAD mesh's triangle boxes are tight (its dominant normal and edge direction), each box widened by its rounding bound |
//! | [`ccd`] | vertex–triangle continuous collision: the paper's float cubic, the exact root parity, the parallel broad phase |
//! | [`sos`], [`ring`], [`expansion`] | the machinery: generic predicate polynomials evaluated in intervals, exact expansions and perturbation polynomials |
//!
//! # Rules for callers (the static-intersection engine)
//!
//! - Give coincident points the same identity when they are the same point
//!   (use [`identity::position_classes`] on a soup), different identities
//!   otherwise. Identities must be consistent across all calls of one
//!   computation: the perturbation is a global function of the identity.
//! - A segment sharing an identity with a triangle's corner never crosses
//!   it; two triangles sharing an edge do not intersect; a triple point is
//!   never a shared vertex ([`intersect`]).
//! - Predicates never fail and never return "zero" except
//!   [`SosSign::Degenerate`] for shared identities. Constructions return
//!   `Result` ([`GeomError`]) because a point may not exist.
//!
//! Inputs must be finite (bulk APIs check and return
//! [`GeomError::NonFinite`]; single predicates given NaN answer arbitrarily
//! but never panic).

#![warn(missing_docs)]

pub mod bvh;
pub mod ccd;
pub mod construct;
pub mod dd;
pub mod distance;
pub mod error;
pub mod expansion;
pub mod frame;
pub mod identity;
pub mod intersect;
pub mod orient;
pub mod ring;
pub mod sos;

pub use bvh::{Aabb, Bvh};
pub use construct::{EdgeTrianglePoint, TriplePoint, edge_triangle_point, triple_point};
pub use error::{GeomError, NonFinite};
pub use frame::BoxFrame;
pub use identity::{index_identities, motion_classes, position_classes, position_key};
pub use intersect::{
    SegEnd, end_side, order_on_segment, segment_triangle_intersect, triangle_triangle_segment,
    triangle_triangle_triangle_point,
};
pub use orient::{Sign, SymPoint2, orient2d, orient2d_sos, orient3d, orient3d_sos};
pub use sos::{SosSign, SymPoint};
