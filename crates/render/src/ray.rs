//! Rays `P(t) = origin + t direction` at a moment `time` of the shutter, and intervals of `t`.

use crate::vec::{Point3, Vec3};

/// A ray with the time at which it was cast (for motion blur).
#[derive(Clone, Copy, Debug)]
pub struct Ray {
    pub origin: Point3,
    pub direction: Vec3,
    pub time: f64,
}

impl Ray {
    #[inline]
    pub fn new(origin: Point3, direction: Vec3, time: f64) -> Self {
        Ray {
            origin,
            direction,
            time,
        }
    }

    /// The point at parameter `t`.
    #[inline]
    pub fn at(&self, t: f64) -> Point3 {
        self.origin + t * self.direction
    }
}

/// A real interval `[min, max]` (empty when `min > max`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interval {
    pub min: f64,
    pub max: f64,
}

impl Interval {
    pub const EMPTY: Interval = Interval {
        min: f64::INFINITY,
        max: f64::NEG_INFINITY,
    };
    pub const UNIVERSE: Interval = Interval {
        min: f64::NEG_INFINITY,
        max: f64::INFINITY,
    };
    /// Every positive parameter: where a ray spawned at a robustly offset origin may hit.
    pub const FORWARD: Interval = Interval {
        min: 0.0,
        max: f64::INFINITY,
    };

    #[inline]
    pub const fn new(min: f64, max: f64) -> Self {
        Interval { min, max }
    }

    /// `min <= x <= max`.
    #[inline]
    pub fn contains(&self, x: f64) -> bool {
        self.min <= x && x <= self.max
    }

    /// `min < x < max`: where a hit counts (a hit exactly at the origin does not).
    #[inline]
    pub fn surrounds(&self, x: f64) -> bool {
        self.min < x && x < self.max
    }

    pub fn size(&self) -> f64 {
        self.max - self.min
    }
}
