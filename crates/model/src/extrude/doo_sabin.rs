//! Doo–Sabin extrusion (TopMod's `extrudeFaceDS`): a plain extrusion
//! whose new ring is smoothed by the Doo–Sabin face mask, so repeated
//! extrusions round off like a subdivision surface.
//!
//! Each repetition takes the current face's corners `p_j` (`n` of them),
//! moves them along the unit normal by the distance and slides each a
//! fraction `twist` towards the next corner, `q_j = (1 − t)·p_j +
//! t·p_(j+1) + d·n`, and places new corner `i` at `Σ_j w_ij·q_j` with
//! Doo & Sabin's (1978) weights `w_ii = 1/4 + 5/(4n)` and `w_ij = (3 +
//! 2·cos(2π(i − j)/n))/(4n)`, then scales the ring about its centroid.
//! The weights sum to 1, so the mask keeps the centroid and shrinks the
//! polygon towards it (a square by a factor 1/2).

use holey_dlfl::{DVec3, FaceId, Mesh};

use super::{ExtrudeError, Extruded, base_face, plain};
use crate::polygon;

/// The parameters of [`extrude_face_doo_sabin`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DooSabinParams {
    /// How far each repetition moves along the unit normal (finite).
    pub distance: f64,
    /// How far each corner slides towards the next before smoothing, as a
    /// fraction of the edge (finite; 0 is none, 1 a whole edge).
    pub twist: f64,
    /// Scale of each new ring about its centroid after smoothing (finite, > 0).
    pub scale: f64,
    /// Number of repetitions, at least 1.
    pub count: usize,
}

impl Default for DooSabinParams {
    /// Distance 1, no twist, scale 1, once.
    fn default() -> Self {
        DooSabinParams {
            distance: 1.0,
            twist: 0.0,
            scale: 1.0,
            count: 1,
        }
    }
}

/// Doo–Sabin extrusion of `face`, `params.count` times.
///
/// Counts as the plain extrusion: a `d`-gon extruded `k` times adds `kd`
/// vertices, `2kd` edges and `kd` faces. Refusals as
/// [`super::extrude_face`].
pub fn extrude_face_doo_sabin(
    mesh: &mut Mesh,
    face: FaceId,
    params: &DooSabinParams,
) -> Result<Extruded, ExtrudeError> {
    plain::check_repeat_params(
        params.distance,
        ("twist", params.twist),
        params.scale,
        params.count,
    )?;
    let (corners, points, frame) = base_face(mesh, face)?;
    plain::extrude_repeated(mesh, face, &corners, points, params.count, |ring| {
        doo_sabin_ring(ring, frame.normal, params)
    })
}

/// One repetition's ring (see the module documentation).
pub(crate) fn doo_sabin_ring(
    points: &[DVec3],
    normal: DVec3,
    params: &DooSabinParams,
) -> Vec<DVec3> {
    let n = points.len();
    let t = params.twist;
    let q: Vec<DVec3> = (0..n)
        .map(|j| points[j] * (1.0 - t) + points[(j + 1) % n] * t + normal * params.distance)
        .collect();
    let nf = n as f64;
    let mut out: Vec<DVec3> = (0..n)
        .map(|i| {
            (0..n)
                .map(|j| {
                    let w = if i == j {
                        0.25 + 5.0 / (4.0 * nf)
                    } else {
                        let angle = std::f64::consts::TAU * (i as f64 - j as f64) / nf;
                        (3.0 + 2.0 * angle.cos()) / (4.0 * nf)
                    };
                    q[j] * w
                })
                .sum()
        })
        .collect();
    let c = polygon::centroid(&out);
    for p in &mut out {
        *p = c + (*p - c) * params.scale;
    }
    out
}
