//! Reference solution of `exercises/ch03_importance_x_sq.rs`, compiled only with `--features solutions`: try the
//! exercise first (`cargo exercises solution ch03_importance_x_sq` shows it once your code passes).

use rand::Rng;

pub fn importance_estimate<R: Rng + ?Sized>(
    n: usize,
    rng: &mut R,
    f: impl Fn(f64) -> f64,
    sample: impl Fn(f64) -> f64,
    pdf: impl Fn(f64) -> f64,
) -> Option<f64> {
    if n == 0 {
        return None;
    }
    let mut sum = 0.0;
    for _ in 0..n {
        let x = sample(rng.random());
        let p = pdf(x);
        if p > 0.0 {
            sum += f(x) / p;
        }
    }
    Some(sum / n as f64)
}
