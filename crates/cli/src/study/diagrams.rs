//! `rtl study diagrams`: the book's geometric diagrams, drawn as SVG from the workspace's own code
//! (rtl-pdf's warps, bases and heuristics, the renderer's Russian roulette constants), so that a change
//! of convention redraws them.

use super::svg::{Anchor, Frame, P2, Svg, View, colour as c, legend};
use anyhow::{Context, ensure};
use clap::Args;
use glam::{DVec2, DVec3};
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use rtl_pdf::{Onb, mis, warp};
use std::f64::consts::{FRAC_PI_2, PI};
use std::path::PathBuf;

#[derive(Args)]
pub struct DiagramsArgs {
    /// Directory for the SVG files (default: a scratch directory, printed; the book's figures are
    /// book/src/figures).
    #[arg(long)]
    pub out: Option<PathBuf>,
}

/// One diagram: its file name (without `.svg`), what it shows, and how it is drawn.
type Draw = fn() -> anyhow::Result<Svg>;

const DIAGRAMS: &[(&str, &str, Draw)] = &[
    (
        "diagram-inverse-transform",
        "inverse transform sampling: u on the CDF's axis mapped to x",
        inverse_transform,
    ),
    ("diagram-solid-angle", "a patch's solid angle", solid_angle),
    (
        "diagram-cosine-directions",
        "cosine-weighted directions over the hemisphere",
        cosine_directions,
    ),
    ("diagram-onb", "the orthonormal basis u, v, w", onb),
    ("diagram-cone", "the cone towards a sphere", cone),
    (
        "diagram-quad-solid-angle",
        "the quad's area-to-solid-angle factor",
        quad_solid_angle,
    ),
    ("diagram-mixture", "the mixture of two densities", mixture),
    (
        "diagram-spherical-rectangle",
        "the spherical rectangle",
        spherical_rectangle,
    ),
    (
        "diagram-power-heuristic",
        "the power heuristic's weights",
        power_heuristic,
    ),
    (
        "diagram-russian-roulette",
        "Russian roulette",
        russian_roulette,
    ),
    (
        "diagram-nee-path",
        "a path with next-event estimation",
        nee_path,
    ),
    (
        "diagram-manifold",
        "the manifold connection through a glass sphere",
        manifold,
    ),
];

pub fn run(args: DiagramsArgs) -> anyhow::Result<()> {
    let out = super::out_dir(args.out, "diagrams")?;
    for (name, what, draw) in DIAGRAMS {
        let svg = draw().with_context(|| format!("drawing {name} ({what})"))?;
        svg.save(&out.join(format!("{name}.svg")))?;
        eprintln!("  {name}.svg: {what}");
    }
    eprintln!("wrote {} diagrams to {}", DIAGRAMS.len(), out.display());
    Ok(())
}

fn title(svg: &mut Svg, width: f64, s: &str) {
    svg.text((width / 2.0, 26.0), s, 17.0, Anchor::Middle, c::INK);
}

fn italic(svg: &mut Svg, p: P2, s: &str, size: f64, anchor: Anchor, fill: &str) {
    svg.text_styled(p, s, size, anchor, fill, r#"font-style="italic""#);
}

/// Chapter 3: the density `p(x) = x / 2` on `[0, 2]`, its CDF `F(x) = x^2 / 4`, and five values of `u`
/// carried across to the curve and down to `x = F^-1(u) = 2 sqrt(u)`.
fn inverse_transform() -> anyhow::Result<Svg> {
    let (w, h) = (760.0, 400.0);
    let mut s = Svg::new(w, h);
    title(&mut s, w, "Inverse transform sampling: x = F⁻¹(u)");
    let density = Frame {
        left: 70.0,
        top: 60.0,
        w: 250.0,
        h: 260.0,
        x0: 0.0,
        x1: 2.0,
        y0: 0.0,
        y1: 1.0,
    };
    density.axes(
        &mut s,
        &[0.0, 0.5, 1.0, 1.5, 2.0],
        &[0.0, 0.5, 1.0],
        "x",
        "p(x)",
    );
    let pts: Vec<P2> = std::iter::once(density.at(0.0, 0.0))
        .chain((0..=40).map(|i| {
            let x = 2.0 * i as f64 / 40.0;
            density.at(x, x / 2.0)
        }))
        .chain(std::iter::once(density.at(2.0, 0.0)))
        .collect();
    s.polygon(&pts, c::SKY, 0.35, c::BLUE, 2.5);
    italic(
        &mut s,
        density.at(0.55, 0.62),
        "p(x) = x / 2",
        15.0,
        Anchor::Middle,
        c::BLUE,
    );

    let cdf = Frame {
        left: 450.0,
        ..density
    };
    cdf.axes(
        &mut s,
        &[0.0, 0.5, 1.0, 1.5, 2.0],
        &[0.0, 0.25, 0.5, 0.75, 1.0],
        "x",
        "u = F(x)",
    );
    cdf.curve(&mut s, |x| x * x / 4.0, 80, c::BLUE, 2.5);
    italic(
        &mut s,
        cdf.at(0.75, 0.55),
        "F(x) = x² / 4",
        15.0,
        Anchor::Middle,
        c::BLUE,
    );
    for &u in &[0.1, 0.3, 0.5, 0.7, 0.9] {
        let x = 2.0 * f64::sqrt(u);
        let on_curve = cdf.at(x, u);
        s.dot(cdf.at(0.0, u), 4.0, c::ORANGE);
        s.arrow(cdf.at(0.0, u), on_curve, c::ORANGE, 1.6);
        s.arrow(on_curve, cdf.at(x, 0.0), c::ORANGE, 1.6);
        s.dot(cdf.at(x, 0.0), 4.0, c::RED);
        // the same x marked under the density: equal steps of u land densely where p is large
        s.line(density.at(x, 0.0), density.at(x, x / 2.0), c::RED, 1.6);
        s.dot(density.at(x, 0.0), 4.0, c::RED);
    }
    s.text(
        (w / 2.0, h - 14.0),
        "equally spaced u (orange) land where p is large (vermilion): x = 2√u",
        13.0,
        Anchor::Middle,
        c::INK,
    );
    Ok(s)
}

/// Chapter 4: a patch `dA` at distance `r`, tilted by `theta` from the line of sight, projected onto
/// the unit sphere: `d omega = dA cos(theta) / r^2`.
fn solid_angle() -> anyhow::Result<Svg> {
    let (w, h) = (700.0, 430.0);
    let mut s = Svg::new(w, h);
    title(&mut s, w, "Solid angle of a patch: dω = dA cos θ / r²");
    let v = View::new(0.35, 0.28, 110.0, (150.0, 230.0));
    // the unit sphere: outline and equator
    s.polygon(
        &v.sphere_outline(DVec3::ZERO, 1.0),
        c::SKY,
        0.12,
        c::GREY,
        1.2,
    );
    s.dashed_polyline(
        &v.arc(DVec3::ZERO, DVec3::X, DVec3::Y, 1.0, 0.0, 2.0 * PI),
        c::LIGHT,
        1.0,
    );
    s.dot(v.at(DVec3::ZERO), 3.5, c::INK);
    italic(
        &mut s,
        (v.at(DVec3::ZERO).0 - 8.0, v.at(DVec3::ZERO).1 + 18.0),
        "o",
        15.0,
        Anchor::End,
        c::INK,
    );
    // the patch: centre at distance r along d, normal n tilted by theta away from -d
    let r = 3.0;
    // away from the viewer, so that the patch (facing o) faces the viewer too
    let d = (0.85 * v.right() - 0.55 * v.towards_viewer() + 0.1 * v.up()).normalize();
    let centre = r * d;
    let theta = 40f64.to_radians();
    // tilt the normal towards the viewer, so that the patch is seen nearly face-on
    let lean = (v.up() - d * v.up().dot(d)).normalize();
    let n = -d * theta.cos() + lean * theta.sin();
    let pn = Onb::new(n);
    let half = 0.5;
    let corners: Vec<DVec3> = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .iter()
        .map(|&(a, b)| centre + half * (a * pn.u() + b * pn.v()))
        .collect();
    for &k in &corners {
        s.dashed(v.at(DVec3::ZERO), v.at(k), c::GREY, 1.0);
    }
    let patch: Vec<P2> = corners.iter().map(|&k| v.at(k)).collect();
    s.polygon(&patch, c::ORANGE, 0.55, c::RED, 2.0);
    // its projection on the unit sphere: corners and edges normalised
    let mut proj = Vec::new();
    for i in 0..4 {
        let (a, b) = (corners[i], corners[(i + 1) % 4]);
        for k in 0..16 {
            let t = k as f64 / 16.0;
            proj.push(v.at((a + t * (b - a)).normalize()));
        }
    }
    s.polygon(&proj, c::BLUE, 0.6, c::BLUE, 1.5);
    s.line(v.at(DVec3::ZERO), v.at(centre), c::INK, 1.3);
    italic(
        &mut s,
        v.at(0.7 * centre + DVec3::new(0.0, 0.0, 0.1)),
        "r",
        16.0,
        Anchor::Middle,
        c::INK,
    );
    s.arrow(v.at(centre), v.at(centre + 0.9 * n), c::RED, 2.0);
    italic(
        &mut s,
        (v.at(centre + 0.9 * n).0 + 6.0, v.at(centre + 0.9 * n).1),
        "n",
        15.0,
        Anchor::Start,
        c::RED,
    );
    s.dashed(v.at(centre), v.at(centre - 0.9 * d), c::RED, 1.2);
    // the angle theta between n and the direction back to o
    let back = -d;
    let side = (n - back * n.dot(back)).normalize();
    s.polyline(&v.arc(centre, back, side, 0.45, 0.0, theta), c::RED, 1.4);
    italic(
        &mut s,
        v.at(centre + 0.6 * (back + 0.5 * side).normalize()),
        "θ",
        15.0,
        Anchor::Middle,
        c::RED,
    );
    s.text(
        (patch[2].0 + 12.0, patch[2].1 - 4.0),
        "dA",
        15.0,
        Anchor::Start,
        c::RED,
    );
    s.text(
        (v.at(DVec3::ZERO).0, v.at(DVec3::ZERO).1 - 128.0),
        "unit sphere around o",
        13.0,
        Anchor::Middle,
        c::GREY,
    );
    s.text(
        (proj[8].0 + 18.0, proj[8].1 - 24.0),
        "dω",
        15.0,
        Anchor::Start,
        c::BLUE,
    );
    s.text(
        (w - 20.0, h - 40.0),
        "the patch, seen from o, covers the blue area dω of the unit sphere:",
        13.0,
        Anchor::End,
        c::INK,
    );
    s.text(
        (w - 20.0, h - 20.0),
        "its area shrinks with r² and with the tilt cos θ",
        13.0,
        Anchor::End,
        c::INK,
    );
    Ok(s)
}

/// Chapter 7: directions from `warp::sample_cosine_hemisphere`, and the density `cos(theta) / pi`
/// against the uniform `1 / (2 pi)` in the plane of the normal.
fn cosine_directions() -> anyhow::Result<Svg> {
    let (w, h) = (800.0, 400.0);
    let mut s = Svg::new(w, h);
    title(&mut s, w, "Cosine-weighted directions: p(ω) = cos θ / π");
    let v = View::new(0.5, 0.35, 150.0, (200.0, 290.0));
    let horizon = v.arc(DVec3::ZERO, DVec3::X, DVec3::Y, 1.0, 0.0, 2.0 * PI);
    s.polygon(&horizon, c::LIGHT, 0.5, c::GREY, 1.0);
    let silhouette_axis = {
        let t = v.towards_viewer();
        DVec3::new(-t.y, t.x, 0.0).normalize()
    };
    s.polyline(
        &v.arc(DVec3::ZERO, silhouette_axis, DVec3::Z, 1.0, 0.0, PI),
        c::GREY,
        1.2,
    );
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(7);
    let mut back = Vec::new();
    let mut front = Vec::new();
    for _ in 0..400 {
        let d = warp::sample_cosine_hemisphere(DVec2::new(rng.random(), rng.random()));
        if v.faces(d) {
            front.push(d)
        } else {
            back.push(d)
        }
    }
    for d in back {
        s.dot(v.at(d), 2.0, c::SKY);
    }
    for d in front {
        s.dot(v.at(d), 2.4, c::BLUE);
    }
    s.arrow(v.at(DVec3::ZERO), v.at(1.35 * DVec3::Z), c::RED, 2.2);
    italic(
        &mut s,
        (v.at(1.35 * DVec3::Z).0 + 8.0, v.at(1.35 * DVec3::Z).1 + 6.0),
        "n",
        16.0,
        Anchor::Start,
        c::RED,
    );
    s.text(
        (200.0, h - 16.0),
        "400 directions from rtl-pdf's cosine warp",
        13.0,
        Anchor::Middle,
        c::INK,
    );

    // right: polar plot in the plane of the normal, radius = density
    let (ox, oy) = (590.0, 320.0);
    let scale = 700.0; // pixels per unit density
    let polar = |theta: f64, r: f64| (ox + scale * r * theta.sin(), oy - scale * r * theta.cos());
    s.line((ox - 190.0, oy), (ox + 190.0, oy), c::INK, 1.2);
    let cos_pts: Vec<P2> = (0..=90)
        .map(|i| {
            let t = -FRAC_PI_2 + PI * i as f64 / 90.0;
            polar(t, warp::cosine_hemisphere_pdf(t.cos()))
        })
        .collect();
    s.polygon(&cos_pts, c::BLUE, 0.2, c::BLUE, 2.5);
    let uni_pts: Vec<P2> = (0..=90)
        .map(|i| polar(-FRAC_PI_2 + PI * i as f64 / 90.0, 1.0 / (2.0 * PI)))
        .collect();
    s.dashed_polyline(&uni_pts, c::ORANGE, 2.0);
    let t = 50f64.to_radians();
    let r_t = warp::cosine_hemisphere_pdf(t.cos());
    s.line((ox, oy), polar(t, r_t), c::GREY, 1.0);
    s.dot(polar(t, r_t), 3.5, c::BLUE);
    s.polyline(
        &(0..=20)
            .map(|i| polar(t * i as f64 / 20.0, 0.09))
            .collect::<Vec<_>>(),
        c::GREY,
        1.0,
    );
    italic(
        &mut s,
        polar(t * 0.5, 0.115),
        "θ",
        14.0,
        Anchor::Middle,
        c::INK,
    );
    s.arrow((ox, oy), (ox, oy - scale * 0.37), c::RED, 2.0);
    italic(
        &mut s,
        (ox + 8.0, oy - scale * 0.37 + 10.0),
        "n",
        16.0,
        Anchor::Start,
        c::RED,
    );
    legend(
        &mut s,
        (ox - 190.0, oy + 30.0),
        &[(c::BLUE, "cos θ / π"), (c::ORANGE, "uniform: 1 / (2π)")],
    );
    s.text(
        (ox + 190.0, 60.0),
        "density as radius,",
        13.0,
        Anchor::End,
        c::INK,
    );
    s.text(
        (ox + 190.0, 78.0),
        "in the plane of n",
        13.0,
        Anchor::End,
        c::INK,
    );
    Ok(s)
}

/// Chapter 8: `Onb::new(w)` for a tilted normal: `u`, `v`, `w` right-handed, and a direction given by
/// local coordinates.
fn onb() -> anyhow::Result<Svg> {
    let (w, h) = (680.0, 440.0);
    let mut s = Svg::new(w, h);
    title(&mut s, w, "An orthonormal basis built from one vector w");
    let v = View::new(0.6, 0.3, 150.0, (330.0, 290.0));
    let normal = DVec3::new(0.45, -0.3, 0.84).normalize();
    let b = Onb::new(normal);
    let (bu, bv, bw) = (b.u(), b.v(), b.w());
    ensure!(
        (bu.cross(bv) - bw).length() < 1e-12,
        "Onb::new gives a left-handed basis: u x v = {:?}, w = {bw:?}",
        bu.cross(bv)
    );
    ensure!(
        bu.dot(bv).abs() < 1e-12 && bu.dot(bw).abs() < 1e-12,
        "Onb::new is not orthogonal"
    );
    // the surface: a square in the plane of u and v
    let sq: Vec<P2> = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .iter()
        .map(|&(x, y)| v.at(0.9 * (x * bu + y * bv)))
        .collect();
    s.polygon(&sq, c::YELLOW, 0.35, c::GREY, 1.0);
    let o = v.at(DVec3::ZERO);
    // a direction in local coordinates (x, y, z) and its image x u + y v + z w
    let local = DVec3::new(0.6, -0.5, 0.62).normalize();
    let a = b.transform(local);
    ensure!(
        (b.to_local(a) - local).length() < 1e-12,
        "Onb::to_local does not invert Onb::transform"
    );
    let foot = local.x * bu + local.y * bv;
    s.dashed(o, v.at(foot), c::PURPLE, 1.2);
    s.dashed(v.at(foot), v.at(a), c::PURPLE, 1.2);
    s.dashed(v.at(local.x * bu), v.at(foot), c::PURPLE, 1.0);
    s.dashed(v.at(local.y * bv), v.at(foot), c::PURPLE, 1.0);
    s.arrow(o, v.at(a), c::PURPLE, 2.2);
    italic(
        &mut s,
        (v.at(a).0 - 8.0, v.at(a).1 - 10.0),
        "a = x u + y v + z w",
        14.0,
        Anchor::End,
        c::PURPLE,
    );
    for (axis, col, name) in [(bu, c::RED, "u"), (bv, c::GREEN, "v"), (bw, c::BLUE, "w")] {
        let tip = v.at(1.2 * axis);
        s.arrow(o, tip, col, 2.8);
        let dx = tip.0 - o.0;
        let dy = tip.1 - o.1;
        let l = (dx * dx + dy * dy).sqrt();
        italic(
            &mut s,
            (tip.0 + 16.0 * dx / l, tip.1 + 16.0 * dy / l + 5.0),
            name,
            18.0,
            Anchor::Middle,
            col,
        );
    }
    s.dot(o, 3.5, c::INK);
    // the world axes, small, in the corner
    let corner = View::new(0.6, 0.3, 40.0, (70.0, 390.0));
    for (axis, name) in [(DVec3::X, "x"), (DVec3::Y, "y"), (DVec3::Z, "z")] {
        let tip = corner.at(axis);
        s.arrow(corner.at(DVec3::ZERO), tip, c::GREY, 1.5);
        italic(
            &mut s,
            (tip.0 + 4.0, tip.1 - 3.0),
            name,
            13.0,
            Anchor::Start,
            c::GREY,
        );
    }
    s.text(
        (w - 16.0, h - 36.0),
        "right-handed: u × v = w (checked when drawn)",
        13.0,
        Anchor::End,
        c::INK,
    );
    s.text(
        (w - 16.0, h - 16.0),
        "w = (0.45, -0.3, 0.84) / |…|, u and v from rtl-pdf's Onb::new",
        13.0,
        Anchor::End,
        c::INK,
    );
    Ok(s)
}

/// Chapter 9: the cone of directions from `p` towards a sphere of radius `R` at distance `d`:
/// `sin(theta_max) = R / d`, the cone's edges tangent to the sphere.
fn cone() -> anyhow::Result<Svg> {
    let (w, h) = (760.0, 400.0);
    let mut s = Svg::new(w, h);
    title(&mut s, w, "The cone towards a sphere: sin θmax = R / d");
    let p: P2 = (90.0, 220.0);
    let centre: P2 = (520.0, 220.0);
    let radius: f64 = 130.0;
    let dist = centre.0 - p.0;
    let sin_max = radius / dist;
    let theta_max = sin_max.asin();
    // tangent points: the radius to them is perpendicular to the line from p
    let phi = (radius / dist).acos(); // angle at the centre between c->p and c->T
    let tangent = |sign: f64| {
        (
            centre.0 - radius * phi.cos(),
            centre.1 - sign * radius * phi.sin(),
        )
    };
    let (t1, t2) = (tangent(1.0), tangent(-1.0));
    let reach = dist * theta_max.cos();
    ensure!(
        ((t1.0 - p.0).hypot(t1.1 - p.1) - reach).abs() < 1e-9,
        "the cone's edge does not touch the sphere"
    );
    s.polygon(&[p, t1, t2], c::ORANGE, 0.25, "none", 0.0);
    s.circle(centre, radius, c::SKY, c::BLUE, 2.0);
    s.line(p, t1, c::ORANGE, 2.2);
    s.line(p, t2, c::ORANGE, 2.2);
    // directions from the cone warp, drawn in the plane through p and c
    let omc = warp::cone_one_minus_cos(sin_max * sin_max);
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(9);
    for _ in 0..14 {
        let d = warp::sample_uniform_cone(DVec2::new(rng.random(), rng.random()), omc);
        // in the cone's frame z is the axis; draw its angle from the axis, on the side of d.x
        let ang = d.z.clamp(-1.0, 1.0).acos() * d.x.signum();
        let len = reach * 0.8;
        s.line(
            p,
            (p.0 + len * ang.cos(), p.1 - len * ang.sin()),
            c::ORANGE,
            0.8,
        );
    }
    // right angles at the tangent points
    for (t, sign) in [(t1, 1.0), (t2, -1.0)] {
        let to_c = ((centre.0 - t.0) / radius, (centre.1 - t.1) / radius);
        let to_p = ((p.0 - t.0) / reach, (p.1 - t.1) / reach);
        let k = 12.0;
        let a = (t.0 + k * to_c.0, t.1 + k * to_c.1);
        let b = (t.0 + k * to_p.0, t.1 + k * to_p.1);
        s.polyline(&[a, (a.0 + k * to_p.0, a.1 + k * to_p.1), b], c::INK, 1.0);
        let _ = sign;
    }
    s.line(centre, t1, c::BLUE, 1.5);
    italic(
        &mut s,
        ((centre.0 + t1.0) / 2.0 + 10.0, (centre.1 + t1.1) / 2.0),
        "R",
        16.0,
        Anchor::Start,
        c::BLUE,
    );
    s.dashed(p, centre, c::INK, 1.2);
    italic(
        &mut s,
        ((p.0 + centre.0) / 2.0 + 40.0, centre.1 + 20.0),
        "d",
        16.0,
        Anchor::Middle,
        c::INK,
    );
    // theta_max arc at p
    let arc_r = 90.0;
    let arc: Vec<P2> = (0..=30)
        .map(|i| {
            let a = theta_max * i as f64 / 30.0;
            (p.0 + arc_r * a.cos(), p.1 - arc_r * a.sin())
        })
        .collect();
    s.polyline(&arc, c::RED, 1.8);
    italic(
        &mut s,
        (p.0 + arc_r + 8.0, p.1 - 12.0),
        "θmax",
        15.0,
        Anchor::Start,
        c::RED,
    );
    s.dot(p, 4.5, c::INK);
    italic(
        &mut s,
        (p.0 - 10.0, p.1 + 5.0),
        "p",
        16.0,
        Anchor::End,
        c::INK,
    );
    s.dot(centre, 3.5, c::BLUE);
    italic(
        &mut s,
        (centre.0 + 8.0, centre.1 + 18.0),
        "c",
        16.0,
        Anchor::Start,
        c::BLUE,
    );
    s.text(
        (w / 2.0, h - 40.0),
        "edges tangent to the sphere; the cone's solid angle is 2π (1 − cos θmax)",
        13.0,
        Anchor::Middle,
        c::INK,
    );
    s.text(
        (w / 2.0, h - 20.0),
        "thin lines: directions from rtl-pdf's cone warp, uniform in solid angle inside it",
        13.0,
        Anchor::Middle,
        c::INK,
    );
    Ok(s)
}

/// Chapter 9: a light quad's patch `dA` at distance `r`, seen at angle `theta'` from its normal:
/// `p_omega = p_A r^2 / |cos theta'|`.
fn quad_solid_angle() -> anyhow::Result<Svg> {
    let (w, h) = (720.0, 420.0);
    let mut s = Svg::new(w, h);
    title(
        &mut s,
        w,
        "From area to solid angle: p(ω) = p(A) d² / |cos θₗ|",
    );
    // cross-section: the ceiling light from x = 330..560 at y = 90, the point p on the floor
    let (lx0, lx1, ly): (f64, f64, f64) = (330.0, 560.0, 90.0);
    let floor = 300.0;
    const HALF: f64 = 40.0;
    s.rect((60.0, floor), (680.0, floor + 10.0), c::LIGHT, 1.0, "none");
    s.rect((lx0, ly - 8.0), (lx1, ly), c::YELLOW, 1.0, c::ORANGE);
    s.text(
        ((lx0 + lx1) / 2.0, ly - 16.0),
        "light quad, area A, p(A) = 1 / A",
        13.0,
        Anchor::Middle,
        c::INK,
    );
    let p: P2 = (180.0, floor);
    let q: P2 = (480.0, ly);
    let (dx, dy) = (q.0 - p.0, q.1 - p.1);
    let r = dx.hypot(dy);
    // the patch dA around q, and its normal pointing down into the room
    s.line((q.0 - HALF, ly), (q.0 + HALF, ly), c::RED, 5.0);
    s.text((q.0 + 26.0, ly + 20.0), "dA", 15.0, Anchor::Start, c::RED);
    s.arrow(q, (q.0, ly + 90.0), c::RED, 2.0);
    italic(
        &mut s,
        (q.0 + 8.0, ly + 92.0),
        "n′",
        15.0,
        Anchor::Start,
        c::RED,
    );
    s.line(p, q, c::BLUE, 2.0);
    italic(
        &mut s,
        ((p.0 + q.0) / 2.0 - 12.0, (p.1 + q.1) / 2.0 - 6.0),
        "d",
        16.0,
        Anchor::End,
        c::BLUE,
    );
    // theta' at q between n' (down) and the direction to p
    let a_down = FRAC_PI_2; // page angle of straight down
    let a_to_p = (p.1 - q.1).atan2(p.0 - q.0);
    let arc: Vec<P2> = (0..=30)
        .map(|i| {
            let a = a_down + (a_to_p - a_down) * i as f64 / 30.0;
            (q.0 + 55.0 * a.cos(), q.1 + 55.0 * a.sin())
        })
        .collect();
    s.polyline(&arc, c::RED, 1.5);
    let mid = (a_down + a_to_p) / 2.0;
    italic(
        &mut s,
        (q.0 + 72.0 * mid.cos(), q.1 + 72.0 * mid.sin() + 5.0),
        "θₗ",
        15.0,
        Anchor::Middle,
        c::RED,
    );
    // the solid angle at p: the patch's edges seen from p, cut by a small circle
    let edge = |x: f64| ((x - p.0), (ly - p.1));
    let a0 = edge(q.0 - HALF).1.atan2(edge(q.0 - HALF).0);
    let a1 = edge(q.0 + HALF).1.atan2(edge(q.0 + HALF).0);
    let rr = 110.0;
    s.polygon(
        &[
            p,
            (p.0 + rr * a0.cos(), p.1 + rr * a0.sin()),
            (p.0 + rr * a1.cos(), p.1 + rr * a1.sin()),
        ],
        c::BLUE,
        0.5,
        c::BLUE,
        1.0,
    );
    s.dashed(p, (q.0 - HALF, ly), c::GREY, 1.0);
    s.dashed(p, (q.0 + HALF, ly), c::GREY, 1.0);
    s.text((p.0 + 46.0, p.1 - 96.0), "dω", 15.0, Anchor::End, c::BLUE);
    s.dot(p, 4.5, c::INK);
    italic(
        &mut s,
        (p.0 - 8.0, p.1 - 8.0),
        "p",
        16.0,
        Anchor::End,
        c::INK,
    );
    let cos_t = (-dy) / r; // n' = (0, +1) on the page (down), direction to p = -(dx, dy)/r
    s.text(
        (w / 2.0, h - 60.0),
        &format!(
            "dω = dA |cos θₗ| / d²: a point uniform on the quad has p(ω) = d² / (A |cos θₗ|) (here cos θₗ = {cos_t:.2})"
        ),
        13.0,
        Anchor::Middle,
        c::INK,
    );
    s.text(
        (w / 2.0, h - 36.0),
        "rtl-pdf: warp::area_to_solid_angle(p_A, origin, point, normal)",
        13.0,
        Anchor::Middle,
        c::INK,
    );
    Ok(s)
}

/// Chapter 10: the cosine density and a light's cone density, and their 50/50 mixture, along the
/// plane through the normal and the light (all per steradian).
fn mixture() -> anyhow::Result<Svg> {
    let (w, h) = (720.0, 420.0);
    let mut s = Svg::new(w, h);
    title(
        &mut s,
        w,
        "A mixture of two densities: p = ½ p_cos + ½ p_light",
    );
    let f = Frame {
        left: 90.0,
        top: 56.0,
        w: 420.0,
        h: 280.0,
        x0: -90.0,
        x1: 90.0,
        y0: 0.0,
        y1: 1.4,
    };
    f.axes(
        &mut s,
        &[-90.0, -60.0, -30.0, 0.0, 30.0, 60.0, 90.0],
        &[0.0, 0.2, 0.4, 0.6, 0.8, 1.0, 1.2, 1.4],
        "angle from the normal, in the plane through the light (degrees)",
        "density per steradian",
    );
    let light_at = 40f64.to_radians();
    let half = 30f64.to_radians();
    let omc = warp::cone_one_minus_cos(half.sin().powi(2));
    let cos_pdf = |deg: f64| warp::cosine_hemisphere_pdf(deg.to_radians().cos());
    let light_pdf = |deg: f64| {
        if (deg.to_radians() - light_at).abs() <= half {
            warp::uniform_cone_pdf(omc)
        } else {
            0.0
        }
    };
    f.curve(&mut s, cos_pdf, 360, c::BLUE, 2.5);
    f.curve(&mut s, light_pdf, 1440, c::ORANGE, 2.5);
    f.curve(
        &mut s,
        |x| 0.5 * cos_pdf(x) + 0.5 * light_pdf(x),
        1440,
        c::INK,
        3.0,
    );
    legend(
        &mut s,
        (530.0, 80.0),
        &[
            (c::BLUE, "p_cos = cos θ / π"),
            (c::ORANGE, "p_light: cone, 30°"),
            (c::INK, "½ p_cos + ½ p_light"),
        ],
    );
    s.text(
        (530.0, 170.0),
        "half the samples go to",
        13.0,
        Anchor::Start,
        c::INK,
    );
    s.text(
        (530.0, 188.0),
        "the light, half follow the",
        13.0,
        Anchor::Start,
        c::INK,
    );
    s.text(
        (530.0, 206.0),
        "material; the mixture is",
        13.0,
        Anchor::Start,
        c::INK,
    );
    s.text(
        (530.0, 224.0),
        "positive wherever either is,",
        13.0,
        Anchor::Start,
        c::INK,
    );
    s.text(
        (530.0, 242.0),
        "so indirect light is still",
        13.0,
        Anchor::Start,
        c::INK,
    );
    s.text(
        (530.0, 260.0),
        "reached (no bias)",
        13.0,
        Anchor::Start,
        c::INK,
    );
    let peak = warp::uniform_cone_pdf(omc);
    s.text(
        (w / 2.0, h - 14.0),
        &format!("inside the light's cone (half-angle 30°, centred 40° off the normal) p_light = 1 / (2π (1 − cos 30°)) = {peak:.2}"),
        13.0,
        Anchor::Middle,
        c::INK,
    );
    Ok(s)
}

/// The spherical rectangle (Urena et al. 2013): a rectangle's projection onto the unit sphere about
/// `p`, with points uniform in solid angle (`SphericalRectangle::sample`) and where they land on the
/// rectangle.
fn spherical_rectangle() -> anyhow::Result<Svg> {
    let (w, h) = (720.0, 460.0);
    let mut s = Svg::new(w, h);
    title(
        &mut s,
        w,
        "The spherical rectangle: directions uniform in solid angle",
    );
    let v = View::new(-0.5, 0.32, 120.0, (300.0, 330.0));
    let q = DVec3::new(-0.6, 0.2, 1.6);
    let ex = DVec3::new(2.6, 0.0, 0.0);
    let ey = DVec3::new(0.0, 1.4, 0.0);
    let rect = warp::SphericalRectangle::new(DVec3::ZERO, q, ex, ey)
        .context("the rectangle has no solid angle from p")?;
    // the hemisphere about p
    s.polygon(
        &v.arc(DVec3::ZERO, DVec3::X, DVec3::Y, 1.0, 0.0, 2.0 * PI),
        c::LIGHT,
        0.4,
        c::GREY,
        1.0,
    );
    let t = v.towards_viewer();
    let sil = DVec3::new(-t.y, t.x, 0.0).normalize();
    s.polyline(
        &v.arc(DVec3::ZERO, sil, DVec3::Z, 1.0, 0.0, PI),
        c::GREY,
        1.0,
    );
    let corners = [q, q + ex, q + ex + ey, q + ey];
    s.polygon(&corners.map(|k| v.at(k)), c::YELLOW, 0.4, c::ORANGE, 2.0);
    let mut outline = Vec::new();
    for i in 0..4 {
        let (a, b) = (corners[i], corners[(i + 1) % 4]);
        for k in 0..24 {
            outline.push(v.at((a + (b - a) * (k as f64 / 24.0)).normalize()));
        }
    }
    s.polygon(&outline, c::SKY, 0.45, c::BLUE, 1.8);
    for k in corners {
        s.dashed(v.at(DVec3::ZERO), v.at(k), c::GREY, 0.8);
    }
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(3);
    for _ in 0..250 {
        let u = DVec2::new(rng.random(), rng.random());
        let point = rect.sample(u);
        s.dot(v.at(point), 1.8, c::RED);
        s.dot(v.at(point.normalize()), 1.6, c::BLUE);
    }
    s.dot(v.at(DVec3::ZERO), 4.0, c::INK);
    italic(
        &mut s,
        (v.at(DVec3::ZERO).0 - 8.0, v.at(DVec3::ZERO).1 + 16.0),
        "p",
        16.0,
        Anchor::End,
        c::INK,
    );
    let solid = rect.solid_angle();
    s.text(
        (w - 20.0, 80.0),
        &format!("solid angle S = {solid:.3} sr"),
        13.0,
        Anchor::End,
        c::INK,
    );
    s.text(
        (w - 20.0, 98.0),
        "density 1 / S per steradian",
        13.0,
        Anchor::End,
        c::INK,
    );
    s.text(
        (w / 2.0, h - 38.0),
        "blue: 250 directions, uniform on the rectangle's projection onto the unit sphere;",
        13.0,
        Anchor::Middle,
        c::INK,
    );
    s.text(
        (w / 2.0, h - 18.0),
        "red: the same samples on the light, denser where it is far and seen edge-on",
        13.0,
        Anchor::Middle,
        c::INK,
    );
    Ok(s)
}

/// The power heuristic's weight `w_f = f^2 / (f^2 + g^2)` against the balance heuristic's `f / (f + g)`,
/// as functions of `t = f / (f + g)`.
fn power_heuristic() -> anyhow::Result<Svg> {
    let (w, h) = (680.0, 420.0);
    let mut s = Svg::new(w, h);
    title(&mut s, w, "Weights of multiple importance sampling");
    let f = Frame {
        left: 90.0,
        top: 56.0,
        w: 340.0,
        h: 280.0,
        x0: 0.0,
        x1: 1.0,
        y0: 0.0,
        y1: 1.0,
    };
    f.axes(
        &mut s,
        &[0.0, 0.25, 0.5, 0.75, 1.0],
        &[0.0, 0.25, 0.5, 0.75, 1.0],
        "share of the density p_f / (p_f + p_g)",
        "weight",
    );
    f.curve(
        &mut s,
        |t| mis::balance_heuristic(1.0, t, 1.0, 1.0 - t),
        200,
        c::ORANGE,
        2.5,
    );
    f.curve(
        &mut s,
        |t| mis::power_heuristic(1.0, t, 1.0, 1.0 - t),
        200,
        c::BLUE,
        3.0,
    );
    f.curve(
        &mut s,
        |t| mis::power_heuristic(1.0, 1.0 - t, 1.0, t),
        200,
        c::SKY,
        2.0,
    );
    legend(
        &mut s,
        (450.0, 80.0),
        &[
            (c::BLUE, "power: p_f² / (p_f² + p_g²)"),
            (c::SKY, "power, strategy g"),
            (c::ORANGE, "balance: p_f / (p_f + p_g)"),
        ],
    );
    s.text(
        (450.0, 160.0),
        "each direction's weights sum",
        13.0,
        Anchor::Start,
        c::INK,
    );
    s.text(
        (450.0, 178.0),
        "to 1 (no bias); the power",
        13.0,
        Anchor::Start,
        c::INK,
    );
    s.text(
        (450.0, 196.0),
        "heuristic gives nearly all",
        13.0,
        Anchor::Start,
        c::INK,
    );
    s.text(
        (450.0, 214.0),
        "the weight to the strategy",
        13.0,
        Anchor::Start,
        c::INK,
    );
    s.text(
        (450.0, 232.0),
        "that is much more likely",
        13.0,
        Anchor::Start,
        c::INK,
    );
    s.text(
        (450.0, 250.0),
        "to make the direction",
        13.0,
        Anchor::Start,
        c::INK,
    );
    s.text(
        (w / 2.0, h - 14.0),
        "curves from rtl-pdf's mis::power_heuristic and mis::balance_heuristic",
        13.0,
        Anchor::Middle,
        c::INK,
    );
    Ok(s)
}

/// Russian roulette as the renderer plays it: from bounce `ROULETTE_AFTER` on, a path survives with
/// probability `q = min(1, throughput / ROULETTE_BELOW)` and its throughput is divided by `q`.
fn russian_roulette() -> anyhow::Result<Svg> {
    use rtl_render::integrator::{ROULETTE_AFTER, ROULETTE_BELOW};
    let (w, h) = (760.0, 440.0);
    let mut s = Svg::new(w, h);
    title(
        &mut s,
        w,
        "Russian roulette: survive with probability q, then divide by q",
    );
    let f = Frame {
        left: 90.0,
        top: 56.0,
        w: 380.0,
        h: 260.0,
        x0: 0.0,
        x1: 12.0,
        y0: 0.0,
        y1: 1.0,
    };
    f.axes(
        &mut s,
        &[0.0, 2.0, 4.0, 6.0, 8.0, 10.0, 12.0],
        &[0.0, 0.25, 0.5, 0.75, 1.0],
        "bounce",
        "probability",
    );
    // a path on white walls (albedo 0.73): throughput before roulette, and the survival probability
    let albedo: f64 = 0.73;
    let mut alive = 1.0;
    let mut prev: Option<(P2, P2)> = None;
    for k in 0..=12u32 {
        let throughput = albedo.powi(k as i32);
        let q = if k >= ROULETTE_AFTER {
            (throughput / ROULETTE_BELOW).min(1.0)
        } else {
            1.0
        };
        alive *= q;
        let a = f.at(k as f64, q);
        let b = f.at(k as f64, alive);
        s.dot(a, 4.0, c::BLUE);
        s.dot(b, 4.0, c::RED);
        if let Some((pa, pb)) = prev {
            s.line(pa, a, c::BLUE, 2.0);
            s.line(pb, b, c::RED, 2.0);
        }
        prev = Some((a, b));
    }
    let cut = (ROULETTE_BELOW.ln() / albedo.ln()).ceil();
    s.dashed(f.at(cut, 0.0), f.at(cut, 1.0), c::GREY, 1.0);
    s.text(
        f.at(cut + 0.2, 0.93),
        "throughput",
        12.0,
        Anchor::Start,
        c::GREY,
    );
    s.text(
        f.at(cut + 0.2, 0.87),
        &format!("< {ROULETTE_BELOW}"),
        12.0,
        Anchor::Start,
        c::GREY,
    );
    legend(
        &mut s,
        (490.0, 80.0),
        &[
            (c::BLUE, "q at this bounce"),
            (c::RED, "probability of reaching it"),
        ],
    );
    s.text(
        (490.0, 140.0),
        "white walls, albedo 0.73:",
        13.0,
        Anchor::Start,
        c::INK,
    );
    s.text(
        (490.0, 158.0),
        &format!("roulette from bounce {ROULETTE_AFTER},"),
        13.0,
        Anchor::Start,
        c::INK,
    );
    s.text(
        (490.0, 176.0),
        &format!("q = min(1, throughput / {ROULETTE_BELOW})"),
        13.0,
        Anchor::Start,
        c::INK,
    );
    // the estimator itself, as two branches
    let (bx, by) = (560.0, 250.0);
    s.text((bx - 40.0, by + 5.0), "X", 16.0, Anchor::End, c::INK);
    s.arrow((bx - 34.0, by), (bx + 60.0, by - 40.0), c::GREEN, 1.8);
    s.arrow((bx - 34.0, by), (bx + 60.0, by + 40.0), c::RED, 1.8);
    s.text(
        (bx + 66.0, by - 36.0),
        "X / q",
        15.0,
        Anchor::Start,
        c::GREEN,
    );
    s.text((bx + 10.0, by - 34.0), "q", 13.0, Anchor::End, c::GREEN);
    s.text((bx + 66.0, by + 46.0), "0", 15.0, Anchor::Start, c::RED);
    s.text((bx + 10.0, by + 44.0), "1 − q", 13.0, Anchor::End, c::RED);
    s.text(
        (bx + 40.0, by + 100.0),
        "E = q · X/q + (1 − q) · 0 = X",
        14.0,
        Anchor::Middle,
        c::INK,
    );
    s.text(
        (w / 2.0, h - 16.0),
        "unbiased: dark paths end early, bright ones carry on; constants from rtl-render's integrator",
        13.0,
        Anchor::Middle,
        c::INK,
    );
    Ok(s)
}

/// A path through a Cornell-box cross-section with next-event estimation: at every diffuse bounce a
/// shadow ray to a point on the light, plus the material-sampled continuation.
fn nee_path() -> anyhow::Result<Svg> {
    let (w, h) = (720.0, 470.0);
    let mut s = Svg::new(w, h);
    title(&mut s, w, "A path with next-event estimation");
    let (x0, x1, y0, y1) = (200.0, 620.0, 60.0, 400.0);
    // a Cornell box seen from the side: ceiling, back wall and floor; the front (left) is open
    s.polyline(&[(x0, y0), (x1, y0), (x1, y1), (x0, y1)], c::INK, 2.0);
    s.dashed((x0, y0), (x0, y1), c::LIGHT, 1.0);
    s.text(
        (x0 + 4.0, y0 + 18.0),
        "ceiling",
        12.0,
        Anchor::Start,
        c::GREY,
    );
    s.text((x0 + 4.0, y1 - 8.0), "floor", 12.0, Anchor::Start, c::GREY);
    s.text_styled(
        (x1 + 16.0, 320.0),
        "back wall",
        12.0,
        Anchor::Middle,
        c::GREY,
        r#"transform="rotate(-90 636 320)""#,
    );
    let (l0, l1) = (360.0, 460.0);
    s.line((l0, y0 + 2.0), (l1, y0 + 2.0), c::ORANGE, 7.0);
    s.text(
        ((l0 + l1) / 2.0, y0 - 10.0),
        "light",
        13.0,
        Anchor::Middle,
        c::ORANGE,
    );
    // a sphere that blocks one shadow ray
    let blocker = (370.0, 264.0);
    s.circle(blocker, 22.0, c::LIGHT, c::GREY, 1.2);
    let cam = (70.0, 250.0);
    s.polygon(
        &[
            (cam.0 - 30.0, cam.1 - 16.0),
            (cam.0 - 30.0, cam.1 + 16.0),
            (cam.0, cam.1),
        ],
        c::GREY,
        1.0,
        "none",
        0.0,
    );
    s.text(
        (cam.0 - 15.0, cam.1 + 36.0),
        "camera",
        13.0,
        Anchor::Middle,
        c::INK,
    );
    let x = [(330.0, y1), (x1, 200.0), (520.0, y1)];
    let light_pts = [(430.0, y0), (380.0, y0), (370.0, y0)];
    let mut prev = cam;
    for (i, &p) in x.iter().enumerate() {
        s.arrow(prev, p, c::BLUE, 2.2);
        prev = p;
        let l = light_pts[i];
        if i == 0 {
            // occluded: the shadow ray stops at the sphere
            let t = (y1 - (blocker.1 + 22.0)) / (y1 - y0);
            let stop = (p.0 + t * (l.0 - p.0), p.1 + t * (l.1 - p.1));
            s.dashed(p, stop, c::GREY, 1.8);
            let m = stop;
            s.line((m.0 - 6.0, m.1 - 6.0), (m.0 + 6.0, m.1 + 6.0), c::INK, 2.0);
            s.line((m.0 - 6.0, m.1 + 6.0), (m.0 + 6.0, m.1 - 6.0), c::INK, 2.0);
        } else {
            s.dashed(p, l, c::ORANGE, 1.8);
            s.dot(l, 4.0, c::ORANGE);
        }
        s.dot(p, 5.0, c::INK);
        let label = format!("x{}", ["₁", "₂", "₃"][i]);
        let off = if p.0 >= x1 {
            (12.0, 4.0)
        } else if p.0 <= x0 {
            (-12.0, 4.0)
        } else {
            (0.0, 22.0)
        };
        let anchor = if p.0 >= x1 {
            Anchor::Start
        } else if p.0 <= x0 {
            Anchor::End
        } else {
            Anchor::Middle
        };
        italic(
            &mut s,
            (p.0 + off.0, p.1 + off.1),
            &label,
            15.0,
            anchor,
            c::INK,
        );
    }
    // the last bounce's material sample hits the light: weighted by MIS against the light sample
    s.arrow(x[2], (440.0, y0 + 3.0), c::BLUE, 2.2);
    s.dot((440.0, y0 + 3.0), 4.0, c::BLUE);
    legend(
        &mut s,
        (24.0, 320.0),
        &[(c::BLUE, "material samples"), (c::ORANGE, "shadow rays")],
    );
    s.text(
        (24.0, 370.0),
        "at each bounce: light",
        12.0,
        Anchor::Start,
        c::INK,
    );
    s.text(
        (24.0, 386.0),
        "sampled directly, weighted",
        12.0,
        Anchor::Start,
        c::INK,
    );
    s.text(
        (24.0, 402.0),
        "by the power heuristic",
        12.0,
        Anchor::Start,
        c::INK,
    );
    s.text(
        (w / 2.0, h - 36.0),
        "a shadow ray counts the light if nothing is in the way (grey: occluded); a material sample",
        13.0,
        Anchor::Middle,
        c::INK,
    );
    s.text(
        (w / 2.0, h - 16.0),
        "that hits the light counts it too, with the other weight, so the two never double-count",
        13.0,
        Anchor::Middle,
        c::INK,
    );
    Ok(s)
}

/// Chapter 12: the manifold connection through a glass sphere (index 1.5), in its plane, each path
/// found by the renderer's own solver ([`rtl_render::manifold::Interface::leaving`]): on the left
/// a point deep inside lit through the top by points across a light, on the right a point near the
/// surface that a point far behind it reaches through three refraction points.
fn manifold() -> anyhow::Result<Svg> {
    use rtl_render::manifold::Interface;
    let (w, h) = (900.0, 470.0);
    let mut s = Svg::new(w, h);
    title(
        &mut s,
        w,
        "Manifold next-event estimation: where light refracts out of the glass towards y",
    );
    let glass = Interface {
        centre: DVec3::ZERO,
        radius: 1.0,
        ior: 1.5,
        material: rtl_render::scene::MaterialId(0),
        filled: 0.0,
        clear: true,
        holds: true,
    };
    let scale = 95.0;
    // panel centres, in pixels
    let panels = [(190.0, 300.0), (730.0, 260.0)];
    let at = |k: usize, p: DVec3| (panels[k].0 + scale * p.x, panels[k].1 - scale * p.y);
    for &c in &panels {
        s.circle(c, scale, "#eef6fb", c::SKY, 2.0);
        s.text(
            (c.0, c.1 + scale + 22.0),
            "glass, index 1.5",
            12.0,
            Anchor::Middle,
            c::GREY,
        );
    }
    // Left: a light above, five points on it, one refraction point each.
    let p = DVec3::new(0.25, -0.35, 0.0);
    let (l0, l1) = (DVec3::new(-1.1, 2.3, 0.0), DVec3::new(0.7, 2.3, 0.0));
    s.line(at(0, l0), at(0, l1), c::ORANGE, 6.0);
    s.text(
        (at(0, l1).0 + 10.0, at(0, l1).1 + 4.0),
        "light",
        13.0,
        Anchor::Start,
        c::ORANGE,
    );
    for i in 0..5 {
        let y = l0 + (l1 - l0) * (0.1 + 0.2 * i as f64);
        let found = glass.leaving(p, y);
        ensure!(
            found.as_slice().len() == 1,
            "expected one refraction point towards the light, found {}",
            found.as_slice().len()
        );
        let r = found.as_slice()[0];
        s.line(at(0, p), at(0, r.x), c::BLUE, 1.8);
        s.arrow(at(0, r.x), at(0, y), c::ORANGE, 1.6);
        s.dot(at(0, r.x), 3.5, c::INK);
    }
    // the straight shadow ray, which meets the glass
    let y_mid = l0 + (l1 - l0) * 0.5;
    let hit = {
        let d = (y_mid - p).normalize();
        let b = p.dot(d);
        p + d * (-b + (b * b - p.length_squared() + 1.0).sqrt())
    };
    s.dashed(at(0, p), at(0, hit), c::GREY, 1.4);
    let m = at(0, hit);
    s.line((m.0 - 5.0, m.1 - 5.0), (m.0 + 5.0, m.1 + 5.0), c::INK, 2.0);
    s.line((m.0 - 5.0, m.1 + 5.0), (m.0 + 5.0, m.1 - 5.0), c::INK, 2.0);
    s.dot(at(0, p), 5.0, c::INK);
    italic(
        &mut s,
        (at(0, p).0 + 10.0, at(0, p).1 + 16.0),
        "p",
        16.0,
        Anchor::Start,
        c::INK,
    );
    // Right: a point near the surface, and one far behind it seen through the far side.
    let p = DVec3::new(0.97, 0.0, 0.0);
    let y = DVec3::new(-3.2, 0.74, 0.0);
    let found = glass.leaving(p, y);
    ensure!(
        found.as_slice().len() >= 2,
        "expected several refraction points, found {}",
        found.as_slice().len()
    );
    let colours = [c::BLUE, c::GREEN, c::PURPLE, c::RED];
    for (r, colour) in found.as_slice().iter().zip(colours) {
        s.line(at(1, p), at(1, r.x), colour, 1.8);
        s.arrow(at(1, r.x), at(1, y), colour, 1.6);
        s.dot(at(1, r.x), 3.5, c::INK);
    }
    s.dot(at(1, p), 5.0, c::INK);
    italic(
        &mut s,
        (at(1, p).0 - 8.0, at(1, p).1 + 18.0),
        "p",
        16.0,
        Anchor::End,
        c::INK,
    );
    s.dot(at(1, y), 6.0, c::ORANGE);
    italic(
        &mut s,
        (at(1, y).0 - 10.0, at(1, y).1 + 5.0),
        "y",
        16.0,
        Anchor::End,
        c::ORANGE,
    );
    s.text(
        (panels[1].0 - 120.0, 80.0),
        &format!(
            "near the surface, seen through the far side: {} refraction points",
            found.as_slice().len()
        ),
        13.0,
        Anchor::Middle,
        c::INK,
    );
    s.text(
        (panels[0].0, 62.0),
        "from deep inside: one refraction point for each y",
        13.0,
        Anchor::Middle,
        c::INK,
    );
    s.text(
        (w / 2.0, h - 34.0),
        "a shadow ray from p (grey) meets the glass; the connection instead solves for the point x where",
        13.0,
        Anchor::Middle,
        c::INK,
    );
    s.text(
        (w / 2.0, h - 14.0),
        "Snell's law bends the ray from p towards y: the stationary points of the optical length 1.5 |x - p| + |y - x|",
        13.0,
        Anchor::Middle,
        c::INK,
    );
    Ok(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_diagram_draws() {
        for (name, _, draw) in DIAGRAMS {
            let svg = draw().unwrap_or_else(|e| panic!("{name}: {e:#}")).finish();
            assert!(
                svg.starts_with("<svg") && svg.ends_with("</svg>\n"),
                "{name}"
            );
            assert!(!svg.contains("NaN"), "{name} has a NaN coordinate");
        }
        assert!(DIAGRAMS.len() >= 10);
    }
}
