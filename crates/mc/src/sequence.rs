//! The first two dimensions of the Sobol sequence, Owen-scrambled by hashing, as `f64` in `[0, 1)`.
//!
//! Sobol (1967) points are `x_i = XOR of the direction numbers v_k for every bit k set in i`. Dimension 0
//! has `v_k = 2^-(k+1)` (the van der Corput sequence: the bits of `i` reversed); dimension 1 has the
//! generating matrix of Pascal's triangle mod 2, `v_0 = 1/2`, `v_k = v_(k-1) XOR (v_(k-1) / 2)`. Together
//! they form a (0, 2)-sequence: every block of `2^m` consecutive points starting at a multiple of `2^m`
//! puts exactly one point in each elementary box `[j 2^-a, (j+1) 2^-a) x [l 2^-b, (l+1) 2^-b)` with
//! `a + b = m`.
//!
//! Owen scrambling (Owen 1995) permutes the digits of each coordinate at random, digit `k` by a
//! permutation that depends on the digits before it. That keeps the box property, makes every point
//! uniform on `[0, 1)`, and lets independent scrambles serve as independent replicates. We use the
//! hash-based nested uniform scramble of Burley, "Practical Hash-based Owen Scrambling" (JCGT 2020):
//! reverse the bits, apply his improved Laine-Karras hash (each output bit depends only on the same
//! and lower input bits), reverse back. The 32 scrambled bits are extended to the 53 of an `f64` with
//! 21 random bits hashed from the seed and the prefix: a full Owen scramble randomises every digit
//! below those that separate the points, so those bits are uniform and independent of the rest.

/// Direction numbers of dimension 1, most significant bit first: column `k` of its generator matrix.
pub const DIRECTIONS_1: [u32; 32] = {
    let mut v = [0u32; 32];
    v[0] = 1 << 31;
    let mut k = 1;
    while k < 32 {
        v[k] = v[k - 1] ^ (v[k - 1] >> 1);
        k += 1;
    }
    v
};

/// The product of a 32 x 32 matrix over GF(2), given by its `columns`, with any 32-bit vector, a byte
/// at a time: `t[b][x]` is the XOR of the columns of the bits set in `x << 8b`, so the product of `i` is
/// the XOR of four lookups, one per byte of `i` (the product is linear).
pub const fn byte_tables(columns: &[u32; 32]) -> [[u32; 256]; 4] {
    let mut t = [[0u32; 256]; 4];
    let mut b = 0;
    while b < 4 {
        let mut x = 0;
        while x < 256 {
            let mut r = 0u32;
            let mut bit = 0;
            while bit < 8 {
                if x & (1 << bit) != 0 {
                    r ^= columns[8 * b + bit];
                }
                bit += 1;
            }
            t[b][x] = r;
            x += 1;
        }
        b += 1;
    }
    t
}

/// [`byte_tables`] of dimension 1's generator matrix.
const SOBOL1_BYTES: [[u32; 256]; 4] = byte_tables(&DIRECTIONS_1);

/// The XOR of `tables[b][byte b of i]` over the four bytes of `i`: the matrix product by
/// [`byte_tables`].
#[inline]
pub fn byte_product(tables: &[[u32; 256]; 4], i: u32) -> u32 {
    tables[0][(i & 0xff) as usize]
        ^ tables[1][((i >> 8) & 0xff) as usize]
        ^ tables[2][((i >> 16) & 0xff) as usize]
        ^ tables[3][(i >> 24) as usize]
}

/// The unscrambled Sobol point `i` in dimension `dim` (0 or 1) as a 32-bit binary fraction: the XOR
/// of the direction numbers of the bits set in `i` (for dimension 1 by four table lookups).
///
/// # Panics
/// For `dim >= 2`: only two dimensions exist, and the dimension is fixed by the calling code, never
/// read from input.
#[inline]
pub fn sobol_bits(i: u32, dim: usize) -> u32 {
    match dim {
        0 => i.reverse_bits(),
        1 => byte_product(&SOBOL1_BYTES, i),
        _ => panic!("only Sobol dimensions 0 and 1 are implemented, not {dim}"),
    }
}

/// Burley's nested uniform scramble of a 32-bit binary fraction: digit `k` (from the top) is flipped
/// by a hash of `seed` and digits `0..k`, so the map is a bijection that preserves every dyadic box.
#[inline]
pub fn owen_scramble(x: u32, seed: u32) -> u32 {
    laine_karras(x.reverse_bits(), seed).reverse_bits()
}

/// Laine and Karras' hash: a permutation of 32-bit values in which each bit depends only on itself
/// and the bits below it, so applied to bit-reversed digits it is a nested uniform (Owen) scramble.
#[inline]
pub fn laine_karras(mut x: u32, seed: u32) -> u32 {
    x = x.wrapping_add(seed);
    for c in LAINE_KARRAS_MULTIPLIERS {
        x ^= x.wrapping_mul(c);
    }
    x
}

/// The multipliers of [`laine_karras`]'s four rounds `x ^= x * c` (each even, so that bit `k` of
/// the product depends only on bits below it).
pub const LAINE_KARRAS_MULTIPLIERS: [u32; 4] = [0x6c50_b47c, 0xb82f_1e52, 0xc7af_e638, 0x8d22_f6e6];

/// SplitMix64's finaliser (Steele, Lea and Flood 2014): a bijective 64-bit hash.
#[inline]
pub fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// The scramble seed of dimension `dim` for the sequence seed `seed`.
#[inline]
fn dimension_seed(seed: u64, dim: usize) -> u64 {
    mix64(seed ^ mix64(dim as u64 + 1))
}

/// Owen-scrambles the 32-bit Sobol coordinate `bits` and extends it to an `f64` in `[0, 1)` with 21
/// random low bits.
#[inline]
fn scrambled_unit(bits: u32, dim_seed: u64) -> f64 {
    let high = owen_scramble(bits, dim_seed as u32);
    let low = mix64(dim_seed ^ u64::from(high)) >> 43; // 21 bits
    ((u64::from(high) << 21) | low) as f64 * (1.0 / (1u64 << 53) as f64)
}

// ANCHOR: scrambled_sobol
/// Point `i` of an Owen-scrambled Sobol sequence in dimension `dim` (0 or 1), as an `f64` in `[0, 1)`.
/// Each `seed` gives an independent scramble; the two dimensions of one seed are scrambled
/// independently of each other.
///
/// ```
/// use rtl_mc::sequence::scrambled_sobol;
/// // The first 4 points put exactly one point in each quarter of [0, 1).
/// let mut quarters: Vec<usize> = (0..4).map(|i| (scrambled_sobol(i, 0, 7) * 4.0) as usize).collect();
/// quarters.sort();
/// assert_eq!(quarters, [0, 1, 2, 3]);
/// ```
#[inline]
pub fn scrambled_sobol(i: u32, dim: usize, seed: u64) -> f64 {
    scrambled_unit(sobol_bits(i, dim), dimension_seed(seed, dim))
}
// ANCHOR_END: scrambled_sobol

/// The 2D scrambled Sobol points of one seed in Gray-code order (Antonov and Saleev 1979): point `k` is
/// Sobol point `k ^ (k >> 1)`, so each step XORs in a single direction number instead of one per set
/// bit. The first `2^m` points are the same set as in natural order, `2^32` points at most.
///
/// ```
/// use rtl_mc::sequence::ScrambledSobol2;
/// let points: Vec<[f64; 2]> = ScrambledSobol2::new(5).take(16).collect();
/// assert!(points.iter().all(|p| (0.0..1.0).contains(&p[0]) && (0.0..1.0).contains(&p[1])));
/// ```
#[derive(Debug, Clone)]
pub struct ScrambledSobol2 {
    seeds: [u64; 2],
    next: u64,
    dim1: u32,
}

impl ScrambledSobol2 {
    /// The sequence scrambled by `seed`.
    pub fn new(seed: u64) -> Self {
        Self {
            seeds: [dimension_seed(seed, 0), dimension_seed(seed, 1)],
            next: 0,
            dim1: 0,
        }
    }
}

impl Iterator for ScrambledSobol2 {
    type Item = [f64; 2];

    #[inline]
    fn next(&mut self) -> Option<[f64; 2]> {
        let k = self.next;
        if k >= 1 << 32 {
            return None;
        }
        if k > 0 {
            // gray(k) = gray(k - 1) ^ 2^ctz(k)
            self.dim1 ^= DIRECTIONS_1[k.trailing_zeros() as usize];
        }
        self.next += 1;
        let gray = (k ^ (k >> 1)) as u32;
        Some([
            scrambled_unit(gray.reverse_bits(), self.seeds[0]),
            scrambled_unit(self.dim1, self.seeds[1]),
        ])
    }
}
