//! A medium whose boundary is several closed pieces (or one closed surface with a dent: an L of
//! quads) fills each of them: a ray through a ball and a box of one black medium keeps `exp(-sigma
//! (l_ball + l_box))` of the light behind them, the same as through two media, one in each. (The
//! boundary's first two crossings alone, book 2's way, gave `exp(-sigma l_ball)`: the box behind
//! the ball was empty.) Camera rays by `cosine` and by `mis` (each sample passes or is absorbed: a
//! Bernoulli variable, whose variance bounds `mis`'s too; z-tests at a false-failure rate of 1e-6).

use rtl_render::Color;
use rtl_render::camera::CameraSettings;
use rtl_render::ids::{GroupId, MaterialId};
use rtl_render::integrator::{MisOptions, Strategy};
use rtl_render::material::{Albedo, Material};
use rtl_render::render::{BOOK_MIXTURE_WEIGHT, RenderSettings, render};
use rtl_render::scene::{Background, Object, Scene, SceneBuilder, SceneError};
use rtl_render::vec::{Point3, Vec3};

const WIDTH: usize = 12;
/// Two-sided z for a false-failure rate of 1e-6.
const Z: f64 = 4.89;
/// The chords along the axis: the ball's diameter and the box's depth.
const BALL: f64 = 2.0;
const BOX: f64 = 1.8;

/// A glass material for the boundaries' surfaces (what the media ignore) and an isotropic phase
/// function of this albedo for the media.
fn glass_and_fog(b: &mut SceneBuilder, albedo: f64) -> (MaterialId, MaterialId) {
    let glass = b.material(Material::Dielectric { ior: 1.5 });
    let fog = b.material(Material::Isotropic {
        albedo: Albedo::Constant(Color::splat(albedo)),
    });
    (glass, fog)
}

/// A ball (radius 1 about `(0, 0, -1.5)`) and a box (`z` from 0.6 to 2.4) on the camera's axis,
/// black fog of density 1 in both: in one medium whose boundary holds both (`one`), or in a
/// medium each. White background, a camera 10 away with a 1-degree view, so that every camera
/// ray crosses the ball along at least 0.998 of its diameter and the box along its depth.
fn ball_and_box(one: bool) -> Scene {
    let mut b = SceneBuilder::new();
    let (glass, black) = glass_and_fog(&mut b, 0.0);
    let ball = b.group();
    b.sphere(ball, Point3::new(0.0, 0.0, -1.5), 1.0, glass)
        .unwrap();
    let cube = b
        .box_group(
            Point3::new(-1.0, -1.0, 0.6),
            Point3::new(1.0, 1.0, 0.6 + BOX),
            glass,
        )
        .unwrap();
    fill(&mut b, [ball, cube], one, 1.0, black);
    seen_against_white(b, Point3::new(0.0, 0.0, -10.0), Point3::ZERO, 1.0)
}

/// Fog of `density` and phase function `fog` in the world of `b`, inside the two `pieces`: one
/// medium whose boundary holds both (`one`), or a medium each.
fn fill(b: &mut SceneBuilder, pieces: [GroupId; 2], one: bool, density: f64, fog: MaterialId) {
    let w = b.world();
    if one {
        let both = b.group();
        for piece in pieces {
            b.add_to(both, Object::Group(piece));
        }
        b.medium(w, both, density, fog).unwrap();
    } else {
        for piece in pieces {
            b.medium(w, piece, density, fog).unwrap();
        }
    }
}

/// The scene of `b`, seen from `lookfrom` towards `lookat` through a square view `vfov` degrees
/// high, against a white background.
fn seen_against_white(mut b: SceneBuilder, lookfrom: Point3, lookat: Point3, vfov: f64) -> Scene {
    b.camera = CameraSettings {
        lookfrom,
        lookat,
        vfov,
        aspect_ratio: 1.0,
        ..CameraSettings::default()
    };
    b.background = Background::Solid(Color::ONE);
    b.max_depth = 8;
    b.build().unwrap()
}

/// The image's mean and the number of samples behind it.
fn mean(scene: &Scene, strategy: Strategy, spp: u64) -> (f64, f64) {
    mean_seeded(scene, strategy, spp, 3)
}

/// [`mean`] with the random numbers of `seed`.
fn mean_seeded(scene: &Scene, strategy: Strategy, spp: u64, seed: u64) -> (f64, f64) {
    let settings = RenderSettings {
        width: WIDTH,
        max_depth: 8,
        seed,
        strategy,
        mixture_weight: BOOK_MIXTURE_WEIGHT,
    };
    let (acc, stats) = render(scene, settings, spp);
    assert_eq!(stats.non_finite, 0);
    let sum: f64 = acc.sum.iter().map(|c| c.x).sum();
    let n = acc.count.iter().sum::<u64>() as f64;
    (sum / n, n)
}

/// `|mean - want|` in standard deviations of a Bernoulli mean of `n` samples, allowing the spread
/// of the chords across the view (the ball's at least `0.998 BALL`: 0.4% of `want`).
fn z(mean: f64, n: f64, want: f64) -> f64 {
    let sd = (want * (1.0 - want) / n).sqrt();
    ((mean - want).abs() - 0.004 * want).max(0.0) / sd
}

/// By `cosine` (book 2's distance sampling) and by `mis` (shadow rays that record each stretch
/// crossed, forced scattering where there is one), one boundary or two.
#[test]
fn a_medium_in_a_ball_and_a_box_fills_both() {
    let want = (-(BALL + BOX)).exp();
    let wrong = (-BALL).exp();
    // (what --explain reports: the one medium of the two pieces, none of the two media)
    assert_eq!(ball_and_box(true).features.media_in_pieces, 1);
    assert_eq!(ball_and_box(false).features.media_in_pieces, 0);
    for strategy in [Strategy::Cosine, Strategy::Mis(MisOptions::DEFAULT)] {
        for one in [true, false] {
            let (m, n) = mean(&ball_and_box(one), strategy, 256);
            let what = format!("{strategy:?}, one boundary {one}");
            assert!(z(m, n, want) < Z, "{what}: {m} of {n}, not {want}");
            // the check can tell: the first stretch alone is far off
            assert!(z(m, n, wrong) > Z, "{what}: {m} is also {wrong}");
        }
    }
}

/// A scene built in code is held to the same rule as a scene file: a medium whose ball reaches
/// into its box is no scene.
#[test]
fn pieces_that_overlap_build_no_scene() {
    let mut b = SceneBuilder::new();
    let w = b.world();
    let (glass, fog) = glass_and_fog(&mut b, 0.5);
    let both = b.group();
    b.sphere(both, Point3::new(0.0, 0.0, 0.3), 1.0, glass)
        .unwrap();
    let cube = b
        .box_group(Point3::new(-1.0, -1.0, 0.6), Point3::ONE, glass)
        .unwrap();
    b.add_to(both, Object::Group(cube));
    b.medium(w, both, 1.0, fog).unwrap();
    let err = b.build().map(|_| ()).unwrap_err();
    assert!(matches!(err, SceneError::TouchingPieces { .. }), "{err}");
    assert!(err.to_string().contains("overlap or touch"), "{err}");
}

/// Nor is a medium whose boundary holds a medium (here through a group within it).
#[test]
fn a_medium_in_a_boundary_builds_no_scene() {
    let mut b = SceneBuilder::new();
    let w = b.world();
    let (glass, fog) = glass_and_fog(&mut b, 0.5);
    let (outer, inner, ball) = (b.group(), b.group(), b.group());
    b.sphere(outer, Point3::ZERO, 1.0, glass).unwrap();
    b.sphere(ball, Point3::new(0.0, 0.0, 5.0), 1.0, glass)
        .unwrap();
    b.medium(inner, ball, 2.0, fog).unwrap();
    b.add_to(outer, Object::Group(inner));
    b.medium(w, outer, 1.0, fog).unwrap();
    let err = b.build().map(|_| ()).unwrap_err();
    assert_eq!(err, SceneError::MediumInBoundary(outer.0), "{err}");
}

/// An L-shaped prism of 14 quads (three unit cells of a 2 x 2 square, `z` from 0 to 1): one closed
/// surface, not convex. A ray that crosses the cell at `(1, 0)`, the missing cell at `(1, 1)`, then
/// the cell at `(0, 1)` spends `0.6 sqrt 2` in each arm: `exp(-1.2 sqrt 2)` of the light gets
/// through, where the first stretch alone let `exp(-0.6 sqrt 2)` through. With `long_walls` the two
/// outer walls along x and y are one quad of length 2 each (12 quads), whose edges meet the floor's
/// and the ceiling's cells midway: T-junctions, closed all the same.
fn l_prism(long_walls: bool) -> Scene {
    let mut b = SceneBuilder::new();
    let w = b.world();
    let (glass, black) = glass_and_fog(&mut b, 0.0);
    let l = b.group();
    let (x, y, z) = (Vec3::X, Vec3::Y, Vec3::Z);
    let cells = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)];
    for (cx, cy) in cells {
        for cz in [0.0, 1.0] {
            b.quad(l, Point3::new(cx, cy, cz), x, y, glass).unwrap();
        }
    }
    // the eight unit walls around the L: (corner, along)
    let walls = [
        (Point3::new(0.0, 0.0, 0.0), x),
        (Point3::new(1.0, 0.0, 0.0), x),
        (Point3::new(2.0, 0.0, 0.0), y),
        (Point3::new(1.0, 1.0, 0.0), x),
        (Point3::new(1.0, 1.0, 0.0), y),
        (Point3::new(0.0, 2.0, 0.0), x),
        (Point3::new(0.0, 0.0, 0.0), y),
        (Point3::new(0.0, 1.0, 0.0), y),
    ];
    for (k, (q, along)) in walls.into_iter().enumerate() {
        match (long_walls, k) {
            // the outer walls at y = 0 and at x = 0 as one quad each, from the origin
            (true, 0 | 6) => b.quad(l, q, 2.0 * along, z, glass).unwrap(),
            (true, 1 | 7) => continue,
            _ => b.quad(l, q, along, z, glass).unwrap(),
        };
    }
    assert!(b.open_quad(l).is_none(), "the L is closed");
    b.medium(w, l, 1.0, black).unwrap();
    // looking along (-1, 1, 0) through (1.9, 0.5, 0.5), from 20 away
    let d = Vec3::new(-1.0, 1.0, 0.0).normalize();
    let at = Point3::new(1.9, 0.5, 0.5);
    seen_against_white(b, at - 20.0 * d, at, 0.05)
}

#[test]
fn a_medium_in_an_l_fills_both_arms() {
    let want = (-1.2 * 2f64.sqrt()).exp();
    let wrong = (-0.6 * 2f64.sqrt()).exp();
    for long_walls in [false, true] {
        let scene = l_prism(long_walls);
        assert_eq!(scene.features.media_in_pieces, 1);
        for strategy in [Strategy::Cosine, Strategy::Mis(MisOptions::DEFAULT)] {
            let (m, n) = mean(&scene, strategy, 256);
            let what = format!("{strategy:?}, long walls {long_walls}");
            assert!(z(m, n, want) < Z, "{what}: {m} of {n}, not {want}");
            assert!(z(m, n, wrong) > Z, "{what}: {m} is also {wrong}");
        }
    }
}

/// Two balls of black fog (density 2) in one plane: one of radius 0.5 moving away from the camera
/// along the view's axis, from 1 before the origin to 7 beyond it, the other of radius 0.3 rising
/// to the origin from 1 below it. Their paths cross (the first passes the origin at time 1/8), but
/// their centres are never nearer than 0.868 (at time 0.139), so one medium may hold both: its
/// boundary's pieces are compared at each time. From time 0.7 on, the small ball crosses the
/// axis in front of the large one: a ray through both keeps `e^-3.2` of the light, where the first
/// stretch alone would keep `e^-1.2`. In one medium or in one each, the image is the same in
/// expectation: the two means (different seeds, each sample passing or absorbed) agree in a z-test
/// at 1e-6, by `cosine` and by `mis`. (Taking the first stretch alone puts them 17 standard
/// deviations apart by `cosine`.)
fn crossing_paths(one: bool) -> Scene {
    let mut b = SceneBuilder::new();
    let (glass, black) = glass_and_fog(&mut b, 0.0);
    let (away, rising) = (b.group(), b.group());
    let p = |x: f64, y: f64| Point3::new(x, y, 0.0);
    b.moving_sphere(away, p(-1.0, 0.0), p(7.0, 0.0), 0.5, glass)
        .unwrap();
    b.moving_sphere(rising, p(0.0, -1.0), p(0.0, 0.0), 0.3, glass)
        .unwrap();
    fill(&mut b, [away, rising], one, 2.0, black);
    // along +x from 10 before the origin, 0.7 wide there
    seen_against_white(b, p(-10.0, 0.0), Point3::ZERO, 4.0)
}

#[test]
fn a_medium_in_two_balls_whose_paths_cross_at_different_times_fills_both() {
    let scene = crossing_paths(true);
    assert_eq!(scene.features.media_in_pieces, 1);
    for strategy in [Strategy::Cosine, Strategy::Mis(MisOptions::DEFAULT)] {
        let (a, n) = mean_seeded(&scene, strategy, 256, 5);
        let (b, m) = mean_seeded(&crossing_paths(false), strategy, 256, 6);
        let sd = (a * (1.0 - a) / n + b * (1.0 - b) / m).sqrt();
        assert!(
            (a - b).abs() < Z * sd,
            "{strategy:?}: {a} of {n} against {b} of {m}"
        );
    }
}
