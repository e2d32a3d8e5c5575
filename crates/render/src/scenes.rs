//! The built-in scenes of books 1, 2 and 3, exactly as the books build them (see SCENES.md).

use crate::camera::CameraSettings;
use crate::material::{Albedo, Material};
use crate::scene::{
    Background, GroupId, ImportanceTarget, MaterialId, Object, Scene, SceneBuilder, SceneError,
    Transform,
};
use crate::shapes::box_quads;
use crate::texture::{ImageData, Texture};
use crate::vec::{Color, Point3, Vec3};
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use std::path::PathBuf;

/// Options a scene may take from the command line.
#[derive(Clone, Debug, Default)]
pub struct SceneOptions {
    /// The image for the earth texture (book 2's `earthmap.jpg`); a generated stand-in if absent.
    pub texture: Option<PathBuf>,
}

/// A scene as built, with anything the user should be told (e.g. a stand-in texture).
pub struct Built {
    pub scene: Scene,
    pub notices: Vec<String>,
}

/// A built-in scene: its name, a one-line description, the book's image width and a default sample count.
pub struct BuiltIn {
    pub name: &'static str,
    pub description: &'static str,
    pub width: usize,
    pub spp: u64,
    pub build: fn(&SceneOptions) -> Result<Built, SceneError>,
}

/// Every built-in scene, in the books' order.
pub const BUILT_INS: &[BuiltIn] = &[
    BuiltIn {
        name: "book1-final",
        description: "book 1's cover: random small spheres around three large ones, defocus blur",
        width: 1200,
        spp: 500,
        build: book1_final,
    },
    BuiltIn {
        name: "bouncing-spheres",
        description: "book 2 ch. 2: the cover scene with bouncing (motion-blurred) spheres on a checker ground",
        width: 400,
        spp: 100,
        build: bouncing_spheres,
    },
    BuiltIn {
        name: "checkered-spheres",
        description: "book 2 ch. 4: two large spheres with a 3D checker texture",
        width: 400,
        spp: 100,
        build: checkered_spheres,
    },
    BuiltIn {
        name: "earth",
        description: "book 2 ch. 4: a globe with an image texture (--texture FILE, else a generated stand-in)",
        width: 400,
        spp: 100,
        build: earth,
    },
    BuiltIn {
        name: "perlin-spheres",
        description: "book 2 ch. 5: Perlin-noise marble on a sphere and the ground",
        width: 400,
        spp: 100,
        build: perlin_spheres,
    },
    BuiltIn {
        name: "quads",
        description: "book 2 ch. 6: five coloured quads",
        width: 400,
        spp: 100,
        build: quads,
    },
    BuiltIn {
        name: "simple-light",
        description: "book 2 ch. 7: marble spheres lit by a quad light and a sphere light",
        width: 400,
        spp: 100,
        build: simple_light,
    },
    BuiltIn {
        name: "cornell-book2",
        description: "book 2 ch. 7-8: the Cornell box with two rotated boxes, two-sided light",
        width: 600,
        spp: 200,
        build: cornell_book2,
    },
    BuiltIn {
        name: "cornell-smoke",
        description: "book 2 ch. 9: the Cornell box with boxes of black and white smoke",
        width: 600,
        spp: 200,
        build: cornell_smoke,
    },
    BuiltIn {
        name: "book2-final",
        description: "book 2's final scene: boxes, fog, smoke, glass, metal, marble, earth, motion (book: 800 wide, 10000 spp)",
        width: 800,
        spp: 1000,
        build: book2_final,
    },
    BuiltIn {
        name: "cornell",
        description: "book 3's final Cornell box: glass sphere, rotated box, one-sided ceiling light",
        width: 600,
        spp: 100,
        build: cornell,
    },
];

/// The built-in scene called `name`, or an error listing every name.
pub fn find(name: &str) -> Result<&'static BuiltIn, String> {
    BUILT_INS.iter().find(|b| b.name == name).ok_or_else(|| {
        let names: Vec<&str> = BUILT_INS.iter().map(|b| b.name).collect();
        format!(
            "unknown scene '{name}'; built-in scenes: {}",
            names.join(", ")
        )
    })
}

fn built(b: SceneBuilder) -> Result<Built, SceneError> {
    Ok(Built {
        scene: b.build()?,
        notices: Vec::new(),
    })
}

fn random_color<R: Rng + ?Sized>(rng: &mut R, lo: f64, hi: f64) -> Color {
    Color::new(
        rng.random_range(lo..hi),
        rng.random_range(lo..hi),
        rng.random_range(lo..hi),
    )
}

/// The random spheres of book 1's cover, shared by `book1-final` and `bouncing-spheres`.
fn cover_spheres(b: &mut SceneBuilder, bouncing: bool) -> Result<(), SceneError> {
    let world = b.world();
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(if bouncing { 2 } else { 1 });
    for a in -11..11 {
        for bb in -11..11 {
            let choose: f64 = rng.random();
            let center = Point3::new(
                a as f64 + 0.9 * rng.random::<f64>(),
                0.2,
                bb as f64 + 0.9 * rng.random::<f64>(),
            );
            if (center - Point3::new(4.0, 0.2, 0.0)).length() <= 0.9 {
                continue;
            }
            if choose < 0.8 {
                let albedo = random_color(&mut rng, 0.0, 1.0) * random_color(&mut rng, 0.0, 1.0);
                let m = b.material(Material::lambertian(albedo));
                if bouncing {
                    let c1 = center + Vec3::new(0.0, rng.random_range(0.0..0.5), 0.0);
                    b.moving_sphere(world, center, c1, 0.2, m)?;
                } else {
                    b.sphere(world, center, 0.2, m)?;
                }
            } else if choose < 0.95 {
                let albedo = random_color(&mut rng, 0.5, 1.0);
                let fuzz = rng.random_range(0.0..0.5);
                let m = b.material(Material::Metal { albedo, fuzz });
                b.sphere(world, center, 0.2, m)?;
            } else {
                let m = b.material(Material::Dielectric { ior: 1.5 });
                b.sphere(world, center, 0.2, m)?;
            }
        }
    }
    let glass = b.material(Material::Dielectric { ior: 1.5 });
    b.sphere(world, Point3::new(0.0, 1.0, 0.0), 1.0, glass)?;
    let brown = b.material(Material::lambertian(Color::new(0.4, 0.2, 0.1)));
    b.sphere(world, Point3::new(-4.0, 1.0, 0.0), 1.0, brown)?;
    let metal = b.material(Material::Metal {
        albedo: Color::new(0.7, 0.6, 0.5),
        fuzz: 0.0,
    });
    b.sphere(world, Point3::new(4.0, 1.0, 0.0), 1.0, metal)?;
    b.camera = CameraSettings {
        aspect_ratio: 16.0 / 9.0,
        vfov: 20.0,
        lookfrom: Point3::new(13.0, 2.0, 3.0),
        lookat: Point3::ZERO,
        vup: Vec3::Y,
        defocus_angle: 0.6,
        focus_dist: 10.0,
    };
    b.max_depth = 50;
    Ok(())
}

fn book1_final(_: &SceneOptions) -> Result<Built, SceneError> {
    let mut b = SceneBuilder::new();
    let ground = b.material(Material::lambertian(Color::splat(0.5)));
    b.sphere(b.world(), Point3::new(0.0, -1000.0, 0.0), 1000.0, ground)?;
    cover_spheres(&mut b, false)?;
    b.background = Background::Sky;
    built(b)
}

const SKY_BLUE: Color = Color::new(0.70, 0.80, 1.00);

fn checker(b: &mut SceneBuilder) -> Material {
    let t = b.texture(Texture::checker(
        0.32,
        Color::new(0.2, 0.3, 0.1),
        Color::splat(0.9),
    ));
    Material::Lambertian {
        albedo: Albedo::Texture(t),
    }
}

fn bouncing_spheres(_: &SceneOptions) -> Result<Built, SceneError> {
    let mut b = SceneBuilder::new();
    let m = checker(&mut b);
    let ground = b.material(m);
    b.sphere(b.world(), Point3::new(0.0, -1000.0, 0.0), 1000.0, ground)?;
    cover_spheres(&mut b, true)?;
    b.background = Background::Solid(SKY_BLUE);
    built(b)
}

fn small_camera(lookfrom: Point3, lookat: Point3, vfov: f64, aspect_ratio: f64) -> CameraSettings {
    CameraSettings {
        aspect_ratio,
        vfov,
        lookfrom,
        lookat,
        vup: Vec3::Y,
        defocus_angle: 0.0,
        focus_dist: 10.0,
    }
}

fn checkered_spheres(_: &SceneOptions) -> Result<Built, SceneError> {
    let mut b = SceneBuilder::new();
    let m = checker(&mut b);
    let m = b.material(m);
    b.sphere(b.world(), Point3::new(0.0, -10.0, 0.0), 10.0, m)?;
    b.sphere(b.world(), Point3::new(0.0, 10.0, 0.0), 10.0, m)?;
    b.camera = small_camera(Point3::new(13.0, 2.0, 3.0), Point3::ZERO, 20.0, 16.0 / 9.0);
    b.background = Background::Solid(SKY_BLUE);
    built(b)
}

/// The earth texture: the user's image, or the stand-in with a notice.
fn earth_texture(
    b: &mut SceneBuilder,
    opts: &SceneOptions,
    notices: &mut Vec<String>,
) -> Result<Material, SceneError> {
    let img = match &opts.texture {
        Some(p) => ImageData::load(p).map_err(SceneError::TextureImage)?,
        None => {
            notices.push("no --texture FILE given: the earth is a generated stand-in (the book's earthmap.jpg is not shipped)".into());
            ImageData::stand_in_earth()
        }
    };
    let t = b.texture(Texture::Image(Box::new(img)));
    Ok(Material::Lambertian {
        albedo: Albedo::Texture(t),
    })
}

fn earth(opts: &SceneOptions) -> Result<Built, SceneError> {
    let mut b = SceneBuilder::new();
    let mut notices = Vec::new();
    let m = earth_texture(&mut b, opts, &mut notices)?;
    let m = b.material(m);
    b.sphere(b.world(), Point3::ZERO, 2.0, m)?;
    b.camera = small_camera(Point3::new(0.0, 0.0, 12.0), Point3::ZERO, 20.0, 16.0 / 9.0);
    b.background = Background::Solid(SKY_BLUE);
    Ok(Built {
        scene: b.build()?,
        notices,
    })
}

fn marble(b: &mut SceneBuilder, scale: f64) -> Material {
    let t = b.texture(Texture::marble(scale));
    Material::Lambertian {
        albedo: Albedo::Texture(t),
    }
}

fn perlin_spheres(_: &SceneOptions) -> Result<Built, SceneError> {
    let mut b = SceneBuilder::new();
    let m = marble(&mut b, 4.0);
    let m = b.material(m);
    b.sphere(b.world(), Point3::new(0.0, -1000.0, 0.0), 1000.0, m)?;
    b.sphere(b.world(), Point3::new(0.0, 2.0, 0.0), 2.0, m)?;
    b.camera = small_camera(Point3::new(13.0, 2.0, 3.0), Point3::ZERO, 20.0, 16.0 / 9.0);
    b.background = Background::Solid(SKY_BLUE);
    built(b)
}

fn quads(_: &SceneOptions) -> Result<Built, SceneError> {
    let mut b = SceneBuilder::new();
    let w = b.world();
    let left_red = b.material(Material::lambertian(Color::new(1.0, 0.2, 0.2)));
    let back_green = b.material(Material::lambertian(Color::new(0.2, 1.0, 0.2)));
    let right_blue = b.material(Material::lambertian(Color::new(0.2, 0.2, 1.0)));
    let upper_orange = b.material(Material::lambertian(Color::new(1.0, 0.5, 0.0)));
    let lower_teal = b.material(Material::lambertian(Color::new(0.2, 0.8, 0.8)));
    b.quad(
        w,
        Point3::new(-3.0, -2.0, 5.0),
        Vec3::new(0.0, 0.0, -4.0),
        Vec3::new(0.0, 4.0, 0.0),
        left_red,
    )?;
    b.quad(
        w,
        Point3::new(-2.0, -2.0, 0.0),
        Vec3::new(4.0, 0.0, 0.0),
        Vec3::new(0.0, 4.0, 0.0),
        back_green,
    )?;
    b.quad(
        w,
        Point3::new(3.0, -2.0, 1.0),
        Vec3::new(0.0, 0.0, 4.0),
        Vec3::new(0.0, 4.0, 0.0),
        right_blue,
    )?;
    b.quad(
        w,
        Point3::new(-2.0, 3.0, 1.0),
        Vec3::new(4.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 4.0),
        upper_orange,
    )?;
    b.quad(
        w,
        Point3::new(-2.0, -3.0, 5.0),
        Vec3::new(4.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, -4.0),
        lower_teal,
    )?;
    b.camera = small_camera(Point3::new(0.0, 0.0, 9.0), Point3::ZERO, 80.0, 1.0);
    b.background = Background::Solid(SKY_BLUE);
    built(b)
}

fn simple_light(_: &SceneOptions) -> Result<Built, SceneError> {
    let mut b = SceneBuilder::new();
    let w = b.world();
    let m = marble(&mut b, 4.0);
    let m = b.material(m);
    b.sphere(w, Point3::new(0.0, -1000.0, 0.0), 1000.0, m)?;
    b.sphere(w, Point3::new(0.0, 2.0, 0.0), 2.0, m)?;
    let light = b.material(Material::DiffuseLight {
        emit: Albedo::Constant(Color::splat(4.0)),
        two_sided: true,
    });
    b.sphere(w, Point3::new(0.0, 7.0, 0.0), 2.0, light)?;
    b.quad(
        w,
        Point3::new(3.0, 1.0, -2.0),
        Vec3::new(2.0, 0.0, 0.0),
        Vec3::new(0.0, 2.0, 0.0),
        light,
    )?;
    b.camera = small_camera(
        Point3::new(26.0, 3.0, 6.0),
        Point3::new(0.0, 2.0, 0.0),
        20.0,
        16.0 / 9.0,
    );
    b.background = Background::Solid(Color::ZERO);
    built(b)
}

struct CornellMaterials {
    red: MaterialId,
    white: MaterialId,
    green: MaterialId,
}

/// The Cornell box's materials and camera (shared by all three boxes).
fn cornell_frame(b: &mut SceneBuilder) -> Result<CornellMaterials, SceneError> {
    let red = b.material(Material::lambertian(Color::new(0.65, 0.05, 0.05)));
    let white = b.material(Material::lambertian(Color::splat(0.73)));
    let green = b.material(Material::lambertian(Color::new(0.12, 0.45, 0.15)));
    b.camera = small_camera(
        Point3::new(278.0, 278.0, -800.0),
        Point3::new(278.0, 278.0, 0.0),
        40.0,
        1.0,
    );
    b.background = Background::Solid(Color::ZERO);
    b.max_depth = 50;
    Ok(CornellMaterials { red, white, green })
}

/// Book 2's green and red side walls.
fn book2_side_walls(b: &mut SceneBuilder, m: &CornellMaterials) -> Result<(), SceneError> {
    let w = b.world();
    b.quad(
        w,
        Point3::new(555.0, 0.0, 0.0),
        Vec3::new(0.0, 555.0, 0.0),
        Vec3::new(0.0, 0.0, 555.0),
        m.green,
    )?;
    b.quad(
        w,
        Point3::new(0.0, 0.0, 0.0),
        Vec3::new(0.0, 555.0, 0.0),
        Vec3::new(0.0, 0.0, 555.0),
        m.red,
    )?;
    Ok(())
}

/// The box `[0, size]` as a group of its own, and the transform that rotates it about y by `degrees`
/// and then translates it by `offset` (book 2's `translate(rotate_y(box))`).
fn rotated_box(
    b: &mut SceneBuilder,
    size: Vec3,
    degrees: f64,
    offset: Vec3,
    m: MaterialId,
) -> Result<(GroupId, Transform), SceneError> {
    let inner = b.box_group(Point3::ZERO, size, m)?;
    Ok((
        inner,
        Transform::rotate_y(degrees).then(Transform::translate(offset)),
    ))
}

/// A quad given as the book writes it: corner `q` and edges `u`, `v`.
type QuadSpec = ([f64; 3], [f64; 3], [f64; 3]);

/// Adds each quad of `quads` to the world with material `m`, in order.
fn quads_of(b: &mut SceneBuilder, quads: &[QuadSpec], m: MaterialId) -> Result<(), SceneError> {
    let w = b.world();
    for &(q, u, v) in quads {
        b.quad(w, Point3::from(q), Vec3::from(u), Vec3::from(v), m)?;
    }
    Ok(())
}

/// Book 2's two white boxes, each a group of its own with the transform that places it: the tall one
/// (rotated 15 degrees) and the short one (rotated -18 degrees).
fn book2_boxes(
    b: &mut SceneBuilder,
    white: MaterialId,
) -> Result<[(GroupId, Transform); 2], SceneError> {
    let tall = rotated_box(
        b,
        Vec3::new(165.0, 330.0, 165.0),
        15.0,
        Vec3::new(265.0, 0.0, 295.0),
        white,
    )?;
    let short = rotated_box(
        b,
        Vec3::new(165.0, 165.0, 165.0),
        -18.0,
        Vec3::new(130.0, 0.0, 65.0),
        white,
    )?;
    Ok([tall, short])
}

/// A two-sided diffuse light of radiance `radiance` (book 2's lights emit on both faces).
fn two_sided_light(b: &mut SceneBuilder, radiance: f64) -> MaterialId {
    b.material(Material::DiffuseLight {
        emit: Albedo::Constant(Color::splat(radiance)),
        two_sided: true,
    })
}

fn cornell_book2(_: &SceneOptions) -> Result<Built, SceneError> {
    let mut b = SceneBuilder::new();
    let w = b.world();
    let mats = cornell_frame(&mut b)?;
    book2_side_walls(&mut b, &mats)?;
    let light = two_sided_light(&mut b, 15.0);
    quads_of(
        &mut b,
        &[(
            [343.0, 554.0, 332.0],
            [-130.0, 0.0, 0.0],
            [0.0, 0.0, -105.0],
        )],
        light,
    )?;
    // floor, ceiling, back wall, in the book's order and orientation
    quads_of(
        &mut b,
        &[
            ([0.0, 0.0, 0.0], [555.0, 0.0, 0.0], [0.0, 0.0, 555.0]),
            (
                [555.0, 555.0, 555.0],
                [-555.0, 0.0, 0.0],
                [0.0, 0.0, -555.0],
            ),
            ([0.0, 0.0, 555.0], [555.0, 0.0, 0.0], [0.0, 555.0, 0.0]),
        ],
        mats.white,
    )?;
    for (group, transform) in book2_boxes(&mut b, mats.white)? {
        b.instance(w, group, transform);
    }
    built(b)
}

fn cornell_smoke(_: &SceneOptions) -> Result<Built, SceneError> {
    let mut b = SceneBuilder::new();
    let w = b.world();
    let mats = cornell_frame(&mut b)?;
    book2_side_walls(&mut b, &mats)?;
    let light = two_sided_light(&mut b, 7.0);
    quads_of(
        &mut b,
        &[([113.0, 554.0, 127.0], [330.0, 0.0, 0.0], [0.0, 0.0, 305.0])],
        light,
    )?;
    // ceiling, floor, back wall, in the book's order and orientation
    quads_of(
        &mut b,
        &[
            ([0.0, 555.0, 0.0], [555.0, 0.0, 0.0], [0.0, 0.0, 555.0]),
            ([0.0, 0.0, 0.0], [555.0, 0.0, 0.0], [0.0, 0.0, 555.0]),
            ([0.0, 0.0, 555.0], [555.0, 0.0, 0.0], [0.0, 555.0, 0.0]),
        ],
        mats.white,
    )?;
    let [(box1, t1), (box2, t2)] = book2_boxes(&mut b, mats.white)?;
    // Each medium's boundary is a group holding the placed box.
    let (boundary1, boundary2) = (b.group(), b.group());
    b.instance(boundary1, box1, t1);
    b.instance(boundary2, box2, t2);
    let black = b.material(Material::Isotropic {
        albedo: Albedo::Constant(Color::ZERO),
    });
    let bright = b.material(Material::Isotropic {
        albedo: Albedo::Constant(Color::ONE),
    });
    b.medium(w, boundary1, 0.01, black)?;
    b.medium(w, boundary2, 0.01, bright)?;
    built(b)
}

fn book2_final(opts: &SceneOptions) -> Result<Built, SceneError> {
    let mut b = SceneBuilder::new();
    let w = b.world();
    let mut notices = Vec::new();
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(3);
    let ground = b.material(Material::lambertian(Color::new(0.48, 0.83, 0.53)));
    let boxes1 = b.group();
    for i in 0..20 {
        for j in 0..20 {
            let wd = 100.0;
            let x0 = -1000.0 + i as f64 * wd;
            let z0 = -1000.0 + j as f64 * wd;
            let y1 = rng.random_range(1.0..101.0);
            let (a, c) = (Point3::new(x0, 0.0, z0), Point3::new(x0 + wd, y1, z0 + wd));
            let quads = box_quads(a, c, ground).ok_or(SceneError::FlatBox { a, b: c })?;
            // All 2400 quads of the ground share one list (one BVH).
            for q in quads {
                b.add_to(boxes1, Object::Quad(q));
            }
        }
    }
    b.add(Object::Group(boxes1));
    let light = b.material(Material::DiffuseLight {
        emit: Albedo::Constant(Color::splat(7.0)),
        two_sided: true,
    });
    b.quad(
        w,
        Point3::new(123.0, 554.0, 147.0),
        Vec3::new(300.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 265.0),
        light,
    )?;
    let c1 = Point3::new(400.0, 400.0, 200.0);
    let orange = b.material(Material::lambertian(Color::new(0.7, 0.3, 0.1)));
    b.moving_sphere(w, c1, c1 + Vec3::new(30.0, 0.0, 0.0), 50.0, orange)?;
    let glass = b.material(Material::Dielectric { ior: 1.5 });
    b.sphere(w, Point3::new(260.0, 150.0, 45.0), 50.0, glass)?;
    let metal = b.material(Material::Metal {
        albedo: Color::new(0.8, 0.8, 0.9),
        fuzz: 1.0,
    });
    b.sphere(w, Point3::new(0.0, 150.0, 145.0), 50.0, metal)?;
    // The blue subsurface sphere: a glass sphere filled with a medium bounded by the same sphere.
    b.sphere(w, Point3::new(360.0, 150.0, 145.0), 70.0, glass)?;
    let boundary = b.group();
    b.sphere(boundary, Point3::new(360.0, 150.0, 145.0), 70.0, glass)?;
    let blue = b.material(Material::Isotropic {
        albedo: Albedo::Constant(Color::new(0.2, 0.4, 0.9)),
    });
    b.medium(w, boundary, 0.2, blue)?;
    let fog_boundary = b.group();
    b.sphere(fog_boundary, Point3::ZERO, 5000.0, glass)?;
    let fog = b.material(Material::Isotropic {
        albedo: Albedo::Constant(Color::ONE),
    });
    b.medium(w, fog_boundary, 0.0001, fog)?;
    let emat = earth_texture(&mut b, opts, &mut notices)?;
    let emat = b.material(emat);
    b.sphere(w, Point3::new(400.0, 200.0, 400.0), 100.0, emat)?;
    let m = marble(&mut b, 0.2);
    let m = b.material(m);
    b.sphere(w, Point3::new(220.0, 280.0, 300.0), 80.0, m)?;
    let white = b.material(Material::lambertian(Color::splat(0.73)));
    let boxes2 = b.group();
    for _ in 0..1000 {
        let p = Point3::new(
            rng.random_range(0.0..165.0),
            rng.random_range(0.0..165.0),
            rng.random_range(0.0..165.0),
        );
        b.sphere(boxes2, p, 10.0, white)?;
    }
    b.instance(
        w,
        boxes2,
        Transform::rotate_y(15.0).then(Transform::translate(Vec3::new(-100.0, 270.0, 395.0))),
    );
    b.camera = small_camera(
        Point3::new(478.0, 278.0, -600.0),
        Point3::new(278.0, 278.0, 0.0),
        40.0,
        1.0,
    );
    b.background = Background::Solid(Color::ZERO);
    b.max_depth = 40;
    Ok(Built {
        scene: b.build()?,
        notices,
    })
}

/// Book 3's final Cornell box (SCENES.md `cornell`).
pub fn cornell(_: &SceneOptions) -> Result<Built, SceneError> {
    let mut b = SceneBuilder::new();
    let w = b.world();
    let CornellMaterials { red, white, green } = cornell_frame(&mut b)?;
    b.quad(
        w,
        Point3::new(555.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 555.0),
        Vec3::new(0.0, 555.0, 0.0),
        green,
    )?;
    b.quad(
        w,
        Point3::new(0.0, 0.0, 555.0),
        Vec3::new(0.0, 0.0, -555.0),
        Vec3::new(0.0, 555.0, 0.0),
        red,
    )?;
    b.quad(
        w,
        Point3::new(0.0, 555.0, 0.0),
        Vec3::new(555.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 555.0),
        white,
    )?;
    b.quad(
        w,
        Point3::new(0.0, 0.0, 555.0),
        Vec3::new(555.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, -555.0),
        white,
    )?;
    b.quad(
        w,
        Point3::new(555.0, 0.0, 555.0),
        Vec3::new(-555.0, 0.0, 0.0),
        Vec3::new(0.0, 555.0, 0.0),
        white,
    )?;
    let light = b.material(Material::DiffuseLight {
        emit: Albedo::Constant(Color::splat(15.0)),
        two_sided: false,
    });
    let lq = b.quad(
        w,
        Point3::new(213.0, 554.0, 227.0),
        Vec3::new(130.0, 0.0, 0.0),
        Vec3::new(0.0, 0.0, 105.0),
        light,
    )?;
    let (box1, t1) = rotated_box(
        &mut b,
        Vec3::new(165.0, 330.0, 165.0),
        15.0,
        Vec3::new(265.0, 0.0, 295.0),
        white,
    )?;
    b.instance(w, box1, t1);
    let glass = b.material(Material::Dielectric { ior: 1.5 });
    b.sphere(w, Point3::new(190.0, 90.0, 190.0), 90.0, glass)?;
    b.targets.push(ImportanceTarget::Quad(lq));
    b.targets
        .push(ImportanceTarget::Sphere(crate::shapes::Sphere::new(
            Point3::new(190.0, 90.0, 190.0),
            90.0,
            glass,
        )));
    built(b)
}
