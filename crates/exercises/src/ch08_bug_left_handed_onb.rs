//! # Bug museum, chapter 8, Orthonormal Bases, "Building a basis from one vector": the left-handed basis
//!
//! The checks of the exercise `crates/exercises/exercises/ch08_bug_left_handed_onb.rs`, which holds
//! the bug to find.
//!
//! The check: chapter 8's check of the basis (the axes, vectors near -z, 1000 random unit vectors:
//! unit, orthogonal, u x v = w); and the consequence of a mirror image: a lobe sampled at local azimuth
//! phi in (0, pi/2) must come out at the same azimuth measured in (u, v) of a right-handed frame.

use crate::ch08_onb::{self, Onb};
use crate::check::{self, CheckResult};
use glam::DVec3;

/// The basis under test: `w -> (u, v, w)`.
pub trait FromW: Fn(DVec3) -> Onb {}
impl<F: Fn(DVec3) -> Onb> FromW for F {}

/// Orthonormal and right-handed for the axes, near -z and at random. The mirror-image diagnosis is
/// given only when the failure is that one: an orthonormal basis with u x v = -w.
pub fn check_right_handed(from_w: impl FromW) -> CheckResult {
    ch08_onb::check_basis(&from_w).map_err(|e| {
        if e.contains("not right-handed") {
            format!(
                "{e}\n(with u x v = -w the basis is a mirror image: a direction sampled at azimuth phi \
                 around w comes out at -phi, so any density that is not symmetric about w, such as a \
                 spherical rectangle's or an anisotropic lobe's, is sampled mirrored)"
            )
        } else {
            e
        }
    })
}

/// The local direction at azimuth 45 degrees and polar angle 60 degrees keeps its azimuth: its world
/// image has positive components along both u and w x u, for 1000 random w.
pub fn check_azimuth(from_w: impl FromW) -> CheckResult {
    let mut rng = check::seeded(81);
    let local = DVec3::new(0.5 * 0.75f64.sqrt(), 0.5 * 0.75f64.sqrt(), 0.5);
    for _ in 0..1000 {
        let w = check::uniform_direction(&mut rng);
        let b = check::calling("Onb::from_w", &[("w", w.into())], || from_w(w));
        let d = local.x * b.u + local.y * b.v + local.z * b.w;
        let (along_u, along_wu) = (d.dot(b.u), d.dot(w.cross(b.u)));
        if !(along_u > 0.0 && along_wu > 0.0) {
            let azimuth = along_wu.atan2(along_u).to_degrees();
            // A mirror image turns +45 degrees into -45; anything else is another fault.
            let what = if (azimuth + 45.0).abs() < 1e-6 {
                "the basis mirrors azimuths"
            } else {
                "the basis does not keep azimuths"
            };
            return Err(format!(
                "around w = {w}, the local direction at azimuth +45 degrees lands at azimuth {} \
                 degrees measured from u towards w x u: {what}",
                check::sig(azimuth, 4)
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn checks_reject_the_books_build_from_w() {
        let book = |w: DVec3| {
            let a = if w.x.abs() > 0.9 { DVec3::Y } else { DVec3::X };
            let v = w.cross(a).normalize();
            let u = w.cross(v);
            Onb { u, v, w }
        };
        let err = check_right_handed(book).unwrap_err();
        assert!(err.contains("mirror"), "{err}");
        assert!(check_azimuth(book).is_err());
        // Wrong in another way: v not normalised. Not a mirror image, and not diagnosed as one.
        let unnormalised = |w: DVec3| {
            let a = if w.x.abs() > 0.9 { DVec3::Y } else { DVec3::X };
            let v = a.cross(w);
            let u = v.cross(w);
            Onb { u, v, w }
        };
        let err = check_right_handed(unnormalised).unwrap_err();
        assert!(!err.contains("mirror"), "{err}");
    }
}
