//! Per-sample random numbers and sub-pixel positions that are *prefix-stable*: sample `k` of pixel `p`
//! depends only on `(seed, p, k)`, never on how many samples the render takes in all. That is what lets
//! progressive passes, a time budget, resuming and merging sample ranges give the same image.
//!
//! - Random numbers: a Xoshiro256++ generator (a stream documented as portable) seeded per
//!   `(seed, pixel, k)` through SplitMix64-style mixing.
//! - Sub-pixel positions: the first two dimensions of the Sobol sequence (a (0,2)-sequence: every
//!   power-of-two prefix is stratified), Owen-scrambled per pixel by hashing, as in Burley,
//!   "Practical Hash-based Owen Scrambling" (JCGT 2020), built on Laine and Karras' permutation.
//! - Every other dimension of a sample ([`Dimension`]: lens, time, and per bounce the light, the
//!   material and Russian roulette) from the [`Sampler`]: padded Owen-scrambled Sobol pairs when
//!   low-discrepancy sampling is on, the sample's generator otherwise.
//!
//! The sample index is 64-bit throughout. A 32-bit Sobol (0,2)-sequence has 2^32 points; sample
//! `k >= 2^32` takes point `k mod 2^32` of a sequence scrambled afresh for block `k >> 32` (its key
//! hashed with the block number), so no sample repeats another and every block of 2^32 is again a
//! stratified (0,2)-sequence. Indices below 2^32 use the key unchanged.

use crate::media_crossed::{MediaCrossed, MediumMode};
use glam::DVec2;
use rand::RngCore;

pub use rtl_mc::sequence::mix64;
use rtl_mc::sequence::{DIRECTIONS_1, byte_product, byte_tables, laine_karras};

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
    let pixel_key = block_key(pixel_key, k);
    let i = k as u32;
    let s0 = pixel_key as u32;
    let s1 = (pixel_key >> 32) as u32;
    // `owen_scramble(v, s) = reverse(laine_karras(reverse(v), s))`. Dimension 0 is `reverse(i)`, so its
    // scramble is `reverse(laine_karras(i, s0))`; dimension 1 is read reversed from the table of
    // reversed columns. The two final reversals are one 64-bit reversal (`x` high, `y` low).
    let x = laine_karras(i, s0);
    let y = laine_karras(sobol1_reversed(i.reverse_bits()), s1);
    let xy = (((y as u64) << 32) | x as u64).reverse_bits();
    let (x, y) = ((xy >> 32) as u32, xy as u32);
    const SCALE: f64 = 1.0 / 4_294_967_296.0;
    // Add half an ulp of the 32-bit grid so positions are centred in their cells and never exactly 0.
    ((x as f64 + 0.5) * SCALE, (y as f64 + 0.5) * SCALE)
}

/// The scramble key for the block of 2^32 samples that `k` lies in: `key` itself for the first block.
#[inline]
fn block_key(key: u64, k: u64) -> u64 {
    match k >> 32 {
        0 => key,
        block => mix64(key ^ block.wrapping_mul(0xc2b2_ae3d_27d4_eb4f)),
    }
}

// ANCHOR: padded_sobol
/// Two-dimensional point `k` of the integrator's dimension pair `dim` for one pixel, each coordinate as
/// 64 random-looking bits whose top 32 are the Owen-scrambled Sobol value (so `random::<f64>()` of them
/// lies in the point's 2^-32 cell), after pbrt-v4's *padded* Sobol sampler. Every pair is Sobol
/// dimensions 0 and 1 (a (0,2)-sequence) with its own scramble, and the sample index is shuffled per
/// pair (pbrt-v4 permutes the pixel's indices) by a nested uniform scramble of its bits (Burley 2020),
/// which maps the first 2^m indices onto one aligned block
/// of 2^m, itself a (0,m,2)-net: so every power-of-two prefix stays stratified, pairs are decorrelated,
/// and point `k` depends only on `(pixel_key, dim, k)` (prefix-stable).
#[inline]
pub fn padded_sobol_2d(pixel_key: u64, dim: u32, k: u64) -> [u64; 2] {
    PaddedIndex::new(pixel_key, k).point_2d(dim)
}

/// What the padded Sobol points of one sample share, whatever the pair: the scramble key of the
/// sample's block of 2^32, the index `k` bit-reversed (the shuffle works on reversed digits), and
/// `k`'s part of the low bits. Made once per sample, so a pair costs only its own scrambles.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PaddedIndex {
    /// [`block_key`] of the pixel's key and `k`.
    key: u64,
    /// `(k mod 2^32)` with its bits reversed.
    reversed: u32,
    /// `k * 0x9e37_79b9_7f4a_7c15` (mod 2^64), mixed into the low bits.
    low: u64,
}

impl PaddedIndex {
    /// Sample `k` of the pixel whose scramble key is `pixel_key`.
    #[inline]
    pub fn new(pixel_key: u64, k: u64) -> PaddedIndex {
        PaddedIndex {
            key: block_key(pixel_key, k),
            reversed: (k as u32).reverse_bits(),
            low: k.wrapping_mul(0x9e37_79b9_7f4a_7c15),
        }
    }

    /// The pair's own scramble: 64 bits hashed from the block key and `dim`.
    #[inline]
    fn pair_hash(&self, dim: u32) -> u64 {
        mix64(self.key ^ (dim as u64 + 1).wrapping_mul(0xa076_1d64_78bd_642f))
    }

    /// [`padded_sobol_2d`] of this sample for the pair `dim`.
    #[inline]
    pub fn point_2d(&self, dim: u32) -> [u64; 2] {
        let h = self.pair_hash(dim);
        // The shuffled index `i = owen_scramble(k)`, kept bit-reversed as `r` (reversing is the costly
        // part of a scramble): `owen_scramble(sobol_bits(i, 0)) = reverse(laine_karras(i))`, and Sobol
        // dimension 1 is read from `r` directly by a table of reversed columns. The final reversals of
        // both coordinates are one 64-bit reversal: `x` in the high half, `y` low.
        let r = laine_karras(self.reversed, (h >> 32) as u32);
        let x = laine_karras(r.reverse_bits(), h as u32);
        let y = laine_karras(sobol1_reversed(r), (h >> 16) as u32 ^ 0x5bd1_e995);
        let xy = (((y as u64) << 32) | x as u64).reverse_bits();
        let low = h.rotate_left(23) ^ self.low;
        [
            (xy & 0xffff_ffff_0000_0000) | (low & 0xffff_ffff),
            (xy << 32) | (low >> 32),
        ]
    }

    /// The first coordinate of [`PaddedIndex::point_2d`] alone (a 1D dimension), without the second's
    /// work.
    #[inline]
    pub fn point_1d(&self, dim: u32) -> u64 {
        let h = self.pair_hash(dim);
        let r = laine_karras(self.reversed, (h >> 32) as u32);
        let x = laine_karras(r.reverse_bits(), h as u32).reverse_bits();
        let low = h.rotate_left(23) ^ self.low;
        ((x as u64) << 32) | (low & 0xffff_ffff)
    }
}
// ANCHOR_END: padded_sobol

/// [`PaddedIndex::point_2d`] of eight samples at once (`indices[i]`, pair `dims[i]`), as uniform
/// numbers in `[0, 1)` ([`Ctx::sample_2d`]'s): each pair's hash and the assembly of its 64 bits lane
/// by lane, the three Laine-Karras hashes and the bit reversals, which are most of the work, in the
/// lanes of AVX2 registers. Integer arithmetic, so the numbers are the same bit for bit.
///
/// # Safety
/// Only where the processor has AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
pub unsafe fn points_2d_avx2(
    indices: &[PaddedIndex; 8],
    dims: &[u32; 8],
) -> (crate::lanes::F64x8, crate::lanes::F64x8) {
    use std::arch::x86_64::*;
    let (mut hashes, mut reversed) = ([0u64; 8], [0u32; 8]);
    let (mut seed_r, mut seed_x, mut seed_y) = ([0u32; 8], [0u32; 8], [0u32; 8]);
    for i in 0..8 {
        let h = indices[i].pair_hash(dims[i]);
        hashes[i] = h;
        reversed[i] = indices[i].reversed;
        seed_r[i] = (h >> 32) as u32;
        seed_x[i] = h as u32;
        seed_y[i] = (h >> 16) as u32 ^ 0x5bd1_e995;
    }
    let load = |a: &[u32; 8]| {
        // SAFETY: 32 bytes read from an array of 32 bytes (unaligned load).
        unsafe { _mm256_loadu_si256(a.as_ptr().cast()) }
    };
    let store = |v: __m256i| {
        let mut a = [0u32; 8];
        // SAFETY: 32 bytes written to an array of 32 bytes (unaligned store).
        unsafe { _mm256_storeu_si256(a.as_mut_ptr().cast(), v) };
        a
    };
    // `r = laine_karras(reversed, h >> 32)`, then `x` from `reverse(r)` and `y` from Sobol
    // dimension 1 of `r` (four table lookups, lane by lane)
    let r = laine_karras8(load(&reversed), load(&seed_r));
    let x = laine_karras8(reverse_bits8(r), load(&seed_x));
    let r = store(r);
    let mut sobol1 = [0u32; 8];
    for i in 0..8 {
        sobol1[i] = sobol1_reversed(r[i]);
    }
    let y = laine_karras8(load(&sobol1), load(&seed_y));
    let (x, y) = (store(reverse_bits8(x)), store(reverse_bits8(y)));
    let (mut ux, mut uy) = (crate::lanes::F64x8::ZERO, crate::lanes::F64x8::ZERO);
    for i in 0..8 {
        let low = hashes[i].rotate_left(23) ^ indices[i].low;
        ux.0[i] = unit(((x[i] as u64) << 32) | (low & 0xffff_ffff));
        uy.0[i] = unit(((y[i] as u64) << 32) | (low >> 32));
    }
    (ux, uy)
}

/// [`laine_karras`] of eight 32-bit lanes with their own seeds (wrapping adds and multiplies, as
/// the scalar hash).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
fn laine_karras8(
    x: std::arch::x86_64::__m256i,
    seed: std::arch::x86_64::__m256i,
) -> std::arch::x86_64::__m256i {
    use std::arch::x86_64::*;
    let mut x = _mm256_add_epi32(x, seed);
    for c in rtl_mc::sequence::LAINE_KARRAS_MULTIPLIERS {
        x = _mm256_xor_si256(x, _mm256_mullo_epi32(x, _mm256_set1_epi32(c as i32)));
    }
    x
}

/// `u32::reverse_bits` of eight lanes: the bytes of each lane reversed, then the bits of each byte
/// by two nibble tables.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
fn reverse_bits8(v: std::arch::x86_64::__m256i) -> std::arch::x86_64::__m256i {
    use std::arch::x86_64::*;
    /// A nibble reversed: `n = b3 b2 b1 b0` to `b0 b1 b2 b3`.
    const REV4: [u8; 16] = [0, 8, 4, 12, 2, 10, 6, 14, 1, 9, 5, 13, 3, 11, 7, 15];
    let table = |shift: u32| {
        let mut t = [0u8; 32];
        for (i, b) in t.iter_mut().enumerate() {
            *b = REV4[i % 16] << shift;
        }
        // SAFETY: 32 bytes read from an array of 32 bytes (unaligned load).
        unsafe { _mm256_loadu_si256(t.as_ptr().cast()) }
    };
    let bytes = _mm256_setr_epi8(
        3, 2, 1, 0, 7, 6, 5, 4, 11, 10, 9, 8, 15, 14, 13, 12, 3, 2, 1, 0, 7, 6, 5, 4, 11, 10, 9, 8,
        15, 14, 13, 12,
    );
    let v = _mm256_shuffle_epi8(v, bytes);
    let nibble = _mm256_set1_epi8(0x0f);
    let low = _mm256_and_si256(v, nibble);
    let high = _mm256_and_si256(_mm256_srli_epi16(v, 4), nibble);
    _mm256_or_si256(
        _mm256_shuffle_epi8(table(4), low),
        _mm256_shuffle_epi8(table(0), high),
    )
}

/// The first coordinate of [`padded_sobol_2d`] alone (a 1D dimension), without the second's work.
#[inline]
pub fn padded_sobol_1d(pixel_key: u64, dim: u32, k: u64) -> u64 {
    PaddedIndex::new(pixel_key, k).point_1d(dim)
}

// ANCHOR: dimensions
/// The dimensions of one sample after the pixel position, in the order a path uses them. Each is a
/// 2D pair (a 1D dimension takes the first coordinate of its pair), so the layout is fixed: pair
/// `Dimension::pair` whatever happened before, and a dimension a path does not need costs nothing.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dimension {
    /// The point on the lens (2D).
    Lens,
    /// The time in the shutter interval (1D).
    Time,
    /// At bounce `b`: the light choice and the light direction (2D; the choice uses the first
    /// coordinate and hands its rest on).
    Light(u32),
    /// At bounce `b`: the material's lobe and direction (2D: a mixture's choice, a Lambertian
    /// direction, a metal's fuzz, a dielectric's reflect-or-refract coin).
    Material(u32),
    /// At bounce `b`: Russian roulette (1D).
    Roulette(u32),
    /// At bounce `b`: where a forced scattering point lies along the ray (1D). It shares
    /// [`Dimension::Roulette`]'s pair: paths are forced to scatter only at bounces before
    /// [`ROULETTE_AFTER`](crate::integrator::ROULETTE_AFTER), where no roulette is played.
    Scatter(u32),
}

impl Dimension {
    /// Pairs per bounce.
    pub const PER_BOUNCE: u32 = 3;

    /// The pair index of the padded Sobol sampler: 0 lens, 1 time, then `2 + 3 b` light,
    /// `3 + 3 b` material, `4 + 3 b` roulette (or forced scattering).
    #[inline]
    pub const fn pair(self) -> u32 {
        match self {
            Dimension::Lens => 0,
            Dimension::Time => 1,
            Dimension::Light(b) => 2 + Self::PER_BOUNCE * b,
            Dimension::Material(b) => 3 + Self::PER_BOUNCE * b,
            Dimension::Roulette(b) | Dimension::Scatter(b) => 4 + Self::PER_BOUNCE * b,
        }
    }
}
// ANCHOR_END: dimensions

/// Where the dimensions of the current sample come from: the one source of numbers for the camera
/// and the integrator.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Sampler {
    /// On: padded Owen-scrambled Sobol pairs; off: the sample's generator, in call order.
    low_discrepancy: bool,
    /// The pixel's scramble key.
    key: u64,
    /// The sample's index `k` in its pixel (64-bit: see the module's notes past 2^32).
    index: u64,
    /// What every pair of this sample shares, made once.
    padded: PaddedIndex,
}

impl Sampler {
    /// Sample `index` of the pixel with scramble key `key` (the padded points' shared part is made
    /// only if they are used).
    #[inline]
    pub fn new(low_discrepancy: bool, key: u64, index: u64) -> Sampler {
        Sampler {
            low_discrepancy,
            key,
            index,
            padded: if low_discrepancy {
                PaddedIndex::new(key, index)
            } else {
                PaddedIndex::default()
            },
        }
    }

    /// Whether the dimensions are padded Sobol pairs (else the sample's generator, in call order).
    pub fn low_discrepancy(&self) -> bool {
        self.low_discrepancy
    }

    /// The pixel's scramble key.
    pub fn key(&self) -> u64 {
        self.key
    }

    /// The sample's index in its pixel.
    pub fn index(&self) -> u64 {
        self.index
    }
}

/// `2^-53`: a 64-bit value's top 53 bits as a uniform number in `[0, 1)` (what `rand` does).
const F64_UNIT: f64 = 1.0 / (1u64 << 53) as f64;

#[inline]
fn unit(bits: u64) -> f64 {
    (bits >> 11) as f64 * F64_UNIT
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
    /// Manifold connections made (vertices inside a dielectric sphere connected to an emitter
    /// through its surface).
    pub manifold_connections: u64,
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
        self.manifold_connections += o.manifold_connections;
        self
    }
}

/// The random number generator one sample uses, counting what it hands out.
#[derive(Clone, Debug)]
pub struct SampleRng {
    rng: Xoshiro256pp,
    pub drawn: u64,
}

impl SampleRng {
    /// The generator of sample `k` of `pixel` under `seed`.
    #[inline]
    pub fn for_sample(seed: u64, pixel: u64, k: u64) -> Self {
        SampleRng {
            rng: Xoshiro256pp::seed_from_u64(sample_key(seed, pixel, k)),
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

/// Xoshiro256++ (Blackman and Vigna, "Scrambled Linear Pseudorandom Number Generators", 2021),
/// seeded from a `u64` by SplitMix64 as rand_xoshiro's `Xoshiro256PlusPlus::seed_from_u64` is: the
/// same stream, number for number (tested against rand_xoshiro). Written here so that seeding one per
/// sample, at every sample, is inlined into the loop that starts the sample (through the crate's
/// functions it was a call and a round trip through a seed of bytes: 3% of a `mixture` sample).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Xoshiro256pp {
    s: [u64; 4],
}

impl Xoshiro256pp {
    /// The state after four outputs of SplitMix64 from `seed` (an all-zero state, which xoshiro
    /// cannot leave, is replaced by seed 0's, as rand_xoshiro does).
    #[inline]
    pub fn seed_from_u64(seed: u64) -> Xoshiro256pp {
        let mut x = seed;
        let mut s = [0u64; 4];
        for word in &mut s {
            x = x.wrapping_add(0x9e37_79b9_7f4a_7c15);
            let mut z = x;
            z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
            *word = z ^ (z >> 31);
        }
        if s == [0; 4] {
            return Xoshiro256pp::seed_from_u64(0);
        }
        Xoshiro256pp { s }
    }
}

impl RngCore for Xoshiro256pp {
    /// The upper half of the next `u64` (the lower bits are the weaker ones).
    #[inline]
    fn next_u32(&mut self) -> u32 {
        (self.next_u64() >> 32) as u32
    }

    /// `rotl(s0 + s3, 23) + s0`, then the state's linear step.
    #[inline]
    fn next_u64(&mut self) -> u64 {
        let s = &mut self.s;
        let out = s[0].wrapping_add(s[3]).rotate_left(23).wrapping_add(s[0]);
        let t = s[1] << 17;
        s[2] ^= s[0];
        s[3] ^= s[1];
        s[1] ^= s[2];
        s[0] ^= s[3];
        s[2] ^= t;
        s[3] = s[3].rotate_left(45);
        out
    }

    fn fill_bytes(&mut self, dst: &mut [u8]) {
        rand::rand_core::impls::fill_bytes_via_next(self, dst)
    }
}

/// What one path needs while it is traced: its numbers and the thread's counters.
pub struct Ctx {
    pub rng: SampleRng,
    pub stats: Stats,
    /// The dimensions of the current sample.
    pub sampler: Sampler,
    /// The bounce the path is at (for [`Dimension`]s the material draws).
    pub bounce: u32,
    /// How a ray meets participating media (set only while a shadow ray is traced).
    pub media: MediumMode,
    /// The stretches of media a shadow ray crossed, collected by [`MediumMode::Record`].
    pub crossed: MediaCrossed,
}

impl Ctx {
    pub fn new() -> Self {
        Ctx {
            rng: SampleRng::for_sample(0, 0, 0),
            stats: Stats::default(),
            sampler: Sampler::default(),
            bounce: 0,
            media: MediumMode::Scatter,
            crossed: MediaCrossed::default(),
        }
    }

    /// A uniform number in [0, 1) from the sample's generator (what no [`Dimension`] covers: a
    /// medium's free-flight distance).
    #[inline]
    pub fn uniform(&mut self) -> f64 {
        rand::Rng::random::<f64>(&mut self.rng)
    }

    /// Two uniform numbers in `[0, 1)` for dimension `d`: the padded Sobol pair `d.pair()` if
    /// low-discrepancy sampling is on, else two draws of the generator.
    #[inline(always)]
    pub fn sample_2d(&mut self, d: Dimension) -> DVec2 {
        if self.sampler.low_discrepancy {
            self.low_discrepancy_2d(d)
        } else {
            let x = unit(self.rng.next_u64());
            DVec2::new(x, unit(self.rng.next_u64()))
        }
    }

    /// One uniform number in `[0, 1)` for dimension `d` (the first coordinate of its pair).
    #[inline(always)]
    pub fn sample_1d(&mut self, d: Dimension) -> f64 {
        if self.sampler.low_discrepancy {
            self.low_discrepancy_1d(d)
        } else {
            unit(self.rng.next_u64())
        }
    }

    /// Whether the dimensions are padded Sobol pairs ([`Ctx::defer_2d`] may be used).
    #[inline(always)]
    pub fn low_discrepancy(&self) -> bool {
        self.sampler.low_discrepancy
    }

    /// Dimension `d` of this low-discrepancy sample, counted as drawn but left to be computed
    /// with seven others ([`points_2d_avx2`]): the sample's padded index and `d`'s pair.
    #[inline(always)]
    pub fn defer_2d(&mut self, d: Dimension) -> (PaddedIndex, u32) {
        debug_assert!(self.sampler.low_discrepancy);
        self.stats.random_numbers += 2;
        (self.sampler.padded, d.pair())
    }

    /// The number [`Ctx::sample_1d`] would return for dimension `d`, without drawing it:
    /// [`Ctx::take_1d`] then draws it, if it is used. (A vertex computed in the lanes,
    /// [`crate::glass8`], learns whether it needs its number only after the lanes have used it.)
    #[inline(always)]
    pub fn peek_1d(&self, d: Dimension) -> f64 {
        if self.sampler.low_discrepancy {
            unit(self.sampler.padded.point_1d(d.pair()))
        } else {
            unit(self.rng.rng.clone().next_u64())
        }
    }

    /// Draw the number [`Ctx::peek_1d`] gave for `d`, as [`Ctx::sample_1d`] would: the same
    /// number, the same counts, the generator moved on.
    #[inline(always)]
    pub fn take_1d(&mut self, d: Dimension) {
        self.sample_1d(d);
    }

    #[inline]
    fn low_discrepancy_2d(&mut self, d: Dimension) -> DVec2 {
        self.stats.random_numbers += 2;
        let [x, y] = self.sampler.padded.point_2d(d.pair());
        DVec2::new(unit(x), unit(y))
    }

    #[inline]
    fn low_discrepancy_1d(&mut self, d: Dimension) -> f64 {
        self.stats.random_numbers += 1;
        unit(self.sampler.padded.point_1d(d.pair()))
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

    /// Whether `mine` (seeded by `seed`) gives rand_xoshiro's Xoshiro256++ stream for `seed`: its
    /// first 64 numbers, and the `f64` and `u32` forms drawn from them.
    fn same_stream<R: RngCore>(seed: u64, mut mine: R) -> bool {
        use rand::{Rng, SeedableRng};
        let mut theirs = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(seed);
        (0..64).all(|_| mine.next_u64() == theirs.next_u64())
            && mine.next_u32() == theirs.next_u32()
            && mine.random::<f64>().to_bits() == theirs.random::<f64>().to_bits()
    }

    #[test]
    fn our_xoshiro_is_rand_xoshiros_stream() {
        let mut seeds = vec![0, 1, u64::MAX, 0x9e37_79b9_7f4a_7c15];
        seeds.extend((0..1000u64).map(|i| sample_key(7, i, i * 3)));
        for seed in seeds {
            assert!(
                same_stream(seed, Xoshiro256pp::seed_from_u64(seed)),
                "{seed}"
            );
        }
        // the generator a sample uses
        assert!(same_stream(
            sample_key(3, 4, 5),
            SampleRng::for_sample(3, 4, 5)
        ));
    }

    #[test]
    fn the_stream_check_catches_a_wrong_rotation() {
        // Xoshiro256++ with the output rotated by 22, not 23.
        struct Wrong(Xoshiro256pp);
        impl RngCore for Wrong {
            fn next_u32(&mut self) -> u32 {
                (self.next_u64() >> 32) as u32
            }
            fn next_u64(&mut self) -> u64 {
                let s = self.0.s;
                let _ = self.0.next_u64();
                s[0].wrapping_add(s[3]).rotate_left(22).wrapping_add(s[0])
            }
            fn fill_bytes(&mut self, dst: &mut [u8]) {
                rand::rand_core::impls::fill_bytes_via_next(self, dst)
            }
        }
        assert!(same_stream(9, Xoshiro256pp::seed_from_u64(9)));
        assert!(!same_stream(9, Wrong(Xoshiro256pp::seed_from_u64(9))));
    }
    use rtl_mc::sequence::{owen_scramble, sobol_bits};

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

    /// The sub-pixel position as first written: two plain scrambles of the Sobol point.
    fn pixel_position_reference(pixel_key: u64, k: u64) -> (f64, f64) {
        let pixel_key = block_key(pixel_key, k);
        let i = k as u32;
        let x = owen_scramble(sobol_bits(i, 0), pixel_key as u32);
        let y = owen_scramble(sobol_bits(i, 1), (pixel_key >> 32) as u32);
        const SCALE: f64 = 1.0 / 4_294_967_296.0;
        ((x as f64 + 0.5) * SCALE, (y as f64 + 0.5) * SCALE)
    }

    #[test]
    fn pixel_positions_agree_with_plain_scrambles() {
        for i in 0..20_000u64 {
            let (key, k) = (mix64(i), i * 7919 + ((i % 3) << 32));
            assert_eq!(
                pixel_position(key, k),
                pixel_position_reference(key, k),
                "{key} {k}"
            );
        }
        // and the comparison sees a wrong variant: the coordinates' scrambles swapped
        let swapped = |key: u64, k| pixel_position_reference(key.rotate_left(32), k);
        assert!((1..100).all(|k| pixel_position(42, k) != swapped(42, k)));
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

    /// How many of `n` batches of eight random samples and pairs (`k` up to past 2^32) the lanes'
    /// points give other bits for than [`Ctx::sample_2d`] one sample at a time; `wrong` flips one
    /// pair's dimension in the lanes (an index or a scramble the check must see).
    #[cfg(target_arch = "x86_64")]
    fn points_2d_mismatches(n: usize, wrong: bool) -> usize {
        let mut bad = 0;
        let mut x = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        };
        for _ in 0..n {
            let mut ctxs: [Ctx; 8] = std::array::from_fn(|_| Ctx::new());
            let (mut indices, mut dims) = ([PaddedIndex::default(); 8], [0u32; 8]);
            let mut ds = [Dimension::Lens; 8];
            for i in 0..8 {
                let k = if next() % 4 == 0 {
                    (1 << 32) + next() % 9
                } else {
                    next() % 4096
                };
                ctxs[i].sampler = Sampler::new(true, next(), k);
                ds[i] = Dimension::Material((next() % 50) as u32);
                (indices[i], dims[i]) = ctxs[i].defer_2d(ds[i]);
                dims[i] ^= (wrong && i == 3) as u32;
            }
            // SAFETY: the caller checked that the processor has AVX2.
            let (ux, uy) = unsafe { points_2d_avx2(&indices, &dims) };
            for (i, ctx) in ctxs.iter_mut().enumerate() {
                let mut one = Ctx::new();
                one.sampler = ctx.sampler;
                let u = one.sample_2d(ds[i]);
                bad += (u.x.to_bits() != ux.0[i].to_bits() || u.y.to_bits() != uy.0[i].to_bits())
                    as usize;
                // counted as drawn, as one at a time counts them
                assert_eq!(ctx.stats.random_numbers, one.stats.random_numbers);
            }
        }
        bad
    }

    /// The lanes' padded Sobol pairs ([`points_2d_avx2`]) are the one-sample numbers bit for bit,
    /// and a lane of another pair is seen.
    #[cfg(target_arch = "x86_64")]
    #[test]
    fn eight_samples_pairs_at_once_are_the_pairs_one_at_a_time() {
        if !std::is_x86_feature_detected!("avx2") {
            return;
        }
        assert_eq!(points_2d_mismatches(2000, false), 0);
        assert_eq!(points_2d_mismatches(200, true), 200);
    }

    #[test]
    fn a_samplers_dimensions_are_the_padded_sobol_points() {
        // The sample's shared part (`PaddedIndex`) made once must give every pair exactly the points of
        // the plain formula, in every block of 2^32 samples.
        let dims = [
            Dimension::Lens,
            Dimension::Time,
            Dimension::Light(0),
            Dimension::Material(5),
            Dimension::Roulette(11),
            Dimension::Scatter(0),
        ];
        for i in 0..4000u64 {
            let (key, k) = (mix64(i), i * 7919 + ((i % 3) << 32));
            let mut ctx = Ctx::new();
            ctx.sampler = Sampler::new(true, key, k);
            for d in dims {
                let [x, y] = padded_sobol_2d_reference(block_key(key, k), d.pair(), k);
                assert_eq!(
                    ctx.sample_2d(d),
                    DVec2::new(unit(x), unit(y)),
                    "{key} {k} {d:?}"
                );
                assert_eq!(ctx.sample_1d(d), unit(x));
            }
        }
    }

    #[test]
    fn the_sampler_check_sees_an_index_left_unreversed() {
        // Deliberately wrong: the shared index not bit-reversed. The comparison above must see it.
        let mut differ = 0;
        for k in 1..200u64 {
            let right = PaddedIndex::new(42, k);
            let wrong = PaddedIndex {
                reversed: k as u32,
                ..right
            };
            differ += (wrong.point_2d(3) != padded_sobol_2d_reference(42, 3, k)) as u32;
            assert_eq!(right.point_2d(3), padded_sobol_2d_reference(42, 3, k));
        }
        assert!(differ > 190, "{differ}");
    }

    #[test]
    fn sample_indices_past_2_pow_32_do_not_repeat() {
        let key = 0x1234_5678_9abc_def0;
        for k in [0u64, 1, 77, (1 << 32) - 1] {
            let wrapped = k + (1 << 32);
            assert_ne!(
                pixel_position(key, k),
                pixel_position(key, wrapped),
                "k = {k}"
            );
            assert_ne!(padded_sobol_2d(key, 3, k), padded_sobol_2d(key, 3, wrapped));
        }
        // the second block is again a (0,2)-sequence: 16 points, one per cell of a 4 x 4 grid
        let mut seen = [false; 16];
        for k in 0..16u64 {
            let (x, y) = pixel_position(key, (1 << 32) + k);
            let cell = (x * 4.0) as usize * 4 + (y * 4.0) as usize;
            assert!(!seen[cell]);
            seen[cell] = true;
        }
    }

    #[test]
    fn padded_sobol_1d_is_the_first_coordinate_of_the_pair() {
        for i in 0..5000u64 {
            let (key, dim, k) = (mix64(i), (i % 37) as u32, i * 7919 + (i << 33));
            assert_eq!(
                padded_sobol_1d(key, dim, k),
                padded_sobol_2d(key, dim, k)[0]
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

    /// `peek_1d` gives the number `sample_1d` would, and leaves the sample as it was; `take_1d`
    /// then leaves it as `sample_1d` would have (the next numbers and the counts), in both modes.
    #[test]
    fn a_number_looked_at_then_taken_is_the_number_drawn() {
        for low_discrepancy in [false, true] {
            let ctx = |i: u64| {
                let mut c = Ctx::new();
                c.rng = SampleRng::for_sample(7, i, i * 3);
                c.sampler = Sampler::new(low_discrepancy, mix64(i), i);
                c
            };
            for i in 0..200u64 {
                let (mut drawn, mut taken) = (ctx(i), ctx(i));
                let d = Dimension::Material((i % 5) as u32);
                let peeked = taken.peek_1d(d);
                assert_eq!(taken.peek_1d(d), peeked, "looking draws nothing");
                assert_eq!(drawn.sample_1d(d), peeked);
                taken.take_1d(d);
                assert_eq!(taken.stats, drawn.stats);
                assert_eq!(taken.rng.drawn, drawn.rng.drawn);
                let next = Dimension::Material((i % 5) as u32 + 1);
                assert_eq!(taken.sample_2d(next), drawn.sample_2d(next));
            }
        }
        // (the check can fail: a look that draws moves the independent stream on)
        let (mut a, mut b) = (Ctx::new(), Ctx::new());
        a.rng = SampleRng::for_sample(7, 1, 1);
        b.rng = SampleRng::for_sample(7, 1, 1);
        let d = Dimension::Material(0);
        a.sample_1d(d);
        assert_ne!(a.peek_1d(d), b.peek_1d(d));
    }
}
