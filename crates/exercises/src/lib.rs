//! # Chapter exercises: the checkers
//!
//! The files learners edit are `crates/exercises/exercises/chNN_*.rs`, one per exercise, named after
//! the chapter of "Ray Tracing: The Rest of Your Life" (and of this workspace's book) that explains it;
//! each states its task in its doc comment. This library holds what checks them, and compiles without
//! them, so that one exercise that does not compile never stops another from being checked:
//!
//! - one module per exercise with the types it is given and its `check_*` functions, which take the
//!   implementation to check as an argument and say what they saw when it is wrong (a z-score, a
//!   chi-square p-value, the first wrong value). Each module's own tests (the *self-tests*, counted by
//!   `cargo test -p rtl-exercises --lib`) feed the checks deliberately wrong implementations and see
//!   them fail, so a check that cannot fail would be noticed;
//! - [`check`], the statistics the checks share;
//! - [`harness`], the program each exercise's test target (`tests/chNN_*.rs`) runs.
//!
//! `cargo exercises list` (or `rtl exercises list`, the same) shows every exercise's state;
//! `cargo test -p rtl-exercises --features solutions` checks the reference solutions in `solutions/`.

pub mod check;
pub mod harness;

pub mod ch02_estimate_pi;
pub mod ch02_jittered_pi;
pub mod ch03_importance_x_sq;
pub mod ch03_inverse_x_sq;
pub mod ch03_tabulated_inverse_cdf;
pub mod ch04_sphere_integral;
pub mod ch05_lambertian_pdf;
pub mod ch06_scatter_weight;
pub mod ch07_cosine_direction;
pub mod ch08_onb;
pub mod ch09_quad_pdf_value;
pub mod ch10_mixture_pdf;
pub mod ch12_nan_guard;
pub mod ch12_sphere_pdf_value;

// The bug museum: working-looking code with the bugs the book's readers have hit for years.
pub mod ch05_bug_normal_length;
pub mod ch07_bug_cosine_factor_two;
pub mod ch08_bug_left_handed_onb;
pub mod ch10_bug_uniform_samples_cosine;
pub mod ch12_bug_cone_cos_theta_max;
pub mod ch12_bug_light_list_pdf;
pub mod ch12_bug_nan_average;
