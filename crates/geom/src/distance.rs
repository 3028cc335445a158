//! Floating-point distances, for brushes that only ask whether something
//! is near and for filters that pass anything close to the exact
//! predicates.

use glam::DVec3;

/// Distance from `p` to the segment `[a, b]`: to the projection of `p` on
/// the line through `a` and `b`, its parameter clamped to the segment
/// (`[0, 1]`), so beyond an end the distance is to that end. A segment of
/// zero length is the point `a`.
pub fn point_segment_distance(p: DVec3, a: DVec3, b: DVec3) -> f64 {
    let ab = b - a;
    let len2 = ab.length_squared();
    let s = if len2 > 0.0 {
        ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p - (a + ab * s)).length()
}
