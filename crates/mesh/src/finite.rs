//! The one error for a NaN or infinite coordinate, shared by every crate
//! that checks its input or its results ([`NonFinite`]): the kernel's
//! builders and operators, the plain meshes, the exact geometry, the
//! modeling tools and subdivision each wrap it in their own error enum
//! (`#[error(transparent)]`), so the message reads the same everywhere
//! and always says which point it was.

use std::fmt;

use glam::DVec3;
use rayon::prelude::*;

/// A point with a NaN or infinite coordinate where a finite one is needed:
/// what the point is, which one, its coordinates when known, and what to
/// change when the cause is known.
///
/// Displayed as `[input: ]what[ index] has a non-finite coordinate[ (x, y,
/// z)][; hint]`, e.g. `end positions: vertex 3 has a non-finite coordinate
/// (NaN, 0, 1)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NonFinite {
    /// The array or input that holds the point (`"mesh"`, `"end
    /// positions"`); empty when there is only one.
    pub input: &'static str,
    /// What the point is: `"vertex"`, `"point"`, `"box"`, `"handle
    /// section"`, …
    pub what: &'static str,
    /// Its index among its kind (in the array checked, or the numbering the
    /// error's owner documents), when it has one.
    pub index: Option<usize>,
    /// Its coordinates, when known.
    pub position: Option<DVec3>,
    /// What the non-finite value means for the caller (e.g. "the weights
    /// are too large for the mesh's scale"); empty when nothing is known
    /// beyond the value itself.
    pub hint: &'static str,
}

impl NonFinite {
    /// Point `index` of kind `what` (`"vertex"`, `"point"`, …), at
    /// `position`.
    pub fn new(what: &'static str, index: usize, position: DVec3) -> NonFinite {
        NonFinite {
            input: "",
            what,
            index: Some(index),
            position: Some(position),
            hint: "",
        }
    }

    /// Vertex `index` at `position`.
    pub fn vertex(index: usize, position: DVec3) -> NonFinite {
        NonFinite::new("vertex", index, position)
    }

    /// A position with no index (given to an operation, or computed by
    /// one): "the position has a non-finite coordinate (x, y, z)".
    pub fn position(position: DVec3) -> NonFinite {
        NonFinite {
            input: "",
            what: "the position",
            index: None,
            position: Some(position),
            hint: "",
        }
    }

    /// Point `index` of kind `what`, whose coordinates are not at hand.
    pub fn at(what: &'static str, index: usize) -> NonFinite {
        NonFinite {
            input: "",
            what,
            index: Some(index),
            position: None,
            hint: "",
        }
    }

    /// The same, naming the array or input that holds the point.
    pub fn in_input(self, input: &'static str) -> NonFinite {
        NonFinite { input, ..self }
    }

    /// The same, saying what the non-finite value means for the caller.
    pub fn with_hint(self, hint: &'static str) -> NonFinite {
        NonFinite { hint, ..self }
    }

    /// The first point of `positions` with a non-finite coordinate, as
    /// point `index` of kind `what` (`"vertex"`, `"point"`, …); `Ok` when
    /// all are finite.
    pub fn check(what: &'static str, positions: &[DVec3]) -> Result<(), NonFinite> {
        // A branch-free pass over blocks first (every live stroke frame
        // checks a whole mesh, a million points at a time), in parallel
        // runs; only the first block with a bad point is searched for it.
        const BLOCK: usize = 256;
        let finite = |block: &[DVec3]| {
            block.iter().fold(true, |ok, p| {
                ok & p.x.is_finite() & p.y.is_finite() & p.z.is_finite()
            })
        };
        let bad = positions
            .par_chunks(BLOCK)
            .with_min_len(crate::PARALLEL_RUN / BLOCK)
            .position_first(|block| !finite(block));
        if let Some(b) = bad {
            let block = &positions[b * BLOCK..positions.len().min((b + 1) * BLOCK)];
            let k = block.iter().position(|p| !p.is_finite()).unwrap_or(0);
            let index = b * BLOCK + k;
            return Err(NonFinite::new(what, index, positions[index]));
        }
        Ok(())
    }
}

impl fmt::Display for NonFinite {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if !self.input.is_empty() {
            write!(f, "{}: ", self.input)?;
        }
        f.write_str(self.what)?;
        if let Some(i) = self.index {
            write!(f, " {i}")?;
        }
        f.write_str(" has a non-finite coordinate")?;
        if let Some(p) = self.position {
            write!(f, " ({}, {}, {})", p.x, p.y, p.z)?;
        }
        if !self.hint.is_empty() {
            write!(f, "; {}", self.hint)?;
        }
        Ok(())
    }
}

impl std::error::Error for NonFinite {}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::NonFinite;

    #[test]
    fn the_message_says_what_which_where_and_why() {
        let p = DVec3::new(f64::NAN, 0.0, 1.0);
        assert_eq!(
            NonFinite::vertex(3, p).to_string(),
            "vertex 3 has a non-finite coordinate (NaN, 0, 1)"
        );
        assert_eq!(
            NonFinite::vertex(3, p)
                .in_input("end positions")
                .to_string(),
            "end positions: vertex 3 has a non-finite coordinate (NaN, 0, 1)"
        );
        assert_eq!(
            NonFinite::at("handle section", 2)
                .with_hint("the weights are too large for the mesh's scale")
                .to_string(),
            "handle section 2 has a non-finite coordinate; the weights are too large for the mesh's scale"
        );
        assert_eq!(
            NonFinite::position(DVec3::new(1.0, f64::INFINITY, 2.0)).to_string(),
            "the position has a non-finite coordinate (1, inf, 2)"
        );
    }

    #[test]
    fn check_finds_the_first_bad_point() {
        let mut ps = vec![DVec3::ZERO; 5];
        assert_eq!(NonFinite::check("point", &ps), Ok(()));
        ps[3].y = f64::NEG_INFINITY;
        ps[4].x = f64::NAN;
        let e = NonFinite::check("point", &ps).unwrap_err();
        assert_eq!((e.what, e.index), ("point", Some(3)));
    }
}
