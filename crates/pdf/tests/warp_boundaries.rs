//! Every warp at every boundary `u` (issue 15): each coordinate in {0, 2⁻⁵³, 1 - 2⁻⁵³} and the edges
//! between (one coordinate at a boundary, the other swept across `[0, 1)`). Each must return a
//! finite direction (or point) inside its support, where its own density is positive, also after an
//! orthonormal frame carries it to the world (whose rounding is about 1e-16).

use glam::{DVec2, DVec3};
use rtl_pdf::Onb;
use rtl_pdf::warp::{self, SphericalRectangle};

const U_MAX: f64 = 1.0 - f64::EPSILON / 2.0; // 1 - 2^-53
const EDGES: [f64; 3] = [0.0, f64::EPSILON / 2.0, U_MAX];

/// The corners and the four edges of the unit square, as `u` reaches them.
fn boundary_u() -> Vec<DVec2> {
    let mut v = Vec::new();
    for a in EDGES {
        for k in 0..=256 {
            let b = (k as f64 / 256.0).min(U_MAX);
            v.push(DVec2::new(a, b));
            v.push(DVec2::new(b, a));
        }
        for b in EDGES {
            v.push(DVec2::new(a, b));
        }
    }
    v
}

/// Normals for which a frame is built: the axes, an f32 case nearly -z, and a few oblique ones.
fn normals() -> Vec<DVec3> {
    let mut n = vec![
        DVec3::X,
        DVec3::Y,
        DVec3::Z,
        -DVec3::X,
        -DVec3::Y,
        -DVec3::Z,
    ];
    n.push(DVec3::new(0.00038527316, 0.00038460016, -0.99999988079).normalize());
    n.push(DVec3::new(1.0, 2.0, 3.0).normalize());
    n.push(DVec3::new(-0.3, 1e-9, 0.2).normalize());
    n
}

fn assert_unit(w: DVec3, what: &str, u: DVec2) {
    assert!(w.is_finite(), "{what} at {u}: {w}");
    assert!(
        (w.length() - 1.0).abs() < 1e-12,
        "{what} at {u}: |w| = {}",
        w.length()
    );
}

/// A hemisphere direction must be above the horizon in its own frame and in every world frame.
fn assert_above_horizon(w: DVec3, what: &str, u: DVec2) {
    assert!(
        w.z > 0.0,
        "{what} at {u}: z = {} is on or below the horizon",
        w.z
    );
    for n in normals() {
        let world = Onb::new(n).transform(w);
        assert!(
            world.dot(n) > 0.0,
            "{what} at {u}, normal {n}: cos = {}",
            world.dot(n)
        );
    }
}

#[test]
fn cosine_warp_at_u_x_zero_samples_above_the_horizon_with_positive_density() {
    // The case: u.x = 0 put the concentric disk's point on the rim, so z = 0 and pdf 0.
    let w = warp::sample_cosine_hemisphere(DVec2::new(0.0, 0.5));
    assert!(warp::cosine_hemisphere_pdf(w.z) > 0.0, "{w}");
    for u in boundary_u() {
        let w = warp::sample_cosine_hemisphere(u);
        assert_unit(w, "cosine", u);
        assert_above_horizon(w, "cosine", u);
        let pdf = warp::cosine_hemisphere_pdf(w.z);
        assert!(pdf > 0.0 && pdf.is_finite(), "cosine at {u}: pdf {pdf}");
    }
}

#[test]
fn uniform_hemisphere_warp_at_u_x_zero_samples_above_the_horizon() {
    for u in boundary_u() {
        let w = warp::sample_uniform_hemisphere(u);
        assert_unit(w, "hemisphere", u);
        assert_above_horizon(w, "hemisphere", u);
    }
}

#[test]
fn uniform_sphere_warp_is_unit_at_every_boundary_u() {
    for u in boundary_u() {
        assert_unit(warp::sample_uniform_sphere(u), "sphere", u);
    }
}

#[test]
fn cone_warp_at_every_boundary_u_stays_inside_its_cone() {
    for max in [2.0, 1.0, 0.3, 1e-10, 5e-19, 1e-300] {
        let pdf = warp::uniform_cone_pdf(max);
        assert!(pdf > 0.0 && pdf.is_finite(), "cone {max}: pdf {pdf}");
        for u in boundary_u() {
            let w = warp::sample_uniform_cone(u, max);
            assert_unit(w, "cone", u);
            let t = warp::one_minus_cos_theta(w);
            assert!(
                t <= max,
                "cone {max} at {u}: 1 - cos theta = {t} outside the cone"
            );
        }
    }
}

#[test]
fn concentric_disk_at_every_boundary_u_stays_in_the_disk() {
    for u in boundary_u() {
        let p = warp::sample_uniform_disk_concentric(u);
        assert!(
            p.is_finite() && p.length_squared() <= 1.0,
            "disk at {u}: {p}"
        );
        let back = warp::invert_uniform_disk_concentric_sample(p);
        assert!(
            back.cmpge(DVec2::ZERO).all() && back.cmplt(DVec2::ONE).all(),
            "{back}"
        );
    }
}

#[test]
fn parallelogram_warp_at_every_boundary_u_stays_on_the_parallelogram() {
    let (q, e1, e2) = (
        DVec3::new(1.0, 2.0, 3.0),
        DVec3::new(0.5, 0.1, 0.0),
        DVec3::new(0.2, -1.0, 0.3),
    );
    let pdf = warp::parallelogram_pdf(e1, e2);
    assert!(pdf > 0.0 && pdf.is_finite());
    for u in boundary_u() {
        let p = warp::sample_parallelogram(u, q, e1, e2);
        let st = warp::invert_parallelogram_sample(p, q, e1, e2);
        assert!(
            p.is_finite() && (st - u).abs().max_element() < 1e-12,
            "{u}: {st}"
        );
    }
}

#[test]
fn spherical_rectangle_at_every_boundary_u_gives_a_point_of_the_rectangle() {
    let cases = [
        (
            DVec3::new(0.3, 0.2, 1.5),
            DVec3::new(-1.0, -0.5, 0.0),
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(0.0, 1.5, 0.0),
        ),
        (
            DVec3::ZERO,
            DVec3::new(-1.0, -1.0, -1.0),
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(0.0, 2.0, 0.0),
        ),
        (DVec3::new(5.0, 0.0, 1e-3), DVec3::ZERO, DVec3::X, DVec3::Y),
        (DVec3::new(0.5, 0.5, 1e6), DVec3::ZERO, DVec3::X, DVec3::Y),
    ];
    for (origin, q, ex, ey) in cases {
        let r = SphericalRectangle::new(origin, q, ex, ey).unwrap();
        assert!(
            r.pdf() > 0.0 && r.pdf().is_finite(),
            "solid angle {}",
            r.solid_angle()
        );
        for u in boundary_u() {
            let p = r.sample(u);
            assert!(p.is_finite(), "rectangle from {origin} at {u}: {p}");
            let st = warp::invert_parallelogram_sample(p, q, ex, ey);
            let tol = 1e-9;
            assert!(
                st.cmpge(DVec2::splat(-tol)).all() && st.cmple(DVec2::splat(1.0 + tol)).all(),
                "rectangle from {origin} at {u}: (s, t) = {st}"
            );
            assert_unit(r.sample_direction(u), "rectangle direction", u);
            let back = r.invert(p);
            assert!(back.is_finite(), "{back}");
        }
    }
}
