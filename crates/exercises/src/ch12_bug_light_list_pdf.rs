//! # Bug museum, chapter 12, after chapter 9, Sampling Lights Directly, "Several lights": the black image of a light list without `pdf_value`
//!
//! The checks of the exercise `crates/exercises/exercises/ch12_bug_light_list_pdf.rs`, which holds the
//! bug to find.
//!
//! The setting, in a few lines: two spherical lights seen from the origin, each a cone of directions
//! ([`ConeLight`], given), and a list of them that samples one at random. Like the book's `hittable`,
//! the trait [`Light`] has a default `pdf_value` of 0.
//!
//! The check: `pdf_value` is positive at every direction `random` generates (1000 of them) and
//! integrates to 1 over the sphere (z-test of 1e5 uniform directions); and the estimate of the lights'
//! total solid angle, the average of 1 / pdf_value over 1e5 generated directions, z-tested against the
//! exact sum of the two cones (false failure 1e-6). An estimator that skips samples of density 0 (as it
//! must, to avoid NaN) estimates 0 there: the black image. Then two lights whose cones overlap: a
//! direction in both can be drawn through either, so its density is exactly (p_1 + p_2) / 2, and one
//! in the first alone p_1 / 2; and that list's `pdf_value` integrates to 1 as well. (With disjoint
//! cones only, the density of "the light the direction points at" divided by 2 would pass.)

use crate::check::{self, CheckResult, Generator};
use glam::DVec3;
use rand::{Rng, RngCore};
use std::f64::consts::PI;

/// A light as the integrator samples it from the origin.
pub trait Light {
    /// The density, per steradian, with which [`Light::random`] draws `direction`. The default is
    /// the book's `hittable::pdf_value`: 0, "not a light".
    fn pdf_value(&self, direction: DVec3) -> f64 {
        let _ = direction;
        0.0
    }
    /// A unit direction towards the light.
    fn random(&self, rng: &mut dyn RngCore) -> DVec3;
}

/// A sphere light seen from the origin: the cone of directions within `cos_max` of `axis` (unit),
/// sampled uniformly (given).
#[derive(Clone, Copy, Debug)]
pub struct ConeLight {
    pub axis: DVec3,
    pub cos_max: f64,
}

impl ConeLight {
    /// The cone's solid angle 2 pi (1 - cos_max).
    pub fn solid_angle(&self) -> f64 {
        2.0 * PI * (1.0 - self.cos_max)
    }
}

impl Light for ConeLight {
    fn pdf_value(&self, d: DVec3) -> f64 {
        if d.dot(self.axis) >= self.cos_max {
            1.0 / self.solid_angle()
        } else {
            0.0
        }
    }
    fn random(&self, rng: &mut dyn RngCore) -> DVec3 {
        let z = 1.0 - rng.random::<f64>() * (1.0 - self.cos_max);
        let r = (1.0 - z * z).max(0.0).sqrt();
        let phi = 2.0 * PI * rng.random::<f64>();
        let w = self.axis;
        let a = if w.x.abs() > 0.9 { DVec3::Y } else { DVec3::X };
        let v = w.cross(a).normalize();
        let u = v.cross(w);
        r * phi.cos() * u + r * phi.sin() * v + z * w
    }
}

/// The two lights of the checks: disjoint cones of different sizes.
pub fn lights() -> [ConeLight; 2] {
    [
        ConeLight {
            axis: DVec3::new(0.0, 0.6, 0.8),
            cos_max: 0.95,
        },
        ConeLight {
            axis: DVec3::new(0.0, -0.8, 0.6),
            cos_max: 0.99,
        },
    ]
}

/// `list.pdf_value(d)`, recorded so that a panic report names `d`.
fn pdf_value(list: &dyn Light, d: DVec3) -> f64 {
    check::calling("LightList::pdf_value", &[("direction", d.into())], || {
        list.pdf_value(d)
    })
}

/// `list.random(rng)`, recorded so that a panic report says how to replay the generator.
fn random(list: &dyn Light, rng: &mut Generator) -> DVec3 {
    let args = [("rng", rng.arg())];
    check::calling("LightList::random", &args, || list.random(rng))
}

/// `pdf_value` is positive where `random` lands, and integrates to 1.
pub fn check_pdf_value(list: &dyn Light) -> CheckResult {
    let mut rng = Generator::new(120);
    let zeros = (0..1000)
        .filter(|_| {
            let d = random(list, &mut rng);
            pdf_value(list, d) <= 0.0
        })
        .count();
    if zeros > 0 {
        return Err(format!(
            "pdf_value is 0 at {zeros} of 1000 directions that random() generated: a density must be \
             positive wherever its sampler lands; an integrator that skips samples of density 0 gets \
             nothing from them (the black image), one that divides gets infinity or NaN"
        ));
    }
    let values =
        (0..100_000).map(|_| 4.0 * PI * pdf_value(list, check::uniform_direction(&mut rng)));
    check::z_test_mean("pdf_value integrated over the sphere", values, 1.0)
}

/// The lights' total solid angle, estimated as the mean of 1 / pdf_value over generated directions.
pub fn check_estimate(list: &dyn Light) -> CheckResult {
    let exact: f64 = lights().iter().map(ConeLight::solid_angle).sum();
    let mut rng = Generator::new(121);
    let values = (0..100_000).map(|_| {
        let d = random(list, &mut rng);
        let p = pdf_value(list, d);
        if p > 0.0 { 1.0 / p } else { 0.0 }
    });
    check::z_test_mean(
        "the estimate of the lights' solid angle, mean of 1 / pdf_value",
        values,
        exact,
    )
}

/// Two lights whose cones overlap: each cone holds the other's axis.
pub fn overlapping_lights() -> [ConeLight; 2] {
    [
        ConeLight {
            axis: DVec3::new(0.0, 0.6, 0.8),
            cos_max: 0.95,
        },
        ConeLight {
            axis: DVec3::new(0.0, 0.8, 0.6),
            cos_max: 0.9,
        },
    ]
}

/// For [`overlapping_lights`]: exactly (p_1 + p_2) / 2 where the cones overlap, p_1 / 2 where only the
/// first holds the direction, 0 outside both; and the density integrates to 1 (z-test of 1e5 uniform
/// directions).
pub fn check_overlapping(list: &dyn Light) -> CheckResult {
    let [a, b] = overlapping_lights();
    // The first light's axis, in both cones; and the first axis turned 15 degrees away from the
    // second, in the first cone only.
    let turn = 15f64.to_radians();
    let first_only = DVec3::new(
        0.0,
        0.6 * turn.cos() - 0.8 * turn.sin(),
        0.8 * turn.cos() + 0.6 * turn.sin(),
    );
    let cases = [
        (
            a.axis,
            "in both cones",
            (a.pdf_value(a.axis) + b.pdf_value(a.axis)) / 2.0,
            "random() draws it through either light",
        ),
        (
            first_only,
            "in the first cone only",
            a.pdf_value(first_only) / 2.0,
            "random() draws it only when it chooses the first light",
        ),
        (-a.axis, "in neither cone", 0.0, "random() never draws it"),
    ];
    for (d, where_, want, how) in cases {
        let got = pdf_value(list, d);
        if (got - want).abs() > 1e-12 * want.max(1e-300) || got.is_nan() {
            return Err(format!(
                "with two lights whose cones overlap, pdf_value({d}) ({where_}) = {}, expected {}: \
                 {how}, and the density must count every way it can come out of random() with \
                 the probability of each",
                check::num(got),
                check::num(want)
            ));
        }
    }
    let mut rng = check::seeded(122);
    let values =
        (0..100_000).map(|_| 4.0 * PI * pdf_value(list, check::uniform_direction(&mut rng)));
    check::z_test_mean(
        "pdf_value of two overlapping lights, integrated over the sphere",
        values,
        1.0,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    struct NoPdf([ConeLight; 2]);
    impl Light for NoPdf {
        fn random(&self, rng: &mut dyn RngCore) -> DVec3 {
            self.0[rng.random_range(0..2)].random(rng)
        }
    }

    /// Wrong in another way: the sum of the values, not their average.
    struct Sum([ConeLight; 2]);
    impl Light for Sum {
        fn pdf_value(&self, d: DVec3) -> f64 {
            self.0.iter().map(|l| l.pdf_value(d)).sum()
        }
        fn random(&self, rng: &mut dyn RngCore) -> DVec3 {
            self.0[rng.random_range(0..2)].random(rng)
        }
    }

    /// Wrong: the density of the first light whose cone holds the direction, divided by the
    /// number of lights. Right for disjoint cones only.
    struct FirstHit(Vec<ConeLight>);
    impl Light for FirstHit {
        fn pdf_value(&self, d: DVec3) -> f64 {
            self.0
                .iter()
                .map(|l| l.pdf_value(d))
                .find(|&p| p > 0.0)
                .unwrap_or(0.0)
                / self.0.len() as f64
        }
        fn random(&self, rng: &mut dyn RngCore) -> DVec3 {
            self.0[rng.random_range(0..self.0.len())].random(rng)
        }
    }

    /// Right: the average of the lights' densities.
    struct Average(Vec<ConeLight>);
    impl Light for Average {
        fn pdf_value(&self, d: DVec3) -> f64 {
            self.0.iter().map(|l| l.pdf_value(d)).sum::<f64>() / self.0.len() as f64
        }
        fn random(&self, rng: &mut dyn RngCore) -> DVec3 {
            self.0[rng.random_range(0..self.0.len())].random(rng)
        }
    }

    #[test]
    fn checks_reject_the_density_of_only_the_light_a_direction_points_at() {
        let disjoint = FirstHit(lights().to_vec());
        assert!(
            check_pdf_value(&disjoint).is_ok(),
            "disjoint cones cannot tell"
        );
        let err = check_overlapping(&FirstHit(overlapping_lights().to_vec())).unwrap_err();
        assert!(
            err.contains("(in both cones)")
                && err.contains("random() draws it through either light"),
            "{err}"
        );
        assert!(
            !err.contains("p_1") && !err.contains("average"),
            "no formula: {err}"
        );
        check_overlapping(&Average(overlapping_lights().to_vec())).unwrap();
    }

    #[test]
    fn checks_reject_the_default_pdf_value_and_a_sum() {
        let err = check_pdf_value(&NoPdf(lights())).unwrap_err();
        assert!(err.contains("black image"), "{err}");
        assert!(check_estimate(&NoPdf(lights())).is_err());
        assert!(check_pdf_value(&Sum(lights())).is_err());
        assert!(check_estimate(&Sum(lights())).is_err());
        assert!(check_overlapping(&NoPdf(overlapping_lights())).is_err());
    }

    /// Panics when it draws the second light, and where its density is asked outside both cones.
    struct Panics([ConeLight; 2]);
    impl Light for Panics {
        fn pdf_value(&self, d: DVec3) -> f64 {
            assert!(
                self.0.iter().any(|l| l.pdf_value(d) > 0.0),
                "outside both cones"
            );
            Average(self.0.to_vec()).pdf_value(d)
        }
        fn random(&self, rng: &mut dyn RngCore) -> DVec3 {
            let i = rng.random_range(0..2);
            assert!(i == 0, "the second light");
            self.0[i].random(rng)
        }
    }

    #[test]
    fn a_panic_names_the_direction_or_how_to_replay_the_generator() {
        let report = crate::harness::panic_of(|| check_estimate(&Panics(lights())));
        // The first call that draws the second light: the calls before it drew the first light
        // (a draw to choose, two for the direction).
        let mut rng = check::seeded(121);
        let mut skip = 0;
        while rng.random_range(0..2) == 0 {
            lights()[0].random(&mut rng);
            skip += 3;
        }
        let rng = if skip == 0 {
            "seeded(121)".to_string()
        } else {
            format!("replay(121, {skip})")
        };
        assert!(
            report.starts_with(&format!(
                "your code panicked in LightList::random(rng = rtl_exercises::check::{rng}), which \
                 drew u = "
            )),
            "{report}"
        );
        let report = crate::harness::panic_of(|| check_pdf_value(&Panics(lights())));
        assert!(
            report.starts_with("your code panicked in LightList::random(rng = "),
            "{report}"
        );
        let report = crate::harness::panic_of(|| check_overlapping(&Panics(overlapping_lights())));
        assert!(
            report.starts_with(
                "your code panicked in LightList::pdf_value(direction = [-0, -0.6, -0.8]) at "
            ),
            "{report}"
        );
    }
}
