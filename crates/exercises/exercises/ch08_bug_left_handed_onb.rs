//! # Bug museum, chapter 8, Orthonormal Bases, "Building a basis from one vector": find and fix the bug
//!
//! **Read first:** the section "Building a basis from one vector" of chapter 8
//! (`book/src/ch08-orthonormal-bases.md`).
//!
//! This basis looks orthonormal: every axis has unit length and every pair is perpendicular. Yet a
//! light sampled through it by spherical rectangles comes out mirrored, and an anisotropic highlight
//! turns the wrong way.
//!
//! **Task.** Find the bug in [`Onb::from_w`] and fix it: (u, v, w) must be orthonormal and
//! right-handed, u x v = w, with `w` the unit vector given.
//!
//! Check your code with `cargo exercises check ch08_bug_left_handed_onb` (or
//! `rtl exercises check ch08_bug_left_handed_onb`, the same);
//! `cargo exercises hint ch08_bug_left_handed_onb` gives a hint.

use glam::DVec3;

/// An orthonormal basis (u, v, w).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Onb {
    pub u: DVec3,
    pub v: DVec3,
    pub w: DVec3,
}

// ANCHOR: exercise
impl Onb {
    /// The right-handed basis with third axis `w` (unit), built as the book's `build_from_w` does.
    pub fn from_w(w: DVec3) -> Onb {
        let a = if w.x.abs() > 0.9 { DVec3::Y } else { DVec3::X };
        let v = w.cross(a).normalize();
        let u = w.cross(v);
        Onb { u, v, w }
    }
}
// ANCHOR_END: exercise
