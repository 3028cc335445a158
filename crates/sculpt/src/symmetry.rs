//! Mirror symmetry for strokes: a brush applied at a point is applied at
//! its mirror images too, across the planes through a centre normal to
//! the chosen axes (SculptGL's and Blender's symmetry).
//!
//! With `k` axes chosen there are `2ᵏ` images, the point itself and its
//! reflections by every non-empty subset of the axes: with X and Y, the
//! reflections in x, in y, and in both (a half-turn about z). Each image
//! of a brush frame is evaluated on the same surface and the
//! displacements added, so on a mirror-symmetric surface the result is
//! mirror-symmetric (up to the rounding of normal sums). The topology
//! change then sees one motion, whatever the number of images.

use glam::DVec3;
use serde::{Deserialize, Serialize};

/// The mirror planes of a stroke: the axes whose planes reflect, through
/// `centre`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Symmetry {
    /// Reflect across the plane normal to x, y, z.
    pub axes: [bool; 3],
    /// The point the planes pass through (the origin, or the mesh's
    /// centre, as the caller chooses).
    pub centre: DVec3,
}

/// Where a stroke file's mirror planes pass.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum About {
    /// Through the origin.
    #[default]
    Origin,
    /// Through the centre of the mesh's bounding box when the stroke
    /// starts.
    Centre,
}

/// One image of the mirror group: `flip` holds +1 or −1 per axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mirror {
    /// The sign each coordinate takes, about the centre.
    pub flip: DVec3,
    /// The centre of the reflection.
    pub centre: DVec3,
}

impl Mirror {
    /// The identity: no reflection.
    pub const IDENTITY: Mirror = Mirror {
        flip: DVec3::ONE,
        centre: DVec3::ZERO,
    };

    /// The image of a point.
    pub fn point(&self, p: DVec3) -> DVec3 {
        if self.flip == DVec3::ONE {
            p
        } else {
            self.centre + self.flip * (p - self.centre)
        }
    }

    /// The image of a displacement (a vector: the centre plays no part).
    pub fn vector(&self, v: DVec3) -> DVec3 {
        self.flip * v
    }
}

impl Symmetry {
    /// No symmetry.
    pub const NONE: Symmetry = Symmetry {
        axes: [false; 3],
        centre: DVec3::ZERO,
    };

    /// Symmetry across the planes of the axes named in `axes` (any of
    /// `x`, `y`, `z`, in any order and case; empty for none) through
    /// `centre`. `None` for any other letter.
    pub fn parse(axes: &str, centre: DVec3) -> Option<Symmetry> {
        let mut on = [false; 3];
        for c in axes.chars() {
            match c.to_ascii_lowercase() {
                'x' => on[0] = true,
                'y' => on[1] = true,
                'z' => on[2] = true,
                _ => return None,
            }
        }
        Some(Symmetry { axes: on, centre })
    }

    /// The images: the identity first, then the reflections by every
    /// non-empty subset of the chosen axes.
    pub fn mirrors(&self) -> Vec<Mirror> {
        let mut out = vec![Mirror::IDENTITY];
        for subset in 1u8..8 {
            let uses = |axis: usize| subset & (1 << axis) != 0;
            if (0..3).any(|a| uses(a) && !self.axes[a]) {
                continue;
            }
            let sign = |a: usize| if uses(a) { -1.0 } else { 1.0 };
            out.push(Mirror {
                flip: DVec3::new(sign(0), sign(1), sign(2)),
                centre: self.centre,
            });
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn images_of_each_choice() {
        assert_eq!(Symmetry::NONE.mirrors(), vec![Mirror::IDENTITY]);
        let x = Symmetry::parse("x", DVec3::new(1.0, 0.0, 0.0)).unwrap_or(Symmetry::NONE);
        let m = x.mirrors();
        assert_eq!(m.len(), 2);
        assert_eq!(
            m[1].point(DVec3::new(3.0, 2.0, 1.0)),
            DVec3::new(-1.0, 2.0, 1.0)
        );
        assert_eq!(
            m[1].vector(DVec3::new(3.0, 2.0, 1.0)),
            DVec3::new(-3.0, 2.0, 1.0)
        );
        let xyz = Symmetry::parse("ZyX", DVec3::ZERO).unwrap_or(Symmetry::NONE);
        let all = xyz.mirrors();
        assert_eq!(all.len(), 8);
        // All eight sign patterns, each once.
        let mut flips: Vec<[i8; 3]> = all
            .iter()
            .map(|m| m.flip.to_array().map(|c| c as i8))
            .collect();
        flips.sort_unstable();
        flips.dedup();
        assert_eq!(flips.len(), 8);
        assert_eq!(
            Symmetry::parse("xz", DVec3::ZERO).map(|s| s.mirrors().len()),
            Some(4)
        );
        assert!(Symmetry::parse("w", DVec3::ZERO).is_none());
        assert_eq!(Symmetry::parse("", DVec3::ZERO), Some(Symmetry::NONE));
    }
}
