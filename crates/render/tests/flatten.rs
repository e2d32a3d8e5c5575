//! Rigid instances flattened into world space (`rtl_render::flatten`) against the same instances
//! traced as placed (the ray moved into the instance's frame and the record moved back).
//!
//! The two compute in different frames, so their hits differ in the last bits; the claim checked here
//! is that they differ by no more than the hits' own error bounds allow. Both hit points lie within
//! their `err` of the same surface (the flattened quad is the placed one up to the rounding of
//! `R Q + t`, `R u`, `R v`, a few ulps of those magnitudes, and `err` is 2^-36 of them, some 10^5
//! times more), and both lie on the ray up to rounding; so they are within `E (1 + 1 / |cos|)` of each
//! other, `E` the sum of the two bounds and `cos` the cosine between the ray and the surface's normal
//! (a plane offset by `E` moves the hit along the ray by `E / |cos|`). A ray that one form hits and
//! the other misses must meet the surface within that distance of an edge of one of its quads.
//! Each check is shown to fail for a deliberately wrong flattening (the box rotated by 1e-7 degree
//! more, or moved by a micrometre in a 555-unit scene).

use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use rtl_render::hit::Hit;
use rtl_render::material::{Albedo, Material};
use rtl_render::ray::{Interval, Ray};
use rtl_render::sampler::Ctx;
use rtl_render::scene::{GroupId, Object, Scene, SceneBuilder, Transform};
use rtl_render::shapes::{Quad, box_quads};
use rtl_render::vec::{Color, Point3, Vec3};

fn unit<R: Rng>(rng: &mut R) -> Vec3 {
    rtl_pdf::warp::sample_uniform_sphere(glam::DVec2::new(rng.random(), rng.random()))
}

/// One random case: a box of size `scale` placed by a rigid transform (a rotation about y, or about a
/// random axis, then a translation of up to `far`), beside a few world quads and perhaps a sphere.
#[derive(Clone, Copy, Debug)]
struct Case {
    seed: u64,
    scale: f64,
    far: f64,
}

/// The scene of `case`, its box's instance flattened or not; `wrong` moves the flattened box's quads
/// by that transform first (the deliberately wrong flattening).
fn scene(case: Case, flatten: bool, wrong: Option<Transform>) -> (Scene, Vec<Quad>) {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(case.seed);
    let mut b = SceneBuilder::new();
    b.flatten = flatten;
    let white = b.material(Material::lambertian(Color::splat(0.7)));
    let red = b.material(Material::lambertian(Color::new(0.6, 0.1, 0.1)));
    let s = case.scale;
    let size = Vec3::new(
        rng.random_range(0.05..1.0),
        rng.random_range(0.05..1.0),
        rng.random_range(0.05..1.0),
    ) * s;
    let rotation = if rng.random::<bool>() {
        Transform::rotate_y(rng.random_range(-180.0..180.0))
    } else {
        Transform {
            rotation: glam::DMat3::from_axis_angle(unit(&mut rng), rng.random_range(-3.2..3.2)),
            translation: Vec3::ZERO,
        }
    };
    let offset = unit(&mut rng) * rng.random_range(0.0..case.far);
    let tr = rotation.then(Transform::translate(offset));
    let corner = unit(&mut rng) * 0.3 * s;
    let quads = box_quads(corner, corner + size, white).unwrap();
    let placed: Vec<Quad> = quads
        .iter()
        .map(|q| {
            let t = wrong.map_or(tr, |w| tr.then(w));
            Quad::new(t.point(q.q), t.vector(q.u), t.vector(q.v), white).unwrap()
        })
        .collect();
    let w = b.world();
    for _ in 0..rng.random_range(0..=5) {
        let q = offset + unit(&mut rng) * 2.0 * s;
        b.quad(w, q, unit(&mut rng) * s, unit(&mut rng) * s, red)
            .unwrap();
    }
    if rng.random::<bool>() {
        b.sphere(w, offset + unit(&mut rng) * 2.0 * s, 0.5 * s, red)
            .unwrap();
    }
    if let Some(wrong) = wrong {
        // The box's quads, placed by hand with the wrong transform.
        for q in box_quads(corner, corner + size, white).unwrap() {
            let t = tr.then(wrong);
            b.quad(w, t.point(q.q), t.vector(q.u), t.vector(q.v), white)
                .unwrap();
        }
    } else {
        let inner = b.group();
        for q in quads {
            b.add_to(inner, Object::Quad(q));
        }
        b.instance(w, inner, tr);
    }
    (b.build().unwrap(), placed)
}

/// The distance from `p` to the boundary of `q`, measured in `q`'s plane (its coordinates `alpha`,
/// `beta` scaled by the widths across the parallelogram), and its distance to the plane.
fn edge_and_plane_distance(q: &Quad, p: Point3) -> (f64, f64) {
    let n = q.u.cross(q.v);
    let nn = n.length_squared();
    let rel = p - q.q;
    let alpha = rel.cross(q.v).dot(n) / nn;
    let beta = q.u.cross(rel).dot(n) / nn;
    let area = nn.sqrt();
    let (wu, wv) = (area / q.v.length(), area / q.u.length());
    let edge =
        (alpha.abs().min((1.0 - alpha).abs()) * wu).min(beta.abs().min((1.0 - beta).abs()) * wv);
    (edge, (rel.dot(n) / area).abs())
}

/// Whether two hits of `ray` (`a` flattened, `b` placed) agree within the bound argued above;
/// `Err` says how they disagree. If `from_surface`, the ray starts on the surface itself and a hit at
/// its origin is no disagreement.
fn agree(
    ray: &Ray,
    a: Option<Hit>,
    b: Option<Hit>,
    quads: &[Quad],
    from_surface: bool,
) -> Result<(), String> {
    let dir = ray.direction.normalize();
    let len = ray.direction.length();
    // Near an edge of a box quad, within `tol` of its plane and of its boundary.
    let near_edge = |h: &Hit, tol: f64| {
        quads.iter().any(|q| {
            let (edge, plane) = edge_and_plane_distance(q, h.p);
            plane <= tol && edge <= tol
        })
    };
    let tol_of = |h: &Hit, e: f64| e * (1.0 + 1.0 / h.normal.dot(dir).abs().max(1e-300));
    // A ray that starts on the surface may meet it again at its origin, in either form: the
    // renderer's offsets (`Hit::spawn`) exist to avoid that, and `spawned` rays check them.
    let at_origin = |h: &Hit, tol: f64| from_surface && (h.p - ray.origin).length() <= tol;
    match (a, b) {
        (None, None) => Ok(()),
        (Some(h), None) | (None, Some(h)) => {
            let tol = tol_of(&h, 2.0 * h.err);
            if near_edge(&h, tol) || at_origin(&h, tol) {
                Ok(())
            } else {
                Err(format!("only one form hits, away from any edge: {h:?}"))
            }
        }
        (Some(a), Some(b)) => {
            let tol = tol_of(&a, a.err + b.err);
            let gap = (a.p - b.p).length();
            let dt = (a.t - b.t).abs() * len;
            if gap <= tol && dt <= tol + 2.0 * f64::EPSILON * a.t * len {
                let same_face = a.normal.dot(b.normal) > 1.0 - 1e-9;
                return if (same_face && a.front_face == b.front_face && a.material == b.material)
                    || near_edge(&a, tol)
                {
                    Ok(())
                } else {
                    Err(format!("the same point on other faces: {a:?} {b:?}"))
                };
            }
            // Different surfaces: the nearer hit's form passed beside an edge the other met.
            let near = if a.t < b.t { &a } else { &b };
            if near_edge(near, tol) || at_origin(near, tol) {
                Ok(())
            } else {
                Err(format!(
                    "points {gap:e} apart (t {dt:e}) beyond the bound {tol:e}: {a:?} {b:?}"
                ))
            }
        }
    }
}

/// Rays at `quads` (the box's, in world space): at random points, edges and corners, from near and
/// far; grazing along a face; and from a hit point on the surface itself.
fn rays<R: Rng>(rng: &mut R, quads: &[Quad], scale: f64, n: usize) -> Vec<(Ray, bool)> {
    (0..n)
        .map(|_| {
            let q = &quads[rng.random_range(0..quads.len())];
            let (a, b) = match rng.random_range(0..3) {
                0 => (rng.random::<f64>(), rng.random::<f64>()),
                1 => (rng.random::<f64>(), [0.0, 1.0][rng.random_range(0..2)]),
                _ => (
                    [0.0, 1.0][rng.random_range(0..2)],
                    [0.0, 1.0][rng.random_range(0..2)],
                ),
            };
            let target = q.q + a * q.u + b * q.v;
            match rng.random_range(0..4) {
                // from far or near
                0 | 1 => {
                    let d = 10f64.powf(rng.random_range(-3.0..4.0)) * scale;
                    let origin = target + unit(rng) * d;
                    (Ray::new(origin, target - origin, 0.0), false)
                }
                // grazing: in the face's plane, or nearly, from a point of that plane (perhaps on the
                // face itself)
                2 => {
                    let along = (q.u * rng.random_range(-1.0..1.0)
                        + q.v * rng.random_range(-1.0..1.0))
                    .normalize();
                    let tilt = q.normal * 10f64.powf(rng.random_range(-12.0..-2.0));
                    (Ray::new(target - along * scale, along + tilt, 0.0), true)
                }
                // from the surface, outwards or inwards
                _ => (Ray::new(target, unit(rng), 0.0), true),
            }
        })
        .collect()
}

/// Disagreements between the flattened scene and the placed one over `cases`, and the hits.
fn disagreements(cases: &[Case], wrong: Option<Transform>) -> (usize, usize, Vec<String>) {
    let mut ctx = Ctx::new();
    let (mut bad, mut hits, mut examples) = (0, 0, Vec::new());
    let mut spawns = 0;
    for &case in cases {
        let (flat, quads) = scene(case, true, wrong);
        let (placed, _) = scene(case, false, None);
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(case.seed ^ 0x9e37);
        let mut check = |ray: &Ray, range: Interval, from_surface: bool, bad: &mut usize| {
            let a = flat.hit_group(GroupId(0), ray, range, &mut ctx);
            let b = placed.hit_group(GroupId(0), ray, range, &mut ctx);
            hits += a.is_some() as usize;
            if let Err(e) = agree(ray, a, b, &quads, from_surface) {
                *bad += 1;
                if examples.len() < 3 {
                    examples.push(format!("{case:?} {ray:?}: {e}"));
                }
            }
            (a, b)
        };
        for (ray, from_surface) in rays(&mut rng, &quads, case.scale, 400) {
            check(
                &ray,
                Interval::new(1e-9, f64::INFINITY),
                from_surface,
                &mut bad,
            );
            let (a, b) = check(&ray, Interval::FORWARD, from_surface, &mut bad);
            // Spawned from either form's hit with its own offset, outwards or inwards: neither form
            // may meet the surface again at the origin. (Not from within a few error bounds of an
            // edge: there the ray may start on the plane of the face across the edge, which an
            // offset along one face's normal does not leave, in either form.)
            for h in [a, b].into_iter().flatten() {
                let edge = quads.iter().any(|q| {
                    let (edge, plane) = edge_and_plane_distance(q, h.p);
                    plane <= 16.0 * h.err && edge <= 16.0 * h.err
                });
                if !edge {
                    let spawned = h.spawn(unit(&mut rng), 0.0);
                    check(&spawned, Interval::FORWARD, false, &mut bad);
                    spawns += 1;
                }
            }
        }
    }
    assert!(spawns > 100 * cases.len(), "{spawns} spawned rays");
    (bad, hits, examples)
}

fn cases() -> Vec<Case> {
    (0..120)
        .map(|i| Case {
            seed: 1000 + i,
            // tiny, the books' own, and far from the origin
            scale: [1e-3, 1.0, 555.0][i as usize % 3],
            far: [1.0, 1e2, 1e5][(i as usize / 3) % 3],
        })
        .collect()
}

#[test]
fn flattened_instances_hit_where_the_placed_ones_do_within_their_error_bounds() {
    let (bad, hits, examples) = disagreements(&cases(), None);
    assert_eq!(bad, 0, "{examples:#?}");
    assert!(hits > 40_000, "{hits} hits");
}

#[test]
fn the_check_fails_for_a_box_rotated_or_moved_a_little() {
    let cases = cases();
    let rotated = Transform::rotate_y(1e-7);
    let (bad, _, _) = disagreements(&cases[..30], Some(rotated));
    assert!(
        bad > 100,
        "only {bad} disagreements for a box rotated by 1e-7 degree"
    );
    let moved = Transform::translate(Vec3::new(0.0, 1e-6, 0.0));
    let (bad, _, _) = disagreements(&cases[1..2], Some(moved));
    assert!(
        bad > 50,
        "only {bad} disagreements for a box moved by 1e-6 at scale 1"
    );
}

#[test]
fn the_flattened_scene_is_the_small_flat_form_and_the_placed_one_is_not() {
    let case = Case {
        seed: 7,
        scale: 1.0,
        far: 1.0,
    };
    let (flat, _) = scene(case, true, None);
    let (placed, _) = scene(case, false, None);
    let world = &flat.groups[0];
    assert!(world.accel.is_small());
    assert!(
        !world
            .objects
            .iter()
            .any(|o| matches!(o, Object::Instance { .. }))
    );
    assert!(
        placed.groups[0]
            .objects
            .iter()
            .any(|o| matches!(o, Object::Instance { .. }))
    );
    // The flattened form against testing its objects one by one, on both paths, bit for bit.
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(3);
    let mut ctx = Ctx::new();
    let quads: Vec<Quad> = world
        .objects
        .iter()
        .filter_map(|o| match o {
            Object::Quad(q) => Some(*q),
            _ => None,
        })
        .collect();
    for (ray, _) in rays(&mut rng, &quads, 1.0, 2000) {
        let key = |h: Option<Hit>| h.map(|h| (h.t.to_bits(), h.p.to_array(), h.normal.to_array()));
        let slow = key(flat.hit_brute_force(GroupId(0), &ray, Interval::FORWARD, &mut ctx));
        assert_eq!(
            key(flat.hit_group(GroupId(0), &ray, Interval::FORWARD, &mut ctx)),
            slow
        );
        assert_eq!(
            key(flat.hit_group_portable(GroupId(0), &ray, Interval::FORWARD, &mut ctx)),
            slow
        );
    }
}

#[test]
fn the_cornell_box_is_flattened_and_its_light_list_is_kept() {
    let built = (rtl_render::scenes::find("cornell").unwrap().build)(&Default::default()).unwrap();
    let scene = &built.scene;
    let world = &scene.groups[0];
    let quads = world
        .objects
        .iter()
        .filter(|o| matches!(o, Object::Quad(_)))
        .count();
    assert_eq!((quads, world.objects.len()), (12, 13));
    assert!(world.accel.is_small());
    assert_eq!(scene.features.emitters, 1);
    assert_eq!(scene.features.flattened_instances, 1);
    let lights = rtl_render::lights::Lights::new(scene, false);
    assert_eq!(
        lights.describe_emitters(),
        "1 emitter (1 of them in the list of targets)"
    );
}

/// What is not flattened: an instance of an emitter (it keeps its place in the light list), a group
/// holding a medium, and a group that would not fit the flat form.
#[test]
fn emitters_media_and_large_groups_keep_their_instances() {
    // the instances left in the top group, and how many were flattened (what `--explain` reports)
    let instances = |b: SceneBuilder| {
        let scene = b.build().unwrap();
        let left = scene.groups[0]
            .objects
            .iter()
            .filter(|o| matches!(o, Object::Instance { .. }))
            .count();
        (left, scene.features.flattened_instances)
    };
    let boxed = |b: &mut SceneBuilder, m| {
        let g = b.box_group(Point3::ZERO, Point3::ONE, m).unwrap();
        b.instance(GroupId(0), g, Transform::rotate_y(15.0));
    };
    // an emitting box
    let mut b = SceneBuilder::new();
    let lamp = b.material(Material::DiffuseLight {
        emit: Albedo::Constant(Color::ONE),
        two_sided: true,
    });
    boxed(&mut b, lamp);
    assert_eq!(instances(b), (1, 0));
    // beside a medium
    let mut b = SceneBuilder::new();
    let white = b.material(Material::lambertian(Color::ONE));
    boxed(&mut b, white);
    let fog = b.group();
    b.sphere(fog, Point3::ZERO, 5.0, white).unwrap();
    b.medium(GroupId(0), fog, 0.1, white).unwrap();
    assert_eq!(instances(b), (1, 0));
    // two boxes and six walls: 18 quads, more than the flat form's three packets
    let mut b = SceneBuilder::new();
    let white = b.material(Material::lambertian(Color::ONE));
    boxed(&mut b, white);
    boxed(&mut b, white);
    for i in 0..6 {
        b.quad(GroupId(0), Point3::splat(i as f64), Vec3::X, Vec3::Z, white)
            .unwrap();
    }
    assert_eq!(instances(b), (2, 0));
    // one box and six walls: flattened
    let mut b = SceneBuilder::new();
    let white = b.material(Material::lambertian(Color::ONE));
    boxed(&mut b, white);
    for i in 0..6 {
        b.quad(GroupId(0), Point3::splat(i as f64), Vec3::X, Vec3::Z, white)
            .unwrap();
    }
    assert_eq!(instances(b), (0, 1));
}
