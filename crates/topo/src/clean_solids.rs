//! Whether two meshes are clean solids, for which the containment
//! union of Theorem 5.2 ([`crate::union`]) gives the winding-number
//! answer: both closed, neither crossing itself, and no piece of either
//! inside another of its pieces. Otherwise a Boolean needs the
//! winding-number arrangement ([`crate::winding_boolean`]). Both Boolean
//! methods use the check, so it has a module of its own below both.

use holey_geom::{Aabb, BoxFrame, Bvh, SymPoint, position_classes};

use crate::engine::TopoError;
use crate::hidden::vertex_components;
use crate::intersect::{FramedTree, crosses_itself_keeping_tree};
use crate::mesh::{MeshError, TriMesh};

/// Which Boolean a pair of meshes needs: the winding-number arrangement
/// ([`crate::winding_boolean::boolean_by_winding`]) when either is not a
/// closed 2-manifold (its generalized winding number then says what is
/// inside), crosses itself (the containment union of Theorem 5.2,
/// [`crate::union::boolean`], keeps a solid's own crossings) or has a
/// piece inside another of its pieces (containment parity counts nested
/// shells modulo two, the winding number by their orientations), else
/// the containment union, which is faster. Costs about one
/// [`crate::engine::self_intersections`] of each.
pub fn needs_arrangement(a: &TriMesh, b: &TriMesh) -> Result<bool, TopoError> {
    Ok(needs_arrangement_when_closed(a, b, a.is_closed() && b.is_closed(), [None, None])?.0)
}

/// [`needs_arrangement`] with whether both surfaces are closed known
/// already (from the containment method's edge tables), and the trees
/// the self-crossing checks of `a` and `b` were made with
/// ([`crosses_itself_keeping_tree`], in `frames`, or in each mesh's own
/// where `None`), for the containment method to reuse; a tree is `None`
/// where no check ran to the end or its tree does not hold every
/// triangle.
pub(crate) fn needs_arrangement_when_closed(
    a: &TriMesh,
    b: &TriMesh,
    closed: bool,
    frames: [Option<BoxFrame>; 2],
) -> Result<(bool, [Option<FramedTree>; 2]), TopoError> {
    if !closed {
        return Ok((true, [None, None]));
    }
    // Both checks at once: each has passes that leave a core idle (the
    // position classes, the top of its tree). One that finds a crossing
    // makes the other's work moot, and the arrangement then costs far more.
    let (checked_a, checked_b) = rayon::join(
        || crosses_itself_keeping_tree(a, frames[0]),
        || crosses_itself_keeping_tree(b, frames[1]),
    );
    // A first: a crossing there answers, whatever B's check says.
    let (crosses_a, tree_a) = checked_a?;
    if crosses_a {
        return Ok((true, [None, None]));
    }
    let (crosses_b, tree_b) = checked_b?;
    if crosses_b {
        return Ok((true, [None, None]));
    }
    let (nested_a, nested_b) = rayon::join(|| has_nested_pieces(a), || has_nested_pieces(b));
    let needs = nested_a? || nested_b?;
    Ok((needs, [tree_a, tree_b]))
}

/// Whether some connected piece of `m` (closed, not crossing itself) lies
/// inside another: one exact ray per piece, from one of its vertices,
/// counting the crossings with the other pieces' triangles (simulation of
/// simplicity; the ray's far end has an identity no vertex has).
fn has_nested_pieces(m: &TriMesh) -> Result<bool, TopoError> {
    let piece = vertex_components(m);
    let count = piece.iter().map(|&c| c as usize + 1).max().unwrap_or(0);
    if count < 2 {
        return Ok(false);
    }
    let ids = position_classes(&m.positions)?;
    let boxes: Vec<Aabb> = (0..m.triangles.len())
        .map(|t| Aabb::from_points(&m.corners(t)))
        .collect();
    let Ok(tree) = Bvh::build(&boxes) else {
        return Ok(true);
    };
    let bounds = tree.bounds();
    let far_id =
        u32::try_from(m.positions.len()).map_err(|_| MeshError::TooLarge(m.positions.len()))?;
    let sym = |v: u32| SymPoint::new(m.positions[v as usize], ids[v as usize]);
    let mut seen = vec![false; count];
    for t in &m.triangles {
        let (v, c) = (t[0], piece[t[0] as usize]);
        if seen[c as usize] {
            continue;
        }
        seen[c as usize] = true;
        let start = sym(v);
        let Some(far) = BoxFrame::IDENTITY.beyond(start.pos, &bounds) else {
            return Ok(true);
        };
        let end = SymPoint::new(far, far_id);
        let mut odd = false;
        tree.for_each_overlap(&Aabb::new(start.pos, far), |t| {
            let tri = m.triangles[t as usize];
            if piece[tri[0] as usize] != c {
                let [p, q, r] = tri.map(sym);
                if holey_geom::segment_triangle_intersect(start, end, p, q, r) {
                    odd = !odd;
                }
            }
        });
        if odd {
            return Ok(true);
        }
    }
    Ok(false)
}
