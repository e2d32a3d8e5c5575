//! The scrambled 2D Sobol sequence: the (0, 2)-sequence box property with and without scrambling,
//! nested permutation of the scramble, uniform points.

mod common;

use common::chi_square_p;
use rtl_mc::sequence::{ScrambledSobol2, owen_scramble, scrambled_sobol, sobol_bits};

/// Checks that points `start .. start + 2^m` put exactly one point in every elementary box of area
/// `2^-m`, for every split `a + b = m` of the resolution between the axes.
fn is_0_m_2_net(points: &[(u32, u32)], m: u32) -> bool {
    (0..=m).all(|a| {
        let b = m - a;
        let mut seen = vec![false; 1 << m];
        points.iter().all(|&(x, y)| {
            // u64 shifts, so a shift by 32 (a or b = 0) gives 0
            let cell = ((x as u64 >> (32 - a)) << b | (y as u64 >> (32 - b))) as usize;
            !std::mem::replace(&mut seen[cell], true)
        })
    })
}

#[test]
fn dimension_1_by_tables_is_the_generator_matrix_product() {
    // The definition, bit by bit: column k is v_k, v_0 = 1/2, v_k = v_(k-1) XOR (v_(k-1) / 2).
    let by_bits = |mut i: u32| {
        let (mut v, mut r) = (1u32 << 31, 0);
        while i != 0 {
            if i & 1 != 0 {
                r ^= v;
            }
            i >>= 1;
            v ^= v >> 1;
        }
        r
    };
    let mut x = 1u32;
    for i in (0..4096u32).chain([u32::MAX, 1 << 31, 0x8000_0001]) {
        assert_eq!(sobol_bits(i, 1), by_bits(i), "index {i}");
        x = x.wrapping_mul(0x9e37_79b9).wrapping_add(7);
        assert_eq!(sobol_bits(x, 1), by_bits(x), "index {x}");
    }
}

#[test]
fn unscrambled_points_form_a_0_2_sequence() {
    assert_eq!(sobol_bits(1, 1), 1 << 31);
    assert_eq!(sobol_bits(2, 1), 3 << 30);
    for m in 0..=12 {
        for block in 0..3u32 {
            let start = block << m;
            let pts: Vec<(u32, u32)> = (start..start + (1 << m))
                .map(|i| (sobol_bits(i, 0), sobol_bits(i, 1)))
                .collect();
            assert!(is_0_m_2_net(&pts, m), "m {m}, block {block}");
        }
    }
}

#[test]
fn the_box_check_rejects_points_that_are_not_a_net() {
    // dimension 0 against itself: stratified on each axis, but on the diagonal
    let pts: Vec<(u32, u32)> = (0..16)
        .map(|i| (sobol_bits(i, 0), sobol_bits(i, 0)))
        .collect();
    assert!(!is_0_m_2_net(&pts, 4));
}

#[test]
fn scrambling_keeps_the_box_property() {
    for seed in [1u32, 0xdead_beef, 77] {
        let s0 = seed;
        let s1 = seed.wrapping_mul(0x9e37_79b9) ^ 0x1234;
        for m in [0, 1, 5, 10] {
            let pts: Vec<(u32, u32)> = (0..1u32 << m)
                .map(|i| {
                    (
                        owen_scramble(sobol_bits(i, 0), s0),
                        owen_scramble(sobol_bits(i, 1), s1),
                    )
                })
                .collect();
            assert!(is_0_m_2_net(&pts, m), "seed {seed}, m {m}");
        }
    }
}

#[test]
fn the_scramble_is_a_nested_permutation() {
    // Digit k of the output depends only on digits 0..=k of the input: the top 10 bits of the image of x
    // are a function of the top 10 bits of x, and a bijection on them.
    for seed in [0u32, 3, 0xffff_ffff] {
        let mut image = vec![u32::MAX; 1 << 10];
        for prefix in 0..1u32 << 10 {
            for low in [0u32, 1, 0x3f_ffff, 0x15_5555] {
                let top = owen_scramble(prefix << 22 | low, seed) >> 22;
                if image[prefix as usize] == u32::MAX {
                    image[prefix as usize] = top;
                }
                assert_eq!(image[prefix as usize], top, "prefix {prefix} low {low}");
            }
        }
        image.sort();
        assert!(image.iter().enumerate().all(|(k, &v)| v == k as u32));
    }
}

#[test]
fn a_scrambled_point_is_uniform_over_seeds() {
    // Point 5 of dimension 1 over 1e5 scrambles: chi-square against uniform in 100 cells. One test at
    // alpha 0.01.
    let mut observed = vec![0u64; 100];
    for seed in 0..100_000u64 {
        let x = scrambled_sobol(5, 1, seed);
        assert!((0.0..1.0).contains(&x));
        observed[(x * 100.0) as usize] += 1;
    }
    let p = chi_square_p(&observed, &[1000.0; 100]);
    assert!(p > 0.01, "p-value {p}");
}

#[test]
fn scrambled_points_use_all_53_bits() {
    let x = scrambled_sobol(3, 0, 9);
    let bits = (x * (1u64 << 53) as f64) as u64;
    assert_eq!(bits as f64 / (1u64 << 53) as f64, x);
    assert_ne!(
        bits & 0x1f_ffff,
        0,
        "the 21 low bits are random, not all zero (1 in 2^21 chance)"
    );
}

#[test]
fn gray_code_order_gives_the_same_point_sets() {
    for m in [0, 3, 8] {
        let mut gray: Vec<[u64; 2]> = ScrambledSobol2::new(42)
            .take(1 << m)
            .map(|p| p.map(f64::to_bits))
            .collect();
        let mut natural: Vec<[u64; 2]> = (0..1u32 << m)
            .map(|i| [scrambled_sobol(i, 0, 42), scrambled_sobol(i, 1, 42)].map(f64::to_bits))
            .collect();
        gray.sort();
        natural.sort();
        assert_eq!(gray, natural, "m {m}");
    }
}
