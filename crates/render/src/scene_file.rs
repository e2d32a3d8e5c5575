//! Scene files: the objects of the built-in scenes described in TOML, so users write scenes without
//! recompiling (`rtl render path/to/scene.toml`).
//!
//! A file reads like the books' `main` functions: named textures and materials in tables, objects in an
//! array of tables, each with a `type`, and an optional list of transform steps applied in order.
//!
//! ```toml
//! description = "a glass ball in a white box"   # top-level keys come before the first [table]
//! lights = ["lamp", "ball"]                      # importance targets: named objects or inline shapes
//!
//! [render]                   # defaults the command line may override
//! width = 400                # --width
//! aspect = 1.0               # or "16:9"
//! spp = 64                   # --spp
//! max_depth = 50             # --max-depth
//! background = [0, 0, 0]     # or "sky" (book 1's gradient)
//!
//! [camera]
//! vfov = 40
//! lookfrom = [278, 278, -800]
//! lookat = [278, 278, 0]
//! vup = [0, 1, 0]            # default [0, 1, 0]
//! defocus_angle = 0          # degrees; 0 is a pinhole
//! focus_dist = 10
//! shutter = [0, 1]           # the times the shutter opens and closes
//!
//! [textures]
//! tiles = { type = "checker", scale = 0.32, even = [0.2, 0.3, 0.1], odd = 0.9 }
//!
//! [materials]
//! white = { type = "lambertian", albedo = 0.73 }
//! floor = { type = "lambertian", albedo = "tiles" }
//! glass = { type = "dielectric", ior = 1.5 }
//! lamp = { type = "light", emit = [15, 15, 15] }   # one-sided unless two_sided = true
//!
//! [[objects]]
//! type = "quad"
//! name = "lamp"
//! q = [213, 554, 227]
//! u = [130, 0, 0]
//! v = [0, 0, 105]
//! material = "lamp"
//!
//! [[objects]]
//! type = "box"
//! a = [0, 0, 0]
//! b = [165, 330, 165]
//! material = "white"
//! transform = [{ rotate_y = 15 }, { translate = [265, 0, 295] }]
//! ```
//!
//! Object types: `sphere` (center, radius), `moving_sphere` (center0 at time 0, center1 at time 1,
//! radius), `quad` (q, u, v), `box` (opposite corners a, b), `group` (its own `[[objects.objects]]`,
//! with its own BVH), `instance` (`of` = the name of a group or box, placed again) and `medium` (a
//! constant-density medium: `density`, `albedo`, and a `boundary` object). Textures: `solid`, `checker`,
//! `marble`, `image` (`file`, relative to the scene file). Materials: `lambertian`, `metal`,
//! `dielectric`, `light`, `isotropic`.
//!
//! Every error names the place: `FILE:LINE:COL: field objects[2].radius: message`.

mod values;

use crate::camera::CameraSettings;
use crate::material::{Albedo, Material};
use crate::scene::{
    Background, GroupId, MaterialId, NO_MATERIAL, Object, SceneBuilder, Target, TextureId,
    Transform,
};
use crate::scenes::Built;
use crate::shapes::{Quad, Sphere};
use crate::texture::{ImageData, Texture};
use crate::vec::Vec3;
use serde::Deserialize;
use std::collections::HashMap;
use std::ops::Range;
use std::path::{Path, PathBuf};
use toml::Spanned;
use toml::de::{DeTable, DeValue, ValueDeserializer};
use values::{Aspect, BackgroundSpec, ColorSpec, Real, Rgb, Step, V3, compose};

type Span = Range<usize>;
type Val<'i> = Spanned<DeValue<'i>>;

/// A scene read from a file, with the render defaults the file asks for.
pub struct SceneFile {
    pub built: Built,
    /// `[render] width`, if given.
    pub width: Option<usize>,
    /// `[render] spp`, if given.
    pub spp: Option<u64>,
    /// The top-level `description`, if given.
    pub description: Option<String>,
}

/// 1-based line and column of a byte offset in `text`.
pub fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, col)
}

/// Parse `text` (read from `path`) as TOML; errors read `path:line:col: message`.
pub fn parse(path: &Path, text: &str) -> Result<toml::Table, String> {
    text.parse::<toml::Table>()
        .map_err(|e| syntax_error(path, text, &e))
}

fn syntax_error(path: &Path, text: &str, e: &toml::de::Error) -> String {
    let (line, col) = e.span().map_or((1, 1), |s| line_col(text, s.start));
    format!(
        "{}:{line}:{col}: {}",
        path.display(),
        e.message().trim_end()
    )
}

/// Load the scene in the file at `path`.
pub fn load(path: &Path) -> Result<Built, String> {
    load_file(path).map(|f| f.built)
}

/// Load the scene in the file at `path`, with its render defaults.
pub fn load_file(path: &Path) -> Result<SceneFile, String> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("{}: cannot read scene file: {e}", path.display()))?;
    from_str(path, &text)
}

/// Build the scene described by `text`; `path` names the file in errors, and image textures are found
/// relative to its directory.
pub fn from_str(path: &Path, text: &str) -> Result<SceneFile, String> {
    let root = DeTable::parse(text).map_err(|e| syntax_error(path, text, &e))?;
    let tree = root.get_ref().clone();
    let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
    Loader::new(dir)
        .load(root)
        .map_err(|f| f.describe(path, text, &tree))
}

/// An error at a span of the file.
#[derive(Debug)]
struct Fail {
    span: Span,
    msg: String,
}

impl From<toml::de::Error> for Fail {
    fn from(e: toml::de::Error) -> Self {
        Fail {
            span: e.span().unwrap_or(0..0),
            msg: e.message().trim_end().to_owned(),
        }
    }
}

fn fail<T>(span: Span, msg: impl Into<String>) -> Result<T, Fail> {
    Err(Fail {
        span,
        msg: msg.into(),
    })
}

impl Fail {
    /// `FILE:LINE:COL: field `path`: message`, the field found from the span.
    fn describe(self, file: &Path, text: &str, tree: &DeTable) -> String {
        let (line, col) = line_col(text, self.span.start);
        // An empty span at the start marks an error about the file as a whole.
        let mut field = if self.span == (0..0) {
            String::new()
        } else {
            field_at(tree, &self.span)
        };
        let mut msg = self.msg;
        if let Some(name) = msg
            .strip_prefix("missing field `")
            .and_then(|r| r.split('`').next())
        {
            field = if field.is_empty() {
                name.to_owned()
            } else {
                format!("{field}.{name}")
            };
        }
        if msg.starts_with("unknown field `lights`")
            || msg.starts_with("unknown field `description`")
        {
            msg.push_str(" (top-level keys must come before the first [table] of the file)");
        }
        let field = if field.is_empty() {
            String::new()
        } else {
            format!("field `{field}`: ")
        };
        format!("{}:{line}:{col}: {field}{msg}", file.display())
    }
}

/// The dotted path (`objects[2].radius`) of the smallest key or value whose span contains `span`.
fn field_at(tree: &DeTable, span: &Span) -> String {
    let mut best = (usize::MAX, String::new());
    walk_table(tree, "", span, &mut best);
    best.1
}

fn consider(s: Span, path: &str, target: &Span, best: &mut (usize, String)) {
    // Ties go to the later (deeper) candidate: an array of tables has the span of its first item.
    if s.start <= target.start && target.end <= s.end && s.len() <= best.0 {
        *best = (s.len(), path.to_owned());
    }
}

fn walk_table(t: &DeTable, prefix: &str, target: &Span, best: &mut (usize, String)) {
    for (k, v) in t.iter() {
        let path = if prefix.is_empty() {
            k.get_ref().to_string()
        } else {
            format!("{prefix}.{}", k.get_ref())
        };
        consider(k.span(), &path, target, best);
        walk_value(v, &path, target, best);
    }
}

fn walk_value(v: &Val, path: &str, target: &Span, best: &mut (usize, String)) {
    consider(v.span(), path, target, best);
    match v.get_ref() {
        DeValue::Table(t) => walk_table(t, path, target, best),
        DeValue::Array(a) => {
            for (i, item) in a.iter().enumerate() {
                walk_value(item, &format!("{path}[{i}]"), target, best);
            }
        }
        _ => {}
    }
}

/// Deserialize a value, keeping the spans of its parts.
fn de<'i, T: Deserialize<'i>>(v: Val<'i>) -> Result<T, Fail> {
    T::deserialize(ValueDeserializer::from(v)).map_err(Fail::from)
}

fn de_table<'i, T: Deserialize<'i>>(t: DeTable<'i>, span: &Span) -> Result<T, Fail> {
    de(Spanned::new(span.clone(), DeValue::Table(t)))
}

/// A table with its `type` taken out: the type, its span, the rest of the table and the table's span.
struct Typed<'i> {
    kind: &'static str,
    table: DeTable<'i>,
    span: Span,
}

/// Take `type` out of the table `v`, which must be one of `kinds` (`what`: "object", "material", ...).
fn typed<'i>(v: Val<'i>, what: &str, kinds: &[&'static str]) -> Result<Typed<'i>, Fail> {
    let span = v.span();
    let DeValue::Table(mut table) = v.into_inner() else {
        return fail(span, format!("expected a table with a `type` (a {what})"));
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
                "unknown {what} type `{name}`; known types: {}",
                kinds.join(", ")
            ),
        ),
    }
}

/// Remove `key` from `t`, with its span.
fn take<'i>(t: &mut DeTable<'i>, key: &str) -> Option<Val<'i>> {
    t.remove(key)
}

/// The entries of a table in file order (toml's map is sorted by key).
fn in_file_order<'i>(t: DeTable<'i>) -> Vec<(Spanned<String>, Val<'i>)> {
    let mut v: Vec<_> = t
        .into_iter()
        .map(|(k, v)| (Spanned::new(k.span(), k.into_inner().into_owned()), v))
        .collect();
    v.sort_by_key(|(k, _)| k.span().start);
    v
}

const TOP_KEYS: &[&str] = &[
    "description",
    "lights",
    "render",
    "camera",
    "textures",
    "materials",
    "objects",
];
const OBJECT_TYPES: &[&str] = &[
    "sphere",
    "moving_sphere",
    "quad",
    "box",
    "group",
    "instance",
    "medium",
];
const MATERIAL_TYPES: &[&str] = &["lambertian", "metal", "dielectric", "light", "isotropic"];
const TEXTURE_TYPES: &[&str] = &["solid", "checker", "marble", "image"];

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RenderDoc {
    width: Option<Spanned<u64>>,
    aspect: Option<Aspect>,
    spp: Option<Spanned<u64>>,
    max_depth: Option<Spanned<u32>>,
    background: Option<BackgroundSpec>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CameraDoc {
    vfov: Option<Spanned<Real>>,
    lookfrom: Spanned<V3>,
    lookat: Spanned<V3>,
    vup: Option<Spanned<V3>>,
    defocus_angle: Option<Spanned<Real>>,
    focus_dist: Option<Spanned<Real>>,
    shutter: Option<Spanned<[Real; 2]>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SolidDoc {
    color: Rgb,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CheckerDoc {
    scale: Spanned<Real>,
    even: Rgb,
    odd: Rgb,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct MarbleDoc {
    scale: Spanned<Real>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ImageDoc {
    file: Spanned<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct AlbedoDoc {
    albedo: Spanned<ColorSpec>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct MetalDoc {
    albedo: Rgb,
    fuzz: Option<Spanned<Real>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct DielectricDoc {
    ior: Spanned<Real>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LightDoc {
    emit: Spanned<ColorSpec>,
    #[serde(default)]
    two_sided: bool,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SphereDoc {
    name: Option<Spanned<String>>,
    center: V3,
    radius: Spanned<Real>,
    material: Spanned<String>,
    #[serde(default)]
    transform: Vec<Step>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct MovingSphereDoc {
    name: Option<Spanned<String>>,
    center0: V3,
    center1: V3,
    radius: Spanned<Real>,
    material: Spanned<String>,
    #[serde(default)]
    transform: Vec<Step>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct QuadDoc {
    name: Option<Spanned<String>>,
    q: V3,
    u: Spanned<V3>,
    v: Spanned<V3>,
    material: Spanned<String>,
    #[serde(default)]
    transform: Vec<Step>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct BoxDoc {
    name: Option<Spanned<String>>,
    a: V3,
    b: Spanned<V3>,
    material: Spanned<String>,
    #[serde(default)]
    transform: Vec<Step>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct GroupDoc {
    name: Option<Spanned<String>>,
    #[serde(default)]
    transform: Vec<Step>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct InstanceDoc {
    name: Option<Spanned<String>>,
    of: Spanned<String>,
    #[serde(default)]
    transform: Vec<Step>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct MediumDoc {
    name: Option<Spanned<String>>,
    density: Spanned<Real>,
    albedo: Spanned<ColorSpec>,
    #[serde(default)]
    transform: Vec<Step>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct TargetSphereDoc {
    center: V3,
    radius: Spanned<Real>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct TargetQuadDoc {
    q: V3,
    u: Spanned<V3>,
    v: Spanned<V3>,
}

/// What a name in the file stands for.
#[derive(Clone, Copy)]
enum Named {
    /// A sphere or quad, in world space (an importance target may name it).
    Sphere(Sphere),
    Quad(Quad),
    /// A group or box (an instance may place it again).
    Group(GroupId),
    /// Anything else (moving spheres, media, instances).
    Other(&'static str),
}

/// Where an object's parts go: straight into the enclosing group, or into a group of their own that an
/// instance then places by the object's transform.
struct Placement {
    group: GroupId,
    instance: Option<Transform>,
    /// Object space to world space, for importance targets.
    to_world: Transform,
}

struct Loader {
    b: SceneBuilder,
    dir: PathBuf,
    textures: Vec<(String, TextureId)>,
    materials: Vec<(String, MaterialId)>,
    names: HashMap<String, (Span, Named)>,
    shutter: (f64, f64),
}

impl Loader {
    fn new(dir: PathBuf) -> Self {
        Loader {
            b: SceneBuilder::new(),
            dir,
            textures: Vec::new(),
            materials: Vec::new(),
            names: HashMap::new(),
            shutter: (0.0, 1.0),
        }
    }

    fn load(mut self, root: Spanned<DeTable<'_>>) -> Result<SceneFile, Fail> {
        let mut t = root.into_inner();
        for (k, _) in t.iter() {
            if !TOP_KEYS.contains(&k.get_ref().as_ref()) {
                return fail(
                    k.span(),
                    format!(
                        "unknown field `{}`, expected one of {}",
                        k.get_ref(),
                        TOP_KEYS.join(", ")
                    ),
                );
            }
        }
        let description = take(&mut t, "description").map(de::<String>).transpose()?;
        let render: RenderDoc = take(&mut t, "render")
            .map(de)
            .transpose()?
            .unwrap_or_default();
        let (width, spp) = self.render(&render)?;
        let Some(camera) = take(&mut t, "camera") else {
            return fail(
                0..0,
                "missing table [camera] (at least lookfrom and lookat)",
            );
        };
        self.camera(de(camera)?, render.aspect)?;
        if let Some(textures) = take(&mut t, "textures") {
            for (name, v) in in_file_order(self.table(textures)?) {
                let tex = self.texture(v)?;
                self.textures.push((name.into_inner(), self.b.texture(tex)));
            }
        }
        if let Some(materials) = take(&mut t, "materials") {
            for (name, v) in in_file_order(self.table(materials)?) {
                let m = self.material(v)?;
                self.materials.push((name.into_inner(), self.b.material(m)));
            }
        }
        let (objects, objects_span) = match take(&mut t, "objects") {
            Some(o) => {
                let span = o.span();
                (
                    self.array(o, "an array of object tables ([[objects]])")?,
                    span,
                )
            }
            None => (Vec::new(), 0..0),
        };
        if objects.is_empty() {
            return fail(
                objects_span,
                "the scene has no objects (add [[objects]] tables)",
            );
        }
        let world = self.b.world();
        for o in objects {
            self.object(world, o, Transform::IDENTITY)?;
        }
        if let Some(lights) = take(&mut t, "lights") {
            for l in self.array(lights, "a list of object names or shapes")? {
                self.light(l)?;
            }
        }
        let scene = self.b.build().map_err(|e| Fail {
            span: 0..0,
            msg: format!("invalid scene: {e}"),
        })?;
        Ok(SceneFile {
            built: Built {
                scene,
                notices: Vec::new(),
            },
            width,
            spp,
            description,
        })
    }

    fn table<'i>(&self, v: Val<'i>) -> Result<DeTable<'i>, Fail> {
        let span = v.span();
        match v.into_inner() {
            DeValue::Table(t) => Ok(t),
            other => fail(
                span,
                format!("expected a table, found {}", other.type_str()),
            ),
        }
    }

    fn array<'i>(&self, v: Val<'i>, what: &str) -> Result<Vec<Val<'i>>, Fail> {
        let span = v.span();
        match v.into_inner() {
            DeValue::Array(a) => Ok(a.into_iter().collect()),
            other => fail(span, format!("expected {what}, found {}", other.type_str())),
        }
    }

    fn render(&mut self, r: &RenderDoc) -> Result<(Option<usize>, Option<u64>), Fail> {
        for (value, what) in [(&r.width, "width"), (&r.spp, "spp")] {
            if let Some(v) = value
                && *v.get_ref() == 0
            {
                return fail(v.span(), format!("{what} must be at least 1"));
            }
        }
        if let Some(d) = &r.max_depth {
            if *d.get_ref() == 0 {
                return fail(d.span(), "max_depth must be at least 1");
            }
            self.b.max_depth = *d.get_ref();
        }
        if let Some(bg) = r.background {
            self.b.background = match bg {
                BackgroundSpec::Sky => Background::Sky,
                BackgroundSpec::Rgb(c) => Background::Solid(c),
            };
        }
        Ok((
            r.width.as_ref().map(|w| *w.get_ref() as usize),
            r.spp.as_ref().map(|s| *s.get_ref()),
        ))
    }

    fn camera(&mut self, c: CameraDoc, aspect: Option<Aspect>) -> Result<(), Fail> {
        let d = CameraSettings::default();
        let real = |x: &Option<Spanned<Real>>, default: f64| {
            x.as_ref()
                .map_or((default, 0..0), |s| (s.get_ref().0, s.span()))
        };
        let (vfov, vfov_span) = real(&c.vfov, d.vfov);
        if !(vfov > 0.0 && vfov < 180.0) {
            return fail(
                vfov_span,
                format!("vfov must lie in (0, 180) degrees, got {vfov}"),
            );
        }
        let (defocus_angle, da_span) = real(&c.defocus_angle, d.defocus_angle);
        if !(0.0..180.0).contains(&defocus_angle) {
            return fail(
                da_span,
                format!("defocus_angle must lie in [0, 180) degrees, got {defocus_angle}"),
            );
        }
        let (focus_dist, fd_span) = real(&c.focus_dist, d.focus_dist);
        if focus_dist <= 0.0 {
            return fail(
                fd_span,
                format!("focus_dist must be positive, got {focus_dist}"),
            );
        }
        let (lookfrom, lookat) = (c.lookfrom.get_ref().0, c.lookat.get_ref().0);
        let view = lookfrom - lookat;
        if view.length_squared() == 0.0 {
            return fail(
                c.lookat.span(),
                "lookfrom and lookat are the same point: the camera has no view direction",
            );
        }
        let vup = c.vup.as_ref().map_or(d.vup, |v| v.get_ref().0);
        if vup.cross(view).length_squared() <= 1e-12 * vup.length_squared() * view.length_squared()
        {
            return fail(
                c.vup.as_ref().map_or(c.lookat.span(), |v| v.span()),
                format!(
                    "vup ({}, {}, {}) is parallel to the view direction (or zero): the image has no up",
                    vup.x, vup.y, vup.z
                ),
            );
        }
        if let Some(s) = &c.shutter {
            let [Real(open), Real(close)] = *s.get_ref();
            if open > close {
                return fail(
                    s.span(),
                    format!("the shutter closes ({close}) before it opens ({open})"),
                );
            }
            self.shutter = (open, close);
        }
        self.b.camera = CameraSettings {
            aspect_ratio: aspect.map_or(d.aspect_ratio, |a| a.0),
            vfov,
            lookfrom,
            lookat,
            vup,
            defocus_angle,
            focus_dist,
        };
        Ok(())
    }

    fn texture(&self, v: Val<'_>) -> Result<Texture, Fail> {
        let Typed { kind, table, span } = typed(v, "texture", TEXTURE_TYPES)?;
        Ok(match kind {
            "solid" => Texture::Solid(de_table::<SolidDoc>(table, &span)?.color.0),
            "checker" => {
                let d: CheckerDoc = de_table(table, &span)?;
                let scale = positive(&d.scale, "scale")?;
                Texture::checker(scale, d.even.0, d.odd.0)
            }
            "marble" => {
                let d: MarbleDoc = de_table(table, &span)?;
                Texture::marble(positive(&d.scale, "scale")?)
            }
            "image" => {
                let d: ImageDoc = de_table(table, &span)?;
                let file = self.dir.join(d.file.get_ref());
                if !file.is_file() {
                    return fail(
                        d.file.span(),
                        format!(
                            "texture file {} not found (paths are relative to the scene file's directory)",
                            file.display()
                        ),
                    );
                }
                let img = ImageData::load(&file).or_else(|e| fail(d.file.span(), e))?;
                Texture::Image(Box::new(img))
            }
            _ => unreachable!("typed() returns one of TEXTURE_TYPES"),
        })
    }

    /// A colour or a named texture.
    fn albedo(&self, c: &Spanned<ColorSpec>) -> Result<Albedo, Fail> {
        match c.get_ref() {
            ColorSpec::Rgb(c) => Ok(Albedo::Constant(*c)),
            ColorSpec::Texture(name) => match self.textures.iter().find(|(n, _)| n == name) {
                Some((_, id)) => Ok(Albedo::Texture(id.0)),
                None => fail(
                    c.span(),
                    format!(
                        "unknown texture `{name}`; {}",
                        known("textures", self.textures.iter().map(|(n, _)| n.as_str()))
                    ),
                ),
            },
        }
    }

    fn material(&self, v: Val<'_>) -> Result<Material, Fail> {
        let Typed { kind, table, span } = typed(v, "material", MATERIAL_TYPES)?;
        Ok(match kind {
            "lambertian" => Material::Lambertian {
                albedo: self.albedo(&de_table::<AlbedoDoc>(table, &span)?.albedo)?,
            },
            "isotropic" => Material::Isotropic {
                albedo: self.albedo(&de_table::<AlbedoDoc>(table, &span)?.albedo)?,
            },
            "metal" => {
                let d: MetalDoc = de_table(table, &span)?;
                let fuzz = match &d.fuzz {
                    Some(f) if !(0.0..=1.0).contains(&f.get_ref().0) => {
                        return fail(
                            f.span(),
                            format!("fuzz must lie in [0, 1], got {}", f.get_ref().0),
                        );
                    }
                    Some(f) => f.get_ref().0,
                    None => 0.0,
                };
                Material::Metal {
                    albedo: d.albedo.0,
                    fuzz,
                }
            }
            "dielectric" => {
                let d: DielectricDoc = de_table(table, &span)?;
                Material::Dielectric {
                    ior: positive(&d.ior, "ior")?,
                }
            }
            "light" => {
                let d: LightDoc = de_table(table, &span)?;
                Material::DiffuseLight {
                    emit: self.albedo(&d.emit)?,
                    two_sided: d.two_sided,
                }
            }
            _ => unreachable!("typed() returns one of MATERIAL_TYPES"),
        })
    }

    fn material_id(&self, name: &Spanned<String>) -> Result<MaterialId, Fail> {
        match self.materials.iter().find(|(n, _)| n == name.get_ref()) {
            Some((_, id)) => Ok(*id),
            None => fail(
                name.span(),
                format!(
                    "unknown material `{}`; {}",
                    name.get_ref(),
                    known("materials", self.materials.iter().map(|(n, _)| n.as_str()))
                ),
            ),
        }
    }

    fn name(&mut self, name: Option<Spanned<String>>, what: Named) -> Result<(), Fail> {
        let Some(name) = name else { return Ok(()) };
        if let Some((first, _)) = self.names.get(name.get_ref()) {
            return fail(
                name.span(),
                format!(
                    "the name `{}` is already used (first at byte {})",
                    name.get_ref(),
                    first.start
                ),
            );
        }
        self.names
            .insert(name.get_ref().clone(), (name.span(), what));
        Ok(())
    }

    /// Where an object with transform `steps` inside group `into` puts its parts.
    fn placement(&mut self, into: GroupId, steps: &[Step], to_world: Transform) -> Placement {
        if steps.is_empty() {
            Placement {
                group: into,
                instance: None,
                to_world,
            }
        } else {
            let t = compose(steps);
            Placement {
                group: self.b.group(),
                instance: Some(t),
                to_world: t.then(to_world),
            }
        }
    }

    fn place(&mut self, into: GroupId, p: &Placement) {
        if let Some(t) = p.instance {
            self.b.instance(into, p.group, t);
        }
    }

    /// Build the object `v` into group `into`; `to_world` maps the group's space to world space.
    fn object(&mut self, into: GroupId, v: Val<'_>, to_world: Transform) -> Result<(), Fail> {
        let Typed {
            kind,
            mut table,
            span,
        } = typed(v, "object", OBJECT_TYPES)?;
        match kind {
            "sphere" => {
                let d: SphereDoc = de_table(table, &span)?;
                let m = self.material_id(&d.material)?;
                let r = positive(&d.radius, "radius")?;
                let p = self.placement(into, &d.transform, to_world);
                self.b
                    .sphere(p.group, d.center.0, r, m)
                    .or_else(|e| fail(span.clone(), e.to_string()))?;
                self.place(into, &p);
                let world = Sphere::new(p.to_world.point(d.center.0), r, m.0);
                self.name(d.name, Named::Sphere(world))
            }
            "moving_sphere" => {
                let d: MovingSphereDoc = de_table(table, &span)?;
                let m = self.material_id(&d.material)?;
                let r = positive(&d.radius, "radius")?;
                // The camera's rays carry times in [0, 1); the file's shutter [open, close] maps onto
                // that, so the centre at ray time s is the file's centre at open + s (close - open).
                let (open, close) = self.shutter;
                let motion = d.center1.0 - d.center0.0;
                let (c0, c1) = (d.center0.0 + open * motion, d.center0.0 + close * motion);
                let p = self.placement(into, &d.transform, to_world);
                self.b
                    .moving_sphere(p.group, c0, c1, r, m)
                    .or_else(|e| fail(span.clone(), e.to_string()))?;
                self.place(into, &p);
                self.name(d.name, Named::Other("a moving sphere"))
            }
            "quad" => {
                let d: QuadDoc = de_table(table, &span)?;
                let m = self.material_id(&d.material)?;
                let (q, u, v) = (d.q.0, d.u.get_ref().0, d.v.get_ref().0);
                check_quad(u, v, &d.u, &d.v)?;
                let p = self.placement(into, &d.transform, to_world);
                self.b
                    .quad(p.group, q, u, v, m)
                    .or_else(|e| fail(span.clone(), e.to_string()))?;
                self.place(into, &p);
                let t = p.to_world;
                let world = Quad::new(t.point(q), t.vector(u), t.vector(v), m.0)
                    .map_or(Named::Other("a quad"), Named::Quad);
                self.name(d.name, world)
            }
            "box" => {
                let d: BoxDoc = de_table(table, &span)?;
                let m = self.material_id(&d.material)?;
                let (a, b) = (d.a.0, d.b.get_ref().0);
                let size = (b - a).abs();
                if size.min_element() == 0.0 {
                    return fail(
                        d.b.span(),
                        format!(
                            "the box is flat: corners a and b must differ in x, y and z (size {} x {} x {})",
                            size.x, size.y, size.z
                        ),
                    );
                }
                let g = self
                    .b
                    .box_group(a, b, m)
                    .or_else(|e| fail(span.clone(), e.to_string()))?;
                if d.transform.is_empty() {
                    self.b.add_to(into, Object::Group(g));
                } else {
                    self.b.instance(into, g, compose(&d.transform));
                }
                self.name(d.name, Named::Group(g))
            }
            "group" => {
                let children = match take(&mut table, "objects") {
                    Some(o) => self.array(o, "an array of object tables ([[objects.objects]])")?,
                    None => Vec::new(),
                };
                let d: GroupDoc = de_table(table, &span)?;
                if children.is_empty() {
                    return fail(
                        span,
                        "a group needs at least one object ([[objects.objects]])",
                    );
                }
                let g = self.b.group();
                let t = compose(&d.transform);
                let inner_to_world = t.then(to_world);
                for c in children {
                    self.object(g, c, inner_to_world)?;
                }
                if d.transform.is_empty() {
                    self.b.add_to(into, Object::Group(g));
                } else {
                    self.b.instance(into, g, t);
                }
                self.name(d.name, Named::Group(g))
            }
            "instance" => {
                let d: InstanceDoc = de_table(table, &span)?;
                let g = match self.names.get(d.of.get_ref()) {
                    Some((_, Named::Group(g))) => *g,
                    _ => {
                        let mut groups: Vec<&str> = self
                            .names
                            .iter()
                            .filter(|(_, (_, n))| matches!(n, Named::Group(_)))
                            .map(|(k, _)| k.as_str())
                            .collect();
                        groups.sort_unstable();
                        return fail(
                            d.of.span(),
                            format!(
                                "`{}` is not a group or box defined earlier in the file; {}",
                                d.of.get_ref(),
                                known("groups and boxes", groups.into_iter())
                            ),
                        );
                    }
                };
                if d.transform.is_empty() {
                    self.b.add_to(into, Object::Group(g));
                } else {
                    self.b.instance(into, g, compose(&d.transform));
                }
                self.name(d.name, Named::Other("an instance"))
            }
            "medium" => {
                let Some(boundary) = take(&mut table, "boundary") else {
                    return fail(span, "missing field `boundary`");
                };
                let d: MediumDoc = de_table(table, &span)?;
                let density = positive(&d.density, "density")?;
                let albedo = self.albedo(&d.albedo)?;
                let p = self.placement(into, &d.transform, to_world);
                let bounds = self.b.group();
                self.object(bounds, boundary, p.to_world)?;
                let phase = self.b.material(Material::Isotropic { albedo });
                self.b
                    .medium(p.group, bounds, density, phase)
                    .or_else(|e| fail(span.clone(), e.to_string()))?;
                self.place(into, &p);
                self.name(d.name, Named::Other("a medium"))
            }
            _ => unreachable!("typed() returns one of OBJECT_TYPES"),
        }
    }

    /// An importance target: the name of a sphere or quad, or an inline `{ type = "sphere" | "quad" }`.
    fn light(&mut self, v: Val<'_>) -> Result<(), Fail> {
        let span = v.span();
        if let Some(name) = v.get_ref().as_str() {
            let target = match self.names.get(name) {
                Some((_, Named::Sphere(s))) => Target::Sphere(*s),
                Some((_, Named::Quad(q))) => Target::Quad(*q),
                Some((_, Named::Group(_))) => {
                    return fail(
                        span,
                        format!(
                            "`{name}` is a group or box; importance targets are spheres and quads"
                        ),
                    );
                }
                Some((_, Named::Other(what))) => {
                    return fail(
                        span,
                        format!("`{name}` is {what}; importance targets are spheres and quads"),
                    );
                }
                None => {
                    let mut shapes: Vec<&str> = self
                        .names
                        .iter()
                        .filter(|(_, (_, n))| matches!(n, Named::Sphere(_) | Named::Quad(_)))
                        .map(|(k, _)| k.as_str())
                        .collect();
                    shapes.sort_unstable();
                    return fail(
                        span,
                        format!(
                            "no object is named `{name}`; {}",
                            known("named spheres and quads", shapes.into_iter())
                        ),
                    );
                }
            };
            self.b.targets.push(target);
            return Ok(());
        }
        let Typed { kind, table, span } = typed(v, "importance target", &["sphere", "quad"])?;
        let target = if kind == "sphere" {
            let d: TargetSphereDoc = de_table(table, &span)?;
            let r = positive(&d.radius, "radius")?;
            Target::Sphere(Sphere::new(d.center.0, r, NO_MATERIAL))
        } else {
            let d: TargetQuadDoc = de_table(table, &span)?;
            let (u, v) = (d.u.get_ref().0, d.v.get_ref().0);
            check_quad(u, v, &d.u, &d.v)?;
            match Quad::new(d.q.0, u, v, NO_MATERIAL) {
                Some(q) => Target::Quad(q),
                None => return fail(span, "degenerate quad"),
            }
        };
        self.b.targets.push(target);
        Ok(())
    }
}

fn positive(x: &Spanned<Real>, what: &str) -> Result<f64, Fail> {
    let v = x.get_ref().0;
    if v > 0.0 {
        Ok(v)
    } else {
        fail(x.span(), format!("{what} must be positive, got {v}"))
    }
}

/// A quad spans an area only if `u x v` is not zero.
fn check_quad(u: Vec3, v: Vec3, us: &Spanned<V3>, vs: &Spanned<V3>) -> Result<(), Fail> {
    let n = u.cross(v);
    if n.length_squared() > 0.0 && n.is_finite() {
        return Ok(());
    }
    let span = if v.length_squared() == 0.0 {
        vs.span()
    } else {
        us.span()
    };
    fail(
        span,
        format!(
            "zero-area quad: u x v = 0 (u = [{}, {}, {}], v = [{}, {}, {}] are parallel or zero)",
            u.x, u.y, u.z, v.x, v.y, v.z
        ),
    )
}

/// "known materials: a, b" or "no materials are defined".
fn known<'a>(what: &str, names: impl Iterator<Item = &'a str>) -> String {
    let names: Vec<String> = names.map(|n| format!("`{n}`")).collect();
    if names.is_empty() {
        format!("no {what} are defined")
    } else {
        format!("known {what}: {}", names.join(", "))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_syntax_error_names_file_line_and_column() {
        let err = parse(Path::new("bad.toml"), "ok = 1\nnot = a [scene\n").unwrap_err();
        assert!(err.starts_with("bad.toml:2:"), "{err}");
    }

    #[test]
    fn field_paths_follow_the_document() {
        let text = "[[objects]]\ntype = \"sphere\"\nradius = 3\n";
        let root = DeTable::parse(text).unwrap();
        let at = text.find('3').unwrap();
        assert_eq!(field_at(root.get_ref(), &(at..at + 1)), "objects[0].radius");
    }
}
