//! Reference solution of `exercises/ch05_bug_normal_length.rs`, compiled only with `--features solutions`: try the
//! exercise first (`cargo exercises solution ch05_bug_normal_length` shows it once your code passes).

use glam::DVec3;

/// The bug: `point - center` has length |radius|. Dividing by the radius (not normalising, which
/// would lose the sign) gives a unit normal, inwards for the book's negative radius.
pub fn outward_normal(center: DVec3, radius: f64, point: DVec3) -> DVec3 {
    (point - center) / radius
}
