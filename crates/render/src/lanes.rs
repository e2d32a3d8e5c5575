//! `f64` lanes side by side: the storage of the quad packets, four aligned so that one AVX instruction
//! loads them, eight so that one AVX-512 instruction does.

/// Four `f64` lanes, 32-byte aligned.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(32))]
pub struct F64x4(pub [f64; 4]);

impl F64x4 {
    pub const ZERO: F64x4 = F64x4([0.0; 4]);
}

/// Eight `f64` lanes, 64-byte aligned.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(64))]
pub struct F64x8(pub [f64; 8]);

impl F64x8 {
    pub const ZERO: F64x8 = F64x8([0.0; 8]);
}

impl Default for F64x8 {
    fn default() -> Self {
        F64x8::ZERO
    }
}

/// The AVX form of the lanes: loads, broadcasts and the arithmetic the packets use, each one
/// instruction on all four lanes. IEEE rounding lane by lane, exactly as the scalar operations (no
/// fused multiply-adds), so code written with these finds bit-identical results to its scalar twin.
#[cfg(target_arch = "x86_64")]
pub mod avx {
    use super::F64x4;
    use std::arch::x86_64::*;

    /// The four lanes in one register.
    ///
    /// # Safety
    /// Only where the processor has AVX.
    #[inline]
    #[target_feature(enable = "avx")]
    pub fn load(x: &F64x4) -> __m256d {
        // SAFETY: `F64x4` is four f64 aligned to 32 bytes, as the aligned load requires.
        unsafe { _mm256_load_pd(x.0.as_ptr()) }
    }

    /// The lanes of a register, as an array.
    ///
    /// # Safety
    /// Only where the processor has AVX.
    #[inline]
    #[target_feature(enable = "avx")]
    pub fn store(x: __m256d) -> [f64; 4] {
        let mut out = F64x4::ZERO;
        // SAFETY: `out` is four f64 aligned to 32 bytes, as the aligned store requires.
        unsafe { _mm256_store_pd(out.0.as_mut_ptr(), x) };
        out.0
    }

    /// `x[0] * y[0] + x[1] * y[1] + x[2] * y[2]`, left to right, lane by lane.
    ///
    /// # Safety
    /// Only where the processor has AVX.
    #[inline]
    #[target_feature(enable = "avx")]
    pub fn dot(x: [__m256d; 3], y: [__m256d; 3]) -> __m256d {
        _mm256_add_pd(
            _mm256_add_pd(_mm256_mul_pd(x[0], y[0]), _mm256_mul_pd(x[1], y[1])),
            _mm256_mul_pd(x[2], y[2]),
        )
    }

    /// The three coordinates of a packet field, each in one register.
    ///
    /// # Safety
    /// Only where the processor has AVX.
    #[inline]
    #[target_feature(enable = "avx")]
    pub fn load3(x: &[F64x4; 3]) -> [__m256d; 3] {
        [load(&x[0]), load(&x[1]), load(&x[2])]
    }

    /// A ray's origin and direction broadcast to all four lanes ([`splat3`]), once per traversal
    /// rather than once per packet.
    #[derive(Clone, Copy, Debug)]
    pub struct RayLanes {
        pub origin: [__m256d; 3],
        pub direction: [__m256d; 3],
    }

    impl RayLanes {
        /// The broadcasts of `origin` and `direction`.
        ///
        /// # Safety
        /// Only where the processor has AVX.
        #[inline]
        #[target_feature(enable = "avx")]
        pub fn new(origin: [f64; 3], direction: [f64; 3]) -> RayLanes {
            RayLanes {
                origin: splat3(origin),
                direction: splat3(direction),
            }
        }

        /// All lanes zero: a placeholder where no AVX code will read it (made without AVX).
        pub fn unused() -> RayLanes {
            // SAFETY: `__m256d` is plain data, for which all-zero bits are a valid value.
            unsafe { std::mem::zeroed() }
        }
    }

    /// A scalar vector broadcast: every lane of register `a` holds coordinate `a`.
    ///
    /// # Safety
    /// Only where the processor has AVX.
    #[inline]
    #[target_feature(enable = "avx")]
    pub fn splat3(v: [f64; 3]) -> [__m256d; 3] {
        [
            _mm256_set1_pd(v[0]),
            _mm256_set1_pd(v[1]),
            _mm256_set1_pd(v[2]),
        ]
    }
}

/// The AVX-512 form of the lanes: as [`avx`], eight lanes to an instruction, with the comparisons
/// giving bit masks. IEEE rounding lane by lane, exactly as the scalar operations (no fused
/// multiply-adds).
#[cfg(target_arch = "x86_64")]
pub mod avx512 {
    use super::F64x8;
    use std::arch::x86_64::*;

    /// The eight lanes in one register.
    ///
    /// # Safety
    /// Only where the processor has AVX-512F.
    #[inline]
    #[target_feature(enable = "avx512f")]
    pub fn load(x: &F64x8) -> __m512d {
        // SAFETY: `F64x8` is eight f64 aligned to 64 bytes, as the aligned load requires.
        unsafe { _mm512_load_pd(x.0.as_ptr()) }
    }

    /// `x[0] * y[0] + x[1] * y[1] + x[2] * y[2]`, left to right, lane by lane.
    ///
    /// # Safety
    /// Only where the processor has AVX-512F.
    #[inline]
    #[target_feature(enable = "avx512f")]
    pub fn dot(x: [__m512d; 3], y: [__m512d; 3]) -> __m512d {
        _mm512_add_pd(
            _mm512_add_pd(_mm512_mul_pd(x[0], y[0]), _mm512_mul_pd(x[1], y[1])),
            _mm512_mul_pd(x[2], y[2]),
        )
    }

    /// The three coordinates of a packet field, each in one register.
    ///
    /// # Safety
    /// Only where the processor has AVX-512F.
    #[inline]
    #[target_feature(enable = "avx512f")]
    pub fn load3(x: &[F64x8; 3]) -> [__m512d; 3] {
        [load(&x[0]), load(&x[1]), load(&x[2])]
    }
}
