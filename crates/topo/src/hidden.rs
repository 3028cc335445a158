//! The surface's pieces (connected components, [`pieces`]) that a change
//! must not leave behind: pieces hidden inside the rest of the surface
//! ([`hidden_pieces`]), and specks, pieces hardly wider than the edges
//! the surface had there are long ([`specks`]).
//!
//! A change can cut a piece loose inside a body: a grab whose strand
//! folded over itself pushed its tip through a wall, the strand vanished
//! as swept and the tip stayed inside, unseen (issue 15: "a hidden second
//! component of 764 triangles inside the head"). For a solid that piece
//! has both sides inside, which Lemma 8.1 deletes; parity on a scan with
//! holes can keep it. The guard ([`crate::guard`]) counts such pieces
//! near what a frame changed, before and after, and a frame that adds
//! one is worse. Counting before too keeps what the surface already
//! held: a ship sculpted inside a bottle is inside the rest before and
//! after.
//!
//! Inside means the generalized winding number of the rest of the
//! surface (every other component) is at least ½ in magnitude (either
//! orientation; the rule of issue 14) at points spread over the piece,
//! every one of them: near the opening of an open sheet the winding
//! number passes ½ without anything being enclosed.
//!
//! A speck is a piece whose bounding box has a diagonal shorter than the
//! shortest edge of the triangles near the change before it. The guard
//! counts them before and after as it counts hidden pieces.
//!
//! A crumple can also leave handles instead of pieces: the cut glues the
//! surface along every intersection curve, and where many triangles
//! cross near one point the curves are far smaller than any triangle,
//! each one a tunnel or neck nobody can see (a rod squeezed through its
//! axis came out of one frame in one piece with genus 10). So
//! [`tiny_new_curves`] counts the curves a frame makes that are smaller
//! than the shortest edge there and lie within one such edge of each
//! other; the guard
//! refuses two or more (one is how every contact starts, and separate
//! contacts lie apart).

use glam::DVec3;

use crate::intersect::{Intersections, Node};
use crate::mesh::{TriMesh, coincident_pairs};
use crate::union_find::UnionFind;
use crate::winding::winding_numbers_at;

/// Most candidate components a count examines (one pass over the
/// surface each); past that the frame has shattered the surface and the
/// other checks speak for it.
const MAX_CANDIDATES: usize = 16;

/// Points sampled on each candidate piece.
const SAMPLES: usize = 8;

/// Whether the triangles of `mesh` are one piece: connected through
/// shared vertex numbers (a mesh without triangles is not). What
/// [`crate::Options::one_piece`] asks a caller to know.
///
/// ```
/// use glam::DVec3;
/// use holey_topo::{TriMesh, is_one_piece};
///
/// // Two triangles sharing the edge 1-2, and a third one apart.
/// let positions = [[0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [1., 1., 0.], [5., 0., 0.], [6., 0., 0.], [5., 1., 0.]];
/// let mut mesh = TriMesh {
///     positions: positions.iter().map(|&p| DVec3::from_array(p)).collect(),
///     triangles: vec![[0, 1, 2], [2, 1, 3]],
/// };
/// assert!(is_one_piece(&mesh));
/// mesh.triangles.push([4, 5, 6]);
/// assert!(!is_one_piece(&mesh));
/// ```
pub fn is_one_piece(mesh: &TriMesh) -> bool {
    !mesh.triangles.is_empty() && pieces_welded(mesh, &|_| false).1 == 1
}

/// The connected component of every triangle of `m` (named by a root
/// vertex; components are joined through shared vertices) and how many
/// components there are.
#[cfg(test)]
pub(crate) fn pieces(m: &TriMesh) -> (Vec<u32>, usize) {
    pieces_welded(m, &|_| false)
}

/// [`pieces`], with the vertices `near` flags that lie on a rim (an edge
/// at them has one triangle) also joined wherever they lie at one exact
/// position: a soup's corners and the two sides of an unwelded seam are
/// one surface there, as the brushes and the engine's identities by
/// position take them. Counted by vertex numbers alone, a soup is a piece
/// per triangle, every one smaller than a speck, and a cut through a
/// triangle makes more of them: the guard held frames that cut a soup for
/// "specks cut off" and took the cut triangles out as debris (61 of the
/// Arduino case soup's in one inflate of the fuzz). Copies with whole
/// fans stay apart: where a pinch was split or sheets fused, the pieces
/// only touch. Only the flagged vertices are looked at: the region a
/// frame changed.
pub(crate) fn pieces_welded(m: &TriMesh, near: &dyn Fn(u32) -> bool) -> (Vec<u32>, usize) {
    let (mut uf, _) = welded_union_find(
        m.positions.len(),
        &|v| m.positions[v as usize],
        &|f| m.triangles.iter().for_each(|&t| f(t)),
        near,
    );
    let root: Vec<u32> = m.triangles.iter().map(|t| uf.find(t[0])).collect();
    let mut seen = vec![false; m.positions.len()];
    let count = root
        .iter()
        .filter(|&&r| !std::mem::replace(&mut seen[r as usize], true))
        .count();
    (root, count)
}

/// A surface's triangles, visited: the function calls its argument once
/// per triangle.
pub(crate) type Triangles<'a> = dyn Fn(&mut dyn FnMut([u32; 3])) + 'a;

/// The count of [`pieces_welded`] of the surface of the triangles
/// `triangles` visits (in any order, more than once) over `n` vertices at
/// `position`, without the surface built: a frame's splice and the count
/// of the pieces it leaves run side by side on a million triangles.
pub(crate) fn piece_count_welded(
    n: usize,
    position: &dyn Fn(u32) -> DVec3,
    triangles: &Triangles<'_>,
    near: &dyn Fn(u32) -> bool,
) -> PieceCount {
    let (mut uf, welded) = welded_union_find(n, position, triangles, near);
    let mut seen = vec![false; n];
    let mut count = 0;
    triangles(&mut |t| {
        let r = uf.find(t[0]) as usize;
        count += usize::from(!std::mem::replace(&mut seen[r], true));
    });
    PieceCount { count, welded }
}

/// What [`piece_count_welded`] found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct PieceCount {
    /// The pieces, rim copies at one position joined.
    pub count: usize,
    /// Whether any rim copies were joined by position. Without, the
    /// count is by shared vertices alone, [`is_one_piece`]'s.
    pub welded: bool,
}

impl PieceCount {
    /// One piece by shared vertices alone: what [`is_one_piece`] says of
    /// the surface counted.
    pub fn one_piece(self) -> bool {
        self.count == 1 && !self.welded
    }
}

/// The union-find of [`pieces_welded`]: vertices joined along the
/// triangles `triangles` visits, and rim copies among the flagged ones
/// at one exact position joined too; and whether any were.
fn welded_union_find(
    n: usize,
    position: &dyn Fn(u32) -> DVec3,
    triangles: &Triangles<'_>,
    near: &dyn Fn(u32) -> bool,
) -> (UnionFind, bool) {
    let mut uf = UnionFind::new(n);
    let mut used = vec![false; n];
    triangles(&mut |t| {
        uf.union(t[0], t[1]);
        uf.union(t[0], t[2]);
        for &v in &t {
            used[v as usize] = true;
        }
    });
    // The flagged vertices that share their position with another: most
    // meshes have none, and then one pass of hashing is all this costs.
    let flagged = (0..n as u32).filter(|&v| used[v as usize] && near(v));
    let shared = coincident_pairs(position, flagged);
    if !shared.is_empty() {
        let mut copy = vec![false; n];
        for &(v, at) in &shared {
            copy[v as usize] = true;
            copy[at as usize] = true;
        }
        // Of those, the ones on a rim (a side at them with one triangle)
        // are one point.
        let mut sides: Vec<(u32, u32)> = Vec::new();
        triangles(&mut |t| {
            for k in 0..3 {
                if copy[t[k] as usize] {
                    sides.push((t[k], t[(k + 1) % 3]));
                    sides.push((t[k], t[(k + 2) % 3]));
                }
            }
        });
        sides.sort_unstable();
        let mut rim: Vec<u32> = sides
            .chunk_by(|x, y| x == y)
            .filter(|run| run.len() == 1)
            .map(|run| run[0].0)
            .collect();
        rim.dedup();
        let joined = coincident_pairs(position, rim);
        for &(v, at) in &joined {
            uf.union(at, v);
        }
        return (uf, !joined.is_empty());
    }
    (uf, false)
}

/// How many connected components of `m` with a vertex that `near` flags
/// lie inside the rest of `m` (module docs), sampled at the centroids of
/// up to [`SAMPLES`] of their triangles. `root` and `count` are
/// [`pieces`] of `m`.
pub(crate) fn hidden_pieces(
    m: &TriMesh,
    (root, count): (&[u32], usize),
    near: &dyn Fn(u32) -> bool,
) -> usize {
    // A single component has no rest to lie in.
    if count < 2 {
        return 0;
    }
    // Candidates: the components near the change, with their triangles.
    let mut candidate = near_components(m, root, near, Vec::<usize>::new);
    if candidate.len() > MAX_CANDIDATES {
        return 0;
    }
    for (i, r) in root.iter().enumerate() {
        if let Some(list) = candidate.get_mut(r) {
            list.push(i);
        }
    }
    let position = |v: u32| m.positions[v as usize];
    candidate
        .iter()
        .filter(|&(&r, tris)| {
            // Samples spread over the piece: the centroids of every k-th
            // of its triangles. A piece near an open sheet can have a
            // point where that sheet's winding number passes ½; a hidden
            // piece is inside at every point.
            let step = tris.len().div_ceil(SAMPLES).max(1);
            let at: Vec<DVec3> = tris
                .iter()
                .step_by(step)
                .map(|&t| m.triangles[t].map(position).iter().sum::<DVec3>() / 3.0)
                .collect();
            winding_numbers_at(&m.triangles, &|u| root[u] != r, &position, &at)
                .iter()
                .all(|w| w.abs() >= 0.5)
        })
        .count()
}

/// How many connected components of `m` with a vertex that `near` flags
/// are specks: the diagonal of their bounding box is shorter than
/// `scale`. `root` and `count` are [`pieces`] of `m`.
///
/// Where many triangles cross near one point (a ring of vertices
/// squeezed through its axis, a crumpled fold) the arrangement of their
/// intersections has cells far smaller than any triangle, and parity
/// can keep some of them as closed pieces of their own: specks no brush
/// shaped and nobody can see or select. With `scale` a small multiple of
/// the median edge the surface had near the change ([`median_edge_near`]),
/// a new speck is debris at or below the surface's resolution (the shortest edge was too
/// fine a scale: a cut earlier in the same frame can leave edges ten
/// thousand times shorter than the rest, and a deflate over the Stanford
/// bunny's fused haunch cut off eleven pieces at once under it).
pub(crate) fn specks(
    m: &TriMesh,
    (root, count): (&[u32], usize),
    near: &dyn Fn(u32) -> bool,
    scale: f64,
) -> usize {
    if count < 2 {
        return 0;
    }
    let mut boxes = near_components(m, root, near, || (DVec3::INFINITY, DVec3::NEG_INFINITY));
    for (i, t) in m.triangles.iter().enumerate() {
        if let Some((lo, hi)) = boxes.get_mut(&root[i]) {
            for &v in t {
                let p = m.positions[v as usize];
                (*lo, *hi) = (lo.min(p), hi.max(p));
            }
        }
    }
    boxes
        .values()
        .filter(|(lo, hi)| (*hi - *lo).length() < scale)
        .count()
}

/// Per triangle of `m`: whether it belongs to debris a change made, a
/// connected piece that has a vertex the change made (`made`), no vertex
/// on the interface with the rest of the surface (`interface`: the piece
/// is whole within `m`), and a bounding box whose diagonal is shorter
/// than `scale` ([`specks`]). `root` and `count` are [`pieces`] of `m`.
/// Such a piece is no part of anything the brush shaped: the arrangement
/// of a crumple closed it off, below the surface's resolution, so the
/// guard takes it out instead of holding the frame (a dwell inflate at
/// bigguy's rim left two tetrahedra of a fold's tip, each inside the
/// body, and stalled for 37 frames). With the number of such pieces;
/// `None` when there is none.
pub(crate) fn debris(
    m: &TriMesh,
    (root, count): (&[u32], usize),
    made: &dyn Fn(u32) -> bool,
    interface: &dyn Fn(u32) -> bool,
    scale: f64,
) -> Option<(Vec<bool>, usize)> {
    if count < 2 {
        return None;
    }
    struct Piece {
        made: bool,
        interface: bool,
        lo: DVec3,
        hi: DVec3,
    }
    let mut found: rustc_hash::FxHashMap<u32, Piece> = rustc_hash::FxHashMap::default();
    for (t, &r) in m.triangles.iter().zip(root) {
        let piece = found.entry(r).or_insert(Piece {
            made: false,
            interface: false,
            lo: DVec3::INFINITY,
            hi: DVec3::NEG_INFINITY,
        });
        for &v in t {
            piece.made |= made(v);
            piece.interface |= interface(v);
            let p = m.positions[v as usize];
            (piece.lo, piece.hi) = (piece.lo.min(p), piece.hi.max(p));
        }
    }
    found.retain(|_, p| p.made && !p.interface && (p.hi - p.lo).length() < scale);
    if found.is_empty() {
        return None;
    }
    Some((
        root.iter().map(|r| found.contains_key(r)).collect(),
        found.len(),
    ))
}

/// The components of `m` (named by `root`, as [`pieces`] gives them)
/// with a vertex that `near` flags, each with `empty()` to fill in.
fn near_components<T>(
    m: &TriMesh,
    root: &[u32],
    near: &dyn Fn(u32) -> bool,
    empty: impl Fn() -> T,
) -> rustc_hash::FxHashMap<u32, T> {
    let mut found = rustc_hash::FxHashMap::default();
    for (t, &r) in m.triangles.iter().zip(root) {
        if touches(t, near) {
            found.entry(r).or_insert_with(&empty);
        }
    }
    found
}

/// Whether triangle `t` has a vertex that `near` flags.
fn touches(t: &[u32; 3], near: &dyn Fn(u32) -> bool) -> bool {
    t.iter().any(|&v| near(v))
}

/// The most intersection curves of `x` that are new, smaller than
/// `scale`, lie within one piece and lie together (their bounding boxes
/// closer than `scale`, directly or through others). New: every triangle
/// pair on the curve is new (`was[i]` says whether pair `x.pairs[i]`
/// intersected at the frame's start). Smaller: the diagonal of the
/// curve's bounding box is shorter than `scale`. Within one piece:
/// `one_piece(s, t)` for every pair `(s, t)` on it; a curve between two
/// pieces joins them (the triangles of a soup welding as they touch)
/// where a curve within one makes a handle. `x` holds the static
/// intersections of `m` with vertex `v` at `at(v)` (a frame's end).
///
/// One such curve is how every contact starts (two bulges touching, a
/// vertex poking through a face), and the next frames grow it; several
/// within an edge of each other in one frame, each smaller than any edge
/// there, are a crumple (module docs).
pub(crate) fn tiny_new_curves(
    m: &TriMesh,
    at: &dyn Fn(u32) -> DVec3,
    x: &Intersections,
    was: &[bool],
    scale: f64,
    one_piece: &dyn Fn(u32, u32) -> bool,
) -> usize {
    let n = x.curve_count;
    let mut new = vec![true; n];
    let mut bounds = vec![(DVec3::INFINITY, DVec3::NEG_INFINITY); n];
    for (piece, &c) in x.pieces.iter().zip(&x.curve_of_piece) {
        let c = c as usize;
        let pair = (piece.tris[0], piece.tris[1]);
        if let Ok(i) = x.pairs.binary_search(&pair)
            && was.get(i).copied().unwrap_or(false)
        {
            new[c] = false;
        }
        if !one_piece(pair.0, pair.1) {
            new[c] = false;
        }
        let (lo, hi) = &mut bounds[c];
        let mut grow = |p: DVec3| (*lo, *hi) = (lo.min(p), hi.max(p));
        for node in piece.ends {
            match node {
                Node::Point(j) => grow(x.points[j as usize].position),
                // A vertex both triangles have: their common corner.
                Node::Shared(_) => {
                    let [a, b] = piece.tris.map(|t| m.triangles[t as usize].map(at));
                    a.iter().filter(|p| b.contains(p)).for_each(|&p| grow(p));
                }
            }
        }
    }
    // The tiny new curves, and of them the largest cluster closer than
    // `scale` to one another (boxes grown by half of it meet): a
    // crumple's curves crowd where its triangles cross, within an edge of
    // each other, while separate contacts (a brush and its mirror image)
    // lie apart.
    let half = DVec3::splat(0.5 * scale);
    let mut tiny: Vec<(DVec3, DVec3)> = new
        .iter()
        .zip(&bounds)
        .filter(|&(&new, (lo, hi))| new && (*hi - *lo).length() < scale)
        .map(|(_, (lo, hi))| (*lo - half, *hi + half))
        .collect();
    // Boxes that meet, by a sweep along x.
    tiny.sort_by(|a, b| a.0.x.total_cmp(&b.0.x));
    let mut uf = UnionFind::new(tiny.len());
    for (i, (lo, hi)) in tiny.iter().enumerate() {
        for (j, (lo2, hi2)) in tiny.iter().enumerate().skip(i + 1) {
            if lo2.x > hi.x {
                break;
            }
            if lo.cmple(*hi2).all() && lo2.cmple(*hi).all() {
                uf.union(i as u32, j as u32);
            }
        }
    }
    let mut size = vec![0usize; tiny.len()];
    for i in 0..tiny.len() as u32 {
        size[uf.find(i) as usize] += 1;
    }
    size.into_iter().max().unwrap_or(0)
}

/// The connected piece of each vertex of `m` (pieces numbered from 0 in
/// order of their first vertex; a vertex no triangle uses is its own).
pub(crate) fn vertex_components(m: &TriMesh) -> Vec<u32> {
    let mut sets = UnionFind::new(m.positions.len());
    for t in &m.triangles {
        sets.union(t[0], t[1]);
        sets.union(t[1], t[2]);
    }
    sets.labels().0
}

/// The median length of the edges of the triangles of `m` with a vertex
/// that `near` flags (each edge once per such triangle; infinite when
/// there is none): the resolution of the surface there, which one short
/// edge left by an earlier cut does not set.
pub(crate) fn median_edge_near(m: &TriMesh, near: &dyn Fn(u32) -> bool) -> f64 {
    let p = |v: u32| m.positions[v as usize];
    let mut lengths: Vec<f64> = m
        .triangles
        .iter()
        .filter(|t| touches(t, near))
        .flat_map(|t| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])])
        .map(|(a, b)| p(a).distance(p(b)))
        .collect();
    if lengths.is_empty() {
        return f64::INFINITY;
    }
    let mid = lengths.len() / 2;
    *lengths.select_nth_unstable_by(mid, f64::total_cmp).1
}

/// The length of the shortest edge of the triangles of `m` with a vertex
/// that `near` flags (infinite when there is none).
pub(crate) fn shortest_edge_near(m: &TriMesh, near: &dyn Fn(u32) -> bool) -> f64 {
    let p = |v: u32| m.positions[v as usize];
    m.triangles
        .iter()
        .filter(|t| touches(t, near))
        .flat_map(|t| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])])
        .map(|(a, b)| p(a).distance(p(b)))
        .fold(f64::INFINITY, f64::min)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::test_meshes::cuboid as cube;

    fn joined(a: &TriMesh, b: &TriMesh) -> TriMesh {
        let mut m = a.clone();
        let n = m.positions.len() as u32;
        m.positions.extend(&b.positions);
        m.triangles
            .extend(b.triangles.iter().map(|t| t.map(|v| v + n)));
        m
    }

    /// A box as a soup (each triangle its own corners) is one piece when
    /// its rim copies are joined by position, twelve by vertex numbers,
    /// and twelve still where only some vertices are looked at; two boxes
    /// touching at a corner through vertices of their own, each with a
    /// whole fan, stay two pieces.
    #[test]
    fn a_soup_is_one_piece_by_position_and_whole_fans_stay_apart() {
        let c = cube(DVec3::ZERO, DVec3::ONE);
        let soup = c.unwelded();
        assert_eq!(pieces_welded(&soup, &|_| true).1, 1);
        assert_eq!(pieces(&soup).1, 12);
        assert_eq!(pieces_welded(&soup, &|_| false).1, 12);
        let touching = joined(&c, &cube(DVec3::ONE, DVec3::splat(2.0)));
        assert_eq!(pieces_welded(&touching, &|_| true).1, 2);
    }

    /// The count without the surface built, from its triangles in any
    /// order and its positions from a function, is the count of the
    /// surface: the testkit's components of a welded mesh (two cubes
    /// touching at a corner: two), one for a cube's soup welded at its
    /// rims, twelve unflagged, one for a cube. It is one piece by shared
    /// vertices ([`PieceCount::one_piece`]) only where `is_one_piece`
    /// says so: the cube, not the soup welded.
    #[test]
    fn the_count_of_pieces_from_the_triangles_alone_is_the_surfaces() {
        let c = cube(DVec3::ZERO, DVec3::ONE);
        let touching = joined(&c, &cube(DVec3::ONE, DVec3::splat(2.0)));
        let soup = c.unwelded();
        for (m, flag, expected) in [
            (
                &touching,
                true,
                holey_testkit::components(&touching.triangles),
            ),
            (&soup, true, 1),
            (&soup, false, 12),
            (&c, true, 1),
        ] {
            let count = piece_count_welded(
                m.positions.len(),
                &|v| m.positions[v as usize],
                &|f| m.triangles.iter().rev().for_each(|&t| f(t)),
                &|_| flag,
            );
            assert_eq!(count.count, expected);
            assert_eq!(count.count, pieces_welded(m, &|_| flag).1);
            // Welded exactly where rim copies were joined: the soup
            // flagged; and one piece by shared vertices only where
            // `is_one_piece` says so.
            assert_eq!(count.welded, flag && std::ptr::eq(m, &soup));
            assert_eq!(count.one_piece(), is_one_piece(m));
        }
    }

    /// A small box beside a big one is debris when it has a vertex the
    /// change made, none on the interface with the rest of the surface,
    /// and is smaller than the scale; the big one never is.
    #[test]
    fn debris_is_small_made_and_whole_within_the_mesh() {
        let big = cube(DVec3::splat(-2.0), DVec3::splat(2.0));
        let m = joined(
            &big,
            &cube(DVec3::new(3.0, -0.5, -0.5), DVec3::new(4.0, 0.5, 0.5)),
        );
        let small = |v: u32| v >= 8;
        let none = |_: u32| false;
        let debris = |m: &TriMesh,
                      made: &dyn Fn(u32) -> bool,
                      interface: &dyn Fn(u32) -> bool,
                      scale: f64| {
            let (root, count) = pieces(m);
            debris(m, (&root, count), made, interface, scale)
        };
        let (mask, count) = debris(&m, &small, &none, 2.0).unwrap();
        assert_eq!(count, 1);
        assert_eq!(
            mask,
            m.triangles.iter().map(|t| t[0] >= 8).collect::<Vec<_>>()
        );
        // Nothing made there, one of its vertices on the interface, or
        // wider than the scale: it stays.
        assert!(debris(&m, &none, &none, 2.0).is_none());
        assert!(debris(&m, &small, &|v| v == 9, 2.0).is_none());
        assert!(debris(&m, &small, &none, 1.5).is_none());
        // One piece alone is never debris.
        assert!(debris(&big, &|_| true, &none, 100.0).is_none());
    }

    /// A small box inside a big one is hidden, beside it is not; the big
    /// one is never inside the small one; only components near the
    /// change count.
    #[test]
    fn a_box_inside_a_box_is_hidden_one_beside_it_is_not() {
        let big = cube(DVec3::splat(-2.0), DVec3::splat(2.0));
        let inside = joined(&big, &cube(DVec3::splat(-0.5), DVec3::splat(0.5)));
        let beside = joined(
            &big,
            &cube(DVec3::new(3.0, -0.5, -0.5), DVec3::new(4.0, 0.5, 0.5)),
        );
        let all = |_: u32| true;
        let hidden = |m: &TriMesh, near: &dyn Fn(u32) -> bool| {
            let (root, count) = pieces(m);
            hidden_pieces(m, (&root, count), near)
        };
        assert_eq!(pieces(&inside).1, 2);
        assert_eq!(hidden(&inside, &all), 1);
        assert_eq!(hidden(&beside, &all), 0);
        assert_eq!(pieces(&big).1, 1);
        assert_eq!(hidden(&big, &all), 0);
        // Inside-out (inward-facing) boxes count alike.
        let flipped = TriMesh {
            triangles: inside
                .triangles
                .iter()
                .map(|t| [t[0], t[2], t[1]])
                .collect(),
            ..inside.clone()
        };
        assert_eq!(hidden(&flipped, &all), 1);
        // Only the big box near the change: the small one is not looked at.
        assert_eq!(hidden(&inside, &|v| v < 8), 0);
    }
}
