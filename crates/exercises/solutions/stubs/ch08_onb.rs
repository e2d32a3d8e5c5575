//! # Chapter 8, Orthonormal Bases, "Building a basis from one vector": a right-handed basis around a unit vector
//!
//! **Read first:** the sections "Building a basis from one vector" and "The cases that break bases"
//! of chapter 8 (`book/src/ch08-orthonormal-bases.md`): the branchless construction of Duff et al.,
//! "Building an Orthonormal Basis, Revisited" (JCGT 2017), and why the book's `build_from_w` and
//! Frisvad's earlier formulas fail.
//!
//! **Task.** Write [`Onb::from_w`]: given a unit vector w, find unit u and v such that (u, v, w) is
//! orthonormal and right-handed, u x v = w (not -w: the book's `build_from_w` gets this sign wrong),
//! keeping `w` exactly as given. It must hold for every unit w: the axes +-x, +-y, +-z, w.z = -0.0,
//! and vectors within 1e-8 of -z, where a formula that divides by 1 + w.z breaks down. And write
//! [`Onb::transform`], which maps local coordinates (a, b, c) to the world vector with those
//! coordinates along (u, v, w) (a direction sampled around +z becomes one around w).
//!
//! The check: w = +-x, +-y, +-z, Duff et al.'s single-precision case near -z and two more, and 1000
//! random unit vectors: u, v of unit length and orthogonal to each other and to w (to 1e-12),
//! u x v = w, `w` kept as given; and [`Onb::transform`] of the axes and of one other vector.
//!
//! Check your code with `cargo exercises check ch08_onb` (or `rtl exercises check ch08_onb`, the
//! same); `cargo exercises hint ch08_onb` gives a hint.

use glam::DVec3;

/// An orthonormal basis (u, v, w), right-handed: u x v = w.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Onb {
    pub u: DVec3,
    pub v: DVec3,
    pub w: DVec3,
}

// ANCHOR: exercise
impl Onb {
    /// The right-handed orthonormal basis with third axis `w` (a unit vector), without a branch
    /// that fails near -z.
    pub fn from_w(w: DVec3) -> Onb {
        let _ = w;
        todo!("ch08 Onb::from_w: a right-handed orthonormal basis around w, u x v = w")
    }

    /// The world vector whose coordinates along (u, v, w) are `a`.
    pub fn transform(&self, a: DVec3) -> DVec3 {
        let _ = a;
        todo!("ch08 Onb::transform: local coordinates to a world vector")
    }
}
// ANCHOR_END: exercise
