//! An orthonormal basis built from one vector (book 3, chapter 8).

use glam::DVec3;

// ANCHOR: onb
/// A right-handed orthonormal basis `(u, v, w)`: `u x v = w`, all unit length and pairwise orthogonal.
///
/// Built from `w` alone by the branchless construction of Duff, Burgess, Christensen, Hery, Kensler,
/// Liani and Villemin, "Building an Orthonormal Basis, Revisited" (JCGT 2017), which is accurate for
/// every unit `w`, including those close to `-z` where Frisvad's 2012 method breaks down.
/// (The book's `build_from_w` picks a helper axis and two cross products; it is left-handed.)
///
/// ```
/// use glam::DVec3;
/// use rtl_pdf::Onb;
/// let onb = Onb::new(DVec3::new(0.0, 0.6, 0.8));
/// assert!((onb.u().cross(onb.v()) - onb.w()).length() < 1e-15);
/// let local = DVec3::new(0.3, -0.2, 0.9);
/// assert!((onb.to_local(onb.transform(local)) - local).length() < 1e-15);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Onb {
    u: DVec3,
    v: DVec3,
    w: DVec3,
}

impl Onb {
    /// The basis whose third axis is `w`, which must be a unit vector.
    #[inline]
    pub fn new(w: DVec3) -> Onb {
        debug_assert!(
            (w.length_squared() - 1.0).abs() < 1e-9,
            "Onb::new: w = {w} is not a unit vector"
        );
        // sign(w.z) with sign(-0) = -1, so that 1 / (sign + w.z) never divides by zero.
        let sign = 1.0f64.copysign(w.z);
        let a = -1.0 / (sign + w.z);
        let b = w.x * w.y * a;
        let u = DVec3::new(1.0 + sign * w.x * w.x * a, sign * b, -sign * w.x);
        let v = DVec3::new(b, sign + w.y * w.y * a, -w.y);
        Onb { u, v, w }
    }

    /// The first tangent axis.
    #[inline]
    pub fn u(&self) -> DVec3 {
        self.u
    }

    /// The second tangent axis, `w x u`.
    #[inline]
    pub fn v(&self) -> DVec3 {
        self.v
    }

    /// The axis the basis was built from (a normal, or the direction to a light).
    #[inline]
    pub fn w(&self) -> DVec3 {
        self.w
    }

    /// Local coordinates `(a, b, c)` to world: `a u + b v + c w`.
    #[inline]
    pub fn transform(&self, local: DVec3) -> DVec3 {
        local.x * self.u + local.y * self.v + local.z * self.w
    }

    /// World to local coordinates: `(d . u, d . v, d . w)`, the inverse of [`Onb::transform`].
    #[inline]
    pub fn to_local(&self, world: DVec3) -> DVec3 {
        DVec3::new(world.dot(self.u), world.dot(self.v), world.dot(self.w))
    }
}
// ANCHOR_END: onb
