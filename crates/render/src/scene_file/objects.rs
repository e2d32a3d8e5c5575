//! The objects of a scene file, one loader function per kind (`sphere`, `moving_sphere`, `quad`, `box`,
//! `group`, `instance`, `medium`), and the importance targets of `lights`.

use super::doc::{
    BoxDoc, GroupDoc, InstanceDoc, MediumDoc, MovingSphereDoc, OBJECT_TYPES, QuadDoc, SphereDoc,
    TargetQuadDoc, TargetSphereDoc, Typed, de_table, take, typed,
};
use super::loader::{Loader, Named, check_quad, known, positive};
use super::span::{Fail, Span, Val, fail};
use super::values::{Num, Step};
use crate::boundary_pieces::{Piece, PieceKind};
use crate::closed_surface::{OpenQuad, OpenSurface};
use crate::hit::{REL_ERROR, SPAWN_ERRORS};
use crate::material::Material;
use crate::scene::{GroupId, ImportanceTarget, NO_MATERIAL, Object, Transform};
use crate::separation::{parallelogram_distance, segment_distance};
use crate::shapes::{Quad, Sphere};
use crate::vec::{Point3, Vec3};
use toml::de::{DeTable, DeValue};

impl Loader<'_> {
    /// Build the object `v` into group `into`; `to_world` maps the group's space to world space.
    pub(super) fn object(
        &mut self,
        into: GroupId,
        v: Val<'_>,
        to_world: Transform,
    ) -> Result<(), Fail> {
        let Typed { kind, table, span } = typed(v, "object", OBJECT_TYPES)?;
        match kind {
            "sphere" => self.sphere(into, table, span, to_world),
            "moving_sphere" => self.moving_sphere(into, table, span, to_world),
            "quad" => self.quad(into, table, span, to_world),
            "box" => self.box_(into, table, span, to_world),
            "group" => self.group(into, table, span, to_world),
            "instance" => self.instance(into, table, span, to_world),
            "medium" => self.medium(into, table, span, to_world),
            _ => unreachable!("typed() returns one of OBJECT_TYPES"),
        }
    }

    /// `sphere`: `center`, `radius`.
    fn sphere(
        &mut self,
        into: GroupId,
        table: DeTable<'_>,
        span: Span,
        to_world: Transform,
    ) -> Result<(), Fail> {
        let d: SphereDoc = de_table(table, &span)?;
        let m = self.material_id(&d.material)?;
        let r = positive(&d.radius, "radius")?;
        let p = self.placement(into, &d.transform, to_world, &span)?;
        self.placeable(&[d.center.0], p.to_world, r, d.radius.span())?;
        self.count(p.group, None, &span, "this sphere")?;
        self.b
            .sphere(p.group, d.center.0, r, m)
            .or_else(|e| fail(span.clone(), e.to_string()))?;
        self.place(into, &p, &span, "this sphere")?;
        let world = Sphere::new(p.to_world.point(d.center.0), r, m);
        self.name(d.name, Named::Sphere(world))
    }

    /// Refuses a sphere (centres `local`, radius `r`, in the coordinates of its group, which
    /// `to_world` places; the object at `span`) whose surface doubles cannot place finely enough
    /// for the camera: the spacing of doubles at its farthest coordinate (a centre's largest plus
    /// the radius, in its group's coordinates, where its hits are computed, or in the world's,
    /// whichever is larger) more than 1/1024 of the distance it is seen at ([`Self::seen_at`]).
    /// Its hits would be off by about that much (a floor of radius 1e17 seen from 10 away rendered
    /// black); seen from far enough, the same sphere renders. Likewise where the rays leaving it
    /// start farther off it than that ([`Self::leaves_close_enough`]).
    fn placeable(
        &self,
        local: &[Point3],
        to_world: Transform,
        r: f64,
        span: Span,
    ) -> Result<(), Fail> {
        let c = &self.b.camera;
        let world: Vec<Point3> = local.iter().map(|&p| to_world.point(p)).collect();
        let surface = world
            .iter()
            .map(|p| ((c.lookfrom - *p).length() - r).abs())
            .fold(f64::INFINITY, f64::min);
        let scale = self.seen_at(surface);
        let far = local
            .iter()
            .chain(&world)
            .map(|p| p.abs().max_element())
            .fold(0.0, f64::max)
            + r;
        let spacing = far.next_up() - far;
        if spacing > scale / 1024.0 {
            return fail(
                span,
                format!(
                    "a sphere reaching {far:.3e} from the origin cannot be placed finely enough for \
                     this camera: doubles there are {spacing:.3e} apart, more than 1/1024 of the \
                     distance it is seen at ({scale:.3e}, the larger of the camera's to lookat and \
                     to the sphere's surface), so its hits would be that far off; a floor this \
                     large is better a quad"
                ),
            );
        }
        Self::leaves_close_enough(far, scale, "sphere", span)
    }

    /// The distance at which the camera sees a surface `distance` from it, the scale its placement
    /// is held to: the larger of that and the camera's distance to `lookat`, the scale of what it
    /// looks at (a camera standing on a floor sees it at that scale, not at 0). (So a `lookat` set
    /// a million times farther off in the same direction lets a larger surface through.)
    fn seen_at(&self, distance: f64) -> f64 {
        let c = &self.b.camera;
        (c.lookfrom - c.lookat).length().max(distance)
    }

    /// Refuses a surface (`what`, at `span`) whose rays would leave it too far off it for the scale
    /// `scale` it is seen at: they start [`SPAWN_ERRORS`] error bounds off the surface, and the bound
    /// is [`REL_ERROR`] times the magnitude of its coordinates (`size`; for a quad the sum of its
    /// corner's and its edges' largest coordinates, as [`Quad::new`] takes it). Refused when that is
    /// more than 1/1024 of `scale`, as for the spacing of doubles: a sphere floor of radius 1e11 under
    /// a camera 5 from what it looks at started its rays 6 above it, over a lamp at 2.5, and rendered
    /// black, every strategy alike.
    fn leaves_close_enough(size: f64, scale: f64, what: &str, span: Span) -> Result<(), Fail> {
        let offset = SPAWN_ERRORS * REL_ERROR * size;
        // (computed numbers to three digits)
        let short = |x: f64| Num(format!("{x:.2e}").parse().unwrap_or(x));
        if offset > scale / 1024.0 {
            return fail(
                span,
                format!(
                    "a {what} reaching {} from the origin is too large for this camera: rays \
                     leave its surface from {} off it ({SPAWN_ERRORS} times its error bound, \
                     2^-36 of its size), more than 1/1024 of the distance it is seen at ({}, \
                     the larger of the camera's to lookat and to the {what}), so light nearer \
                     to it than that would not reach it; make it smaller, or keep it nearer \
                     the origin",
                    short(size),
                    short(offset),
                    short(scale)
                ),
            );
        }
        Ok(())
    }

    /// Refuse a quad (corner `q`, edges `u`, `v`, placed by `to_world`; the object at `span`) whose
    /// edges cannot be placed finely enough for the camera, as [`Self::placeable`] a sphere: a hit
    /// is inside the quad by its coordinates relative to `q`, which carry the rounding of the largest
    /// coordinate of the quad (its corners, its edges' lengths, before and after its transform), so
    /// an edge is off by the spacing of doubles there. A floor with `q = [-1e20, 0, 1e20]` whose
    /// edge at x = 0 passed 2 from the camera had that edge 16,000 away from its place, the image
    /// silently another (at 1e16, 2 off). Refused when that spacing is more than 1/1024 of the
    /// distance the nearest edge is seen at (the larger of the camera's distance to `lookat` and to
    /// that edge); a large quad whose edges are far away (a floor centred in view) is not.
    fn edges_placeable(
        &self,
        q: Point3,
        u: Vec3,
        v: Vec3,
        to_world: Transform,
        span: &Span,
    ) -> Result<(), Fail> {
        let corners = |q: Point3, u: Vec3, v: Vec3| [q, q + u, q + v, q + u + v];
        let largest = |q: Point3, u: Vec3, v: Vec3| {
            corners(q, u, v)
                .iter()
                .chain(&[u, v])
                .map(|p| p.abs().max_element())
                .fold(0.0, f64::max)
        };
        let (wq, wu, wv) = (to_world.point(q), to_world.vector(u), to_world.vector(v));
        let far = largest(q, u, v).max(largest(wq, wu, wv));
        let c = &self.b.camera;
        let [a, b, cc, d] = corners(wq, wu, wv);
        let edge = [(a, b), (a, cc), (b, d), (cc, d)]
            .iter()
            .map(|&(s, e)| segment_distance(c.lookfrom, s, e))
            .fold(f64::INFINITY, f64::min);
        let scale = self.seen_at(edge);
        let spacing = far.next_up() - far;
        if spacing > scale / 1024.0 {
            return fail(
                span.clone(),
                format!(
                    "a quad (or a box's face) reaching {far:.3e} from the origin cannot have its \
                     edges placed finely \
                     enough for this camera: doubles there are {spacing:.3e} apart, more than 1/1024 \
                     of the distance its nearest edge is seen at ({scale:.3e}, the larger of the \
                     camera's to lookat and to the edge), so its edges would be that far off; make \
                     the quad smaller, or keep its corners nearer the origin"
                ),
            );
        }
        let size = |q: Point3, u: Vec3, v: Vec3| {
            q.abs().max_element() + u.abs().max_element() + v.abs().max_element()
        };
        let seen_at = self.seen_at(parallelogram_distance(c.lookfrom, wq, wu, wv));
        Self::leaves_close_enough(
            size(q, u, v).max(size(wq, wu, wv)),
            seen_at,
            "quad (or box face)",
            span.clone(),
        )
    }

    /// `moving_sphere`: `center0` at time 0, `center1` at time 1, `radius`.
    fn moving_sphere(
        &mut self,
        into: GroupId,
        table: DeTable<'_>,
        span: Span,
        to_world: Transform,
    ) -> Result<(), Fail> {
        let d: MovingSphereDoc = de_table(table, &span)?;
        let m = self.material_id(&d.material)?;
        let r = positive(&d.radius, "radius")?;
        // The camera's rays carry times in [0, 1); the file's shutter [open, close] maps onto that, so
        // the centre at ray time s is the file's centre at open + s (close - open).
        let (open, close) = self.shutter;
        let motion = d.center1.0 - d.center0.0;
        let (c0, c1) = (d.center0.0 + open * motion, d.center0.0 + close * motion);
        let p = self.placement(into, &d.transform, to_world, &span)?;
        self.placeable(&[c0, c1], p.to_world, r, d.radius.span())?;
        self.count(p.group, None, &span, "this moving sphere")?;
        self.b
            .moving_sphere(p.group, c0, c1, r, m)
            .or_else(|e| fail(span.clone(), e.to_string()))?;
        self.place(into, &p, &span, "this moving sphere")?;
        self.name(d.name, Named::Other("a moving sphere"))
    }

    /// `quad`: corner `q` and edges `u`, `v`.
    fn quad(
        &mut self,
        into: GroupId,
        table: DeTable<'_>,
        span: Span,
        to_world: Transform,
    ) -> Result<(), Fail> {
        let d: QuadDoc = de_table(table, &span)?;
        let m = self.material_id(&d.material)?;
        let (q, u, v) = (d.q.0, d.u.get_ref().0, d.v.get_ref().0);
        check_quad(u, v, &d.u, &d.v)?;
        let p = self.placement(into, &d.transform, to_world, &span)?;
        self.edges_placeable(q, u, v, p.to_world, &span)?;
        self.count(p.group, None, &span, "this quad")?;
        let index = self.b.objects(p.group).len();
        self.b
            .quad(p.group, q, u, v, m)
            .or_else(|e| fail(span.clone(), e.to_string()))?;
        self.quad_spans.insert((p.group.0, index), span.clone());
        self.place(into, &p, &span, "this quad")?;
        let t = p.to_world;
        let world = Quad::new(t.point(q), t.vector(u), t.vector(v), m)
            .map_or(Named::Other("a quad"), Named::Quad);
        self.name(d.name, world)
    }

    /// `box`: opposite corners `a`, `b`; six quads in a group of their own.
    fn box_(
        &mut self,
        into: GroupId,
        table: DeTable<'_>,
        span: Span,
        to_world: Transform,
    ) -> Result<(), Fail> {
        let d: BoxDoc = de_table(table, &span)?;
        let m = self.material_id(&d.material)?;
        let (a, b) = (d.a.0, d.b.get_ref().0);
        let size = (b - a).abs();
        if size.min_element() == 0.0 {
            return fail(
                d.b.span(),
                format!(
                    "the box is flat: corners a and b must differ in x, y and z (size {} x {} x {})",
                    Num(size.x),
                    Num(size.y),
                    Num(size.z)
                ),
            );
        }
        // its six faces, each a quad whose edges must be placeable as a quad's are
        let world = self.compose(&d.transform, &span)?.then(to_world);
        let (lo, hi) = (a.min(b), a.max(b));
        let [x, y, z] = [Vec3::X * size.x, Vec3::Y * size.y, Vec3::Z * size.z];
        for (q, u, v) in [
            (lo, x, y),
            (lo, x, z),
            (lo, y, z),
            (hi, -x, -y),
            (hi, -x, -z),
            (hi, -y, -z),
        ] {
            self.edges_placeable(q, u, v, world, &span)?;
        }
        let g = self
            .b
            .box_group(a, b, m)
            .or_else(|e| fail(span.clone(), e.to_string()))?;
        let label = match &d.name {
            Some(n) => format!("box `{}`", crate::text::shown(n.get_ref())),
            None => format!("the box at {}", self.at(span.start)),
        };
        self.labels.insert(g.0, label.clone());
        // (a box is six quads)
        for _ in 0..6 {
            self.count(g, None, &span, "this box")?;
        }
        self.add_placed(
            into,
            g,
            &d.transform,
            &span,
            &this(&label, d.name.is_some()),
        )?;
        self.name(d.name, Named::Group(g))
    }

    /// `group`: its own `[[objects.objects]]`, with its own BVH.
    fn group(
        &mut self,
        into: GroupId,
        mut table: DeTable<'_>,
        span: Span,
        to_world: Transform,
    ) -> Result<(), Fail> {
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
        let label = match &d.name {
            Some(n) => format!("group `{}`", crate::text::shown(n.get_ref())),
            None => format!("the group at {}", self.at(span.start)),
        };
        self.labels.insert(g.0, label.clone());
        let t = self.compose(&d.transform, &span)?;
        let inner_to_world = t.then(to_world);
        for c in children {
            self.object(g, c, inner_to_world)?;
        }
        self.add_placed(
            into,
            g,
            &d.transform,
            &span,
            &this(&label, d.name.is_some()),
        )?;
        self.name(d.name, Named::Group(g))
    }

    /// `instance`: `of` = the name of a group or box defined earlier, placed again.
    fn instance(
        &mut self,
        into: GroupId,
        table: DeTable<'_>,
        span: Span,
        to_world: Transform,
    ) -> Result<(), Fail> {
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
                        crate::text::shown(d.of.get_ref()),
                        known("groups and boxes", groups.into_iter())
                    ),
                );
            }
        };
        let what = format!("this instance of `{}`", crate::text::shown(d.of.get_ref()));
        // Its shapes where this instance puts them, held to the placement rules (the group's
        // own placement was checked where it was defined; a million over the whole file at most).
        let world = self.compose(&d.transform, &span)?.then(to_world);
        let mut budget = self.instance_shape_checks;
        // (its spheres too: a floor placed a long way off, the camera beside it, rendered black)
        self.b
            .each_shape(g, world, &mut budget, &mut |o, t| match o {
                Object::Quad(q) => self.edges_placeable(q.q, q.u, q.v, t, &span),
                Object::Sphere(s) => {
                    self.placeable(&[s.center, s.center + s.motion], t, s.radius, span.clone())
                }
                _ => Ok(()),
            })?;
        self.instance_shape_checks = budget;
        self.add_placed(into, g, &d.transform, &span, &what)?;
        self.name(d.name, Named::Other("an instance"))
    }

    /// `medium`: a constant-density medium (`density`, `albedo`) inside a `boundary` object.
    fn medium(
        &mut self,
        into: GroupId,
        mut table: DeTable<'_>,
        span: Span,
        to_world: Transform,
    ) -> Result<(), Fail> {
        let Some(boundary) = take(&mut table, "boundary") else {
            return fail(span, "missing field `boundary`");
        };
        // The boundary's `type` (or the boundary itself), where a boundary that encloses no volume
        // is refused.
        let place = match boundary.get_ref() {
            DeValue::Table(b) => b.get("type").map_or(boundary.span(), |t| t.span()),
            _ => boundary.span(),
        };
        // A quad bounds no volume: a ray enters it and never leaves, so the medium was invisible
        // without a word.
        if let DeValue::Table(b) = boundary.get_ref()
            && let Some(t) = b.get("type")
            && t.get_ref().as_str() == Some("quad")
        {
            return fail(
                place,
                format!(
                    "{ENCLOSE}; a quad encloses none, and the medium inside it would be invisible"
                ),
            );
        }
        let d: MediumDoc = de_table(table, &span)?;
        let density = positive(&d.density, "density")?;
        let albedo = self.reflectance(&d.albedo)?;
        let p = self.placement(into, &d.transform, to_world, &span)?;
        let bounds = self.b.group();
        self.labels.insert(
            bounds.0,
            format!("the boundary of the medium at {}", self.at(span.start)),
        );
        self.object(bounds, boundary, p.to_world)?;
        // Nor does a group of quads that leaves a gap: a ray leaves it through the gap without a
        // second crossing, and the medium found between the two crossings is not the one inside.
        if let Some(open) = self.b.open_quad(bounds) {
            return fail(place, self.open_boundary(open));
        }
        // A medium in the boundary: its scattering points would count as crossings.
        if self.b.holds_medium(bounds) {
            return fail(
                place,
                "a medium's boundary is surfaces alone, and this one holds a medium (each hit of a \
                 boundary counts as a crossing, and a medium's hits are where it scatters); place \
                 that medium in the scene instead",
            );
        }
        // Nor do pieces that overlap or touch: the crossings no longer alternate in and out.
        let pieces = self.b.boundary_pieces(bounds);
        if let Some((i, j, exact)) = pieces.first_touching() {
            let (a, b) = (&pieces.pieces[i], &pieces.pieces[j]);
            return fail(place, touching_pieces(a, b, exact));
        }
        let phase = self.b.material(Material::Isotropic { albedo });
        self.count(p.group, Some(bounds), &span, "this medium")?;
        self.b
            .medium(p.group, bounds, density, phase)
            .or_else(|e| fail(span.clone(), e.to_string()))?;
        self.place(into, &p, &span, "this medium")?;
        self.name(d.name, Named::Other("a medium"))
    }

    /// Why a medium's boundary whose quad `open` keeps it from enclosing a volume is refused.
    fn open_boundary(&self, open: OpenQuad) -> String {
        let quad = match self.quad_spans.get(&(open.group.0, open.index)) {
            Some(s) => format!("the quad at {}", self.at(s.start)),
            None => "a quad".to_owned(),
        };
        let why = match open.problem {
            OpenSurface::Edge { from, to, others } => {
                let shared = match others {
                    0 => "no other quad of the boundary: the surface is open there".to_owned(),
                    n => format!(
                        "{n} other quads of the boundary: a closed surface has two quads meet at \
                         each edge"
                    ),
                };
                format!(
                    "the edge of {quad} from {} to {} (in the boundary's coordinates) is an edge of \
                     {shared}, and the medium inside it would be invisible or wrong",
                    Num::v3(from),
                    Num::v3(to)
                )
            }
            OpenSurface::Junction { from, to, other } => {
                let other = match self.quad_spans.get(&(other.0.0, other.1)) {
                    Some(s) => format!("the quad at {}", self.at(s.start)),
                    None => "another quad".to_owned(),
                };
                format!(
                    "the edge of {quad} from {} to {} (in the boundary's coordinates) runs along \
                     part of an edge of {other}, but the quads' edges along that line do not pair \
                     up (each stretch of an edge must be an edge of exactly one other quad, where \
                     edges meet corner to corner or one runs along part of another): the surface \
                     is open there or overlaps itself",
                    Num::v3(from),
                    Num::v3(to)
                )
            }
            OpenSurface::Sliver => format!(
                "two corners of {quad} are one corner (to within a part in 1e9 of its \
                 coordinates): it encloses no volume, and the medium inside it would be invisible"
            ),
            OpenSurface::Unchecked { levels } => format!(
                "its quads come in {levels} scales (powers of two apart), and finding which of their \
                 corners meet would take more than {} looks (stopped at {quad}): a medium's boundary \
                 needs far fewer kinds of quad",
                crate::closed_surface::MAX_LOOKUPS
            ),
            OpenSurface::UncheckedJunctions { edges } => format!(
                "{edges} edges of its quads are edges of no other quad, and finding which run along \
                 which (T-junctions) would take more than {} comparisons (stopped at {quad}): make \
                 the boundary's quads meet corner to corner",
                crate::closed_surface::MAX_LOOKUPS
            ),
            OpenSurface::Coincident => format!(
                "{quad} lies where another quad of the boundary does, and the two enclose no volume: \
                 the medium inside would be invisible"
            ),
        };
        format!("{ENCLOSE}; {why}")
    }

    /// Add group `g` to `into`, through an instance if it has a transform (`what`: the object at
    /// `span` that places it, for messages).
    fn add_placed(
        &mut self,
        into: GroupId,
        g: GroupId,
        steps: &[Step],
        span: &Span,
        what: &str,
    ) -> Result<(), Fail> {
        self.count(into, Some(g), span, what)?;
        if steps.is_empty() {
            self.b.add_to(into, Object::Group(g));
        } else {
            let t = self.compose(steps, span)?;
            self.b.instance(into, g, t);
        }
        Ok(())
    }

    /// An importance target: the name of a sphere or quad, or an inline `{ type = "sphere" | "quad" }`.
    /// The importance target an item of `lights` stands for: a name, or a sphere or quad written out.
    pub(super) fn light(&mut self, v: Val<'_>) -> Result<ImportanceTarget, Fail> {
        let span = v.span();
        if let Some(name) = v.get_ref().as_str() {
            return self.named_target(name, span);
        }
        let Typed { kind, table, span } = typed(v, "importance target", &["sphere", "quad"])?;
        let target = if kind == "sphere" {
            let d: TargetSphereDoc = de_table(table, &span)?;
            let r = positive(&d.radius, "radius")?;
            ImportanceTarget::Sphere(Sphere::new(d.center.0, r, NO_MATERIAL))
        } else {
            let d: TargetQuadDoc = de_table(table, &span)?;
            let (u, v) = (d.u.get_ref().0, d.v.get_ref().0);
            check_quad(u, v, &d.u, &d.v)?;
            match Quad::new(d.q.0, u, v, NO_MATERIAL) {
                Some(q) => ImportanceTarget::Quad(q),
                None => return fail(span, "degenerate quad"),
            }
        };
        Ok(target)
    }

    /// The importance target a name in `lights` stands for.
    fn named_target(&self, name: &str, span: Span) -> Result<ImportanceTarget, Fail> {
        match self.names.get(name) {
            Some((_, Named::Sphere(s))) => Ok(ImportanceTarget::Sphere(*s)),
            Some((_, Named::Quad(q))) => Ok(ImportanceTarget::Quad(*q)),
            Some((_, Named::Group(_))) => fail(
                span,
                format!(
                    "`{}` is a group or box; importance targets are spheres and quads",
                    crate::text::shown(name)
                ),
            ),
            Some((_, Named::Other(what))) => fail(
                span,
                format!(
                    "`{}` is {what}; importance targets are spheres and quads",
                    crate::text::shown(name)
                ),
            ),
            None => {
                let mut shapes: Vec<&str> = self
                    .names
                    .iter()
                    .filter(|(_, (_, n))| matches!(n, Named::Sphere(_) | Named::Quad(_)))
                    .map(|(k, _)| k.as_str())
                    .collect();
                shapes.sort_unstable();
                fail(
                    span,
                    format!(
                        "no object is named `{}`; {}",
                        crate::text::shown(name),
                        known("named spheres and quads", shapes.into_iter())
                    ),
                )
            }
        }
    }
}

/// Why a medium's boundary whose pieces `a` and `b` overlap or touch is refused (`exact`: whether
/// they were compared exactly, not by a surface of quads' bounding box).
fn touching_pieces(a: &Piece, b: &Piece, exact: bool) -> String {
    let name = |p: &Piece| match p.kind {
        PieceKind::Ball { center, radius } => {
            format!(
                "the sphere at {} of radius {}",
                Num::v3(center),
                Num(radius)
            )
        }
        PieceKind::MovingSphere { from, to, radius } => format!(
            "the sphere of radius {} moving from {} to {}",
            Num(radius),
            Num::v3(from),
            Num::v3(to)
        ),
        PieceKind::Box { axes, .. } if axes == glam::DMat3::IDENTITY => format!(
            "the box within {} to {}",
            Num::v3(p.bounds.min),
            Num::v3(p.bounds.max)
        ),
        PieceKind::Box { center, half, .. } => format!(
            "the turned box of size {} centred at {} (within {} to {})",
            Num::v3(half * 2.0),
            Num::v3(center),
            Num::v3(p.bounds.min),
            Num::v3(p.bounds.max)
        ),
        PieceKind::Quads { .. } => format!(
            "the quads within {} to {}",
            Num::v3(p.bounds.min),
            Num::v3(p.bounds.max)
        ),
    };
    let how = if exact {
        "overlap or touch"
    } else {
        "may overlap or touch (past 10^7 tests of quads, surfaces of quads are compared by their \
         bounding boxes)"
    };
    format!(
        "the pieces of a medium's boundary must lie apart, and {} and {} (in the boundary's \
         coordinates) {how}: a ray's crossings would no longer alternate in and out, and the \
         medium would be wrong where they meet; move them apart, or give each a medium of its own \
         (where media overlap, their densities add)",
        name(a),
        name(b)
    )
}

/// What a medium's boundary may be.
const ENCLOSE: &str = "a medium's boundary must enclose a volume (a sphere, a moving sphere, a box, a \
     group or instance of them, or quads that close a surface: each edge of each quad an edge of \
     exactly one other, or shared stretch by stretch where other quads' corners lie along it)";

/// A group's or box's label as the subject of a message: "this group `g`" where it is named, "the
/// group at line 20:1" where it is not (not "this the group at ...").
fn this(label: &str, named: bool) -> String {
    if named {
        format!("this {label}")
    } else {
        label.to_owned()
    }
}
