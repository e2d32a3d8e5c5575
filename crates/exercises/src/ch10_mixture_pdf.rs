//! # Chapter 10, Mixture Densities, "MixturePdf": a mixture pdf whose value is what it generates
//!
//! The checks of the exercise `crates/exercises/exercises/ch10_mixture_pdf.rs`, which states the
//! task, and what that exercise is given ([`Pdf`], [`CosinePdf`], [`ConePdf`]).
//!
//! The check: `value` equals w a + (1 - w) b at 1000 random directions (to rounding), for weights 0,
//! 0.3, 1; a part of weight 0 that is [`Undefined`] (its value NaN, its samples NaN) is neither
//! evaluated nor sampled, as the book's `MixturePdf` does; and, for the mixture of a cosine lobe
//! around +z and a narrow cone towards +z (like the book's cosine-plus-light mixture), a chi-square
//! test of 1e5 generated directions in 16 x 25 (phi, z) cells against `n` times the integral of the
//! mixture's own `value` over each cell: whatever `generate` samples, `value` must be its density.

use crate::check::{self, Arg, CheckResult, Generator, SphereBins};
use glam::DVec3;
use rand::{Rng, RngCore};
use std::f64::consts::{FRAC_1_PI, PI};

/// A density over directions (per steradian), with a sampler of it.
pub trait Pdf {
    /// The density of `direction` (unit) w.r.t. solid angle; never negative.
    fn value(&self, direction: DVec3) -> f64;
    /// A unit direction drawn with density [`Pdf::value`].
    fn generate(&self, rng: &mut dyn RngCore) -> DVec3;
}

/// The cosine density max(0, z) / pi around +z (given).
#[derive(Clone, Copy, Debug)]
pub struct CosinePdf;

impl Pdf for CosinePdf {
    fn value(&self, d: DVec3) -> f64 {
        d.z.max(0.0) * FRAC_1_PI
    }
    fn generate(&self, rng: &mut dyn RngCore) -> DVec3 {
        let (u1, u2): (f64, f64) = (rng.random(), rng.random());
        let phi = 2.0 * PI * u1;
        DVec3::new(
            phi.cos() * u2.sqrt(),
            phi.sin() * u2.sqrt(),
            (1.0 - u2).sqrt(),
        )
    }
}

/// The uniform density 1 / (2 pi (1 - cos_max)) on the cone z >= cos_max around +z (given), like
/// the directions towards a sphere light.
#[derive(Clone, Copy, Debug)]
pub struct ConePdf {
    pub cos_max: f64,
}

impl Pdf for ConePdf {
    fn value(&self, d: DVec3) -> f64 {
        if d.z >= self.cos_max {
            1.0 / (2.0 * PI * (1.0 - self.cos_max))
        } else {
            0.0
        }
    }
    fn generate(&self, rng: &mut dyn RngCore) -> DVec3 {
        let (u1, u2): (f64, f64) = (rng.random(), rng.random());
        let z = 1.0 - u2 * (1.0 - self.cos_max);
        let r = (1.0 - z * z).max(0.0).sqrt();
        let phi = 2.0 * PI * u1;
        DVec3::new(r * phi.cos(), r * phi.sin(), z)
    }
}

/// A part that is no density at all: its value is NaN everywhere and its samples are NaN. A part of
/// weight 0 may be anything (a list of lights with no light in it, say): the mixture must neither
/// evaluate nor sample it.
#[derive(Clone, Copy, Debug)]
pub struct Undefined;

impl Pdf for Undefined {
    fn value(&self, _: DVec3) -> f64 {
        f64::NAN
    }
    fn generate(&self, _: &mut dyn RngCore) -> DVec3 {
        DVec3::NAN
    }
}

/// The cone of the checks: z >= 0.84, a cell edge of the chi-square binning.
const CONE: ConePdf = ConePdf { cos_max: 0.84 };

/// `m.value(d)` of the mixture of weight `w`, recorded so that a panic report names them.
fn value(m: &impl Pdf, w: f64, d: DVec3) -> f64 {
    let args = [
        ("self.weight_a", Arg::Real(w)),
        ("direction", Arg::Vector(d)),
    ];
    check::calling("MixturePdf::value", &args, || m.value(d))
}

/// `m.generate(rng)` of the mixture of weight `w`, recorded so that a panic report names the weight
/// and how to replay the generator.
fn generate(m: &impl Pdf, w: f64, rng: &mut Generator) -> DVec3 {
    let args = [("self.weight_a", Arg::Real(w)), ("rng", rng.arg())];
    check::calling("MixturePdf::generate", &args, || m.generate(rng))
}

/// `value` equals the weighted sum of the parts' values at 1000 random directions.
pub fn check_value<P: Pdf>(mix: impl Fn(CosinePdf, ConePdf, f64) -> P) -> CheckResult {
    let mut rng = check::seeded(100);
    for w in [0.0, 0.3, 1.0] {
        let m = mix(CosinePdf, CONE, w);
        for k in 0..1000 {
            // Half the directions inside the cone, where both parts are positive.
            let d = if k % 2 == 0 {
                check::uniform_direction(&mut rng)
            } else {
                CONE.generate(&mut rng)
            };
            let want = w * CosinePdf.value(d) + (1.0 - w) * CONE.value(d);
            let got = value(&m, w, d);
            if (got.is_nan() || got < 0.0) || (got - want).abs() > 1e-14 * want.max(1.0) {
                return Err(format!(
                    "MixturePdf(weight {w}).value({d}) = {}, expected {}",
                    check::num(got),
                    check::num(want)
                ));
            }
        }
    }
    Ok(())
}

/// A part of weight 0 that is [`Undefined`] is neither evaluated nor sampled: `weight_0_a` builds
/// the mixture of weight `w` = 0 of `Undefined` and a cone, `weight_1_b` the one of weight 1 of a
/// cosine lobe and `Undefined`. Their `value` must be the other part's, exactly, at 100 directions,
/// and `generate` must never return `Undefined`'s NaN in 1000 draws, the first of them with
/// u = 0 (weight 0) and u = 1 - 2^-53 (weight 1).
pub fn check_weight_zero<P: Pdf, Q: Pdf>(
    weight_0_a: impl Fn(Undefined, ConePdf, f64) -> P,
    weight_1_b: impl Fn(CosinePdf, Undefined, f64) -> Q,
) -> CheckResult {
    let zero_a = weight_0_a(Undefined, CONE, 0.0);
    let zero_b = weight_1_b(CosinePdf, Undefined, 1.0);
    let unused = |w: f64| if w == 0.0 { "a" } else { "b" };
    let mut rng = check::seeded(102);
    for k in 0..100 {
        let d = if k % 2 == 0 {
            check::uniform_direction(&mut rng)
        } else {
            CONE.generate(&mut rng)
        };
        for (w, got, want) in [
            (0.0, value(&zero_a, 0.0, d), CONE.value(d)),
            (1.0, value(&zero_b, 1.0, d), CosinePdf.value(d)),
        ] {
            if got != want {
                return Err(format!(
                    "MixturePdf(weight_a {w}).value({d}) = {}, expected {}: part {}, of weight 0, \
                     has no number for a value there (NaN), and a part of weight 0 may be \
                     anything; it must not change the mixture's value",
                    check::num(got),
                    check::num(want),
                    unused(w)
                ));
            }
        }
    }
    for (w, u) in [(0.0, 0.0), (1.0, check::U_MAX)] {
        let mut rng = Generator::scripted(&[u], 103);
        for k in 0..1000 {
            let d = if w == 0.0 {
                generate(&zero_a, w, &mut rng)
            } else {
                generate(&zero_b, w, &mut rng)
            };
            if d.is_nan() {
                return Err(format!(
                    "MixturePdf(weight_a {w}).generate() returned {d} (call {} of 1000, the first \
                     with u = {}): it sampled part {}, whose weight is 0",
                    k + 1,
                    check::num(u),
                    unused(w)
                ));
            }
        }
    }
    Ok(())
}

/// Chi-square: 1e5 generated directions against the mixture's own `value`, for weights 0.3 and 0.
pub fn check_generate<P: Pdf>(mix: impl Fn(CosinePdf, ConePdf, f64) -> P) -> CheckResult {
    // 25 rings of z: the cone's edge 0.84 is a ring edge; the horizon z = 0 lies inside a ring, where
    // the cosine lobe is continuous.
    let bins = SphereBins {
        n_phi: 16,
        n_z: 25,
        z_min: -1.0,
        z_max: 1.0,
        pole: "the normal",
    };
    let n = 100_000;
    let mut rng = Generator::new(101);
    for w in [0.3, 0.0] {
        let m = mix(CosinePdf, CONE, w);
        let mut dirs = Vec::with_capacity(n);
        for _ in 0..n {
            let d = generate(&m, w, &mut rng);
            check::unit(&format!("MixturePdf(weight {w}).generate()"), d)?;
            dirs.push(d);
        }
        let what = format!("MixturePdf(weight {w}): generate against value");
        let observed = bins.histogram(&what, dirs)?;
        // The support, decided analytically: the cosine lobe covers z > 0, the cone z >= 0.84.
        let support =
            |_z_lo: f64, z_hi: f64| (w > 0.0 && z_hi > 0.0) || (w < 1.0 && z_hi > CONE.cos_max);
        let expected = bins.expected(n, |d| value(&m, w, d), support, 16);
        check::chi_square(&what, &observed, &expected, &bins)?;
    }
    Ok(())
}

/// All of this exercise's checks.
pub fn check_mixture<P: Pdf>(mix: impl Fn(CosinePdf, ConePdf, f64) -> P) -> CheckResult {
    check_value(&mix)?;
    check_generate(&mix)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A mixture that samples with one weight and values with another.
    struct Inconsistent {
        sample_weight: f64,
        value_weight: f64,
    }

    impl Pdf for Inconsistent {
        fn value(&self, d: DVec3) -> f64 {
            self.value_weight * CosinePdf.value(d) + (1.0 - self.value_weight) * CONE.value(d)
        }
        fn generate(&self, rng: &mut dyn RngCore) -> DVec3 {
            if rng.random::<f64>() < self.sample_weight {
                CosinePdf.generate(rng)
            } else {
                CONE.generate(rng)
            }
        }
    }

    #[test]
    fn checks_accept_a_consistent_mixture_of_the_given_parts() {
        let consistent = |_: CosinePdf, _: ConePdf, w: f64| Inconsistent {
            sample_weight: w,
            value_weight: w,
        };
        check_mixture(consistent).unwrap();
    }

    /// The mixture of the given parts `a`, `b`: the weighted sum of both values whatever the
    /// weights (`sum`), or leaving out a part of weight 0; sampling `a` when u < w, or when u <= w
    /// (`or_equal`).
    struct Mix<A, B> {
        a: A,
        b: B,
        w: f64,
        sum: bool,
        or_equal: bool,
    }

    impl<A: Pdf, B: Pdf> Pdf for Mix<A, B> {
        fn value(&self, d: DVec3) -> f64 {
            if self.sum || (self.w > 0.0 && self.w < 1.0) {
                self.w * self.a.value(d) + (1.0 - self.w) * self.b.value(d)
            } else if self.w == 0.0 {
                self.b.value(d)
            } else {
                self.a.value(d)
            }
        }
        fn generate(&self, rng: &mut dyn RngCore) -> DVec3 {
            let u = rng.random::<f64>();
            if u < self.w || (self.or_equal && u == self.w) {
                self.a.generate(rng)
            } else {
                self.b.generate(rng)
            }
        }
    }

    fn check_mix(sum: bool, or_equal: bool) -> CheckResult {
        check_weight_zero(
            |a, b, w| Mix {
                a,
                b,
                w,
                sum,
                or_equal,
            },
            |a, b, w| Mix {
                a,
                b,
                w,
                sum,
                or_equal,
            },
        )
    }

    #[test]
    fn a_part_of_weight_0_must_be_neither_evaluated_nor_sampled() {
        check_mix(false, false).unwrap();
        // Wrong: w a(d) + (1 - w) b(d) for every weight: 0 times NaN is NaN.
        let err = check_mix(true, false).unwrap_err();
        assert!(
            err.starts_with("MixturePdf(weight_a 0).value(") && err.contains(") = NaN, expected "),
            "{err}"
        );
        assert!(err.contains("part a, of weight 0"), "{err}");
        // Wrong: u <= w samples part a at u = 0 with weight 0.
        let err = check_mix(false, true).unwrap_err();
        assert!(
            err.starts_with(
                "MixturePdf(weight_a 0).generate() returned [NaN, NaN, NaN] (call 1 of 1000, the \
                 first with u = 0): it sampled part a, whose weight is 0"
            ),
            "{err}"
        );
        // Only this check sees them: with parts that are numbers, the sum is right.
        let wrong = |a: CosinePdf, b: ConePdf, w| Mix {
            a,
            b,
            w,
            sum: true,
            or_equal: true,
        };
        // (generate differs only where u equals the weight, 2^-53 of the draws.)
        assert!(check_value(wrong).is_ok());
    }

    #[test]
    fn checks_reject_a_mixture_whose_value_is_not_what_it_samples() {
        // Wrong: picks a with probability 1 - w (weights swapped in generate).
        let swapped = |_: CosinePdf, _: ConePdf, w: f64| Inconsistent {
            sample_weight: 1.0 - w,
            value_weight: w,
        };
        assert!(check_value(swapped).is_ok(), "value alone is right");
        let err = check_generate(swapped).unwrap_err();
        // Weight 0.3 samples the cone 30% of the time instead of 70%: too few in the cone
        // (z >= 0.84), too many in the cosine lobe outside it.
        assert!(
            err.contains("\ntoo few at cos theta in [0.84, 0.92]: ")
                && err.contains("\ntoo many at cos theta in [0.76, 0.84]: "),
            "{err}"
        );
        // Wrong: the book's 50/50 value whatever the weight.
        let half = |_: CosinePdf, _: ConePdf, w: f64| Inconsistent {
            sample_weight: w,
            value_weight: 0.5,
        };
        assert!(check_value(half).is_err());
        assert!(check_generate(half).is_err());
    }

    /// Right, but panics where it samples the cone at its edge (z < 0.8404), and where its value is
    /// asked below the horizon.
    struct PanicsAtTheEdge(f64);
    impl Pdf for PanicsAtTheEdge {
        fn value(&self, d: DVec3) -> f64 {
            assert!(d.z >= 0.0, "below the horizon");
            self.0 * CosinePdf.value(d) + (1.0 - self.0) * CONE.value(d)
        }
        fn generate(&self, rng: &mut dyn RngCore) -> DVec3 {
            if rng.random::<f64>() < self.0 {
                return CosinePdf.generate(rng);
            }
            let d = CONE.generate(rng);
            assert!(d.z >= 0.8404, "at the edge of the cone");
            d
        }
    }

    #[test]
    fn a_panic_names_the_weight_and_how_to_replay_the_generator() {
        let report = crate::harness::panic_of(|| {
            check_generate(|_: CosinePdf, _: ConePdf, w: f64| PanicsAtTheEdge(w))
        });
        // "... generate(self.weight_a = 0.3, rng = rtl_exercises::check::replay(101, K)), which
        // drew u = U1, U2, U3, at ...": the generator replayed from K draws the same three values,
        // and generate panics on them.
        let (head, _) = report.split_once(", at ").expect(&report);
        let rest = head
            .strip_prefix(
                "your code panicked in MixturePdf::generate(self.weight_a = 0.3, rng = \
                 rtl_exercises::check::replay(101, ",
            )
            .expect(&report);
        let (skip, drew) = rest.split_once(")), which drew u = ").expect(&report);
        let mut replayed = check::replay(101, skip.parse().unwrap());
        let u: Vec<String> = (0..3).map(|_| check::num(replayed.random())).collect();
        assert_eq!(drew, u.join(", "), "{report}");
        let again = std::panic::catch_unwind(|| {
            PanicsAtTheEdge(0.3).generate(&mut check::replay(101, skip.parse().unwrap()))
        });
        assert!(again.is_err());
        // Its value panics below the horizon, where half the directions of check_value lie.
        let report = crate::harness::panic_of(|| {
            check_value(|_: CosinePdf, _: ConePdf, w: f64| PanicsAtTheEdge(w))
        });
        assert!(
            report.starts_with(
                "your code panicked in MixturePdf::value(self.weight_a = 0, direction = ["
            ),
            "{report}"
        );
    }
}
