//! The hierarchy over a long list of targets ([`TargetIndex`]) changes nothing but the time: the
//! density of every direction, and every sample, is the whole list's to the bit, on near, far, tiny,
//! grazing and one-sided targets, seen from outside and inside them. A deliberately wrong index (one
//! that forgets a target) is caught by the same comparison.

use glam::{DVec2, DVec3};
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use rtl_pdf::{
    HittablePdf, MAX_CANDIDATES, Pdf, QuadTarget, ShapeIndex, ShapeSampler, SphereTarget,
};
use rtl_render::lights::LightTarget;
use rtl_render::target_index::{INDEX_FROM, TargetIndex};

/// `n` targets of every kind: spheres and quads (one- and two-sided, some by spherical rectangles)
/// of sizes from 1e-6 to 10, from 1 to 1e6 away from the origin, some in axis planes.
fn targets(n: usize, rng: &mut Xoshiro256PlusPlus) -> Vec<LightTarget> {
    (0..n)
        .map(|i| {
            let far = 10f64.powf(rng.random_range(0.0..6.0));
            let c = DVec3::new(
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
            ) * far;
            let size = 10f64.powf(rng.random_range(-6.0..1.0));
            match i % 3 {
                0 => LightTarget::Sphere(SphereTarget::new(c, size)),
                1 => LightTarget::Quad {
                    // in an axis plane, as the book's lights are
                    quad: QuadTarget::new(c, DVec3::X * size, DVec3::Z * size * 0.7),
                    one_sided: i % 2 == 0,
                },
                _ => {
                    let u = DVec3::new(rng.random(), rng.random(), rng.random()) * size;
                    let v = DVec3::new(rng.random(), rng.random(), rng.random()) * size;
                    LightTarget::Quad {
                        quad: QuadTarget::new(c, u, v).with_spherical_rectangles(i % 5 == 0),
                        one_sided: i % 4 == 0,
                    }
                }
            }
        })
        .collect()
}

/// Where the list is seen from: near each of some targets (inside a sphere too), and far away.
fn origins(list: &[LightTarget], rng: &mut Xoshiro256PlusPlus) -> Vec<DVec3> {
    let mut out: Vec<DVec3> = list
        .iter()
        .take(12)
        .map(|t| match t {
            LightTarget::Sphere(s) => s.center() + DVec3::X * s.radius() * 0.5, // inside
            LightTarget::Quad { quad, .. } => quad.q() + quad.normal() * 1e-3 + quad.u() * 0.3,
        })
        .collect();
    for _ in 0..12 {
        out.push(
            DVec3::new(
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
            ) * 10f64.powf(rng.random_range(0.0..6.0)),
        );
    }
    out
}

/// Compares `index` with the whole list, as the renderer uses it: for each origin, directions
/// drawn towards the list (and towards each of some targets, and at random), the densities and the
/// samples bit for bit. The first difference, or how many directions were compared.
fn agrees(list: &[LightTarget], index: &dyn ShapeIndex, seed: u64) -> Result<usize, String> {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let mut compared = 0;
    for x in origins(list, &mut rng) {
        let whole = HittablePdf::new(x, list).unwrap();
        let fast = HittablePdf::new(x, list).unwrap().with_index(index);
        let mut directions = Vec::new();
        for _ in 0..200 {
            let u = DVec2::new(rng.random(), rng.random());
            let (a, b) = (whole.sample(u), fast.sample(u));
            let same = match (a, b) {
                (Some(a), Some(b)) => {
                    a.direction == b.direction && a.pdf.to_bits() == b.pdf.to_bits()
                }
                (None, None) => true,
                _ => false,
            };
            if !same {
                return Err(format!("from {x}, u = {u}: sample {a:?} against {b:?}"));
            }
            directions.extend(a.map(|s| s.direction));
        }
        for t in list.iter().take(30) {
            let u = DVec2::new(rng.random(), rng.random());
            directions.extend(t.sample(x, u).map(|s| s.direction));
        }
        for _ in 0..50 {
            // (unit vectors, as the densities ask)
            let d = DVec3::new(
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
            );
            directions.push(d.normalize());
        }
        for d in directions {
            let (a, b) = (whole.pdf(d), fast.pdf(d));
            if a.to_bits() != b.to_bits() {
                return Err(format!("from {x} towards {d}: density {a:e} against {b:e}"));
            }
            compared += 1;
        }
    }
    Ok(compared)
}

#[test]
fn an_indexed_list_gives_the_whole_lists_densities_and_samples_to_the_bit() {
    for (n, seed) in [(INDEX_FROM, 1), (300, 2), (2000, 3)] {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
        let list = targets(n, &mut rng);
        let index = TargetIndex::new(&list);
        let compared = agrees(&list, &index, seed).unwrap();
        assert!(compared > 5000, "{compared}");
    }
}

#[test]
fn many_targets_stacked_along_one_direction_fall_back_to_the_whole_list() {
    // More than MAX_CANDIDATES spheres on one line: the index gives up for that direction, and the
    // density is still the whole list's.
    let list: Vec<LightTarget> = (0..(2 * MAX_CANDIDATES + INDEX_FROM))
        .map(|i| LightTarget::Sphere(SphereTarget::new(DVec3::Z * (5.0 + i as f64), 0.4)))
        .collect();
    let index = TargetIndex::new(&list);
    let mut out = [0; MAX_CANDIDATES];
    assert_eq!(index.candidates(DVec3::ZERO, DVec3::Z, &mut out), None);
    let whole = HittablePdf::new(DVec3::ZERO, &list).unwrap();
    let fast = HittablePdf::new(DVec3::ZERO, &list)
        .unwrap()
        .with_index(&index);
    assert!(whole.pdf(DVec3::Z) > 0.0);
    assert_eq!(whole.pdf(DVec3::Z).to_bits(), fast.pdf(DVec3::Z).to_bits());
    assert!(agrees(&list, &index, 9).is_ok());
}

/// An index that forgets the last target it finds.
struct Forgetful<'a>(&'a TargetIndex);

impl ShapeIndex for Forgetful<'_> {
    fn candidates(
        &self,
        origin: DVec3,
        direction: DVec3,
        out: &mut [u32; MAX_CANDIDATES],
    ) -> Option<usize> {
        self.0
            .candidates(origin, direction, out)
            .map(|k| k.saturating_sub(1))
    }
}

#[test]
fn the_comparison_catches_an_index_that_forgets_a_target() {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(4);
    let list = targets(300, &mut rng);
    let index = TargetIndex::new(&list);
    let err = agrees(&list, &Forgetful(&index), 4).unwrap_err();
    assert!(err.contains("density") || err.contains("sample"), "{err}");
}

/// A scene file of a floor under `n` small lamps in a row.
fn lamps(n: usize) -> String {
    let mut s = String::from(
        "[camera]\nlookfrom = [0, 5, 20]\nlookat = [0, 0, 0]\n\n[materials]\n\
         white = { type = \"lambertian\", albedo = 0.73 }\nlamp = { type = \"light\", emit = 4 }\n\n\
         [[objects]]\ntype = \"quad\"\nq = [-50, 0, -50]\nu = [100, 0, 0]\nv = [0, 0, 100]\n\
         material = \"white\"\n",
    );
    for i in 0..n {
        s += &format!(
            "\n[[objects]]\ntype = \"sphere\"\ncenter = [{}, 3, 0]\nradius = 0.2\nmaterial = \"lamp\"\n",
            i as f64 - n as f64 / 2.0
        );
    }
    s
}

#[test]
fn a_scene_with_many_emitters_gets_an_index_and_the_same_densities() {
    use rtl_render::lights::Lights;
    let load = |n| {
        let file =
            rtl_render::scene_file::load_str(&lamps(n), "lamps.toml", std::path::Path::new(""))
                .unwrap();
        Lights::new(&file.built.scene, false)
    };
    assert!(load(INDEX_FROM - 1).emitter_index.is_none());
    let lights = load(100);
    assert_eq!(lights.emitters.len(), 100);
    assert!(lights.emitter_index.is_some());
    assert!(lights.describe_emitters().contains("hierarchy"));
    // Next-event estimation's density from the floor, towards the lamps and elsewhere: the whole
    // list's, bit for bit.
    // (the whole list chosen as next-event estimation chooses: through the light tree, above 16
    // emitters)
    let x = DVec3::new(0.3, 0.0, 0.1);
    let tree = lights.emitter_tree.as_ref().unwrap();
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(5);
    let mut positive = 0;
    for k in 0..2000 {
        let u = DVec2::new(rng.random(), rng.random());
        // (without the floor's normal and with it)
        let normal = (k % 2 == 1).then_some(DVec3::Y);
        let d = lights
            .sample_emitters(x, normal, u)
            .map(|s| s.direction)
            .unwrap_or(DVec3::Y);
        let whole = tree.pdf(x, normal, d, &lights.emitters, None, None);
        let (a, b) = (whole, lights.emitters_pdf(x, normal, d));
        assert_eq!(a.to_bits(), b.to_bits(), "{d}");
        positive += usize::from(a > 0.0);
    }
    assert!(positive > 1900, "{positive}");
}
