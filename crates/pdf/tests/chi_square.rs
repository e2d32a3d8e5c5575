//! Chi-square goodness-of-fit tests of every warp and every `Pdf` type against its own density
//! (method: the team's testing guide (TESTING.md), module `rtl_pdf::chi2`).
//!
//! Each test draws `N` = 1e5 samples from a fixed seed (the `#[ignore]`d `heavy_` variants 1e6) and
//! rejects below `alpha = 0.01`, Sidak-corrected over every acceptance check in this file, so a
//! correct sampler fails a full run with probability 1%.

use glam::{DVec2, DVec3};
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use rtl_pdf::chi2::{
    Chi2Failure, Chi2Report, ChiSquareTest, ConeDomain, Domain, HemisphereDomain,
    ParallelogramDomain, SphereDomain, sidak_alpha,
};
use rtl_pdf::warp::{self, SphericalRectangle};
use rtl_pdf::{
    CosinePdf, HemispherePdf, HittablePdf, MixtureOfPdfs, MixturePdf, Onb, Pdf, QuadTarget,
    Selection, SpherePdf, SphereTarget, SphereView,
};

const N: usize = 100_000;
const N_HEAVY: usize = 1_000_000;

/// The number of `accept(` calls in this file (checked by `sidak_count_matches_this_file`).
const CHI2_TESTS: usize = 31;

fn alpha() -> f64 {
    sidak_alpha(0.01, CHI2_TESTS)
}

fn accept(name: &str, report: Result<Chi2Report, Chi2Failure>) {
    let r = report.unwrap_or_else(|e| panic!("{name}: failed outright: {e}"));
    eprintln!(
        "{name}: p = {:.4}, statistic {:.1}, {} dof",
        r.p_value, r.statistic, r.dof
    );
    assert!(
        (r.expected_fraction - 1.0).abs() < 1e-3,
        "{name}: the density integrates to {} over its domain",
        r.expected_fraction
    );
    assert!(
        r.p_value >= alpha(),
        "{name}: rejected, p = {:.3e} < {:.3e} (statistic {:.1}, {} dof)",
        r.p_value,
        alpha(),
        r.statistic,
        r.dof
    );
}

fn rng(seed: u64) -> Xoshiro256PlusPlus {
    Xoshiro256PlusPlus::seed_from_u64(seed)
}

fn u2<R: Rng>(rng: &mut R) -> DVec2 {
    DVec2::new(rng.random(), rng.random())
}

fn tilted() -> DVec3 {
    DVec3::new(0.3, -0.5, 0.8).normalize()
}

fn everywhere(_: DVec2, _: DVec2) -> bool {
    true
}

/// For a [`SphereDomain`] about a normal: the cell reaches above the horizon `y = 1/2`.
fn upper_half(_: DVec2, hi: DVec2) -> bool {
    hi.y > 0.5
}

fn frame_z() -> Onb {
    Onb::new(DVec3::Z)
}

// ---------------------------------------------------------------- warps

fn uniform_sphere_warp(n: usize) {
    let mut r = rng(1);
    let t = ChiSquareTest::new(20, 20);
    accept(
        "uniform sphere warp",
        t.run(
            &SphereDomain(frame_z()),
            |_| warp::uniform_sphere_pdf(),
            everywhere,
            n,
            || warp::sample_uniform_sphere(u2(&mut r)),
        ),
    );
}

#[test]
fn chi_square_uniform_sphere_warp() {
    uniform_sphere_warp(N);
}

fn uniform_hemisphere_warp(n: usize) {
    let mut r = rng(2);
    let t = ChiSquareTest::new(20, 20);
    accept(
        "uniform hemisphere warp",
        t.run(
            &HemisphereDomain(frame_z()),
            |_| warp::uniform_hemisphere_pdf(),
            everywhere,
            n,
            || warp::sample_uniform_hemisphere(u2(&mut r)),
        ),
    );
}

#[test]
fn chi_square_uniform_hemisphere_warp() {
    uniform_hemisphere_warp(N);
}

fn cosine_hemisphere_warp(n: usize) {
    let mut r = rng(3);
    let t = ChiSquareTest::new(20, 20);
    accept(
        "cosine hemisphere warp",
        t.run(
            &HemisphereDomain(frame_z()),
            |d| warp::cosine_hemisphere_pdf(d.z),
            everywhere,
            n,
            || warp::sample_cosine_hemisphere(u2(&mut r)),
        ),
    );
}

#[test]
fn chi_square_cosine_hemisphere_warp() {
    cosine_hemisphere_warp(N);
}

fn uniform_cone_warp(n: usize) {
    for (i, omc) in [0.3, 1e-7, 1.7].into_iter().enumerate() {
        let mut r = rng(4 + i as u64);
        let t = ChiSquareTest::new(20, 20);
        let domain = ConeDomain {
            frame: frame_z(),
            one_minus_cos_max: omc,
        };
        let report = t.run(
            &domain,
            |_| warp::uniform_cone_pdf(omc),
            everywhere,
            n,
            || warp::sample_uniform_cone(u2(&mut r), omc),
        );
        match i {
            0 => accept("uniform cone warp, 1 - cos = 0.3", report),
            1 => accept("uniform cone warp, 1 - cos = 1e-7", report),
            _ => accept("uniform cone warp, 1 - cos = 1.7", report),
        }
    }
}

#[test]
fn chi_square_uniform_cone_warp() {
    uniform_cone_warp(N);
}

/// A parallelogram (not a rectangle) 1.5 above the origin.
fn slanted_quad() -> (DVec3, DVec3, DVec3, DVec3) {
    let origin = DVec3::new(0.2, -0.1, 0.0);
    let q = DVec3::new(-1.0, -0.7, 1.5);
    let e1 = DVec3::new(2.0, 0.3, 0.4);
    let e2 = DVec3::new(0.6, 1.4, -0.2);
    (origin, q, e1, e2)
}

fn quad_area_warp(n: usize) {
    let (origin, q, e1, e2) = slanted_quad();
    let normal = e1.cross(e2).normalize();
    let mut r = rng(7);
    let t = ChiSquareTest::new(20, 20);
    let domain = ParallelogramDomain { origin, q, e1, e2 };
    let density = |d: DVec3| {
        // the point of the parallelogram in direction d
        let st = domain.to_square(d).expect("direction through the quad");
        let p = warp::sample_parallelogram(st, q, e1, e2);
        warp::area_to_solid_angle(warp::parallelogram_pdf(e1, e2), origin, p, normal)
    };
    accept(
        "quad area warp",
        t.run(&domain, density, everywhere, n, || {
            (warp::sample_parallelogram(u2(&mut r), q, e1, e2) - origin).normalize()
        }),
    );
}

#[test]
fn chi_square_quad_area_warp() {
    quad_area_warp(N);
}

fn spherical_rectangle_warp(n: usize) {
    // near (large solid angle, strongly non-uniform in area), and off to the side
    let cases = [
        (DVec3::new(0.1, 0.2, 0.3), DVec3::new(-1.0, -0.5, 0.0)),
        (DVec3::new(3.0, -2.0, 0.5), DVec3::new(-1.0, -0.5, 0.0)),
    ];
    let (ex, ey) = (DVec3::new(2.0, 0.0, 0.0), DVec3::new(0.0, 1.5, 0.0));
    for (i, (origin, q)) in cases.into_iter().enumerate() {
        let sr = SphericalRectangle::new(origin, q, ex, ey).unwrap();
        let mut r = rng(8 + i as u64);
        let t = ChiSquareTest::new(20, 20);
        let domain = ParallelogramDomain {
            origin,
            q,
            e1: ex,
            e2: ey,
        };
        let report = t.run(
            &domain,
            |_| sr.pdf(),
            everywhere,
            n,
            || sr.sample_direction(u2(&mut r)),
        );
        if i == 0 {
            accept("spherical rectangle warp, near", report);
        } else {
            accept("spherical rectangle warp, to the side", report);
        }
    }
}

#[test]
fn chi_square_spherical_rectangle_warp() {
    spherical_rectangle_warp(N);
}

// ANCHOR: factor_two_bug
/// The checker must catch a wrong sampler: the cosine warp of the book's first editions multiplied
/// `x` and `y` by 2 (`x = cos(phi) 2 sqrt(r2)`, fixed in RayTracing/TheRestOfYourLife#70). Even with
/// the result normalised, its directions are not distributed as `cos theta / pi`.
#[test]
fn chi_square_rejects_the_books_old_factor_two_cosine_warp() {
    let mut r = rng(10);
    let t = ChiSquareTest::new(20, 20);
    let report = t
        .run(
            &HemisphereDomain(frame_z()),
            |d| warp::cosine_hemisphere_pdf(d.z),
            everywhere,
            N,
            || {
                let (r1, r2): (f64, f64) = (r.random(), r.random());
                let phi = std::f64::consts::TAU * r1;
                let x = phi.cos() * 2.0 * r2.sqrt();
                let y = phi.sin() * 2.0 * r2.sqrt();
                let z = (1.0 - r2).sqrt();
                DVec3::new(x, y, z).normalize()
            },
        )
        .expect("a well-formed run");
    assert!(
        report.p_value < alpha(),
        "the buggy warp passed: p = {}",
        report.p_value
    );
    assert!(
        report.p_value < 1e-100,
        "the buggy warp is rejected overwhelmingly: p = {}",
        report.p_value
    );
}
// ANCHOR_END: factor_two_bug

/// And a subtler one: a cone sampled as the book's chapter 12 does but with `cos theta_max` computed
/// by `sqrt(1 - r^2/d^2)` while the sampler used a cone 10% too wide.
#[test]
fn chi_square_rejects_a_cone_sampled_ten_percent_too_wide() {
    let omc = 0.2;
    let mut r = rng(11);
    let t = ChiSquareTest::new(20, 20);
    let domain = ConeDomain {
        frame: frame_z(),
        one_minus_cos_max: omc,
    };
    let failure = t.run(
        &domain,
        |_| warp::uniform_cone_pdf(omc),
        everywhere,
        N,
        || warp::sample_uniform_cone(u2(&mut r), omc * 1.1),
    );
    assert!(
        matches!(failure, Err(Chi2Failure::OutsideDomain { .. })),
        "samples outside the cone must fail at once: {failure:?}"
    );
}

/// The area-to-solid-angle conversion without `cos theta_light` (a classic slip): rejected.
#[test]
fn chi_square_rejects_a_quad_pdf_without_the_light_cosine() {
    let (origin, q, e1, e2) = slanted_quad();
    let mut r = rng(12);
    let domain = ParallelogramDomain { origin, q, e1, e2 };
    let area = e1.cross(e2).length();
    // normalised so it still integrates to 1: only its shape is wrong
    let wrong = |d: DVec3| {
        let st = domain.to_square(d).unwrap();
        let p = warp::sample_parallelogram(st, q, e1, e2);
        (p - origin).length_squared() / area
    };
    let t = ChiSquareTest::new(20, 20);
    let total: f64 = t
        .expected(&domain, wrong, everywhere, N)
        .unwrap()
        .iter()
        .sum();
    let report = t
        .run(
            &domain,
            |d| wrong(d) / total,
            everywhere,
            N,
            || (warp::sample_parallelogram(u2(&mut r), q, e1, e2) - origin).normalize(),
        )
        .unwrap();
    assert!(
        report.p_value < alpha(),
        "a pdf without the cosine passed: p = {}",
        report.p_value
    );
}

// ---------------------------------------------------------------- Pdf types

fn sphere_pdf(n: usize) {
    let mut r = rng(20);
    let t = ChiSquareTest::new(20, 20);
    accept(
        "SpherePdf",
        t.run(
            &SphereDomain(Onb::new(tilted())),
            |d| SpherePdf.value(d),
            everywhere,
            n,
            || SpherePdf.generate(&mut r),
        ),
    );
}

#[test]
fn chi_square_sphere_pdf() {
    sphere_pdf(N);
}

fn hemisphere_pdf(n: usize) {
    let pdf = HemispherePdf::new(tilted());
    let mut r = rng(21);
    // 21 rows, so the horizon y = 1/2 runs through the middle of a row of cells
    let t = ChiSquareTest::new(20, 21);
    accept(
        "HemispherePdf",
        t.run(
            &SphereDomain(Onb::new(tilted())),
            |d| pdf.value(d),
            upper_half,
            n,
            || pdf.generate(&mut r),
        ),
    );
}

#[test]
fn chi_square_hemisphere_pdf() {
    hemisphere_pdf(N);
}

fn cosine_pdf(n: usize) {
    let pdf = CosinePdf::new(tilted());
    let mut r = rng(22);
    let t = ChiSquareTest::new(20, 21);
    accept(
        "CosinePdf",
        t.run(
            &SphereDomain(Onb::new(tilted())),
            |d| pdf.value(d),
            upper_half,
            n,
            || pdf.generate(&mut r),
        ),
    );
}

#[test]
fn chi_square_cosine_pdf() {
    cosine_pdf(N);
}

fn mixture_pdf_cosine_and_sphere(n: usize) {
    let pdf = MixturePdf::new(CosinePdf::new(tilted()), SpherePdf);
    let mut r = rng(23);
    let t = ChiSquareTest::new(20, 21);
    accept(
        "MixturePdf(cosine, sphere)",
        t.run(
            &SphereDomain(Onb::new(tilted())),
            |d| pdf.value(d),
            everywhere,
            n,
            || pdf.generate(&mut r),
        ),
    );
}

#[test]
fn chi_square_mixture_pdf_cosine_and_sphere() {
    mixture_pdf_cosine_and_sphere(N);
}

fn mixture_pdf_cosine_and_sphere_light(n: usize) {
    // a floor point under a sphere light: the cone's edge cuts across cells (adaptive quadrature)
    let light = [SphereTarget::new(DVec3::new(0.5, 0.4, 2.0), 0.8)];
    let towards = HittablePdf::new(DVec3::ZERO, &light).unwrap();
    let pdf = MixturePdf::with_weight(towards, CosinePdf::new(DVec3::Z), 0.3).unwrap();
    let mut r = rng(24);
    let t = ChiSquareTest::new(24, 21);
    accept(
        "MixturePdf(sphere light, cosine) 30/70",
        t.run(
            &SphereDomain(frame_z()),
            |d| pdf.value(d),
            upper_half,
            n,
            || pdf.generate(&mut r),
        ),
    );
}

#[test]
fn chi_square_mixture_pdf_sphere_light_and_cosine_weighted() {
    mixture_pdf_cosine_and_sphere_light(N);
}

fn mixture_of_three_pdfs(n: usize) {
    #[derive(Clone, Copy)]
    enum Part {
        Cosine(CosinePdf),
        Sphere(SpherePdf),
        Hemisphere(HemispherePdf),
    }
    impl Pdf for Part {
        fn pdf(&self, d: DVec3) -> f64 {
            match self {
                Part::Cosine(p) => p.pdf(d),
                Part::Sphere(p) => p.pdf(d),
                Part::Hemisphere(p) => p.pdf(d),
            }
        }
        fn sample(&self, u: DVec2) -> Option<rtl_pdf::DirectionSample> {
            match self {
                Part::Cosine(p) => p.sample(u),
                Part::Sphere(p) => p.sample(u),
                Part::Hemisphere(p) => p.sample(u),
            }
        }
    }
    let parts = [
        Part::Cosine(CosinePdf::new(DVec3::Z)),
        Part::Sphere(SpherePdf),
        Part::Hemisphere(HemispherePdf::new(-DVec3::X)),
    ];
    let table = Selection::from_weights(&[0.5, 0.2, 0.3]).unwrap();
    let pdf = MixtureOfPdfs::new(&parts, &table).unwrap();
    let mut r = rng(25);
    let t = ChiSquareTest::new(21, 21);
    accept(
        "MixtureOfPdfs(cosine, sphere, hemisphere)",
        t.run(
            &SphereDomain(frame_z()),
            |d| pdf.value(d),
            everywhere,
            n,
            || pdf.generate(&mut r),
        ),
    );
}

#[test]
fn chi_square_mixture_of_three_pdfs() {
    mixture_of_three_pdfs(N);
}

// ---------------------------------------------------------------- HittablePdf towards a sphere

/// Towards a sphere from `origin`, binned in the cone it subtends (or the whole sphere from inside).
fn hittable_sphere(
    name: &str,
    origin: DVec3,
    seed: u64,
    n: usize,
) -> Result<Chi2Report, Chi2Failure> {
    let light = [SphereTarget::new(DVec3::new(1.0, -2.0, 0.5), 1.5)];
    let pdf = HittablePdf::new(origin, &light).unwrap();
    let mut r = rng(seed);
    let t = ChiSquareTest::new(20, 20);
    match light[0].view(origin) {
        SphereView::Cone {
            axis,
            one_minus_cos_max,
        } => {
            let domain = ConeDomain {
                frame: Onb::new(axis),
                one_minus_cos_max,
            };
            t.run(
                &domain,
                |d| pdf.value(d),
                everywhere,
                n,
                || pdf.generate(&mut r),
            )
        }
        SphereView::Surrounding => {
            let _ = name;
            t.run(
                &SphereDomain(frame_z()),
                |d| pdf.value(d),
                everywhere,
                n,
                || pdf.generate(&mut r),
            )
        }
    }
}

fn sphere_origins() -> [(&'static str, DVec3); 4] {
    let c = DVec3::new(1.0, -2.0, 0.5);
    let out = DVec3::new(0.3, 0.9, -0.3).normalize();
    [
        ("near: 1e-3 above the surface", c + out * (1.5 + 1e-3)),
        ("middling: 4 radii away", c + out * 6.0),
        ("far: 1e4 away", c + out * 1e4),
        ("inside", c + out * 0.7),
    ]
}

#[test]
fn chi_square_hittable_pdf_sphere_near() {
    let (name, o) = sphere_origins()[0];
    accept(name, hittable_sphere(name, o, 30, N));
}

#[test]
fn chi_square_hittable_pdf_sphere_middling() {
    let (name, o) = sphere_origins()[1];
    accept(name, hittable_sphere(name, o, 31, N));
}

#[test]
fn chi_square_hittable_pdf_sphere_far() {
    let (name, o) = sphere_origins()[2];
    accept(name, hittable_sphere(name, o, 32, N));
}

#[test]
fn chi_square_hittable_pdf_sphere_from_inside() {
    let (name, o) = sphere_origins()[3];
    accept(name, hittable_sphere(name, o, 33, N));
}

// ---------------------------------------------------------------- HittablePdf towards a quad

// ANCHOR: hittable_quad_test
/// Towards a 2 x 1.5 rectangle in the plane z = 0, binned by the rectangle's (s, t).
fn hittable_quad(
    origin: DVec3,
    spherical: bool,
    seed: u64,
    n: usize,
) -> Result<Chi2Report, Chi2Failure> {
    let (q, u, v) = (
        DVec3::new(-1.0, -0.5, 0.0),
        DVec3::new(2.0, 0.0, 0.0),
        DVec3::new(0.0, 1.5, 0.0),
    );
    let light = [QuadTarget::new(q, u, v).with_spherical_rectangles(spherical)];
    let pdf = HittablePdf::new(origin, &light).unwrap();
    let mut r = rng(seed);
    let t = ChiSquareTest::new(20, 20);
    let domain = ParallelogramDomain {
        origin,
        q,
        e1: u,
        e2: v,
    };
    t.run(
        &domain,
        |d| pdf.value(d),
        everywhere,
        n,
        || pdf.generate(&mut r),
    )
}
// ANCHOR_END: hittable_quad_test

const QUAD_NEAR: DVec3 = DVec3::new(0.2, 0.1, 0.05);
const QUAD_FAR: DVec3 = DVec3::new(3.0, -40.0, 100.0);
/// Outside the quad's extent and barely above its plane: every direction to it is grazing.
const QUAD_GRAZING: DVec3 = DVec3::new(2.5, 0.3, 0.02);
const QUAD_MIDDLING: DVec3 = DVec3::new(0.7, -0.4, 1.2);

#[test]
fn chi_square_hittable_pdf_quad_area_near() {
    accept(
        "quad, area sampling, near",
        hittable_quad(QUAD_NEAR, false, 40, N),
    );
}

#[test]
fn chi_square_hittable_pdf_quad_area_far() {
    accept(
        "quad, area sampling, far",
        hittable_quad(QUAD_FAR, false, 41, N),
    );
}

#[test]
fn chi_square_hittable_pdf_quad_area_grazing() {
    accept(
        "quad, area sampling, grazing",
        hittable_quad(QUAD_GRAZING, false, 42, N),
    );
}

#[test]
fn chi_square_hittable_pdf_quad_spherical_rectangle_near() {
    accept(
        "quad, spherical rectangles, near",
        hittable_quad(QUAD_NEAR, true, 43, N),
    );
}

#[test]
fn chi_square_hittable_pdf_quad_spherical_rectangle_middling() {
    accept(
        "quad, spherical rectangles, middling",
        hittable_quad(QUAD_MIDDLING, true, 44, N),
    );
}

#[test]
fn chi_square_hittable_pdf_quad_spherical_rectangle_grazing() {
    accept(
        "quad, spherical rectangles, grazing",
        hittable_quad(QUAD_GRAZING, true, 45, N),
    );
}

#[test]
fn chi_square_hittable_pdf_quad_spherical_rectangle_far_falls_back_to_area() {
    // from 100 away the rectangle's solid angle (3e-4 sr) is at the limit; either way it must fit
    accept(
        "quad, spherical rectangles, far",
        hittable_quad(QUAD_FAR, true, 46, N),
    );
}

/// Two disjoint coplanar quads chosen 1:3 (say, by power), binned in a parallelogram holding both;
/// the support (cells touching either quad) is decided from the geometry.
fn light_list_two_quads(n: usize, seed: u64) -> Result<Chi2Report, Chi2Failure> {
    let table = Selection::from_weights(&[1.0, 3.0]).unwrap();
    two_quads_chosen_by(n, seed, |origin, lights, f| {
        f(&HittablePdf::with_selection(origin, lights, &table).unwrap())
    })
}

/// [`light_list_two_quads`] with the probabilities 1:3 given per call ([`HittablePdf::with_pmf`]).
fn light_list_two_quads_per_call(n: usize, seed: u64) -> Result<Chi2Report, Chi2Failure> {
    let pmf = [0.25, 0.75];
    two_quads_chosen_by(n, seed, |origin, lights, f| {
        f(&HittablePdf::with_pmf(origin, lights, &pmf).unwrap())
    })
}

/// The chi-square test of the list of two quads, with the list built by `build(origin, lights, f)`,
/// which hands it to `f`.
fn two_quads_chosen_by(
    n: usize,
    seed: u64,
    build: impl Fn(
        DVec3,
        &[QuadTarget],
        &mut dyn FnMut(&HittablePdf<'_, QuadTarget>) -> Result<Chi2Report, Chi2Failure>,
    ) -> Result<Chi2Report, Chi2Failure>,
) -> Result<Chi2Report, Chi2Failure> {
    let lights = [
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
    ];
    let origin = DVec3::new(0.1, 0.2, 0.0);
    let big_q = DVec3::new(-2.0, -1.0, 1.0);
    let (e1, e2) = (DVec3::new(4.0, 0.0, 0.0), DVec3::new(0.0, 2.5, 0.0));
    let domain = ParallelogramDomain {
        origin,
        q: big_q,
        e1,
        e2,
    };
    // a cell [lo, hi] of the big parallelogram touches a light iff the rectangles overlap
    let in_support = |lo: DVec2, hi: DVec2| {
        lights.iter().any(|l| {
            let a = warp::invert_parallelogram_sample(l.q(), big_q, e1, e2);
            let b = warp::invert_parallelogram_sample(l.q() + l.u() + l.v(), big_q, e1, e2);
            lo.x < b.x && a.x < hi.x && lo.y < b.y && a.y < hi.y
        })
    };
    let mut r = rng(seed);
    build(origin, &lights, &mut |pdf| {
        ChiSquareTest::new(24, 20).run(
            &domain,
            |d| pdf.value(d),
            in_support,
            n,
            || pdf.generate(&mut r),
        )
    })
}

#[test]
fn chi_square_hittable_pdf_light_list_two_quads() {
    accept("light list: two quads 1:3", light_list_two_quads(N, 47));
}

#[test]
fn chi_square_hittable_pdf_light_list_two_quads_pmf_per_call() {
    accept(
        "light list: two quads 1:3 per call",
        light_list_two_quads_per_call(N, 48),
    );
}

// ---------------------------------------------------------------- heavy variants (1e6 samples)

#[test]
#[ignore = "1e6 samples; run with --ignored"]
fn chi_square_heavy_warps() {
    uniform_sphere_warp(N_HEAVY);
    uniform_hemisphere_warp(N_HEAVY);
    cosine_hemisphere_warp(N_HEAVY);
    quad_area_warp(N_HEAVY);
    spherical_rectangle_warp(N_HEAVY);
}

#[test]
#[ignore = "1e6 samples; run with --ignored"]
fn chi_square_heavy_pdfs() {
    sphere_pdf(N_HEAVY);
    hemisphere_pdf(N_HEAVY);
    cosine_pdf(N_HEAVY);
    mixture_pdf_cosine_and_sphere(N_HEAVY);
    mixture_pdf_cosine_and_sphere_light(N_HEAVY);
    mixture_of_three_pdfs(N_HEAVY);
    accept("heavy: light list", light_list_two_quads(N_HEAVY, 48));
    accept(
        "heavy: quad spherical rectangles near",
        hittable_quad(QUAD_NEAR, true, 49, N_HEAVY),
    );
    accept(
        "heavy: sphere near",
        hittable_sphere("near", sphere_origins()[0].1, 50, N_HEAVY),
    );
}

/// Keeps the Sidak correction honest: `CHI2_TESTS` counts the acceptance checks written in this
/// file (each case of a loop is written as a call of its own).
#[test]
fn sidak_count_matches_this_file() {
    let calls = include_str!("chi_square.rs")
        .lines()
        .map(str::trim_start)
        .filter(|l| !l.starts_with("//") && !l.starts_with("fn ") && !l.contains("CHI2_TESTS"))
        .filter(|l| l.contains("accept(") && !l.contains(".matches"))
        .count();
    assert_eq!(
        calls, CHI2_TESTS,
        "set CHI2_TESTS to the number of acceptance calls"
    );
}
