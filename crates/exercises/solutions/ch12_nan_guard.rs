//! Reference solution of `exercises/ch12_nan_guard.rs`, compiled only with `--features solutions`: try the
//! exercise first (`cargo exercises solution ch12_nan_guard` shows it once your code passes).

use glam::DVec3;

#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PixelAccumulator {
    pub mean: DVec3,
    pub used: u64,
    pub dropped: u64,
}

impl PixelAccumulator {
    pub fn new() -> Self {
        Self::default()
    }

    pub fn add(&mut self, sample: DVec3) {
        if !sample.is_finite() {
            self.dropped += 1;
            return;
        }
        self.used += 1;
        self.mean += (sample - self.mean) / self.used as f64;
    }

    pub fn mean(&self) -> Option<DVec3> {
        (self.used > 0).then_some(self.mean)
    }
}
