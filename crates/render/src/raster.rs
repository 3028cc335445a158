//! Scan conversion of faces and edges into a supersampled z-buffer, and
//! the resolve to pixels.
//!
//! ## Triangles
//!
//! Vertices are snapped to a grid of 1/256 sample and every triangle is
//! scan-converted with exact integer edge functions
//! E_ab(p) = (b − a) × (p − a); a sample (centre at (i + ½, j + ½)) is
//! covered when all three are ≥ 0 after orienting the triangle
//! positively. Because the arithmetic is exact, two triangles sharing an
//! edge agree on which side every sample lies, so there are no cracks.
//! The z-buffer stores w = 1/z, which is an affine function of the screen
//! position under perspective, so it is interpolated with the screen
//! barycentrics bᵢ = Eᵢ / 2A; a larger w is nearer, 0 is empty. Vertex
//! attributes are interpolated perspective-correctly with weights
//! bᵢwᵢ / Σ bⱼwⱼ.
//!
//! Triangles with a vertex behind the near plane are clipped against it
//! in view space; triangles reaching beyond a guard band far outside the
//! picture are clipped in screen space, interpolating x, y, w and
//! attribute·w linearly (all affine on the screen). Both only happen with
//! a caller's [`crate::Framing::Fixed`] camera: automatic framing keeps
//! the whole model in view.
//!
//! ## Edges
//!
//! Each polygon boundary edge is drawn once (edges are deduplicated by
//! their vertex pair, remembering every face that has them) as a
//! rectangle `edge_width` pixels wide with square caps, after all faces.
//! Its visibility is decided at stations one sample apart along its
//! centre line: a station is visible when one of the 3 × 3 samples around
//! it shows one of the edge's own faces, or shows the background, or
//! when the farthest surface among them is no more than a tolerance in
//! front of the edge. The face test makes edges between visible faces
//! show whatever their slope; the depth test keeps edges of faces too
//! small to own a sample. Each painted sample then takes the visibility of
//! its nearest station, and is skipped if another face covers it more
//! than the tolerance in front of the edge (so lines do not spill over
//! nearer surfaces). Edges write colour only, never depth, so the order
//! in which they are drawn does not matter.

use glam::{DVec3, Vec3};
use holey_mesh::PolyMesh;

use crate::camera::{Projector, SVert, ViewPoint};
use crate::image::Image;
use crate::prep::Prepared;
use crate::shade::{Shader, pack, pack_linear, rgb_linear};
use crate::{Background, Colors, RenderError, RenderOptions};

/// Per-vertex attributes: eye-space normal (3) and linear albedo (3).
type Attr = [f32; 6];

/// The face id of samples showing no face.
const NO_FACE: u32 = u32::MAX;

/// Sub-sample grid of the rasterizer.
const SUB: f64 = 256.0;

/// Distance in samples beyond the picture inside which triangles are
/// rasterized without 2D clipping. Bounds the fixed-point coordinates to
/// 2^18 · 256 = 2^26, so edge functions stay below 2^53.
const GUARD: f64 = 65_536.0;

/// log₂ of the side of a buffer tile, in samples.
const TILE_BITS: usize = 5;
/// Side of a buffer tile: 32 × 32 samples, 4 KiB of depth.
const TILE: usize = 1 << TILE_BITS;

/// The supersampled buffers, stored in 32 × 32-sample tiles (row-major
/// inside a tile, tiles row-major): a small triangle then touches one or a
/// few memory pages instead of one page per sample row, which halves the
/// cost of dense meshes.
pub(crate) struct Target {
    /// Size in samples.
    pub width: usize,
    pub height: usize,
    tiles_x: usize,
    /// Samples per pixel side.
    ss: usize,
    /// 1/z of the nearest surface, 0 where empty.
    pub depth: Vec<f32>,
    /// Packed sRGBA colour.
    pub color: Vec<u32>,
    /// The face shown, or [`NO_FACE`]; empty when no edges are drawn.
    pub face: Vec<u32>,
}

impl Target {
    /// Empty buffers of `width` × `height` samples, with face ids if
    /// `faces`, coloured by `row_color(sample row)`.
    fn with_size(
        width: usize,
        height: usize,
        ss: usize,
        faces: bool,
        row_color: impl Fn(usize) -> u32,
    ) -> Target {
        let tiles_x = width.div_ceil(TILE);
        let tiles_y = height.div_ceil(TILE);
        let n = tiles_x * tiles_y * TILE * TILE;
        let mut color = vec![0u32; n];
        for ty in 0..tiles_y {
            for tx in 0..tiles_x {
                let tile = (ty * tiles_x + tx) << (2 * TILE_BITS);
                for r in 0..TILE {
                    let c = row_color((ty * TILE + r).min(height.saturating_sub(1)));
                    let row = tile + (r << TILE_BITS);
                    color[row..row + TILE].fill(c);
                }
            }
        }
        Target {
            width,
            height,
            tiles_x,
            ss,
            depth: vec![0.0; n],
            color,
            face: if faces { vec![NO_FACE; n] } else { Vec::new() },
        }
    }

    /// Buffers for the picture, filled with the background.
    fn new(opts: &RenderOptions, ss: u32, faces: bool) -> Target {
        let ss = ss as usize;
        let rows = opts.height as usize;
        Self::with_size(opts.width as usize * ss, rows * ss, ss, faces, |j| {
            background_row(&opts.background, j / ss, rows)
        })
    }

    /// The buffer index of sample (i, j).
    #[inline]
    pub fn at(&self, i: usize, j: usize) -> usize {
        ((((j >> TILE_BITS) * self.tiles_x + (i >> TILE_BITS)) << TILE_BITS | (j & (TILE - 1)))
            << TILE_BITS)
            | (i & (TILE - 1))
    }
}

/// The packed background colour of pixel row `y`; a gradient is
/// interpolated in sRGB (perceptually even) at the row's centre.
fn background_row(bg: &Background, y: usize, height: usize) -> u32 {
    match *bg {
        Background::Solid(c) => pack([c[0], c[1], c[2]], c[3]),
        Background::Gradient { top, bottom } => {
            let t = (y as f64 + 0.5) / height as f64;
            let mix =
                |a: u8, b: u8| (f64::from(a) + (f64::from(b) - f64::from(a)) * t).round() as u8;
            pack(
                [
                    mix(top[0], bottom[0]),
                    mix(top[1], bottom[1]),
                    mix(top[2], bottom[2]),
                ],
                255,
            )
        }
    }
}

/// What a triangle writes into covered samples.
#[derive(Clone, Copy)]
enum Mode<'a> {
    /// Nearer samples get one packed colour (flat shading).
    Flat(u32),
    /// Nearer samples are shaded from interpolated attributes.
    Shade(&'a Shader),
    /// Only the depth of nearer samples (the pre-pass).
    Depth,
    /// After a depth pre-pass: samples whose depth is exactly the final
    /// one are shaded, so each visible sample is shaded once.
    ShadeVisible(&'a Shader),
}

pub(crate) fn render_impl(
    mesh: &PolyMesh,
    colors: Option<Colors<'_>>,
    opts: &RenderOptions,
) -> Result<Image, RenderError> {
    let ss = opts.validate()?;
    let prep = Prepared::new(mesh, opts.smooth, opts.crease_angle)?;
    let proj = Projector::new(&prep, opts, ss)?;
    let mut target = Target::new(opts, ss, opts.edges);
    let scene = Scene::new(&prep, &proj, &target);
    scene.fill_faces(&mut target, colors, opts, None);
    if opts.edges {
        scene.draw_edges(&mut target, opts, ss);
    }
    Ok(resolve(&target, ss as usize, opts.width, opts.height))
}

/// The prepared mesh seen through the camera.
struct Scene<'a> {
    prep: &'a Prepared<'a>,
    proj: &'a Projector,
    /// View-space position of every used vertex.
    view: Vec<ViewPoint>,
    /// Sample-space projection of every used vertex in front of the near
    /// plane.
    screen: Vec<SVert>,
    /// Whether the vertex is in front of the near plane and inside the
    /// guard band (triangles of such vertices need no clipping).
    simple: Vec<bool>,
}

impl<'a> Scene<'a> {
    fn new(prep: &'a Prepared<'a>, proj: &'a Projector, target: &Target) -> Scene<'a> {
        let n = prep.q.len();
        let mut view = vec![DVec3::ZERO; n];
        let mut screen = vec![
            SVert {
                x: 0.0,
                y: 0.0,
                w: 0.0
            };
            n
        ];
        let mut simple = vec![false; n];
        let (gw, gh) = (target.width as f64 + GUARD, target.height as f64 + GUARD);
        for v in 0..n {
            if !prep.used[v] {
                continue;
            }
            view[v] = proj.view(prep.q[v]);
            if view[v].z >= proj.near {
                let s = proj.project(view[v]);
                screen[v] = s;
                simple[v] = s.x >= -GUARD && s.x <= gw && s.y >= -GUARD && s.y <= gh;
            }
        }
        Scene {
            prep,
            proj,
            view,
            screen,
            simple,
        }
    }

    /// Fills every drawable face with non-zero area, fan-triangulated from
    /// its first corner. `pre_pass` overrides the choice of a depth
    /// pre-pass for interpolated shading (tests compare both).
    fn fill_faces(
        &self,
        target: &mut Target,
        colors: Option<Colors<'_>>,
        opts: &RenderOptions,
        pre_pass: Option<bool>,
    ) {
        let prep = self.prep;
        let shader = Shader::default();
        let front = rgb_linear(opts.color);
        let back_tint = rgb_linear(opts.back_color);
        let per_vertex = matches!(colors, Some(Colors::PerVertex(_)));
        let interpolate = opts.smooth || per_vertex;
        // A depth pre-pass costs a second scan conversion of every
        // triangle but shades each visible sample once: it pays when
        // triangles are large and overlap (a Menger sponge's tunnels), not
        // for a million tiny ones. Decided from sizes only, so the same
        // input always takes the same path.
        let triangles: usize = prep
            .drawable
            .iter()
            .map(|&f| prep.face(f as usize).len() - 2)
            .sum();
        let pre_pass =
            interpolate && pre_pass.unwrap_or(triangles * 32 < target.width * target.height);
        // Faces seen from the front are drawn first: on closed models the
        // back faces then fail the depth test before any shading.
        let facing: Vec<bool> = prep
            .drawable
            .iter()
            .map(|&f| {
                let face = prep.face(f as usize);
                prep.normal[f as usize].dot(self.proj.eye - prep.q[face[0] as usize]) < 0.0
            })
            .collect();
        let order = prep
            .drawable
            .iter()
            .zip(&facing)
            .filter(|(_, b)| !**b)
            .chain(prep.drawable.iter().zip(&facing).filter(|(_, b)| **b));
        if pre_pass {
            let none = [[0.0; 6]; 3];
            for (&f, _) in order.clone() {
                let face = prep.face(f as usize);
                if prep.normal[f as usize] == DVec3::ZERO {
                    continue;
                }
                for k in 1..face.len() - 1 {
                    self.triangle(
                        target,
                        [face[0], face[k], face[k + 1]],
                        none,
                        f,
                        Mode::Depth,
                    );
                }
            }
        }
        let shade_mode = if pre_pass {
            Mode::ShadeVisible(&shader)
        } else {
            Mode::Shade(&shader)
        };
        for (&f, &back) in order {
            let f = f as usize;
            let nf = prep.normal[f];
            if nf == DVec3::ZERO {
                continue;
            }
            let face = prep.face(f);
            let n_eye = self.proj.to_eye(if back { -nf } else { nf }).as_vec3();
            // How much of the back tint a face seen from behind gets: none
            // when seen edge-on, all from 30° off edge-on. Closed models
            // show slivers of back faces along their silhouettes; fading
            // keeps those neutral while holes, inside-out parts and open
            // sheets seen from behind are clearly tinted.
            let tint = if back {
                let to_eye =
                    crate::unit(self.proj.eye - prep.q[face[0] as usize]).unwrap_or(DVec3::ZERO);
                ((nf.dot(to_eye).abs() as f32 - 0.1) / 0.4).clamp(0.0, 1.0)
            } else {
                0.0
            };
            // A caller's colour seen from behind is mixed up to half and
            // half with the back tint, so it stays recognisable.
            let side = |c: Vec3, k: f32| c + (back_tint - c) * (tint * k);
            let albedo = match colors {
                None | Some(Colors::PerVertex(_)) => side(front, 1.0),
                Some(Colors::PerFace(c)) => side(rgb_linear(c[f]), 0.5),
            };
            let start = prep.offsets[f] as usize;
            if !interpolate {
                let mode = Mode::Flat(pack_linear(shader.shade(n_eye, albedo)));
                let none = [[0.0; 6]; 3];
                for k in 1..face.len() - 1 {
                    self.triangle(
                        target,
                        [face[0], face[k], face[k + 1]],
                        none,
                        f as u32,
                        mode,
                    );
                }
                continue;
            }
            let attr = |k: usize| -> Attr {
                let n = if opts.smooth {
                    let cn = prep.corner_normal[start + k].as_dvec3();
                    self.proj.to_eye(if back { -cn } else { cn }).as_vec3()
                } else {
                    n_eye
                };
                let a = match colors {
                    Some(Colors::PerVertex(c)) => side(rgb_linear(c[face[k] as usize]), 0.5),
                    _ => albedo,
                };
                [n.x, n.y, n.z, a.x, a.y, a.z]
            };
            let first = attr(0);
            let mut prev = attr(1);
            for k in 1..face.len() - 1 {
                let next = attr(k + 1);
                self.triangle(
                    target,
                    [face[0], face[k], face[k + 1]],
                    [first, prev, next],
                    f as u32,
                    shade_mode,
                );
                prev = next;
            }
        }
    }

    /// Rasterizes one triangle of mesh vertices, clipping when needed.
    fn triangle(&self, target: &mut Target, v: [u32; 3], attr: [Attr; 3], face: u32, mode: Mode) {
        let [a, b, c] = v.map(|i| i as usize);
        if self.simple[a] && self.simple[b] && self.simple[c] {
            fill_triangle(
                target,
                [self.screen[a], self.screen[b], self.screen[c]],
                attr,
                face,
                mode,
            );
            return;
        }
        // Clip against the near plane in view space.
        let near = self.proj.near;
        let poly: Vec<(DVec3, Attr)> = [(a, 0), (b, 1), (c, 2)]
            .iter()
            .map(|&(v, k)| (self.view[v], attr[k]))
            .collect();
        let clipped = clip_polygon(
            &poly,
            |p| p.0.z - near,
            |p, q, t| (p.0 + (q.0 - p.0) * t, lerp_attr(&p.1, &q.1, t as f32)),
        );
        if clipped.len() < 3 {
            return;
        }
        // Project; attributes are carried as a·w, which is affine on the
        // screen like x, y and w.
        let mut poly: Vec<(SVert, Attr)> = clipped
            .iter()
            .map(|(p, a)| {
                let s = self.proj.project(*p);
                (s, a.map(|x| x * s.w as f32))
            })
            .collect();
        let (lo_x, lo_y) = (-GUARD, -GUARD);
        let (hi_x, hi_y) = (target.width as f64 + GUARD, target.height as f64 + GUARD);
        let lerp = |p: &(SVert, Attr), q: &(SVert, Attr), t: f64| {
            (
                SVert {
                    x: p.0.x + (q.0.x - p.0.x) * t,
                    y: p.0.y + (q.0.y - p.0.y) * t,
                    w: p.0.w + (q.0.w - p.0.w) * t,
                },
                lerp_attr(&p.1, &q.1, t as f32),
            )
        };
        poly = clip_polygon(&poly, |p| p.0.x - lo_x, lerp);
        poly = clip_polygon(&poly, |p| hi_x - p.0.x, lerp);
        poly = clip_polygon(&poly, |p| p.0.y - lo_y, lerp);
        poly = clip_polygon(&poly, |p| hi_y - p.0.y, lerp);
        if poly.len() < 3 {
            return;
        }
        let unw = |(s, a): &(SVert, Attr)| -> (SVert, Attr) {
            let inv = if s.w > 0.0 { 1.0 / s.w as f32 } else { 0.0 };
            (*s, a.map(|x| x * inv))
        };
        let (s0, a0) = unw(&poly[0]);
        for k in 1..poly.len() - 1 {
            let (s1, a1) = unw(&poly[k]);
            let (s2, a2) = unw(&poly[k + 1]);
            fill_triangle(target, [s0, s1, s2], [a0, a1, a2], face, mode);
        }
    }

    /// Draws every polygon boundary edge of the drawable faces.
    fn draw_edges(&self, target: &mut Target, opts: &RenderOptions, ss: u32) {
        let prep = self.prep;
        // Every boundary edge of every face as (higher vertex, face),
        // bucketed by its lower vertex (a counting sort), so the copies of
        // an edge land in the same small bucket.
        let n = prep.q.len();
        let mut start = vec![0usize; n + 1];
        let each_edge = |f: u32, visit: &mut dyn FnMut(u32, u32)| {
            let face = prep.face(f as usize);
            let mut prev = face[face.len() - 1];
            for &v in face {
                if v != prev {
                    visit(prev.min(v), prev.max(v));
                }
                prev = v;
            }
        };
        for &f in &prep.drawable {
            each_edge(f, &mut |lo, _| start[lo as usize + 1] += 1);
        }
        for i in 0..n {
            start[i + 1] += start[i];
        }
        let mut fill = start.clone();
        let mut bucket = vec![(0u32, 0u32); start[n]];
        for &f in &prep.drawable {
            each_edge(f, &mut |lo, hi| {
                bucket[fill[lo as usize]] = (hi, f);
                fill[lo as usize] += 1;
            });
        }
        let half = opts.edge_width * f64::from(ss) / 2.0;
        let tol = 0.004 + 2.0 * self.proj.sample_size();
        let color = pack(opts.edge_color, 255);
        let mut faces: Vec<u32> = Vec::new();
        let mut stations: Vec<bool> = Vec::new();
        for lo in 0..n {
            let row = &mut bucket[start[lo]..start[lo + 1]];
            // Buckets are small (a vertex's valence); insertion order is
            // face order, so sorting makes the result independent of it.
            row.sort_unstable();
            let mut i = 0;
            while i < row.len() {
                let hi = row[i].0;
                faces.clear();
                while i < row.len() && row[i].0 == hi {
                    if faces.last() != Some(&row[i].1) {
                        faces.push(row[i].1);
                    }
                    i += 1;
                }
                let Some((p0, p1)) = self.segment(lo, hi as usize, target, half + 2.0) else {
                    continue;
                };
                // Edges shorter than a few pixels fade out: a dense mesh
                // shows its shading instead of a black blanket, and
                // foreshortened edges do not pile up near silhouettes.
                let length = ((p1.x - p0.x).powi(2) + (p1.y - p0.y).powi(2)).sqrt() / f64::from(ss);
                let alpha = ((length - FADE_START) / (FADE_FULL - FADE_START)).clamp(0.0, 1.0);
                let alpha = (alpha * 256.0) as u32;
                if alpha == 0 {
                    continue;
                }
                let line = Line {
                    p0,
                    p1,
                    half,
                    faces: &faces,
                    color,
                    alpha,
                    tol,
                };
                line.draw(target, &mut stations);
            }
        }
    }

    /// The screen segment of edge a–b clipped to the near plane and to the
    /// picture grown by `margin` samples, or `None` if nothing is left.
    fn segment(&self, a: usize, b: usize, target: &Target, margin: f64) -> Option<(SVert, SVert)> {
        let near = self.proj.near;
        let (mut va, mut vb) = (self.view[a], self.view[b]);
        if va.z < near && vb.z < near {
            return None;
        }
        if va.z < near {
            va = va + (vb - va) * ((near - va.z) / (vb.z - va.z));
        } else if vb.z < near {
            vb = vb + (va - vb) * ((near - vb.z) / (va.z - vb.z));
        }
        let (p, q) = (self.proj.project(va), self.proj.project(vb));
        // Liang–Barsky against the grown picture; w is affine on the
        // screen so it is interpolated like x and y.
        let (mut t0, mut t1) = (0.0f64, 1.0f64);
        let d = (q.x - p.x, q.y - p.y);
        let bounds = [
            (-d.0, p.x + margin),
            (d.0, target.width as f64 + margin - p.x),
            (-d.1, p.y + margin),
            (d.1, target.height as f64 + margin - p.y),
        ];
        for (den, num) in bounds {
            if den == 0.0 {
                if num < 0.0 {
                    return None;
                }
            } else {
                let t = num / den;
                if den < 0.0 {
                    t0 = t0.max(t);
                } else {
                    t1 = t1.min(t);
                }
            }
        }
        if t0.is_nan() || t1.is_nan() || t0 > t1 {
            return None;
        }
        let at = |t: f64| SVert {
            x: p.x + (q.x - p.x) * t,
            y: p.y + (q.y - p.y) * t,
            w: p.w + (q.w - p.w) * t,
        };
        Some((at(t0), at(t1)))
    }
}

fn lerp_attr(a: &Attr, b: &Attr, t: f32) -> Attr {
    std::array::from_fn(|k| a[k] + (b[k] - a[k]) * t)
}

/// Sutherland–Hodgman: the part of a convex polygon where `dist ≥ 0`.
fn clip_polygon<T: Copy>(
    poly: &[T],
    dist: impl Fn(&T) -> f64,
    lerp: impl Fn(&T, &T, f64) -> T,
) -> Vec<T> {
    let mut out = Vec::with_capacity(poly.len() + 2);
    let Some(last) = poly.last() else {
        return out;
    };
    let mut prev = last;
    let mut dp = dist(prev);
    for cur in poly {
        let dc = dist(cur);
        if dc >= 0.0 {
            if dp < 0.0 {
                out.push(lerp(prev, cur, dp / (dp - dc)));
            }
            out.push(*cur);
        } else if dp >= 0.0 {
            out.push(lerp(prev, cur, dp / (dp - dc)));
        }
        prev = cur;
        dp = dc;
    }
    out
}

/// Scan-converts one triangle (see the module documentation).
fn fill_triangle(target: &mut Target, v: [SVert; 3], attr: [Attr; 3], face: u32, mode: Mode) {
    let fx = |t: f64| floor_i(t * SUB + 0.5);
    let mut x = [fx(v[0].x), fx(v[1].x), fx(v[2].x)];
    let mut y = [fx(v[0].y), fx(v[1].y), fx(v[2].y)];
    let mut w = [v[0].w, v[1].w, v[2].w];
    let mut attr = attr;
    let mut area = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
    if area == 0 {
        return;
    }
    if area < 0 {
        x.swap(1, 2);
        y.swap(1, 2);
        w.swap(1, 2);
        attr.swap(1, 2);
        area = -area;
    }
    // Samples whose centre 256·i + 128 lies in the bounding box.
    let step = SUB as i64;
    let half = step / 2;
    // ⌈(lo − 128) / 256⌉ and ⌊(hi − 128) / 256⌋ by arithmetic shifts.
    let range = |lo: i64, hi: i64, n: usize| {
        let first = -((half - lo) >> 8);
        let last = (hi - half) >> 8;
        (first.max(0), last.min(n as i64 - 1))
    };
    let (i0, i1) = range(
        x[0].min(x[1]).min(x[2]),
        x[0].max(x[1]).max(x[2]),
        target.width,
    );
    let (j0, j1) = range(
        y[0].min(y[1]).min(y[2]),
        y[0].max(y[1]).max(y[2]),
        target.height,
    );
    if i0 > i1 || j0 > j1 {
        return;
    }
    // e[k] is the edge function of the edge opposite vertex k, so
    // e[k] / area is vertex k's barycentric coordinate.
    let opp = [(1, 2), (2, 0), (0, 1)];
    let (px, py) = (i0 * step + half, j0 * step + half);
    let mut row: [i64; 3] =
        opp.map(|(a, b)| (x[b] - x[a]) * (py - y[a]) - (y[b] - y[a]) * (px - x[a]));
    let dx: [i64; 3] = opp.map(|(a, b)| -(y[b] - y[a]) * step);
    let dy: [i64; 3] = opp.map(|(a, b)| (x[b] - x[a]) * step);
    let inv = 1.0 / area as f64;
    // w is affine in the sample position: w = Σ e[k]·w[k] / area.
    let plane = |e: [i64; 3]| (e[0] as f64 * w[0] + e[1] as f64 * w[1] + e[2] as f64 * w[2]) * inv;
    let dwdx = plane(dx);
    let lut = crate::shade::lut();
    let track = !target.face.is_empty();
    // Narrow triangles (most of a dense mesh) find each row's span by
    // testing its few samples; wide ones solve for it, which costs three
    // divisions per row but no per-sample tests.
    let narrow = i1 - i0 < 16;
    for j in j0..=j1 {
        let e = row;
        row = [row[0] + dy[0], row[1] + dy[1], row[2] + dy[2]];
        // The covered samples of this row: e[k] + t·dx[k] ≥ 0 for all k.
        let (mut lo, mut hi) = (0i64, i1 - i0);
        if narrow {
            let mut t = e;
            let (mut first, mut last) = (-1, -2);
            for i in 0..=hi {
                if (t[0] | t[1] | t[2]) >= 0 {
                    if first < 0 {
                        first = i;
                    }
                    last = i;
                }
                t = [t[0] + dx[0], t[1] + dx[1], t[2] + dx[2]];
            }
            (lo, hi) = (first, last);
        } else {
            // Solve with a float division (exact to ±1 since all values
            // are below 2^53), clamped to just outside the row, then make
            // it exact with integer tests.
            let span = i1 - i0;
            let covered = |k: usize, t: i64| e[k] + t * dx[k] >= 0;
            for k in 0..3 {
                if dx[k] > 0 {
                    let mut t = ceil_i(-(e[k] as f64) / dx[k] as f64).clamp(-2, span + 2);
                    if !covered(k, t) {
                        t += 1;
                    } else if covered(k, t - 1) {
                        t -= 1;
                    }
                    lo = lo.max(t);
                } else if dx[k] < 0 {
                    let mut t = floor_i(e[k] as f64 / -dx[k] as f64).clamp(-2, span + 2);
                    if !covered(k, t) {
                        t -= 1;
                    } else if covered(k, t + 1) {
                        t += 1;
                    }
                    hi = hi.min(t);
                } else if e[k] < 0 {
                    hi = -1;
                }
            }
        }
        if lo > hi || lo < 0 {
            continue;
        }
        let mut wi = plane(e) + dwdx * lo as f64;
        let mut e = [e[0] + dx[0] * lo, e[1] + dx[1] * lo, e[2] + dx[2] * lo];
        let mut shaded: Option<(usize, u32)> = None;
        // The span, cut where it crosses into the next tile.
        let (mut i, end) = ((i0 + lo) as usize, (i0 + hi) as usize);
        while i <= end {
            let stop = end.min(i | (TILE - 1));
            let base = target.at(i, j as usize);
            let len = stop - i + 1;
            let first_col = i;
            i = stop + 1;
            let depth = &mut target.depth[base..base + len];
            let colors = &mut target.color[base..base + len];
            let faces: &mut [u32] = if track {
                &mut target.face[base..base + len]
            } else {
                &mut []
            };
            match mode {
                Mode::Flat(c) => {
                    for (k, (d, col)) in depth.iter_mut().zip(colors.iter_mut()).enumerate() {
                        let wf = wi as f32;
                        if wf > *d {
                            *d = wf;
                            *col = c;
                            if let Some(f) = faces.get_mut(k) {
                                *f = face;
                            }
                        }
                        wi += dwdx;
                    }
                }
                Mode::Depth => {
                    for d in depth.iter_mut() {
                        let wf = wi as f32;
                        if wf > *d {
                            *d = wf;
                        }
                        wi += dwdx;
                    }
                }
                Mode::Shade(shader) | Mode::ShadeVisible(shader) => {
                    let visible_only = matches!(mode, Mode::ShadeVisible(_));
                    for (k, (d, col)) in depth.iter_mut().zip(colors.iter_mut()).enumerate() {
                        let wf = wi as f32;
                        let pass = if visible_only { wf >= *d } else { wf > *d };
                        if pass {
                            *d = wf;
                            if let Some(f) = faces.get_mut(k) {
                                *f = face;
                            }
                            // One shading per pixel and sample row: the
                            // other samples of the pixel in this row reuse
                            // it (they are under a pixel apart).
                            let pixel = (first_col + k) / target.ss;
                            if let Some((p, c)) = shaded
                                && p == pixel
                            {
                                *col = c;
                                wi += dwdx;
                                e = [e[0] + dx[0], e[1] + dx[1], e[2] + dx[2]];
                                continue;
                            }
                            // Perspective-correct weights bₖwₖ / Σ bⱼwⱼ.
                            let pw = [e[0] as f64 * w[0], e[1] as f64 * w[1], e[2] as f64 * w[2]];
                            let norm = 1.0 / (pw[0] + pw[1] + pw[2]);
                            let l = pw.map(|p| (p * norm) as f32);
                            let at: Attr = std::array::from_fn(|k| {
                                l[0] * attr[0][k] + l[1] * attr[1][k] + l[2] * attr[2][k]
                            });
                            let n = Vec3::new(at[0], at[1], at[2]).normalize_or(Vec3::Z);
                            *col = lut.pack(shader.shade(n, Vec3::new(at[3], at[4], at[5])));
                            shaded = Some((pixel, *col));
                        }
                        wi += dwdx;
                        e = [e[0] + dx[0], e[1] + dx[1], e[2] + dx[2]];
                    }
                }
            }
        }
    }
}

/// ⌊x⌋ without a libm call (the baseline x86-64 target has no rounding
/// instruction); NaN gives 0 and huge values saturate.
#[inline]
fn floor_i(x: f64) -> i64 {
    let t = x as i64;
    t - i64::from(x < t as f64)
}

/// ⌈x⌉, like [`floor_i`].
#[inline]
fn ceil_i(x: f64) -> i64 {
    let t = x as i64;
    t + i64::from(x > t as f64)
}

/// Edges shorter than this many pixels on screen are not drawn.
pub const FADE_START: f64 = 1.5;
/// Edges at least this many pixels long are drawn opaque; between
/// [`FADE_START`] and this their opacity grows linearly.
pub const FADE_FULL: f64 = 5.0;

/// One edge to draw, in sample space.
struct Line<'a> {
    p0: SVert,
    p1: SVert,
    /// Half the line width, in samples.
    half: f64,
    /// The faces that have this edge.
    faces: &'a [u32],
    color: u32,
    /// Opacity in 256ths (1..=256).
    alpha: u32,
    /// Depth tolerance (normalized units).
    tol: f64,
}

impl Line<'_> {
    fn draw(&self, target: &mut Target, stations: &mut Vec<bool>) {
        let (p0, p1) = (self.p0, self.p1);
        let (dx, dy) = (p1.x - p0.x, p1.y - p0.y);
        let len = (dx * dx + dy * dy).sqrt();
        let (len, ux, uy) = if len > 1e-9 {
            (len, dx / len, dy / len)
        } else {
            (0.0, 1.0, 0.0)
        };
        // Stations at most one sample apart along the centre line; each
        // looks at the samples across the line (the neighbours along it
        // are the next stations').
        let count = ceil_i(len) as usize + 1;
        let last = (count - 1).max(1) as f64;
        let (ax, ay) = if ux.abs() >= uy.abs() { (0, 1) } else { (1, 0) };
        stations.clear();
        for k in 0..count {
            let t = k as f64 / last;
            let w = p0.w + (p1.w - p0.w) * t;
            stations.push(self.station_visible(
                target,
                floor_i(p0.x + dx * t),
                floor_i(p0.y + dy * t),
                (ax, ay),
                w,
            ));
        }
        if !stations.iter().any(|&v| v) {
            return;
        }
        // The rectangle: along ∈ [−half, len + half], across ∈ [−half,
        // half], with along/across the coordinates of a point relative to
        // p0 in the frame (u, u⊥).
        let h = self.half;
        let corners = [
            (p0.x - (ux + uy) * h, p0.y - (uy - ux) * h),
            (p0.x - (ux - uy) * h, p0.y - (uy + ux) * h),
            (p1.x + (ux + uy) * h, p1.y + (uy - ux) * h),
            (p1.x + (ux - uy) * h, p1.y + (uy + ux) * h),
        ];
        let ymin = corners.iter().map(|c| c.1).fold(f64::INFINITY, f64::min);
        let ymax = corners
            .iter()
            .map(|c| c.1)
            .fold(f64::NEG_INFINITY, f64::max);
        let j0 = ceil_i(ymin - 0.5).max(0);
        let j1 = floor_i(ymax - 0.5).min(target.height as i64 - 1);
        for j in j0..=j1 {
            let ry = j as f64 + 0.5 - p0.y;
            // along(x) = (x − p0.x)·ux + ry·uy, across(x) = −(x − p0.x)·uy + ry·ux.
            let Some((a0, a1)) = slab(ux, ry * uy, -h, len + h) else {
                continue;
            };
            let Some((c0, c1)) = slab(-uy, ry * ux, -h, h) else {
                continue;
            };
            let (lo, hi) = (a0.max(c0) + p0.x, a1.min(c1) + p0.x);
            let i0 = ceil_i(lo - 0.5).max(0);
            let i1 = floor_i(hi - 0.5).min(target.width as i64 - 1);
            for i in i0..=i1 {
                let along = (i as f64 + 0.5 - p0.x) * ux + ry * uy;
                let t = if len > 0.0 {
                    (along / len).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                if !stations[(t * last + 0.5) as usize] {
                    continue;
                }
                let s = target.at(i as usize, j as usize);
                let surface = target.depth[s];
                let line_w = p0.w + (p1.w - p0.w) * t;
                if surface > 0.0
                    && !self.faces.contains(&target.face[s])
                    && 1.0 / line_w > 1.0 / f64::from(surface) + self.tol
                {
                    continue;
                }
                target.color[s] = blend(target.color[s], self.color, self.alpha);
            }
        }
    }

    /// Whether the centre-line point in sample (ci, cj), at 1/z = `w`, is
    /// visible: the samples at −1, 0, +1 along `across` show one of the
    /// edge's faces or background, or nothing there lies more than the
    /// tolerance in front of the edge.
    fn station_visible(
        &self,
        target: &Target,
        ci: i64,
        cj: i64,
        across: (i64, i64),
        w: f64,
    ) -> bool {
        let mut farthest = f32::INFINITY;
        for k in -1..=1 {
            let (i, j) = (ci + k * across.0, cj + k * across.1);
            if i < 0 || j < 0 || i >= target.width as i64 || j >= target.height as i64 {
                continue;
            }
            let s = target.at(i as usize, j as usize);
            let d = target.depth[s];
            if d <= 0.0 || self.faces.contains(&target.face[s]) {
                return true;
            }
            farthest = farthest.min(d);
        }
        farthest != f32::INFINITY && 1.0 / w <= 1.0 / f64::from(farthest) + self.tol
    }
}

/// `top` over `under` with opacity `alpha`/256, per 8-bit channel; the
/// result is opaque if either is.
#[inline]
fn blend(under: u32, top: u32, alpha: u32) -> u32 {
    if alpha >= 256 {
        return top;
    }
    let mut out = 0;
    for shift in [0, 8, 16, 24] {
        let (u, t) = (under >> shift & 255, top >> shift & 255);
        out |= ((u * (256 - alpha) + t * alpha) >> 8) << shift;
    }
    out
}

/// The x-interval where lo ≤ coef·x + c ≤ hi, or `None` if empty; the
/// whole line when coef is 0 and c is in range.
fn slab(coef: f64, c: f64, lo: f64, hi: f64) -> Option<(f64, f64)> {
    if coef.abs() < 1e-12 {
        return (lo..=hi)
            .contains(&c)
            .then_some((f64::NEG_INFINITY, f64::INFINITY));
    }
    let (a, b) = ((lo - c) / coef, (hi - c) / coef);
    Some((a.min(b), a.max(b)))
}

/// Averages each pixel's samples in linear light with premultiplied
/// alpha, then converts to 8-bit sRGB with straight alpha. A pixel whose
/// samples are all equal keeps that colour exactly (the sRGB → linear →
/// sRGB round trip is the identity), which is also the fast path.
fn resolve(target: &Target, ss: usize, width: u32, height: u32) -> Image {
    let (w, h) = (width as usize, height as usize);
    let mut data = vec![0u8; w * h * 4];
    let n = (ss * ss) as f32;
    let lut = crate::shade::lut();
    // Each pixel row's ss sample rows, copied out of the tiles into plain
    // lines, then each pixel's samples gathered from them.
    let mut lines = vec![0u32; ss * target.width];
    let mut buf = [0u32; (crate::MAX_SUPERSAMPLE * crate::MAX_SUPERSAMPLE) as usize];
    for (py, out_row) in data.chunks_exact_mut(w * 4).enumerate().take(h) {
        for (r, line) in lines.chunks_exact_mut(target.width).enumerate() {
            let j = py * ss + r;
            for (t, chunk) in line.chunks_mut(TILE).enumerate() {
                let s = target.at(t * TILE, j);
                chunk.copy_from_slice(&target.color[s..s + chunk.len()]);
            }
        }
        for (px, out) in out_row.chunks_exact_mut(4).enumerate() {
            for r in 0..ss {
                let src = &lines[r * target.width + px * ss..][..ss];
                for (slot, &c) in buf[r * ss..(r + 1) * ss].iter_mut().zip(src) {
                    *slot = c;
                }
            }
            let samples = &buf[..ss * ss];
            let first = samples[0];
            if samples.iter().all(|&c| c == first) {
                out.copy_from_slice(&first.to_le_bytes());
                continue;
            }
            let mut sum = [0.0f32; 4];
            for &c in samples {
                let a = (c >> 24) as f32 / 255.0;
                sum[0] += lut.to_linear[(c & 255) as usize] * a;
                sum[1] += lut.to_linear[(c >> 8 & 255) as usize] * a;
                sum[2] += lut.to_linear[(c >> 16 & 255) as usize] * a;
                sum[3] += a;
            }
            if sum[3] > 0.0 {
                let inv = 1.0 / sum[3];
                out.copy_from_slice(&[
                    lut.encode(sum[0] * inv),
                    lut.encode(sum[1] * inv),
                    lut.encode(sum[2] * inv),
                    (sum[3] / n * 255.0 + 0.5) as u8,
                ]);
            }
        }
    }
    Image::from_parts(width, height, data)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn empty(width: usize, height: usize) -> Target {
        Target::with_size(width, height, 1, true, |_| 0)
    }

    /// Tiles map every sample of the picture to its own buffer slot.
    #[test]
    fn tiled_layout_is_a_bijection() {
        for (w, h) in [(1, 1), (33, 7), (64, 65), (100, 31)] {
            let t = empty(w, h);
            let mut seen = vec![false; t.depth.len()];
            for j in 0..h {
                for i in 0..w {
                    let s = t.at(i, j);
                    assert!(!seen[s], "{w}x{h}: ({i}, {j})");
                    seen[s] = true;
                }
            }
        }
    }

    /// Shading after a depth pre-pass gives the picture of direct
    /// shading (up to which of two equally near triangles wins a sample
    /// on a shared edge).
    #[test]
    fn depth_pre_pass_does_not_change_the_picture() {
        let mesh = holey_shapes::parse_primitive("@torus:12:8").unwrap();
        let opts = RenderOptions {
            width: 90,
            height: 70,
            smooth: true,
            ..RenderOptions::default()
        };
        let prep = Prepared::new(&mesh, true, 60.0).unwrap();
        let proj = Projector::new(&prep, &opts, 2).unwrap();
        let mut pictures = Vec::new();
        for pre in [false, true] {
            let mut target = Target::new(&opts, 2, false);
            let scene = Scene::new(&prep, &proj, &target);
            scene.fill_faces(&mut target, None, &opts, Some(pre));
            pictures.push(target);
        }
        let n = pictures[0].color.len();
        let differ = (0..n)
            .filter(|&s| pictures[0].color[s] != pictures[1].color[s])
            .count();
        assert_eq!(pictures[0].depth, pictures[1].depth);
        assert!(differ * 500 < n, "{differ} of {n}");
    }

    /// A horizontal line 4.5 samples wide centred on y = 45 covers the
    /// sample rows whose centres are within 2.25: 43 to 46.
    #[test]
    fn line_width_in_samples() {
        let mut t = empty(120, 90);
        let line = Line {
            p0: SVert {
                x: 10.0,
                y: 45.0,
                w: 1.0,
            },
            p1: SVert {
                x: 100.0,
                y: 45.0,
                w: 1.0,
            },
            half: 2.25,
            faces: &[],
            color: 1,
            alpha: 256,
            tol: 0.01,
        };
        line.draw(&mut t, &mut Vec::new());
        let rows: Vec<usize> = (0..90).filter(|&j| t.color[t.at(50, j)] == 1).collect();
        assert_eq!(rows, vec![43, 44, 45, 46]);
        // Square caps: half a width beyond each end, no further.
        let cols: Vec<usize> = (0..120).filter(|&i| t.color[t.at(i, 45)] == 1).collect();
        assert_eq!(cols, (8..=101).collect::<Vec<_>>());
    }
}
