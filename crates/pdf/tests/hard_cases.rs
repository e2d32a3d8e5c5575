//! The hard cases of the team's testing guide (TESTING.md) for directions, orthonormal bases, sphere and quad
//! lights, the cosine and mixture pdfs, and light lists: each a named test.

use glam::{DVec2, DVec3};
use rand::{Rng, RngCore, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use rtl_pdf::chi2::{ChiSquareTest, ParallelogramDomain};
use rtl_pdf::warp;
use rtl_pdf::{
    CosinePdf, HemispherePdf, HittablePdf, MIN_CONE_SIN2, MixtureError, MixturePdf, Onb, Pdf,
    QuadTarget, Selection, SelectionError, ShapeSampler, SpherePdf, SphereTarget, SphereView,
};
use std::f64::consts::{PI, TAU};

fn rng(seed: u64) -> Xoshiro256PlusPlus {
    Xoshiro256PlusPlus::seed_from_u64(seed)
}

fn assert_unit(d: DVec3, what: &str) {
    assert!(d.is_finite(), "{what}: {d} is not finite");
    assert!(
        (d.length() - 1.0).abs() < 1e-12,
        "{what}: |{d}| = {}",
        d.length()
    );
}

/// A generator that always returns the same bits: all zeros gives `u = 0`, all ones `u = 1 - 2^-53`.
struct ConstRng(u64);

impl RngCore for ConstRng {
    fn next_u32(&mut self) -> u32 {
        self.0 as u32
    }
    fn next_u64(&mut self) -> u64 {
        self.0
    }
    fn fill_bytes(&mut self, dst: &mut [u8]) {
        dst.fill(self.0 as u8)
    }
}

// ---------------------------------------------------------------- ONB

fn assert_onb(w: DVec3) {
    let b = Onb::new(w);
    let (u, v, w) = (b.u(), b.v(), b.w());
    for (name, x) in [("u", u), ("v", v), ("w", w)] {
        assert!(
            (x.length() - 1.0).abs() < 1e-12,
            "onb of {w}: |{name}| = {}",
            x.length()
        );
    }
    assert!(
        u.dot(v).abs() < 1e-12 && u.dot(w).abs() < 1e-12 && v.dot(w).abs() < 1e-12,
        "onb of {w}: not orthogonal"
    );
    assert!(
        (u.cross(v) - w).length() < 1e-12,
        "onb of {w}: u x v = {} (left-handed?)",
        u.cross(v)
    );
    let local = DVec3::new(0.3, -0.7, 0.2);
    assert!(
        (b.to_local(b.transform(local)) - local).length() < 1e-12,
        "onb of {w}: to_local does not undo transform"
    );
}

#[test]
fn onb_on_the_six_axes() {
    for w in [
        DVec3::X,
        -DVec3::X,
        DVec3::Y,
        -DVec3::Y,
        DVec3::Z,
        -DVec3::Z,
    ] {
        assert_onb(w);
    }
    // -0.0 in z picks the other branch of the sign
    assert_onb(DVec3::new(1.0, 0.0, -0.0));
    assert_onb(DVec3::new(0.0, -1.0, -0.0));
}

#[test]
fn onb_nearly_minus_z_f32_case() {
    // the case that breaks Frisvad's 2012 construction in f32 (Duff et al. 2017, figure 1)
    assert_onb(DVec3::new(0.000_385_273_16, 0.000_384_600_16, -0.999_999_880_79).normalize());
    assert_onb(DVec3::new(1e-9, -1e-9, -1.0).normalize());
    assert_onb(DVec3::new(-1e-300, 0.0, 1.0).normalize());
}

#[test]
fn onb_of_1000_random_directions() {
    let mut r = rng(100);
    for _ in 0..1000 {
        assert_onb(warp::sample_uniform_sphere(DVec2::new(
            r.random(),
            r.random(),
        )));
    }
}

// ---------------------------------------------------------------- directions

#[test]
fn directions_sphere_and_cosine_pdfs_at_u_zero_and_u_max_are_unit() {
    let n = DVec3::new(0.0, 0.6, -0.8);
    for bits in [0u64, u64::MAX, 1, 1 << 11] {
        let mut r = ConstRng(bits);
        let what = format!("rng bits {bits:#x}");
        assert_unit(SpherePdf.generate(&mut r), &format!("sphere, {what}"));
        let d = HemispherePdf::new(n).generate(&mut r);
        assert_unit(d, &format!("hemisphere, {what}"));
        assert!(d.dot(n) >= -1e-15, "hemisphere below its horizon, {what}");
        let d = CosinePdf::new(n).generate(&mut r);
        assert_unit(d, &format!("cosine, {what}"));
        assert!(d.dot(n) >= -1e-15, "cosine below its horizon, {what}");
        let s = [SphereTarget::new(DVec3::new(0.0, 0.0, 1e9), 1.0)];
        assert_unit(
            HittablePdf::new(DVec3::ZERO, &s).unwrap().generate(&mut r),
            &format!("far sphere cone, {what}"),
        );
    }
}

#[test]
fn directions_tiny_inputs_never_underflow() {
    // u just above 0 (tiny "rejection-sized" inputs) and the largest u below 1
    let tiny = [f64::MIN_POSITIVE, 1e-300, 5e-324, 1e-17];
    for &a in &tiny {
        for u in [
            DVec2::new(a, a),
            DVec2::new(a, 0.5),
            DVec2::new(0.5, a),
            DVec2::new(1.0 - f64::EPSILON / 2.0, a),
        ] {
            assert_unit(warp::sample_uniform_sphere(u), "sphere");
            let c = warp::sample_cosine_hemisphere(u);
            assert_unit(c, "cosine");
            assert!(c.z >= 0.0);
            let h = warp::sample_uniform_hemisphere(u);
            assert_unit(h, "hemisphere");
            assert!(h.z >= 0.0);
        }
    }
}

// ---------------------------------------------------------------- sphere light

#[test]
fn sphere_light_from_inside_on_and_just_above() {
    let s = SphereTarget::new(DVec3::new(0.0, 0.0, 0.0), 1.0);
    let cases = [
        ("inside", DVec3::new(0.3, -0.2, 0.1)),
        ("centre", DVec3::ZERO),
        ("exactly on", DVec3::new(1.0, 0.0, 0.0)),
        ("1e-4 above", DVec3::new(1.0 + 1e-4, 0.0, 0.0)),
    ];
    let mut r = rng(101);
    for (name, o) in cases {
        let n = 100_000;
        let mut positive = 0;
        for _ in 0..n {
            let d = s.random(o, &mut r);
            assert_unit(d, name);
            let p = s.pdf_value(o, d);
            assert!(p.is_finite() && p >= 0.0, "{name}: pdf {p}");
            positive += (p > 0.0) as usize;
        }
        // fixed directions too, including away from the sphere
        for d in [
            DVec3::X,
            -DVec3::X,
            DVec3::Y,
            DVec3::new(-1.0, 1.0, 0.0).normalize(),
        ] {
            let p = s.pdf_value(o, d);
            assert!(p.is_finite() && p >= 0.0, "{name}: pdf {p} towards {d}");
        }
        assert!(
            positive as f64 >= 0.999 * n as f64,
            "{name}: only {positive} of {n} directions have pdf > 0"
        );
    }
}

#[test]
fn sphere_light_far_away_solid_angle_without_cancellation() {
    for d in [1e2f64, 1e4, 1e6, 1e9] {
        let o = DVec3::new(0.3, -0.4, 0.0);
        let s = SphereTarget::new(o + DVec3::new(0.0, 0.0, d), 1.0);
        // exact: 2 pi (1 - sqrt(1 - x)), x = 1/d^2, by its series x/2 + x^2/8 + x^3/16 + 5 x^4 / 128
        let x = 1.0 / (d * d);
        let exact = TAU * (x / 2.0 + x * x / 8.0 + x * x * x / 16.0 + 5.0 * x.powi(4) / 128.0);
        // the solid angle of the cone sampled: 2 pi (1 - cos theta_max)
        let SphereView::Cone {
            one_minus_cos_max, ..
        } = s.view(o)
        else {
            panic!("outside the sphere")
        };
        let got = TAU * one_minus_cos_max;
        assert!(
            ((got - exact) / exact).abs() < 1e-6,
            "d = {d}: solid angle {got} vs {exact}"
        );
        // the naive formula cancels: at 1e9 it gives 0
        if d >= 1e9 {
            assert_eq!(TAU * (1.0 - (1.0 - x).sqrt()), 0.0);
        }
        let mut r = rng(102);
        for _ in 0..1000 {
            let dir = s.random(o, &mut r);
            assert_unit(dir, "far sphere");
            let p = s.pdf_value(o, dir);
            assert!(p.is_finite() && p > 0.0, "d = {d}: pdf {p}");
            assert!(((p - 1.0 / exact) * exact).abs() < 1e-6);
        }
    }
}

/// A sphere more than 1.3e154 away (where `|c - o|^2` overflows) or less than 1.5e-154 across
/// (where `r^2` leaves the normal range) is the same cone as the scene scaled to ordinary sizes:
/// the axis was the zero vector (a panic in `Onb::new` in debug builds, no sample in release) and
/// a tiny scene's `r^2 / d^2` was computed from subnormals (a 2e-3 wrong density, or none).
#[test]
fn sphere_light_beyond_the_squares_of_f64_is_the_scaled_cone() {
    // (origin, centre, radius) at ordinary scale, and the factor each is seen at
    let ordinary = [
        (DVec3::new(0.3, -0.4, 0.2), DVec3::new(1.0, 2.0, 1e5), 1.0),
        (DVec3::new(1e-10, 0.0, 0.0), DVec3::new(0.0, 0.0, 1.0), 0.1),
        (DVec3::new(0.5, 0.5, 0.5), DVec3::new(-3.0, 2.0, 4.0), 2.0),
    ];
    let top = 1.0 - f64::EPSILON / 2.0;
    let us = [
        DVec2::ZERO,
        DVec2::new(0.3, 0.7),
        DVec2::new(top, 0.25),
        DVec2::new(top, top),
    ];
    for (o, c, r) in ordinary {
        let plain = SphereTarget::new(c, r);
        for k in [1e150, 1e-160, 1e-300] {
            let scaled = SphereTarget::new(c * k, r * k);
            let what = format!("scale {k:e}, centre {c}, radius {r}");
            for u in us {
                let want = plain.sample(o, u).unwrap();
                let got = scaled
                    .sample(o * k, u)
                    .unwrap_or_else(|| panic!("{what}: no sample"));
                assert_unit(got.direction, &what);
                assert!(
                    (got.direction - want.direction).length() < 1e-12,
                    "{what} at {u}: {} vs {}",
                    got.direction,
                    want.direction
                );
                assert!(
                    (got.pdf - want.pdf).abs() <= 1e-12 * want.pdf,
                    "{what} at {u}: pdf {} vs {}",
                    got.pdf,
                    want.pdf
                );
                let value = scaled.pdf(o * k, got.direction);
                assert!(
                    (value - got.pdf).abs() <= 1e-12 * got.pdf,
                    "{what} at {u}: pdf {value} of a sample that carries {}",
                    got.pdf
                );
            }
        }
    }
}

/// A sphere so small that its density overflows (radius 1e-160 seen from 1): `sample` gives no
/// direction, so `pdf` must be 0 for every direction, also straight at its centre (it was `inf`).
/// (Below the floor of [`sphere_light_at_the_resolution_of_directions`] too, which says no first.)
#[test]
fn sphere_light_too_small_to_weigh_has_pdf_zero_where_it_gives_no_sample() {
    for r in [1e-160, 1e-170, 0.0] {
        let s = SphereTarget::new(DVec3::Z, r);
        for u in [DVec2::ZERO, DVec2::splat(0.5)] {
            assert!(s.sample(DVec3::ZERO, u).is_none(), "radius {r}");
        }
        for d in [DVec3::Z, DVec3::new(1e-170, 0.0, 1.0), -DVec3::Z] {
            assert_eq!(s.pdf(DVec3::ZERO, d), 0.0, "radius {r} towards {d}");
        }
        let list = [s];
        let h = HittablePdf::new(DVec3::ZERO, &list).unwrap();
        assert_eq!(h.pdf(DVec3::Z), 0.0);
        assert!(h.sample(DVec2::ZERO).is_none());
    }
}

/// The floor of the cones sampled, `MIN_CONE_SIN2` (`sin theta_max = 2^-32`): a sphere just wider
/// is sampled, and its samples lie in their cone (rounded directions fall outside about
/// `3.5e-17 / theta` of the time, 1.5e-7 here); one just narrower gives no sample and density 0
/// (it gave samples its own density called misses: every one of them below about 4e-17 rad). At
/// every scale of the scene, as the floor is a ratio.
#[test]
fn sphere_light_at_the_resolution_of_directions() {
    assert_eq!(MIN_CONE_SIN2, 2f64.powi(-64));
    let axis = DVec3::new(0.48, 0.6, -0.64);
    for scale in [1.0, 1e-150, 1e12, 1e160] {
        let o = DVec3::new(0.3, -0.2, 0.1) * scale;
        let c = o + axis * 3.0 * scale;
        let (wider, narrower) = (2f64.powf(-31.9), 2f64.powf(-32.1));
        let s = SphereTarget::new(c, 3.0 * scale * wider);
        let mut r = rng(104);
        for _ in 0..10_000 {
            let d = s.sample(o, DVec2::new(r.random(), r.random())).unwrap();
            assert_eq!(s.pdf(o, d.direction), d.pdf, "scale {scale:e}");
        }
        let s = SphereTarget::new(c, 3.0 * scale * narrower);
        for u in [
            DVec2::ZERO,
            DVec2::splat(0.5),
            DVec2::splat(1.0 - f64::EPSILON / 2.0),
        ] {
            assert!(s.sample(o, u).is_none(), "scale {scale:e}");
        }
        assert_eq!(s.pdf(o, axis), 0.0, "scale {scale:e}");
    }
}

// ---------------------------------------------------------------- quad light

fn unit_quad() -> QuadTarget {
    QuadTarget::new(
        DVec3::new(-1.0, -1.0, 0.0),
        DVec3::new(2.0, 0.0, 0.0),
        DVec3::new(0.0, 2.0, 0.0),
    )
}

#[test]
fn quad_light_origin_in_the_plane_is_a_miss() {
    let mut r = rng(103);
    for spherical in [false, true] {
        let quad = unit_quad().with_spherical_rectangles(spherical);
        for o in [
            DVec3::new(3.0, 0.2, 0.0),
            DVec3::new(0.3, 0.2, 0.0),
            DVec3::new(-1.0, -1.0, 0.0),
            DVec3::new(1e6, 0.0, 0.0),
        ] {
            for target in [
                DVec3::ZERO,
                DVec3::new(0.9, 0.9, 0.0),
                DVec3::new(-0.5, 0.7, 0.0),
            ] {
                let d = (target - o).normalize_or(DVec3::X);
                assert_eq!(quad.pdf_value(o, d), 0.0, "from {o} towards {target}");
            }
            for _ in 0..1000 {
                let d = quad.random(o, &mut r);
                assert!(d.is_finite(), "from {o}: {d}");
                assert_eq!(quad.pdf_value(o, d), 0.0, "from {o} along {d}");
            }
        }
    }
}

#[test]
fn quad_light_1e_9_above_the_plane_is_finite() {
    let mut r = rng(104);
    for spherical in [false, true] {
        let quad = unit_quad().with_spherical_rectangles(spherical);
        for o in [
            DVec3::new(3.0, 0.2, 1e-9),
            DVec3::new(0.3, 0.2, 1e-9),
            DVec3::new(0.3, 0.2, -1e-9),
        ] {
            let to_centre = (DVec3::ZERO - o).normalize();
            let p = quad.pdf_value(o, to_centre);
            assert!(
                p.is_finite() && p > 0.0,
                "from {o}: pdf {p} towards the centre"
            );
            for _ in 0..1000 {
                let d = quad.random(o, &mut r);
                assert_unit(d, "just above a quad");
                let p = quad.pdf_value(o, d);
                assert!(p.is_finite() && p >= 0.0, "from {o}: pdf {p}");
            }
        }
    }
}

/// The quads and origins of [`quad_light_samples_on_its_edges_keep_their_density`]: near, far and
/// grazing origins (on both sides: the target is two-sided) of a unit square, the Cornell box's light
/// (far from the coordinates' origin) and a slanted parallelogram; each origin with the factor by
/// which it is ill-conditioned, `distance / height` (at a grazing origin the height, and with it the
/// cosine at the light, is known to a relative error of about `epsilon distance / height`).
fn quads_and_origins() -> Vec<(&'static str, QuadTarget, Vec<DVec3>)> {
    let square = unit_quad();
    let cornell = QuadTarget::new(
        DVec3::new(343.0, 554.0, 332.0),
        DVec3::new(-130.0, 0.0, 0.0),
        DVec3::new(0.0, 0.0, -105.0),
    );
    let slanted = QuadTarget::new(
        DVec3::new(0.3, 1.7, -2.1),
        DVec3::new(1.3, 0.2, 0.1),
        DVec3::new(0.1, -0.7, 0.9),
    );
    let mut out = Vec::new();
    for (name, quad) in [
        ("square", square),
        ("cornell", cornell),
        ("slanted", slanted),
    ] {
        let (q, u, v, n) = (quad.q(), quad.u(), quad.v(), quad.normal());
        let size = u.length().max(v.length());
        let centre = q + 0.5 * (u + v);
        let mut origins = Vec::new();
        for side in [1.0, -1.0] {
            let up = side * n * size;
            // near: above the centre, a corner and an edge, and just above the plane inside
            origins.push(centre + 0.5 * up);
            origins.push(q + 0.01 * up);
            origins.push(q + 0.5 * u + 1e-3 * up);
            origins.push(centre + 1e-6 * up);
            // off to the side, above and beyond the edges
            origins.push(q + 1.7 * u + 0.3 * v + 0.2 * up);
            origins.push(q - 0.8 * u - 0.6 * v + 0.7 * up);
            // far: 1e3 and 1e6 sizes away
            origins.push(centre + 1e3 * up + 300.0 * u);
            origins.push(centre + 1e6 * up);
            // grazing: beyond an edge, at heights of 1e-3 and 1e-6 of the distance
            origins.push(q + 3.0 * u + 0.4 * v + 3e-3 * up);
            origins.push(q - 2.0 * v + 0.5 * u + 2e-6 * up);
            origins.push(q + 1e3 * u + 1e3 * v + 1.0 * up);
        }
        out.push((name, quad, origins));
        if quad.is_rectangle() {
            let sr = quad.with_spherical_rectangles(true);
            let name = if name == "square" {
                "square, spherical rectangles"
            } else {
                "cornell, spherical rectangles"
            };
            let origins = out.last().unwrap().2.clone();
            out.push((name, sr, origins));
        }
    }
    out
}

/// A point sampled on a quad light's edge (`u = 0`, `u = 2^-60`, which rounds onto the edge, or
/// `u = 1 - 2^-53`) is a direction the density must give its own number: the quad's `pdf` of the
/// direction its `sample` returns is positive, finite and the sample's density (to a relative
/// 1e-12 times the origin's condition `distance / height`), or `sample` gives `None` and `pdf` of
/// every direction towards the quad is 0. (Rounding in the ray-quad intersection put such points
/// at alpha = -1e-17, outside, for a density of 0 where the sampler said positive: for 24% of the
/// samples with a coordinate on an edge, drawn from random origins around three quads.)
#[test]
fn quad_light_samples_on_its_edges_keep_their_density() {
    let top = 1.0 - f64::EPSILON / 2.0;
    let us = [0.0, 2f64.powi(-60), 0.5, top];
    let mut checked = 0;
    for (name, quad, origins) in quads_and_origins() {
        let centre = quad.q() + 0.5 * (quad.u() + quad.v());
        let size = quad.u().length() + quad.v().length();
        for o in origins {
            let height = quad.normal().dot(o - quad.q()).abs();
            let condition = ((o - centre).length() + size) / height;
            for ux in us {
                for uy in us {
                    let u = DVec2::new(ux, uy);
                    let Some(s) = quad.sample(o, u) else {
                        let towards = (centre - o).normalize();
                        assert_eq!(
                            quad.pdf(o, towards),
                            0.0,
                            "{name} from {o}: no sample, yet a density"
                        );
                        continue;
                    };
                    assert_unit(s.direction, name);
                    assert!(
                        s.pdf > 0.0 && s.pdf.is_finite(),
                        "{name} from {o} at {u}: {}",
                        s.pdf
                    );
                    let p = quad.pdf(o, s.direction);
                    assert!(
                        p > 0.0 && p.is_finite(),
                        "{name} from {o} at {u}: the sample's density is {}, pdf of its direction {p}",
                        s.pdf
                    );
                    let tol = 1e-12 * condition.max(1.0);
                    assert!(
                        (p - s.pdf).abs() <= tol * s.pdf,
                        "{name} from {o} at {u}: sample {}, pdf {p} (relative {:e} > {tol:e})",
                        s.pdf,
                        (p - s.pdf).abs() / s.pdf
                    );
                    checked += 1;
                }
            }
        }
    }
    assert!(checked > 1000, "only {checked} samples checked");
}

/// The slack that lets a point drawn on an edge count as on the quad is a rounding error wide: from
/// above the middle of a quad (near and far) a direction 1e-12 of an edge outside it is a miss and
/// one 1e-12 inside a hit; only a grazing origin, whose height is known to a relative `epsilon
/// distance / height`, gets more, and never more than `MAX_EDGE_SLACK`.
#[test]
fn quad_light_edge_slack_is_a_rounding_error_wide() {
    let quad = unit_quad();
    let (q, u, v) = (quad.q(), quad.u(), quad.v());
    for o in [DVec3::new(0.1, 0.2, 1.0), DVec3::new(-0.3, 0.4, -50.0)] {
        for (along, across) in [(u, v), (v, u)] {
            for s in [0.0, 0.3, 1.0] {
                for (edge, out) in [(q, -1.0), (q + across, 1.0)] {
                    let at =
                        |offset: f64| (edge + s * along + offset * out * across - o).normalize();
                    assert_eq!(quad.pdf(o, at(1e-12)), 0.0, "from {o}: 1e-12 outside");
                    assert!(quad.pdf(o, at(-1e-12)) > 0.0, "from {o}: 1e-12 inside");
                }
            }
        }
    }
    let reach = |o: DVec3| (o - q).abs().max_element();
    let above = DVec3::new(0.1, 0.2, 1.0);
    let slack = quad.edge_slack(above, reach(above), 1.0, 1.0);
    // (16 epsilon |dual| t (reach + |o| + |q| + |u| + |v| + t) / |h| = 1.5e-14 here)
    assert!(slack > 0.0 && slack < 1e-13, "{slack}");
    let grazing = DVec3::new(5.0, 0.0, 1e-6);
    let slack = quad.edge_slack(grazing, reach(grazing), 1e-6, 5.0);
    assert!(slack > 1e-12 && slack <= rtl_pdf::MAX_EDGE_SLACK, "{slack}");
    let barely = DVec3::new(1e3, 0.0, 1e-10);
    let slack = quad.edge_slack(barely, reach(barely), 1e-10, 1e3);
    assert_eq!(slack, rtl_pdf::MAX_EDGE_SLACK);
}

#[test]
fn quad_light_spherical_rectangles_only_for_rectangles() {
    let slanted = QuadTarget::new(DVec3::ZERO, DVec3::X, DVec3::new(0.5, 1.0, 0.0))
        .with_spherical_rectangles(true);
    assert_eq!(slanted.sampling(), rtl_pdf::QuadSampling::Area);
    assert_eq!(
        unit_quad().with_spherical_rectangles(true).sampling(),
        rtl_pdf::QuadSampling::SphericalRectangle
    );
}

/// The quad target makes its rectangle's frame once (`RectangleFrame`) and only the part that depends
/// on the origin per call: its samples and densities are bit for bit those of a spherical rectangle
/// set up from scratch at each origin, from grazing to far, for an axis-aligned and a tilted
/// rectangle (whose frame is not the axes).
#[test]
fn quad_light_spherical_rectangle_frame_made_once_gives_the_same_numbers() {
    use rtl_pdf::warp::SphericalRectangle;
    let tilted_u = DVec3::new(1.0, 0.5, 0.25);
    let tilted_v = tilted_u.cross(DVec3::new(0.3, -1.0, 0.7)).normalize() * 0.7;
    let cases = [
        (DVec3::new(-0.5, -0.5, 0.0), DVec3::X, DVec3::Y),
        (DVec3::new(2.0, -1.0, 3.0), tilted_u, tilted_v),
    ];
    let mut r = rng(106);
    let mut compared = 0;
    for (q, u, v) in cases {
        let target = QuadTarget::new(q, u, v).with_spherical_rectangles(true);
        assert_eq!(target.sampling(), rtl_pdf::QuadSampling::SphericalRectangle);
        let n = u.cross(v).normalize();
        for i in 0..4000 {
            // heights from grazing (1e-6) to far (1e3), offsets across and beyond the rectangle
            let height =
                10f64.powf(r.random_range(-6.0..3.0)) * if i % 2 == 0 { 1.0 } else { -1.0 };
            let origin =
                q + r.random_range(-2.0..3.0) * u + r.random_range(-2.0..3.0) * v + height * n;
            let uu = DVec2::new(r.random(), r.random());
            let fresh = SphericalRectangle::new(origin, q, u, v).filter(|sr| {
                (rtl_pdf::MIN_SPHERICAL_RECTANGLE_SOLID_ANGLE
                    ..=rtl_pdf::MAX_SPHERICAL_RECTANGLE_SOLID_ANGLE)
                    .contains(&sr.solid_angle())
            });
            let Some(sr) = fresh else { continue };
            let s = target
                .sample(origin, uu)
                .expect("a direction towards the rectangle");
            let d = sr.sample_direction(uu);
            assert_eq!(
                s.direction.to_array().map(f64::to_bits),
                d.to_array().map(f64::to_bits)
            );
            assert_eq!(s.pdf.to_bits(), sr.pdf().to_bits(), "at {origin}");
            assert_eq!(
                target.pdf(origin, d).to_bits(),
                sr.pdf().to_bits(),
                "at {origin}"
            );
            compared += 1;
        }
    }
    assert!(
        compared > 2000,
        "only {compared} origins used spherical rectangles"
    );
}

#[test]
fn quad_light_degenerate_quad_is_never_hit() {
    let q = QuadTarget::new(DVec3::ZERO, DVec3::X, DVec3::X * 2.0);
    let mut r = rng(105);
    let o = DVec3::new(0.0, 0.0, 1.0);
    assert_eq!(q.pdf_value(o, -DVec3::Z), 0.0);
    assert!(q.random(o, &mut r).is_finite());
}

// ---------------------------------------------------------------- cosine pdf

#[test]
fn cosine_pdf_is_exactly_zero_below_the_horizon_and_finite_when_grazing() {
    let n = DVec3::new(0.0, 0.6, 0.8);
    let pdf = CosinePdf::new(n);
    let b = Onb::new(n);
    for cos in [-1.0f64, -0.5, -1e-12, -1e-300, -0.0, 0.0] {
        let sin = (1.0 - cos * cos).sqrt();
        let d = b.transform(DVec3::new(sin, 0.0, cos));
        let v = pdf.value(d);
        if d.dot(n) <= 0.0 {
            assert_eq!(v, 0.0, "cos = {cos}: value {v}");
        }
        assert!(v >= 0.0);
    }
    // grazing but above: a Lambertian's f cos / p is the albedo, finite
    for cos in [1e-300f64, 1e-100, 1e-12, 1e-6] {
        let sin = (1.0 - cos * cos).sqrt();
        let d = b.transform(DVec3::new(sin, 0.0, cos));
        let (v, c) = (pdf.value(d), d.dot(n));
        if c > 0.0 {
            let ratio = (0.5 / PI) * c / v;
            assert!(
                v > 0.0 && ratio.is_finite() && (ratio - 0.5).abs() < 1e-9,
                "cos = {cos}: f cos/p = {ratio}"
            );
        } else {
            assert_eq!(v, 0.0);
        }
    }
}

// ---------------------------------------------------------------- mixture pdf

#[test]
fn mixture_value_is_the_weighted_sum_for_any_weight() {
    let (a, b) = (CosinePdf::new(DVec3::Z), SpherePdf);
    let mut r = rng(106);
    for w in [0.0, 1e-12, 0.25, 0.5, 0.9, 1.0] {
        let m = MixturePdf::with_weight(a, b, w).unwrap();
        for _ in 0..200 {
            let d = warp::sample_uniform_sphere(DVec2::new(r.random(), r.random()));
            let expected = w * a.value(d) + (1.0 - w) * b.value(d);
            assert!(
                (m.value(d) - expected).abs() <= 1e-15 * expected.max(1.0),
                "w = {w}"
            );
        }
        // weight 1: only `a` is sampled, so every direction is above a's horizon
        if w == 1.0 {
            for _ in 0..1000 {
                assert!(m.generate(&mut r).z >= 0.0);
            }
        }
    }
    assert!(
        (MixturePdf::new(a, b).weight() - 0.5).abs() == 0.0,
        "the book's default is 50/50"
    );
    for bad in [-0.1, 1.5, f64::NAN] {
        assert!(matches!(
            MixturePdf::with_weight(a, b, bad),
            Err(MixtureError::BadWeight(_))
        ));
    }
}

/// `pdf_given_b` with the second part's own density is `pdf`, bit for bit, for any weight (0 and 1
/// included) and directions above, below and along the cosine lobe's horizon; given a wrong density
/// for `b` it differs (so the comparison can fail).
#[test]
fn mixture_pdf_given_the_second_density_is_the_same_number() {
    let mut r = rng(107);
    let n = DVec3::new(0.2, 0.9, -0.4).normalize();
    let lights = [SphereTarget::new(DVec3::new(0.0, 3.0, 0.0), 1.0)];
    let towards = HittablePdf::new(DVec3::ZERO, &lights).unwrap();
    let mut differed = 0;
    for weight in [0.0, 0.25, 0.5, 0.9, 1.0] {
        let m = MixturePdf::with_weight(towards, CosinePdf::new(n), weight).unwrap();
        for i in 0..2000 {
            let d = if i % 10 == 0 {
                // along the horizon of the cosine lobe
                Onb::new(n).transform(DVec3::new(1.0, 0.0, 0.0))
            } else {
                warp::sample_uniform_sphere(DVec2::new(r.random(), r.random()))
            };
            let b = CosinePdf::new(n).pdf(d);
            assert_eq!(
                m.pdf_given_b(d, b).to_bits(),
                m.pdf(d).to_bits(),
                "w {weight}, {d}"
            );
            differed += (m.pdf_given_b(d, b * 1.5 + 0.01) != m.pdf(d)) as usize;
        }
    }
    assert!(
        differed > 4000,
        "a wrong density for b went unnoticed: {differed}"
    );
}

/// A part of weight 0 is never sampled, for any `u.x` the mixture may be handed: `u.x = NaN` or
/// `1` (outside `[0, 1)`) used to choose the second part of a weight-1 mixture, and report the
/// first part's density there, 0 where the first part does not reach.
#[test]
fn mixture_never_samples_a_part_of_weight_zero_even_for_u_nan_or_one() {
    let quad = [QuadTarget::new(
        DVec3::new(-1.0, -1.0, 3.0),
        DVec3::X * 2.0,
        DVec3::Y * 2.0,
    )];
    let towards = HittablePdf::new(DVec3::ZERO, &quad).unwrap();
    let away = CosinePdf::new(-DVec3::Z); // never towards the quad
    for ux in [f64::NAN, 1.0, 2.0, f64::INFINITY, -1.0, -0.0] {
        let u = DVec2::new(ux, 0.5);
        for (w, a_only) in [(1.0, true), (0.0, false)] {
            let m = MixturePdf::with_weight(towards, away, w).unwrap();
            let s = m.sample(u).unwrap();
            assert!(
                s.pdf > 0.0 && s.pdf.is_finite(),
                "weight {w}, u.x = {ux}: pdf {}",
                s.pdf
            );
            assert_eq!(s.pdf, m.pdf(s.direction), "weight {w}, u.x = {ux}");
            assert_eq!(s.direction.z > 0.0, a_only, "weight {w}, u.x = {ux}");
        }
        // and as the choice among parts takes it: NaN as 0, the rest below 1
        let m = MixturePdf::new(towards, away);
        let clamped = if ux.is_nan() || ux <= 0.0 {
            0.0
        } else {
            1.0 - f64::EPSILON / 2.0
        };
        let want = m.sample(DVec2::new(clamped, 0.5)).unwrap();
        assert_eq!(m.sample(u).unwrap(), want, "u.x = {ux}");
    }
}

#[test]
fn mixture_of_a_part_with_weight_zero_never_evaluates_it() {
    // a part whose value is NaN must not poison a mixture that never samples it
    struct Broken;
    impl Pdf for Broken {
        fn pdf(&self, _: DVec3) -> f64 {
            f64::NAN
        }
        fn sample(&self, _: DVec2) -> Option<rtl_pdf::DirectionSample> {
            rtl_pdf::DirectionSample::new(DVec3::X, 1.0)
        }
    }
    let m = MixturePdf::with_weight(Broken, SpherePdf, 0.0).unwrap();
    assert_eq!(m.value(DVec3::Z), 1.0 / (4.0 * PI));
}

// ---------------------------------------------------------------- light list

#[test]
fn light_list_empty_is_a_clear_none_or_error() {
    let none: [QuadTarget; 0] = [];
    assert!(HittablePdf::new(DVec3::ZERO, &none).is_none());
    let table = Selection::uniform(1).unwrap();
    assert_eq!(
        HittablePdf::with_selection(DVec3::ZERO, &none, &table).err(),
        Some(SelectionError::Empty)
    );
    assert_eq!(Selection::uniform(0).err(), Some(SelectionError::Empty));
    let one = [unit_quad()];
    let two = Selection::uniform(2).unwrap();
    assert_eq!(
        HittablePdf::with_selection(DVec3::Z, &one, &two).err(),
        Some(SelectionError::LengthMismatch { table: 2, parts: 1 })
    );
    assert_eq!(
        HittablePdf::with_pmf(DVec3::ZERO, &none, &[]).err(),
        Some(SelectionError::Empty)
    );
    assert_eq!(
        HittablePdf::with_pmf(DVec3::Z, &one, &[0.5, 0.5]).err(),
        Some(SelectionError::LengthMismatch { table: 2, parts: 1 })
    );
    // every probability 0 (nothing can contribute from here): no sample, density 0
    let lights = two_quads();
    let nothing = HittablePdf::with_pmf(DVec3::new(0.1, 0.2, 0.0), &lights, &[0.0, 0.0]).unwrap();
    assert!(nothing.sample(DVec2::new(0.3, 0.6)).is_none());
    assert_eq!(nothing.pdf(DVec3::Z), 0.0);
}

#[test]
fn light_list_pmf_per_call_draws_what_the_table_draws() {
    // the same probabilities given per call and tabulated: the same directions and densities
    let lights = two_quads();
    let origin = DVec3::new(0.1, 0.2, 0.0);
    let table = Selection::from_weights(&[1.0, 3.0]).unwrap();
    let tabulated = HittablePdf::with_selection(origin, &lights, &table).unwrap();
    let pmf = [0.25, 0.75];
    let per_call = HittablePdf::with_pmf(origin, &lights, &pmf).unwrap();
    let mut r = rng(108);
    for _ in 0..2000 {
        let u = DVec2::new(r.random(), r.random());
        let (a, b) = (tabulated.sample(u).unwrap(), per_call.sample(u).unwrap());
        assert!((a.direction - b.direction).length() < 1e-12, "u = {u}");
        assert!((a.pdf - b.pdf).abs() <= 1e-12 * a.pdf);
        assert!((tabulated.pdf(a.direction) - per_call.pdf(a.direction)).abs() <= 1e-12 * a.pdf);
    }
    assert_eq!(
        (per_call.pmf(0), per_call.pmf(1), per_call.pmf(2)),
        (0.25, 0.75, 0.0)
    );
    // a shape of probability 0 is never chosen, and its directions have only the others' density
    let only_second = [0.0, 1.0];
    let second = HittablePdf::with_pmf(origin, &lights, &only_second).unwrap();
    for _ in 0..500 {
        let s = second.sample(DVec2::new(r.random(), r.random())).unwrap();
        assert!(lights[1].pdf_value(origin, s.direction) > 0.0);
        assert_eq!(lights[0].pdf_value(origin, s.direction), 0.0);
    }
}

fn two_quads() -> [QuadTarget; 2] {
    [
        QuadTarget::new(
            DVec3::new(-1.9, -0.83, 1.0),
            DVec3::new(1.3, 0.0, 0.0),
            DVec3::new(0.0, 0.9, 0.0),
        ),
        QuadTarget::new(
            DVec3::new(0.55, -0.4, 1.0),
            DVec3::new(1.1, 0.0, 0.0),
            DVec3::new(0.0, 1.7, 0.0),
        ),
    ]
}

#[test]
fn light_list_two_disjoint_quads_value_is_weighted_and_integrates_to_one() {
    let lights = two_quads();
    let origin = DVec3::new(0.1, 0.2, 0.0);
    let table = Selection::from_weights(&[1.0, 3.0]).unwrap();
    let weighted = HittablePdf::with_selection(origin, &lights, &table).unwrap();
    let uniform = HittablePdf::new(origin, &lights).unwrap();
    let mut r = rng(107);
    for _ in 0..2000 {
        let d = weighted.generate(&mut r);
        assert_unit(d, "two quads");
        let (v0, v1) = (
            lights[0].pdf_value(origin, d),
            lights[1].pdf_value(origin, d),
        );
        assert!(v0 == 0.0 || v1 == 0.0, "disjoint quads: one of them is hit");
        assert!((weighted.value(d) - (0.25 * v0 + 0.75 * v1)).abs() <= 1e-15 * weighted.value(d));
        assert!((uniform.value(d) - (0.5 * v0 + 0.5 * v1)).abs() <= 1e-15 * uniform.value(d));
        assert!(weighted.value(d) > 0.0);
    }
    // the integral over all directions is the sum of the integrals over the directions through each
    // quad (they are disjoint, and the density is 0 elsewhere), by quadrature over each quad's (s, t)
    for (name, pdf) in [("weighted", weighted), ("uniform", uniform)] {
        let total: f64 = lights
            .iter()
            .map(|l| {
                let domain = ParallelogramDomain {
                    origin,
                    q: l.q(),
                    e1: l.u(),
                    e2: l.v(),
                };
                let cells = ChiSquareTest::new(8, 8).expected(
                    &domain,
                    |d| pdf.value(d),
                    |_, _| true,
                    1_000_000,
                );
                cells.unwrap().iter().sum::<f64>()
            })
            .sum();
        assert!((total - 1.0).abs() < 1e-9, "{name}: integrates to {total}");
    }
}

// ---------------------------------------------------------------- chosen inputs

#[test]
fn samples_carry_their_own_density_for_chosen_inputs() {
    // u at the corners of the square and on the boundary of every discrete choice: each sample's
    // density is `pdf` of its direction, and the rest of a choice's number is handed on.
    let lights = [
        QuadTarget::new(DVec3::new(-1.0, 2.0, -1.0), DVec3::X * 2.0, DVec3::Z * 2.0),
        QuadTarget::new(DVec3::new(2.0, 1.0, -1.0), DVec3::Z * 2.0, DVec3::Y),
    ];
    let origin = DVec3::new(0.1, 0.0, 0.2);
    let towards = HittablePdf::new(origin, &lights).unwrap();
    let mixture = MixturePdf::with_weight(towards, CosinePdf::new(DVec3::Y), 0.25).unwrap();
    let top = 1.0 - f64::EPSILON / 2.0;
    fn check(what: &str, u: DVec2, pdf: &impl Pdf) {
        let Some(s) = pdf.sample(u) else { return };
        assert_unit(s.direction, what);
        let want = pdf.pdf(s.direction);
        assert!(
            (s.pdf - want).abs() <= 1e-12 * want,
            "{what} at {u}: sample says {}, pdf {want}",
            s.pdf
        );
    }
    for ux in [0.0, 0.125, 0.25, 0.5, 0.625, top] {
        for uy in [0.0, 0.5, top] {
            let u = DVec2::new(ux, uy);
            check("lights", u, &towards);
            check("mixture", u, &mixture);
        }
    }
    // the choice's rest is handed on: u.x = 1/8 < 1/4 picks the lights with u.x' = 1/2, which picks
    // the second quad (u.x'' = 0) ...
    let s = mixture.sample(DVec2::new(0.125, 0.5)).unwrap();
    let direct = lights[1].sample(origin, DVec2::new(0.0, 0.5)).unwrap();
    assert_eq!(s.direction, direct.direction);
    // ... and u.x = 1/4 + 3/8 picks the cosine part with its rest 1/2
    let s = mixture.sample(DVec2::new(0.625, 0.5)).unwrap();
    let cosine = CosinePdf::new(DVec3::Y)
        .sample(DVec2::new(0.5, 0.5))
        .unwrap();
    assert_eq!(s.direction, cosine.direction);
}

#[test]
fn a_mixtures_generate_is_the_direction_its_sample_draws() {
    // `MixturePdf::generate` skips the other part's density, which only the pdf needs: the direction
    // must be the one `sample` draws from the same two numbers, for either part and at the weights'
    // ends.
    let quad = [QuadTarget::new(
        DVec3::new(-1.0, -0.5, 2.0),
        DVec3::new(2.0, 0.0, 0.0),
        DVec3::new(0.0, 1.5, 0.0),
    )];
    let to_quad = HittablePdf::new(DVec3::new(0.1, 0.2, 0.0), &quad).unwrap();
    for w in [0.0, 0.25, 0.5, 1.0] {
        let mixture = MixturePdf::with_weight(to_quad, CosinePdf::new(DVec3::Z), w).unwrap();
        let (mut a, mut b) = (rng(17), rng(17));
        for _ in 0..10_000 {
            let generated = mixture.generate(&mut a);
            let u = DVec2::new(b.random::<f64>(), b.random::<f64>());
            let sampled = mixture.sample(u).map_or(DVec3::ZERO, |s| s.direction);
            assert_eq!(generated, sampled, "weight {w}, u = {u}");
        }
    }
}
