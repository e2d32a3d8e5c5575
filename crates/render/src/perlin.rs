//! Perlin noise with random gradient vectors and Hermite-smoothed trilinear interpolation, and
//! turbulence (a sum of octaves), as book 2 builds them.

use crate::vec::{Point3, Vec3, floor_i64};
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;

const POINT_COUNT: usize = 256;

/// Gradient noise on the integer lattice, hashed through three permutations.
#[derive(Clone, Debug)]
pub struct Perlin {
    gradients: [Vec3; POINT_COUNT],
    perm_x: [u8; POINT_COUNT],
    perm_y: [u8; POINT_COUNT],
    perm_z: [u8; POINT_COUNT],
}

impl Perlin {
    /// A noise table drawn from a fixed seed.
    pub fn new(seed: u64) -> Self {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
        let mut gradients = [Vec3::ZERO; POINT_COUNT];
        for g in &mut gradients {
            *g = loop {
                let v = Vec3::new(
                    rng.random_range(-1.0..1.0),
                    rng.random_range(-1.0..1.0),
                    rng.random_range(-1.0..1.0),
                );
                if v.length_squared() > 1e-6 {
                    break v.normalize();
                }
            };
        }
        let mut perm = || {
            let mut p = [0u8; POINT_COUNT];
            for (i, x) in p.iter_mut().enumerate() {
                *x = i as u8;
            }
            for i in (1..POINT_COUNT).rev() {
                let target = rng.random_range(0..=i);
                p.swap(i, target);
            }
            p
        };
        let perm_x = perm();
        let perm_y = perm();
        let perm_z = perm();
        Perlin {
            gradients,
            perm_x,
            perm_y,
            perm_z,
        }
    }

    /// Noise in about [-1, 1] at `p`.
    pub fn noise(&self, p: Point3) -> f64 {
        let (i, j, k) = (floor_i64(p.x), floor_i64(p.y), floor_i64(p.z));
        let (u, v, w) = (p.x - i as f64, p.y - j as f64, p.z - k as f64);
        let uu = u * u * (3.0 - 2.0 * u);
        let vv = v * v * (3.0 - 2.0 * v);
        let ww = w * w * (3.0 - 2.0 * w);
        let mut acc = 0.0;
        for di in 0..2i64 {
            for dj in 0..2i64 {
                for dk in 0..2i64 {
                    let idx = self.perm_x[((i + di) & 255) as usize]
                        ^ self.perm_y[((j + dj) & 255) as usize]
                        ^ self.perm_z[((k + dk) & 255) as usize];
                    let g = self.gradients[idx as usize];
                    let weight = Vec3::new(u - di as f64, v - dj as f64, w - dk as f64);
                    let (fi, fj, fk) = (di as f64, dj as f64, dk as f64);
                    acc += (fi * uu + (1.0 - fi) * (1.0 - uu))
                        * (fj * vv + (1.0 - fj) * (1.0 - vv))
                        * (fk * ww + (1.0 - fk) * (1.0 - ww))
                        * g.dot(weight);
                }
            }
        }
        acc
    }

    /// Turbulence: `|sum_i 2^-i noise(2^i p)|` over `depth` octaves.
    pub fn turbulence(&self, p: Point3, depth: u32) -> f64 {
        let mut acc = 0.0;
        let mut q = p;
        let mut weight = 1.0;
        for _ in 0..depth {
            acc += weight * self.noise(q);
            weight *= 0.5;
            q *= 2.0;
        }
        acc.abs()
    }
}
