//! `mis` in media and inside dielectrics, against `cosine` (which never samples lights) on the mean
//! of every image region (batch means, Welch t-test), each with a deliberately wrong variant that must
//! be caught:
//! - a glass ball filled with a medium (book 2's subsurface sphere) with an emitter inside it, under a
//!   ceiling light: `mis` takes no light sample inside the glass (wrong: the emission found from there
//!   weighted as if it had), and plays Russian roulette in media with its own threshold (wrong:
//!   without reweighting the survivors);
//! - a thin fog around everything (book 2's) and a denser smoke box with a glowing ball in it: `mis`
//!   takes the light sample of a medium at an equiangular point of the path's segment (wrong: without
//!   the transmittance from the segment's start), and must also agree with the light sample taken
//!   where the path scatters;
//! - fuzzy metal balls (fuzz 0.5 and 1.6) under a light: `mis` weights light samples and emission
//!   hits by the metal's density (wrong: a cosine lobe's density), and must also agree with the metal
//!   treated as a specular bounce;
//! - a wide bright lamp and a dim ball: next-event estimation chooses the emitter per shading point
//!   (wrong: the emission met by material sampling weighted by the uniform choice's density);
//! - 24 emitters of powers 600 times apart: next-event estimation chooses through the light tree
//!   (wrong: the uniform choice's density again);
//! - two walls of one-sided panels facing each other: the light tree culls clusters by their cones
//!   of normals (wrong: the uniform choice's density again);
//! - lamps above a floor and, brighter, just under it: the light tree bounds the cosine at the
//!   shading point, which gives the lamps under the floor only their uniform share there (wrong: the
//!   emission met by material sampling weighted by the tree's density without the normal);
//! - a glass ball listed as a target under a light, beside a second lamp seen mostly from behind:
//!   material sampling draws `OTHERS_SHARE` of its
//!   directions towards the ball (wrong: divided by the density of the book's even mixture).

use rtl_render::Color;
use rtl_render::camera::CameraSettings;
use rtl_render::integrator::{MisOptions, MisVariant, Strategy};
use rtl_render::material::{Albedo, Material};
use rtl_render::render::{RenderSettings, Renderer, render};
use rtl_render::scene::{Background, GroupId, ImportanceTarget, MaterialId, Scene, SceneBuilder};
use rtl_render::shapes::Sphere;
use rtl_render::vec::{Point3, Vec3};

mod batch_means;
mod variant_batches;
use batch_means::{mean_var, welch_p};

const WIDTH: usize = 24;
const BATCHES: u64 = 32;
const BATCH_SPP: u64 = 16;
/// The image is cut into `GRID x GRID` regions of 6 x 6 pixels.
const GRID: usize = 4;
const MAX_DEPTH: u32 = 50;

/// The scene `b` seen from `lookfrom` towards `lookat` (vertical field of view `vfov` degrees),
/// against a black background, paths of at most [`MAX_DEPTH`] bounces.
fn framed(mut b: SceneBuilder, lookfrom: Point3, lookat: Point3, vfov: f64) -> Scene {
    b.camera = CameraSettings {
        lookfrom,
        lookat,
        vfov,
        ..CameraSettings::default()
    };
    b.background = Background::Solid(Color::ZERO);
    b.max_depth = MAX_DEPTH;
    b.build().unwrap()
}

/// The floor every scene here stands on: an 8 x 6 quad at height 0 about the origin.
fn floor(b: &mut SceneBuilder, w: GroupId, material: MaterialId) {
    b.quad(
        w,
        Point3::new(-4.0, 0.0, 3.0),
        Vec3::new(8.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, -6.0),
        material,
    )
    .unwrap();
}

/// A one-sided emitter of grey radiance `l`.
fn one_sided_lamp(l: f64) -> Material {
    Material::DiffuseLight {
        emit: Albedo::Constant(Color::splat(l)),
        two_sided: false,
    }
}

/// A floor under a one-sided ceiling light, and on it a glass ball (radius 1) filled with a medium
/// (density 1.5, albedo 0.8) with a small glowing ball at its centre. Nothing is listed as a target:
/// next-event estimation finds both emitters by itself.
pub fn glass_ball_with_medium_and_glow() -> Scene {
    let mut b = SceneBuilder::new();
    let w = b.world();
    let white = b.material(Material::lambertian(Color::splat(0.7)));
    let glass = b.material(Material::Dielectric { ior: 1.5 });
    let smoke = b.material(Material::Isotropic {
        albedo: Albedo::Constant(Color::splat(0.8)),
    });
    let lamp = b.material(one_sided_lamp(5.0));
    let glow = b.material(Material::DiffuseLight {
        emit: Albedo::Constant(Color::splat(4.0)),
        two_sided: true,
    });
    floor(&mut b, w, white);
    b.quad(
        w,
        Point3::new(-1.0, 3.5, -1.0),
        Vec3::new(2.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 2.0),
        lamp,
    )
    .unwrap();
    let centre = Point3::new(0.0, 1.0, 0.0);
    b.sphere(w, centre, 1.0, glass).unwrap();
    let boundary = b.group();
    b.sphere(boundary, centre, 1.0, glass).unwrap();
    b.medium(w, boundary, 1.5, smoke).unwrap();
    b.sphere(w, centre, 0.25, glow).unwrap();
    framed(
        b,
        Point3::new(0.0, 1.5, 5.0),
        Point3::new(0.0, 1.0, 0.0),
        40.0,
    )
}

/// A floor under a one-sided ceiling light, all inside a fog (a ball of radius 12, density 0.04,
/// albedo 0.9, the camera in it), and on the floor a smoke box (density 0.6, albedo 0.8) with a
/// glowing ball inside: segments cross one medium or two at once.
pub fn fog_and_smoke() -> Scene {
    let mut b = SceneBuilder::new();
    let w = b.world();
    let white = b.material(Material::lambertian(Color::splat(0.7)));
    let glass = b.material(Material::Dielectric { ior: 1.5 });
    let fog = b.material(Material::Isotropic {
        albedo: Albedo::Constant(Color::splat(0.9)),
    });
    let smoke = b.material(Material::Isotropic {
        albedo: Albedo::Constant(Color::splat(0.8)),
    });
    let lamp = b.material(one_sided_lamp(6.0));
    let glow = b.material(Material::DiffuseLight {
        emit: Albedo::Constant(Color::splat(3.0)),
        two_sided: true,
    });
    floor(&mut b, w, white);
    b.quad(
        w,
        Point3::new(-1.0, 4.0, -1.0),
        Vec3::new(2.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 2.0),
        lamp,
    )
    .unwrap();
    let boundary = b
        .box_group(
            Point3::new(-2.5, 0.5, -1.5),
            Point3::new(0.5, 2.5, 1.5),
            white,
        )
        .unwrap();
    b.medium(w, boundary, 0.6, smoke).unwrap();
    b.sphere(w, Point3::new(-1.0, 1.5, 0.0), 0.3, glow).unwrap();
    let fog_boundary = b.group();
    b.sphere(fog_boundary, Point3::ZERO, 12.0, glass).unwrap();
    b.medium(w, fog_boundary, 0.04, fog).unwrap();
    framed(
        b,
        Point3::new(0.0, 2.0, 7.0),
        Point3::new(0.0, 1.8, 0.0),
        55.0,
    )
}

/// A floor under a one-sided ceiling light with two fuzzy metal balls on it (fuzz 0.5: directions in
/// a cone about the mirror direction; fuzz 1.6: all around it) and a small two-sided light beside.
pub fn fuzzy_metals() -> Scene {
    let mut b = SceneBuilder::new();
    let w = b.world();
    let white = b.material(Material::lambertian(Color::splat(0.7)));
    let narrow = b.material(Material::Metal {
        albedo: Color::splat(0.9),
        fuzz: 0.5,
    });
    let wide = b.material(Material::Metal {
        albedo: Color::splat(0.8),
        fuzz: 1.6,
    });
    let lamp = b.material(one_sided_lamp(6.0));
    let glow = b.material(Material::DiffuseLight {
        emit: Albedo::Constant(Color::splat(4.0)),
        two_sided: true,
    });
    floor(&mut b, w, white);
    b.quad(
        w,
        Point3::new(-1.0, 4.0, -1.0),
        Vec3::new(2.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 2.0),
        lamp,
    )
    .unwrap();
    b.sphere(w, Point3::new(-1.1, 1.0, 0.0), 1.0, narrow)
        .unwrap();
    b.sphere(w, Point3::new(1.1, 1.0, 0.0), 1.0, wide).unwrap();
    b.sphere(w, Point3::new(0.0, 0.4, 1.6), 0.3, glow).unwrap();
    framed(
        b,
        Point3::new(0.0, 1.5, 6.0),
        Point3::new(0.0, 1.0, 0.0),
        45.0,
    )
}

fn settings(seed: u64, strategy: Strategy) -> RenderSettings {
    variant_batches::settings(WIDTH, MAX_DEPTH, seed, strategy)
}

fn render_variant(scene: &Scene, seed: u64, variant: MisVariant) -> Vec<Color> {
    variant_batches::render_variant(scene, WIDTH, MAX_DEPTH, BATCH_SPP, seed, variant)
}

/// Per region, its mean radiance in each of `BATCHES` renders.
fn batch_means(image: impl Fn(u64) -> Vec<Color>) -> Vec<Vec<f64>> {
    variant_batches::region_means(WIDTH, GRID, BATCHES, 3000, image)
}

fn disagreements(a: &[Vec<f64>], b: &[Vec<f64>]) -> Vec<String> {
    variant_batches::disagreements(a, b, GRID)
}

fn cosine_means(scene: &Scene) -> Vec<Vec<f64>> {
    batch_means(|seed| {
        let (acc, stats) = render(scene, settings(seed, Strategy::Cosine), BATCH_SPP);
        assert_eq!(stats.non_finite, 0);
        acc.image()
    })
}

#[test]
fn mis_inside_glass_agrees_with_cosine_and_the_wrong_variants_are_caught() {
    let scene = glass_ball_with_medium_and_glow();
    let cosine = cosine_means(&scene);
    let mis = batch_means(|seed| render_variant(&scene, seed, MisVariant::Book));
    let d = disagreements(&cosine, &mis);
    assert!(d.is_empty(), "mis vs cosine:\n{}", d.join("\n"));
    let wrong =
        batch_means(|seed| render_variant(&scene, seed, MisVariant::WrongWeightInsideDielectrics));
    assert!(
        !disagreements(&cosine, &wrong).is_empty(),
        "the wrong weight inside the glass went unnoticed"
    );
    // The glow reaches the camera through many scatterings in the ball: roulette that does not
    // reweight its survivors loses that light.
    let wrong = batch_means(|seed| render_variant(&scene, seed, MisVariant::WrongRouletteInMedia));
    assert!(
        !disagreements(&cosine, &wrong).is_empty(),
        "roulette in media without reweighting went unnoticed"
    );
    // The lamp's light reaches the medium through the glass: the manifold connection finds it,
    // material sampling too, and their weights must sum to 1.
    let wrong = batch_means(|seed| render_variant(&scene, seed, MisVariant::WrongManifoldWeight));
    assert!(
        !disagreements(&cosine, &wrong).is_empty(),
        "light through the glass counted twice went unnoticed"
    );
    let wrong = batch_means(|seed| render_variant(&scene, seed, MisVariant::WrongManifoldGeometry));
    assert!(
        !disagreements(&cosine, &wrong).is_empty(),
        "the connection's geometry term without its rotation went unnoticed"
    );
}

/// A floor under two emitters of very different importance: a wide one-sided 6 x 6 lamp low above
/// it (radiance 2; from the floor it fills much of the sky, so material sampling finds it as often as
/// the light sample does) and a dim ball (radiance 0.5, radius 0.3) on the floor beside it, which
/// takes most of next-event estimation's choices near it and few elsewhere.
pub fn bright_lamp_and_dim_ball() -> Scene {
    let mut b = SceneBuilder::new();
    let w = b.world();
    let white = b.material(Material::lambertian(Color::splat(0.7)));
    let lamp = b.material(one_sided_lamp(2.0));
    let dim = b.material(one_sided_lamp(0.5));
    floor(&mut b, w, white);
    // u x v = (0, -36, 0): shines down
    b.quad(
        w,
        Point3::new(-3.0, 1.2, -3.0),
        Vec3::new(6.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 6.0),
        lamp,
    )
    .unwrap();
    b.sphere(w, Point3::new(1.5, 0.5, 0.5), 0.3, dim).unwrap();
    framed(
        b,
        Point3::new(0.0, 0.8, 6.0),
        Point3::new(0.0, 0.4, 0.0),
        50.0,
    )
}

#[test]
fn emitters_chosen_per_point_agree_and_a_uniform_weight_is_caught() {
    let scene = bright_lamp_and_dim_ball();
    let lights = rtl_render::lights::Lights::new(&scene, false);
    assert!(lights.weighs_emitters(), "two emitters: weighed per point");
    agrees_and_the_uniform_weight_is_caught(&scene);
}

/// `mis` agrees with `cosine` on `scene`, and the variant whose MIS weight takes the uniform
/// choice's density for the emission that material sampling meets does not.
fn agrees_and_the_uniform_weight_is_caught(scene: &Scene) {
    let cosine = cosine_means(scene);
    let mis = batch_means(|seed| render_variant(scene, seed, MisVariant::Book));
    let d = disagreements(&cosine, &mis);
    assert!(d.is_empty(), "mis vs cosine:\n{}", d.join("\n"));
    let wrong =
        batch_means(|seed| render_variant(scene, seed, MisVariant::WrongUniformLightWeight));
    assert!(
        !disagreements(&cosine, &wrong).is_empty(),
        "the uniform choice's density in the MIS weight went unnoticed"
    );
}

/// The floor and a back wall under 24 emitting spheres and quads whose powers span a factor of 600
/// (sizes 0.04 to 0.4, radiance 1 to 6): more than `MAX_WEIGHED_EMITTERS`, so next-event estimation
/// chooses through the light tree, by power and distance at each point. Two of the quads are one-sided and face up: the
/// floor sees them from behind, where their density is 0.
pub fn many_emitters_of_unequal_power() -> Scene {
    let mut b = SceneBuilder::new();
    let w = b.world();
    let white = b.material(Material::lambertian(Color::splat(0.7)));
    floor(&mut b, w, white);
    b.quad(
        w,
        Point3::new(-4.0, 0.0, -3.0),
        Vec3::new(8.0, 0.0, 0.0),
        Vec3::new(0.0, 5.0, 0.0),
        white,
    )
    .unwrap();
    for i in 0..24 {
        let emit = 1.0 + (i % 6) as f64;
        let one_sided = i % 4 == 1;
        let m = b.material(if one_sided {
            one_sided_lamp(emit)
        } else {
            Material::DiffuseLight {
                emit: Albedo::Constant(Color::splat(emit)),
                two_sided: true,
            }
        });
        let (x, z) = (-3.8 + 0.33 * i as f64, -2.8 + 0.2 * (i % 7) as f64);
        let size = 0.04 * (1.0 + (i * 7 % 10) as f64);
        if i % 3 == 0 {
            // u x v = (0, -1, 0), down; the one-sided ones (i = 9, 21) the other way, up
            let (u, v) = (
                Vec3::new(2.0 * size, 0.0, 0.0),
                Vec3::new(0.0, 0.0, 2.0 * size),
            );
            let (u, v) = if one_sided { (v, u) } else { (u, v) };
            b.quad(w, Point3::new(x, 3.5, z), u, v, m).unwrap();
        } else {
            b.sphere(w, Point3::new(x, 1.0 + 0.1 * i as f64, z), size, m)
                .unwrap();
        }
    }
    framed(
        b,
        Point3::new(0.0, 2.0, 7.0),
        Point3::new(0.0, 1.5, 0.0),
        60.0,
    )
}

#[test]
fn many_emitters_chosen_through_the_light_tree_agree_and_a_uniform_weight_is_caught() {
    let scene = many_emitters_of_unequal_power();
    let lights = rtl_render::lights::Lights::new(&scene, false);
    assert_eq!(lights.emitters.len(), 24);
    assert!(
        lights.emitter_tree.is_some(),
        "24 emitters: chosen through the light tree"
    );
    assert!(lights.describe_emitters().contains("light tree"));
    agrees_and_the_uniform_weight_is_caught(&scene);
}

/// A floor between two walls of 12 one-sided panels each, facing each other across it (x = -3.5
/// facing +x, x = 3.5 facing -x), with a white block between them: more than `MAX_WEIGHED_EMITTERS`,
/// so the light tree chooses, and its clusters of panels all one-sided, so it culls by their cones
/// of normals (from each wall's foot, the panels above it are behind).
pub fn facing_walls_of_panels() -> Scene {
    let mut b = SceneBuilder::new();
    let w = b.world();
    let white = b.material(Material::lambertian(Color::splat(0.7)));
    floor(&mut b, w, white);
    b.sphere(w, Point3::new(0.0, 0.8, 0.0), 0.8, white).unwrap();
    for (i, side) in [-1.0, 1.0].into_iter().enumerate() {
        for k in 0..12 {
            let m = b.material(one_sided_lamp(1.0 + ((k + i) % 4) as f64));
            let (y, z) = (0.3 + 0.7 * (k / 4) as f64, -2.4 + 1.2 * (k % 4) as f64);
            let (u, v) = (Vec3::new(0.0, 0.5, 0.0), Vec3::new(0.0, 0.0, 0.8));
            // u x v = +x faces the room from x = -3.5; turned round at x = 3.5
            let (u, v) = if side < 0.0 { (u, v) } else { (v, u) };
            b.quad(w, Point3::new(3.5 * side, y, z), u, v, m).unwrap();
        }
    }
    framed(
        b,
        Point3::new(0.0, 3.0, 7.0),
        Point3::new(0.0, 0.8, 0.0),
        60.0,
    )
}

#[test]
fn facing_walls_of_panels_through_the_cones_agree_and_a_uniform_weight_is_caught() {
    let scene = facing_walls_of_panels();
    let lights = rtl_render::lights::Lights::new(&scene, false);
    assert_eq!(lights.emitters.len(), 24);
    assert!(lights.emitter_tree.is_some());
    agrees_and_the_uniform_weight_is_caught(&scene);
}

/// A floor with a white ball on it, 12 bright lamps just under the floor (below the horizon of
/// every point on it) and 12 dimmer ones above it: the light tree chooses, and at the floor the
/// cosine bound at the shading point gives the cluster under it nothing but its uniform share
/// (without the normal the near, bright lamps under the floor take most of the choice).
pub fn lamps_above_and_below_a_floor() -> Scene {
    let mut b = SceneBuilder::new();
    let w = b.world();
    let white = b.material(Material::lambertian(Color::splat(0.7)));
    floor(&mut b, w, white);
    b.sphere(w, Point3::new(0.8, 0.6, -0.5), 0.6, white)
        .unwrap();
    // a 4 x 3 grid of lamps at each height, its heights further apart than its width (the tree's
    // first split is between the two grids)
    for i in 0..24 {
        let below = i % 2 == 0;
        let k = i / 2;
        let (x, z) = (-1.2 + 0.8 * (k % 4) as f64, -0.8 + 0.8 * (k / 4) as f64);
        let (y, r, emit) = if below {
            (-0.5, 0.3, 8.0)
        } else {
            (2.0 + 0.1 * (k % 3) as f64, 0.3 + 0.03 * (k % 4) as f64, 3.0)
        };
        let m = b.material(Material::DiffuseLight {
            emit: Albedo::Constant(Color::splat(emit)),
            two_sided: true,
        });
        b.sphere(w, Point3::new(x, y, z), r, m).unwrap();
    }
    framed(
        b,
        Point3::new(0.0, 4.0, 6.0),
        Point3::new(0.0, 0.5, 0.0),
        55.0,
    )
}

#[test]
fn the_light_tree_with_the_shading_normal_agrees_and_a_weight_without_it_is_caught() {
    let scene = lamps_above_and_below_a_floor();
    let lights = rtl_render::lights::Lights::new(&scene, false);
    assert_eq!(lights.emitters.len(), 24);
    assert!(lights.emitter_tree.is_some());
    let cosine = cosine_means(&scene);
    let mis = batch_means(|seed| render_variant(&scene, seed, MisVariant::Book));
    let d = disagreements(&cosine, &mis);
    assert!(d.is_empty(), "mis vs cosine:\n{}", d.join("\n"));
    let wrong =
        batch_means(|seed| render_variant(&scene, seed, MisVariant::WrongTreeWeightWithoutNormal));
    let d = disagreements(&cosine, &wrong);
    assert!(
        !d.is_empty(),
        "the MIS weight without the normal the light sample's choice used went unnoticed"
    );
    eprintln!("without the normal in the weight:\n{}", d.join("\n"));
}

/// A floor under a one-sided ceiling light, a dim one-sided lamp standing on it, and a glass ball
/// (radius 0.8) between floor and ceiling light, listed as an importance target the way the book lists the Cornell box's glass sphere: `mis` mixes it into
/// material sampling, for the caustic it focuses on the floor (which only material sampling finds:
/// the shadow rays towards the light meet the glass).
pub fn glass_ball_listed_under_a_light() -> Scene {
    let mut b = SceneBuilder::new();
    let w = b.world();
    let white = b.material(Material::lambertian(Color::splat(0.7)));
    let glass = b.material(Material::Dielectric { ior: 1.5 });
    let lamp = b.material(one_sided_lamp(8.0));
    floor(&mut b, w, white);
    // u x v = (0, -4, 0): shines down
    b.quad(
        w,
        Point3::new(-1.0, 4.0, -1.0),
        Vec3::new(2.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 2.0),
        lamp,
    )
    .unwrap();
    // A second, dim one-sided lamp standing on the floor, u x v = (2, 0, 0): it shines towards +x,
    // and the floor left of it (most of the image) sees only its back, where its density and its
    // emission are 0.
    let side = b.material(one_sided_lamp(2.0));
    b.quad(
        w,
        Point3::new(1.8, 0.2, 1.0),
        Vec3::new(0.0, 0.0, -2.0),
        Vec3::new(0.0, 1.0, 0.0),
        side,
    )
    .unwrap();
    let ball = Point3::new(0.0, 1.6, 0.0);
    b.sphere(w, ball, 0.8, glass).unwrap();
    b.targets.push(ImportanceTarget::Sphere(Sphere::new(
        ball,
        0.8,
        rtl_render::scene::NO_MATERIAL,
    )));
    framed(
        b,
        Point3::new(0.0, 4.0, 3.0),
        Point3::new(0.0, 0.0, 0.0),
        50.0,
    )
}

#[test]
fn material_sampling_mixed_with_a_listed_ball_agrees_and_a_wrong_share_is_caught() {
    let scene = glass_ball_listed_under_a_light();
    let lights = rtl_render::lights::Lights::new(&scene, false);
    assert_eq!(
        lights.others.len(),
        1,
        "the ball is a target that does not emit"
    );
    assert_eq!(
        lights.emitters.len(),
        2,
        "both lamps are found without a list"
    );
    let cosine = cosine_means(&scene);
    let mis = batch_means(|seed| render_variant(&scene, seed, MisVariant::Book));
    let d = disagreements(&cosine, &mis);
    assert!(d.is_empty(), "mis vs cosine:\n{}", d.join("\n"));
    let wrong = batch_means(|seed| render_variant(&scene, seed, MisVariant::WrongOthersShare));
    assert!(
        !disagreements(&cosine, &wrong).is_empty(),
        "dividing by the even mixture's density went unnoticed"
    );
    // The caustic the ball focuses on the floor: crossing connections and material sampling
    // both find it, and weights that do not sum to 1 are caught. (The crossing's geometry term is
    // checked against finite differences in `manifold::crossing`'s tests: here, where material
    // sampling takes most of the focus, a wrong one moves the image too little to be caught.)
    assert!(!lights.manifold.crossable.is_empty());
    let wrong = batch_means(|seed| render_variant(&scene, seed, MisVariant::WrongManifoldWeight));
    assert!(
        !disagreements(&cosine, &wrong).is_empty(),
        "the caustic counted twice went unnoticed"
    );
}

/// A floor under a small one-sided lamp, and on it a clear glass ball (radius 1) with a white
/// Lambertian ball (radius 0.45) inside, off its centre: the light reaches the inner ball only
/// through the glass, by material sampling and by the manifold connection from its surface (seen
/// through the far side of the glass too, where a point may have several refraction points).
pub fn diffuse_ball_in_glass() -> Scene {
    let mut b = SceneBuilder::new();
    let w = b.world();
    let white = b.material(Material::lambertian(Color::splat(0.7)));
    let glass = b.material(Material::Dielectric { ior: 1.5 });
    let lamp = b.material(one_sided_lamp(12.0));
    floor(&mut b, w, white);
    b.quad(
        w,
        Point3::new(-0.6, 3.0, -0.9),
        Vec3::new(1.2, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 1.2),
        lamp,
    )
    .unwrap();
    b.sphere(w, Point3::new(0.0, 1.0, 0.0), 1.0, glass).unwrap();
    b.sphere(w, Point3::new(0.2, 0.8, 0.25), 0.45, white)
        .unwrap();
    framed(
        b,
        Point3::new(0.0, 1.6, 4.0),
        Point3::new(0.0, 1.0, 0.0),
        35.0,
    )
}

#[test]
fn a_diffuse_ball_in_glass_agrees_with_cosine_and_double_counting_is_caught() {
    let scene = diffuse_ball_in_glass();
    let lights = rtl_render::lights::Lights::new(&scene, false);
    assert!(
        lights.manifold.is_active(),
        "the glass holds a diffuse ball"
    );
    // Where the scene's paths go through the lanes (one small group, a processor with AVX2), they
    // make the connections as one path at a time does: the same image, bit for bit.
    let st = settings(1, Strategy::Mis(MisOptions::DEFAULT));
    let image = |r: &Renderer<'_>| {
        let mut acc = r.accumulator();
        r.render_pass(&mut acc, 0, 4, &|| {});
        acc.image()
            .iter()
            .flat_map(|c| c.to_array().map(f64::to_bits))
            .collect::<Vec<u64>>()
    };
    use rtl_render::traversal::HitTier;
    assert!(Renderer::new(&scene, st).paths_in_lanes() || HitTier::current() == HitTier::Portable);
    assert_eq!(
        image(&Renderer::new(&scene, st)),
        image(&Renderer::new(&scene, st).one_path_at_a_time())
    );
    let (_, stats) = render(&scene, settings(1, Strategy::Mis(MisOptions::DEFAULT)), 4);
    assert!(
        stats.manifold_connections > 200,
        "{} connections",
        stats.manifold_connections
    );
    let off = MisOptions {
        manifold: false,
        ..MisOptions::DEFAULT
    };
    let (_, stats) = render(&scene, settings(1, Strategy::Mis(off)), 4);
    assert_eq!(stats.manifold_connections, 0);
    let cosine = cosine_means(&scene);
    let mis = batch_means(|seed| render_variant(&scene, seed, MisVariant::Book));
    let d = disagreements(&cosine, &mis);
    assert!(d.is_empty(), "mis vs cosine:\n{}", d.join("\n"));
    let wrong = batch_means(|seed| render_variant(&scene, seed, MisVariant::WrongManifoldWeight));
    assert!(
        !disagreements(&cosine, &wrong).is_empty(),
        "light through the glass counted twice went unnoticed"
    );
}

#[test]
fn the_variant_loop_is_the_renderers() {
    // `render_variant` with the estimator itself gives the renderer's image, bit for bit.
    let scene = glass_ball_with_medium_and_glow();
    let (acc, _) = render(
        &scene,
        settings(7, Strategy::Mis(MisOptions::DEFAULT)),
        BATCH_SPP,
    );
    let ours = render_variant(&scene, 7, MisVariant::Book);
    for (a, b) in acc.image().iter().zip(&ours) {
        assert!((*a - *b).abs().max_element() <= 1e-12 * a.abs().max_element().max(1.0));
    }
}

#[test]
fn mis_with_segment_light_samples_agrees_and_the_missing_transmittance_is_caught() {
    let scene = fog_and_smoke();
    let cosine = cosine_means(&scene);
    let mis = batch_means(|seed| render_variant(&scene, seed, MisVariant::Book));
    let d = disagreements(&cosine, &mis);
    assert!(d.is_empty(), "mis vs cosine:\n{}", d.join("\n"));
    let scattered =
        batch_means(|seed| render_variant(&scene, seed, MisVariant::LightSampleWhereScattered));
    let d = disagreements(&scattered, &mis);
    assert!(
        d.is_empty(),
        "light samples on segments vs where scattered:\n{}",
        d.join("\n")
    );
    let wrong =
        batch_means(|seed| render_variant(&scene, seed, MisVariant::WrongSegmentTransmittance));
    assert!(
        !disagreements(&cosine, &wrong).is_empty(),
        "the missing transmittance went unnoticed"
    );
}

#[test]
fn mis_with_the_fuzzy_metals_density_agrees_and_a_cosine_lobe_is_caught() {
    let scene = fuzzy_metals();
    let cosine = cosine_means(&scene);
    let mis = batch_means(|seed| render_variant(&scene, seed, MisVariant::Book));
    let d = disagreements(&cosine, &mis);
    assert!(d.is_empty(), "mis vs cosine:\n{}", d.join("\n"));
    let specular = batch_means(|seed| render_variant(&scene, seed, MisVariant::MetalAsSpecular));
    let d = disagreements(&specular, &mis);
    assert!(
        d.is_empty(),
        "metal by its density vs specular:\n{}",
        d.join("\n")
    );
    let wrong = batch_means(|seed| render_variant(&scene, seed, MisVariant::WrongMetalDensity));
    assert!(
        !disagreements(&cosine, &wrong).is_empty(),
        "the cosine lobe's density went unnoticed"
    );
}

/// book2-final itself: the estimator against the one before segment sampling and the metal's
/// density, and against itself without manifold connections, region by region (32 x 32 pixels, 16
/// batches of 64 samples). Expensive: run with
/// `cargo test --release -p rtl-render --test mis_variants -- --ignored --nocapture`.
#[test]
#[ignore = "expensive: run in release with --ignored"]
fn book2_final_agrees_with_the_estimator_before() {
    let built =
        (rtl_render::scenes::find("book2-final").unwrap().build)(&Default::default()).unwrap();
    let scene = &built.scene;
    let (width, spp, batches) = (32, 64, 16);
    let means = |variant| {
        variant_batches::region_means(width, GRID, batches, 5000, |seed| {
            variant_batches::render_variant(scene, width, scene.max_depth, spp, seed, variant)
        })
    };
    let before = means(MisVariant::LightSampleWhereScattered);
    let now = means(MisVariant::Book);
    for (r, (x, y)) in before.iter().zip(&now).enumerate() {
        eprintln!(
            "region {r}: {:.5} +- {:.5} vs {:.5} +- {:.5}, p = {:.3}",
            mean_var(x).0,
            (mean_var(x).1 / batches as f64).sqrt(),
            mean_var(y).0,
            (mean_var(y).1 / batches as f64).sqrt(),
            welch_p(x, y)
        );
    }
    let d = disagreements(&before, &now);
    assert!(d.is_empty(), "{}", d.join("\n"));
    // and without the manifold connections through the glass balls
    let without = variant_batches::region_means(width, GRID, batches, 5000, |seed| {
        let options = MisOptions {
            manifold: false,
            ..MisOptions::DEFAULT
        };
        let st = variant_batches::settings(width, scene.max_depth, seed, Strategy::Mis(options));
        let (acc, _) = render(scene, st, spp);
        acc.image()
    });
    let d = disagreements(&without, &now);
    assert!(d.is_empty(), "without connections:\n{}", d.join("\n"));
}
