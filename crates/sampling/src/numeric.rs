//! Numerical inversion of a CDF given as code: solve `F(x) = u` on a bracket `[a, b]` to a stated
//! tolerance in `u`, and report the error reached.
//!
//! * With the density `p = F'`, Newton's step `x ← x - (F(x) - u) / p(x)` converges quadratically
//!   near the root; it is only taken when it lands strictly inside the current bracket, otherwise
//!   the bracket is halved (bracketed Newton, as in Numerical Recipes' `rtsafe`).
//! * Without the density, Brent's method (Brent, "Algorithms for Minimization without Derivatives",
//!   1973) mixes inverse quadratic interpolation, the secant step and bisection, also never leaving
//!   the bracket.
//!
//! Both stop when `|F(x) - u| ≤ tolerance`, or when the bracket has shrunk to two neighbouring
//! floats (then `F` jumps there, or rounds: the returned [`Inversion::u_error`] tells by how much).
//!
//! ```
//! use rtl_sampling::numeric::NumericInverse;
//! // p(x) = 3x²/8 on [0, 2], F(x) = x³/8: the exact answer is 2 ∛u.
//! let inv = NumericInverse::new(|x: f64| x * x * x / 8.0, 0.0, 2.0)
//!     .unwrap()
//!     .with_tolerance(1e-12)
//!     .unwrap();
//! let r = inv.invert(0.3).unwrap();
//! assert!(r.u_error <= 1e-12);
//! assert!((r.x - 2.0 * 0.3f64.cbrt()).abs() < 1e-11);
//! ```

use crate::SamplingError;

/// The answer of a numerical inversion.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Inversion {
    /// The `x` found.
    pub x: f64,
    /// The error reached, `|F(x) - u|`.
    pub u_error: f64,
    /// How many times `F` was evaluated.
    pub evaluations: u32,
}

/// A user CDF `F` on a bracket `[a, b]`, with its density `p` if known, inverted to a tolerance.
#[derive(Clone, Debug)]
pub struct NumericInverse<F, P = fn(f64) -> f64> {
    cdf: F,
    pdf: Option<P>,
    a: f64,
    b: f64,
    fa: f64,
    fb: f64,
    tolerance: f64,
}

/// The most evaluations one inversion may take. Bisection halves the bracket's width, so it needs
/// about `log2(width / spacing of the floats at the root)` steps to reach neighbouring floats: 52
/// for `[1, 2]`, about 1100 for a root near 1 in `[-f64::MAX, f64::MAX]`, and up to about 2100 for
/// a subnormal root in that bracket, which this limit stops short of (the best `x` found is then
/// returned, with its `u_error`).
const MAX_EVALUATIONS: u32 = 2000;

impl<F: Fn(f64) -> f64> NumericInverse<F> {
    /// Inverts `cdf` on `[a, b]` by Brent's method. `F(a)` and `F(b)` are evaluated once here and
    /// bound the range of `u`. The default tolerance is `1e-12`.
    pub fn new(cdf: F, a: f64, b: f64) -> Result<Self, SamplingError> {
        Self::build(cdf, None, a, b)
    }
}

impl<F: Fn(f64) -> f64, P: Fn(f64) -> f64> NumericInverse<F, P> {
    /// Inverts `cdf` on `[a, b]` by bracketed Newton steps with the density `pdf = F'`.
    pub fn with_density(cdf: F, pdf: P, a: f64, b: f64) -> Result<Self, SamplingError> {
        Self::build(cdf, Some(pdf), a, b)
    }

    fn build(cdf: F, pdf: Option<P>, a: f64, b: f64) -> Result<Self, SamplingError> {
        if !(a.is_finite() && b.is_finite() && a < b) {
            return Err(SamplingError::BadInterval { a, b });
        }
        let (fa, fb) = (cdf(a), cdf(b));
        for (x, value) in [(a, fa), (b, fb)] {
            if !value.is_finite() {
                return Err(SamplingError::BadCdfValue { x, value });
            }
        }
        if fb <= fa {
            return Err(SamplingError::ZeroMass { f: fa });
        }
        Ok(Self {
            cdf,
            pdf,
            a,
            b,
            fa,
            fb,
            tolerance: 1e-12,
        })
    }

    /// Sets the tolerance in `u` (finite, `>= 0`; 0 asks for the best that floating point allows).
    pub fn with_tolerance(mut self, tolerance: f64) -> Result<Self, SamplingError> {
        if !(tolerance.is_finite() && tolerance >= 0.0) {
            return Err(SamplingError::BadTolerance(tolerance));
        }
        self.tolerance = tolerance;
        Ok(self)
    }

    /// The range `[F(a), F(b)]` of `u`.
    pub fn range(&self) -> (f64, f64) {
        (self.fa, self.fb)
    }

    /// Solves `F(x) = u` for `u` in `[F(a), F(b)]`; any other `u` (or NaN) is an error, as is a
    /// non-finite value of `F` on the way.
    pub fn invert(&self, u: f64) -> Result<Inversion, SamplingError> {
        if !(self.fa..=self.fb).contains(&u) {
            return Err(SamplingError::OutsideRange {
                u,
                lo: self.fa,
                hi: self.fb,
            });
        }
        let (ga, gb) = (self.fa - u, self.fb - u);
        for (x, g) in [(self.a, ga), (self.b, gb)] {
            if g.abs() <= self.tolerance {
                return Ok(Inversion {
                    x,
                    u_error: g.abs(),
                    evaluations: 0,
                });
            }
        }
        match &self.pdf {
            Some(p) => self.newton(p, u, ga),
            None => self.brent(u, ga, gb),
        }
    }

    /// `g(x) = F(x) - u`, checked.
    fn g(&self, x: f64, u: f64) -> Result<f64, SamplingError> {
        let value = (self.cdf)(x);
        if value.is_finite() {
            Ok(value - u)
        } else {
            Err(SamplingError::BadCdfValue { x, value })
        }
    }

    // ANCHOR: newton
    /// Bracketed Newton: `g(lo) < 0 < g(hi)` holds throughout; a Newton step is taken only if it
    /// lands strictly inside the bracket, otherwise the bracket is bisected.
    fn newton(&self, p: &P, u: f64, ga: f64) -> Result<Inversion, SamplingError> {
        let (mut lo, mut hi) = (self.a, self.b);
        // Start where the chord from (a, F(a)) to (b, F(b)) meets u.
        let mut x = lo + (hi - lo) * (-ga / (self.fb - self.fa));
        let mut best = Inversion {
            x: lo,
            u_error: ga.abs(),
            evaluations: 0,
        };
        for evaluations in 1..=MAX_EVALUATIONS {
            if !(x > lo && x < hi) {
                x = 0.5 * lo + 0.5 * hi;
            }
            let g = self.g(x, u)?;
            if g.abs() < best.u_error {
                best = Inversion {
                    x,
                    u_error: g.abs(),
                    evaluations,
                };
            }
            best.evaluations = evaluations;
            if g.abs() <= self.tolerance {
                break;
            }
            if g < 0.0 {
                lo = x
            } else {
                hi = x
            }
            if lo.next_up() >= hi {
                break; // two neighbouring floats: nothing left to refine
            }
            let slope = p(x);
            // Bisect when Newton would leave the bracket or make too little progress.
            let step = g / slope;
            let next = x - step;
            x = if slope > 0.0 && next > lo && next < hi && evaluations < 100 {
                next
            } else {
                0.5 * lo + 0.5 * hi
            };
        }
        Ok(best)
    }
    // ANCHOR_END: newton

    /// Brent's method on `g = F - u` with `g(a) g(b) < 0`.
    fn brent(&self, u: f64, ga: f64, gb: f64) -> Result<Inversion, SamplingError> {
        // b is the best estimate, a the previous one, c the other end of the bracket [b, c].
        let (mut a, mut b) = (self.a, self.b);
        let (mut fa, mut fb) = (ga, gb);
        let (mut c, mut fc) = (a, fa);
        let mut d = b - a;
        let mut e = d;
        let mut evaluations = 0;
        loop {
            if (fb > 0.0) == (fc > 0.0) {
                // The root lies between a and b: make a the other end.
                c = a;
                fc = fa;
                d = b - a;
                e = d;
            }
            if fc.abs() < fb.abs() {
                (a, b, c) = (b, c, b);
                (fa, fb, fc) = (fb, fc, fb);
            }
            let tol1 = 2.0 * f64::EPSILON * b.abs() + f64::MIN_POSITIVE;
            // halves first: c - b overflows on a bracket wider than f64::MAX
            let xm = 0.5 * c - 0.5 * b;
            if fb.abs() <= self.tolerance || xm.abs() <= tol1 || evaluations >= MAX_EVALUATIONS {
                return Ok(Inversion {
                    x: b,
                    u_error: fb.abs(),
                    evaluations,
                });
            }
            if e.abs() >= tol1 && fa.abs() > fb.abs() {
                // Interpolate: secant with two points, inverse quadratic with three.
                let s = fb / fa;
                let (mut p, mut q);
                if a == c {
                    p = 2.0 * xm * s;
                    q = 1.0 - s;
                } else {
                    let qa = fa / fc;
                    let r = fb / fc;
                    p = s * (2.0 * xm * qa * (qa - r) - (b - a) * (r - 1.0));
                    q = (qa - 1.0) * (r - 1.0) * (s - 1.0);
                }
                if p > 0.0 {
                    q = -q;
                } else {
                    p = -p;
                }
                // Accept the step only if it stays well inside the bracket and shrinks fast enough.
                if 2.0 * p < (3.0 * xm * q - (tol1 * q).abs()).min((e * q).abs()) {
                    e = d;
                    d = p / q;
                } else {
                    d = xm;
                    e = d;
                }
            } else {
                d = xm;
                e = d;
            }
            a = b;
            fa = fb;
            b += if d.abs() > tol1 { d } else { tol1.copysign(xm) };
            fb = self.g(b, u)?;
            evaluations += 1;
        }
    }
}

impl<F: Fn(f64) -> f64, P: Fn(f64) -> f64> rand::distr::Distribution<f64> for NumericInverse<F, P> {
    /// Inverts `u = F(a) + (F(b) - F(a)) U` for a uniform `U`; NaN where `F` turns non-finite on
    /// the way (the error [`NumericInverse::invert`] reports).
    fn sample<R: rand::Rng + ?Sized>(&self, rng: &mut R) -> f64 {
        let u = self.fa + (self.fb - self.fa) * rng.random::<f64>();
        self.invert(u.clamp(self.fa, self.fb))
            .map_or(f64::NAN, |r| r.x)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cdf(x: f64) -> f64 {
        x * x / 4.0
    }

    #[test]
    fn both_methods_reach_each_tolerance() {
        let brent = NumericInverse::new(cdf, 0.0, 2.0).unwrap();
        let newton = NumericInverse::with_density(cdf, |x: f64| x / 2.0, 0.0, 2.0).unwrap();
        for tol in [1e-4, 1e-8, 1e-12, 0.0] {
            for k in 0..100 {
                let u = (k as f64 + 0.5) / 100.0;
                for (name, r) in [
                    (
                        "brent",
                        brent.clone().with_tolerance(tol).unwrap().invert(u),
                    ),
                    (
                        "newton",
                        newton.clone().with_tolerance(tol).unwrap().invert(u),
                    ),
                ] {
                    let r = r.unwrap();
                    assert!(
                        r.u_error <= tol.max(2.0 * f64::EPSILON),
                        "{name} tol {tol} u {u}: {r:?}"
                    );
                    assert!((cdf(r.x) - u).abs() == r.u_error, "{name}: reported error");
                    assert!((0.0..=2.0).contains(&r.x));
                }
            }
        }
    }

    #[test]
    fn a_flat_cdf_and_a_jump_stay_in_the_bracket() {
        // F jumps from 0.25 to 0.75 at x = 1: u = 0.5 cannot be met; the bracket closes on 1.
        let step = |x: f64| {
            if x < 1.0 {
                0.25 * x
            } else {
                0.75 + 0.25 * (x - 1.0)
            }
        };
        let inv = NumericInverse::new(step, 0.0, 2.0).unwrap();
        let r = inv.invert(0.5).unwrap();
        assert!((r.x - 1.0).abs() <= 1e-15, "{r:?}");
        assert!((r.u_error - 0.25).abs() < 1e-12, "{r:?}");
        let newton = NumericInverse::with_density(step, |_| 0.25, 0.0, 2.0).unwrap();
        let r = newton.invert(0.5).unwrap();
        assert!((r.x - 1.0).abs() <= 1e-15, "{r:?}");
    }

    #[test]
    fn bad_queries_and_bad_cdfs_are_errors() {
        let inv = NumericInverse::new(cdf, 0.0, 2.0).unwrap();
        assert!(matches!(
            inv.invert(1.5),
            Err(SamplingError::OutsideRange { .. })
        ));
        assert!(matches!(
            inv.invert(f64::NAN),
            Err(SamplingError::OutsideRange { .. })
        ));
        assert!(matches!(
            NumericInverse::new(cdf, 2.0, 0.0),
            Err(SamplingError::BadInterval { .. })
        ));
        let nan_inside = |x: f64| {
            if (0.9..1.1).contains(&x) {
                f64::NAN
            } else {
                x / 2.0
            }
        };
        let inv = NumericInverse::new(nan_inside, 0.0, 2.0).unwrap();
        assert!(matches!(
            inv.invert(0.5),
            Err(SamplingError::BadCdfValue { .. })
        ));
        assert!(matches!(
            NumericInverse::new(cdf, 0.0, 2.0)
                .unwrap()
                .with_tolerance(-1.0),
            Err(SamplingError::BadTolerance(_))
        ));
    }
}
