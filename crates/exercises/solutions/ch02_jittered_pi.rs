//! Reference solution of `exercises/ch02_jittered_pi.rs`, compiled only with `--features solutions`: try the
//! exercise first (`cargo exercises solution ch02_jittered_pi` shows it once your code passes).

use rand::Rng;

pub fn jittered_pi<R: Rng + ?Sized>(sqrt_n: usize, rng: &mut R) -> Option<f64> {
    if sqrt_n == 0 {
        return None;
    }
    let cell = 2.0 / sqrt_n as f64;
    let mut inside = 0usize;
    for i in 0..sqrt_n {
        for j in 0..sqrt_n {
            let x = -1.0 + cell * (i as f64 + rng.random::<f64>());
            let y = -1.0 + cell * (j as f64 + rng.random::<f64>());
            if x * x + y * y < 1.0 {
                inside += 1;
            }
        }
    }
    Some(4.0 * inside as f64 / (sqrt_n * sqrt_n) as f64)
}
