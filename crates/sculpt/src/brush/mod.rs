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
/// order: one scan of the triangles, work only where they are used.
fn normals_of(mesh: &TriMesh, which: &[u32]) -> Vec<DVec3> {
    let mut slot = vec![u32::MAX; mesh.positions.len()];
    let class = coincident(mesh, which);
    for (i, &v) in which.iter().enumerate() {
        slot[v as usize] = class[i];
    }
    let mut n = vec![DVec3::ZERO; which.len()];
    for t in &mesh.triangles {
        if t.iter().all(|&v| slot[v as usize] == u32::MAX) {
            continue;
        }
        let [a, b, c] = t.map(|v| mesh.positions[v as usize]);
        // The cross product's length is twice the area: area weighting for free.
        let w = (b - a).cross(c - a);
        for &v in t {
            if let Some(x) = n.get_mut(slot[v as usize] as usize) {
                *x += w;
            }
        }
    }
    class
        .iter()
        .map(|&c| n[c as usize].normalize_or_zero())
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
        let (positions, triangles) = holey_testkit::meshes::tetrahedron();
        TriMesh {
            positions: positions.map(DVec3::from_array).to_vec(),
            triangles: triangles.to_vec(),
        }
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
