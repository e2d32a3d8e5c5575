//! Reference solution of `exercises/ch03_inverse_x_sq.rs`, compiled only with `--features solutions`: try the
//! exercise first (`cargo exercises solution ch03_inverse_x_sq` shows it once your code passes).

/// P(x) = x^2 / 4 on [0, 2], so x = 2 sqrt(u).
pub fn sample_linear(u: f64) -> f64 {
    2.0 * u.sqrt()
}

/// P(x) = x^3 / 8 on [0, 2], so x = 2 cbrt(u).
pub fn sample_quadratic(u: f64) -> f64 {
    2.0 * u.cbrt()
}
