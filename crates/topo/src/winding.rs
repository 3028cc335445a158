//! The generalized winding number of a triangle mesh (Jacobson, Kavan &
//! Sorkine-Hornung 2013): w(p) = (1/4π) Σ Ω_t(p), the signed solid angles
//! of the triangles seen from p. For a closed, consistently oriented
//! surface it is the containment number of Appendix C (an integer off the
//! surface, +1 inside an outward-oriented solid); for a surface with
//! holes it is a smooth field that stays near those integers away from
//! the holes, which is what lets a scan with a few holes (the Stanford
//! bunny's five underneath) be treated as the solid it is where it is
//! sculpted.

use glam::DVec3;
use holey_geom::Aabb;
use rayon::prelude::*;
use rustc_hash::FxHashMap;

/// The signed solid angle of triangle `abc` seen from `p` (Van Oosterom &
/// Strackee 1983): `tan(Ω/2) = det[a b c] / (|a||b||c| + (a·b)|c| +
/// (b·c)|a| + (c·a)|b|)` with the corners taken relative to `p`. Positive
/// when `p` is behind the triangle (on the side its normal points away
/// from); in `[-2π, 2π]`; 0 for a degenerate triangle.
pub fn solid_angle(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> f64 {
    let (a, b, c) = (a - p, b - p, c - p);
    let (la, lb, lc) = (a.length(), b.length(), c.length());
    let det = a.dot(b.cross(c));
    let den = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
    2.0 * det.atan2(den)
}

/// The winding number at `p` of the triangles `triangles` (corner
/// positions by `position`), every triangle but `skip`: (1/4π) Σ Ω.
pub fn winding_number(
    triangles: &[[u32; 3]],
    position: &(dyn Fn(u32) -> DVec3 + Sync),
    p: DVec3,
    skip: Option<usize>,
) -> f64 {
    triangles
        .par_iter()
        .enumerate()
        .filter(|(t, _)| Some(*t) != skip)
        .map(|(_, t)| {
            let [a, b, c] = t.map(position);
            solid_angle(p, a, b, c)
        })
        .sum::<f64>()
        / (4.0 * std::f64::consts::PI)
}

/// The winding numbers at each of `points` of the triangles of
/// `triangles` that `keep` admits (by index), in one parallel pass over
/// them: for a handful of points on a big surface this is cheaper than
/// building a [`WindingField`], which every frame that changes topology
/// would rebuild for a few queries. Each triangle counts by its exact
/// solid angle at a point within [`TRIANGLE_FAR`] times its radius (the
/// largest distance of a corner from its centroid), by its dipole term
/// `A·n̂·(c − p) / |c − p|³` farther off (the far field of Barill et al.
/// 2018, per triangle).
///
/// The triangles go in runs of [`RUN`]: each run's dipoles are set up
/// once, then summed point by point into a register, so that no point's
/// running sum waits on a store to memory (about twice as fast as adding
/// each triangle to every point's sum in turn).
pub fn winding_numbers_at<K, P>(
    triangles: &[[u32; 3]],
    keep: &K,
    position: &P,
    points: &[DVec3],
) -> Vec<f64>
where
    K: Fn(usize) -> bool + Sync + ?Sized,
    P: Fn(u32) -> DVec3 + Sync + ?Sized,
{
    winding_sums(triangles, keep, position, points, false).0
}

/// [`winding_numbers_at`], and in the same pass the signed volume of all
/// of `triangles` (kept or not), `Σ a·(b×c) / 6`: a frame's containment
/// needs both, the far field at its pieces' samples and the orientation
/// of the whole surface, and on a million triangles each pass over them
/// costs milliseconds.
pub fn winding_numbers_and_volume_at<K, P>(
    triangles: &[[u32; 3]],
    keep: &K,
    position: &P,
    points: &[DVec3],
) -> (Vec<f64>, f64)
where
    K: Fn(usize) -> bool + Sync + ?Sized,
    P: Fn(u32) -> DVec3 + Sync + ?Sized,
{
    winding_sums(triangles, keep, position, points, true)
}

/// The winding numbers at `points` of the kept triangles and, with
/// `volume`, the signed volume of all of them (else 0).
fn winding_sums<K, P>(
    triangles: &[[u32; 3]],
    keep: &K,
    position: &P,
    points: &[DVec3],
    volume: bool,
) -> (Vec<f64>, f64)
where
    K: Fn(usize) -> bool + Sync + ?Sized,
    P: Fn(u32) -> DVec3 + Sync + ?Sized,
{
    if points.is_empty() && !volume {
        return (Vec::new(), 0.0);
    }
    classified_sums(triangles, position, points, &|t, _| (keep(t), volume))
}

/// The winding numbers at `points` of the triangles `class` keeps, and
/// the signed volume of those it counts in the volume, in one parallel
/// pass: `class(t, triangle)` is (kept for the winding numbers, counted
/// in the volume), from the triangle's number and its vertices, so that
/// a triangle counted in neither has its corners never read.
pub(crate) fn classified_sums<C, P>(
    triangles: &[[u32; 3]],
    position: &P,
    points: &[DVec3],
    class: &C,
) -> (Vec<f64>, f64)
where
    C: Fn(usize, &[u32; 3]) -> (bool, bool) + Sync + ?Sized,
    P: Fn(u32) -> DVec3 + Sync + ?Sized,
{
    let k = points.len();
    let add = |(mut x, u): (Vec<f64>, f64), (y, v): (Vec<f64>, f64)| {
        for (a, b) in x.iter_mut().zip(y) {
            *a += b;
        }
        (x, u + v)
    };
    let (sums, six_volume) = triangles
        .par_chunks(RUN)
        .enumerate()
        .with_min_len(4096 / RUN)
        .fold(
            || (vec![0.0; k], 0.0),
            |(mut acc, mut six), (r, run)| {
                let mut items = [Dipole::default(); RUN];
                let mut count = 0;
                for (i, tri) in run.iter().enumerate() {
                    let (kept, in_volume) = class(r * RUN + i, tri);
                    if !(kept || in_volume) {
                        continue;
                    }
                    let corners = tri.map(position);
                    if in_volume {
                        let [a, b, c] = corners;
                        six += a.dot(b.cross(c));
                    }
                    if kept {
                        items[count] = Dipole::of(corners);
                        count += 1;
                    }
                }
                let items = &items[..count];
                for (sum, &p) in acc.iter_mut().zip(points) {
                    *sum += items.iter().map(|t| t.at(p)).sum::<f64>();
                }
                (acc, six)
            },
        )
        .reduce(|| (vec![0.0; k], 0.0), add);
    (
        sums.into_iter()
            .map(|s| s / (4.0 * std::f64::consts::PI))
            .collect(),
        six_volume / 6.0,
    )
}

/// Up to this many points, one pass over the triangles
/// ([`winding_numbers_at`]) is cheaper than building a [`WindingField`]
/// (about as costly as twenty such passes) and querying it.
pub const FEW_POINTS: usize = 16;

/// The winding numbers at `points` of every triangle of `triangles`, each
/// point without its own triangle (`own[i]` for `points[i]`, if any): the
/// winding number of the rest of a surface at a point on one of its
/// triangles, where that triangle's own solid angle is ±2π by side. Up to
/// [`FEW_POINTS`] points, one pass ([`winding_numbers_at`]) with the own
/// triangle's term taken back out exactly as it went in; for more, the
/// octree field.
pub fn winding_numbers_without_own<P>(
    triangles: &[[u32; 3]],
    position: &P,
    points: &[DVec3],
    own: &[Option<usize>],
) -> Vec<f64>
where
    P: Fn(u32) -> DVec3 + Sync,
{
    if points.len() > FEW_POINTS {
        let field = WindingField::new(triangles, position);
        return points
            .par_iter()
            .zip(own)
            .map(|(&p, &t)| field.at(p, t))
            .collect();
    }
    let mut w = winding_numbers_at(triangles, &|_| true, position, points);
    for ((w, &p), own) in w.iter_mut().zip(points).zip(own) {
        if let Some(t) = *own {
            *w -= Dipole::of(triangles[t].map(position)).at(p) / (4.0 * std::f64::consts::PI);
        }
    }
    w
}

/// Triangles whose dipoles [`winding_numbers_at`] sets up together.
const RUN: usize = 32;

/// A triangle for [`winding_numbers_at`]: its corners, centroid, squared
/// radius around it and area vector `A·n̂`.
#[derive(Clone, Copy, Default)]
struct Dipole {
    corners: [DVec3; 3],
    centre: DVec3,
    radius2: f64,
    area_vector: DVec3,
}

impl Dipole {
    #[inline]
    fn of(corners: [DVec3; 3]) -> Dipole {
        let [a, b, c] = corners;
        let centre = (a + b + c) / 3.0;
        Dipole {
            corners,
            centre,
            radius2: a
                .distance_squared(centre)
                .max(b.distance_squared(centre))
                .max(c.distance_squared(centre)),
            area_vector: 0.5 * (b - a).cross(c - a),
        }
    }

    /// The triangle's solid angle at `p`: by its dipole beyond
    /// [`TRIANGLE_FAR`] times its radius, exactly nearer.
    #[inline]
    fn at(&self, p: DVec3) -> f64 {
        let d = self.centre - p;
        let d2 = d.length_squared();
        if d2 > TRIANGLE_FAR * TRIANGLE_FAR * self.radius2 {
            self.area_vector.dot(d) / (d2 * d2.sqrt())
        } else {
            let [a, b, c] = self.corners;
            solid_angle(p, a, b, c)
        }
    }
}

/// A triangle farther than this many times its radius from a point counts
/// by its dipole in [`winding_numbers_at`].
pub const TRIANGLE_FAR: f64 = 6.0;

/// The winding number of a fixed set of triangles, fast: the triangles
/// are bucketed by centroid into a uniform grid of 2^k cells a side (one
/// pass, O(n)), summarised level by level into an octree: each cell keeps
/// its area vector Σ A·n̂, area-weighted centre and the radius around it
/// that holds its triangles. A query descends from the root, taking a
/// cell's dipole term `(Σ A·n̂)·(c − p) / |c − p|³` once it is farther than
/// three times its radius and the exact solid angles of the triangles in the
/// finest cells that are not (the far field of Barill et al., *Fast
/// Winding Numbers for Soups and Clouds*, 2018, on a regular octree that
/// is cheap to rebuild every frame). The far-field error is a few percent
/// of a cell's contribution, far below the quarter the callers' rounding
/// to an integer allows.
pub struct WindingField<'a> {
    triangles: &'a [[u32; 3]],
    position: &'a (dyn Fn(u32) -> DVec3 + Sync),
    tree: Octree,
}

/// The octree of a [`WindingField`], without the triangles it was built
/// over: a field that owns its surface ([`crate::far_field::FarField`])
/// keeps it beside them.
pub(crate) struct Octree {
    /// Finest cells per side (a power of two) and the octree's depth.
    side: usize,
    depth: u32,
    /// Triangles by finest cell (CSR), and each triangle's cell.
    start: Vec<u32>,
    order: Vec<u32>,
    cell: Vec<u32>,
    /// Per level, from the root (1 cell) to the finest: per cell,
    /// Σ area vector, area-weighted centre, radius, triangle count.
    levels: Vec<Vec<Summary>>,
    /// Per level likewise, the box of each cell's triangles' corners
    /// (empty unless built [`Octree::with_boxes`]).
    boxes: Vec<Vec<Aabb>>,
    /// The finest cells holding more than [`DENSE`] triangles, each with
    /// an octree of its own over them ([`Dense`]).
    dense: FxHashMap<u32, Dense>,
}

/// A finest cell of an [`Octree`] that holds a cluster: more than
/// [`DENSE`] triangles, where the grid's cells hold about eight on
/// average. A uniform grid of at most 64 cells a side puts a cluster
/// much smaller than the surface in one cell, such as the slivers of a
/// contact storm in a sculpting frame's arrangement (about 2,000 pieces
/// in 27k triangles on the 1.1M bunny), and every point near the cluster
/// then summed each of its triangles exactly: [`Octree::sum`] descends
/// into the cell's own tree instead.
struct Dense {
    /// The cell's triangles, in the order of its members.
    triangles: Vec<[u32; 3]>,
    tree: Octree,
}

/// More triangles than this in a finest cell get an octree of their own.
const DENSE: usize = 64;

/// Octrees of dense cells nest at most this deep (a cluster of
/// coincident triangles does not split however fine the grid).
const MAX_NEST: u32 = 2;

/// What a cell of a [`WindingField`] holds, for its far field.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Summary {
    area_vector: DVec3,
    centre: DVec3,
    radius: f64,
    area: f64,
    count: u32,
    /// Six times the signed volume of its triangles, `Σ a·(b×c)`.
    six_volume: f64,
}

/// An [`Octree`]'s triangles split by whether their box meets a box `b`
/// ([`Octree::residue`]).
pub(crate) struct Residue {
    /// Per level, the area vector and triangle count of each cell whose
    /// box meets `b`, without the triangles whose own box meets it.
    levels: Vec<FxHashMap<u32, (DVec3, u32)>>,
    /// How many triangles have a box meeting `b`.
    pub meeting: usize,
    /// Six times the signed volume of the triangles whose box misses `b`.
    pub six_kept: f64,
}

impl<'a> WindingField<'a> {
    /// The field of `triangles` with corners at `position`.
    pub fn new(
        triangles: &'a [[u32; 3]],
        position: &'a (dyn Fn(u32) -> DVec3 + Sync),
    ) -> WindingField<'a> {
        WindingField {
            triangles,
            position,
            tree: Octree::new(triangles, position),
        }
    }

    /// The signed volume of the field's triangles, `Σ a·(b×c) / 6`
    /// (summed with the cells, so a caller that needs the orientation
    /// too makes no other pass over them).
    pub fn signed_volume(&self) -> f64 {
        self.tree
            .levels
            .first()
            .and_then(|root| root.first())
            .map_or(0.0, |root| root.six_volume / 6.0)
    }

    /// The winding number at `p` of every triangle but `skip`.
    pub fn at(&self, p: DVec3, skip: Option<usize>) -> f64 {
        self.at_skipping(p, skip.as_slice())
    }

    /// The winding number at `p` of every triangle but those of `skip`
    /// (the triangles `p` lies on: their solid angle there is ±2π by side,
    /// which the caller adds).
    ///
    /// A few skipped triangles are looked up in place (no allocation: this
    /// runs per vertex in sculpting's containment); many (a cell shared by
    /// 300,000 coincident triangles of a degenerate storm) are sorted
    /// once with the cells that hold them, so the cost stays
    /// `O((n + k) log k)` instead of `n · k`.
    pub fn at_skipping(&self, p: DVec3, skip: &[usize]) -> f64 {
        self.tree
            .sum_skipping(self.triangles, self.position, p, skip)
    }
}

impl Octree {
    /// The octree of `triangles` with corners at `position`.
    pub(crate) fn new(triangles: &[[u32; 3]], position: &(dyn Fn(u32) -> DVec3 + Sync)) -> Octree {
        Octree::build(triangles, position, false, 0)
    }

    /// [`Octree::new`], with the box of every cell's triangles, for
    /// [`Octree::residue`] and [`Octree::sum_outside`].
    pub(crate) fn with_boxes(
        triangles: &[[u32; 3]],
        position: &(dyn Fn(u32) -> DVec3 + Sync),
    ) -> Octree {
        Octree::build(triangles, position, true, 0)
    }

    /// Whether the box of the triangles of cell `c` of `level` meets `b`
    /// (always, without boxes).
    pub(crate) fn cell_meets(&self, level: u32, c: usize, b: &Aabb) -> bool {
        self.boxes
            .get(level as usize)
            .and_then(|l| l.get(c))
            .is_none_or(|cell| cell.overlaps(b))
    }

    fn build(
        triangles: &[[u32; 3]],
        position: &(dyn Fn(u32) -> DVec3 + Sync),
        with_boxes: bool,
        nest: u32,
    ) -> Octree {
        let centroid = |t: &[u32; 3]| t.map(position).iter().sum::<DVec3>() / 3.0;
        // Rebuilt every frame a sculpting stroke changes topology, over
        // the whole surface around the brush: each pass is parallel.
        let centroids: Vec<DVec3> = triangles.par_iter().map(centroid).collect();
        let (lo, hi) = centroids
            .par_iter()
            .fold(
                || (DVec3::INFINITY, DVec3::NEG_INFINITY),
                |(l, h), c| (l.min(*c), h.max(*c)),
            )
            .reduce(
                || (DVec3::INFINITY, DVec3::NEG_INFINITY),
                |(l1, h1), (l2, h2)| (l1.min(l2), h1.max(h2)),
            );
        // About eight triangles a finest cell, at most 64 cells a side.
        let wanted = ((triangles.len() as f64 / 8.0).cbrt().ceil() as usize).clamp(1, 64);
        let depth = wanted.next_power_of_two().trailing_zeros();
        let side = 1usize << depth;
        let size = ((hi - lo) / side as f64).max(DVec3::splat(f64::MIN_POSITIVE));
        let cell_of = |c: DVec3| -> usize {
            let k = ((c - lo) / size).floor();
            let clamp = |x: f64| (x.max(0.0) as usize).min(side - 1);
            index(clamp(k.x), clamp(k.y), clamp(k.z), side)
        };
        let cell: Vec<u32> = centroids.par_iter().map(|&c| cell_of(c) as u32).collect();
        let n_cells = side * side * side;
        let mut start = vec![0u32; n_cells + 1];
        for &c in &cell {
            start[c as usize + 1] += 1;
        }
        for c in 0..n_cells {
            start[c + 1] += start[c];
        }
        let mut fill = start.clone();
        let mut order = vec![0u32; triangles.len()];
        for (t, &c) in cell.iter().enumerate() {
            order[fill[c as usize] as usize] = t as u32;
            fill[c as usize] += 1;
        }
        // Each finest cell's summary, and its box when asked, in one
        // visit of its triangles' corners: they are read in cell order,
        // scattered over the mesh, and on a million triangles each such
        // pass costs tens of milliseconds.
        let cell_summary = |c: usize| {
            let members = &order[start[c] as usize..start[c + 1] as usize];
            summary(members, |t| triangles[t as usize].map(position), &centroids)
        };
        let (finest, boxes): (Vec<Summary>, _) = if with_boxes {
            let (finest, finest_boxes) = (0..n_cells).into_par_iter().map(cell_summary).unzip();
            (finest, box_levels(side, finest_boxes))
        } else {
            let finest = (0..n_cells)
                .into_par_iter()
                .map(|c| cell_summary(c).0)
                .collect();
            (finest, Vec::new())
        };
        let mut levels = vec![finest];
        let mut s = side;
        while s > 1 {
            let half = s / 2;
            let below = levels.last().map(Vec::as_slice).unwrap_or(&[]);
            let mut up = vec![Summary::default(); half * half * half];
            for x in 0..half {
                for y in 0..half {
                    for z in 0..half {
                        let mut kids = [Summary::default(); 8];
                        let mut n = 0;
                        for k in 0..8 {
                            let kid = below[index(
                                2 * x + (k >> 2),
                                2 * y + ((k >> 1) & 1),
                                2 * z + (k & 1),
                                s,
                            )];
                            if kid.count > 0 {
                                kids[n] = kid;
                                n += 1;
                            }
                        }
                        up[index(x, y, z, half)] = merge(&kids[..n]);
                    }
                }
            }
            levels.push(up);
            s = half;
        }
        levels.reverse();
        let dense = if nest < MAX_NEST && side > 1 {
            (0..n_cells)
                .filter(|&c| (start[c + 1] - start[c]) as usize > DENSE)
                .map(|c| {
                    let members = &order[start[c] as usize..start[c + 1] as usize];
                    let triangles: Vec<[u32; 3]> =
                        members.iter().map(|&t| triangles[t as usize]).collect();
                    let tree = Octree::build(&triangles, position, false, nest + 1);
                    (c as u32, Dense { triangles, tree })
                })
                .collect()
        } else {
            FxHashMap::default()
        };
        Octree {
            side,
            depth,
            start,
            order,
            cell,
            levels,
            boxes,
            dense,
        }
    }

    /// The cells from the root down: `visit(level, (x, y, z), index,
    /// summary)` for every cell that holds triangles and whose parent it
    /// asked to open (by returning true), the root first.
    fn walk(&self, mut visit: impl FnMut(u32, (usize, usize, usize), usize, &Summary) -> bool) {
        let mut stack = vec![(0u32, 0usize, 0usize, 0usize)];
        while let Some((level, x, y, z)) = stack.pop() {
            let s = 1usize << level;
            let c = (x * s + y) * s + z;
            let cell = &self.levels[level as usize][c];
            if cell.count > 0 && visit(level, (x, y, z), c, cell) && level < self.depth {
                push_children(&mut stack, level, (x, y, z));
            }
        }
    }

    /// The triangles of finest cell `c`.
    fn members(&self, c: usize) -> &[u32] {
        &self.order[self.start[c] as usize..self.start[c + 1] as usize]
    }

    /// The finest cell's coordinates of cell index `k`.
    fn finest(&self, k: usize) -> (usize, usize, usize) {
        let fs = self.side;
        (k / (fs * fs), (k / fs) % fs, k % fs)
    }

    /// The winding number at `p` of the tree's triangles but those of
    /// `skip` ([`WindingField::at_skipping`]): no cell holding one of
    /// them counts whole.
    fn sum_skipping(
        &self,
        triangles: &[[u32; 3]],
        position: &(dyn Fn(u32) -> DVec3 + Sync),
        p: DVec3,
        skip: &[usize],
    ) -> f64 {
        if skip.len() <= FEW_SKIPPED {
            let holds = |level: u32, (x, y, z): (usize, usize, usize)| {
                let shift = self.depth - level;
                skip.iter().filter_map(|&t| self.cell.get(t)).any(|&k| {
                    let (kx, ky, kz) = self.finest(k as usize);
                    (kx >> shift, ky >> shift, kz >> shift) == (x, y, z)
                })
            };
            return self.sum(
                triangles,
                position,
                p,
                |level, cell, _| !holds(level, cell),
                |t| skip.contains(&t),
            );
        }
        let mut skipped = skip.to_vec();
        skipped.sort_unstable();
        skipped.dedup();
        let mut cells: Vec<(u32, usize, usize, usize)> = Vec::new();
        for k in skipped.iter().filter_map(|&t| self.cell.get(t)) {
            let (kx, ky, kz) = self.finest(*k as usize);
            for level in 0..=self.depth {
                let shift = self.depth - level;
                cells.push((level, kx >> shift, ky >> shift, kz >> shift));
            }
        }
        cells.sort_unstable();
        cells.dedup();
        self.sum(
            triangles,
            position,
            p,
            |level, (x, y, z), _| cells.binary_search(&(level, x, y, z)).is_err(),
            |t| skipped.binary_search(&t).is_ok(),
        )
    }

    /// The winding number at `p` of the triangles of the tree (`triangles`
    /// at `position`, those it was built over), by cells: a cell counts by
    /// its dipole when it is far and `whole(level, (x, y, z), c)` (`c` the
    /// cell's index in its level)
    /// admits it whole, else it is opened, down to the finest cells,
    /// whose triangles count exactly unless `skipped(t)`.
    pub(crate) fn sum(
        &self,
        triangles: &[[u32; 3]],
        position: &(dyn Fn(u32) -> DVec3 + Sync),
        p: DVec3,
        whole: impl Fn(u32, (usize, usize, usize), usize) -> bool,
        skipped: impl Fn(usize) -> bool,
    ) -> f64 {
        self.dipoles_and_exact(
            p,
            |level, xyz, c, cell| (cell.area_vector, cell.count, whole(level, xyz, c)),
            |c| {
                let members = self.members(c);
                if let Some(d) = self.dense.get(&(c as u32)) {
                    // Its own tree's cells count whole when far, unless
                    // they hold a skipped triangle (by its place among
                    // the members, which its tree was built over).
                    let skip: Vec<usize> = (0..members.len())
                        .filter(|&k| skipped(members[k] as usize))
                        .collect();
                    return 4.0
                        * std::f64::consts::PI
                        * d.tree.sum_skipping(&d.triangles, position, p, &skip);
                }
                members
                    .iter()
                    .filter(|&&t| !skipped(t as usize))
                    .map(|&t| {
                        let [a, b, e] = triangles[t as usize].map(position);
                        solid_angle(p, a, b, e)
                    })
                    .sum()
            },
        ) / (4.0 * std::f64::consts::PI)
    }

    /// The walk of [`Octree::sum`] and [`Octree::sum_outside`] from `p`:
    /// `cell(level, (x, y, z), c, summary)` gives the area vector and
    /// triangle count a cell counts with (none: left out) and whether it
    /// may count whole; such a cell farther than [`FAR`] times its radius
    /// adds its dipole term, the other finest cells `exact(c)` (their
    /// solid angles), and the rest are opened. The sum of solid angles.
    fn dipoles_and_exact(
        &self,
        p: DVec3,
        cell: impl Fn(u32, (usize, usize, usize), usize, &Summary) -> (DVec3, u32, bool),
        exact: impl Fn(usize) -> f64,
    ) -> f64 {
        let mut total = 0.0;
        self.walk(|level, xyz, c, summary| {
            let (area_vector, count, may_be_whole) = cell(level, xyz, c, summary);
            if count == 0 {
                return false;
            }
            let d = summary.centre - p;
            let dist = d.length();
            if may_be_whole && dist > FAR * summary.radius {
                total += area_vector.dot(d) / (dist * dist * dist);
                false
            } else if level == self.depth {
                total += exact(c);
                false
            } else {
                true
            }
        });
        total
    }

    /// The tree's triangles split by whether their box meets `b`
    /// ([`Residue`]): how many meet it, six times the signed volume of
    /// the others, and the area vectors and counts of the cells meeting
    /// it without the triangles that meet it, which
    /// [`Octree::sum_outside`] reads in place of those cells' sums. Cells
    /// whose box misses `b` count whole; one visit of the triangles of the
    /// finest cells that meet it.
    pub(crate) fn residue(
        &self,
        triangles: &[[u32; 3]],
        position: &(dyn Fn(u32) -> DVec3 + Sync),
        b: &Aabb,
    ) -> Residue {
        let mut residue = Residue {
            levels: vec![FxHashMap::default(); self.depth as usize + 1],
            meeting: 0,
            six_kept: 0.0,
        };
        residue.six_kept = self
            .residue_below(triangles, position, b, 0, (0, 0, 0), &mut residue)
            .2;
        residue
    }

    /// [`Octree::residue`] of cell `(x, y, z)` of `level` and the cells
    /// below it; returns the cell's area vector, count and six times the
    /// signed volume without the triangles meeting `b`.
    fn residue_below(
        &self,
        triangles: &[[u32; 3]],
        position: &(dyn Fn(u32) -> DVec3 + Sync),
        b: &Aabb,
        level: u32,
        (x, y, z): (usize, usize, usize),
        residue: &mut Residue,
    ) -> (DVec3, u32, f64) {
        let s = 1usize << level;
        let c = index(x, y, z, s);
        let cell = &self.levels[level as usize][c];
        if cell.count == 0 || !self.cell_meets(level, c, b) {
            return (cell.area_vector, cell.count, cell.six_volume);
        }
        let (mut area_vector, mut count, mut six) = (DVec3::ZERO, 0u32, 0.0);
        if level == self.depth {
            for &t in self.members(c) {
                let corners = triangles[t as usize].map(position);
                if corners_meet(&corners, b) {
                    residue.meeting += 1;
                } else {
                    let [a, bb, e] = corners;
                    area_vector += 0.5 * (bb - a).cross(e - a);
                    count += 1;
                    six += a.dot(bb.cross(e));
                }
            }
        } else {
            for k in 0..8 {
                let kid = (2 * x + (k >> 2), 2 * y + ((k >> 1) & 1), 2 * z + (k & 1));
                let (v, n, w) = self.residue_below(triangles, position, b, level + 1, kid, residue);
                area_vector += v;
                count += n;
                six += w;
            }
        }
        residue.levels[level as usize].insert(c as u32, (area_vector, count));
        (area_vector, count, six)
    }

    /// The winding number at `p` of the tree's triangles whose box misses
    /// `b` (`residue` is [`Octree::residue`] for `b`): [`Octree::sum`]
    /// with each cell meeting `b` summed without the triangles meeting
    /// it. Such a cell still counts by its dipole when it is far: about
    /// its own centre and within its own radius, which bound what is
    /// left of it. So a point costs what it costs in a tree without the
    /// box, however many triangles the box holds, where opening every
    /// cell that meets the box costs the number of triangles in it.
    pub(crate) fn sum_outside(
        &self,
        triangles: &[[u32; 3]],
        position: &(dyn Fn(u32) -> DVec3 + Sync),
        p: DVec3,
        b: &Aabb,
        residue: &Residue,
    ) -> f64 {
        self.dipoles_and_exact(
            p,
            |level, _, c, cell| {
                let (area_vector, count) = if self.cell_meets(level, c, b) {
                    residue.levels[level as usize]
                        .get(&(c as u32))
                        .copied()
                        .unwrap_or((DVec3::ZERO, 0))
                } else {
                    (cell.area_vector, cell.count)
                };
                (area_vector, count, true)
            },
            |c| {
                let meets = self.cell_meets(self.depth, c, b);
                self.members(c)
                    .iter()
                    .map(|&t| triangles[t as usize].map(position))
                    .filter(|corners| !(meets && corners_meet(corners, b)))
                    .map(|[a, bb, e]| solid_angle(p, a, bb, e))
                    .sum()
            },
        ) / (4.0 * std::f64::consts::PI)
    }
}

/// The eight cells of the level below cell `(x, y, z)` of `level`, onto
/// a traversal's stack.
fn push_children(
    stack: &mut Vec<(u32, usize, usize, usize)>,
    level: u32,
    (x, y, z): (usize, usize, usize),
) {
    for k in 0..8 {
        stack.push((
            level + 1,
            2 * x + (k >> 2),
            2 * y + ((k >> 1) & 1),
            2 * z + (k & 1),
        ));
    }
}

/// The boxes of the cells of every level, the root's first, from those of
/// the finest cells (`side` a side; [`Aabb::EMPTY`] for an empty cell).
fn box_levels(side: usize, finest: Vec<Aabb>) -> Vec<Vec<Aabb>> {
    let mut levels = vec![finest];
    let mut s = side;
    while s > 1 {
        let half = s / 2;
        let below = levels.last().map(Vec::as_slice).unwrap_or(&[]);
        let up = (0..half * half * half)
            .map(|c| {
                let (x, y, z) = (c / (half * half), (c / half) % half, c % half);
                (0..8).fold(Aabb::EMPTY, |b, k| {
                    b.union(
                        &below[index(2 * x + (k >> 2), 2 * y + ((k >> 1) & 1), 2 * z + (k & 1), s)],
                    )
                })
            })
            .collect();
        levels.push(up);
        s = half;
    }
    levels.reverse();
    levels
}

/// Whether the box of a triangle's corners meets `b`: not all three
/// beyond one face of it ([`Aabb::outcode`]).
pub(crate) fn corners_meet(corners: &[DVec3; 3], b: &Aabb) -> bool {
    corners.iter().fold(0x3f, |code, &p| code & b.outcode(p)) == 0
}

/// The index of cell `(x, y, z)` in a level of `side` cells a side.
fn index(x: usize, y: usize, z: usize, side: usize) -> usize {
    (x * side + y) * side + z
}

/// The summary of a finest cell holding the triangles `members`.
#[inline]
fn summary(
    members: &[u32],
    corners: impl Fn(u32) -> [DVec3; 3],
    centroids: &[DVec3],
) -> (Summary, Aabb) {
    if members.is_empty() {
        return (Summary::default(), Aabb::EMPTY);
    }
    let (mut n, mut weighted, mut area, mut six) = (DVec3::ZERO, DVec3::ZERO, 0.0, 0.0);
    for &t in members {
        let [a, b, d] = corners(t);
        let v = 0.5 * (b - a).cross(d - a);
        let len = v.length();
        n += v;
        weighted += len * (a + b + d) / 3.0;
        area += len;
        six += a.dot(b.cross(d));
    }
    let centre = if area > 0.0 {
        weighted / area
    } else {
        centroids[members[0] as usize]
    };
    let (radius, bx) = members
        .iter()
        .flat_map(|&t| corners(t))
        .fold((0.0, Aabb::EMPTY), |(r, b): (f64, Aabb), p| {
            (r.max(p.distance(centre)), b.union(&Aabb::new(p, p)))
        });
    (
        Summary {
            area_vector: n,
            centre,
            radius,
            area,
            count: members.len() as u32,
            six_volume: six,
        },
        bx,
    )
}

/// Up to this many skipped triangles are looked up in place.
const FEW_SKIPPED: usize = 8;

/// A cell farther than this many times its radius counts by its dipole.
const FAR: f64 = 3.0;

/// The summary of the union of cells.
fn merge(kids: &[Summary]) -> Summary {
    let area: f64 = kids.iter().map(|k| k.area).sum();
    let count: u32 = kids.iter().map(|k| k.count).sum();
    if count == 0 {
        return Summary::default();
    }
    let centre = if area > 0.0 {
        kids.iter().map(|k| k.area * k.centre).sum::<DVec3>() / area
    } else {
        kids.iter().map(|k| k.centre).sum::<DVec3>() / kids.len() as f64
    };
    Summary {
        area_vector: kids.iter().map(|k| k.area_vector).sum(),
        centre,
        radius: kids
            .iter()
            .map(|k| k.centre.distance(centre) + k.radius)
            .fold(0.0, f64::max),
        area,
        count,
        six_volume: kids.iter().map(|k| k.six_volume).sum(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tetra() -> (Vec<DVec3>, Vec<[u32; 3]>) {
        (
            vec![
                DVec3::new(1.0, 1.0, 1.0),
                DVec3::new(1.0, -1.0, -1.0),
                DVec3::new(-1.0, 1.0, -1.0),
                DVec3::new(-1.0, -1.0, 1.0),
            ],
            vec![[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]],
        )
    }

    /// A unit sphere of `rings` rings and `segs` segments (poles first),
    /// outward: positions, triangles, and `segs`.
    fn uv_sphere(rings: u32, segs: u32) -> (Vec<DVec3>, Vec<[u32; 3]>, u32) {
        let m = crate::test_meshes::uv_sphere(DVec3::ZERO, 1.0, rings, segs);
        (m.positions, m.triangles, segs)
    }

    #[test]
    fn inside_is_one_outside_is_zero() {
        let (p, t) = tetra();
        let at = |v: u32| p[v as usize];
        let w = |q: DVec3| winding_number(&t, &at, q, None);
        assert!((w(DVec3::ZERO) - 1.0).abs() < 1e-12);
        assert!(w(DVec3::new(0.1, -0.2, 0.05)) > 0.999_999);
        assert!(w(DVec3::new(3.0, 0.0, 0.0)).abs() < 1e-12);
        // Flipped orientation: −1 inside.
        let flipped: Vec<[u32; 3]> = t.iter().map(|f| [f[0], f[2], f[1]]).collect();
        assert!((winding_number(&flipped, &at, DVec3::ZERO, None) + 1.0).abs() < 1e-12);
    }

    #[test]
    fn the_grid_field_agrees_with_the_exact_sum() {
        // A finely triangulated sphere (UV), queried inside, outside and
        // close to the surface.
        let (pos, tris, _) = uv_sphere(40, 60);
        let p = |v: u32| pos[v as usize];
        let field = WindingField::new(&tris, &p);
        for q in [
            DVec3::ZERO,
            DVec3::new(0.3, -0.2, 0.5),
            DVec3::new(0.0, 0.0, 0.97),
            DVec3::new(2.0, 1.0, 0.0),
            DVec3::new(0.0, 1.03, 0.0),
        ] {
            let exact = winding_number(&tris, &p, q, None);
            let fast = field.at(q, None);
            assert!((exact - fast).abs() < 0.03, "{q}: {exact} vs {fast}");
        }
        // On a face, without it: a half.
        let c = tris[500].map(p).iter().sum::<DVec3>() / 3.0;
        assert!((field.at(c, Some(500)) - winding_number(&tris, &p, c, Some(500))).abs() < 0.03);
    }

    /// The field's signed volume, summed with its cells, is the one-pass
    /// volume to rounding, near the closed form 4π/3 of the unit sphere
    /// (a UV sphere of 40 rings is inscribed: a little less), and turns
    /// sign with the orientation.
    #[test]
    fn the_field_keeps_the_signed_volume() {
        let (pos, tris, _) = uv_sphere(40, 60);
        let p = |v: u32| pos[v as usize];
        let field = WindingField::new(&tris, &p);
        let (_, pass) = winding_numbers_and_volume_at(&tris, &|_| true, &p, &[]);
        let v = field.signed_volume();
        assert!((v - pass).abs() < 1e-12 * pass.abs(), "{v} vs {pass}");
        let ball = 4.0 * std::f64::consts::PI / 3.0;
        assert!(v < ball && v > 0.99 * ball, "{v}");
        let flipped: Vec<[u32; 3]> = tris.iter().map(|t| [t[0], t[2], t[1]]).collect();
        let inward = WindingField::new(&flipped, &p);
        assert!(
            (inward.signed_volume() + v).abs() < 1e-12 * v,
            "{}",
            inward.signed_volume()
        );
    }

    /// A cluster much smaller than the surface (a sphere of radius 0.004
    /// holding 7,200 triangles inside a unit sphere of 9,600, as the
    /// slivers of a contact storm cluster in a frame's arrangement) falls
    /// in one finest cell of the grid, which gets a tree of its own: the
    /// field agrees with the exact sum inside the cluster, just outside
    /// it, on one of its triangles without that triangle, and with a band
    /// of its triangles left out, seen from nearby and from afar.
    #[test]
    fn a_dense_cluster_gets_a_tree_of_its_own_and_the_same_winding_numbers() {
        let outer = crate::test_meshes::uv_sphere(DVec3::ZERO, 1.0, 60, 80);
        let centre = DVec3::new(0.31, -0.07, 0.06);
        let r = 0.004;
        let small = crate::test_meshes::uv_sphere(centre, r, 60, 60);
        let mut pos = outer.positions.clone();
        let mut tris = outer.triangles.clone();
        let base = pos.len() as u32;
        let first_small = tris.len();
        pos.extend(&small.positions);
        tris.extend(small.triangles.iter().map(|t| t.map(|v| v + base)));
        let at = |v: u32| pos[v as usize];
        let field = WindingField::new(&tris, &at);
        assert!(
            field
                .tree
                .dense
                .values()
                .any(|d| d.triangles.len() >= small.triangles.len()),
            "the cluster's cell has a tree of its own"
        );
        let own = first_small + 1234;
        let on = tris[own].map(at).iter().sum::<DVec3>() / 3.0;
        let cases: [(DVec3, Option<usize>, f64); 4] = [
            (centre, None, 2.0),
            (centre + DVec3::new(1.5 * r, 0.0, 0.0), None, 1.0),
            (centre + DVec3::new(0.0, 0.0, 0.99 * r), None, 2.0),
            (on, Some(own), 1.5),
        ];
        for (q, skip, expected) in cases {
            let exact = winding_number(&tris, &at, q, skip);
            let fast = field.at(q, skip);
            assert!((exact - fast).abs() < 0.03, "{q}: {exact} vs {fast}");
            assert!(
                (fast - expected).abs() < 0.05,
                "{q}: {fast}, not {expected}"
            );
        }
        // A band of the cluster left out (the sorted path, in its tree).
        let band: Vec<usize> = (first_small + 2000..first_small + 2600).collect();
        for q in [
            centre,
            centre + DVec3::new(0.0, 3.0 * r, 0.0),
            DVec3::new(2.0, 0.0, 0.0),
        ] {
            let exact = winding_number(&tris, &at, q, None)
                - band
                    .iter()
                    .map(|&t| winding_number(&tris[t..t + 1], &at, q, None))
                    .sum::<f64>();
            let fast = field.at_skipping(q, &band);
            assert!((exact - fast).abs() < 0.03, "{q}: {exact} vs {fast}");
        }
    }

    /// Many skipped triangles (the sorted path) give what summing every
    /// other triangle exactly gives, as a few (the in-place path) do: a
    /// band of 600 of a sphere's triangles left out, and 300,000 copies
    /// of one triangle (a degenerate storm's group) with all but one left
    /// out, in the one finest cell that holds them all.
    #[test]
    fn many_skipped_triangles_are_left_out_exactly_as_few() {
        let (pos, tris, _) = uv_sphere(40, 60);
        let p = |v: u32| pos[v as usize];
        let field = WindingField::new(&tris, &p);
        let band: Vec<usize> = (1000..1600).collect();
        let rest: Vec<[u32; 3]> = tris
            .iter()
            .enumerate()
            .filter(|(t, _)| !band.contains(t))
            .map(|(_, t)| *t)
            .collect();
        for q in [
            DVec3::ZERO,
            DVec3::new(0.3, -0.2, 0.5),
            DVec3::new(2.0, 1.0, 0.0),
        ] {
            let exact = winding_number(&rest, &p, q, None);
            let fast = field.at_skipping(q, &band);
            assert!((exact - fast).abs() < 0.03, "{q}: {exact} vs {fast}");
        }

        let corners = [DVec3::ZERO, DVec3::X, DVec3::Y];
        let at = |v: u32| corners[v as usize];
        let copies = vec![[0u32, 1, 2]; 300_000];
        let storm = WindingField::new(&copies, &at);
        let skip: Vec<usize> = (1..copies.len()).collect();
        let q = DVec3::new(0.25, 0.25, 1.0);
        let one = winding_number(&copies[..1], &at, q, None);
        assert!((storm.at_skipping(q, &skip) - one).abs() < 1e-9);
        // And all of them left out: nothing.
        let all: Vec<usize> = (0..copies.len()).collect();
        assert_eq!(storm.at_skipping(q, &all), 0.0);
    }

    /// The one-pass sum at several points agrees with the exact sum, on
    /// a fine sphere and with a band of triangles left out (an open
    /// surface: fractional winding numbers).
    #[test]
    fn the_one_pass_sum_agrees_with_the_exact_sum() {
        let (pos, tris, segs) = uv_sphere(60, 90);
        let p = |v: u32| pos[v as usize];
        let points = [
            DVec3::ZERO,
            DVec3::new(0.3, -0.2, 0.5),
            DVec3::new(0.0, 0.0, 0.97),
            DVec3::new(2.0, 1.0, 0.0),
            DVec3::new(0.0, 1.03, 0.0),
            DVec3::new(0.5, 0.5, -0.6),
        ];
        for band in [None, Some((20u32, 30u32))] {
            // Without a band of rings the sphere is open.
            let keep = |t: usize| {
                band.is_none_or(|(lo, hi)| {
                    let v = tris[t][0];
                    v < 2 || !(lo..hi).contains(&((v - 2) / segs + 1))
                })
            };
            let kept: Vec<[u32; 3]> = (0..tris.len())
                .filter(|&t| keep(t))
                .map(|t| tris[t])
                .collect();
            let fast = winding_numbers_at(&tris, &keep, &p, &points);
            for (q, w) in points.iter().zip(&fast) {
                let exact = winding_number(&kept, &p, *q, None);
                assert!((exact - w).abs() < 0.01, "{q}: {exact} vs {w}");
            }
        }
        assert!(winding_numbers_at(&tris, &|_| true, &p, &[]).is_empty());
    }

    /// The pass with the volume gives the same winding numbers, and the
    /// signed volume of every triangle, kept or not: the tetrahedron with
    /// corners (±1, ±1, ±1) of an even count of minus signs has sides 2√2
    /// and volume (2√2)³ / (6√2) = 8/3, negative turned inside out.
    #[test]
    fn the_pass_with_the_volume_finds_the_tetrahedrons_eight_thirds() {
        let (p, t) = tetra();
        let at = |v: u32| p[v as usize];
        let points = [DVec3::ZERO, DVec3::new(3.0, 0.5, 0.0)];
        let keep = |i: usize| i != 2;
        let (w, volume) = winding_numbers_and_volume_at(&t, &keep, &at, &points);
        assert_eq!(w, winding_numbers_at(&t, &keep, &at, &points));
        assert!((volume - 8.0 / 3.0).abs() < 1e-12, "{volume}");
        let turned: Vec<[u32; 3]> = t.iter().map(|&[a, b, c]| [a, c, b]).collect();
        let (_, volume) = winding_numbers_and_volume_at(&turned, &keep, &at, &[]);
        assert!((volume + 8.0 / 3.0).abs() < 1e-12, "{volume}");
    }

    #[test]
    fn on_a_face_it_is_a_half_without_that_face() {
        let (p, t) = tetra();
        let at = |v: u32| p[v as usize];
        // The centroid of face 0: the other three faces see it with a
        // winding of exactly 1/2 (the face's own would be ±1/2).
        let c = (p[0] + p[1] + p[2]) / 3.0;
        assert!((winding_number(&t, &at, c, Some(0)) - 0.5).abs() < 1e-12);
        // A single triangle seen from straight behind and in front.
        let one = [[0u32, 1, 2]];
        let behind = (p[0] + p[1] + p[2]) / 3.0 - (p[1] - p[0]).cross(p[2] - p[0]) * 1e-9;
        assert!((winding_number(&one, &at, behind, None) - 0.5).abs() < 1e-6);
        // The one-pass sum without each point's own face.
        let w = winding_numbers_without_own(&t, &at, &[c], &[Some(0)]);
        assert!((w[0] - 0.5).abs() < 1e-12, "{w:?}");
    }

    /// At the centroids of faces of a closed sphere, the rest of it has
    /// winding number 1/2 (the closed form: a closed surface's own point
    /// sees half a turn), far triangles counted by their dipoles; a face
    /// not left out would count as ±2π more or less.
    #[test]
    fn without_its_own_face_a_point_on_a_sphere_sees_a_half() {
        let (pos, tris, _) = uv_sphere(60, 90);
        let p = |v: u32| pos[v as usize];
        let own: Vec<usize> = vec![0, 77, 1234, 3001, tris.len() - 1];
        let points: Vec<DVec3> = own
            .iter()
            .map(|&t| tris[t].map(p).iter().sum::<DVec3>() / 3.0)
            .collect();
        let some: Vec<Option<usize>> = own.iter().map(|&t| Some(t)).collect();
        let w = winding_numbers_without_own(&tris, &p, &points, &some);
        for ((&t, &q), w) in own.iter().zip(&points).zip(&w) {
            let exact = winding_number(&tris, &p, q, Some(t));
            assert!((w - 0.5).abs() < 0.01, "face {t}: {w}");
            assert!((w - exact).abs() < 0.01, "face {t}: {w} against {exact}");
        }
        // With nothing left out the same points are not a half.
        let none = vec![None; own.len()];
        let all = winding_numbers_without_own(&tris, &p, &points, &none);
        assert!(all.iter().all(|w| (w - 0.5).abs() > 0.4), "{all:?}");
    }
}
