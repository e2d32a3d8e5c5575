//! Reference solution of `exercises/ch12_bug_light_list_pdf.rs`, compiled only with `--features solutions`: try the
//! exercise first (`cargo exercises solution ch12_bug_light_list_pdf` shows it once your code passes).

use glam::DVec3;
use rand::{Rng, RngCore};
use rtl_exercises::ch12_bug_light_list_pdf::{ConeLight, Light};

pub struct LightList {
    pub lights: Vec<ConeLight>,
}

impl Light for LightList {
    /// The bug: without this, the trait's default 0 is the list's density. Choosing light i with
    /// probability 1/n and then sampling it gives the density (1/n) sum_i p_i(d).
    fn pdf_value(&self, direction: DVec3) -> f64 {
        let sum: f64 = self.lights.iter().map(|l| l.pdf_value(direction)).sum();
        sum / self.lights.len() as f64
    }

    fn random(&self, rng: &mut dyn RngCore) -> DVec3 {
        let i = rng.random_range(0..self.lights.len());
        self.lights[i].random(rng)
    }
}
