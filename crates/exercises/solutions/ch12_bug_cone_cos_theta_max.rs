//! Reference solution of `exercises/ch12_bug_cone_cos_theta_max.rs`, compiled only with `--features solutions`: try the
//! exercise first (`cargo exercises solution ch12_bug_cone_cos_theta_max` shows it once your code passes).

/// The bug: 1 - r^2/d^2 is cos^2 theta_max (sin theta_max = r/d), not its cosine.
pub fn cos_theta_max(radius: f64, distance: f64) -> f64 {
    (1.0 - radius * radius / (distance * distance))
        .max(0.0)
        .sqrt()
}
