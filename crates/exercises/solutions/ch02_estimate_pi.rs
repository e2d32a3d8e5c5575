//! Reference solution of `exercises/ch02_estimate_pi.rs`, compiled only with `--features solutions`: try the
//! exercise first (`cargo exercises solution ch02_estimate_pi` shows it once your code passes).

use rand::Rng;

pub fn estimate_pi<R: Rng + ?Sized>(n: usize, rng: &mut R) -> Option<f64> {
    if n == 0 {
        return None;
    }
    let inside = (0..n)
        .filter(|_| {
            let x = rng.random_range(-1.0..1.0);
            let y = rng.random_range(-1.0..1.0);
            x * x + y * y < 1.0
        })
        .count();
    Some(4.0 * inside as f64 / n as f64)
}
