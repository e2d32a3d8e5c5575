//! What a list of lights draws is what its density describes, for several lights of different kinds:
//! a chi-square test of `HittablePdf` over a one-sided quad seen from the front, a one-sided quad seen
//! from behind (right behind the first, so that directions drawn towards it would meet the first's
//! front), a sphere and a two-sided quad (TESTING.md, "light list").
//!
//! `pdf` is a sub-probability density here: the light seen from behind has no directions, so a sample
//! that chose it fails (`None`), with probability its selection probability. The test bins the
//! directions over the whole sphere (the lights are large and near, so every cell has room) and adds
//! one cell for failures, expected `N * P(choose the light seen from behind)`.

use glam::{DVec2, DVec3};
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use rtl_pdf::chi2::{Chi2Failure, Chi2Report, ChiSquareTest, SphereDomain, sidak_alpha};
use rtl_pdf::{
    DirectionSample, HittablePdf, Onb, Pdf, QuadTarget, Selection, ShapeSampler, SphereTarget,
};
use rtl_render::light_tree::LightTree;
use rtl_render::lights::{EmitterWeight, LightTarget, Lights, MAX_WEIGHED_EMITTERS, UNIFORM_SHARE};

const N: usize = 100_000;
/// Tests of a correct sampler in this file's run (for the Sidak correction).
const TESTS: usize = 16;

/// The origin is (0, 0, 0); the lights around it.
fn lights(spherical_rectangles: bool) -> [LightTarget; 4] {
    [
        // y = 1, facing down (u x v = -y): the origin sees its front
        LightTarget::Quad {
            quad: QuadTarget::new(
                DVec3::new(-1.0, 1.0, -1.0),
                DVec3::new(2.0, 0.0, 0.0),
                DVec3::new(0.0, 0.0, 2.0),
            )
            .with_spherical_rectangles(spherical_rectangles),
            one_sided: true,
        },
        // y = 2, facing up (u x v = +y): the origin is behind it, and every direction towards it
        // passes through the quad above
        LightTarget::Quad {
            quad: QuadTarget::new(
                DVec3::new(-0.8, 2.0, -0.8),
                DVec3::new(0.0, 0.0, 1.6),
                DVec3::new(1.6, 0.0, 0.0),
            )
            .with_spherical_rectangles(spherical_rectangles),
            one_sided: true,
        },
        LightTarget::Sphere(SphereTarget::new(DVec3::new(2.0, -0.3, 0.2), 0.8)),
        // upright at z = -1.5, two-sided
        LightTarget::Quad {
            quad: QuadTarget::new(
                DVec3::new(-1.0, -1.0, -1.5),
                DVec3::new(2.0, 0.0, 0.0),
                DVec3::new(0.0, 1.5, 0.0),
            )
            .with_spherical_rectangles(spherical_rectangles),
            one_sided: false,
        },
    ]
}

/// The chi-square test of `draw` (one uniform point in, a direction or a failure out) against
/// `density` over the whole sphere, plus the failure cell expecting `N * p_fail`.
fn test(
    density: impl Fn(DVec3) -> f64,
    p_fail: f64,
    seed: u64,
    draw: impl Fn(DVec2) -> Option<DirectionSample>,
) -> Chi2Report {
    let t = ChiSquareTest::new(36, 36);
    // A tilted frame, so that no cell edge lies on a quad's edge.
    let domain = SphereDomain(Onb::new(DVec3::new(0.3, 0.2, 1.0).normalize()));
    let probs = t.expected(&domain, &density, |_, _| true, N).unwrap();
    let mut observed = vec![0u64; probs.len() + 1];
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    for _ in 0..N {
        let u = DVec2::new(rng.random(), rng.random());
        match draw(u) {
            None => observed[probs.len()] += 1,
            Some(s) => {
                let d = s.direction;
                assert!(d.is_finite() && (d.length() - 1.0).abs() < 1e-9, "{d}");
                // the density a sample carries is the density of its direction
                let p = density(d);
                assert!(
                    (s.pdf - p).abs() <= 1e-9 * p,
                    "sample's pdf {} vs pdf {p} at {d}",
                    s.pdf
                );
                let x = rtl_pdf::chi2::Domain::to_square(&domain, d).unwrap();
                let ix = ((x.x * t.nx as f64) as usize).min(t.nx - 1);
                let iy = ((x.y * t.ny as f64) as usize).min(t.ny - 1);
                observed[iy * t.nx + ix] += 1;
            }
        }
    }
    let mut expected: Vec<f64> = probs.iter().map(|p| p * N as f64).collect();
    expected.push(p_fail * N as f64);
    let total: f64 = expected.iter().sum();
    assert!(
        (total / N as f64 - 1.0).abs() < 1e-3,
        "the expected counts add up to {total}, not {N}"
    );
    t.statistic(&observed, &expected, N).unwrap()
}

#[test]
fn several_lights_uniform_selection_draw_what_their_pdf_says() {
    let alpha = sidak_alpha(0.01, TESTS);
    for (spherical, seed) in [(false, 1), (true, 2)] {
        let targets = lights(spherical);
        let origin = DVec3::ZERO;
        let pdf = HittablePdf::new(origin, &targets).unwrap();
        // the light seen from behind: no direction, density 0
        assert!(targets[1].sample(origin, DVec2::splat(0.5)).is_none());
        assert_eq!(targets[1].pdf(origin, DVec3::Y), 0.0);
        let r = test(|d| pdf.pdf(d), 0.25, seed, |u| pdf.sample(u));
        assert!(
            r.p_value >= alpha,
            "spherical rectangles {spherical}: {r:?}"
        );
    }
}

#[test]
fn several_lights_weighted_selection_draw_what_their_pdf_says() {
    let targets = lights(false);
    let table = Selection::from_weights(&[1.0, 2.0, 3.0, 4.0]).unwrap();
    let pdf = HittablePdf::with_selection(DVec3::ZERO, &targets, &table).unwrap();
    let r = test(|d| pdf.pdf(d), 0.2, 3, |u| pdf.sample(u));
    assert!(r.p_value >= sidak_alpha(0.01, TESTS), "{r:?}");
}

/// The light tree over the four lights of [`lights`] (radiance 1 to 4).
fn tree_over(targets: &[LightTarget]) -> LightTree {
    let weights: Vec<EmitterWeight> = targets
        .iter()
        .enumerate()
        .map(|(i, t)| EmitterWeight::new(t, 1.0 + i as f64))
        .collect();
    LightTree::new(targets, &weights).unwrap()
}

#[test]
fn the_light_tree_draws_what_its_density_says() {
    let targets = lights(false);
    let tree = tree_over(&targets);
    let x = DVec3::ZERO;
    // without a shading normal and with two (the cosine at x bounded in the importance)
    for (k, normal) in [None, Some(DVec3::Y), Some(DVec3::new(0.6, 0.0, -0.8))]
        .into_iter()
        .enumerate()
    {
        // the light seen from behind (1) fails its samples: its probability is the failure cell's
        // (with the share of descents that stop)
        let p_fail = 1.0
            - [0, 2, 3]
                .iter()
                .map(|&i| tree.pmf(x, normal, i))
                .sum::<f64>();
        assert!(
            p_fail > 0.99 * UNIFORM_SHARE / 4.0 && p_fail < 0.5,
            "{normal:?}: {p_fail}"
        );
        let r = test(
            |d| tree.pdf(x, normal, d, &targets, None, None),
            p_fail,
            4 + k as u64,
            |u| tree.sample(x, normal, u, &targets, None),
        );
        assert!(r.p_value >= sidak_alpha(0.01, TESTS), "{normal:?}: {r:?}");
    }
}

/// Forty lights of sizes, radiances and orientations drawn at random around the origin, a third of
/// them one-sided quads.
fn forty_lights() -> (Vec<LightTarget>, Vec<EmitterWeight>) {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(40);
    let mut point = |scale: f64| {
        DVec3::new(rng.random(), rng.random(), rng.random()) * 2.0 * scale - DVec3::splat(scale)
    };
    let (mut targets, mut weights) = (Vec::new(), Vec::new());
    for i in 0..40 {
        let c = point(10.0);
        let t = if i % 3 == 0 {
            LightTarget::Quad {
                quad: QuadTarget::new(c, point(1.0), point(1.0)),
                one_sided: true,
            }
        } else {
            LightTarget::Sphere(SphereTarget::new(c, 0.05 + 0.1 * (i % 5) as f64))
        };
        targets.push(t);
        weights.push(EmitterWeight::new(&t, 1.0 + (i % 7) as f64));
    }
    (targets, weights)
}

/// The chi-square test of how often `tree` chooses each light at `x` in `N` draws against `pmf`,
/// with a cell for draws that choose nothing (an error if a light `pmf` gives 0 is chosen).
fn choices(
    tree: &LightTree,
    x: DVec3,
    normal: Option<DVec3>,
    seed: u64,
    pmf: impl Fn(usize) -> f64,
) -> Result<Chi2Report, Chi2Failure> {
    let n = tree.len();
    let mut observed = vec![0u64; n + 1];
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    for _ in 0..N {
        match tree.choose(x, normal, rng.random()) {
            Some((i, u)) => {
                assert!((0.0..1.0).contains(&u), "{u}");
                observed[i] += 1;
            }
            None => observed[n] += 1,
        }
    }
    let mut expected: Vec<f64> = (0..n).map(|i| N as f64 * pmf(i)).collect();
    expected.push((N as f64 - expected.iter().sum::<f64>()).max(0.0));
    ChiSquareTest::new(n + 1, 1).statistic(&observed, &expected, N)
}

#[test]
fn the_light_tree_chooses_each_light_as_often_as_its_probability_says() {
    let (targets, weights) = forty_lights();
    let tree = LightTree::new(&targets, &weights).unwrap();
    let alpha = sidak_alpha(0.01, TESTS);
    for (k, x) in [
        DVec3::ZERO,
        DVec3::new(8.0, -9.0, 3.0),
        DVec3::new(40.0, 0.0, 0.0),
    ]
    .into_iter()
    .enumerate()
    {
        // without a shading normal, and with normals that put some of the lights below the horizon
        let normals = [None, Some(DVec3::Y), Some(DVec3::new(-0.48, 0.6, 0.64))];
        for (m, normal) in normals.into_iter().enumerate() {
            let seed = 10 + 3 * k as u64 + m as u64;
            // (with a normal, descents stop where both clusters are below the horizon: the rest is
            // the chi-square's cell for choices of nothing)
            let sum: f64 = (0..tree.len()).map(|i| tree.pmf(x, normal, i)).sum();
            let least = if normal.is_some() { UNIFORM_SHARE } else { 0.9 };
            assert!(sum <= 1.0 + 1e-12 && sum > least, "{normal:?}: {sum}");
            let r = choices(&tree, x, normal, seed, |i| tree.pmf(x, normal, i)).unwrap();
            assert!(r.p_value >= alpha, "at {x} {normal:?}: {r:?}");
            // The checker catches probabilities that forget the uniform share.
            let forgetful =
                |i| (tree.pmf(x, normal, i) - UNIFORM_SHARE / 40.0) / (1.0 - UNIFORM_SHARE);
            // (a light seen from behind is chosen by its uniform share alone: outside the support)
            let wrong = choices(&tree, x, normal, seed, forgetful);
            assert!(
                wrong.as_ref().map_or(true, |r| r.p_value < alpha),
                "at {x} {normal:?}: {wrong:?}"
            );
            // ... and the choice with the normal against the probabilities without it
            if normal.is_some() {
                let blind = choices(&tree, x, normal, seed, |i| tree.pmf(x, None, i));
                assert!(
                    blind.as_ref().map_or(true, |r| r.p_value < alpha),
                    "at {x} {normal:?}: {blind:?}"
                );
            }
        }
    }
    // Numbers at the ends of [0, 1) and beyond, and a point that is not a number: a light or none,
    // never a panic; probabilities that are numbers.
    for u in [0.0, rtl_pdf::ONE_MINUS_EPSILON, 1.0, f64::NAN, -1.0] {
        for x in [DVec3::ZERO, DVec3::splat(f64::NAN), DVec3::splat(1e300)] {
            for normal in [None, Some(DVec3::Y)] {
                if let Some((i, v)) = tree.choose(x, normal, u) {
                    assert!(i < 40 && (0.0..1.0).contains(&v), "{u} {x}: {i} {v}");
                }
                let pmf = |i| tree.pmf(x, normal, i);
                assert!((0..40).all(|i| pmf(i).is_finite() && pmf(i) > 0.0));
            }
        }
    }
}

/// Two walls of 12 one-sided panels each, at x = -3 facing +x and at x = 3 facing -x.
fn facing_walls() -> (Vec<LightTarget>, Vec<EmitterWeight>) {
    let (mut targets, mut weights) = (Vec::new(), Vec::new());
    for side in [-1.0, 1.0] {
        for k in 0..12 {
            let (y, z) = (0.5 + (k / 4) as f64, -2.0 + (k % 4) as f64);
            let (u, v) = (DVec3::new(0.0, 0.6, 0.0), DVec3::new(0.0, 0.0, 0.6));
            // u x v = +x: the wall at -3 faces +x; the other is turned round
            let (u, v) = if side < 0.0 { (u, v) } else { (v, u) };
            let t = LightTarget::Quad {
                quad: QuadTarget::new(DVec3::new(3.0 * side, y, z), u, v),
                one_sided: true,
            };
            targets.push(t);
            weights.push(EmitterWeight::new(&t, 2.0));
        }
    }
    (targets, weights)
}

#[test]
fn the_light_tree_sends_a_point_to_the_panels_that_face_it() {
    let (targets, weights) = facing_walls();
    let with = LightTree::new(&targets, &weights).unwrap();
    let without = LightTree::build_over(&targets, &weights, false).unwrap();
    // just behind the wall at 3, inside its cluster's bounding sphere, in front of the far wall: the
    // far wall should take all but the near wall's uniform share, 1 - 0.1 x 12 / 24 (without the
    // cones, 0.15: the near panels' distance wins and their samples fail)
    let x = DVec3::new(3.2, 1.5, -0.5);
    let far: f64 = (0..12).map(|i| with.pmf(x, None, i)).sum();
    let far_without: f64 = (0..12).map(|i| without.pmf(x, None, i)).sum();
    assert!(far > 0.94, "{far}");
    assert!(
        far > far_without + 0.2,
        "{far} vs {far_without} without the cones"
    );
    let r = choices(&with, x, None, 31, |i| with.pmf(x, None, i)).unwrap();
    assert!(r.p_value >= sidak_alpha(0.01, TESTS), "{r:?}");
}

/// main's light: from behind a one-sided quad it still sampled towards the quad, while its pdf said 0.
#[derive(Clone, Copy)]
struct SampledFromBehind(LightTarget);

impl ShapeSampler for SampledFromBehind {
    fn pdf(&self, origin: DVec3, direction: DVec3) -> f64 {
        self.0.pdf(origin, direction)
    }
    fn sample(&self, origin: DVec3, u: DVec2) -> Option<DirectionSample> {
        let s = match self.0 {
            LightTarget::Quad { quad, .. } => quad.sample(origin, u)?,
            sphere => sphere.sample(origin, u)?,
        };
        // and the density it reports is its pdf, which knows the quad is one-sided
        Some(DirectionSample {
            direction: s.direction,
            pdf: self.pdf(origin, s.direction),
        })
    }
}

#[test]
fn the_test_catches_a_light_sampled_from_behind() {
    let targets = lights(false).map(SampledFromBehind);
    let pdf = HittablePdf::new(DVec3::ZERO, &targets).unwrap();
    // the one light behind the origin never fails now: its directions land in the front quad's cells
    let sample = |u| {
        let s = pdf.sample(u)?;
        let p = pdf.pdf(s.direction);
        Some(DirectionSample {
            direction: s.direction,
            pdf: p,
        })
    };
    let r = test(|d| pdf.pdf(d), 0.25, 4, sample);
    assert!(r.p_value < 1e-100, "{r:?}");
}

// ---------------------------------------------------------------------------------------------------
// Stratification with two emitters

use rtl_render::Color;
use rtl_render::material::{Albedo, Material};
use rtl_render::sampler::{Ctx, Dimension, SampleRng, Sampler};
use rtl_render::scene::SceneBuilder;
use rtl_render::vec::Point3;

/// Two emitting quads (different sizes, both facing down) above a point on a floor; their emitters
/// as the renderer samples them, by area, each chosen by its importance at the shading point.
fn two_emitters() -> Lights {
    let mut b = SceneBuilder::new();
    let w = b.world();
    let light = b.material(Material::DiffuseLight {
        emit: Albedo::Constant(Color::ONE),
        two_sided: false,
    });
    b.quad(
        w,
        Point3::new(-2.0, 2.0, -1.0),
        Vec3::new(1.5, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 1.0),
        light,
    )
    .unwrap();
    b.quad(
        w,
        Point3::new(0.5, 1.5, -0.5),
        Vec3::new(0.6, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 2.0),
        light,
    )
    .unwrap();
    let scene = b.build().unwrap();
    let lights = rtl_render::lights::Lights::new(&scene, false);
    assert_eq!(
        lights.emitters.len(),
        2,
        "both emitters found without a list"
    );
    lights
}

use rtl_render::vec::Vec3;

const P: DVec3 = DVec3::new(0.1, 0.0, 0.2);

/// The irradiance / pi at `P` (normal +y) from the two unit-radiance quads, by 64 x 64 Gauss-Legendre
/// points over each quad's area (a smooth integrand: exact to ~1e-12).
fn exact(lights: &[LightTarget]) -> f64 {
    let gl = gauss_legendre_64();
    let mut total = 0.0;
    for l in lights {
        let LightTarget::Quad { quad, .. } = l else {
            unreachable!()
        };
        for &(s, ws) in &gl {
            for &(t, wt) in &gl {
                let x = quad.q() + s * quad.u() + t * quad.v();
                let to = x - P;
                let d2 = to.length_squared();
                let cos_p = to.y / d2.sqrt();
                let cos_l = quad.normal().dot(to).abs() / d2.sqrt();
                total += ws * wt * quad.area() * cos_p * cos_l / (std::f64::consts::PI * d2);
            }
        }
    }
    total
}

/// Nodes and weights of 64-point Gauss-Legendre on [0, 1], by Newton's method on P_64.
fn gauss_legendre_64() -> Vec<(f64, f64)> {
    let n = 64;
    (0..n)
        .map(|i| {
            let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            let mut dp = 0.0;
            for _ in 0..100 {
                let (mut p0, mut p1) = (1.0, x);
                for k in 2..=n {
                    let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                    p0 = p1;
                    p1 = p2;
                }
                dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
                let dx = p1 / dp;
                x -= dx;
                if dx.abs() < 1e-16 {
                    break;
                }
            }
            let w = 2.0 / ((1.0 - x * x) * dp * dp);
            ((1.0 + x) / 2.0, w / 2.0)
        })
        .collect()
}

/// One sample of the direct-light estimate `L cos / (pi p)` at `P` for the light point `u`, drawn as
/// the renderer's next-event estimation draws it.
fn estimate(lights: &Lights, u: DVec2) -> f64 {
    let mut pmf = [0.0; MAX_WEIGHED_EMITTERS];
    let pdf = lights.towards_emitters(P, &mut pmf).unwrap();
    pdf.sample(u).map_or(0.0, |s| {
        s.direction.y.max(0.0) / (std::f64::consts::PI * s.pdf)
    })
}

/// The slope of log RMSE against log N over 64 independent scrambles (or seeds), N = 16 .. 4096,
/// for the uniform points `point(key, k)`.
fn slope(lights: &Lights, point: impl Fn(u64, u64) -> DVec2) -> f64 {
    let truth = exact(&lights.emitters);
    let sizes = [16u64, 64, 256, 1024, 4096];
    let mut xs = Vec::new();
    let mut ys = Vec::new();
    for &n in &sizes {
        let mut se = 0.0;
        let replicates = 64u64;
        for r in 0..replicates {
            let key = rtl_render::sampler::mix64(r + 1);
            let mean = (0..n).map(|k| estimate(lights, point(key, k))).sum::<f64>() / n as f64;
            se += (mean - truth) * (mean - truth);
        }
        xs.push((n as f64).ln());
        ys.push((se / replicates as f64).sqrt().ln());
    }
    let mx = xs.iter().sum::<f64>() / xs.len() as f64;
    let my = ys.iter().sum::<f64>() / ys.len() as f64;
    let sxy: f64 = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = xs.iter().map(|x| (x - mx) * (x - mx)).sum();
    sxy / sxx
}

/// The renderer's light pair of bounce 0 for sample `k` of a pixel with scramble `key`.
fn light_pair(low_discrepancy: bool) -> impl Fn(u64, u64) -> DVec2 {
    move |key, k| {
        let mut ctx = Ctx::new();
        ctx.rng = SampleRng::for_sample(7, key, k);
        ctx.sampler = Sampler::new(low_discrepancy, key, k);
        ctx.sample_2d(Dimension::Light(0))
    }
}

#[test]
fn two_emitters_stay_stratified_with_low_discrepancy_samples() {
    let lights = two_emitters();
    // The light choice takes u.x and hands the rest on, so each light's directions are a stratified
    // set of their own: the error falls much faster than N^-1/2.
    let lds = slope(&lights, light_pair(true));
    eprintln!("low-discrepancy slope {lds:.3}");
    assert!(lds < -0.9, "low-discrepancy: slope {lds:.2}");
    // Independent numbers: N^-1/2 (64 replicates: the slope is within about 0.05 of -0.5).
    let random = slope(&lights, light_pair(false));
    eprintln!("random slope {random:.3}");
    assert!(
        (-0.62..-0.38).contains(&random),
        "random: slope {random:.2}"
    );
}

#[test]
fn the_stratification_test_sees_a_choice_that_breaks_the_point() {
    // Deliberately wrong, as the renderer once did: the first coordinate picks the light and the
    // direction comes from elsewhere (here: the point's coordinates hashed), so no light's directions
    // are stratified: back to N^-1/2.
    let lights = two_emitters();
    let pair = light_pair(true);
    let broken = slope(&lights, |key, k| {
        let u = pair(key, k);
        let h = rtl_render::sampler::mix64(u.x.to_bits() ^ u.y.to_bits().rotate_left(17));
        let v = ((h >> 11) as f64) / (1u64 << 53) as f64;
        // choice by u.x (< 1/2: light 0), the direction from (v, u.y) instead of u.x's rest
        DVec2::new(
            if u.x < 0.5 { 0.5 * v } else { 0.5 + 0.5 * v },
            rtl_render::sampler::mix64(h) as f64 / u64::MAX as f64,
        )
    });
    eprintln!("broken slope {broken:.3}");
    assert!(
        broken > -0.62,
        "slope {broken:.2}: the check cannot see a broken point"
    );
}

// ---------------------------------------------------------------------------------------------------
// Every emitter, wherever it is placed

#[test]
fn emitters_in_instanced_groups_are_found_in_world_space() {
    use rtl_render::ray::Ray;
    use rtl_render::scene::Transform;
    // One emitting quad in a group, placed twice (rotated and moved), and an emitting sphere in a
    // nested group; nothing listed.
    let mut b = SceneBuilder::new();
    let w = b.world();
    let light = b.material(Material::DiffuseLight {
        emit: Albedo::Constant(Color::ONE),
        two_sided: true,
    });
    let g = b.group();
    b.quad(
        g,
        Point3::new(-0.5, 0.0, -0.5),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 1.0),
        light,
    )
    .unwrap();
    b.instance(
        w,
        g,
        Transform::rotate_y(30.0).then(Transform::translate(Vec3::new(0.0, 3.0, 0.0))),
    );
    b.instance(
        w,
        g,
        Transform::rotate_y(-45.0).then(Transform::translate(Vec3::new(4.0, 2.0, 1.0))),
    );
    let inner = b.group();
    b.sphere(inner, Point3::new(-3.0, 1.0, 0.0), 0.5, light)
        .unwrap();
    b.add_to(w, rtl_render::scene::Object::Group(inner));
    let scene = b.build().unwrap();
    let lights = rtl_render::lights::Lights::new(&scene, false);
    assert_eq!(lights.emitters.len(), 3);
    assert_eq!(lights.listed_emitters, 0);
    // From a point below them, every direction sampled towards an emitter meets an emitter there.
    let origin = Point3::new(0.5, -1.0, 0.3);
    let pdf = HittablePdf::new(origin, &lights.emitters).unwrap();
    let mut ctx = Ctx::new();
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(9);
    for _ in 0..2000 {
        let s = pdf
            .sample(DVec2::new(rng.random(), rng.random()))
            .expect("two-sided emitters are never behind");
        let hit = scene
            .hit(&Ray::new(origin, s.direction, 0.0), &mut ctx)
            .expect("the sampled direction meets the scene");
        assert!(
            scene.materials[hit.material.index()].is_emitter(),
            "a direction towards an emitter met something else"
        );
        assert!(pdf.pdf(s.direction) > 0.0);
    }
}

// ---------------------------------------------------------------------------------------------------
// Which emitter next-event estimation chooses, per shading point

/// A one-sided quad lamp (radiance 2, 2 x 2 at y = 3, facing down), a two-sided sphere (radiance
/// (1, 2, 3), mean 2, radius 0.5 at (4, 1, 0)) and a two-sided quad (radiance 0.5, 1 x 1 upright in
/// the plane x = -3).
fn three_emitters() -> Lights {
    let mut b = SceneBuilder::new();
    let w = b.world();
    let lamp = b.material(Material::DiffuseLight {
        emit: Albedo::Constant(Color::splat(2.0)),
        two_sided: false,
    });
    let ball = b.material(Material::DiffuseLight {
        emit: Albedo::Constant(Color::new(1.0, 2.0, 3.0)),
        two_sided: true,
    });
    let panel = b.material(Material::DiffuseLight {
        emit: Albedo::Constant(Color::splat(0.5)),
        two_sided: true,
    });
    // u x v = (0, -4, 0): shines down
    b.quad(
        w,
        Point3::new(-1.0, 3.0, -1.0),
        Vec3::new(2.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 2.0),
        lamp,
    )
    .unwrap();
    b.sphere(w, Point3::new(4.0, 1.0, 0.0), 0.5, ball).unwrap();
    b.quad(
        w,
        Point3::new(-3.0, 0.0, -0.5),
        Vec3::new(0.0, 1.0, 0.0),
        Vec3::new(0.0, 0.0, 1.0),
        panel,
    )
    .unwrap();
    let mut lights = Lights::new(&b.build().unwrap(), false);
    assert_eq!(lights.emitters.len(), 3);
    // In the order lamp, ball, panel (the scene lists them in its own order).
    let rank = |t: &LightTarget| match t {
        LightTarget::Quad {
            one_sided: true, ..
        } => 0,
        LightTarget::Sphere(_) => 1,
        LightTarget::Quad { .. } => 2,
    };
    let mut both: Vec<_> = lights
        .emitters
        .iter()
        .copied()
        .zip(lights.emitter_weights.iter().copied())
        .collect();
    both.sort_by_key(|(t, _)| rank(t));
    (lights.emitters, lights.emitter_weights) = both.into_iter().unzip();
    lights
}

#[test]
fn emitters_are_chosen_by_radiance_times_solid_angle_at_the_point() {
    let lights = three_emitters();
    let radiance: Vec<f64> = lights
        .emitter_weights
        .iter()
        .map(|w| w.radiance())
        .collect();
    assert_eq!(radiance, [2.0, 2.0, 0.5]);
    assert!(lights.weighs_emitters());
    let pmf_at = |x: Point3| {
        let mut pmf = [0.0; MAX_WEIGHED_EMITTERS];
        let h = lights.towards_emitters(x, &mut pmf).unwrap();
        [h.pmf(0), h.pmf(1), h.pmf(2)]
    };
    // Below the lamp at the origin: the lamp's A h / d^3 = 4 x 3 / 27, the sphere's cone with
    // s = 0.25 / 17, the panel's 1 x 3 / 9.25^(3/2) (its centre at (-3, 0.5, 0)).
    let x = Point3::ZERO;
    let s = 0.25 / 17.0;
    let w = [
        2.0 * 4.0 * 3.0 / 27.0,
        2.0 * std::f64::consts::TAU * s / (1.0 + (1.0 - s).sqrt()),
        0.5 * 3.0 / 9.25f64.powf(1.5),
    ];
    let total: f64 = w.iter().sum();
    let want = w.map(|w| (1.0 - UNIFORM_SHARE) * w / total + UNIFORM_SHARE / 3.0);
    let got = pmf_at(x);
    for i in 0..3 {
        assert!(
            (got[i] - want[i]).abs() < 1e-12,
            "{i}: {got:?} against {want:?}"
        );
    }
    assert!((got.iter().sum::<f64>() - 1.0).abs() < 1e-12);
    assert!(got[0] > 0.5, "the lamp overhead is the likeliest: {got:?}");
    // Beside the sphere, it takes most of the choices instead.
    let near_ball = pmf_at(Point3::new(4.0, 0.2, 0.0));
    assert!(near_ball[1] > 0.8, "{near_ball:?}");
    // Above the one-sided lamp: exactly 0 for it (it sends nothing there), the others share all.
    let above = pmf_at(Point3::new(0.0, 4.0, 0.0));
    assert_eq!(above[0], 0.0);
    assert!(above[1] >= UNIFORM_SHARE / 2.0 && above[2] >= UNIFORM_SHARE / 2.0);
    assert!((above[1] + above[2] - 1.0).abs() < 1e-12);
    // In the plane of the two-sided panel (no solid angle): its floor, never 0.
    let in_plane = pmf_at(Point3::new(-3.0, 0.5, 2.0));
    assert!(in_plane[2] >= UNIFORM_SHARE / 3.0 - 1e-15, "{in_plane:?}");
    // Far from everything: every emitter keeps at least its uniform share.
    for x in [Point3::new(1e6, -1e6, 3e5), Point3::new(4.0, 1.0, 0.0)] {
        let p = pmf_at(x);
        assert!(
            p.iter().all(|&p| p >= UNIFORM_SHARE / 3.0 - 1e-15),
            "{x}: {p:?}"
        );
    }
    assert!(lights.describe_emitters().contains("per shading point"));
    // A point that is not a number (a ray gone wrong upstream): a distribution all the same, no panic.
    let nan = pmf_at(Point3::splat(f64::NAN));
    assert!((nan.iter().sum::<f64>() - 1.0).abs() < 1e-12, "{nan:?}");
}

#[test]
fn the_light_sample_and_the_mis_weight_use_the_same_density() {
    // The density a sample comes with is the one `emitters_pdf` (the MIS weight's) gives its
    // direction, from points all around the emitters; and from behind the lamp its directions never
    // have the lamp's density.
    let lights = three_emitters();
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(31);
    let mut behind = 0;
    for _ in 0..3000 {
        let x = Point3::new(
            rng.random_range(-6.0..6.0),
            rng.random_range(-2.0..5.0),
            rng.random_range(-3.0..3.0),
        );
        let mut pmf = [0.0; MAX_WEIGHED_EMITTERS];
        let h = lights.towards_emitters(x, &mut pmf).unwrap();
        let Some(s) = h.sample(DVec2::new(rng.random(), rng.random())) else {
            continue;
        };
        let p = lights.emitters_pdf(x, None, s.direction);
        assert!(
            (s.pdf - p).abs() <= 1e-9 * p,
            "at {x}: sampled with {} but weighted by {p}",
            s.pdf
        );
        if x.y > 3.0 {
            behind += 1;
            assert_eq!(lights.emitters[0].pdf(x, s.direction), 0.0);
        }
    }
    assert!(behind > 100);
}

#[test]
fn one_emitter_keeps_the_uniform_choice_and_more_than_the_stack_holds_take_the_tree() {
    let light = |b: &mut SceneBuilder, c: f64| {
        b.material(Material::DiffuseLight {
            emit: Albedo::Constant(Color::splat(c)),
            two_sided: false,
        })
    };
    // More emitters than MAX_WEIGHED_EMITTERS: chosen through the light tree, per point.
    let mut b = SceneBuilder::new();
    let w = b.world();
    let n = MAX_WEIGHED_EMITTERS + 1;
    for i in 0..n {
        let m = light(&mut b, 1.0 + i as f64);
        b.sphere(w, Point3::new(2.0 * i as f64, 3.0, 0.0), 0.3, m)
            .unwrap();
    }
    let lights = Lights::new(&b.build().unwrap(), false);
    assert!(!lights.weighs_emitters());
    let tree = lights.emitter_tree.as_ref().unwrap();
    let mut pmf = [0.0; MAX_WEIGHED_EMITTERS];
    assert!(
        lights.towards_emitters(Point3::ZERO, &mut pmf).is_none(),
        "a HittablePdf cannot express the tree's choice"
    );
    // Every emitter keeps at least its uniform share; the probabilities add up to 1; an emitter is
    // far likelier under it than 16 units away.
    let under = |k: usize| Point3::new(2.0 * k as f64, 0.0, 0.0);
    for k in [0, 8, 16] {
        let p: Vec<f64> = (0..n).map(|i| tree.pmf(under(k), None, i)).collect();
        assert!((p.iter().sum::<f64>() - 1.0).abs() < 1e-12, "{p:?}");
        assert!(p.iter().all(|&p| p >= UNIFORM_SHARE / n as f64), "{p:?}");
        let away = under((k + 8) % 16);
        assert!(p[k] > 3.0 * tree.pmf(away, None, k), "{k}: {p:?}");
    }
    assert!(lights.describe_emitters().ends_with(&format!(
        "chosen per shading point through a light tree by their power and distance (more than \
         {MAX_WEIGHED_EMITTERS} emitters; 10% spread uniformly)"
    )));
    // The Cornell box's one light: no weights, the description as before.
    let cornell =
        (rtl_render::scenes::find("cornell").unwrap().build)(&Default::default()).unwrap();
    let lights = Lights::new(&cornell.scene, false);
    assert!(!lights.weighs_emitters());
    assert_eq!(
        lights.describe_emitters(),
        "1 emitter (1 of them in the list of targets)"
    );
    // Behind every one-sided emitter: nothing to sample, density 0.
    let mut b = SceneBuilder::new();
    let w = b.world();
    let m = light(&mut b, 1.0);
    for x in [-1.0, 1.0] {
        b.quad(
            w,
            Point3::new(x, 2.0, 0.0),
            Vec3::new(0.0, 0.0, 1.0),
            Vec3::new(1.0, 0.0, 0.0),
            m,
        )
        .unwrap(); // u x v = +y: shines up
    }
    let lights = Lights::new(&b.build().unwrap(), false);
    assert!(lights.weighs_emitters());
    assert!(lights.towards_emitters(Point3::ZERO, &mut pmf).is_none());
    assert_eq!(lights.emitters_pdf(Point3::ZERO, None, Vec3::Y), 0.0);
    assert!(
        lights
            .towards_emitters(Point3::new(0.0, 5.0, 0.0), &mut pmf)
            .is_some()
    );
}
