//! Property tests of the warps (proptest, a short budget in the normal `cargo test` run): at
//! arbitrary `u`, with the boundary values `0`, `2^-53` and `1 - 2^-53` drawn often, every warp gives
//! a finite unit direction (or a point) inside its support where its density is positive, and its
//! inverse gives `u` back.

use glam::{DVec2, DVec3};
use proptest::prelude::*;
use rtl_pdf::Onb;
use rtl_pdf::warp;

const U_MAX: f64 = 1.0 - f64::EPSILON / 2.0;

fn coordinate() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(0.0),
        Just(f64::EPSILON / 2.0),
        Just(U_MAX),
        Just(0.5),
        0.0..1e-12f64,
        (1.0 - 1e-12)..U_MAX,
        0.0..1.0f64,
    ]
}

fn u() -> impl Strategy<Value = DVec2> {
    (coordinate(), coordinate()).prop_map(|(a, b)| DVec2::new(a, b))
}

fn normal() -> impl Strategy<Value = DVec3> {
    (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64)
        .prop_filter("not too short", |(x, y, z)| x * x + y * y + z * z > 1e-6)
        .prop_map(|(x, y, z)| DVec3::new(x, y, z).normalize())
}

/// 512 cases from a fixed seed unless `PROPTEST_CASES` / `PROPTEST_RNG_SEED` say otherwise.
fn config() -> ProptestConfig {
    let from_env = ProptestConfig::default();
    let set = |var: &str| std::env::var_os(var).is_some();
    ProptestConfig {
        cases: if set("PROPTEST_CASES") {
            from_env.cases
        } else {
            512
        },
        rng_seed: if set("PROPTEST_RNG_SEED") {
            from_env.rng_seed
        } else {
            proptest::test_runner::RngSeed::Fixed(15)
        },
        failure_persistence: None,
        ..from_env
    }
}

fn unit(w: DVec3) -> bool {
    w.is_finite() && (w.length() - 1.0).abs() < 1e-12
}

/// The azimuth wraps: 0 and 1 are the same `u.y`.
fn close(a: DVec2, b: DVec2, tol: f64) -> bool {
    let dy = (a.y - b.y).abs();
    (a.x - b.x).abs() < tol && dy.min(1.0 - dy) < tol
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn hemisphere_warps_stay_above_the_horizon_in_every_frame(u in u(), n in normal()) {
        let frame = Onb::new(n);
        for (name, w) in [
            ("cosine", warp::sample_cosine_hemisphere(u)),
            ("hemisphere", warp::sample_uniform_hemisphere(u)),
        ] {
            prop_assert!(unit(w), "{} at {}: {}", name, u, w);
            prop_assert!(w.z > 0.0, "{} at {}: z = {}", name, u, w.z);
            prop_assert!(frame.transform(w).dot(n) > 0.0, "{} at {} about {}", name, u, n);
        }
        let w = warp::sample_cosine_hemisphere(u);
        prop_assert!(warp::cosine_hemisphere_pdf(w.z) > 0.0);
    }

    #[test]
    fn sphere_and_cone_warps_are_unit_and_inside(u in u(), max in prop_oneof![Just(2.0), Just(1e-300), 1e-18..2.0f64]) {
        prop_assert!(unit(warp::sample_uniform_sphere(u)));
        let w = warp::sample_uniform_cone(u, max);
        prop_assert!(unit(w), "cone {} at {}: {}", max, u, w);
        prop_assert!(warp::one_minus_cos_theta(w) <= max, "cone {} at {}: outside", max, u);
    }

    #[test]
    fn inverses_give_u_back(u in u()) {
        let inner = u.clamp(DVec2::splat(1e-9), DVec2::splat(1.0 - 1e-9));
        prop_assert!(close(warp::invert_uniform_sphere_sample(warp::sample_uniform_sphere(inner)), inner, 1e-9));
        prop_assert!(close(warp::invert_uniform_hemisphere_sample(warp::sample_uniform_hemisphere(inner)), inner, 1e-9));
        let c = warp::invert_cosine_hemisphere_sample(warp::sample_cosine_hemisphere(inner));
        prop_assert!((c - inner).abs().max_element() < 1e-6, "{} vs {}", c, inner);
        // at the boundary itself the inverse stays in [0, 1)
        let d = warp::invert_uniform_disk_concentric_sample(warp::sample_uniform_disk_concentric(u));
        prop_assert!(d.cmpge(DVec2::ZERO).all() && d.cmplt(DVec2::ONE).all(), "{}", d);
    }
}
