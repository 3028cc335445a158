//! The brushes, as pure functions of positions and triangles: each
//! returns the positions at the end of one frame and never changes
//! connectivity. Topology change is the session's business (see
//! [`crate::session`]). One file per brush, each stating its displacement
//! field: §4's [`mod@inflate`], [`mod@smooth`], [`grab`] and move ([`moving`]);
//! the sculptor's [`draw`], [`clay`], [`crease`], [`flatten`], [`layer`],
//! [`pinch`], [`scrape`], [`scale`] and the [`snake_hook`], which pulls a
//! tentacle out of the surface along the pointer's path. Every centred
//! brush weighs its displacement by a [`Falloff`] curve; the sculptor's
//! brushes act on the connected patch under them ([`region`]).
//!
//! Every function works on any triangle list (open, non-manifold,
//! unoriented, many components), because the engine does.

pub mod clay;
pub mod crease;
pub mod draw;
pub mod falloff;
pub mod flatten;
pub mod grab;
pub mod inflate;
pub mod layer;
pub mod moving;
pub mod pinch;
pub mod region;
pub mod scale;
pub mod scrape;
pub mod smooth;
pub mod snake_hook;

pub use falloff::Falloff;
pub use grab::{grab_weights, grab_weights_with};
pub use inflate::{inflate, inflate_with};
pub use moving::component_of;
use region::Region;
pub use smooth::{smooth, smooth_with};

use glam::DVec3;
use holey_geom::position_key;
use holey_topo::TriMesh;
use serde::{Deserialize, Serialize};

/// The brushes: the four of §4 and the sculptor's set.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Brush {
    /// Instantaneous displacement along the surface normal (negative
    /// strength deflates).
    #[default]
    Inflate,
    /// Instantaneous explicit Laplacian smoothing, masked by the brush.
    Smooth,
    /// Hold part of the surface with a distance-based falloff and drag it.
    Grab,
    /// Drag a part rigidly: with a radius, the part of the picked piece
    /// within it (held whole in the inner half, blended out to the rim:
    /// [`crate::live::move_falloff`]); with radius 0, the whole connected
    /// piece, as §4's move.
    Move,
    /// Pull the surface under the brush along the path in short steps,
    /// stretching it into a tentacle that fuses with what it is pulled
    /// into ([`snake_hook`]); topology changes every frame, as for
    /// inflate.
    SnakeHook,
    /// Raise along the brush's normal ([`draw`]).
    Draw,
    /// Build up to a plane just above the surface ([`clay`]).
    Clay,
    /// Cut a sharp groove ([`crease`]).
    Crease,
    /// Pull towards the brush plane ([`flatten`]).
    Flatten,
    /// Draw together towards the centre ([`pinch`]).
    Pinch,
    /// Flatten only what stands above the plane ([`scrape`]).
    Scrape,
    /// Grow or shrink about the centre ([`scale`]).
    Scale,
    /// Raise to a plateau a fixed height above the stroke's start
    /// ([`layer`]).
    Layer,
}

/// What pen pressure (0 to 1 per frame) scales in a paint frame. Drags
/// (grab, move) follow the pointer and ignore it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PressureDrives {
    /// The frame's strength is multiplied by the pressure.
    #[default]
    Strength,
    /// The frame's radius is multiplied by the pressure.
    Radius,
}

/// Every brush, in the modeler's order.
pub const ALL_BRUSHES: [Brush; 13] = [
    Brush::Inflate,
    Brush::Smooth,
    Brush::Grab,
    Brush::Move,
    Brush::SnakeHook,
    Brush::Draw,
    Brush::Clay,
    Brush::Crease,
    Brush::Flatten,
    Brush::Pinch,
    Brush::Scrape,
    Brush::Scale,
    Brush::Layer,
];

impl Brush {
    /// The name used in stroke files.
    pub fn name(self) -> &'static str {
        match self {
            Brush::Inflate => "inflate",
            Brush::Smooth => "smooth",
            Brush::Grab => "grab",
            Brush::Move => "move",
            Brush::SnakeHook => "snake_hook",
            Brush::Draw => "draw",
            Brush::Clay => "clay",
            Brush::Crease => "crease",
            Brush::Flatten => "flatten",
            Brush::Pinch => "pinch",
            Brush::Scrape => "scrape",
            Brush::Scale => "scale",
            Brush::Layer => "layer",
        }
    }

    /// The brush a stroke file or the modeler names, if any.
    pub fn from_name(name: &str) -> Option<Brush> {
        ALL_BRUSHES.into_iter().find(|b| b.name() == name)
    }

    /// Whether the strength is a share of the way per frame, checked to
    /// lie in `[0, 1]` (`[−1, 1]` for scale and pinch) rather than a
    /// distance in world units (inflate, draw, clay, crease, layer) or a scale of
    /// the pointer's motion (grab, move, snake hook).
    pub fn strength_is_a_share(self) -> bool {
        matches!(
            self,
            Brush::Smooth | Brush::Flatten | Brush::Scrape | Brush::Pinch | Brush::Scale
        )
    }

    /// The range a share strength must lie in.
    pub fn share_range(self) -> (f64, f64) {
        match self {
            Brush::Pinch | Brush::Scale => (-1.0, 1.0),
            _ => (0.0, 1.0),
        }
    }

    /// Whether the brush accumulates parity over the whole drag and changes
    /// topology once at release (§4), rather than every frame.
    pub fn is_drag(self) -> bool {
        matches!(self, Brush::Grab | Brush::Move)
    }
}

impl std::fmt::Display for Brush {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// The brush falloff: `(1 - (d/r)²)²` inside the radius, 0 outside. It is
/// 1 at the centre and has zero slope at both ends, so the displaced
/// region blends smoothly into the rest of the surface (no crease at the
/// rim, which would make needless self-intersections).
pub fn falloff(distance: f64, radius: f64) -> f64 {
    // Written so that NaN falls outside.
    let inside = radius > 0.0 && distance < radius;
    if !inside {
        return 0.0;
    }
    let s = distance / radius;
    let t = 1.0 - s * s;
    t * t
}

/// Area-weighted vertex normals (unit length, or zero where the incident
/// area cancels or vanishes). The triangles' own winding decides the side,
/// so on an unoriented mesh the normal is whatever the incident triangles
/// agree on; the sculptor sees that as the surface's front. Vertices at
/// exactly one position (the corners of a soup, the unwelded seams of
/// patches) are one point of the surface and get one normal, summed over
/// all their triangles.
pub fn vertex_normals(mesh: &TriMesh) -> Vec<DVec3> {
    let all: Vec<u32> = (0..mesh.positions.len() as u32).collect();
    normals_of(mesh, &all)
}

/// The classes of coincident positions among `which` (increasing; exact
/// equality with `-0.0 == 0.0`, as the engine's identities):
/// `class[i]` is the first index into `which` with the same position.
/// Only the brushed vertices are hashed.
fn coincident(mesh: &TriMesh, which: &[u32]) -> Vec<u32> {
    let mut first: std::collections::HashMap<[u64; 3], u32> =
        std::collections::HashMap::with_capacity(which.len());
    which
        .iter()
        .enumerate()
        .map(|(i, &v)| {
            *first
                .entry(position_key(mesh.positions[v as usize]))
                .or_insert(i as u32)
        })
        .collect()
}

/// [`vertex_normals`] of the vertices `which` only (increasing), in that
/// order: one scan of the triangles, work only where they are used. A
/// vertex on the surface's rim gets its [`rim_normals`] instead.
fn normals_of(mesh: &TriMesh, which: &[u32]) -> Vec<DVec3> {
    let class = coincident(mesh, which);
    let (sums, near) = area_sums(mesh, which, &class);
    let rim = rim_normals(mesh, which, &class, &sums, &near);
    class
        .iter()
        .map(|&c| {
            rim.get(&c)
                .copied()
                .unwrap_or(sums[c as usize])
                .normalize_or_zero()
        })
        .collect()
}

/// The area vectors of the triangles around each class of `which`
/// (`class` from [`coincident`]), summed (twice the area-weighted
/// normal), and the triangles with a corner in `which`.
fn area_sums(mesh: &TriMesh, which: &[u32], class: &[u32]) -> (Vec<DVec3>, Vec<usize>) {
    let mut slot = vec![u32::MAX; mesh.positions.len()];
    for (i, &v) in which.iter().enumerate() {
        slot[v as usize] = class[i];
    }
    let mut n = vec![DVec3::ZERO; which.len()];
    let mut near = Vec::new();
    for (i, t) in mesh.triangles.iter().enumerate() {
        if t.iter().all(|&v| slot[v as usize] == u32::MAX) {
            continue;
        }
        near.push(i);
        let [a, b, c] = t.map(|v| mesh.positions[v as usize]);
        // The cross product's length is twice the area: area weighting for free.
        let w = (b - a).cross(c - a);
        for &v in t {
            if let Some(x) = n.get_mut(slot[v as usize] as usize) {
                *x += w;
            }
        }
    }
    (n, near)
}

/// The normals (unnormalized, by class of `which`) of the vertices of
/// `which` on the surface's rim: an edge to them that one triangle alone
/// uses, edges taken by position so that coincident copies (a soup's
/// corners, unwelded seams) count as one point.
///
/// A rim vertex sees the surface from one side only, and its own fan's
/// normal can be far from the surface's: on the ragged rim of a scan's
/// hole the fans are a few thin triangles, and on the bunny's base-hole
/// rims they differ from their inner neighbours' by 40° to 66°. An
/// inflate step of length `s` moves two neighbours apart by about
/// `s·|n₁ − n₂|`, and where that exceeds the height of a thin triangle
/// between them the triangle turns over within the frame: a crossing
/// the stroke made out of nothing, which the guard then holds (a dwell
/// on a bunny base-hole rim vertex, with remeshing, held 29 of its 40
/// frames from frame 11 on, where a rim triangle with sides of 0.6 to
/// 1.7 thousandths turned over under steps of 0.3 thousandths). So a
/// rim vertex takes the area-weighted normal of the triangles around it
/// and around its neighbours (its two-ring, 22° from the inner
/// neighbour's there): it moves as the surface beside it moves.
fn rim_normals(
    mesh: &TriMesh,
    which: &[u32],
    class: &[u32],
    sums: &[DVec3],
    near: &[usize],
) -> rustc_hash::FxHashMap<u32, DVec3> {
    type Key = [u64; 3];
    let mut found = rustc_hash::FxHashMap::default();
    let key = |v: u32| position_key(mesh.positions[v as usize]);
    let of_key: rustc_hash::FxHashMap<Key, u32> = which
        .iter()
        .zip(class)
        .map(|(&v, &c)| (key(v), c))
        .collect();
    let rim: rustc_hash::FxHashSet<Key> = rim_points(mesh, near)
        .into_iter()
        .filter(|p| of_key.contains_key(p))
        .collect();
    if rim.is_empty() {
        return found;
    }
    // The neighbours of each rim vertex, by position.
    let mut neighbours: rustc_hash::FxHashMap<Key, Vec<Key>> = Default::default();
    for &i in near {
        let k = mesh.triangles[i].map(key);
        for (j, p) in k.iter().enumerate() {
            if rim.contains(p) {
                let list = neighbours.entry(*p).or_default();
                for q in [k[(j + 1) % 3], k[(j + 2) % 3]] {
                    if q != *p && !list.contains(&q) {
                        list.push(q);
                    }
                }
            }
        }
    }
    // The area vectors around every such neighbour: a scan of the
    // triangles, hashing only those with a corner in the neighbours' box.
    let mut around: rustc_hash::FxHashMap<Key, DVec3> = neighbours
        .values()
        .flatten()
        .map(|&q| (q, DVec3::ZERO))
        .collect();
    let (lo, hi) = around
        .keys()
        .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), q| {
            let p = DVec3::from_array(q.map(f64::from_bits));
            (lo.min(p), hi.max(p))
        });
    let in_box = |p: DVec3| p.cmpge(lo).all() && p.cmple(hi).all();
    for t in &mesh.triangles {
        let [a, b, c] = t.map(|v| mesh.positions[v as usize]);
        if !(in_box(a) || in_box(b) || in_box(c)) {
            continue;
        }
        let k = t.map(key);
        let w = (b - a).cross(c - a);
        // A triangle counts once per distinct corner position.
        for (j, p) in k.iter().enumerate() {
            if k[..j].contains(p) {
                continue;
            }
            if let Some(x) = around.get_mut(p) {
                *x += w;
            }
        }
    }
    for (p, list) in &neighbours {
        let c = of_key[p];
        let own = sums[c as usize];
        // A neighbour across a crease folded back past a right angle
        // (a CAD part's thin wall, a sheet folded onto itself) is the
        // other side, not more of this one.
        let two_ring = list
            .iter()
            .map(|q| around[q])
            .filter(|n| n.dot(own) > 0.0)
            .sum::<DVec3>()
            + own;
        found.insert(c, two_ring);
    }
    found
}

/// The positions at the ends of the rim's sides among the triangles
/// `near`: the sides, taken by position (so that coincident copies, a
/// soup's corners or an unwelded seam, count as one point), that one
/// triangle alone uses in either direction.
///
/// A side two triangles share by vertex number is shared by position too,
/// so only the sides one triangle alone has by number (the rim's, and
/// both sides of a seam) can be; they are found by sorting numbers. Then
/// every side whose two ends lie at positions of theirs is counted by
/// position: that counts every side at each of their positions, so those
/// counted once are exactly the rim's. A closed, welded surface finds
/// none by number and hashes nothing.
fn rim_points(mesh: &TriMesh, near: &[usize]) -> rustc_hash::FxHashSet<[u64; 3]> {
    let key = |v: u32| position_key(mesh.positions[v as usize]);
    let sides = |i: usize| {
        let t = mesh.triangles[i];
        [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])]
    };
    let mut by_number: Vec<u64> = Vec::with_capacity(3 * near.len());
    for &i in near {
        for (a, b) in sides(i) {
            if key(a) != key(b) {
                by_number.push((u64::from(a.min(b)) << 32) | u64::from(a.max(b)));
            }
        }
    }
    by_number.sort_unstable();
    let mut ends: rustc_hash::FxHashSet<[u64; 3]> = Default::default();
    for run in by_number.chunk_by(|x, y| x == y) {
        if run.len() == 1 {
            ends.insert(key((run[0] >> 32) as u32));
            ends.insert(key(run[0] as u32));
        }
    }
    if ends.is_empty() {
        return ends;
    }
    let mut by_position: rustc_hash::FxHashMap<([u64; 3], [u64; 3]), u32> = Default::default();
    for &i in near {
        for (a, b) in sides(i) {
            let (ka, kb) = (key(a), key(b));
            if ka != kb && ends.contains(&ka) && ends.contains(&kb) {
                *by_position.entry((ka.min(kb), ka.max(kb))).or_insert(0) += 1;
            }
        }
    }
    by_position
        .into_iter()
        .filter(|(_, n)| *n == 1)
        .flat_map(|((a, b), _)| [a, b])
        .collect()
}

/// Vertices used by at least one triangle. Unreferenced vertices are not
/// part of the surface, so brushes leave them alone.
fn referenced(mesh: &TriMesh) -> Vec<bool> {
    let mut used = vec![false; mesh.positions.len()];
    for t in &mesh.triangles {
        for &v in t {
            used[v as usize] = true;
        }
    }
    used
}

/// The vertices within `radius` of `centre` that a triangle uses, in
/// increasing order: all a brush frame touches.
fn touched(mesh: &TriMesh, centre: DVec3, radius: f64) -> Vec<u32> {
    let inside: Vec<bool> = mesh
        .positions
        .iter()
        .map(|p| falloff(p.distance(centre), radius) > 0.0)
        .collect();
    let mut used = vec![false; mesh.positions.len()];
    for t in &mesh.triangles {
        for &v in t {
            used[v as usize] = inside[v as usize];
        }
    }
    (0..mesh.positions.len() as u32)
        .filter(|&v| used[v as usize])
        .collect()
}

/// One frame of a centred brush (every brush but grab, move and the snake
/// hook) at `centre`: the positions at the end of the frame. The others
/// are driven by [`crate::LiveStroke`] from their picks.
pub fn paint_at(
    mesh: &TriMesh,
    brush: Brush,
    centre: DVec3,
    radius: f64,
    strength: f64,
    curve: Falloff,
) -> Vec<DVec3> {
    match brush {
        Brush::Smooth => return smooth_with(mesh, centre, radius, strength, curve),
        Brush::Inflate | Brush::Grab | Brush::Move | Brush::SnakeHook => {
            return inflate_with(mesh, centre, radius, strength, curve);
        }
        _ => {}
    }
    let region = Region::gather(mesh, centre, radius, curve);
    match brush {
        Brush::Draw => draw::draw(mesh, &region, strength),
        Brush::Clay => clay::clay(mesh, &region, strength),
        Brush::Crease => crease::crease(mesh, &region, centre, radius, strength),
        Brush::Flatten => flatten::flatten(mesh, &region, strength),
        Brush::Pinch => pinch::pinch(mesh, &region, centre, strength),
        Brush::Scrape => scrape::scrape(mesh, &region, strength),
        Brush::Scale => scale::scale(mesh, &region, centre, strength),
        // The layer needs the stroke's heights: LiveStroke calls it
        // itself; without them it is a draw capped at half a layer.
        Brush::Layer => layer::layer(mesh, &region, strength, &mut layer::Heights::new()),
        _ => inflate_with(mesh, centre, radius, strength, curve),
    }
}

/// The closest point of a surface to `query`: `(triangle, point,
/// distance)`, the first triangle in order on ties, or `None` without
/// triangles. Brute force over all triangles: picking happens once per
/// stroke.
pub fn closest_point(mesh: &TriMesh, query: DVec3) -> Option<(usize, DVec3, f64)> {
    let mut best: Option<(usize, DVec3, f64)> = None;
    for (t, tri) in mesh.triangles.iter().enumerate() {
        let [a, b, c] = tri.map(|v| mesh.positions[v as usize]);
        let p = closest_on_triangle(query, a, b, c);
        let d = p.distance(query);
        if best.is_none_or(|(_, _, bd)| d < bd) {
            best = Some((t, p, d));
        }
    }
    best
}

/// The point of triangle `abc` closest to `p` (Ericson, *Real-Time
/// Collision Detection*, §5.1.5), by Voronoi regions; degenerate triangles
/// fall into an edge or vertex region and still give a point of the
/// triangle.
pub fn closest_on_triangle(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> DVec3 {
    let ab = b - a;
    let ac = c - a;
    let ap = p - a;
    let d1 = ab.dot(ap);
    let d2 = ac.dot(ap);
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = p - b;
    let d3 = ab.dot(bp);
    let d4 = ac.dot(bp);
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let v = d1 / (d1 - d3);
        return a + v * ab;
    }
    let cp = p - c;
    let d5 = ab.dot(cp);
    let d6 = ac.dot(cp);
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let w = d2 / (d2 - d6);
        return a + w * ac;
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return b + w * (c - b);
    }
    let denom = va + vb + vc;
    if denom == 0.0 || !denom.is_finite() {
        // Collinear corners that escaped the edge tests by rounding: the
        // nearest corner is a point of the triangle and close enough.
        return [a, b, c]
            .into_iter()
            .min_by(|x, y| x.distance_squared(p).total_cmp(&y.distance_squared(p)))
            .unwrap_or(a);
    }
    let v = vb / denom;
    let w = vc / denom;
    a + ab * v + ac * w
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn tetra() -> TriMesh {
        let (positions, triangles) = holey_testkit::tetrahedron();
        TriMesh::from_arrays(&positions, &triangles)
    }

    #[test]
    fn falloff_shape() {
        assert_eq!(falloff(0.0, 1.0), 1.0);
        assert_eq!(falloff(1.0, 1.0), 0.0);
        assert_eq!(falloff(2.0, 1.0), 0.0);
        assert!((falloff(0.5, 1.0) - 0.5625).abs() < 1e-15);
        assert_eq!(falloff(0.0, 0.0), 0.0);
        assert_eq!(falloff(f64::NAN, 1.0), 0.0);
    }

    #[test]
    fn normals_point_outwards_on_a_ccw_tetrahedron() {
        let m = tetra();
        for (p, n) in m.positions.iter().zip(vertex_normals(&m)) {
            assert!((n.length() - 1.0).abs() < 1e-12);
            assert!(n.dot(*p) > 0.0, "normal {n} at {p} points inwards");
        }
    }

    /// A patch of a cylinder, `n × n` squares over a third of a turn,
    /// each cut into two triangles facing outwards.
    fn cylinder_patch(n: u32) -> TriMesh {
        let at = |i: u32, j: u32| {
            let angle = f64::from(i) / f64::from(n) * 2.0;
            DVec3::new(angle.cos(), angle.sin(), f64::from(j) / f64::from(n))
        };
        let index = |i: u32, j: u32| i * (n + 1) + j;
        TriMesh {
            positions: (0..=n)
                .flat_map(|i| (0..=n).map(move |j| at(i, j)))
                .collect(),
            triangles: (0..n)
                .flat_map(|i| {
                    (0..n).flat_map(move |j| {
                        let (a, b) = (index(i, j), index(i + 1, j));
                        let (c, d) = (index(i + 1, j + 1), index(i, j + 1));
                        [[a, b, c], [a, c, d]]
                    })
                })
                .collect(),
        }
    }

    /// `rim_points` finds the patch's rim, its outer ring of vertices (7 ×
    /// 7 grid: i or j at 0 or 6), welded, as a soup and with its two halves
    /// unwelded along a seam; a sphere has none.
    #[test]
    fn the_rim_is_the_patch_outline_welded_unwelded_or_a_soup() {
        let welded = cylinder_patch(6);
        let outline: std::collections::BTreeSet<[u64; 3]> = (0..49)
            .filter(|v| [0, 6].contains(&(v / 7)) || [0, 6].contains(&(v % 7)))
            .map(|v| position_key(welded.positions[v]))
            .collect();
        let all = |m: &TriMesh| (0..m.triangles.len()).collect::<Vec<_>>();
        let rim = |m: &TriMesh| {
            rim_points(m, &all(m))
                .into_iter()
                .collect::<std::collections::BTreeSet<_>>()
        };
        assert_eq!(rim(&welded), outline, "welded");
        let soup = welded.unwelded();
        assert_eq!(rim(&soup), outline, "soup");
        // The second half of the triangles gets its own copies.
        let mut seamed = welded.clone();
        let half = seamed.triangles.len() / 2;
        let mut copy = std::collections::HashMap::new();
        for t in &mut seamed.triangles[half..] {
            for v in t.iter_mut() {
                *v = *copy.entry(*v).or_insert_with(|| {
                    seamed.positions.push(welded.positions[*v as usize]);
                    (seamed.positions.len() - 1) as u32
                });
            }
        }
        assert_eq!(rim(&seamed), outline, "seamed");
        let sphere = octahedron();
        assert!(rim(&sphere).is_empty(), "a sphere has no rim");
    }

    /// testkit's closed octahedron.
    fn octahedron() -> TriMesh {
        let (p, t) = holey_testkit::octahedron();
        TriMesh {
            positions: p.iter().map(|&c| DVec3::from_array(c)).collect(),
            triangles: t.to_vec(),
        }
    }

    /// The rim is found by position: the same patch as a soup (every
    /// triangle its own three corners) gets, at every corner, the normal
    /// of the welded vertex there, on the rim too, where the rim normals
    /// differ from the one-ring's. Inside the patch both are the
    /// one-ring's, and every normal faces outwards from the axis.
    #[test]
    fn rim_normals_are_the_same_on_a_soup_and_welded() {
        let welded = cylinder_patch(6);
        let soup = welded.unwelded();
        let of_welded = vertex_normals(&welded);
        let of_soup = vertex_normals(&soup);
        for (corner, t) in welded.triangles.iter().flatten().enumerate() {
            let (w, s) = (of_welded[*t as usize], of_soup[corner]);
            assert!((w - s).length() < 1e-12, "corner {corner}: {w} against {s}");
        }
        let one_ring = |v: usize| {
            let mut n = DVec3::ZERO;
            for t in welded.triangles.iter().filter(|t| t.contains(&(v as u32))) {
                let [a, b, c] = t.map(|u| welded.positions[u as usize]);
                n += (b - a).cross(c - a);
            }
            n.normalize()
        };
        let mut rim_moved = 0;
        for (v, (&p, &n)) in welded.positions.iter().zip(&of_welded).enumerate() {
            let radial = DVec3::new(p.x, p.y, 0.0);
            assert!(n.dot(radial) > 0.9, "vertex {v} at {p}: normal {n}");
            let (i, j) = (v / 7, v % 7);
            let inner = (1..6).contains(&i) && (1..6).contains(&j);
            if inner {
                assert!((n - one_ring(v)).length() < 1e-12, "inner vertex {v}");
            } else if (n - one_ring(v)).length() > 1e-6 {
                rim_moved += 1;
            }
        }
        assert!(rim_moved > 0, "rim vertices take the two-ring's normal");
    }

    /// A small square (two triangles facing +z) with a large sheet folded
    /// back over it from one side (a hairpin: the sheet faces down). The
    /// square's rim vertices take their two-ring's normal, but the
    /// crease vertices' normals, dominated by the folded sheet, are the
    /// other side: left out, the square's corners keep facing up (summed
    /// in, the one away from the crease would face down).
    #[test]
    fn a_sheet_folded_back_is_not_averaged_in() {
        let m = TriMesh {
            positions: vec![
                DVec3::new(0.0, 0.0, 0.0),  // w, on the crease
                DVec3::new(1.0, 0.0, 0.0),  // v
                DVec3::new(1.0, 1.0, 0.0),  // p
                DVec3::new(0.0, 1.0, 0.0),  // u, on the crease
                DVec3::new(10.0, 0.0, 0.5), // q, the folded sheet
                DVec3::new(10.0, 1.0, 0.5), // s
            ],
            triangles: vec![[0, 1, 2], [0, 2, 3], [0, 3, 5], [0, 5, 4]],
        };
        let n = vertex_normals(&m);
        for v in [1, 2] {
            assert!(n[v].z > 0.99, "corner {v} of the square faces {}", n[v]);
        }
        for v in [4, 5] {
            assert!(
                n[v].z < -0.99,
                "corner {v} of the folded sheet faces {}",
                n[v]
            );
        }
    }

    #[test]
    fn inflate_moves_only_within_the_radius() {
        let m = tetra();
        let out = inflate(&m, m.positions[0], 1.0, 0.1);
        assert!((out[0].length() - m.positions[0].length() - 0.1).abs() < 1e-12);
        assert_eq!(&out[1..], &m.positions[1..]);
        let deflated = inflate(&m, m.positions[0], 1.0, -0.1);
        assert!(deflated[0].length() < m.positions[0].length());
    }

    #[test]
    fn smooth_moves_towards_the_neighbour_mean() {
        // A fan: the centre lifted above its planar ring.
        let mut positions = vec![DVec3::new(0.0, 0.0, 1.0)];
        for k in 0..6 {
            let a = k as f64 * std::f64::consts::TAU / 6.0;
            positions.push(DVec3::new(a.cos(), a.sin(), 0.0));
        }
        let triangles = (0..6).map(|k| [0, 1 + k, 1 + (k + 1) % 6]).collect();
        let m = TriMesh {
            positions,
            triangles,
        };
        let out = smooth(&m, DVec3::new(0.0, 0.0, 1.0), 0.5, 1.0);
        assert!(out[0].z.abs() < 1e-12, "full step reaches the mean");
        assert_eq!(&out[1..], &m.positions[1..], "ring is outside the radius");
        let half = smooth(&m, DVec3::new(0.0, 0.0, 1.0), 0.5, 0.5);
        assert!((half[0].z - 0.5).abs() < 1e-12);
    }

    #[test]
    fn closest_point_regions() {
        let (a, b, c) = (DVec3::ZERO, DVec3::X, DVec3::Y);
        let q = closest_on_triangle(DVec3::new(0.2, 0.2, 5.0), a, b, c);
        assert!((q - DVec3::new(0.2, 0.2, 0.0)).length() < 1e-15);
        assert_eq!(closest_on_triangle(DVec3::new(-1.0, -1.0, 0.0), a, b, c), a);
        let e = closest_on_triangle(DVec3::new(0.5, -3.0, 1.0), a, b, c);
        assert!((e - DVec3::new(0.5, 0.0, 0.0)).length() < 1e-15);
        let h = closest_on_triangle(DVec3::new(1.0, 1.0, 0.0), a, b, c);
        assert!((h - DVec3::new(0.5, 0.5, 0.0)).length() < 1e-15);
        // Degenerate: all three corners on a line.
        let d = closest_on_triangle(DVec3::new(0.5, 1.0, 0.0), a, b, 2.0 * b);
        assert!((d - DVec3::new(0.5, 0.0, 0.0)).length() < 1e-15);
        let m = tetra();
        let (_, p, dist) = closest_point(&m, DVec3::new(3.0, 3.0, 3.0)).unwrap();
        assert_eq!(p, m.positions[0]);
        assert!((dist - 12f64.sqrt()).abs() < 1e-12);
        assert!(closest_point(&TriMesh::default(), DVec3::ZERO).is_none());
    }

    #[test]
    fn components_and_weights() {
        let mut m = tetra();
        let n = m.positions.len() as u32;
        m.positions
            .extend(tetra().positions.iter().map(|p| *p + DVec3::X * 10.0));
        m.triangles
            .extend(tetra().triangles.iter().map(|t| t.map(|v| v + n)));
        m.positions.push(DVec3::ZERO); // unreferenced
        let c = component_of(&m, 5);
        assert_eq!(c.iter().filter(|&&x| x).count(), 4);
        assert!(c[4..8].iter().all(|&x| x));
        let w = grab_weights(&m, DVec3::ZERO, 100.0);
        assert_eq!(w[8], 0.0, "unreferenced vertices are not grabbed");
        assert!(w[0] > 0.0);
        assert!(component_of(&m, 99).iter().all(|&x| !x));
    }
}
