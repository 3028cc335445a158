//! Triangle meshes as the engine takes them, and their edges: the plain
//! triangle mesh of `holey-mesh` ([`holey_mesh::tri`]), re-exported where
//! the engine's stages have always found it.
//!
//! The engine works on *any* list of triangles (§2.1 of the paper): edges of
//! any degree, open, unoriented, disconnected, unwelded soups, duplicate and
//! zero-area triangles. Edges are identified by vertex *indices*: two
//! triangles of a soup that only touch at equal positions share no edge.

pub use holey_mesh::tri::*;

/// Each of the vertices `among` (any order, each once) that lies at the
/// exact position (`position` gives it; `-0.0 == 0.0`) of an earlier one
/// of them, paired with the first at that position. Soups and unwelded
/// seams meet only there: where the audit and the piece rules take such
/// copies on a rim as one point of the surface
/// ([`crate::audit::SurfaceAudit::topology`], `hidden::pieces_welded`).
pub(crate) fn coincident_pairs(
    position: &dyn Fn(u32) -> glam::DVec3,
    among: impl IntoIterator<Item = u32>,
) -> Vec<(u32, u32)> {
    let mut first: rustc_hash::FxHashMap<[u64; 3], u32> = rustc_hash::FxHashMap::default();
    let mut pairs = Vec::new();
    for v in among {
        let at = *first
            .entry(holey_geom::position_key(position(v)))
            .or_insert(v);
        if at != v {
            pairs.push((v, at));
        }
    }
    pairs
}
