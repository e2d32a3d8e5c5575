//! Eight `f64` lanes as one number: the arithmetic that eight paths traced side by side
//! ([`crate::paths8`]) share, written once ([`Wide8`]) and compiled for two instruction sets chosen
//! at run time: AVX-512 ([`Avx512`], one register and a bit mask) and AVX2 ([`Avx2`], two registers
//! of four lanes and vector masks).
//!
//! Every operation is IEEE arithmetic lane by lane, exactly as the scalar one (no fused
//! multiply-adds), so code written with these types computes in each lane the number its scalar
//! twin computes. `min` and `max` are glam's (`a < b ? a : b`), which is what the `vminpd` and
//! `vmaxpd` instructions compute, NaN included.
//!
//! A value of these types can only be made where the processor has the instructions (by the
//! `unsafe` constructors [`Lanes::splat`] and [`Wide8::load`]): the operators on values are
//! therefore safe.

#![cfg(target_arch = "x86_64")]

use crate::lanes::F64x8;
use std::arch::x86_64::*;
use std::ops::{Add, BitAnd, BitOr, BitXor, Div, Mul, Neg, Not, Sub};

/// A set of lanes: the result of a comparison.
pub trait LaneMask:
    Copy + BitAnd<Output = Self> + BitOr<Output = Self> + BitXor<Output = Self> + Not<Output = Self>
{
    /// Bit `i` set for lane `i`.
    fn bits(self) -> u8;
    /// No lane set.
    fn is_empty(self) -> bool {
        self.bits() == 0
    }
}

/// A register's worth of `f64` lanes (eight, or four in [`Avx2Half`]): the arithmetic, the
/// comparisons and the choices lane by lane.
pub trait Lanes:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    type Mask: LaneMask;

    /// `x` in every lane.
    ///
    /// # Safety
    /// Only where the processor has the type's instructions.
    unsafe fn splat(x: f64) -> Self;
    /// The lanes whose bit is set in `bits`.
    fn mask(self, bits: u8) -> Self::Mask;

    fn sqrt(self) -> Self;
    /// The sign bit cleared.
    fn abs(self) -> Self;
    /// `self`'s magnitude with `sign`'s sign.
    fn copysign(self, sign: Self) -> Self;
    /// glam's `min`: `self < b ? self : b`; also `f64::min(self, b)` where `b` is never NaN.
    fn min(self, b: Self) -> Self;
    /// glam's `max`: `self > b ? self : b`; also `f64::max(self, b)` where `b` is never NaN.
    fn max(self, b: Self) -> Self;
    /// Rounded towards zero (exact).
    fn trunc(self) -> Self;
    fn lt(self, b: Self) -> Self::Mask;
    fn le(self, b: Self) -> Self::Mask;
    fn gt(self, b: Self) -> Self::Mask;
    fn ge(self, b: Self) -> Self::Mask;
    /// `self == b` (so `-0 == 0`; NaN equals nothing).
    fn eq(self, b: Self) -> Self::Mask;
    /// The lanes that are NaN.
    fn is_nan(self) -> Self::Mask;
    /// `b` where `m` is set, `self` elsewhere.
    fn select(self, m: Self::Mask, b: Self) -> Self;
    /// `self` where `m` is set, `+0` elsewhere.
    fn zero_unless(self, m: Self::Mask) -> Self;

    /// `+0` in every lane.
    #[inline(always)]
    fn zero_like(self) -> Self {
        self.zero_unless(self.mask(0))
    }

    /// `x` in every lane (made from a value, which proves the instructions are there).
    #[inline(always)]
    fn splat_like(self, x: f64) -> Self {
        // SAFETY: `self` exists, so the processor has the type's instructions.
        unsafe { Self::splat(x) }
    }

    /// `f64::clamp(self, lo, hi)`: `lo` below, `hi` above, NaN kept.
    #[inline(always)]
    fn clamp(self, lo: f64, hi: f64) -> Self {
        let (lo, hi) = (self.splat_like(lo), self.splat_like(hi));
        let x = self.select(self.lt(lo), lo);
        x.select(x.gt(hi), hi)
    }

    /// `f64::round`: to the nearest integer, halves away from zero (the instructions' own
    /// rounding takes halves to even, so the half is decided from the exact fraction).
    #[inline(always)]
    fn round(self) -> Self {
        let a = self.abs();
        let t = a.trunc();
        let up = (a - t).ge(self.splat_like(0.5));
        t.select(up, t + self.splat_like(1.0)).copysign(self)
    }

    /// `x > 0 && x <= f64::MAX`: rtl-pdf's `positive_finite`.
    #[inline(always)]
    fn positive_finite(self) -> Self::Mask {
        self.gt(self.zero_like()) & self.le(self.splat_like(f64::MAX))
    }
}

/// Eight `f64` lanes: [`Lanes`] loaded from and stored to eight numbers.
pub trait Wide8: Lanes {
    /// The lanes of `x`.
    ///
    /// # Safety
    /// As [`Lanes::splat`].
    unsafe fn load(x: &F64x8) -> Self;
    /// The lanes of `x`, at any alignment.
    ///
    /// # Safety
    /// As [`Lanes::splat`].
    unsafe fn load_unaligned(x: &[f64; 8]) -> Self;
    /// Eight rows of `N` numbers as `N` columns: lane `i` of column `j` is `rows[i][j]` (the rows
    /// transposed in registers, by shuffles, not by stores that a load reads back); `N` is a
    /// multiple of four.
    ///
    /// # Safety
    /// As [`Lanes::splat`].
    unsafe fn columns<const N: usize>(rows: &[&[f64; N]; 8]) -> [Self; N];
    /// The lanes, stored.
    fn store(self) -> F64x8;
}

/// Three coordinates, each eight lanes.
pub type V3<W> = [W; 3];

/// glam's `dot`: `(a.x b.x + a.y b.y) + a.z b.z`.
#[inline(always)]
pub fn dot<W: Lanes>(a: V3<W>, b: V3<W>) -> W {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// glam's `cross`.
#[inline(always)]
pub fn cross<W: Lanes>(a: V3<W>, b: V3<W>) -> V3<W> {
    [
        a[1] * b[2] - b[1] * a[2],
        a[2] * b[0] - b[2] * a[0],
        a[0] * b[1] - b[0] * a[1],
    ]
}

/// `a + b`, coordinate by coordinate.
#[inline(always)]
pub fn add3<W: Lanes>(a: V3<W>, b: V3<W>) -> V3<W> {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// `a - b`.
#[inline(always)]
pub fn sub3<W: Lanes>(a: V3<W>, b: V3<W>) -> V3<W> {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `-a`, coordinate by coordinate (each sign flipped).
#[inline(always)]
pub fn neg3<W: Lanes>(a: V3<W>) -> V3<W> {
    [-a[0], -a[1], -a[2]]
}

/// `s * a` (glam's `f64 * DVec3`, the scalar first).
#[inline(always)]
pub fn scale3<W: Lanes>(s: W, a: V3<W>) -> V3<W> {
    [s * a[0], s * a[1], s * a[2]]
}

/// glam's `max_element`: `max(x, max(y, z))`.
#[inline(always)]
pub fn max_element<W: Lanes>(a: V3<W>) -> W {
    a[0].max(a[1].max(a[2]))
}

/// `b` where `m` is set, `a` elsewhere.
#[inline(always)]
pub fn select3<W: Lanes>(a: V3<W>, m: W::Mask, b: V3<W>) -> V3<W> {
    [
        a[0].select(m, b[0]),
        a[1].select(m, b[1]),
        a[2].select(m, b[2]),
    ]
}

/// A vector in every lane.
///
/// # Safety
/// As [`Lanes::splat`].
#[inline(always)]
pub unsafe fn splat3<W: Lanes>(v: glam::DVec3) -> V3<W> {
    // SAFETY: as this function's.
    unsafe { [W::splat(v.x), W::splat(v.y), W::splat(v.z)] }
}

/// A vector in every lane (made from a value, which proves the instructions are there).
#[inline(always)]
pub fn splat3_like<W: Lanes>(like: W, v: glam::DVec3) -> V3<W> {
    [
        like.splat_like(v.x),
        like.splat_like(v.y),
        like.splat_like(v.z),
    ]
}

/// Three coordinates, stored.
#[inline(always)]
pub fn store3<W: Wide8>(v: V3<W>) -> [F64x8; 3] {
    [v[0].store(), v[1].store(), v[2].store()]
}

/// Three coordinates of eight lanes each, loaded.
///
/// # Safety
/// As [`Lanes::splat`].
#[inline(always)]
pub unsafe fn load3<W: Wide8>(v: &[F64x8; 3]) -> V3<W> {
    // SAFETY: as this function's.
    unsafe { [W::load(&v[0]), W::load(&v[1]), W::load(&v[2])] }
}

/// Numbers `at..at + 4` of four rows as four columns: lane `i` of column `j` is `rows[i][at + j]`
/// (a 4 x 4 transpose: pairs interleaved, then halves exchanged).
///
/// # Safety
/// Only where the processor has AVX; `at + 4 <= N`.
#[inline(always)]
unsafe fn columns4<const N: usize>(rows: [&[f64; N]; 4], at: usize) -> [__m256d; 4] {
    debug_assert!(at + 4 <= N);
    // SAFETY: as this function's; each load reads `rows[i][at..at + 4]`, inside the row.
    unsafe {
        // (written out: in a closure the loads would not be compiled with the caller's AVX)
        let r = [
            _mm256_loadu_pd(rows[0].as_ptr().add(at)),
            _mm256_loadu_pd(rows[1].as_ptr().add(at)),
            _mm256_loadu_pd(rows[2].as_ptr().add(at)),
            _mm256_loadu_pd(rows[3].as_ptr().add(at)),
        ];
        // (r0[0] r1[0] r0[2] r1[2]), (r0[1] r1[1] r0[3] r1[3]), and the same of r2 and r3
        let t0 = _mm256_unpacklo_pd(r[0], r[1]);
        let t1 = _mm256_unpackhi_pd(r[0], r[1]);
        let t2 = _mm256_unpacklo_pd(r[2], r[3]);
        let t3 = _mm256_unpackhi_pd(r[2], r[3]);
        [
            _mm256_permute2f128_pd::<0x20>(t0, t2),
            _mm256_permute2f128_pd::<0x20>(t1, t3),
            _mm256_permute2f128_pd::<0x31>(t0, t2),
            _mm256_permute2f128_pd::<0x31>(t1, t3),
        ]
    }
}

/// The AVX-512 form: one 512-bit register, comparisons to a bit mask.
#[derive(Clone, Copy)]
pub struct Avx512(__m512d);

/// The AVX-512 form's mask: one bit per lane.
#[derive(Clone, Copy)]
pub struct Bits8(u8);

impl LaneMask for Bits8 {
    #[inline(always)]
    fn bits(self) -> u8 {
        self.0
    }
}

impl BitAnd for Bits8 {
    type Output = Bits8;
    #[inline(always)]
    fn bitand(self, b: Bits8) -> Bits8 {
        Bits8(self.0 & b.0)
    }
}

impl BitOr for Bits8 {
    type Output = Bits8;
    #[inline(always)]
    fn bitor(self, b: Bits8) -> Bits8 {
        Bits8(self.0 | b.0)
    }
}

impl BitXor for Bits8 {
    type Output = Bits8;
    #[inline(always)]
    fn bitxor(self, b: Bits8) -> Bits8 {
        Bits8(self.0 ^ b.0)
    }
}

impl Not for Bits8 {
    type Output = Bits8;
    #[inline(always)]
    fn not(self) -> Bits8 {
        Bits8(!self.0)
    }
}

/// An AVX-512 operation on values that exist (so the processor has AVX-512F).
macro_rules! avx512 {
    ($e:expr) => {
        // SAFETY: an `Avx512` value exists only where the processor has AVX-512F, and these are
        // inlined into functions compiled with it.
        unsafe { $e }
    };
}

impl Add for Avx512 {
    type Output = Avx512;
    #[inline(always)]
    fn add(self, b: Avx512) -> Avx512 {
        avx512!(Avx512(_mm512_add_pd(self.0, b.0)))
    }
}

impl Sub for Avx512 {
    type Output = Avx512;
    #[inline(always)]
    fn sub(self, b: Avx512) -> Avx512 {
        avx512!(Avx512(_mm512_sub_pd(self.0, b.0)))
    }
}

impl Mul for Avx512 {
    type Output = Avx512;
    #[inline(always)]
    fn mul(self, b: Avx512) -> Avx512 {
        avx512!(Avx512(_mm512_mul_pd(self.0, b.0)))
    }
}

impl Div for Avx512 {
    type Output = Avx512;
    #[inline(always)]
    fn div(self, b: Avx512) -> Avx512 {
        avx512!(Avx512(_mm512_div_pd(self.0, b.0)))
    }
}

impl Neg for Avx512 {
    type Output = Avx512;
    /// The sign bit flipped (Rust's `-`, so `-0` from `0`).
    #[inline(always)]
    fn neg(self) -> Avx512 {
        avx512!(Avx512(_mm512_castsi512_pd(_mm512_xor_si512(
            _mm512_castpd_si512(self.0),
            _mm512_set1_epi64(i64::MIN)
        ))))
    }
}

impl Lanes for Avx512 {
    type Mask = Bits8;

    #[inline(always)]
    unsafe fn splat(x: f64) -> Self {
        avx512!(Avx512(_mm512_set1_pd(x)))
    }
    #[inline(always)]
    fn mask(self, bits: u8) -> Bits8 {
        Bits8(bits)
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        avx512!(Avx512(_mm512_sqrt_pd(self.0)))
    }
    #[inline(always)]
    fn abs(self) -> Self {
        avx512!(Avx512(_mm512_castsi512_pd(_mm512_and_si512(
            _mm512_castpd_si512(self.0),
            _mm512_set1_epi64(i64::MAX)
        ))))
    }
    #[inline(always)]
    fn copysign(self, sign: Self) -> Self {
        avx512!({
            let m = _mm512_and_si512(_mm512_castpd_si512(self.0), _mm512_set1_epi64(i64::MAX));
            let s = _mm512_and_si512(_mm512_castpd_si512(sign.0), _mm512_set1_epi64(i64::MIN));
            Avx512(_mm512_castsi512_pd(_mm512_or_si512(m, s)))
        })
    }
    #[inline(always)]
    fn min(self, b: Self) -> Self {
        avx512!(Avx512(_mm512_min_pd(self.0, b.0)))
    }
    #[inline(always)]
    fn max(self, b: Self) -> Self {
        avx512!(Avx512(_mm512_max_pd(self.0, b.0)))
    }
    #[inline(always)]
    fn trunc(self) -> Self {
        avx512!(Avx512(_mm512_roundscale_pd::<
            { _MM_FROUND_TO_ZERO | _MM_FROUND_NO_EXC },
        >(self.0)))
    }
    #[inline(always)]
    fn lt(self, b: Self) -> Bits8 {
        avx512!(Bits8(_mm512_cmp_pd_mask::<_CMP_LT_OQ>(self.0, b.0)))
    }
    #[inline(always)]
    fn le(self, b: Self) -> Bits8 {
        avx512!(Bits8(_mm512_cmp_pd_mask::<_CMP_LE_OQ>(self.0, b.0)))
    }
    #[inline(always)]
    fn gt(self, b: Self) -> Bits8 {
        avx512!(Bits8(_mm512_cmp_pd_mask::<_CMP_GT_OQ>(self.0, b.0)))
    }
    #[inline(always)]
    fn ge(self, b: Self) -> Bits8 {
        avx512!(Bits8(_mm512_cmp_pd_mask::<_CMP_GE_OQ>(self.0, b.0)))
    }
    #[inline(always)]
    fn eq(self, b: Self) -> Bits8 {
        avx512!(Bits8(_mm512_cmp_pd_mask::<_CMP_EQ_OQ>(self.0, b.0)))
    }
    #[inline(always)]
    fn is_nan(self) -> Bits8 {
        avx512!(Bits8(_mm512_cmp_pd_mask::<_CMP_UNORD_Q>(self.0, self.0)))
    }
    #[inline(always)]
    fn select(self, m: Bits8, b: Self) -> Self {
        avx512!(Avx512(_mm512_mask_mov_pd(self.0, m.0, b.0)))
    }
    #[inline(always)]
    fn zero_unless(self, m: Bits8) -> Self {
        avx512!(Avx512(_mm512_maskz_mov_pd(m.0, self.0)))
    }
}

impl Wide8 for Avx512 {
    #[inline(always)]
    unsafe fn load(x: &F64x8) -> Self {
        // `F64x8` is eight f64 aligned to 64 bytes, as the aligned load requires.
        avx512!(Avx512(_mm512_load_pd(x.0.as_ptr())))
    }
    #[inline(always)]
    unsafe fn load_unaligned(x: &[f64; 8]) -> Self {
        avx512!(Avx512(_mm512_loadu_pd(x.as_ptr())))
    }
    #[inline(always)]
    unsafe fn columns<const N: usize>(rows: &[&[f64; N]; 8]) -> [Self; N] {
        const { assert!(N.is_multiple_of(4)) };
        let mut out = [avx512!(Avx512(_mm512_setzero_pd())); N];
        for block in 0..N / 4 {
            // (AVX-512F implies the AVX that `columns4` takes)
            let (lo, hi) = avx512!((
                columns4([rows[0], rows[1], rows[2], rows[3]], 4 * block),
                columns4([rows[4], rows[5], rows[6], rows[7]], 4 * block),
            ));
            for j in 0..4 {
                out[4 * block + j] = avx512!(Avx512(_mm512_insertf64x4::<1>(
                    _mm512_castpd256_pd512(lo[j]),
                    hi[j]
                )));
            }
        }
        out
    }
    #[inline(always)]
    fn store(self) -> F64x8 {
        let mut out = F64x8::ZERO;
        avx512!(_mm512_store_pd(out.0.as_mut_ptr(), self.0));
        out
    }
}

/// The AVX2 form: lanes 0-3 in one 256-bit register and 4-7 in another, comparisons to vector
/// masks (all ones or all zeros per lane).
#[derive(Clone, Copy)]
pub struct Avx2([__m256d; 2]);

/// The AVX2 form's mask: all ones in a set lane.
#[derive(Clone, Copy)]
pub struct Lanes4x2([__m256d; 2]);

/// An AVX2 operation on values that exist (so the processor has AVX2).
macro_rules! avx2 {
    ($e:expr) => {
        // SAFETY: an `Avx2` value exists only where the processor has AVX2, and these are inlined
        // into functions compiled with it.
        unsafe { $e }
    };
}

/// The intrinsic `$f` on both halves (written out, not through a closure: a closure is not
/// compiled with the caller's instructions, and the intrinsics in it would be calls).
macro_rules! halves {
    ($t:ident, $a:expr, $b:expr, $f:ident) => {
        avx2!($t([$f($a.0[0], $b.0[0]), $f($a.0[1], $b.0[1])]))
    };
}

impl LaneMask for Lanes4x2 {
    #[inline(always)]
    fn bits(self) -> u8 {
        avx2!((_mm256_movemask_pd(self.0[0]) | _mm256_movemask_pd(self.0[1]) << 4) as u8)
    }
}

impl BitAnd for Lanes4x2 {
    type Output = Lanes4x2;
    #[inline(always)]
    fn bitand(self, b: Lanes4x2) -> Lanes4x2 {
        halves!(Lanes4x2, self, b, _mm256_and_pd)
    }
}

impl BitOr for Lanes4x2 {
    type Output = Lanes4x2;
    #[inline(always)]
    fn bitor(self, b: Lanes4x2) -> Lanes4x2 {
        halves!(Lanes4x2, self, b, _mm256_or_pd)
    }
}

impl BitXor for Lanes4x2 {
    type Output = Lanes4x2;
    #[inline(always)]
    fn bitxor(self, b: Lanes4x2) -> Lanes4x2 {
        halves!(Lanes4x2, self, b, _mm256_xor_pd)
    }
}

impl Not for Lanes4x2 {
    type Output = Lanes4x2;
    #[inline(always)]
    fn not(self) -> Lanes4x2 {
        avx2!({
            let ones = _mm256_castsi256_pd(_mm256_set1_epi64x(-1));
            Lanes4x2([
                _mm256_xor_pd(self.0[0], ones),
                _mm256_xor_pd(self.0[1], ones),
            ])
        })
    }
}

impl Add for Avx2 {
    type Output = Avx2;
    #[inline(always)]
    fn add(self, b: Avx2) -> Avx2 {
        halves!(Avx2, self, b, _mm256_add_pd)
    }
}

impl Sub for Avx2 {
    type Output = Avx2;
    #[inline(always)]
    fn sub(self, b: Avx2) -> Avx2 {
        halves!(Avx2, self, b, _mm256_sub_pd)
    }
}

impl Mul for Avx2 {
    type Output = Avx2;
    #[inline(always)]
    fn mul(self, b: Avx2) -> Avx2 {
        halves!(Avx2, self, b, _mm256_mul_pd)
    }
}

impl Div for Avx2 {
    type Output = Avx2;
    #[inline(always)]
    fn div(self, b: Avx2) -> Avx2 {
        halves!(Avx2, self, b, _mm256_div_pd)
    }
}

impl Neg for Avx2 {
    type Output = Avx2;
    /// The sign bit flipped.
    #[inline(always)]
    fn neg(self) -> Avx2 {
        let sign = self.splat_like(-0.0);
        halves!(Avx2, self, sign, _mm256_xor_pd)
    }
}

impl Avx2 {
    /// Lanes 0-3 and 4-7, each in a register of its own.
    #[inline(always)]
    pub fn halves(self) -> [Avx2Half; 2] {
        [Avx2Half(self.0[0]), Avx2Half(self.0[1])]
    }

    /// Lanes 0-3 from `halves[0]` and 4-7 from `halves[1]`.
    #[inline(always)]
    pub fn from_halves(halves: [Avx2Half; 2]) -> Avx2 {
        Avx2([halves[0].0, halves[1].0])
    }

    /// A comparison of both halves.
    #[inline(always)]
    fn cmp<const P: i32>(self, b: Avx2) -> Lanes4x2 {
        avx2!(Lanes4x2([
            _mm256_cmp_pd::<P>(self.0[0], b.0[0]),
            _mm256_cmp_pd::<P>(self.0[1], b.0[1]),
        ]))
    }
}

impl Lanes for Avx2 {
    type Mask = Lanes4x2;

    #[inline(always)]
    unsafe fn splat(x: f64) -> Self {
        avx2!(Avx2([_mm256_set1_pd(x), _mm256_set1_pd(x)]))
    }
    #[inline(always)]
    fn mask(self, bits: u8) -> Lanes4x2 {
        avx2!({
            let pick = _mm256_set_epi64x(8, 4, 2, 1);
            let lo = _mm256_and_si256(_mm256_set1_epi64x((bits & 15) as i64), pick);
            let hi = _mm256_and_si256(_mm256_set1_epi64x((bits >> 4) as i64), pick);
            Lanes4x2([
                _mm256_castsi256_pd(_mm256_cmpeq_epi64(lo, pick)),
                _mm256_castsi256_pd(_mm256_cmpeq_epi64(hi, pick)),
            ])
        })
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        avx2!(Avx2([_mm256_sqrt_pd(self.0[0]), _mm256_sqrt_pd(self.0[1])]))
    }
    #[inline(always)]
    fn abs(self) -> Self {
        let magnitude = avx2!(Avx2([_mm256_castsi256_pd(_mm256_set1_epi64x(i64::MAX)); 2]));
        halves!(Avx2, self, magnitude, _mm256_and_pd)
    }
    #[inline(always)]
    fn copysign(self, sign: Self) -> Self {
        let s = self.splat_like(-0.0);
        avx2!(Avx2([
            _mm256_or_pd(
                _mm256_andnot_pd(s.0[0], self.0[0]),
                _mm256_and_pd(s.0[0], sign.0[0])
            ),
            _mm256_or_pd(
                _mm256_andnot_pd(s.0[1], self.0[1]),
                _mm256_and_pd(s.0[1], sign.0[1])
            ),
        ]))
    }
    #[inline(always)]
    fn min(self, b: Self) -> Self {
        halves!(Avx2, self, b, _mm256_min_pd)
    }
    #[inline(always)]
    fn max(self, b: Self) -> Self {
        halves!(Avx2, self, b, _mm256_max_pd)
    }
    #[inline(always)]
    fn trunc(self) -> Self {
        avx2!(Avx2([
            _mm256_round_pd::<{ _MM_FROUND_TO_ZERO | _MM_FROUND_NO_EXC }>(self.0[0]),
            _mm256_round_pd::<{ _MM_FROUND_TO_ZERO | _MM_FROUND_NO_EXC }>(self.0[1]),
        ]))
    }
    #[inline(always)]
    fn lt(self, b: Self) -> Lanes4x2 {
        self.cmp::<_CMP_LT_OQ>(b)
    }
    #[inline(always)]
    fn le(self, b: Self) -> Lanes4x2 {
        self.cmp::<_CMP_LE_OQ>(b)
    }
    #[inline(always)]
    fn gt(self, b: Self) -> Lanes4x2 {
        self.cmp::<_CMP_GT_OQ>(b)
    }
    #[inline(always)]
    fn ge(self, b: Self) -> Lanes4x2 {
        self.cmp::<_CMP_GE_OQ>(b)
    }
    #[inline(always)]
    fn eq(self, b: Self) -> Lanes4x2 {
        self.cmp::<_CMP_EQ_OQ>(b)
    }
    #[inline(always)]
    fn is_nan(self) -> Lanes4x2 {
        self.cmp::<_CMP_UNORD_Q>(self)
    }
    #[inline(always)]
    fn select(self, m: Lanes4x2, b: Self) -> Self {
        avx2!(Avx2([
            _mm256_blendv_pd(self.0[0], b.0[0], m.0[0]),
            _mm256_blendv_pd(self.0[1], b.0[1], m.0[1]),
        ]))
    }
    #[inline(always)]
    fn zero_unless(self, m: Lanes4x2) -> Self {
        avx2!(Avx2([
            _mm256_and_pd(self.0[0], m.0[0]),
            _mm256_and_pd(self.0[1], m.0[1]),
        ]))
    }
}

impl Wide8 for Avx2 {
    #[inline(always)]
    unsafe fn load(x: &F64x8) -> Self {
        // `F64x8` is aligned to 64 bytes, so each half to 32, as the aligned loads require.
        avx2!(Avx2([
            _mm256_load_pd(x.0.as_ptr()),
            _mm256_load_pd(x.0.as_ptr().add(4))
        ]))
    }
    #[inline(always)]
    unsafe fn load_unaligned(x: &[f64; 8]) -> Self {
        avx2!(Avx2([
            _mm256_loadu_pd(x.as_ptr()),
            _mm256_loadu_pd(x.as_ptr().add(4))
        ]))
    }
    #[inline(always)]
    unsafe fn columns<const N: usize>(rows: &[&[f64; N]; 8]) -> [Self; N] {
        const { assert!(N.is_multiple_of(4)) };
        let mut out = [avx2!(Avx2([_mm256_setzero_pd(); 2])); N];
        for block in 0..N / 4 {
            let (lo, hi) = avx2!((
                columns4([rows[0], rows[1], rows[2], rows[3]], 4 * block),
                columns4([rows[4], rows[5], rows[6], rows[7]], 4 * block),
            ));
            for j in 0..4 {
                out[4 * block + j] = Avx2([lo[j], hi[j]]);
            }
        }
        out
    }
    #[inline(always)]
    fn store(self) -> F64x8 {
        let mut out = F64x8::ZERO;
        avx2!({
            _mm256_store_pd(out.0.as_mut_ptr(), self.0[0]);
            _mm256_store_pd(out.0.as_mut_ptr().add(4), self.0[1]);
        });
        out
    }
}

/// Half of the AVX2 form: four lanes in one 256-bit register ([`Avx2::halves`]), for work that only
/// some of the eight lanes need (the quads of an instance, behind its box, in [`crate::ray8`]).
#[derive(Clone, Copy)]
pub struct Avx2Half(__m256d);

/// [`Avx2Half`]'s mask: all ones in a set lane.
#[derive(Clone, Copy)]
pub struct Lanes4(__m256d);

/// The intrinsic `$f` on one register.
macro_rules! half {
    ($t:ident, $a:expr, $b:expr, $f:ident) => {
        avx2!($t($f($a.0, $b.0)))
    };
}

impl LaneMask for Lanes4 {
    #[inline(always)]
    fn bits(self) -> u8 {
        avx2!(_mm256_movemask_pd(self.0) as u8)
    }
}

impl BitAnd for Lanes4 {
    type Output = Lanes4;
    #[inline(always)]
    fn bitand(self, b: Lanes4) -> Lanes4 {
        half!(Lanes4, self, b, _mm256_and_pd)
    }
}

impl BitOr for Lanes4 {
    type Output = Lanes4;
    #[inline(always)]
    fn bitor(self, b: Lanes4) -> Lanes4 {
        half!(Lanes4, self, b, _mm256_or_pd)
    }
}

impl BitXor for Lanes4 {
    type Output = Lanes4;
    #[inline(always)]
    fn bitxor(self, b: Lanes4) -> Lanes4 {
        half!(Lanes4, self, b, _mm256_xor_pd)
    }
}

impl Not for Lanes4 {
    type Output = Lanes4;
    #[inline(always)]
    fn not(self) -> Lanes4 {
        avx2!(Lanes4(_mm256_xor_pd(
            self.0,
            _mm256_castsi256_pd(_mm256_set1_epi64x(-1))
        )))
    }
}

impl Add for Avx2Half {
    type Output = Avx2Half;
    #[inline(always)]
    fn add(self, b: Avx2Half) -> Avx2Half {
        half!(Avx2Half, self, b, _mm256_add_pd)
    }
}

impl Sub for Avx2Half {
    type Output = Avx2Half;
    #[inline(always)]
    fn sub(self, b: Avx2Half) -> Avx2Half {
        half!(Avx2Half, self, b, _mm256_sub_pd)
    }
}

impl Mul for Avx2Half {
    type Output = Avx2Half;
    #[inline(always)]
    fn mul(self, b: Avx2Half) -> Avx2Half {
        half!(Avx2Half, self, b, _mm256_mul_pd)
    }
}

impl Div for Avx2Half {
    type Output = Avx2Half;
    #[inline(always)]
    fn div(self, b: Avx2Half) -> Avx2Half {
        half!(Avx2Half, self, b, _mm256_div_pd)
    }
}

impl Neg for Avx2Half {
    type Output = Avx2Half;
    /// The sign bit flipped.
    #[inline(always)]
    fn neg(self) -> Avx2Half {
        let sign = self.splat_like(-0.0);
        half!(Avx2Half, self, sign, _mm256_xor_pd)
    }
}

impl Avx2Half {
    /// A comparison.
    #[inline(always)]
    fn cmp<const P: i32>(self, b: Avx2Half) -> Lanes4 {
        avx2!(Lanes4(_mm256_cmp_pd::<P>(self.0, b.0)))
    }
}

impl Lanes for Avx2Half {
    type Mask = Lanes4;

    #[inline(always)]
    unsafe fn splat(x: f64) -> Self {
        avx2!(Avx2Half(_mm256_set1_pd(x)))
    }
    #[inline(always)]
    fn mask(self, bits: u8) -> Lanes4 {
        avx2!({
            let pick = _mm256_set_epi64x(8, 4, 2, 1);
            let set = _mm256_and_si256(_mm256_set1_epi64x((bits & 15) as i64), pick);
            Lanes4(_mm256_castsi256_pd(_mm256_cmpeq_epi64(set, pick)))
        })
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        avx2!(Avx2Half(_mm256_sqrt_pd(self.0)))
    }
    #[inline(always)]
    fn abs(self) -> Self {
        let magnitude = avx2!(Avx2Half(_mm256_castsi256_pd(_mm256_set1_epi64x(i64::MAX))));
        half!(Avx2Half, self, magnitude, _mm256_and_pd)
    }
    #[inline(always)]
    fn copysign(self, sign: Self) -> Self {
        let s = self.splat_like(-0.0);
        avx2!(Avx2Half(_mm256_or_pd(
            _mm256_andnot_pd(s.0, self.0),
            _mm256_and_pd(s.0, sign.0)
        )))
    }
    #[inline(always)]
    fn min(self, b: Self) -> Self {
        half!(Avx2Half, self, b, _mm256_min_pd)
    }
    #[inline(always)]
    fn max(self, b: Self) -> Self {
        half!(Avx2Half, self, b, _mm256_max_pd)
    }
    #[inline(always)]
    fn trunc(self) -> Self {
        avx2!(Avx2Half(_mm256_round_pd::<
            { _MM_FROUND_TO_ZERO | _MM_FROUND_NO_EXC },
        >(self.0)))
    }
    #[inline(always)]
    fn lt(self, b: Self) -> Lanes4 {
        self.cmp::<_CMP_LT_OQ>(b)
    }
    #[inline(always)]
    fn le(self, b: Self) -> Lanes4 {
        self.cmp::<_CMP_LE_OQ>(b)
    }
    #[inline(always)]
    fn gt(self, b: Self) -> Lanes4 {
        self.cmp::<_CMP_GT_OQ>(b)
    }
    #[inline(always)]
    fn ge(self, b: Self) -> Lanes4 {
        self.cmp::<_CMP_GE_OQ>(b)
    }
    #[inline(always)]
    fn eq(self, b: Self) -> Lanes4 {
        self.cmp::<_CMP_EQ_OQ>(b)
    }
    #[inline(always)]
    fn is_nan(self) -> Lanes4 {
        self.cmp::<_CMP_UNORD_Q>(self)
    }
    #[inline(always)]
    fn select(self, m: Lanes4, b: Self) -> Self {
        avx2!(Avx2Half(_mm256_blendv_pd(self.0, b.0, m.0)))
    }
    #[inline(always)]
    fn zero_unless(self, m: Lanes4) -> Self {
        avx2!(Avx2Half(_mm256_and_pd(self.0, m.0)))
    }
}
