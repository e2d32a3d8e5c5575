//! # Chapter 8, Orthonormal Bases, "Building a basis from one vector": a right-handed basis around a unit vector
//!
//! The checks of the exercise `crates/exercises/exercises/ch08_onb.rs`, which states the task.
//!
//! The check: w = +-x, +-y, +-z, the f32 case of Duff et al. near -z, and 1000 random unit vectors:
//! u, v of unit length and orthogonal to each other and to w (to 1e-12), u x v = w, `w` kept as given;
//! and `Onb::transform` of the axes gives u, v, w.

use crate::check::{self, Arg, CheckResult};
use glam::DVec3;

/// An orthonormal basis (u, v, w), right-handed: u x v = w.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Onb {
    pub u: DVec3,
    pub v: DVec3,
    pub w: DVec3,
}

/// The basis under test, as a function of w.
pub trait FromW: Fn(DVec3) -> Onb {}
impl<F: Fn(DVec3) -> Onb> FromW for F {}

fn orthonormal_right_handed(w: DVec3, b: Onb) -> CheckResult {
    let what = format!("Onb::from_w({w})");
    let fail = |why: &str| Err(format!("{what} = {b:?}: {why}"));
    if !(b.u.is_finite() && b.v.is_finite() && b.w.is_finite()) {
        return fail("not finite");
    }
    if (b.w - w).length() > 1e-15 {
        return fail("w is not the vector given");
    }
    for (name, x) in [("|u|", b.u.length()), ("|v|", b.v.length())] {
        if (x - 1.0).abs() > 1e-12 {
            return fail(&format!("{name} = {}, not 1", check::num(x)));
        }
    }
    for (name, x) in [
        ("u.v", b.u.dot(b.v)),
        ("u.w", b.u.dot(b.w)),
        ("v.w", b.v.dot(b.w)),
    ] {
        if x.abs() > 1e-12 {
            return fail(&format!("{name} = {}, not 0", check::num(x)));
        }
    }
    if (b.u.cross(b.v) - b.w).length() > 1e-12 {
        return fail(&format!(
            "u x v = {} is not w: the basis is not right-handed",
            b.u.cross(b.v)
        ));
    }
    Ok(())
}

/// The axes, the f32 case near -z, and 1000 random unit vectors.
pub fn check_basis(from_w: impl FromW) -> CheckResult {
    let mut ws = vec![
        DVec3::X,
        -DVec3::X,
        DVec3::Y,
        -DVec3::Y,
        DVec3::Z,
        -DVec3::Z,
    ];
    // Duff et al.'s example where Frisvad's method fails in f32: normalise it first.
    ws.push(DVec3::new(0.00038527316, 0.00038460016, -0.99999988079).normalize());
    ws.push(DVec3::new(1e-9, -2e-9, -1.0).normalize());
    ws.push(DVec3::new(0.0, 0.0, -1.0 + 1e-16).normalize());
    let mut rng = check::seeded(80);
    ws.extend((0..1000).map(|_| check::uniform_direction(&mut rng)));
    for w in ws {
        let basis = check::calling("Onb::from_w", &[("w", Arg::Vector(w))], || from_w(w));
        orthonormal_right_handed(w, basis)?;
    }
    Ok(())
}

/// `transform` of the local axes gives u, v, w, and of a general vector the combination.
pub fn check_transform(transform: impl Fn(&Onb, DVec3) -> DVec3) -> CheckResult {
    let b = Onb {
        u: DVec3::new(0.0, 0.0, 1.0),
        v: DVec3::new(1.0, 0.0, 0.0),
        w: DVec3::new(0.0, 1.0, 0.0),
    };
    let cases = [
        (DVec3::X, b.u),
        (DVec3::Y, b.v),
        (DVec3::Z, b.w),
        (DVec3::new(0.5, -2.0, 0.25), DVec3::new(-2.0, 0.25, 0.5)),
    ];
    for (a, want) in cases {
        let args = [
            ("self.u", Arg::Vector(b.u)),
            ("self.v", Arg::Vector(b.v)),
            ("self.w", Arg::Vector(b.w)),
            ("a", Arg::Vector(a)),
        ];
        let got = check::calling("Onb::transform", &args, || transform(&b, a));
        if got != want {
            return Err(format!(
                "Onb::transform({a}) = {got} in the basis {b:?}, expected {want}"
            ));
        }
    }
    Ok(())
}

/// All of this exercise's checks.
pub fn check_onb(from_w: impl FromW, transform: impl Fn(&Onb, DVec3) -> DVec3) -> CheckResult {
    check_basis(from_w)?;
    check_transform(transform)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn checks_reject_the_books_left_handed_basis_and_frisvads_near_minus_z() {
        // Wrong: the book's build_from_w: v = w x a, u = w x v, which makes u x v = -w.
        let book = |w: DVec3| {
            let a = if w.x.abs() > 0.9 { DVec3::Y } else { DVec3::X };
            let v = w.cross(a).normalize();
            let u = w.cross(v);
            Onb { u, v, w }
        };
        let err = check_basis(book).unwrap_err();
        assert!(err.contains("right-handed"), "{err}");
        // Wrong: Frisvad (2012), a = -1 / (1 + z), breaks down at and near w = -z.
        let frisvad = |w: DVec3| {
            let a = -1.0 / (1.0 + w.z);
            let b = w.x * w.y * a;
            Onb {
                u: DVec3::new(1.0 + w.x * w.x * a, b, -w.x),
                v: DVec3::new(b, 1.0 + w.y * w.y * a, -w.y),
                w,
            }
        };
        assert!(check_basis(frisvad).is_err());
        // Wrong: transform with u and v swapped.
        assert!(check_transform(|b: &Onb, a: DVec3| a.x * b.v + a.y * b.u + a.z * b.w).is_err());
    }
}
