//! Every warp's inverse tested as the inverse at the values of `u` where one is most likely to slip:
//! each coordinate in {0, 1/2, 1 - 2⁻⁵³}. The tolerances are a few ulps, except where the warp
//! documents that it moves `u` (the hemisphere's `cos theta >= MIN_COS_THETA`, the cone's
//! `u.x <= CONE_U_MAX`, the disk's `2 u - 1` within `±CONCENTRIC_MAX`), where the inverse must give
//! the `u` the warp used. The density beside each warp must be positive and finite at its sample.
//! The discrete choice of a part ([`Selection`]) is tested the same way.

use glam::{DVec2, DVec3};
use rtl_pdf::warp::{self, SphericalRectangle};
use rtl_pdf::{MIN_SPHERICAL_RECTANGLE_SOLID_ANGLE, ONE_MINUS_EPSILON, Selection};

const US: [f64; 3] = [0.0, 0.5, ONE_MINUS_EPSILON];
const EPS: f64 = f64::EPSILON;

fn corners() -> impl Iterator<Item = DVec2> {
    US.into_iter()
        .flat_map(|a| US.into_iter().map(move |b| DVec2::new(a, b)))
}

/// `|a - b|` of an azimuth in turns, where 0 and 1 are the same.
fn turns_apart(a: f64, b: f64) -> f64 {
    let d = (a - b).abs();
    d.min(1.0 - d)
}

#[test]
fn sphere_inverse_returns_u() {
    for u in corners() {
        let w = warp::sample_uniform_sphere(u);
        let back = warp::invert_uniform_sphere_sample(w);
        assert!((back.x - u.x).abs() <= 2.0 * EPS, "{u} -> {w} -> {back}");
        // at the pole u.x = 0 every u.y is the same direction
        if u.x > 0.0 {
            assert!(
                turns_apart(back.y, u.y) <= 2.0 * EPS,
                "{u} -> {w} -> {back}"
            );
        }
        assert!(warp::uniform_sphere_pdf() > 0.0);
    }
}

#[test]
fn hemisphere_inverse_returns_the_u_the_warp_used() {
    for u in corners() {
        let w = warp::sample_uniform_hemisphere(u);
        let back = warp::invert_uniform_hemisphere_sample(w);
        let used = u.x.max(warp::MIN_COS_THETA);
        assert!((back.x - used).abs() <= 2.0 * EPS, "{u} -> {w} -> {back}");
        assert!(
            turns_apart(back.y, u.y) <= 2.0 * EPS,
            "{u} -> {w} -> {back}"
        );
        assert!(w.z > 0.0 && warp::uniform_hemisphere_pdf() > 0.0);
    }
}

#[test]
fn disk_and_cosine_inverses_return_u() {
    for u in corners() {
        // u = 0 is drawn as 2^-53, a quarter of the tolerance
        let p = warp::sample_uniform_disk_concentric(u);
        let back = warp::invert_uniform_disk_concentric_sample(p);
        assert!(
            (back - u).abs().max_element() <= 2.0 * EPS,
            "disk: {u} -> {p} -> {back}"
        );
        assert!(p.length_squared() < 1.0 && warp::uniform_disk_pdf() > 0.0);

        let w = warp::sample_cosine_hemisphere(u);
        let back = warp::invert_cosine_hemisphere_sample(w);
        assert!(
            (back - u).abs().max_element() <= 2.0 * EPS,
            "cosine: {u} -> {w} -> {back}"
        );
        let pdf = warp::cosine_hemisphere_pdf(w.z);
        assert!(
            pdf > 0.0 && pdf.is_finite(),
            "cosine: {u} -> {w}: pdf {pdf}"
        );
    }
}

#[test]
fn cone_inverse_returns_the_u_the_warp_used() {
    for max in [2.0, 1.0, 0.2, 1e-10] {
        for u in corners() {
            let w = warp::sample_uniform_cone(u, max);
            let back = warp::invert_uniform_cone_sample(w, max);
            let used = u.x.min(warp::CONE_U_MAX);
            assert!(
                (back.x - used).abs() <= 4.0 * EPS,
                "cone {max}: {u} -> {w} -> {back}"
            );
            // at the apex u.x = 0 every u.y is the same direction
            if u.x > 0.0 {
                assert!(
                    turns_apart(back.y, u.y) <= 2.0 * EPS,
                    "cone {max}: {u} -> {w} -> {back}"
                );
            }
            let pdf = warp::uniform_cone_pdf(max);
            assert!(pdf > 0.0 && pdf.is_finite());
        }
    }
}

#[test]
fn parallelogram_inverse_returns_u() {
    let (q, e1, e2) = (
        DVec3::new(1.0, 2.0, 3.0),
        DVec3::new(0.5, 0.1, 0.0),
        DVec3::new(0.2, -1.0, 0.3),
    );
    for u in corners() {
        let p = warp::sample_parallelogram(u, q, e1, e2);
        let back = warp::invert_parallelogram_sample(p, q, e1, e2);
        assert!(
            (back - u).abs().max_element() <= 4.0 * EPS,
            "{u} -> {p} -> {back}"
        );
    }
    let pdf = warp::parallelogram_pdf(e1, e2);
    assert!(pdf > 0.0 && pdf.is_finite());
}

/// Within the solid angles where a `QuadTarget` samples by spherical rectangles
/// (`MIN_SPHERICAL_RECTANGLE_SOLID_ANGLE` to `MAX_...`), the inverse returns `u` to 1e-12. Below, the
/// angle sum `g0 + g1 - k` cancels (the sampler's own terms lose precision, which is why the quad
/// falls back to area sampling there): at 1e-5 sr the round trip errs by about 2e-8.
#[test]
fn spherical_rectangle_inverse_returns_u_near_far_and_grazing() {
    let unit = (DVec3::ZERO, DVec3::X, DVec3::Y);
    let cases = [
        // (origin, (corner, ex, ey), tolerance): near and off-centre, a cube face from its centre,
        // nearly a hemisphere, grazing, far (at the lower limit), grazing below the limit
        (
            DVec3::new(0.3, 0.2, 1.5),
            (
                DVec3::new(-1.0, -0.5, 0.0),
                DVec3::new(2.0, 0.0, 0.0),
                DVec3::new(0.0, 1.5, 0.0),
            ),
            1e-12,
        ),
        (
            DVec3::ZERO,
            (
                DVec3::new(-1.0, -1.0, -1.0),
                DVec3::new(2.0, 0.0, 0.0),
                DVec3::new(0.0, 2.0, 0.0),
            ),
            1e-12,
        ),
        (DVec3::new(0.5, 0.5, 1e-3), unit, 1e-12),
        (DVec3::new(3.0, 0.0, 0.3), unit, 1e-12),
        (DVec3::new(0.5, 0.5, 50.0), unit, 1e-12),
        (DVec3::new(5.0, 0.0, 1e-3), unit, 1e-7),
    ];
    for (origin, (q, ex, ey), tol) in cases {
        let r = SphericalRectangle::new(origin, q, ex, ey).unwrap();
        assert!(r.pdf() > 0.0 && r.pdf().is_finite(), "from {origin}");
        if tol == 1e-12 {
            assert!(
                r.solid_angle() >= MIN_SPHERICAL_RECTANGLE_SOLID_ANGLE,
                "from {origin}"
            );
        }
        for u in corners() {
            let p = r.sample(u);
            let back = r.invert(p);
            assert!(
                (back - u).abs().max_element() <= tol,
                "from {origin} (S = {:e}): {u} -> {p} -> {back}",
                r.solid_angle()
            );
        }
    }
}

#[test]
fn selection_inverse_returns_u() {
    let s = Selection::from_weights(&[0.0, 1.0, 0.0, 3.0, 0.0]).unwrap();
    for u in US {
        let c = s.sample(u);
        assert!(c.pmf > 0.0 && c.pmf == s.pmf(c.index), "{u}: {c:?}");
        let back = s.invert(c.index, c.u_remapped);
        assert!((back - u).abs() <= EPS, "{u} -> {c:?} -> {back}");
    }
}

/// `Selection::sample` promises a part with `p_i > 0` whatever `u` is: a NaN `u` (which `f64::clamp`
/// keeps) is taken as 0, as rtl-sampling's tables take it.
#[test]
fn selection_of_a_nan_u_is_a_part_of_positive_probability() {
    let s = Selection::from_weights(&[0.0, 1.0]).unwrap();
    let c = s.sample(f64::NAN);
    assert!(c.index == 1 && c.pmf > 0.0, "{c:?}");
    assert!((0.0..1.0).contains(&c.u_remapped), "{c:?}");
}
