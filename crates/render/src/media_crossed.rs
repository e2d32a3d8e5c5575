//! What a ray records of the participating media it crosses: whether a medium scatters it or lets
//! it through ([`MediumMode`]), and the stretches it passed through, from which the optical depth
//! `tau = sum_i sigma_i l_i` and the transmittance `exp(-tau)` of constant media follow
//! ([`MediaCrossed`]).

/// What a constant medium does to a ray that crosses it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum MediumMode {
    /// Scatter at an exponentially distributed distance (book 2): the path's own rays.
    #[default]
    Scatter,
    /// Pass through, recording the stretch inside in [`Ctx::crossed`](crate::sampler::Ctx::crossed): a shadow ray.
    Record,
}

/// The stretches `(t0, t1, density)` of media a shadow ray passed through, in the order they were
/// tested; stretches beyond the ray's surface are clipped when the optical depth is taken.
#[derive(Clone, Copy, Debug, Default)]
pub struct MediaCrossed {
    stretches: [(f64, f64, f64); MediaCrossed::CAPACITY],
    /// The phase function (material index) of each recorded stretch's medium.
    phases: [u32; MediaCrossed::CAPACITY],
    len: usize,
    /// The optical depth of the stretches that did not fit, unclipped.
    spill: f64,
    /// More stretches than fit: the optical depth is then found by a second traversal whose range
    /// ends at the surface (so every stretch, spilled or not, is already clipped).
    pub overflow: bool,
}

impl MediaCrossed {
    /// Stretches held without allocating.
    pub const CAPACITY: usize = 8;

    /// Forget every stretch.
    #[inline]
    pub fn clear(&mut self) {
        self.len = 0;
        self.spill = 0.0;
        self.overflow = false;
    }

    /// Record the stretch `t0..t1` (ray parameter) of a medium of `density` per unit length of the
    /// ray's direction (`density * |direction|`).
    #[inline]
    pub fn push(&mut self, t0: f64, t1: f64, density: f64) {
        if self.len < Self::CAPACITY {
            self.stretches[self.len] = (t0, t1, density);
            self.len += 1;
        } else {
            self.spill += (t1 - t0).max(0.0) * density;
            self.overflow = true;
        }
    }

    /// [`MediaCrossed::push`] for a medium whose phase function is material `phase`.
    #[inline]
    pub fn push_medium(&mut self, t0: f64, t1: f64, density: f64, phase: u32) {
        if self.len < Self::CAPACITY {
            self.phases[self.len] = phase;
        }
        self.push(t0, t1, density);
    }

    /// How many stretches are recorded (not counting the spilled ones).
    #[inline]
    pub fn len(&self) -> usize {
        self.len
    }

    /// No stretch recorded.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The recorded stretches `((t0, t1, density), phase)` (not the spilled ones).
    #[inline]
    pub fn stretches(&self) -> impl Iterator<Item = ((f64, f64, f64), u32)> + '_ {
        self.stretches[..self.len]
            .iter()
            .copied()
            .zip(self.phases[..self.len].iter().copied())
    }

    /// `sum_i density_i * |[t0_i, t1_i] clipped to t < t_max|` (the spilled stretches unclipped).
    #[inline]
    pub fn optical_depth(&self, t_max: f64) -> f64 {
        self.spill
            + self.stretches[..self.len]
                .iter()
                .map(|&(t0, t1, density)| (t1.min(t_max) - t0).max(0.0) * density)
                .sum::<f64>()
    }
}

#[cfg(test)]
mod tests {
    use super::MediaCrossed;

    #[test]
    fn media_crossed_clips_at_the_surface_and_spills_past_capacity() {
        let mut m = MediaCrossed::default();
        m.push(1.0, 3.0, 0.5);
        m.push(2.0, 10.0, 0.25);
        // clipped at t = 4: 2 * 0.5 + 2 * 0.25
        assert_eq!(m.optical_depth(4.0), 1.5);
        assert!(!m.overflow);
        for i in 0..MediaCrossed::CAPACITY {
            m.push(i as f64, i as f64 + 1.0, 1.0);
        }
        assert!(m.overflow);
        // the two that did not fit are counted whole
        assert_eq!(m.optical_depth(f64::INFINITY), 1.0 + 2.0 + 6.0 + 2.0);
        m.clear();
        assert_eq!((m.optical_depth(1e9), m.overflow), (0.0, false));
    }
}
