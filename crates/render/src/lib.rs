//! rtl-render: the renderer of "Ray Tracing in One Weekend" and "The Next Week", the ground the
//! importance sampling of "The Rest of Your Life" stands on.
//!
//! One concept a module, in the books' order: vectors ([`vec`](mod@vec)) and rays ([`ray`]); bounding boxes
//! ([`aabb`]) and the BVH ([`bvh`]), with four-lane packets ([`lanes`]) and rigid instances flattened into
//! world space ([`flatten`]); hit records and robust ray offsets ([`hit`]); shapes ([`shapes`]);
//! textures ([`texture`], [`perlin`]); materials ([`material`]); the camera ([`camera`]); scenes,
//! instances and media ([`scene`]); the built-in scenes ([`scenes`]); importance targets ([`lights`]);
//! the integrator and its sampling strategies ([`integrator`]); 32 paths traced side by side in
//! the vector lanes ([`paths8`]: their rays intersected eight at a time by [`ray8`], their vertices
//! on Lambertian quads and glass spheres computed in the lanes by [`vertex8`] and [`glass8`], the
//! mixture's directions drawn together by [`mixture8`] and [`warp8`], all written once over
//! [`wide8`]'s lanes), and `mis` paths side by side too ([`mis8`]);
//! prefix-stable per-sample randomness ([`sampler`]); progressive rendering into an accumulation buffer
//! ([`render`]); checkpoints and parts of long renders ([`checkpoint`]); image files ([`output`]).
//!
//! ```
//! use rtl_render::{integrator::Strategy, render::{RenderSettings, render}, scenes};
//! let built = (scenes::find("cornell").unwrap().build)(&Default::default()).unwrap();
//! let settings = RenderSettings {
//!     width: 8, max_depth: 50, seed: 1, strategy: Strategy::Cosine, mixture_weight: 0.5,
//! };
//! let (image, stats) = render(&built.scene, settings, 2);
//! assert_eq!(stats.samples, 8 * 8 * 2);
//! assert!(image.image().iter().all(|c| c.is_finite()));
//! ```

// Only x86-64 has the vector lanes (`paths8`, `mis8` and their parts): elsewhere their set-up is
// compiled but never used.
#![cfg_attr(not(target_arch = "x86_64"), allow(unused_imports, dead_code))]

pub mod aabb;
pub mod boundary_pieces;
pub mod builder;
pub mod bvh;
pub mod camera;
pub mod checkpoint;
pub mod closed_surface;
pub mod connection;
pub mod flatten;
pub mod glass8;
pub mod hit;
pub mod hit_tier;
pub mod ids;
pub mod integrator;
pub mod lanes;
pub mod light_tree;
pub mod lights;
pub mod limits;
pub mod manifold;
pub mod material;
pub mod media_crossed;
pub mod metal_pdf;
pub mod mis8;
pub mod mis_vertex8;
pub mod mixture8;
pub mod output;
pub mod paths8;
pub mod perlin;
pub mod quad8;
pub mod ray;
pub mod ray8;
pub mod render;
pub mod sampler;
pub mod scene;
pub mod scene_file;
pub mod scenes;
pub mod separation;
pub mod shapes;
pub mod target_index;
pub mod text;
pub mod texture;
pub mod tier_race;
pub mod transform;
pub mod traversal;
pub mod vec;
pub mod vertex8;
pub mod warp8;
pub mod wide8;

pub use vec::{Color, Point3, Vec3};
