//! A frame resolved by containment number where the surface is a solid:
//! the result parity-based topology change gives a solid (Appendix C,
//! Lemma 8.1), computed from the final surface so that it is closed by
//! construction.
//!
//! For a solid, collision parity deletes exactly the surface whose two
//! sides are both inside or both outside (Lemma 8.1). The discrete parity
//! field only approximates that: it is sampled at vertices, misses what
//! passes between them (two edges crossing, a fold between a fan's
//! triangles), and a drag that folds the surface over itself (a grab
//! pushed against its own falloff) collides it with itself all along the
//! fold; error correction then has no consistent field to find, and on a
//! scan with holes underneath the solid guard ([`crate::solid`]), which
//! needs a closed mesh, cannot step in. So where the brushed region is a
//! piece of a solid — every edge there has two triangles running opposite
//! ways, and the region did not cross itself before the frame — the frame
//! is resolved from the surface it ends on: the arrangement of the region
//! (cut along every curve the frame made) keeps each piece whose two sides
//! differ in being inside, by the *sign* interpretation of Appendix C
//! (inside where the containment number, counted with the surface's own
//! orientation, is at least 1): the union of everything the surface
//! encloses. For ω ∈ {−1, 0, 1, 2}, all a frame of sculpting makes, it
//! agrees with the modulo interpretation the lemma names: a part pushed
//! through the far wall turns inside out there (ω = −1) and is deleted,
//! which opens Figure 1's tunnel; a part pushed into a body (ω = 2) fuses
//! with it. Where a crumpled drag overlaps a part three times it keeps the
//! union whole instead of opening a void inside it.
//!
//! The containment number of a piece comes from the generalized winding
//! number ([`crate::winding`]) of the whole surface at a point of it, so a
//! mesh open far from the brush (a scan's holes underneath) still counts
//! as the solid it is where it is sculpted: a piece whose winding number
//! is not within a quarter of an integer on both sides makes the frame
//! fall back to parity.

use glam::DVec3;

use crate::cut::{AroundCurve, Deletion, cancel_opposite, cut, reconnect_crossings, same_corners};
use crate::engine::{
    Geometry, Options, Outcome, Report, TopoError, geometry, old_curves, split_new_pinches,
};
use crate::far_field::{Ask, FarField};
use crate::local::Bounds;
use crate::mesh::{Edges, TriMesh, repeats_a_corner};
use crate::solid::{regions, signed_volume};
use crate::union_find::UnionFind;
use crate::winding::{
    FEW_POINTS, WindingField, winding_numbers_and_volume_at, winding_numbers_at,
    winding_numbers_without_own,
};

/// How far a winding number may be from an integer for its piece to be
/// labelled by it: a quarter (holes far away shift it by the solid angle
/// they subtend; one that shifts it by a quarter is no longer far away).
const WINDING_SLACK: f64 = 0.25;

/// How near an integer a piece's winding number must be for its sample to
/// decide it (see `settle_unsure`).
const SURE: f64 = 0.05;

/// Most pieces a frame relabels by winding number (one query each); a
/// frame that crumples the surface into more falls back to parity, whose
/// result the guard still checks.
const MAX_LABELLED_PIECES: usize = 4096;

/// The surface around a region, for winding numbers: the triangles of the
/// whole mesh outside the region, at the frame's end positions. Gathered
/// on first use: most frames cross nothing and never need them.
pub(crate) struct Surroundings<'a> {
    mesh: &'a TriMesh,
    inside: &'a [bool],
    pub positions: &'a [DVec3],
    orientation: std::sync::OnceLock<f64>,
    outside: std::sync::OnceLock<Vec<[u32; 3]>>,
    /// A stroke's kept field, and the box of the region's vertices at the
    /// start and the end ([`FarField`]).
    far: Option<(&'a FarField, Bounds)>,
}

impl<'a> Surroundings<'a> {
    /// The triangles of `mesh` that `inside` does not flag, at `end`;
    /// with `far`, a stroke's kept field and the box of the region's
    /// vertices at the start and at `end`.
    pub fn new(
        mesh: &'a TriMesh,
        inside: &'a [bool],
        end: &'a [DVec3],
        far: Option<(&'a FarField, Bounds)>,
    ) -> Surroundings<'a> {
        Surroundings {
            mesh,
            inside,
            positions: end,
            orientation: std::sync::OnceLock::new(),
            outside: std::sync::OnceLock::new(),
            far,
        }
    }

    /// The sign of the whole surface's signed volume at the end: +1 when
    /// it faces outward (inside has winding number +1), −1 when inward.
    pub fn orientation(&self) -> f64 {
        *self
            .orientation
            .get_or_init(|| orientation_of(signed_volume(self.positions, &self.mesh.triangles)))
    }

    /// The winding numbers of the outside triangles at `points`: up to
    /// [`FEW_POINTS`] points summed over them once for all, for more
    /// from the stroke's kept field ([`FarField`]) where the caller keeps
    /// one, else from an octree field built for this query.
    pub fn winding_numbers_at(&self, points: &[DVec3]) -> Vec<f64> {
        if let Some((far, region)) = self.far
            && let Some((w, volume)) = far.winding_numbers_and_volume_at(&Ask {
                mesh: self.mesh,
                inside: self.inside,
                end: self.positions,
                region,
                points,
            })
        {
            let _ = self.orientation.set(orientation_of(volume));
            return w;
        }
        let at = |v: u32| self.positions[v as usize];
        if points.len() <= FEW_POINTS {
            let keep = |t: usize| !self.inside[t];
            if self.orientation.get().is_some() {
                return winding_numbers_at(&self.mesh.triangles, &keep, &at, points);
            }
            // The orientation comes with the pass: one pass over the
            // whole surface instead of two.
            let (far, volume) =
                winding_numbers_and_volume_at(&self.mesh.triangles, &keep, &at, points);
            let _ = self.orientation.set(orientation_of(volume));
            return far;
        }
        // One pass gathers the outside triangles and sums six times the
        // signed volume of the region's: the orientation then comes from
        // the field's volume and the region's, with no pass of its own.
        let mut region_six = None;
        let outside = self.outside.get_or_init(|| {
            let mut six = 0.0;
            let mut outside = Vec::new();
            for (t, &inside) in self.mesh.triangles.iter().zip(self.inside) {
                if inside {
                    let [a, b, c] = t.map(at);
                    six += a.dot(b.cross(c));
                } else {
                    outside.push(*t);
                }
            }
            region_six = Some(six);
            outside
        });
        let field = WindingField::new(outside, &at);
        if self.orientation.get().is_none() {
            // Every call that gathers the outside sets the orientation,
            // so it is unset only here, where the pass just ran.
            let region = region_six.unwrap_or(0.0) / 6.0;
            let _ = self
                .orientation
                .set(orientation_of(field.signed_volume() + region));
        }
        points.iter().map(|&p| field.at(p, None)).collect()
    }
}

/// +1 for a surface of positive signed volume (facing outward), −1 for
/// one of negative volume.
fn orientation_of(volume: f64) -> f64 {
    if volume < 0.0 { -1.0 } else { 1.0 }
}

/// The frame of `sub` (a region of a mesh, at its start positions)
/// moving to `end`, resolved by containment number (module
/// documentation); `None` when the region is not a piece of a solid (a
/// non-manifold edge, two triangles running the same way along an edge,
/// a degenerate triangle), it crossed itself before the frame, or some
/// piece's winding number is not near an integer.
pub(crate) fn by_containment(
    sub: &TriMesh,
    end: &[DVec3],
    options: &Options,
    surroundings: &Surroundings<'_>,
    known: Option<Geometry>,
) -> Result<Option<Outcome>, TopoError> {
    let started = std::time::Instant::now();
    let edges = Edges::new(sub);
    if !piece_of_a_solid(sub, &edges) {
        return Ok(None);
    }
    // The end's intersections, unless the caller has them for this very
    // submesh and end already.
    let g = match known {
        Some(g) => g,
        None => geometry(sub, end, options)?,
    };
    let (edges, ids, x) = (g.edges, g.ids, g.x);
    if x.pairs.is_empty() {
        // Nothing crosses at the end: the frame only moves the surface.
        let n = sub.positions.len();
        return Ok(Some(Outcome {
            mesh: TriMesh {
                positions: end.to_vec(),
                triangles: sub.triangles.clone(),
            },
            report: Report {
                solid_input: true,
                ..Report::default()
            },
            raw_odd: vec![false; n],
            corrected_odd: vec![false; n],
            intersections: x,
            vertex_origin: (0..n as u32).collect(),
        }));
    }
    if old_curves(sub, &x)?.contains(&true) {
        return Ok(None);
    }
    let mut arrangement = cut(sub, end, &edges, &ids, &x, Deletion::Nothing, None);
    let arr = &arrangement.mesh;
    let region = regions(arr);
    let count = region.iter().copied().max().map_or(0, |r| r as usize + 1);
    // Only the pieces a curve bounds are relabelled; a piece no curve of
    // the frame touches stays as it is (an inner shell the surface had,
    // say, which the containment number would call inside).
    let arr_edges = Edges::new(arr);
    let mut touched = vec![false; count];
    for e in 0..arr_edges.len() {
        let around = arr_edges.triangles(e);
        if around.len() > 2 {
            for &t in around {
                touched[region[t as usize] as usize] = true;
            }
        }
    }
    if touched.iter().filter(|&&t| t).count() > MAX_LABELLED_PIECES {
        return Ok(None);
    }
    let inside = |w: f64| surroundings.orientation() * w >= 0.5;
    let Some((mut label, unsure)) = label_pieces(arr, &region, &touched, surroundings) else {
        return Ok(None);
    };
    settle_unsure(arr, &arr_edges, &region, &unsure, &mut label);
    let mut keep: Vec<bool> = region.iter().map(|&r| label[r as usize].0).collect();
    // The triangles as they will be output: reversed where their inside
    // lies in front.
    let output: Vec<[u32; 3]> = arr
        .triangles
        .iter()
        .enumerate()
        .map(|(t, tri)| {
            if label[region[t] as usize].1 {
                [tri[0], tri[2], tri[1]]
            } else {
                *tri
            }
        })
        .collect();
    fill_voids(
        arr,
        &output,
        &region,
        &touched,
        &mut keep,
        surroundings,
        &inside,
    );
    // As in a motion's cut: one triangle twice from two sources, facing
    // opposite ways, a pillow of no volume, cancels (`cut/coincident.rs`);
    // where all four sides of a crossing are kept (an open sheet's rim
    // through another sheet near that sheet's rim: a curve that bounds no
    // piece), the sheets fuse instead of meeting at a non-manifold edge
    // (`cut/crossings.rs`). The paper's part assembly keeps both.
    let mut output = output;
    let mut positions = arr.positions.clone();
    let (mut pillows, mut reconnected) = (0, 0);
    if !options.nonmanifold_joins {
        let source_of = |t: usize| sub.triangles[arrangement.source[t].0 as usize];
        // Only a triangle with a point the cut made can be half of one.
        let made = |v: u32| arrangement.origin.get(v as usize) == Some(&u32::MAX);
        pillows = cancel_opposite(
            &output,
            &mut keep,
            |t| output[t].iter().any(|&v| made(v)),
            |i, j| !same_corners(source_of(i), source_of(j)),
        );
        // The edges where sheets meet, with their triangles.
        let around: AroundCurve = (0..arr_edges.len())
            .filter(|&e| arr_edges.triangles(e).len() > 2)
            .map(|e| {
                let [a, b] = arr_edges.ends[e];
                let on: Vec<usize> = arr_edges.triangles(e).iter().map(|&t| t as usize).collect();
                ((a, b), on)
            })
            .collect();
        reconnected = reconnect_crossings(
            &mut output,
            &mut keep,
            std::mem::take(&mut arrangement.source),
            &around,
            &mut positions,
        );
    }
    let mut triangles = Vec::with_capacity(output.len());
    let mut deleted = 0;
    for (t, tri) in output.iter().enumerate() {
        if keep[t] {
            triangles.push(*tri);
        } else {
            deleted += 1;
        }
    }
    let (mut mesh, local) = TriMesh {
        positions,
        triangles,
    }
    .compacted_with_origin();
    let mut origin: Vec<u32> = local
        .iter()
        // A point a crossing's split made is new.
        .map(|&v| {
            arrangement
                .origin
                .get(v as usize)
                .copied()
                .unwrap_or(u32::MAX)
        })
        .collect();
    let mut cut_report = arrangement.report;
    cut_report.triangles_deleted = deleted;
    cut_report.crossings_reconnected = reconnected;
    cut_report.opposite_pairs_cancelled = pillows;
    cut_report.solid_relabelled = true;
    cut_report.pinches_split = split_new_pinches(&mut mesh, &mut origin, sub);
    // A vertex of the input is deleted when no output vertex comes from it.
    let mut kept = vec![false; sub.positions.len()];
    for &o in &origin {
        if let Some(k) = kept.get_mut(o as usize) {
            *k = true;
        }
    }
    let used = {
        let mut used = vec![false; sub.positions.len()];
        for t in &sub.triangles {
            for &v in t {
                used[v as usize] = true;
            }
        }
        used
    };
    let corrected: Vec<bool> = kept.iter().zip(&used).map(|(&k, &u)| u && !k).collect();
    let report = Report {
        corrected_odd_vertices: corrected.iter().filter(|&&o| o).count(),
        cut: cut_report,
        solid_input: true,
        timings: crate::engine::Timings {
            total: started.elapsed().as_secs_f64(),
            ..Default::default()
        },
        ..Report::of_intersections(&x)
    };
    Ok(Some(Outcome {
        mesh,
        report,
        raw_odd: vec![false; sub.positions.len()],
        corrected_odd: corrected,
        intersections: x,
        vertex_origin: origin,
    }))
}

/// A piece's fate: keep it, and flip it.
type Label = (bool, bool);

/// Per piece of the arrangement `arr` (pieces `region`) that a curve
/// `touched`: keep it, and flip it (its inside lies on the other side of
/// it than the rest of the surface's does), from the containment number
/// at a sample on its largest triangle (the arrangement's own near field
/// plus the `surroundings`' far field); and the pieces whose sample was
/// not sure (within rounding of another sheet), for their neighbours to
/// decide. `None` when some piece's winding number is not near an
/// integer.
fn label_pieces(
    arr: &TriMesh,
    region: &[u32],
    touched: &[bool],
    surroundings: &Surroundings<'_>,
) -> Option<(Vec<Label>, Vec<usize>)> {
    let area = |t: &[u32; 3]| {
        let [a, b, c] = t.map(|v| arr.positions[v as usize]);
        (b - a).cross(c - a).length()
    };
    let count = touched.len();
    let mut seed: Vec<Option<(f64, usize)>> = vec![None; count];
    for (t, tri) in arr.triangles.iter().enumerate() {
        let r = region[t] as usize;
        let a = area(tri);
        if touched[r] && seed[r].is_none_or(|(best, _)| a > best) {
            seed[r] = Some((a, t));
        }
    }
    // The sign interpretation: inside where the containment number,
    // counted with the surface's own orientation, is at least 1.
    let inside = |w: f64| surroundings.orientation() * w >= 0.5;
    let arr_at = |v: u32| arr.positions[v as usize];
    // Per region: keep, and flip (its inside lies on the other side of it
    // than the rest of the surface's does).
    let mut label = vec![(true, false); count];
    // Pieces whose winding number is not within a twentieth of an
    // integer are slivers between curves meeting at a point, whose sample
    // lies within rounding of another sheet: they are decided by their
    // neighbours below instead.
    let mut unsure: Vec<usize> = Vec::new();
    let samples: Vec<(usize, usize, DVec3)> = seed
        .iter()
        .enumerate()
        .filter_map(|(r, s)| {
            let (_, t) = (*s)?;
            Some((
                r,
                t,
                arr.triangles[t].map(arr_at).iter().sum::<DVec3>() / 3.0,
            ))
        })
        .collect();
    let points: Vec<DVec3> = samples.iter().map(|s| s.2).collect();
    let own: Vec<Option<usize>> = samples.iter().map(|s| Some(s.1)).collect();
    let near = winding_numbers_without_own(&arr.triangles, &arr_at, &points, &own);
    // The far field first: its pass also finds the orientation.
    let far = surroundings.winding_numbers_at(&points);
    let outward = surroundings.orientation() > 0.0;
    for ((&(r, _, _), far), near) in samples.iter().zip(far).zip(near) {
        let w = near + far;
        // The seed's own triangle adds ±1/2 on its two sides.
        let (behind, front) = (w + 0.5, w - 0.5);
        let off = (behind - behind.round()).abs();
        if off > WINDING_SLACK {
            return None;
        }
        if off > SURE {
            unsure.push(r);
        }
        label[r] = (inside(behind) != inside(front), inside(behind) != outward);
    }
    Some((label, unsure))
}

/// Decides the pieces in `unsure` by the pieces around them: at an edge
/// where curves cross (four pieces, two per sheet), a 2-manifold keeps
/// exactly two, running opposite ways along it. So an unsure piece is
/// kept where one of the others at its curve edges is, deleted where two
/// are (a vote over its curve edges), and faces against the kept one.
/// Repeated while it settles something, for unsure pieces next to each
/// other.
fn settle_unsure(
    arr: &TriMesh,
    edges: &Edges,
    region: &[u32],
    unsure: &[usize],
    label: &mut [(bool, bool)],
) {
    let mut open: Vec<usize> = unsure.to_vec();
    let mut decided = vec![true; label.len()];
    for &r in &open {
        decided[r] = false;
    }
    // Each unsure piece's curve edges.
    let mut curve_edges: rustc_hash::FxHashMap<usize, Vec<usize>> = Default::default();
    for e in 0..edges.len() {
        let around = edges.triangles(e);
        if around.len() > 2 {
            for &t in around {
                let r = region[t as usize] as usize;
                if !decided[r] {
                    curve_edges.entry(r).or_default().push(e);
                }
            }
        }
    }
    // Whether triangle `t` (as output, flipped per `flip`) runs along edge
    // `e` from its first end.
    let runs = |t: u32, e: usize, flip: bool| {
        edges
            .runs_forward(&arr.triangles, t, e)
            .map(|forward| forward != flip)
    };
    loop {
        let mut progress = false;
        open.retain(|&r| {
            let mut votes = (0i32, 0i32); // (keep, delete)
            let mut facing: Option<bool> = None;
            for &e in curve_edges.get(&r).map(Vec::as_slice).unwrap_or(&[]) {
                let around = edges.triangles(e);
                let own = around.iter().find(|&&t| region[t as usize] as usize == r);
                let others: Vec<u32> = around
                    .iter()
                    .copied()
                    .filter(|&t| region[t as usize] as usize != r)
                    .collect();
                if others
                    .iter()
                    .any(|&t| !decided[region[t as usize] as usize])
                {
                    continue;
                }
                let kept: Vec<u32> = others
                    .iter()
                    .copied()
                    .filter(|&t| label[region[t as usize] as usize].0)
                    .collect();
                match kept.len() {
                    1 => {
                        votes.0 += 1;
                        if let (Some(&own), Some(other)) = (own, kept.first()) {
                            let theirs = runs(*other, e, label[region[*other as usize] as usize].1);
                            let mine = runs(own, e, false);
                            if let (Some(theirs), Some(mine)) = (theirs, mine) {
                                // Opposite ways: flip when the unflipped
                                // piece runs the same way as the kept one.
                                facing = Some(mine == theirs);
                            }
                        }
                    }
                    _ => votes.1 += 1,
                }
            }
            if votes == (0, 0) {
                return true;
            }
            label[r] = (votes.0 > votes.1, facing.unwrap_or(label[r].1));
            decided[r] = true;
            progress = true;
            false
        });
        if !progress || open.is_empty() {
            break;
        }
    }
}

/// Deletes the closed pieces of the kept surface that a relabelled piece
/// belongs to and that the rest of the surface encloses: voids a closing
/// crease traps, a part pushed wholly inside. By the sign
/// interpretation they bound outside space, but space nobody can reach:
/// a hidden shell inside the solid, which a sculptor sees nothing of and
/// every later frame pays for. Shells that no curve of the frame touches
/// are left alone.
fn fill_voids(
    arr: &TriMesh,
    output: &[[u32; 3]],
    region: &[u32],
    touched: &[bool],
    keep: &mut [bool],
    surroundings: &Surroundings<'_>,
    inside: &dyn Fn(f64) -> bool,
) {
    // Components of the kept triangles, through edges that exactly two
    // kept triangles share (not through single vertices: where a void
    // touched the outer surface at a point, that point is split later).
    let mut sets = UnionFind::new(arr.triangles.len());
    let mut sides: Vec<((u32, u32), u32)> = Vec::new();
    for (t, tri) in arr.triangles.iter().enumerate() {
        if keep[t] {
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                sides.push(((a.min(b), a.max(b)), t as u32));
            }
        }
    }
    sides.sort_unstable();
    for run in sides.chunk_by(|x, y| x.0 == y.0) {
        if let [(_, t), (_, u)] = run {
            sets.union(*t, *u);
        }
    }
    // Per component (by its root): touched by a curve, and open for sure
    // (a side no other kept triangle has). Only the components left are
    // gathered and checked for closedness edge by edge: the surface
    // around the brush is one big open component, which this way costs
    // no more than the sort above.
    let n = arr.triangles.len();
    let mut touched_root = vec![false; n];
    let mut open_root = vec![false; n];
    for run in sides.chunk_by(|x, y| x.0 == y.0) {
        if let [(_, t)] = run {
            let r = sets.find(*t) as usize;
            open_root[r] = true;
        }
    }
    let mut members_of: rustc_hash::FxHashMap<u32, Vec<usize>> = Default::default();
    for t in (0..n).filter(|&t| keep[t]) {
        let r = sets.find(t as u32);
        touched_root[r as usize] |= touched[region[t] as usize];
        if !open_root[r as usize] {
            members_of.entry(r).or_default().push(t);
        }
    }
    let candidates: Vec<Vec<usize>> = members_of
        .into_iter()
        .filter(|(r, members)| touched_root[*r as usize] && closed(arr, members))
        .map(|(_, members)| members)
        .collect();
    if candidates.is_empty() {
        return;
    }
    let kept: Vec<[u32; 3]> = output
        .iter()
        .zip(keep.iter())
        .filter(|(_, k)| **k)
        .map(|(t, _)| *t)
        .collect();
    let kept_index: Vec<usize> = (0..arr.triangles.len()).filter(|&t| keep[t]).collect();
    let arr_at = |v: u32| arr.positions[v as usize];
    // At a point of each shell's first triangle, the rest of the kept
    // surface: everything kept but that triangle, less the rest of the
    // shell, which a closed surface's own point sees as a half (of the
    // sign of its orientation).
    let points: Vec<DVec3> = candidates
        .iter()
        .map(|members| output[members[0]].map(arr_at).iter().sum::<DVec3>() / 3.0)
        .collect();
    let own: Vec<Option<usize>> = candidates
        .iter()
        .map(|members| kept_index.binary_search(&members[0]).ok())
        .collect();
    let near = winding_numbers_without_own(&kept, &arr_at, &points, &own);
    let far = surroundings.winding_numbers_at(&points);
    for ((members, far), near) in candidates.into_iter().zip(far).zip(near) {
        let volume: f64 = members
            .iter()
            .map(|&t| {
                let [a, b, c] = output[t].map(arr_at);
                a.dot(b.cross(c))
            })
            .sum();
        let shell = if volume < 0.0 { -0.5 } else { 0.5 };
        let w = near - shell + far;
        if inside(w) {
            for t in members {
                keep[t] = false;
            }
        }
    }
}

/// Whether the triangles `members` of `mesh` use every edge of theirs
/// exactly twice (a closed surface).
fn closed(mesh: &TriMesh, members: &[usize]) -> bool {
    let mut count: rustc_hash::FxHashMap<(u32, u32), u32> = Default::default();
    for &t in members {
        let tri = mesh.triangles[t];
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            *count.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    count.values().all(|&c| c == 2)
}

/// Whether every edge of `sub` has one triangle (where the region meets
/// the rest of the mesh, a seam, or a hole: the winding numbers decide
/// whether the surface is closed enough there) or two running opposite
/// ways, and no triangle repeats a vertex.
fn piece_of_a_solid(sub: &TriMesh, edges: &Edges) -> bool {
    if sub.triangles.iter().any(repeats_a_corner) {
        return false;
    }
    (0..edges.len()).all(|e| match edges.triangles(e).len() {
        1 => true,
        2 => edges.opposite(&sub.triangles, e),
        _ => false,
    })
}
