//! # Bug museum, chapter 5, Light Scattering, "The Lambertian surface": find and fix the bug
//!
//! **Read first:** the section "The Lambertian surface" of chapter 5
//! (`book/src/ch05-light-scattering.md`).
//!
//! A renderer's spheres reflect too much light: a white sphere of radius 2 glows brighter than the
//! light that falls on it, and the bigger the sphere, the worse. Small unit spheres look right.
//!
//! **Task.** [`outward_normal`] feeds the Lambertian density, which takes n . d as the cosine of
//! the angle between the normal n and a direction d. Find why the light grows with the radius and
//! fix it.
//!
//! The radius may be negative. Earlier editions of the first book of the series, *Ray Tracing in
//! One Weekend* ("Modeling a Hollow Glass Sphere"), make a glass bubble of a sphere of negative
//! radius: the same surface, with its normal pointing inwards, towards the centre, so that the
//! bubble's outside is the glass around it. The function keeps that: its normal points outwards for
//! a positive radius, inwards for a negative one.
//!
//! Check your code with `cargo exercises check ch05_bug_normal_length` (or
//! `rtl exercises check ch05_bug_normal_length`, the same);
//! `cargo exercises hint ch05_bug_normal_length` gives a hint.

use glam::DVec3;

// ANCHOR: exercise
/// The normal at `point` of the sphere (`center`, `radius`): outwards for a positive radius, inwards
/// for a negative one.
pub fn outward_normal(center: DVec3, radius: f64, point: DVec3) -> DVec3 {
    let _ = radius;
    point - center
}
// ANCHOR_END: exercise
