//! The document of a scene file: the tables it may hold, one serde type per kind of texture, material,
//! object and importance target, and the helpers that take a typed table apart with its spans.

use super::span::{Fail, Span, Val, fail};
use super::values::{Aspect, BackgroundSpec, ColorSpec, Real, Rgb, Step, V3};
use serde::Deserialize;
use toml::Spanned;
use toml::de::{DeTable, DeValue, ValueDeserializer};

/// Deserialize a value, keeping the spans of its parts.
pub(super) fn de<'i, T: Deserialize<'i>>(v: Val<'i>) -> Result<T, Fail> {
    T::deserialize(ValueDeserializer::from(v)).map_err(Fail::from)
}

pub(super) fn de_table<'i, T: Deserialize<'i>>(t: DeTable<'i>, span: &Span) -> Result<T, Fail> {
    de(Spanned::new(span.clone(), DeValue::Table(t)))
}

/// A table with its `type` taken out: the type, its span, the rest of the table and the table's span.
pub(super) struct Typed<'i> {
    pub(super) kind: &'static str,
    pub(super) table: DeTable<'i>,
    pub(super) span: Span,
}

/// Take `type` out of the table `v`, which must be one of `kinds` (`what`: "object", "material", ...).
pub(super) fn typed<'i>(v: Val<'i>, what: &str, kinds: &[&'static str]) -> Result<Typed<'i>, Fail> {
    let span = v.span();
    let DeValue::Table(mut table) = v.into_inner() else {
        let article = if what.starts_with(['a', 'e', 'i', 'o', 'u']) {
            "an"
        } else {
            "a"
        };
        return fail(
            span,
            format!("expected a table with a `type` ({article} {what})"),
        );
    };
    let Some(ty) = table.remove("type") else {
        return fail(span, "missing field `type`");
    };
    let ty_span = ty.span();
    let Some(name) = ty.get_ref().as_str() else {
        return fail(
            ty_span,
            format!("`type` must be a string, one of: {}", kinds.join(", ")),
        );
    };
    match kinds.iter().find(|k| **k == name) {
        Some(kind) => Ok(Typed { kind, table, span }),
        None => fail(
            ty_span,
            format!(
                "unknown {what} type `{}`; known types: {}",
                crate::text::shown(name),
                kinds.join(", ")
            ),
        ),
    }
}

/// Remove `key` from `t`, with its span.
pub(super) fn take<'i>(t: &mut DeTable<'i>, key: &str) -> Option<Val<'i>> {
    t.remove(key)
}

/// The entries of a table in file order (toml's map is sorted by key).
pub(super) fn in_file_order<'i>(t: DeTable<'i>) -> Vec<(Spanned<String>, Val<'i>)> {
    let mut v: Vec<_> = t
        .into_iter()
        .map(|(k, v)| (Spanned::new(k.span(), k.into_inner().into_owned()), v))
        .collect();
    v.sort_by_key(|(k, _)| k.span().start);
    v
}

pub(super) const TOP_KEYS: &[&str] = &[
    "description",
    "lights",
    "render",
    "camera",
    "textures",
    "materials",
    "objects",
];
pub(super) const OBJECT_TYPES: &[&str] = &[
    "sphere",
    "moving_sphere",
    "quad",
    "box",
    "group",
    "instance",
    "medium",
];
pub(super) const MATERIAL_TYPES: &[&str] =
    &["lambertian", "metal", "dielectric", "light", "isotropic"];
pub(super) const TEXTURE_TYPES: &[&str] = &["solid", "checker", "marble", "image"];

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(super) struct RenderDoc {
    pub(super) width: Option<Spanned<u64>>,
    pub(super) aspect: Option<Aspect>,
    pub(super) spp: Option<Spanned<u64>>,
    pub(super) max_depth: Option<Spanned<u32>>,
    pub(super) background: Option<BackgroundSpec>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct CameraDoc {
    pub(super) vfov: Option<Spanned<Real>>,
    pub(super) lookfrom: Spanned<V3>,
    pub(super) lookat: Spanned<V3>,
    pub(super) vup: Option<Spanned<V3>>,
    pub(super) defocus_angle: Option<Spanned<Real>>,
    pub(super) focus_dist: Option<Spanned<Real>>,
    pub(super) shutter: Option<Spanned<[Real; 2]>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct SolidDoc {
    pub(super) color: Rgb,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct CheckerDoc {
    pub(super) scale: Spanned<Real>,
    pub(super) even: Rgb,
    pub(super) odd: Rgb,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct MarbleDoc {
    pub(super) scale: Spanned<Real>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct ImageDoc {
    pub(super) file: Spanned<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct AlbedoDoc {
    pub(super) albedo: Spanned<ColorSpec>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct MetalDoc {
    pub(super) albedo: Spanned<Rgb>,
    pub(super) fuzz: Option<Spanned<Real>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct DielectricDoc {
    pub(super) ior: Spanned<Real>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct LightDoc {
    pub(super) emit: Spanned<ColorSpec>,
    #[serde(default)]
    pub(super) two_sided: bool,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct SphereDoc {
    pub(super) name: Option<Spanned<String>>,
    pub(super) center: V3,
    pub(super) radius: Spanned<Real>,
    pub(super) material: Spanned<String>,
    #[serde(default)]
    pub(super) transform: Vec<Step>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct MovingSphereDoc {
    pub(super) name: Option<Spanned<String>>,
    pub(super) center0: V3,
    pub(super) center1: V3,
    pub(super) radius: Spanned<Real>,
    pub(super) material: Spanned<String>,
    #[serde(default)]
    pub(super) transform: Vec<Step>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct QuadDoc {
    pub(super) name: Option<Spanned<String>>,
    pub(super) q: V3,
    pub(super) u: Spanned<V3>,
    pub(super) v: Spanned<V3>,
    pub(super) material: Spanned<String>,
    #[serde(default)]
    pub(super) transform: Vec<Step>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct BoxDoc {
    pub(super) name: Option<Spanned<String>>,
    pub(super) a: V3,
    pub(super) b: Spanned<V3>,
    pub(super) material: Spanned<String>,
    #[serde(default)]
    pub(super) transform: Vec<Step>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct GroupDoc {
    pub(super) name: Option<Spanned<String>>,
    #[serde(default)]
    pub(super) transform: Vec<Step>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct InstanceDoc {
    pub(super) name: Option<Spanned<String>>,
    pub(super) of: Spanned<String>,
    #[serde(default)]
    pub(super) transform: Vec<Step>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct MediumDoc {
    pub(super) name: Option<Spanned<String>>,
    pub(super) density: Spanned<Real>,
    pub(super) albedo: Spanned<ColorSpec>,
    #[serde(default)]
    pub(super) transform: Vec<Step>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct TargetSphereDoc {
    pub(super) center: V3,
    pub(super) radius: Spanned<Real>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct TargetQuadDoc {
    pub(super) q: V3,
    pub(super) u: Spanned<V3>,
    pub(super) v: Spanned<V3>,
}

/// Refuses a control character (other than tab, line feed and carriage return) or a bidirectional
/// control ([`crate::text::acts`]) in any key or string of the document: names and descriptions are
/// printed to a terminal (`--explain`, errors), where an escape sequence would act rather than
/// show, and a right-to-left override would make the line read otherwise than it is.
pub(super) fn plain_text(t: &DeTable<'_>) -> Result<(), Fail> {
    fn control(s: &str) -> Option<char> {
        s.chars().find(|&c| crate::text::acts(c))
    }
    fn refuse(span: Span, what: &str, c: char) -> Result<(), Fail> {
        let kind = if c.is_control() {
            "a control character"
        } else {
            "a bidirectional control"
        };
        fail(
            span,
            format!(
                "{kind} (U+{:04X}) in {what}: a scene file's text must print as it reads",
                c as u32
            ),
        )
    }
    fn value(v: &Val<'_>) -> Result<(), Fail> {
        match v.get_ref() {
            DeValue::String(s) => match control(s) {
                Some(c) => refuse(v.span(), "a string", c),
                None => Ok(()),
            },
            DeValue::Table(t) => plain_text(t),
            DeValue::Array(a) => a.iter().try_for_each(value),
            _ => Ok(()),
        }
    }
    for (k, v) in t.iter() {
        if let Some(c) = control(k.get_ref()) {
            return refuse(k.span(), "a key", c);
        }
        value(v)?;
    }
    Ok(())
}
