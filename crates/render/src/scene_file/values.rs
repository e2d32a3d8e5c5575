//! The value types of a scene file, each read by its own serde visitor so that a bad value is reported
//! at its own position: finite numbers, 3-vectors, colours that may name a texture, aspect ratios,
//! backgrounds and transform steps.

use crate::limits::{ASPECT_RANGE, MAX_MAGNITUDE};
use crate::scene::Transform;
use crate::vec::{Color, Vec3};
use glam::DMat3;
use serde::de::{self, Deserialize, Deserializer, SeqAccess, Visitor};
use std::fmt;

pub use crate::vec::Num;

/// A finite real number of magnitude at most [`MAX_MAGNITUDE`] (integers are accepted: `radius = 90`).
/// `nan`, `inf` and numbers such as `1e308`, whose squares and products would overflow, are refused.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Real(pub f64);

struct RealVisitor;

impl Visitor<'_> for RealVisitor {
    type Value = Real;
    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a finite number")
    }
    fn visit_f64<E: de::Error>(self, v: f64) -> Result<Real, E> {
        if !v.is_finite() {
            Err(E::custom(format!("{v} is not a finite number")))
        } else if v.abs() > MAX_MAGNITUDE {
            Err(E::custom(format!(
                "{v:e} is too large: numbers in a scene file may be at most {MAX_MAGNITUDE:e} in \
                 magnitude"
            )))
        } else {
            Ok(Real(v))
        }
    }
    fn visit_i64<E: de::Error>(self, v: i64) -> Result<Real, E> {
        Ok(Real(v as f64))
    }
    fn visit_u64<E: de::Error>(self, v: u64) -> Result<Real, E> {
        Ok(Real(v as f64))
    }
}

impl<'de> Deserialize<'de> for Real {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_f64(RealVisitor)
    }
}

/// Read exactly three finite numbers from a sequence.
fn three<'de, A: SeqAccess<'de>>(mut seq: A, what: &str) -> Result<Vec3, A::Error> {
    let mut x = [0.0; 3];
    for (i, xi) in x.iter_mut().enumerate() {
        match seq.next_element::<Real>()? {
            Some(Real(v)) => *xi = v,
            None => {
                return Err(de::Error::custom(format!(
                    "expected {what} of 3 numbers, got {i}"
                )));
            }
        }
    }
    if seq.next_element::<de::IgnoredAny>()?.is_some() {
        return Err(de::Error::custom(format!(
            "expected {what} of 3 numbers, got more"
        )));
    }
    Ok(Vec3::from_array(x))
}

/// A point or vector `[x, y, z]` of finite numbers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct V3(pub Vec3);

impl<'de> Deserialize<'de> for V3 {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = V3;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a vector [x, y, z] of finite numbers")
            }
            fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<V3, A::Error> {
                three(seq, "a vector [x, y, z]").map(V3)
            }
        }
        d.deserialize_seq(V)
    }
}

/// A colour: `[r, g, b]`, or one number for a grey. Components must be finite and non-negative.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rgb(pub Color);

/// A reflectance or emission: a colour as [`Rgb`], or the name of a texture in `[textures]`.
#[derive(Clone, Debug, PartialEq)]
pub enum ColorSpec {
    Rgb(Color),
    Texture(String),
}

struct ColorVisitor {
    texture: bool,
}

impl ColorVisitor {
    fn checked<E: de::Error>(c: Color) -> Result<ColorSpec, E> {
        if c.min_element() < 0.0 {
            Err(E::custom(format!(
                "colour components must be non-negative, got {}",
                Num::v3(c)
            )))
        } else {
            Ok(ColorSpec::Rgb(c))
        }
    }
}

impl<'de> Visitor<'de> for ColorVisitor {
    type Value = ColorSpec;
    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        if self.texture {
            f.write_str("a colour [r, g, b], a grey level or the name of a texture")
        } else {
            f.write_str("a colour [r, g, b] or a grey level")
        }
    }
    fn visit_f64<E: de::Error>(self, v: f64) -> Result<ColorSpec, E> {
        let Real(v) = RealVisitor.visit_f64(v)?;
        Self::checked(Color::splat(v))
    }
    fn visit_i64<E: de::Error>(self, v: i64) -> Result<ColorSpec, E> {
        Self::checked(Color::splat(v as f64))
    }
    fn visit_u64<E: de::Error>(self, v: u64) -> Result<ColorSpec, E> {
        Self::checked(Color::splat(v as f64))
    }
    fn visit_str<E: de::Error>(self, v: &str) -> Result<ColorSpec, E> {
        if self.texture {
            Ok(ColorSpec::Texture(v.to_owned()))
        } else {
            Err(E::invalid_type(de::Unexpected::Str(v), &self))
        }
    }
    fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<ColorSpec, A::Error> {
        Self::checked(three(seq, "a colour [r, g, b]")?)
    }
}

impl<'de> Deserialize<'de> for ColorSpec {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(ColorVisitor { texture: true })
    }
}

impl<'de> Deserialize<'de> for Rgb {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        match d.deserialize_any(ColorVisitor { texture: false })? {
            ColorSpec::Rgb(c) => Ok(Rgb(c)),
            ColorSpec::Texture(_) => unreachable!("texture names are refused by the visitor"),
        }
    }
}

/// Width over height: a positive number (`1.5`) or a ratio string (`"16:9"`, `"16/9"`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aspect(pub f64);

impl<'de> Deserialize<'de> for Aspect {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl V {
            fn positive<E: de::Error>(v: f64) -> Result<Aspect, E> {
                let (lo, hi) = ASPECT_RANGE;
                if v.is_finite() && (lo..=hi).contains(&v) {
                    Ok(Aspect(v))
                } else {
                    Err(E::custom(format!(
                        "the aspect ratio (width over height) must lie in [1/{hi}, {hi}], got {v:e}"
                    )))
                }
            }
        }
        impl Visitor<'_> for V {
            type Value = Aspect;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a positive number or a ratio such as \"16:9\"")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Aspect, E> {
                Self::positive(v)
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Aspect, E> {
                Self::positive(v as f64)
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Aspect, E> {
                Self::positive(v as f64)
            }
            fn visit_str<E: de::Error>(self, s: &str) -> Result<Aspect, E> {
                let parsed = s.split_once([':', '/']).and_then(|(a, b)| {
                    Some((a.trim().parse::<f64>().ok()?, b.trim().parse::<f64>().ok()?))
                });
                match parsed {
                    Some((w, h)) if h > 0.0 => Self::positive(w / h),
                    _ => Err(E::invalid_value(de::Unexpected::Str(s), &self)),
                }
            }
        }
        d.deserialize_any(V)
    }
}

/// The background: `"sky"` (book 1's gradient) or a colour.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BackgroundSpec {
    Sky,
    Rgb(Color),
}

impl<'de> Deserialize<'de> for BackgroundSpec {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        match d.deserialize_any(ColorVisitor { texture: true })? {
            ColorSpec::Rgb(c) => Ok(BackgroundSpec::Rgb(c)),
            ColorSpec::Texture(s) if s == "sky" => Ok(BackgroundSpec::Sky),
            ColorSpec::Texture(s) => Err(de::Error::custom(format!(
                "unknown background \"{s}\": expected \"sky\" or a colour [r, g, b]"
            ))),
        }
    }
}

/// One step of an object's transform list; the steps apply in order (`[{ rotate_y = 15 },
/// { translate = [265, 0, 295] }]` rotates, then translates, as book 2's `translate(rotate_y(box))`).
#[derive(Clone, Copy, Debug, PartialEq, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Step {
    /// Rotation by this many degrees about +x.
    RotateX(Real),
    /// Rotation by this many degrees about +y: `x' = cos x + sin z`, `z' = -sin x + cos z`.
    RotateY(Real),
    /// Rotation by this many degrees about +z.
    RotateZ(Real),
    Translate(V3),
}

impl Step {
    pub fn transform(self) -> Transform {
        let rotation = |m: DMat3| Transform {
            rotation: m,
            translation: Vec3::ZERO,
        };
        match self {
            Step::RotateX(Real(d)) => rotation(DMat3::from_rotation_x(d.to_radians())),
            Step::RotateY(Real(d)) => Transform::rotate_y(d),
            Step::RotateZ(Real(d)) => rotation(DMat3::from_rotation_z(d.to_radians())),
            Step::Translate(V3(t)) => Transform::translate(t),
        }
    }
}

/// The transform of a list of steps, applied in order (identity for an empty list).
pub fn compose(steps: &[Step]) -> Transform {
    steps
        .iter()
        .map(|s| s.transform())
        .reduce(Transform::then)
        .unwrap_or(Transform::IDENTITY)
}
