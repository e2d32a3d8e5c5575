//! # Chapter exercises
//!
//! One module per exercise, named after the chapter of "Ray Tracing: The Rest of Your Life" (and of
//! this workspace's book) that explains it. Each states its task in its doc comment and leaves a
//! function body with `todo!()` for you to fill in; its tests check your code with the same rigour as
//! the workspace's crates: exact values, the chapter's hard cases, z-tests and chi-square tests.
//!
//! - `cargo test -p rtl-exercises` checks your work (it fails until every exercise is done);
//!   `cargo test -p rtl-exercises ch07` checks one chapter's.
//! - `cargo run -p rtl-exercises --example status` lists every exercise as done, failing (and why) or
//!   not started.
//! - `cargo test -p rtl-exercises --features solutions` checks the checks against the reference
//!   solutions (hidden in each file's `solution` module: try first, peek later).
//!
//! Each module exposes `check_*` functions that take the implementation to check as an argument;
//! every module also has a test that feeds them a deliberately wrong implementation and sees them fail,
//! so a check that cannot fail would be noticed. The shared statistics live in [`check`].

pub mod check;

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

/// One exercise: its module, the book's chapter and section that explain it, and its checks.
#[derive(Clone, Copy, Debug)]
pub struct Exercise {
    /// The module (and file `src/<name>.rs`) of the exercise.
    pub name: &'static str,
    /// Chapter and section of the book that explain it.
    pub chapter: &'static str,
    /// Runs all of the exercise's checks on the learner's code.
    pub check: fn() -> check::CheckResult,
}

/// Every exercise, in the book's order.
pub const EXERCISES: &[Exercise] = &[
    Exercise {
        name: "ch02_estimate_pi",
        chapter: "2 A Simple Monte Carlo Program: Estimating Pi",
        check: ch02_estimate_pi::check,
    },
    Exercise {
        name: "ch02_jittered_pi",
        chapter: "2 A Simple Monte Carlo Program: Stratified Samples (Jittering)",
        check: ch02_jittered_pi::check,
    },
    Exercise {
        name: "ch03_inverse_x_sq",
        chapter: "3 One Dimensional MC Integration: Inverse Transform Sampling",
        check: ch03_inverse_x_sq::check,
    },
    Exercise {
        name: "ch03_tabulated_inverse_cdf",
        chapter: "3 One Dimensional MC Integration: Approximating Distributions",
        check: ch03_tabulated_inverse_cdf::check,
    },
    Exercise {
        name: "ch03_importance_x_sq",
        chapter: "3 One Dimensional MC Integration: Importance Sampling",
        check: ch03_importance_x_sq::check,
    },
    Exercise {
        name: "ch04_sphere_integral",
        chapter: "4 MC Integration on the Sphere of Directions",
        check: ch04_sphere_integral::check,
    },
    Exercise {
        name: "ch05_lambertian_pdf",
        chapter: "5 Light Scattering: The Scattering PDF",
        check: ch05_lambertian_pdf::check,
    },
    Exercise {
        name: "ch06_scatter_weight",
        chapter: "6 Playing with Importance Sampling: Returning to the Cornell Box",
        check: ch06_scatter_weight::check,
    },
    Exercise {
        name: "ch07_cosine_direction",
        chapter: "7 Generating Random Directions: Cosine Sampling a Hemisphere",
        check: ch07_cosine_direction::check,
    },
    Exercise {
        name: "ch08_onb",
        chapter: "8 Orthonormal Bases: Generating an Orthonormal Basis",
        check: ch08_onb::check,
    },
    Exercise {
        name: "ch09_quad_pdf_value",
        chapter: "9 Sampling Lights Directly: Getting the PDF of a Light",
        check: ch09_quad_pdf_value::check,
    },
    Exercise {
        name: "ch10_mixture_pdf",
        chapter: "10 Mixture Densities: The Mixture PDF Class",
        check: ch10_mixture_pdf::check,
    },
    Exercise {
        name: "ch12_sphere_pdf_value",
        chapter: "12 Cleaning Up PDF Management: Sampling a Sphere Object",
        check: ch12_sphere_pdf_value::check,
    },
    Exercise {
        name: "ch12_nan_guard",
        chapter: "12 Cleaning Up PDF Management: Handling Surface Acne",
        check: ch12_nan_guard::check,
    },
];

#[cfg(test)]
mod tests {
    use super::EXERCISES;

    #[test]
    fn every_exercise_file_is_listed_once_and_every_listed_exercise_has_a_file() {
        let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/src");
        let mut files: Vec<String> = std::fs::read_dir(dir)
            .expect("src is readable")
            .filter_map(|e| e.ok()?.file_name().into_string().ok())
            .filter(|n| {
                n.starts_with("ch")
                    && n[2..].starts_with(|c: char| c.is_ascii_digit())
                    && n.ends_with(".rs")
            })
            .map(|n| n.trim_end_matches(".rs").to_string())
            .collect();
        files.sort();
        let mut listed: Vec<String> = EXERCISES.iter().map(|e| e.name.to_string()).collect();
        listed.sort();
        assert_eq!(files, listed);
        assert!(EXERCISES.len() >= 12);
        for e in EXERCISES {
            let chapter: u32 = e.name[2..4].parse().expect("chNN_ names");
            assert!(
                e.chapter.starts_with(&format!("{chapter} ")),
                "{} is explained in {}",
                e.name,
                e.chapter
            );
        }
    }
}
