//! # Chapter 8, "Orthonormal Bases": a right-handed basis around a unit vector
//!
//! **Task.** Write [`Onb::from_w`]: given a unit vector w, find unit u and v such that (u, v, w) is
//! orthonormal and right-handed, u x v = w; and [`Onb::transform`], which maps local coordinates
//! (a, b, c) to the world vector a u + b v + c w (a direction sampled around +z becomes one around w).
//!
//! Use the branchless construction of Duff et al., "Building an Orthonormal Basis, Revisited"
//! (JCGT 2017): with s = sign(w.z) (+1 for w.z = +-0 as well) and a = -1 / (s + w.z),
//! b = w.x w.y a:
//!
//! u = (1 + s w.x^2 a, s b, -s w.x),  v = (b, s + w.y^2 a, -w.y).
//!
//! It is exact at the poles and stable near them; Frisvad's earlier version (a = -1 / (1 + w.z))
//! divides by ~0 near w = -z. Note that the book's `build_from_w` (v = w x a, u = w x v) gives a
//! left-handed basis.
//!
//! The check: w = +-x, +-y, +-z, the f32 case of Duff et al. near -z, and 1000 random unit vectors:
//! u, v of unit length and orthogonal to each other and to w (to 1e-12), u x v = w, `w` kept as given;
//! and [`Onb::transform`] of the axes gives u, v, w.
//!
//! Check your code with `rtl exercises check ch08_onb`; `rtl exercises hint ch08_onb` gives a hint.

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
    /// The right-handed basis with third axis `w` (a unit vector), by Duff et al. (2017).
    pub fn from_w(w: DVec3) -> Onb {
        let _ = w;
        todo!("ch08 Onb::from_w: Duff et al.'s branchless basis, u x v = w")
    }

    /// The world vector with local coordinates `a`: a.x u + a.y v + a.z w.
    pub fn transform(&self, a: DVec3) -> DVec3 {
        let _ = a;
        todo!("ch08 Onb::transform: a.x u + a.y v + a.z w")
    }
}
// ANCHOR_END: exercise
