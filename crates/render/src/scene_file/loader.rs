//! The loader: the file's top-level tables in order (render settings, camera, textures, materials,
//! objects, importance targets) into a [`SceneBuilder`], refusing every value the renderer cannot use
//! with its span. The objects, one function per kind, are in `objects.rs`.

use super::SceneFile;
use super::doc::{
    AlbedoDoc, CameraDoc, CheckerDoc, DielectricDoc, ImageDoc, LightDoc, MATERIAL_TYPES, MarbleDoc,
    MetalDoc, RenderDoc, SolidDoc, TEXTURE_TYPES, TOP_KEYS, Typed, de, de_table, in_file_order,
    plain_text, take, typed,
};
use super::span::{Fail, Span, Val, fail, line_col};
use super::values::{Aspect, BackgroundSpec, ColorSpec, Num, Real, Step, V3, compose};
use crate::camera::CameraSettings;
use crate::limits::{self, MAX_EXPANDED_OBJECTS, MAX_NESTING, MAX_SIDE, MIN_POSITIVE};
use crate::material::{Albedo, Material};
use crate::scene::{
    Background, GroupId, ImportanceTarget, MaterialId, SceneBuilder, TextureId, Transform,
};
use crate::scenes::Built;
use crate::shapes::{Quad, Sphere};
use crate::texture::{ImageData, Texture};
use crate::vec::Vec3;
use std::collections::HashMap;
use std::path::PathBuf;
use toml::Spanned;
use toml::de::{DeTable, DeValue};

/// What a name in the file stands for.
#[derive(Clone, Copy)]
pub(super) enum Named {
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
pub(super) struct Placement {
    pub(super) group: GroupId,
    pub(super) instance: Option<Transform>,
    /// Object space to world space, for importance targets.
    pub(super) to_world: Transform,
}

/// What a group holds once its instances are expanded.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct GroupSize {
    /// Its objects, each counted once for each place it ends up in ([`MAX_EXPANDED_OBJECTS`]).
    pub(super) objects: u64,
    /// How deep groups nest inside it (0: it holds shapes alone).
    pub(super) nesting: u32,
}

pub(super) struct Loader<'t> {
    /// The file's text, for places named in messages.
    pub(super) text: &'t str,
    pub(super) b: SceneBuilder,
    pub(super) dir: PathBuf,
    pub(super) textures: Vec<(String, TextureId)>,
    pub(super) materials: Vec<(String, MaterialId)>,
    /// `textures` and `materials` by name (a file of 100,000 materials looked each up in the list).
    pub(super) texture_ids: HashMap<String, TextureId>,
    pub(super) material_ids: HashMap<String, MaterialId>,
    pub(super) names: HashMap<String, (Span, Named)>,
    pub(super) shutter: (f64, f64),
    /// Per group (by index), what it holds so far once expanded; the world's is the scene's.
    pub(super) sizes: Vec<GroupSize>,
    /// Per group the file writes (a `group`, a `box`, a medium's boundary), how messages name it.
    pub(super) labels: HashMap<u32, String>,
    /// The image files the textures were read from (inputs a render must not overwrite).
    pub(super) texture_files: Vec<PathBuf>,
    /// How many more shapes (quads, spheres) placed again by instances the placement rules look
    /// at (a bound on the loader's time for instances of instances).
    pub(super) instance_shape_checks: usize,
    /// Where each quad of the file was written, by its group and index among the group's objects
    /// (a medium's boundary that is open names its quad).
    pub(super) quad_spans: HashMap<(u32, usize), Span>,
}

impl<'t> Loader<'t> {
    pub(super) fn new(dir: PathBuf, text: &'t str) -> Self {
        Loader {
            text,
            b: SceneBuilder::new(),
            dir,
            textures: Vec::new(),
            materials: Vec::new(),
            texture_ids: HashMap::new(),
            material_ids: HashMap::new(),
            names: HashMap::new(),
            shutter: (0.0, 1.0),
            sizes: Vec::new(),
            labels: HashMap::new(),
            texture_files: Vec::new(),
            instance_shape_checks: 1 << 20,
            quad_spans: HashMap::new(),
        }
    }

    /// `line L:C`, the place of byte `offset` of the file.
    pub(super) fn at(&self, offset: usize) -> String {
        let (line, col) = line_col(self.text, offset);
        format!("line {line}:{col}")
    }

    fn size(&mut self, g: GroupId) -> &mut GroupSize {
        let i = g.0 as usize;
        if self.sizes.len() <= i {
            self.sizes.resize(i + 1, GroupSize::default());
        }
        &mut self.sizes[i]
    }

    /// How messages name group `g`: "the scene", "group `name`", ...
    fn label(&self, g: GroupId) -> String {
        if g == self.b.world() {
            "the scene".into()
        } else {
            self.labels
                .get(&g.0)
                .cloned()
                .unwrap_or_else(|| "its group".into())
        }
    }

    /// Count an object added to group `into` by the object of the file at `span` (`what` names it in
    /// messages): a shape (`inner` = `None`), or an instance, nested group or medium that places group
    /// `inner`, which counts again every object of `inner` and nests one deeper. Refused once `into`
    /// would hold more than [`MAX_EXPANDED_OBJECTS`] objects expanded or nest deeper than
    /// [`MAX_NESTING`]: before anything is expanded, so that a few kilobytes of instances of instances
    /// (2^40 shapes) are refused at once.
    pub(super) fn count(
        &mut self,
        into: GroupId,
        inner: Option<GroupId>,
        span: &Span,
        what: &str,
    ) -> Result<(), Fail> {
        let placed = match inner {
            Some(g) => *self.size(g),
            None => GroupSize::default(),
        };
        let added = placed.objects.saturating_add(1);
        let nesting = if inner.is_some() {
            placed.nesting.saturating_add(1)
        } else {
            0
        };
        let size = *self.size(into);
        let objects = size.objects.saturating_add(added);
        if objects > MAX_EXPANDED_OBJECTS {
            let total = if objects == u64::MAX {
                "more than 2^64".to_owned()
            } else {
                objects.to_string()
            };
            return fail(
                span.clone(),
                format!(
                    "too many objects once instances are expanded: {what} ({added} object{}) brings \
                     {} to {total}, more than the {MAX_EXPANDED_OBJECTS} a scene may hold (an \
                     instance counts again every object of the group it places)",
                    if added == 1 { "" } else { "s" },
                    self.label(into),
                ),
            );
        }
        if nesting > MAX_NESTING {
            return fail(
                span.clone(),
                format!(
                    "groups nest too deep: {what} puts {nesting} levels of groups, instances and \
                     media inside one another in {}, more than the {MAX_NESTING} allowed",
                    self.label(into),
                ),
            );
        }
        *self.size(into) = GroupSize {
            objects,
            nesting: size.nesting.max(nesting),
        };
        Ok(())
    }

    pub(super) fn load(mut self, root: Spanned<DeTable<'_>>) -> Result<SceneFile, Fail> {
        let mut t = root.into_inner();
        plain_text(&t)?;
        for (k, _) in t.iter() {
            if !TOP_KEYS.contains(&k.get_ref().as_ref()) {
                return fail(
                    k.span(),
                    format!(
                        "unknown field `{}`, expected one of {}",
                        crate::text::shown(k.get_ref()),
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
        let width_at = render
            .width
            .as_ref()
            .map(|w| line_col(self.text, w.span().start));
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
                let (name, id) = (name.into_inner(), self.b.texture(tex));
                self.texture_ids.insert(name.clone(), id);
                self.textures.push((name, id));
            }
        }
        if let Some(materials) = take(&mut t, "materials") {
            for (name, v) in in_file_order(self.table(materials)?) {
                let m = self.material(v)?;
                let (name, id) = (name.into_inner(), self.b.material(m));
                self.material_ids.insert(name.clone(), id);
                self.materials.push((name, id));
            }
        }
        self.size(self.b.world());
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
            // Each target once, by name and by shape (a name, another name of the same shape, or
            // the shape written out): listed twice it would only take twice the share of the
            // samples, and one listed 200,000 times made a 32 x 32 render take 10 s, not 0.
            let mut listed: HashMap<String, usize> = HashMap::new();
            let mut shapes: HashMap<[u64; 10], usize> = HashMap::new();
            for l in self.array(lights, "a list of object names or shapes")? {
                if let Some(name) = l.get_ref().as_str() {
                    if let Some(&first) = listed.get(name) {
                        return fail(
                            l.span(),
                            format!(
                                "`{}` is already in `lights` (at {}): list each target once",
                                crate::text::shown(name),
                                self.at(first)
                            ),
                        );
                    }
                    listed.insert(name.to_owned(), l.span().start);
                }
                let span = l.span();
                let target = self.light(l)?;
                if let Some(&first) = shapes.get(&shape_key(&target)) {
                    return fail(
                        span,
                        format!(
                            "this target is already in `lights` (at {}), the same shape: list \
                             each target once",
                            self.at(first)
                        ),
                    );
                }
                shapes.insert(shape_key(&target), span.start);
                self.b.targets.push(target);
            }
        }
        let scene = self.b.build().map_err(|e| Fail {
            span: 0..0,
            msg: format!("invalid scene: {e}"),
        })?;
        // Not an error (a scene may be a study of shadows in progress), but a black image with no
        // word of why looks like a bug of the renderer's.
        let mut notices = Vec::new();
        if scene.features.emitters == 0
            && matches!(scene.background, Background::Solid(c) if c == Vec3::ZERO)
        {
            notices.push(
                "the scene has no light: no sphere or quad is of a `light` material and the \
                 background is black, so the image is black (give an object a `light` material, \
                 or [render] background = \"sky\")"
                    .to_string(),
            );
        }
        Ok(SceneFile {
            built: Built { scene, notices },
            width,
            width_at,
            spp,
            description,
            texture_files: self.texture_files,
        })
    }

    pub(super) fn table<'i>(&self, v: Val<'i>) -> Result<DeTable<'i>, Fail> {
        let span = v.span();
        match v.into_inner() {
            DeValue::Table(t) => Ok(t),
            other => fail(
                span,
                format!("expected a table, found {}", other.type_str()),
            ),
        }
    }

    pub(super) fn array<'i>(&self, v: Val<'i>, what: &str) -> Result<Vec<Val<'i>>, Fail> {
        let span = v.span();
        match v.into_inner() {
            DeValue::Array(a) => Ok(a.into_iter().collect()),
            other => fail(span, format!("expected {what}, found {}", other.type_str())),
        }
    }

    pub(super) fn render(&mut self, r: &RenderDoc) -> Result<(Option<usize>, Option<u64>), Fail> {
        for (value, what) in [(&r.width, "width"), (&r.spp, "spp")] {
            if let Some(v) = value
                && *v.get_ref() == 0
            {
                return fail(v.span(), format!("{what} must be at least 1"));
            }
        }
        if let Some(w) = &r.width
            && *w.get_ref() > MAX_SIDE as u64
        {
            return fail(
                w.span(),
                format!("width must be at most {MAX_SIDE}, got {}", w.get_ref()),
            );
        }
        if let Some(d) = &r.max_depth {
            if let Some(problem) = limits::max_depth_problem(*d.get_ref()) {
                return fail(d.span(), format!("max_depth {problem}"));
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

    pub(super) fn camera(&mut self, c: CameraDoc, aspect: Option<Aspect>) -> Result<(), Fail> {
        let d = CameraSettings::default();
        let real = |x: &Option<Spanned<Real>>, default: f64| {
            x.as_ref()
                .map_or((default, 0..0), |s| (s.get_ref().0, s.span()))
        };
        let (vfov, vfov_span) = real(&c.vfov, d.vfov);
        if !(vfov > 0.0 && vfov < 180.0) {
            return fail(
                vfov_span,
                format!("vfov must lie in (0, 180) degrees, got {}", Num(vfov)),
            );
        }
        let (defocus_angle, da_span) = real(&c.defocus_angle, d.defocus_angle);
        if !(0.0..180.0).contains(&defocus_angle) {
            return fail(
                da_span,
                format!(
                    "defocus_angle must lie in [0, 180) degrees, got {}",
                    Num(defocus_angle)
                ),
            );
        }
        // (at least MIN_POSITIVE, as every quantity that must be positive: at 1e-300 the camera's
        // ray directions, of that length, have squares that underflow to 0)
        let focus_dist = match &c.focus_dist {
            Some(f) => positive(f, "focus_dist")?,
            None => d.focus_dist,
        };
        let (lookfrom, lookat) = (c.lookfrom.get_ref().0, c.lookat.get_ref().0);
        let view = lookfrom - lookat;
        if lookfrom == lookat {
            return fail(
                c.lookat.span(),
                "lookfrom and lookat are the same point: the camera has no view direction",
            );
        }
        // (the distance scaled by the largest difference: its square would underflow to 0 for points
        // 1e-300 apart)
        let largest = view.abs().max_element();
        let distance = largest * (view / largest).length();
        if distance < MIN_POSITIVE {
            return fail(
                c.lookat.span(),
                format!(
                    "lookfrom and lookat are only {} apart: they must be at least {MIN_POSITIVE:e} \
                     apart to give the camera a view direction",
                    Num(distance)
                ),
            );
        }
        let vup = c.vup.as_ref().map_or(d.vup, |v| v.get_ref().0);
        if vup.cross(view).length_squared() <= 1e-12 * vup.length_squared() * view.length_squared()
        {
            return fail(
                c.vup.as_ref().map_or(c.lookat.span(), |v| v.span()),
                format!(
                    "vup {} is parallel to the view direction (or zero): the image has no up",
                    Num::v3(vup)
                ),
            );
        }
        if let Some(s) = &c.shutter {
            let [Real(open), Real(close)] = *s.get_ref();
            if open > close {
                return fail(
                    s.span(),
                    format!(
                        "the shutter closes ({}) before it opens ({})",
                        Num(close),
                        Num(open)
                    ),
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

    pub(super) fn texture(&mut self, v: Val<'_>) -> Result<Texture, Fail> {
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
                if d.file.get_ref().is_empty() {
                    return fail(d.file.span(), "the texture file's name is empty");
                }
                let file = self.dir.join(d.file.get_ref());
                if !file.exists() {
                    return fail(
                        d.file.span(),
                        format!(
                            "texture file {} not found (paths are relative to the scene file's directory)",
                            file.display()
                        ),
                    );
                }
                let img = ImageData::load(&file).or_else(|e| fail(d.file.span(), e))?;
                self.texture_files.push(file);
                Texture::Image(Box::new(img))
            }
            _ => unreachable!("typed() returns one of TEXTURE_TYPES"),
        })
    }

    /// A colour or a named texture.
    pub(super) fn albedo(&self, c: &Spanned<ColorSpec>) -> Result<Albedo, Fail> {
        match c.get_ref() {
            ColorSpec::Rgb(c) => Ok(Albedo::Constant(*c)),
            ColorSpec::Texture(name) => match self.texture_ids.get(name) {
                Some(id) => Ok(Albedo::Texture(*id)),
                None => fail(
                    c.span(),
                    format!(
                        "unknown texture `{}`; {}",
                        crate::text::shown(name),
                        known("textures", self.textures.iter().map(|(n, _)| n.as_str()))
                    ),
                ),
            },
        }
    }

    /// A reflectance (the albedo of a surface or a medium): a colour or a named texture whose
    /// components lie in [0, 1], since a surface reflects at most the light it receives (above 1 the
    /// throughput of a path grows with every bounce until it overflows).
    pub(super) fn reflectance(&self, c: &Spanned<ColorSpec>) -> Result<Albedo, Fail> {
        let albedo = self.albedo(c)?;
        let most = match albedo {
            Albedo::Constant(c) => c.max_element(),
            Albedo::Texture(t) => match &self.b.textures[t.index()] {
                Texture::Solid(c) => c.max_element(),
                Texture::Checker { even, odd, .. } => even.max_element().max(odd.max_element()),
                // Images are 8-bit values decoded to [0, 1]; marble is a grey in [0, 1].
                Texture::Image(_) | Texture::Marble { .. } => 0.0,
            },
        };
        if most > 1.0 {
            return fail(
                c.span(),
                format!(
                    "an albedo reflects a fraction of the light, so its components must lie in [0, 1]; \
                     got {}",
                    Num(most)
                ),
            );
        }
        Ok(albedo)
    }

    pub(super) fn material(&self, v: Val<'_>) -> Result<Material, Fail> {
        let Typed { kind, table, span } = typed(v, "material", MATERIAL_TYPES)?;
        Ok(match kind {
            "lambertian" => Material::Lambertian {
                albedo: self.reflectance(&de_table::<AlbedoDoc>(table, &span)?.albedo)?,
            },
            "isotropic" => Material::Isotropic {
                albedo: self.reflectance(&de_table::<AlbedoDoc>(table, &span)?.albedo)?,
            },
            "metal" => {
                let d: MetalDoc = de_table(table, &span)?;
                let fuzz = match &d.fuzz {
                    Some(f) if !(0.0..=1.0).contains(&f.get_ref().0) => {
                        return fail(
                            f.span(),
                            format!("fuzz must lie in [0, 1], got {}", Num(f.get_ref().0)),
                        );
                    }
                    Some(f) => f.get_ref().0,
                    None => 0.0,
                };
                let albedo = d.albedo.get_ref().0;
                if albedo.max_element() > 1.0 {
                    return fail(
                        d.albedo.span(),
                        format!(
                            "a metal reflects a fraction of the light, so its albedo must lie in \
                             [0, 1]; got {}",
                            Num(albedo.max_element())
                        ),
                    );
                }
                Material::Metal { albedo, fuzz }
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

    pub(super) fn material_id(&self, name: &Spanned<String>) -> Result<MaterialId, Fail> {
        match self.material_ids.get(name.get_ref()) {
            Some(id) => Ok(*id),
            None => fail(
                name.span(),
                format!(
                    "unknown material `{}`; {}",
                    crate::text::shown(name.get_ref()),
                    known("materials", self.materials.iter().map(|(n, _)| n.as_str()))
                ),
            ),
        }
    }

    pub(super) fn name(&mut self, name: Option<Spanned<String>>, what: Named) -> Result<(), Fail> {
        let Some(name) = name else { return Ok(()) };
        if let Some((first, _)) = self.names.get(name.get_ref()) {
            return fail(
                name.span(),
                format!(
                    "the name `{}` is already used (first at {})",
                    crate::text::shown(name.get_ref()),
                    self.at(first.start)
                ),
            );
        }
        self.names
            .insert(name.get_ref().clone(), (name.span(), what));
        Ok(())
    }

    /// Where an object with transform `steps` inside group `into` puts its parts.
    pub(super) fn placement(
        &mut self,
        into: GroupId,
        steps: &[Step],
        to_world: Transform,
        span: &Span,
    ) -> Result<Placement, Fail> {
        Ok(if steps.is_empty() {
            Placement {
                group: into,
                instance: None,
                to_world,
            }
        } else {
            let t = self.compose(steps, span)?;
            Placement {
                group: self.b.group(),
                instance: Some(t),
                to_world: t.then(to_world),
            }
        })
    }

    /// The transform of `steps` (the object at `span`), refused unless every number of it is finite:
    /// translations that add up past `f64::MAX` would put the object at infinity.
    pub(super) fn compose(&self, steps: &[Step], span: &Span) -> Result<Transform, Fail> {
        let t = compose(steps);
        if t.rotation.is_finite() && t.translation.is_finite() {
            Ok(t)
        } else {
            fail(
                span.clone(),
                format!(
                    "field `transform`: the steps add up to a translation of {}, which is not finite",
                    Num::v3(t.translation)
                ),
            )
        }
    }

    /// Put the parts of the object at `span` (`what`, for messages) where `p` says: through an instance
    /// into `into` if it has a transform (counted there; its parts were counted in their own group).
    pub(super) fn place(
        &mut self,
        into: GroupId,
        p: &Placement,
        span: &Span,
        what: &str,
    ) -> Result<(), Fail> {
        if let Some(t) = p.instance {
            self.count(into, Some(p.group), span, what)?;
            self.b.instance(into, p.group, t);
        }
        Ok(())
    }
}

pub(super) fn positive(x: &Spanned<Real>, what: &str) -> Result<f64, Fail> {
    let v = x.get_ref().0;
    if v >= MIN_POSITIVE {
        Ok(v)
    } else if v > 0.0 {
        fail(
            x.span(),
            format!("{what} must be at least {MIN_POSITIVE:e}, got {v:e}"),
        )
    } else {
        fail(x.span(), format!("{what} must be positive, got {}", Num(v)))
    }
}

/// A quad spans an area only if `u x v` is not zero.
pub(super) fn check_quad(u: Vec3, v: Vec3, us: &Spanned<V3>, vs: &Spanned<V3>) -> Result<(), Fail> {
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
            "zero-area quad: u x v = 0 (u = {}, v = {} are parallel or zero)",
            Num::v3(u),
            Num::v3(v)
        ),
    )
}

/// "known materials: a, b" or "no materials are defined"; past 20 names, "and 99980 more".
pub(super) fn known<'a>(what: &str, names: impl Iterator<Item = &'a str>) -> String {
    const SHOWN: usize = 20;
    let mut names = names.peekable();
    if names.peek().is_none() {
        return format!("no {what} are defined");
    }
    let shown: Vec<String> = names
        .by_ref()
        .take(SHOWN)
        .map(|n| format!("`{}`", crate::text::shown(n)))
        .collect();
    let more = names.count();
    let more = if more > 0 {
        format!(" and {more} more")
    } else {
        String::new()
    };
    format!("known {what}: {}{more}", shown.join(", "))
}

/// An importance target's shape as bits (a sphere's centre, motion and radius, a quad's corner and
/// edges; `-0` taken as `0`), the same for the same shape however `lights` names it.
fn shape_key(t: &ImportanceTarget) -> [u64; 10] {
    let b = |x: f64| (x + 0.0).to_bits();
    match t {
        ImportanceTarget::Sphere(s) => {
            let (c, m) = (s.center, s.motion);
            [
                0,
                b(c.x),
                b(c.y),
                b(c.z),
                b(m.x),
                b(m.y),
                b(m.z),
                b(s.radius),
                0,
                0,
            ]
        }
        ImportanceTarget::Quad(q) => {
            let (p, u, v) = (q.q, q.u, q.v);
            [
                1,
                b(p.x),
                b(p.y),
                b(p.z),
                b(u.x),
                b(u.y),
                b(u.z),
                b(v.x),
                b(v.y),
                b(v.z),
            ]
        }
    }
}
