//! Eight paths traced side by side ([`rtl_render::paths8`]) against one path at a time: the same
//! image bit for bit, for every strategy that takes the lanes, in every tier this processor runs;
//! and each of the lanes' parts against its scalar twin, bit for bit: the rays' intersection
//! ([`rtl_render::ray8`]), rtl-pdf's warps ([`rtl_render::warp8`]) and the mixture's density
//! ([`rtl_render::mixture8`]). Every check is also shown to catch a deliberately wrong lane.
#![cfg(target_arch = "x86_64")]

use glam::{DVec2, DVec3};
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use rtl_pdf::{CosinePdf, QuadTarget, SphereTarget};
use rtl_render::camera::CameraSettings;
mod hit_bits;
use hit_bits::record;
use rtl_render::integrator::{MisOptions, Strategy, sample_diffuse};
use rtl_render::lanes::F64x8;
use rtl_render::lights::{LightTarget, Lights};
use rtl_render::material::{Albedo, Material, ScatterPdf};
use rtl_render::mixture8::Mixture8;
use rtl_render::ray::{Interval, Ray};
use rtl_render::ray8::{
    Closest8, Cluster, LaneQuads, Rays8, closest_avx2, closest_avx512, closest_portable,
};
use rtl_render::render::{Accumulator, RenderSettings, Renderer};
use rtl_render::sampler::Ctx;
use rtl_render::scene::{Background, GroupId, ImportanceTarget, Scene, SceneBuilder, Transform};
use rtl_render::shapes::Sphere;
use rtl_render::traversal::{Found, HitTier};
use rtl_render::vec::{Color, Point3, Vec3};
use rtl_render::warp8;
use rtl_render::wide8::{Avx2, Avx512, Wide8};

/// The lane forms this processor runs (AVX2, AVX-512), said on the test's output.
fn tiers() -> Vec<HitTier> {
    let run: Vec<HitTier> = [HitTier::Avx2, HitTier::Avx512]
        .into_iter()
        .filter(|t| t.available())
        .collect();
    eprintln!("lane forms tested: {run:?}");
    run
}

fn unit<R: Rng>(rng: &mut R) -> Vec3 {
    rtl_pdf::warp::sample_uniform_sphere(DVec2::new(rng.random(), rng.random()))
}

fn point<R: Rng>(rng: &mut R, r: f64) -> Point3 {
    Point3::new(
        rng.random_range(-r..r),
        rng.random_range(-r..r),
        rng.random_range(-r..r),
    )
}

// ---------------------------------------------------------------------------------------------
// Whole images

/// A small room of random quads (walls, a one- or two-sided lamp, a rotated box flattened into the
/// room), a glass, a metal or a textured ball and a second sphere, the lamp and the first ball
/// listed as targets: one small group, as the lanes take it.
fn small_room(rng: &mut Xoshiro256PlusPlus) -> Scene {
    small_room_lit(rng, false)
}

/// [`small_room`], with a second lamp (small, of another radiance, not listed) if `second`:
/// `mis` then chooses its emitter per shading point.
fn small_room_lit(rng: &mut Xoshiro256PlusPlus, second: bool) -> Scene {
    let mut b = SceneBuilder::new();
    let w = b.world();
    let wall = b.material(Material::lambertian(Color::new(0.7, 0.6, 0.5)));
    let red = b.material(Material::lambertian(Color::new(0.65, 0.05, 0.05)));
    let lamp = b.material(Material::DiffuseLight {
        emit: Albedo::Constant(Color::splat(rng.random_range(2.0..15.0))),
        two_sided: rng.random(),
    });
    let ball = match rng.random_range(0..3) {
        0 => Material::Dielectric { ior: 1.5 },
        1 => Material::Metal {
            albedo: Color::splat(0.8),
            fuzz: rng.random_range(0.0..0.5),
        },
        _ => {
            let t = b.texture(rtl_render::texture::Texture::Checker {
                inv_scale: 1.0 / 0.7,
                even: Color::splat(0.2),
                odd: Color::splat(0.9),
            });
            Material::Lambertian {
                albedo: Albedo::Texture(t),
            }
        }
    };
    let ball = b.material(ball);
    let s = 4.0;
    let (x, y, z) = (Vec3::X * 2.0 * s, Vec3::Y * 2.0 * s, Vec3::Z * 2.0 * s);
    let c = Point3::splat(-s);
    b.quad(w, c, x, z, wall).unwrap(); // floor
    b.quad(w, c + y, z, x, wall).unwrap(); // ceiling
    b.quad(w, c + z, y, x, wall).unwrap(); // back
    b.quad(w, c, y, z, red).unwrap(); // left
    let light = (
        Point3::new(-1.0, s - 1e-3, -1.0),
        Vec3::X * 2.0,
        Vec3::Z * 2.0,
    );
    b.quad(w, light.0, light.1, light.2, lamp).unwrap();
    let inner = b
        .box_group(Point3::ZERO, Point3::new(1.5, 3.0, 1.5), wall)
        .unwrap();
    let tr = Transform::rotate_y(rng.random_range(-90.0..90.0))
        .then(Transform::translate(Point3::new(-2.5, -s, -1.0)));
    b.instance(w, inner, tr);
    let centre = Point3::new(1.5, -s + 1.2, 0.5);
    b.sphere(w, centre, 1.2, ball).unwrap();
    b.sphere(w, Point3::new(-2.0, 1.0, 2.0), 0.6, red).unwrap();
    if second {
        let glow = b.material(Material::DiffuseLight {
            emit: Albedo::Constant(Color::new(20.0, 8.0, 2.0)),
            two_sided: false,
        });
        let corner = Point3::new(2.0, s - 2e-3, 2.0);
        b.quad(w, corner, Vec3::X * 0.5, Vec3::Z * 0.5, glow)
            .unwrap();
    }
    b.targets.push(ImportanceTarget::Quad(
        rtl_render::shapes::Quad::new(light.0, light.1, light.2, rtl_render::scene::NO_MATERIAL)
            .unwrap(),
    ));
    if rng.random() {
        b.targets.push(ImportanceTarget::Sphere(Sphere::new(
            centre,
            1.2,
            rtl_render::scene::NO_MATERIAL,
        )));
    }
    b.camera = CameraSettings {
        lookfrom: Point3::new(0.0, 0.0, 3.0 * s),
        lookat: Point3::ZERO,
        vfov: 50.0,
        ..CameraSettings::default()
    };
    b.background = Background::Solid(Color::new(0.1, 0.1, 0.2));
    b.max_depth = 20;
    b.build().unwrap()
}

fn builtin(name: &str) -> Scene {
    (rtl_render::scenes::find(name).unwrap().build)(&Default::default())
        .unwrap()
        .scene
}

fn settings(width: usize, seed: u64, max_depth: u32, strategy: Strategy, w: f64) -> RenderSettings {
    RenderSettings {
        width,
        max_depth,
        seed,
        strategy,
        mixture_weight: w,
    }
}

/// The accumulator of passes `passes` (sample ranges) by `r`.
fn passes(r: &Renderer, ranges: &[(u64, u64)]) -> Accumulator {
    let mut acc = r.accumulator();
    for &(k0, k1) in ranges {
        r.render_pass(&mut acc, k0, k1, &|| {});
    }
    acc
}

/// Whether two accumulators are the same bit for bit (sums, counts, drops).
fn same(a: &Accumulator, b: &Accumulator) -> bool {
    let bits = |acc: &Accumulator| -> Vec<u64> {
        acc.sum
            .iter()
            .flat_map(|c| c.to_array().map(f64::to_bits))
            .collect()
    };
    bits(a) == bits(b) && a.count == b.count && a.dropped == b.dropped
}

/// Renders `scene` with the lanes and one path at a time, in each tier, and says whether every
/// image agrees bit for bit with the one-path-at-a-time image; `lanes` builds the lanes' renderer
/// (a deliberately wrong one for the check's own test).
fn lanes_agree(
    scene: &Scene,
    st: RenderSettings,
    ranges: &[(u64, u64)],
    lanes: impl for<'s> Fn(&'s Scene, RenderSettings) -> Renderer<'s>,
) -> bool {
    let reference = passes(&Renderer::new(scene, st).one_path_at_a_time(), ranges);
    let before = HitTier::current();
    let mut agree = true;
    for tier in tiers() {
        tier.select().unwrap();
        let r = lanes(scene, st);
        assert!(
            r.paths_in_lanes(),
            "{tier:?}: the lanes should take this scene ({st:?})"
        );
        agree &= same(&passes(&r, ranges), &reference);
    }
    before.select().unwrap();
    agree
}

/// The renderer as the renderer makes it.
fn plain(scene: &Scene, st: RenderSettings) -> Renderer<'_> {
    Renderer::new(scene, st)
}

#[test]
fn paths_side_by_side_give_the_image_of_one_at_a_time() {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(88);
    let strategies = [
        Strategy::Uniform,
        Strategy::Cosine,
        Strategy::Light,
        Strategy::Mixture,
    ];
    // The book's Cornell box, book 2's, and random small rooms; sample ranges that start past 0
    // and passes of one sample, as a progressive render takes them.
    for (i, name) in ["cornell", "cornell-book2", "quads"]
        .into_iter()
        .enumerate()
    {
        let scene = builtin(name);
        for (s, &strategy) in strategies.iter().enumerate() {
            let st = settings(12, 3 + i as u64, scene.max_depth, strategy, 0.5);
            let ranges: &[(u64, u64)] = if s % 2 == 0 {
                &[(0, 5)]
            } else {
                &[(2, 3), (3, 9)]
            };
            assert!(
                lanes_agree(&scene, st, ranges, plain),
                "{name} {strategy:?}"
            );
            if strategy == Strategy::Mixture {
                // the Lambertian vertex in the lanes (every wall of these rooms), and without it
                assert!(
                    lanes_agree(&scene, st, ranges, |s, st| {
                        let r = Renderer::new(s, st);
                        // (only the book 3 box lists targets: elsewhere no mixture in the lanes)
                        let lambertian = r.lambertian_vertex_in_lanes().is_some();
                        assert_eq!(lambertian, r.mixture_in_lanes().is_some(), "{name}");
                        assert!(lambertian || name != "cornell", "{name}");
                        r
                    }),
                    "{name}: the vertex in the lanes"
                );
                assert!(
                    lanes_agree(&scene, st, ranges, |s, st| Renderer::new(s, st)
                        .without_lambertian_vertex_in_lanes()),
                    "{name}: the vertex built lane by lane"
                );
                assert!(
                    lanes_agree(&scene, st, ranges, |s, st| {
                        let r = Renderer::new(s, st);
                        // (book 3's box has a glass ball)
                        let glass = r.glass_vertex_in_lanes().is_some();
                        assert!(glass || name != "cornell", "{name}");
                        r.without_glass_vertex_in_lanes()
                    }),
                    "{name}: the glass vertex built lane by lane"
                );
            }
        }
    }
    for i in 0..12 {
        let scene = small_room(&mut rng);
        let strategy = strategies[i % 4];
        let w = [0.5, 0.15, 0.85][i % 3];
        let depth = [20, 1, 2, 0][i % 4];
        let st = settings(10, i as u64, depth, strategy, w);
        assert!(
            lanes_agree(&scene, st, &[(0, 6)], plain),
            "room {i} {strategy:?}"
        );
    }
}

/// `mis` paths side by side ([`rtl_render::mis8`]) against one at a time: the book's boxes and
/// random small rooms (with one lamp or two, at depths 0 to 20), with each of the options on and
/// off. Scenes with media stay one path at a time.
#[test]
fn mis_paths_side_by_side_give_the_image_of_one_at_a_time() {
    let options = [
        MisOptions::DEFAULT,
        MisOptions {
            russian_roulette: false,
            spherical_rectangles: true,
            low_discrepancy: false,
            manifold: true,
        },
        MisOptions {
            russian_roulette: true,
            spherical_rectangles: true,
            low_discrepancy: true,
            manifold: true,
        },
    ];
    for (i, name) in ["cornell", "cornell-book2", "quads"]
        .into_iter()
        .enumerate()
    {
        let scene = builtin(name);
        for (o, &option) in options.iter().enumerate() {
            let st = settings(
                12,
                5 + i as u64,
                scene.max_depth,
                Strategy::Mis(option),
                0.5,
            );
            let ranges: &[(u64, u64)] = if o % 2 == 0 {
                &[(0, 5)]
            } else {
                &[(2, 3), (3, 9)]
            };
            assert!(lanes_agree(&scene, st, ranges, plain), "{name} {option:?}");
        }
    }
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(1717);
    for i in 0..12 {
        let scene = small_room_lit(&mut rng, i % 2 == 1);
        let depth = [20, 1, 2, 0, 3, 50][i % 6];
        let st = settings(10, i as u64, depth, Strategy::Mis(options[i % 3]), 0.5);
        assert!(
            lanes_agree(&scene, st, &[(0, 6)], plain),
            "room {i} depth {depth} {:?}",
            options[i % 3]
        );
    }
    // a medium: one path at a time
    let smoke = builtin("cornell-smoke");
    let r = Renderer::new(&smoke, settings(8, 1, 50, Strategy::default(), 0.5));
    assert!(!r.paths_in_lanes());
}

/// `mis`'s Lambertian vertex in the lanes ([`rtl_render::mis_vertex8`]) against one path at a
/// time: the Cornell box and small rooms with one lamp and a listed ball (glass, metal or a
/// texture), at depths 1 to 50, with Russian roulette and low-discrepancy numbers on and off; and
/// the same rooms with the vertex computed one path at a time inside the lanes.
#[test]
fn the_mis_vertex_in_the_lanes_gives_the_image_of_one_path_at_a_time() {
    let options = [
        MisOptions::DEFAULT,
        MisOptions {
            russian_roulette: false,
            spherical_rectangles: false,
            low_discrepancy: false,
            manifold: true,
        },
        MisOptions {
            russian_roulette: true,
            spherical_rectangles: false,
            low_discrepancy: false,
            manifold: true,
        },
    ];
    let cornell = builtin("cornell");
    for (o, &option) in options.iter().enumerate() {
        let st = settings(12, 3 + o as u64, 50, Strategy::Mis(option), 0.5);
        if !tiers().is_empty() {
            assert!(Renderer::new(&cornell, st).mis_vertex_in_lanes().is_some());
        }
        assert!(
            lanes_agree(&cornell, st, &[(0, 3), (3, 7)], plain),
            "{option:?}"
        );
    }
    if tiers().is_empty() {
        return; // no lanes here: no vertex in them to look for below
    }
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(1818);
    let mut rooms = 0;
    while rooms < 9 {
        let scene = small_room(&mut rng);
        let depth = [50, 1, 2, 3, 20][rooms % 5];
        let st = settings(
            10,
            rooms as u64,
            depth,
            Strategy::Mis(options[rooms % 3]),
            0.5,
        );
        if Renderer::new(&scene, st).mis_vertex_in_lanes().is_none() {
            continue; // the ball is not listed: no other target
        }
        assert!(lanes_agree(&scene, st, &[(0, 6)], plain), "room {rooms}");
        assert!(
            lanes_agree(&scene, st, &[(0, 6)], |s, st| Renderer::new(s, st)
                .with_mis_vertex_in_lanes(None)),
            "room {rooms}"
        );
        rooms += 1;
    }
    // two lamps (a choice of emitter to weigh): one path at a time
    let two = small_room_lit(&mut rng, true);
    let st = settings(8, 1, 20, Strategy::default(), 0.5);
    assert!(Renderer::new(&two, st).mis_vertex_in_lanes().is_none());
}

#[test]
fn the_image_check_catches_a_mis_vertex_with_another_share() {
    // The lanes' share of the other targets one ulp above the integrator's.
    let scene = builtin("cornell");
    let st = settings(10, 1, 50, Strategy::default(), 0.5);
    fn wrong(scene: &Scene, st: RenderSettings) -> Renderer<'_> {
        let r = Renderer::new(scene, st);
        let share = f64::from_bits(rtl_render::integrator::OTHERS_SHARE.to_bits() + 1);
        let m = rtl_render::mis_vertex8::MisLanes::with_share(&r.lights, share);
        assert!(m.is_some());
        r.with_mis_vertex_in_lanes(m)
    }
    assert!(lanes_agree(&scene, st, &[(0, 4)], plain));
    if !tiers().is_empty() {
        assert!(!lanes_agree(&scene, st, &[(0, 4)], wrong));
    }
}

#[test]
fn the_image_check_catches_lanes_with_another_mixture_weight() {
    // Lanes drawing with a weight one ulp above the one the single path uses.
    let scene = builtin("cornell");
    let st = settings(10, 1, 50, Strategy::Mixture, 0.5);
    assert!(lanes_agree(&scene, st, &[(0, 4)], plain));
    fn wrong(scene: &Scene, st: RenderSettings) -> Renderer<'_> {
        let r = Renderer::new(scene, st);
        let m = Mixture8::new(
            &r.lights.all,
            f64::from_bits(st.mixture_weight.to_bits() + 1),
        );
        r.with_mixture_in_lanes(m)
    }
    if !tiers().is_empty() {
        assert!(!lanes_agree(&scene, st, &[(0, 4)], wrong));
    }
}

/// Small rooms whose ball is glass, traced by `mixture` to depths from 1 to 50, with the glass
/// vertex in the lanes (every tier) and without.
#[test]
fn the_glass_vertex_in_the_lanes_gives_the_image_of_one_path_at_a_time() {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(1616);
    let mut rooms = 0;
    while rooms < 6 {
        let scene = small_room(&mut rng);
        let glass = scene
            .materials
            .iter()
            .any(|m| matches!(m, Material::Dielectric { .. }));
        if !glass {
            continue;
        }
        let depth = [50, 1, 3][rooms % 3];
        let st = settings(
            10,
            rooms as u64,
            depth,
            Strategy::Mixture,
            [0.5, 0.2][rooms % 2],
        );
        let r = Renderer::new(&scene, st);
        if !tiers().is_empty() {
            assert!(r.glass_vertex_in_lanes().is_some(), "room {rooms}");
        }
        assert!(lanes_agree(&scene, st, &[(0, 6)], plain), "room {rooms}");
        assert!(
            lanes_agree(&scene, st, &[(0, 6)], |s, st| Renderer::new(s, st)
                .without_glass_vertex_in_lanes()),
            "room {rooms}"
        );
        rooms += 1;
    }
}

#[test]
fn the_image_check_catches_a_glass_vertex_with_another_index() {
    // The lanes' glass one ulp denser than the scene's.
    let scene = builtin("cornell");
    let st = settings(10, 1, 50, Strategy::Mixture, 0.5);
    fn wrong(scene: &Scene, st: RenderSettings) -> Renderer<'_> {
        let mut denser = scene.clone();
        for m in &mut denser.materials {
            if let Material::Dielectric { ior } = m {
                *ior = f64::from_bits(ior.to_bits() + 1);
            }
        }
        let g = rtl_render::glass8::GlassSpheres::new(&denser, GroupId(0));
        assert!(g.is_some());
        Renderer::new(scene, st).with_glass_vertex_in_lanes(g)
    }
    assert!(lanes_agree(&scene, st, &[(0, 4)], plain));
    if !tiers().is_empty() {
        assert!(!lanes_agree(&scene, st, &[(0, 4)], wrong));
    }
}

#[test]
fn a_stopped_row_of_lanes_gives_up_and_the_rest_is_kept() {
    let scene = builtin("cornell");
    let st = settings(16, 2, 50, Strategy::Mixture, 0.5);
    let r = Renderer::new(&scene, st);
    let asked = std::sync::atomic::AtomicUsize::new(0);
    let mut acc = r.accumulator();
    let stop = || asked.fetch_add(1, std::sync::atomic::Ordering::Relaxed) > 40;
    assert!(r.render_pass_until(&mut acc, 0, 4, &|| {}, &stop).is_none());
    // and without stopping, the same counters as one path at a time
    let mut a = r.accumulator();
    let sa = r.render_pass(&mut a, 0, 4, &|| {});
    let one = Renderer::new(&scene, st).one_path_at_a_time();
    let mut b = one.accumulator();
    let sb = one.render_pass(&mut b, 0, 4, &|| {});
    assert_eq!(sa, sb);
    assert!(same(&a, &b));
}

// ---------------------------------------------------------------------------------------------
// The rays' intersection

/// Rays from outside and from inside a scene of size about 6, aimed near its middle or anywhere,
/// and some aimed at a quad's corner or edge exactly.
fn rays8<R: Rng>(rng: &mut R, corners: &[Point3]) -> [Ray; 8] {
    std::array::from_fn(|_| {
        let o = if rng.random::<bool>() {
            unit(rng) * 20.0
        } else {
            point(rng, 6.0)
        };
        let d = match rng.random_range(0..4) {
            0 => point(rng, 5.0) - o,
            1 if !corners.is_empty() => corners[rng.random_range(0..corners.len())] - o,
            3 if !corners.is_empty() => {
                // in an axis plane through a corner `c`: hits on the edge lines of the quads
                // in axis planes, where `alpha` or `beta` is exactly zero (of either sign)
                let c = corners[rng.random_range(0..corners.len())];
                let axis = rng.random_range(0..3);
                let mut o = o;
                o[axis] = c[axis];
                let mut d = point(rng, 5.0) - o;
                d[axis] = if rng.random() { 0.0 } else { -0.0 };
                return Ray::new(o, d, 0.0);
            }
            _ => unit(rng),
        };
        Ray::new(o, d, 0.0)
    })
}

/// A small random group (up to twelve quads and two spheres, or a rotated box instance that stays
/// an instance), as its world.
fn small_group<R: Rng>(rng: &mut R) -> (Scene, Vec<Point3>) {
    let mut b = SceneBuilder::new();
    let m = b.material(Material::lambertian(Color::splat(0.5)));
    let w = b.world();
    let mut corners = Vec::new();
    for _ in 0..rng.random_range(1..=12) {
        let (q, u, v) = (
            point(rng, 6.0),
            unit(rng) * rng.random_range(0.5..6.0),
            unit(rng) * rng.random_range(0.5..6.0),
        );
        // some quads in axis planes, as the Cornell box's, their sides either way along the axes
        let (u, v) = if rng.random::<bool>() {
            let axes = [Vec3::X, Vec3::Y, Vec3::Z];
            let a = rng.random_range(0..3);
            let b = (a + rng.random_range(1..3)) % 3;
            let sign = |rng: &mut R| if rng.random() { 1.0 } else { -1.0 };
            (
                axes[a] * u.length() * sign(rng),
                axes[b] * v.length() * sign(rng),
            )
        } else {
            (u, v)
        };
        b.quad(w, q, u, v, m).unwrap();
        corners.extend([q, q + u, q + v, q + u + v, q + 0.5 * u]);
    }
    for _ in 0..rng.random_range(0..=2) {
        if rng.random_range(0..4) == 0 {
            let inner = b.box_group(Point3::ZERO, Point3::ONE * 2.0, m).unwrap();
            b.instance(w, inner, Transform::rotate_y(rng.random_range(-90.0..90.0)));
        } else {
            b.sphere(w, point(rng, 5.0), rng.random_range(0.3..3.0), m)
                .unwrap();
        }
    }
    // (an instance flattened or not: tested behind its box in the lanes, or as another object)
    b.flatten = rng.random();
    (b.build().unwrap(), corners)
}

/// How many lanes `Scene::hit8_small` (in `tier`) finds otherwise than `Scene::hit_group` one ray at
/// a time, over the batches of rays.
fn hit8_mismatches(scene: &Scene, tier: HitTier, batches: &[[Ray; 8]]) -> usize {
    let g = GroupId(0);
    if !scene.hits_eight_at_once(g) {
        return 0;
    }
    let mut wrong = 0;
    let mut ctxs: [Ctx; 8] = std::array::from_fn(|_| Ctx::new());
    let mut ctx = Ctx::new();
    for rays in batches {
        let mut lanes = Rays8::default();
        for (l, r) in rays.iter().enumerate() {
            lanes.set(l, r);
        }
        let mut found = Closest8::default();
        let mut per_lane = [Found::NOTHING; 8];
        let active = 0b1011_1111; // one lane idle
        // SAFETY: `tier` is one this processor runs (see `tiers`).
        let hits = unsafe {
            scene.hit8_small(
                tier,
                g,
                rays,
                &lanes,
                active,
                Interval::FORWARD,
                &mut ctxs,
                &mut found,
                &mut per_lane,
            )
        };
        for (l, ray) in rays.iter().enumerate() {
            if active & (1 << l) == 0 {
                continue;
            }
            let one = record(scene.hit_group(g, ray, Interval::FORWARD, &mut ctx));
            wrong += (record(hits.record(&found, &per_lane, l, ray)) != one) as usize;
        }
    }
    wrong
}

#[test]
fn eight_rays_at_once_meet_what_one_ray_at_a_time_meets() {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(8);
    let mut lanes_tested = 0;
    for _ in 0..150 {
        let (scene, corners) = small_group(&mut rng);
        let batches: Vec<[Ray; 8]> = (0..40).map(|_| rays8(&mut rng, &corners)).collect();
        lanes_tested += scene.hits_eight_at_once(GroupId(0)) as usize;
        for tier in tiers() {
            assert_eq!(hit8_mismatches(&scene, tier, &batches), 0, "{tier:?}");
        }
    }
    assert!(lanes_tested > 100, "{lanes_tested}");
}

/// [`closest_avx512`] or [`closest_avx2`] (`tier`) of the small group `accel` with the spheres
/// `spheres`, for the rays `lanes`, over [`Interval::FORWARD`].
fn closest_in(
    tier: HitTier,
    accel: &rtl_render::traversal::Accel,
    spheres: &[(Sphere, rtl_render::aabb::Aabb)],
    lanes: &Rays8,
) -> Closest8 {
    closest_with(tier, &accel.lane_quads, spheres, lanes)
}

/// [`closest_avx512`] or [`closest_avx2`] (`tier`) of the quads `quads` and the spheres `spheres`,
/// for the rays `lanes`, over [`Interval::FORWARD`].
fn closest_with(
    tier: HitTier,
    quads: &LaneQuads,
    spheres: &[(Sphere, rtl_render::aabb::Aabb)],
    lanes: &Rays8,
) -> Closest8 {
    let mut got = Closest8::default();
    let range = Interval::FORWARD;
    // SAFETY: the tests pass only tiers this processor runs (see `tiers`).
    unsafe {
        match tier {
            HitTier::Avx512 => closest_avx512(quads, spheres, lanes, range, &mut got),
            _ => closest_avx2(quads, spheres, lanes, range, &mut got),
        }
    }
    got
}

/// The box of quad `k` of a small group's packets (`accel`, of the group `objects`).
fn quad_bounds(
    accel: &rtl_render::traversal::Accel,
    objects: &[rtl_render::scene::Object],
    k: usize,
) -> rtl_render::aabb::Aabb {
    let object = accel.packets[k / 4].index[k % 4] as usize;
    match &objects[object] {
        rtl_render::scene::Object::Quad(q) => q.bounds(),
        _ => unreachable!("a packet's lane holds a quad"),
    }
}

/// Up to two disjoint random sets of a small group's quads, each behind the union of its quads'
/// boxes; `shrink`: each box only its first quad's (too small for the rest: a wrong cluster).
fn random_clusters<R: Rng>(
    rng: &mut R,
    accel: &rtl_render::traversal::Accel,
    objects: &[rtl_render::scene::Object],
    shrink: bool,
) -> Vec<Cluster> {
    let n = accel
        .packets
        .iter()
        .map(|p| p.index.iter().filter(|&&i| i != u32::MAX).count())
        .sum::<usize>();
    let mut clusters: Vec<Cluster> = Vec::new();
    let mut taken = 0u64;
    for _ in 0..rng.random_range(1..=2) {
        let mut quads = 0u64;
        for k in 0..n {
            if taken & (1 << k) == 0 && rng.random_range(0..3) == 0 {
                quads |= 1 << k;
            }
        }
        if quads == 0 {
            continue;
        }
        taken |= quads;
        let first = quads.trailing_zeros() as usize;
        let mut bounds = quad_bounds(accel, objects, first);
        if !shrink {
            for k in (0..n).filter(|k| quads & (1 << k) != 0) {
                bounds = bounds.union(&quad_bounds(accel, objects, k));
            }
        }
        clusters.push(Cluster { quads, bounds });
    }
    clusters
}

/// How many lanes differ from [`closest_portable`] (bit for bit: the hit, `t`, `alpha`, `beta`)
/// with random clusters of the quads ([`random_clusters`]), and how many lanes' closest hit is a
/// cluster's quad, over random small groups and rays.
fn cluster_mismatches(seed: u64, tier: HitTier, shrink: bool) -> (usize, usize) {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let (mut wrong, mut in_clusters) = (0, 0);
    for _ in 0..150 {
        let (scene, corners) = small_group(&mut rng);
        let group = &scene.groups[0];
        let accel = &group.accel;
        if !accel.flat {
            continue;
        }
        let spheres = accel.spheres.as_deref().unwrap_or(&[]);
        let clusters = random_clusters(&mut rng, accel, &group.objects, shrink);
        let quads = LaneQuads::new(&accel.packets, &clusters);
        let clustered = clusters.iter().fold(0, |all, c| all | c.quads);
        for _ in 0..40 {
            let mut rays = Rays8::default();
            for (l, r) in rays8(&mut rng, &corners).iter().enumerate() {
                rays.set(l, r);
            }
            let want = closest_portable(&accel.packets, spheres, &rays, Interval::FORWARD);
            let got = closest_with(tier, &quads, spheres, &rays);
            for l in 0..8 {
                wrong += (lane_bits(&got, l) != lane_bits(&want, l)) as usize;
                let h = want.hit[l];
                in_clusters += (h < 64 && clustered & (1 << h) != 0) as usize;
            }
        }
    }
    (wrong, in_clusters)
}

#[test]
fn quads_behind_their_box_are_found_as_in_order_bit_for_bit() {
    for tier in tiers() {
        let (wrong, in_clusters) = cluster_mismatches(31, tier, false);
        assert_eq!(wrong, 0, "{tier:?}");
        assert!(in_clusters > 2_000, "{tier:?}: {in_clusters}");
    }
}

#[test]
fn the_cluster_check_catches_a_box_too_small_for_its_quads() {
    for tier in tiers() {
        let (wrong, _) = cluster_mismatches(31, tier, true);
        assert!(wrong > 100, "{tier:?}: {wrong}");
    }
}

#[test]
fn on_equal_distances_a_cluster_yields_to_an_earlier_quad_and_wins_over_a_later_one() {
    // Two copies of one floor (quads 0 and 1) and three more quads: every ray down meets both copies
    // at the same `t`, and the first copy must win whichever of them is behind a box.
    let mut b = SceneBuilder::new();
    let m = b.material(Material::lambertian(Color::splat(0.5)));
    let w = b.world();
    let floor = (
        Point3::new(-2.0, 0.0, -2.0),
        Vec3::new(4.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 4.0),
    );
    b.quad(w, floor.0, floor.1, floor.2, m).unwrap();
    b.quad(w, floor.0, floor.1, floor.2, m).unwrap();
    for x in [3.0, 4.0, 5.0] {
        b.quad(w, Point3::new(x, 0.0, 0.0), Vec3::Y, Vec3::Z, m)
            .unwrap();
    }
    b.flatten = false;
    let scene = b.build().unwrap();
    let group = &scene.groups[0];
    let accel = &group.accel;
    let copies: Vec<usize> = (0..5)
        .filter(|&k| quad_bounds(accel, &group.objects, k).max.y < 1e-3)
        .collect();
    assert_eq!(copies.len(), 2, "both copies of the floor in the packets");
    let mut rays = Rays8::default();
    for l in 0..8 {
        let o = Point3::new(-1.5 + 0.4 * l as f64, 1.0, 0.3);
        rays.set(l, &Ray::new(o, Vec3::new(0.01, -1.0, 0.02), 0.0));
    }
    for tier in tiers() {
        for behind in [copies[0], copies[1]] {
            let bounds = quad_bounds(accel, &group.objects, behind);
            let clusters = [Cluster {
                quads: 1 << behind,
                bounds,
            }];
            let got = closest_with(tier, &LaneQuads::new(&accel.packets, &clusters), &[], &rays);
            assert_eq!(
                got.hit, [copies[0] as u32; 8],
                "{tier:?}, quad {behind} behind a box"
            );
        }
    }
}

/// The closest hits of the eight rays `rays`: [`closest_portable`]'s against the spheres `spheres`,
/// then [`closest_in`]'s in `tier` against `spheres_for_lanes` (the same, unless a test gives the
/// lanes a wrong sphere).
fn portable_and_lanes(
    tier: HitTier,
    accel: &rtl_render::traversal::Accel,
    spheres: &[(Sphere, rtl_render::aabb::Aabb)],
    spheres_for_lanes: &[(Sphere, rtl_render::aabb::Aabb)],
    rays: &[Ray; 8],
) -> (Closest8, Closest8) {
    let mut lanes = Rays8::default();
    for (l, r) in rays.iter().enumerate() {
        lanes.set(l, r);
    }
    let want = closest_portable(&accel.packets, spheres, &lanes, Interval::FORWARD);
    (want, closest_in(tier, accel, spheres_for_lanes, &lanes))
}

/// Lane `l` of `c` bit for bit: the hit and `t`.
fn lane_bits(c: &Closest8, l: usize) -> (u32, u64) {
    (c.hit[l], c.t[l].to_bits())
}

/// How many lanes of [`closest_avx512`] or [`closest_avx2`] (`tier`) differ from
/// [`closest_portable`], over random rays.
fn closest_mismatches(
    rng: &mut Xoshiro256PlusPlus,
    tier: HitTier,
    scene: &Scene,
    spheres_for_lanes: &[(Sphere, rtl_render::aabb::Aabb)],
) -> usize {
    let accel = &scene.groups[0].accel;
    let spheres = accel.spheres.as_deref().unwrap_or(&[]);
    let mut wrong = 0;
    for _ in 0..60 {
        let rays = rays8(rng, &[]);
        let (want, got) = portable_and_lanes(tier, accel, spheres, spheres_for_lanes, &rays);
        wrong += (0..8)
            .filter(|&l| lane_bits(&got, l) != lane_bits(&want, l))
            .count();
    }
    wrong
}

/// [`closest_in`] for the rays `lanes` (in `tier`) against [`closest_portable`], bit for bit lane by
/// lane; the portable form's answer.
fn assert_lanes_agree(
    tier: HitTier,
    accel: &rtl_render::traversal::Accel,
    spheres: &[(Sphere, rtl_render::aabb::Aabb)],
    lanes: &[Ray; 8],
) -> Closest8 {
    let (want, got) = portable_and_lanes(tier, accel, spheres, spheres, lanes);
    for l in 0..8 {
        assert_eq!(lane_bits(&got, l), lane_bits(&want, l), "{tier:?} lane {l}");
    }
    want
}

/// The quad a lane's hit `h` names (its place in the packets' order).
fn quad_of(scene: &Scene, h: u32) -> &rtl_render::shapes::Quad {
    let group = &scene.groups[0];
    let index = group.accel.packets[h as usize / 4].index[h as usize % 4];
    match &group.objects[index as usize] {
        rtl_render::scene::Object::Quad(q) => q,
        _ => panic!("a packet lane names a quad"),
    }
}

#[test]
fn eight_rays_at_once_find_the_edges_of_quads_in_axis_planes_bit_for_bit() {
    // Rays in axis planes through the quads' corners hit edge lines, where `alpha` or `beta` is a
    // zero of either sign (`ray8::QuadForm`): the lanes find the hits the one-ray test finds, and
    // the Lambertian vertex's coordinates of them are `Quad::coordinates`', zeros' signs too.
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(10);
    for tier in tiers() {
        let mut zeros = [0usize; 2];
        for _ in 0..150 {
            let (scene, corners) = small_group(&mut rng);
            let accel = &scene.groups[0].accel;
            let spheres = accel.spheres.as_deref().unwrap_or(&[]);
            let surfaces = rtl_render::vertex8::QuadSurfaces::new(&scene, GroupId(0));
            for _ in 0..40 {
                let rays = rays8(&mut rng, &corners);
                let want = assert_lanes_agree(tier, accel, spheres, &rays);
                let quads = (0..8).filter(|&l| want.hit[l] < rtl_render::ray8::SPHERE);
                let lanes = quads.clone().fold(0u8, |m, l| m | 1 << l);
                let Some(surfaces) = surfaces.as_ref().filter(|_| lanes != 0) else {
                    continue;
                };
                let mut packed = Rays8::default();
                for (l, r) in rays.iter().enumerate() {
                    packed.set(l, r);
                }
                // SAFETY: `tiers` gives only the forms this processor runs.
                let [alpha, beta] = unsafe {
                    rtl_render::vertex8::coordinates(tier, surfaces, &want, &packed, lanes)
                };
                for l in quads {
                    let q = quad_of(&scene, want.hit[l]);
                    let (a, b) = q.coordinates(&rays[l], want.t[l]);
                    let got = [alpha.0[l], beta.0[l]];
                    assert_eq!(got.map(f64::to_bits), [a, b].map(f64::to_bits), "{tier:?}");
                    for x in [a, b] {
                        if x == 0.0 {
                            zeros[x.is_sign_negative() as usize] += 1;
                        }
                    }
                }
            }
        }
        assert!(
            zeros[0] > 50 && zeros[1] > 50,
            "{tier:?}: edge hits {zeros:?}"
        );
    }
}

#[test]
fn a_ray_with_a_nan_coordinate_meets_in_the_lanes_what_it_meets_alone() {
    // A NaN in a coordinate of the origin that an axis-plane quad's `t` does not read makes its
    // `alpha` or `beta` NaN while `t` is a fine number: the lanes' `0 <= alpha, beta <= 1` (a
    // `min` and a `max`, `ray8`) must refuse it as the portable form does, whichever it is in.
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(12);
    for tier in tiers() {
        let mut nan_lanes = 0;
        for _ in 0..150 {
            let (scene, corners) = small_group(&mut rng);
            let accel = &scene.groups[0].accel;
            let spheres = accel.spheres.as_deref().unwrap_or(&[]);
            for _ in 0..20 {
                let mut lanes = rays8(&mut rng, &corners);
                for (l, ray) in lanes.iter_mut().enumerate().filter(|(l, _)| l % 4 != 3) {
                    let mut o = ray.origin;
                    o[l % 3] = f64::NAN;
                    *ray = Ray::new(o, ray.direction, 0.0);
                    nan_lanes += 1;
                }
                assert_lanes_agree(tier, accel, spheres, &lanes);
            }
        }
        assert!(nan_lanes > 10_000, "{nan_lanes}");
    }
}

#[test]
fn the_intersection_check_catches_a_sphere_one_ulp_too_large() {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(9);
    for tier in tiers() {
        let (mut caught, mut tried) = (0, 0);
        while tried < 20 {
            let (scene, _) = small_group(&mut rng);
            let Some(spheres) = scene.groups[0].accel.spheres.clone() else {
                continue;
            };
            if spheres.is_empty() {
                continue;
            }
            tried += 1;
            assert_eq!(closest_mismatches(&mut rng, tier, &scene, &spheres), 0);
            let grown: Vec<_> = spheres
                .iter()
                .map(|(s, b)| {
                    let mut s = *s;
                    s.radius = f64::from_bits(s.radius.to_bits() + 1) * (1.0 + 1e-9);
                    (s, *b)
                })
                .collect();
            caught += (closest_mismatches(&mut rng, tier, &scene, &grown) > 0) as usize;
        }
        assert!(caught >= 10, "{tier:?}: {caught} of {tried}");
    }
}

// ---------------------------------------------------------------------------------------------
// The warps

/// Numbers for the warps: random ones, and the ends and middles that take special branches.
fn numbers(rng: &mut Xoshiro256PlusPlus) -> Vec<[f64; 2]> {
    let edges = [
        0.0,
        1.0 - f64::EPSILON / 2.0,
        0.5,
        0.25,
        0.75,
        0.125,
        0.375,
        0.625,
        0.875,
        f64::EPSILON,
        0.5 - f64::EPSILON / 4.0,
    ];
    let mut out = Vec::new();
    for &a in &edges {
        for &b in &edges {
            out.push([a, b]);
        }
    }
    out.extend((0..4000).map(|_| [rng.random(), rng.random()]));
    out
}

/// Eight lanes of `x`, from `f(i)`.
fn lanes_of(f: impl Fn(usize) -> f64) -> F64x8 {
    F64x8(std::array::from_fn(f))
}

/// The warps of `W` on `us`, against rtl-pdf's; `wrong` perturbs the lanes' input by one ulp in
/// lane 3 (a deliberately wrong lane, for the check's own test). Returns the lanes that differ.
///
/// # Safety
/// Only where the processor has `W`'s instructions.
unsafe fn warp_mismatches<W: Wide8>(us: &[[f64; 2]], wrong: bool) -> usize {
    let mut bad = 0;
    for chunk in us.chunks(8) {
        let u = |i: usize, c: usize| chunk[i % chunk.len()][c];
        let x = lanes_of(|i| {
            let v = u(i, 0);
            if wrong && i == 3 {
                f64::from_bits(v.to_bits() + 1)
            } else {
                v
            }
        });
        let y = lanes_of(|i| u(i, 1));
        // SAFETY: as this function's.
        let (ux, uy) = unsafe { (W::load(&x), W::load(&y)) };
        let cos = warp8::sample_cosine_hemisphere([ux, uy]);
        let sphere = warp8::sample_uniform_sphere([ux, uy]);
        let omc = ux.splat_like(0.3) * ux + ux.splat_like(1e-9);
        let cone = warp8::sample_uniform_cone([ux, uy], omc);
        let one_minus = warp8::cone_one_minus_cos(ux);
        let onb = warp8::Onb8::new(sphere).transform(cos);
        let pdf = warp8::uniform_cone_pdf(omc);
        let stored = |v: [W; 3]| v.map(|c| c.store());
        let (cos, sphere, cone, onb) = (stored(cos), stored(sphere), stored(cone), stored(onb));
        let (omc, one_minus, pdf) = (omc.store(), one_minus.store(), pdf.store());
        for i in 0..chunk.len() {
            let uv = DVec2::new(u(i, 0), u(i, 1));
            let lane = |v: &[F64x8; 3]| DVec3::new(v[0].0[i], v[1].0[i], v[2].0[i]);
            let s_sphere = rtl_pdf::warp::sample_uniform_sphere(uv);
            let want = [
                rtl_pdf::warp::sample_cosine_hemisphere(uv),
                s_sphere,
                rtl_pdf::warp::sample_uniform_cone(uv, omc.0[i]),
                rtl_pdf::Onb::new(s_sphere).transform(rtl_pdf::warp::sample_cosine_hemisphere(uv)),
            ];
            let got = [lane(&cos), lane(&sphere), lane(&cone), lane(&onb)];
            let scalars = [
                (rtl_pdf::warp::cone_one_minus_cos(u(i, 0)), one_minus.0[i]),
                (rtl_pdf::warp::uniform_cone_pdf(omc.0[i]), pdf.0[i]),
            ];
            let differs = want
                .iter()
                .zip(&got)
                .any(|(w, g)| w.to_array().map(f64::to_bits) != g.to_array().map(f64::to_bits))
                || scalars.iter().any(|(w, g)| w.to_bits() != g.to_bits());
            bad += differs as usize;
        }
    }
    bad
}

#[test]
fn the_lanes_warps_are_rtl_pdfs_bit_for_bit() {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(5);
    let us = numbers(&mut rng);
    for tier in tiers() {
        // SAFETY: the processor runs `tier`, whose instructions each form needs.
        let (right, wrong) = unsafe {
            match tier {
                HitTier::Avx512 => (
                    warp_mismatches::<Avx512>(&us, false),
                    warp_mismatches::<Avx512>(&us, true),
                ),
                _ => (
                    warp_mismatches::<Avx2>(&us, false),
                    warp_mismatches::<Avx2>(&us, true),
                ),
            }
        };
        assert_eq!(right, 0, "{tier:?}");
        assert!(
            wrong > us.len() / 16,
            "{tier:?}: a perturbed lane went unnoticed ({wrong})"
        );
    }
}

// ---------------------------------------------------------------------------------------------
// The mixture

/// Target lists: the book's light and glass ball; a one-sided lamp alone; a sphere alone; three
/// targets (a count that is no power of two); two spheres, one around the origins.
fn target_lists() -> Vec<Vec<LightTarget>> {
    let quad = |one_sided| LightTarget::Quad {
        quad: QuadTarget::new(
            DVec3::new(-1.0, 4.0, -1.0),
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(0.0, 0.0, 2.0),
        ),
        one_sided,
    };
    let tilted = LightTarget::Quad {
        quad: QuadTarget::new(
            DVec3::new(3.0, 0.0, -2.0),
            DVec3::new(0.3, 1.5, 0.2),
            DVec3::new(-0.4, 0.1, 1.8),
        ),
        one_sided: true,
    };
    let ball = LightTarget::Sphere(SphereTarget::new(DVec3::new(1.0, 0.5, 0.5), 0.9));
    let tiny = LightTarget::Sphere(SphereTarget::new(DVec3::new(-2.0, 1.0, 3.0), 1e-9));
    let around = LightTarget::Sphere(SphereTarget::new(DVec3::ZERO, 6.0));
    vec![
        vec![quad(false), ball],
        vec![quad(true)],
        vec![ball],
        vec![quad(true), ball, tilted],
        vec![tiny, around],
    ]
}

/// How many of the lanes of [`Mixture8`] (`targets` with `lanes_weight`, in `tier`) differ from
/// `sample_diffuse` of `mixture` with weight `w` (direction, weight, or whether the path goes on).
fn mixture_mismatches(
    rng: &mut Xoshiro256PlusPlus,
    tier: HitTier,
    targets: &[LightTarget],
    w: f64,
    lanes_weight: f64,
) -> usize {
    let lights = Lights {
        all: targets.to_vec(),
        ..Lights::default()
    };
    let m = Mixture8::new(&lights.all, lanes_weight).expect("the lanes take these targets");
    let mut wrong = 0;
    for round in 0..300 {
        let p: [DVec3; 8] = std::array::from_fn(|i| match (round + i) % 5 {
            // on the lamp's plane, and exactly below its corner
            0 => DVec3::new(
                rng.random_range(-3.0..3.0),
                4.0,
                rng.random_range(-3.0..3.0),
            ),
            1 => DVec3::new(-1.0, rng.random_range(-3.0..3.0), -1.0),
            _ => point(rng, 5.0),
        });
        let n: [DVec3; 8] = std::array::from_fn(|_| unit(rng));
        let u: [DVec2; 8] = std::array::from_fn(|i| match (round + i) % 7 {
            0 => DVec2::new(w, rng.random()),
            1 => DVec2::new(0.0, 0.0),
            2 => DVec2::new(1.0 - f64::EPSILON / 2.0, 1.0 - f64::EPSILON / 2.0),
            _ => DVec2::new(rng.random(), rng.random()),
        });
        let coord = |v: &[DVec3; 8], a: usize| lanes_of(|i| v[i][a]);
        let (pp, nn) = (
            [coord(&p, 0), coord(&p, 1), coord(&p, 2)],
            [coord(&n, 0), coord(&n, 1), coord(&n, 2)],
        );
        let uu = [lanes_of(|i| u[i].x), lanes_of(|i| u[i].y)];
        let lanes = 0b1111_0111; // one lane idle
        // SAFETY: `tier` is one this processor runs.
        let (d, weight, ok) = unsafe { m.sample(tier, &pp, &nn, &uu, lanes) };
        for i in 0..8 {
            if lanes & (1 << i) == 0 {
                continue;
            }
            let pdf = ScatterPdf::Cosine(CosinePdf::new(n[i]));
            let want = sample_diffuse(Strategy::Mixture, w, &pdf, p[i], n[i], &lights, u[i]);
            let got = (ok & (1 << i) != 0)
                .then(|| (DVec3::new(d[0].0[i], d[1].0[i], d[2].0[i]), weight.0[i]));
            let bits = |x: Option<(DVec3, f64)>| {
                x.map(|(d, w)| (d.to_array().map(f64::to_bits), w.to_bits()))
            };
            wrong += (bits(got) != bits(want)) as usize;
        }
    }
    wrong
}

#[test]
fn the_mixture_in_the_lanes_is_sample_diffuse_bit_for_bit() {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(10);
    for tier in tiers() {
        for targets in target_lists() {
            for w in [0.5, 0.15, 0.9] {
                let bad = mixture_mismatches(&mut rng, tier, &targets, w, w);
                assert_eq!(bad, 0, "{tier:?}, {} targets, w {w}", targets.len());
            }
        }
    }
}

#[test]
fn the_mixture_check_catches_a_weight_one_ulp_off() {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(11);
    for tier in tiers() {
        let targets = &target_lists()[0];
        let off = f64::from_bits(0.5f64.to_bits() + 1);
        assert!(
            mixture_mismatches(&mut rng, tier, targets, 0.5, off) > 100,
            "{tier:?}"
        );
    }
}

#[test]
fn the_lanes_refuse_what_they_do_not_follow() {
    let quad = QuadTarget::new(DVec3::ZERO, DVec3::X, DVec3::Z);
    let by_rectangles = LightTarget::Quad {
        quad: quad.with_spherical_rectangles(true),
        one_sided: false,
    };
    assert!(Mixture8::new(&[by_rectangles], 0.5).is_none());
    assert!(Mixture8::new(&[], 0.5).is_none());
    let plain = LightTarget::Quad {
        quad,
        one_sided: false,
    };
    assert!(Mixture8::new(&[plain], 0.5).is_some());
    assert!(Mixture8::new(&vec![plain; rtl_render::mixture8::MAX_TARGETS + 1], 0.5).is_none());
    // a tree is not one small group (for mis neither, whose lanes are tested above)
    let cornell = builtin("cornell");
    let tree = builtin("book2-final");
    let mis = Renderer::new(&tree, settings(8, 1, 40, Strategy::default(), 0.5));
    assert!(!mis.paths_in_lanes());
    let r = Renderer::new(&tree, settings(8, 1, 40, Strategy::Mixture, 0.5));
    assert!(!r.paths_in_lanes());
    // where an AVX tier runs, the book's Cornell box takes the lanes for mixture
    let m = Renderer::new(&cornell, settings(8, 1, 50, Strategy::Mixture, 0.5));
    assert_eq!(
        m.paths_in_lanes(),
        HitTier::current() != HitTier::Portable,
        "{:?}",
        HitTier::current()
    );
}

// ---------------------------------------------------------------------------------------------
// The glass vertex

/// How many of `n` rays at book 3's glass ball (from outside, and from inside at every angle, so
/// that some reflect totally) get from [`rtl_render::glass8::dielectric`], with the glass spheres
/// `glass`, another next ray than `Material::scatter` and `Hit::spawn` give, or another answer to
/// whether the vertex asked for its uniform number; and how many asked for it.
fn glass_mismatches(glass: &rtl_render::glass8::GlassSpheres, n: usize) -> (usize, usize) {
    use rtl_render::glass8::{Glass8, GlassSpheres, dielectric};
    use rtl_render::sampler::{Dimension, SampleRng};
    let scene = builtin("cornell");
    let spheres = scene.groups[0]
        .accel
        .spheres
        .as_ref()
        .expect("static spheres");
    let (i, (ball, _)) = spheres
        .iter()
        .enumerate()
        .find(|(i, _)| glass.sphere(rtl_render::ray8::SPHERE | *i as u32).is_some())
        .expect("a glass ball");
    let material = scene.materials[ball.material.index()];
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(99);
    let (mut mismatches, mut asked_for) = (0, 0);
    let mut done = 0;
    while done < n {
        // eight rays that meet the ball, with the scalar answers
        let mut g = Glass8::default();
        let mut want = Vec::new();
        while want.len() < 8 {
            let inside = rng.random::<bool>();
            let origin = if inside {
                ball.center + unit(&mut rng) * ball.radius * rng.random_range(0.0..0.999)
            } else {
                point(&mut rng, 270.0) + Vec3::splat(277.0)
            };
            let aim = ball.center + unit(&mut rng) * ball.radius * 1.1;
            let direction = if inside {
                unit(&mut rng) * rng.random_range(0.5..3.0)
            } else {
                aim - origin
            };
            let ray = Ray::new(origin, direction, rng.random());
            let Some(t) = ball.hit_t(&ray, Interval::FORWARD) else {
                continue;
            };
            let Some(err) = GlassSpheres::error(ball, &ray, t) else {
                continue;
            };
            let mut ctx = Ctx::new();
            ctx.rng = SampleRng::for_sample(5, want.len() as u64, done as u64);
            ctx.bounce = 2;
            let u = ctx.peek_1d(Dimension::Material(2));
            let hit = ball.hit_at(&ray, t);
            let before = ctx.rng.drawn;
            let Some(rtl_render::material::Scatter::Specular { direction, .. }) =
                material.scatter(&ray, &hit, &[], &mut ctx)
            else {
                panic!("glass scatters")
            };
            let lane = want.len();
            (g.sphere[lane], g.t[lane], g.err[lane], g.u[lane]) = (i as u32, t, err, u);
            g.rays.set(lane, &ray);
            want.push((hit.spawn(direction, ray.time), ctx.rng.drawn > before));
        }
        for tier in tiers() {
            let mut lanes = g;
            // SAFETY: the tier runs here.
            let asked = unsafe { dielectric(tier, glass, &mut lanes, 0xff) };
            for (lane, (next, asks)) in want.iter().enumerate() {
                let got = lanes.rays.ray(lane, next.time);
                let same = got.origin.to_array().map(f64::to_bits)
                    == next.origin.to_array().map(f64::to_bits)
                    && got.direction.to_array().map(f64::to_bits)
                        == next.direction.to_array().map(f64::to_bits);
                mismatches += (!same || (asked & (1 << lane) != 0) != *asks) as usize;
                asked_for += *asks as usize;
            }
        }
        done += 8;
    }
    (mismatches, asked_for)
}

#[test]
fn the_glass_vertex_in_the_lanes_is_the_dielectrics_bit_for_bit() {
    let scene = builtin("cornell");
    let glass = rtl_render::glass8::GlassSpheres::new(&scene, GroupId(0)).expect("a glass ball");
    let n = 4000;
    let (mismatches, asked) = glass_mismatches(&glass, n);
    assert_eq!(mismatches, 0);
    // both answers were tested: reflections without the number (total internal reflection), and
    // vertices that asked for it
    let runs = n * tiers().len();
    assert!(
        tiers().is_empty() || (asked > 0 && asked < runs),
        "{asked} of {runs}"
    );
}

#[test]
fn the_glass_check_catches_glass_one_ulp_denser() {
    let mut denser = builtin("cornell");
    for m in &mut denser.materials {
        if let Material::Dielectric { ior } = m {
            *ior = f64::from_bits(ior.to_bits() + 1);
        }
    }
    let glass = rtl_render::glass8::GlassSpheres::new(&denser, GroupId(0)).expect("a glass ball");
    if !tiers().is_empty() {
        assert!(glass_mismatches(&glass, 400).0 > 0);
    }
}

// ---------------------------------------------------------------------------------------------
// The light met without a record

/// What a path gathers from a light quad without its record (`QuadLight::emitted`) is what
/// `Material::emitted` gives on the record, from the front and from behind, for book 3's one-sided
/// ceiling light and a two-sided copy of it.
#[test]
fn a_light_met_without_its_record_gives_what_the_material_emits() {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(17);
    for two_sided in [false, true] {
        let mut scene = builtin("cornell");
        for m in &mut scene.materials {
            if let Material::DiffuseLight { two_sided: t, .. } = m {
                *t = two_sided;
            }
        }
        let surfaces =
            rtl_render::vertex8::QuadSurfaces::new(&scene, GroupId(0)).expect("the room's quads");
        let group = &scene.groups[0];
        let (mut lights, mut dark) = (0, 0);
        for h in 0..4 * group.accel.packets.len() as u32 {
            let Some(light) = surfaces.light(h) else {
                continue;
            };
            lights += 1;
            let index = group.accel.packets[h as usize / 4].index[h as usize % 4];
            let rtl_render::scene::Object::Quad(quad) = &group.objects[index as usize] else {
                panic!("a light quad")
            };
            let material = scene.materials[quad.material.index()];
            for _ in 0..200 {
                // from either side of the light's plane, at a point inside it
                let at = quad.q + rng.random::<f64>() * quad.u + rng.random::<f64>() * quad.v;
                let side = if rng.random() { 1.0 } else { -1.0 };
                let from = at + side * quad.normal * rng.random_range(1.0..50.0) + unit(&mut rng);
                let ray = Ray::new(from, at - from, 0.0);
                let Some(hit) = quad.hit(&ray, Interval::FORWARD) else {
                    continue;
                };
                let want = material.emitted(&hit, &scene.textures, &mut Ctx::new());
                assert_eq!(light.emitted(ray.direction), want, "two-sided {two_sided}");
                dark += (want == Color::ZERO) as usize;
            }
        }
        assert_eq!(lights, 1);
        // (the check can fail: from behind, the one-sided light gives nothing, the other its light)
        assert_eq!(dark > 0, !two_sided);
    }
}

/// What hit number `h` of the scene's first group is, read from its materials: a Lambertian quad of
/// constant albedo, a light of constant radiance, a glass ball (a static dielectric sphere).
fn kind_of(scene: &Scene, h: u32) -> [bool; 3] {
    use rtl_render::ray8::SPHERE;
    use rtl_render::scene::Object;
    let group = &scene.groups[0];
    let material = |m: &rtl_render::ids::MaterialId| &scene.materials[m.index()];
    if h & SPHERE != 0 {
        let spheres = group.accel.spheres.as_deref().unwrap_or(&[]);
        let glass = spheres.get((h & !SPHERE) as usize).is_some_and(|(s, _)| {
            matches!(material(&s.material), Material::Dielectric { .. }) && !s.is_moving()
        });
        return [false, false, glass];
    }
    let quad = group
        .accel
        .packets
        .get(h as usize / 4)
        .map(|p| p.index[h as usize % 4])
        .and_then(|i| match group.objects.get(i as usize) {
            Some(Object::Quad(q)) => Some(q),
            _ => None,
        });
    let Some(q) = quad else {
        return [false; 3];
    };
    [
        matches!(
            material(&q.material),
            Material::Lambertian {
                albedo: Albedo::Constant(_)
            }
        ),
        matches!(
            material(&q.material),
            Material::DiffuseLight {
                emit: Albedo::Constant(_),
                ..
            }
        ),
        false,
    ]
}

/// The lanes of each kind as [`rtl_render::ray8::HitKinds`] sorts them (through `QuadSurfaces` and
/// `GlassSpheres`), and as the scene's materials say, over `hits`; how many lanes of any kind there
/// were.
fn kind_mismatches(scene: &Scene, hits: &[[u32; 8]]) -> (usize, usize) {
    let g = GroupId(0);
    let s = rtl_render::vertex8::QuadSurfaces::new(scene, g).expect("Lambertian quads");
    let glass = rtl_render::glass8::GlassSpheres::new(scene, g).expect("a glass ball");
    let (mut wrong, mut some) = (0, 0);
    for hit in hits {
        let got = [
            s.lambertian_lanes(hit),
            s.light_lanes(hit),
            glass.glass_lanes(hit),
        ];
        for (k, got) in got.into_iter().enumerate() {
            let want = (0..8).fold(0u8, |m, l| m | (kind_of(scene, hit[l])[k] as u8) << l);
            wrong += (got != want) as usize;
            some += want.count_ones() as usize;
        }
        // the one-lane forms, and the light's record where the bits say a light
        for &h in hit {
            let [lambertian, light, is_glass] = kind_of(scene, h);
            wrong += (s.lambertian(h) != lambertian) as usize;
            wrong += (s.light(h).is_some() != light) as usize;
            wrong += (glass.is_glass(h) != is_glass) as usize;
        }
    }
    (wrong, some)
}

/// Every number a lane's hit can hold in the Cornell box (its quads, its spheres, none) and some
/// it cannot, eight at a time.
fn hit_numbers(rng: &mut Xoshiro256PlusPlus) -> Vec<[u32; 8]> {
    use rtl_render::ray8::{NO_HIT, SPHERE};
    (0..2000)
        .map(|_| {
            std::array::from_fn(|_| match rng.random_range(0..4) {
                0 => NO_HIT,
                1 => SPHERE | rng.random_range(0..3),
                _ => rng.random_range(0..16),
            })
        })
        .collect()
}

#[test]
fn the_lanes_are_sorted_by_what_they_met_as_one_lane_at_a_time() {
    let scene = builtin("cornell");
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(12);
    let (wrong, some) = kind_mismatches(&scene, &hit_numbers(&mut rng));
    assert_eq!(wrong, 0);
    // (about 7,300 of the 16,000: of the numbers 0-15, eleven are Lambertian quads and one the
    // light; of the three sphere numbers, one is the glass ball)
    assert!(some > 5_000, "{some} lanes of some kind");
    // past fifteen quads or spheres the table of 32 has no room: no kinds, and no lanes form
    use rtl_render::ray8::HitKinds;
    assert!(HitKinds::new(16, 2, |_| true).is_none());
    assert!(HitKinds::new(12, 16, |_| true).is_none());
    let all = HitKinds::new(15, 15, |_| true).unwrap();
    assert_eq!(
        all.lanes(&[rtl_render::ray8::NO_HIT; 8]),
        0,
        "no hit is of no kind"
    );
    assert_eq!(
        all.lanes(&[14, rtl_render::ray8::SPHERE | 14, 0, 0, 0, 0, 0, 0]),
        0xff
    );
}

#[test]
fn the_kind_check_catches_a_number_the_table_aliases() {
    // the glass ball's hits numbered 16, which no quad of the Cornell box has: the table of 32
    // reads it as quad 0 (`hit_key` keeps four bits of a quad's number), the lookups as nothing,
    // and the check sees the two disagree
    let scene = builtin("cornell");
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(13);
    let wrong_numbers: Vec<[u32; 8]> = hit_numbers(&mut rng)
        .into_iter()
        .map(|hit| hit.map(|h| if h == rtl_render::ray8::SPHERE { 16 } else { h }))
        .collect();
    let (wrong, _) = kind_mismatches(&scene, &wrong_numbers);
    assert!(wrong > 0);
}
