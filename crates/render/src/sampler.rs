//! Per-sample random numbers and sub-pixel positions that are *prefix-stable*: sample `k` of pixel `p`
//! depends only on `(seed, p, k)`, never on how many samples the render takes in all. That is what lets
//! progressive passes, a time budget, resuming and merging sample ranges give the same image.
//!
//! - Random numbers: a Xoshiro256++ generator (a stream documented as portable) seeded per
//!   `(seed, pixel, k)` through SplitMix64-style mixing.
//! - Sub-pixel positions: the first two dimensions of the Sobol sequence (a (0,2)-sequence: every
//!   power-of-two prefix is stratified), Owen-scrambled per pixel by hashing, as in Burley,
//!   "Practical Hash-based Owen Scrambling" (JCGT 2020), built on Laine and Karras' permutation.

use rand::{RngCore, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;

pub use rtl_mc::sequence::mix64;
use rtl_mc::sequence::{
    DIRECTIONS_1, byte_product, byte_tables, laine_karras, owen_scramble, sobol_bits,
};

/// A well-mixed 64-bit key for `(seed, pixel, k)`.
#[inline]
pub fn sample_key(seed: u64, pixel: u64, k: u64) -> u64 {
    let h = mix64(seed ^ 0x9e37_79b9_7f4a_7c15);
    let h = mix64(h ^ pixel.wrapping_mul(0xd1b5_4a32_d192_ed03));
    mix64(h ^ k.wrapping_mul(0x8cb9_2ba7_2f3d_8dd7))
}

/// Sobol dimension 1 of a bit-reversed index, bit-reversed: `reverse(sobol1(reverse(r)))` is again a
/// product over GF(2), whose column `j` is the reversed column `31 - j` of dimension 1's matrix.
const SOBOL1_REVERSED_BYTES: [[u32; 256]; 4] = byte_tables(&{
    let mut c = [0u32; 32];
    let mut j = 0;
    while j < 32 {
        c[j] = DIRECTIONS_1[31 - j].reverse_bits();
        j += 1;
    }
    c
});

/// `reverse(sobol1(reverse(r)))` by four table lookups.
#[inline]
fn sobol1_reversed(r: u32) -> u32 {
    byte_product(&SOBOL1_REVERSED_BYTES, r)
}

/// The sub-pixel position of sample `k` of a pixel, in `[0, 1)^2`: point `k` of the pixel's own
/// Owen-scrambled Sobol (0,2)-sequence, whose scramble is keyed by `pixel_key` (a hash of seed and
/// pixel). Every prefix of 2^m samples puts one point in each of the 2^m elementary intervals of any
/// shape; a prefix that is not a power of two is still well spread.
#[inline]
pub fn pixel_position(pixel_key: u64, k: u64) -> (f64, f64) {
    let i = k as u32;
    let s0 = pixel_key as u32;
    let s1 = (pixel_key >> 32) as u32;
    let x = owen_scramble(sobol_bits(i, 0), s0);
    let y = owen_scramble(sobol_bits(i, 1), s1);
    const SCALE: f64 = 1.0 / 4_294_967_296.0;
    // Add half an ulp of the 32-bit grid so positions are centred in their cells and never exactly 0.
    ((x as f64 + 0.5) * SCALE, (y as f64 + 0.5) * SCALE)
}

// ANCHOR: padded_sobol
/// Two-dimensional point `k` of the integrator's dimension pair `dim` for one pixel, each coordinate as
/// 64 random-looking bits whose top 32 are the Owen-scrambled Sobol value (so `random::<f64>()` of them
/// lies in the point's 2^-32 cell): pbrt-v4's *padded* Sobol sampler. Every pair is Sobol dimensions 0
/// and 1 (a (0,2)-sequence) with its own scramble, and the sample index is shuffled per pair by a nested
/// uniform scramble of its bits (Burley 2020), which maps the first 2^m indices onto one aligned block
/// of 2^m, itself a (0,m,2)-net: so every power-of-two prefix stays stratified, pairs are decorrelated,
/// and point `k` depends only on `(pixel_key, dim, k)` (prefix-stable).
#[inline]
pub fn padded_sobol_2d(pixel_key: u64, dim: u32, k: u64) -> [u64; 2] {
    let h = mix64(pixel_key ^ (dim as u64 + 1).wrapping_mul(0xa076_1d64_78bd_642f));
    // The shuffled index `i = owen_scramble(k)`, kept bit-reversed as `r` (reversing is the costly part
    // of a scramble): `owen_scramble(sobol_bits(i, 0)) = reverse(laine_karras(i))`, and Sobol dimension 1 is
    // read from `r` directly by a table of reversed columns.
    // The final reversals of both coordinates are one 64-bit reversal: `x` in the high half, `y` low.
    let r = laine_karras((k as u32).reverse_bits(), (h >> 32) as u32);
    let x = laine_karras(r.reverse_bits(), h as u32);
    let y = laine_karras(sobol1_reversed(r), (h >> 16) as u32 ^ 0x5bd1_e995);
    let xy = (((y as u64) << 32) | x as u64).reverse_bits();
    let low = h.rotate_left(23) ^ k.wrapping_mul(0x9e37_79b9_7f4a_7c15);
    [
        (xy & 0xffff_ffff_0000_0000) | (low & 0xffff_ffff),
        (xy << 32) | (low >> 32),
    ]
}
// ANCHOR_END: padded_sobol

/// Where the integrator's low-discrepancy dimensions come from for the current sample.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Lds {
    /// Off: every dimension is drawn from the sample's random number generator.
    pub on: bool,
    /// The pixel's scramble key.
    pub key: u64,
    /// The sample's index `k` in its pixel.
    pub index: u64,
}

/// A random number generator that first hands out a few preset 64-bit values (low-discrepancy
/// coordinates, say) and then falls back to the sample's generator: a way to feed chosen numbers to a
/// `Pdf::generate` that takes any `Rng`.
pub struct Preset<'a> {
    values: [u64; 3],
    next: usize,
    len: usize,
    rng: &'a mut SampleRng,
}

impl<'a> Preset<'a> {
    /// Hands out `values` in order, then numbers from `rng`.
    #[inline]
    pub fn new(values: &[u64], rng: &'a mut SampleRng) -> Self {
        let mut v = [0u64; 3];
        let len = values.len().min(3);
        v[..len].copy_from_slice(&values[..len]);
        Preset {
            values: v,
            next: 0,
            len,
            rng,
        }
    }
}

impl RngCore for Preset<'_> {
    #[inline]
    fn next_u32(&mut self) -> u32 {
        (self.next_u64() >> 32) as u32
    }
    #[inline]
    fn next_u64(&mut self) -> u64 {
        if self.next < self.len {
            self.next += 1;
            self.values[self.next - 1]
        } else {
            self.rng.next_u64()
        }
    }
    fn fill_bytes(&mut self, dst: &mut [u8]) {
        self.rng.fill_bytes(dst)
    }
}

/// Counters of what a render did, kept per thread (plain adds, no atomics) and summed at the end.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Stats {
    /// Samples (camera paths) traced.
    pub samples: u64,
    /// Rays intersected with the scene (camera rays, scattered rays, shadow rays).
    pub rays: u64,
    /// 64-bit random numbers drawn.
    pub random_numbers: u64,
    /// Points sampled on the lens (thin-lens defocus).
    pub lens_samples: u64,
    /// Times sampled in the shutter interval (motion blur).
    pub time_samples: u64,
    /// Evaluations of a constant medium (a ray tested against a medium's boundary).
    pub medium_evaluations: u64,
    /// Evaluations of a non-constant texture.
    pub texture_evaluations: u64,
    /// Samples whose value was NaN or infinite, dropped from their pixel.
    pub non_finite: u64,
}

impl std::ops::Add for Stats {
    type Output = Stats;
    fn add(mut self, o: Stats) -> Stats {
        self.samples += o.samples;
        self.rays += o.rays;
        self.random_numbers += o.random_numbers;
        self.lens_samples += o.lens_samples;
        self.time_samples += o.time_samples;
        self.medium_evaluations += o.medium_evaluations;
        self.texture_evaluations += o.texture_evaluations;
        self.non_finite += o.non_finite;
        self
    }
}

/// The random number generator one sample uses, counting what it hands out.
#[derive(Clone, Debug)]
pub struct SampleRng {
    rng: Xoshiro256PlusPlus,
    pub drawn: u64,
}

impl SampleRng {
    /// The generator of sample `k` of `pixel` under `seed`.
    pub fn for_sample(seed: u64, pixel: u64, k: u64) -> Self {
        SampleRng {
            rng: Xoshiro256PlusPlus::seed_from_u64(sample_key(seed, pixel, k)),
            drawn: 0,
        }
    }
}

impl RngCore for SampleRng {
    #[inline]
    fn next_u32(&mut self) -> u32 {
        self.drawn += 1;
        self.rng.next_u32()
    }
    #[inline]
    fn next_u64(&mut self) -> u64 {
        self.drawn += 1;
        self.rng.next_u64()
    }
    fn fill_bytes(&mut self, dst: &mut [u8]) {
        self.drawn += 1;
        self.rng.fill_bytes(dst)
    }
}

/// What one path needs while it is traced: its random numbers and the thread's counters.
pub struct Ctx {
    pub rng: SampleRng,
    pub stats: Stats,
    /// Low-discrepancy dimensions of the current sample (used by the `mis` strategy).
    pub lds: Lds,
}

impl Ctx {
    pub fn new() -> Self {
        Ctx {
            rng: SampleRng::for_sample(0, 0, 0),
            stats: Stats::default(),
            lds: Lds::default(),
        }
    }

    /// A uniform number in [0, 1).
    #[inline]
    pub fn uniform(&mut self) -> f64 {
        rand::Rng::random::<f64>(&mut self.rng)
    }

    /// Two coordinates (as 64-bit values for [`Preset`]) of dimension pair `dim`: low-discrepancy if
    /// `lds.on`, else two draws of the generator.
    #[inline]
    pub fn sample_2d(&mut self, dim: u32) -> [u64; 2] {
        if self.lds.on {
            self.stats.random_numbers += 2;
            padded_sobol_2d(self.lds.key, dim, self.lds.index)
        } else {
            [self.rng.next_u64(), self.rng.next_u64()]
        }
    }
}

impl Default for Ctx {
    fn default() -> Self {
        Self::new()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pixel_positions_are_stratified_at_every_power_of_two() {
        for key in [1u64, 0xdead_beef_1234_5678, 42] {
            for m in 0..=8u32 {
                let n = 1u64 << m;
                // (0,2)-sequence: for every split 2^a x 2^b with a + b = m, one point per cell.
                for a in 0..=m {
                    let (nx, ny) = (1u64 << a, 1u64 << (m - a));
                    let mut seen = vec![false; n as usize];
                    for k in 0..n {
                        let (x, y) = pixel_position(key, k);
                        assert!((0.0..1.0).contains(&x) && (0.0..1.0).contains(&y));
                        let cell = (x * nx as f64) as u64 * ny + (y * ny as f64) as u64;
                        assert!(!seen[cell as usize], "two points in one cell: m {m}, a {a}");
                        seen[cell as usize] = true;
                    }
                }
            }
        }
    }

    #[test]
    fn padded_sobol_pairs_are_stratified_at_every_power_of_two() {
        for (key, dim) in [(1u64, 0u32), (0xdead_beef, 3), (42, 17)] {
            for m in 0..=8u32 {
                let n = 1u64 << m;
                for a in 0..=m {
                    let (nx, ny) = (1u64 << a, 1u64 << (m - a));
                    let mut seen = vec![false; n as usize];
                    for k in 0..n {
                        let [x, y] = padded_sobol_2d(key, dim, k);
                        let (x, y) = (
                            (x >> 32) as f64 / 4294967296.0,
                            (y >> 32) as f64 / 4294967296.0,
                        );
                        let cell = (x * nx as f64) as u64 * ny + (y * ny as f64) as u64;
                        assert!(!seen[cell as usize], "two points in one cell: m {m}, a {a}");
                        seen[cell as usize] = true;
                    }
                }
            }
        }
        // pairs differ from each other
        assert_ne!(padded_sobol_2d(1, 0, 5), padded_sobol_2d(1, 1, 5));
    }

    /// The padded Sobol point as first written: three plain scrambles.
    fn padded_sobol_2d_reference(pixel_key: u64, dim: u32, k: u64) -> [u64; 2] {
        let h = mix64(pixel_key ^ (dim as u64 + 1).wrapping_mul(0xa076_1d64_78bd_642f));
        let i = owen_scramble(k as u32, (h >> 32) as u32);
        let x = owen_scramble(sobol_bits(i, 0), h as u32);
        let y = owen_scramble(sobol_bits(i, 1), (h >> 16) as u32 ^ 0x5bd1_e995);
        let low = h.rotate_left(23) ^ k.wrapping_mul(0x9e37_79b9_7f4a_7c15);
        [
            ((x as u64) << 32) | (low & 0xffff_ffff),
            ((y as u64) << 32) | (low >> 32),
        ]
    }

    #[test]
    fn padded_sobol_agrees_with_plain_scrambles() {
        let mut x = 1u32;
        for i in 0..20_000u32 {
            x = x.wrapping_mul(0x9e37_79b9).wrapping_add(7);
            let r = x.reverse_bits();
            assert_eq!(
                sobol1_reversed(r),
                sobol_bits(x, 1).reverse_bits(),
                "index {x}"
            );
            let (key, dim, k) = (mix64(i as u64), i % 40, (i as u64 * 7919) % 5000);
            assert_eq!(
                padded_sobol_2d(key, dim, k),
                padded_sobol_2d_reference(key, dim, k)
            );
        }
    }

    #[test]
    fn scrambles_differ_between_pixels() {
        let a = pixel_position(sample_key(1, 0, 0), 0);
        let b = pixel_position(sample_key(1, 1, 0), 0);
        assert_ne!(a, b);
    }

    #[test]
    fn the_checker_sees_an_unstratified_sequence() {
        // Deliberately wrong: a plain hash per sample is not stratified, and the check above must see it.
        let mut clash = false;
        let n = 64u64;
        let mut seen = vec![false; n as usize];
        for k in 0..n {
            let h = mix64(k + 1);
            let (x, y) = (
                (h >> 40) as f64 / (1u64 << 24) as f64,
                (h & 0xff_ffff) as f64 / (1u64 << 24) as f64,
            );
            let cell = ((x * 8.0) as u64) * 8 + (y * 8.0) as u64;
            clash |= seen[cell as usize];
            seen[cell as usize] = true;
        }
        assert!(clash);
    }
}
