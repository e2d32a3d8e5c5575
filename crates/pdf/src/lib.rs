//! # rtl-pdf: directions on the sphere
//!
//! The third layer of the workspace (after `rtl-mc` and `rtl-sampling`), following chapters 4 and 7-10
//! of "Ray Tracing: The Rest of Your Life":
//!
//! - [`warp`]: maps from the unit square to directions (uniform sphere, hemisphere, cosine, cone,
//!   spherical rectangle) and points (disk, parallelogram), each with its density and inverse;
//! - [`Onb`]: an orthonormal basis from one vector, to carry local directions to the world;
//! - [`Pdf`] with [`SpherePdf`], [`HemispherePdf`], [`CosinePdf`], [`HittablePdf`] (towards [`ShapeSampler`]s
//!   such as [`SphereTarget`] and [`QuadTarget`]) and [`MixturePdf`];
//! - [`mis`]: balance and power heuristics for multiple importance sampling;
//! - [`chi2`]: the chi-square goodness-of-fit test that checks every sampler against its density.
//!
//! One vocabulary throughout: `sample(u)` takes its uniform numbers and returns the direction with its
//! density ([`DirectionSample`]), `pdf(d)` evaluates that density, and `invert` (the warps, the
//! [`Selection`]) maps a result back to its `u`. The book's `generate(rng)` / `value(d)` are thin
//! wrappers. Everything per sample is static dispatch and allocation-free: mixtures are generic over
//! their parts, and lists of targets are borrowed slices.
//!
//! ```
//! use glam::DVec3;
//! use rand::SeedableRng;
//! use rtl_pdf::{CosinePdf, HittablePdf, MixturePdf, Pdf, QuadTarget};
//! let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(1);
//! // A point on the floor, a square light above it: the book's mixture of light and cosine sampling.
//! let light = [QuadTarget::new(DVec3::new(-1.0, 5.0, -1.0), DVec3::X * 2.0, DVec3::Z * 2.0)];
//! let towards_light = HittablePdf::new(DVec3::ZERO, &light).unwrap();
//! let pdf = MixturePdf::new(towards_light, CosinePdf::new(DVec3::Y));
//! let d = pdf.generate(&mut rng); // the book's way: a random number generator
//! assert!(d.y > 0.0 && pdf.value(d) > 0.0);
//! // ours: chosen numbers in, the direction and its density out
//! let s = pdf.sample(glam::DVec2::new(0.25, 0.5)).unwrap();
//! assert!((s.pdf - pdf.pdf(s.direction)).abs() < 1e-12 * s.pdf);
//! ```

pub mod chi2;
mod hittable;
pub mod mis;
mod mixture;
mod onb;
mod pdf;
mod selection;
mod target;
pub mod warp;

pub use hittable::{HittablePdf, MAX_CANDIDATES, ShapeIndex};
pub use mis::{balance_heuristic, power_heuristic};
pub use mixture::{MixtureError, MixtureOfPdfs, MixturePdf};
pub use onb::Onb;
pub use pdf::{CosinePdf, DirectionSample, HemispherePdf, Pdf, SpherePdf};
/// The largest `f64` below 1, `1 - 2^-53`: where a remapped uniform number is kept (from rtl-sampling).
pub use rtl_sampling::ONE_MINUS_EPSILON;
pub use selection::{Choice, Selection, SelectionError, choose_uniform};
pub use target::{
    EDGE_ROUNDING, MAX_EDGE_SLACK, MAX_SPHERICAL_RECTANGLE_SOLID_ANGLE, MIN_CONE_SIN2,
    MIN_SPHERICAL_RECTANGLE_SOLID_ANGLE, QuadSampling, QuadTarget, ShapeSampler, SphereTarget,
    SphereView,
};
