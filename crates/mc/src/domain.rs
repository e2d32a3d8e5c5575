//! The domains we integrate over: an interval `[a, b]` and a rectangle `[a, b] x [c, d]`.

use crate::McError;

/// A closed interval `[a, b]` with finite `a < b`: the domain of a one-dimensional integral.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Interval {
    a: f64,
    b: f64,
}

impl Interval {
    /// `[a, b]`, or [`McError::EmptyInterval`] unless `a < b` and both are finite, or
    /// [`McError::IntervalTooWide`] if `b - a` overflows (`[-1e308, 1e308]`).
    ///
    /// ```
    /// use rtl_mc::Interval;
    /// assert_eq!(Interval::new(0.0, 2.0).unwrap().length(), 2.0);
    /// assert!(Interval::new(1.0, 1.0).is_err());
    /// assert!(Interval::new(-1e308, 1e308).is_err());
    /// ```
    pub fn new(a: f64, b: f64) -> Result<Self, McError> {
        if !(a.is_finite() && b.is_finite() && a < b) {
            Err(McError::EmptyInterval { a, b })
        } else if !(b - a).is_finite() {
            Err(McError::IntervalTooWide { a, b })
        } else {
            Ok(Self { a, b })
        }
    }

    /// The lower end `a`.
    pub fn start(&self) -> f64 {
        self.a
    }

    /// The upper end `b`.
    pub fn end(&self) -> f64 {
        self.b
    }

    /// `b - a`: the measure of the interval, and the constant `1 / p` of uniform sampling on it.
    pub fn length(&self) -> f64 {
        self.b - self.a
    }

    /// The point a fraction `t` of the way from `a` to `b`: maps `[0, 1)` onto `[a, b)`.
    #[inline]
    pub fn lerp(&self, t: f64) -> f64 {
        self.a + (self.b - self.a) * t
    }
}

/// A rectangle `x in [a, b]`, `y in [c, d]`: the domain of a two-dimensional integral.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rect {
    pub x: Interval,
    pub y: Interval,
}

impl Rect {
    /// The rectangle `[a, b] x [c, d]`, or [`McError::EmptyInterval`] naming the bad side, or
    /// [`McError::AreaTooLarge`] if its area overflows.
    pub fn new(a: f64, b: f64, c: f64, d: f64) -> Result<Self, McError> {
        let r = Self {
            x: Interval::new(a, b)?,
            y: Interval::new(c, d)?,
        };
        r.checked_area()?;
        Ok(r)
    }

    /// Its area, or [`McError::AreaTooLarge`] (the sides are public, so a `Rect` built by hand is
    /// checked here, where the estimators ask for it).
    pub fn checked_area(&self) -> Result<f64, McError> {
        let area = self.area();
        if area.is_finite() {
            Ok(area)
        } else {
            Err(McError::AreaTooLarge {
                width: self.x.length(),
                height: self.y.length(),
            })
        }
    }

    /// Its area `(b - a)(d - c)`.
    pub fn area(&self) -> f64 {
        self.x.length() * self.y.length()
    }

    /// The point at fractions `(s, t)` across the rectangle.
    #[inline]
    pub fn lerp(&self, s: f64, t: f64) -> [f64; 2] {
        [self.x.lerp(s), self.y.lerp(t)]
    }
}
