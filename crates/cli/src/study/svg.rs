//! A small SVG writer for the book's diagrams and sample histograms: lines, arrows, shapes and text in
//! page coordinates (pixels, y down), a 2D plot frame with linear axes, and an orthographic view of 3D
//! space (right-handed, z up) for the sphere-of-directions pictures.

use glam::DVec3;
use std::fmt::Write as _;
use std::path::Path;

/// Colours shared by every figure (colour-blind safe: the Okabe-Ito palette).
pub mod colour {
    pub const INK: &str = "#222222";
    pub const GREY: &str = "#888888";
    pub const LIGHT: &str = "#dddddd";
    pub const BLUE: &str = "#0072b2";
    pub const ORANGE: &str = "#e69f00";
    pub const GREEN: &str = "#009e73";
    pub const RED: &str = "#d55e00";
    pub const PURPLE: &str = "#cc79a7";
    pub const SKY: &str = "#56b4e9";
    pub const YELLOW: &str = "#f0e442";
}

/// A point on the page, in pixels, y pointing down.
pub type P2 = (f64, f64);

/// Text placement relative to its anchor point.
#[derive(Clone, Copy)]
pub enum Anchor {
    Start,
    Middle,
    End,
}

/// An SVG document being written.
pub struct Svg {
    width: f64,
    height: f64,
    body: String,
}

fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

impl Svg {
    /// An empty white page of `width` x `height` pixels.
    pub fn new(width: f64, height: f64) -> Svg {
        Svg {
            width,
            height,
            body: String::new(),
        }
    }

    pub fn line(&mut self, a: P2, b: P2, stroke: &str, width: f64) {
        let _ = writeln!(
            self.body,
            r#"<line x1="{:.2}" y1="{:.2}" x2="{:.2}" y2="{:.2}" stroke="{stroke}" stroke-width="{width}" stroke-linecap="round"/>"#,
            a.0, a.1, b.0, b.1
        );
    }

    pub fn dashed(&mut self, a: P2, b: P2, stroke: &str, width: f64) {
        let _ = writeln!(
            self.body,
            r#"<line x1="{:.2}" y1="{:.2}" x2="{:.2}" y2="{:.2}" stroke="{stroke}" stroke-width="{width}" stroke-dasharray="6 4"/>"#,
            a.0, a.1, b.0, b.1
        );
    }

    fn points(pts: &[P2]) -> String {
        let mut s = String::new();
        for p in pts {
            let _ = write!(s, "{:.2},{:.2} ", p.0, p.1);
        }
        s
    }

    pub fn polyline(&mut self, pts: &[P2], stroke: &str, width: f64) {
        let _ = writeln!(
            self.body,
            r#"<polyline points="{}" fill="none" stroke="{stroke}" stroke-width="{width}" stroke-linejoin="round"/>"#,
            Self::points(pts)
        );
    }

    pub fn dashed_polyline(&mut self, pts: &[P2], stroke: &str, width: f64) {
        let _ = writeln!(
            self.body,
            r#"<polyline points="{}" fill="none" stroke="{stroke}" stroke-width="{width}" stroke-dasharray="5 4"/>"#,
            Self::points(pts)
        );
    }

    /// A closed polygon filled with `fill` at `opacity`, outlined with `stroke` (or "none").
    pub fn polygon(&mut self, pts: &[P2], fill: &str, opacity: f64, stroke: &str, width: f64) {
        let _ = writeln!(
            self.body,
            r#"<polygon points="{}" fill="{fill}" fill-opacity="{opacity}" stroke="{stroke}" stroke-width="{width}" stroke-linejoin="round"/>"#,
            Self::points(pts)
        );
    }

    pub fn rect(&mut self, a: P2, b: P2, fill: &str, opacity: f64, stroke: &str) {
        let (x0, x1) = (a.0.min(b.0), a.0.max(b.0));
        let (y0, y1) = (a.1.min(b.1), a.1.max(b.1));
        let _ = writeln!(
            self.body,
            r#"<rect x="{x0:.2}" y="{y0:.2}" width="{:.2}" height="{:.2}" fill="{fill}" fill-opacity="{opacity}" stroke="{stroke}" stroke-width="1"/>"#,
            x1 - x0,
            y1 - y0
        );
    }

    pub fn circle(&mut self, c: P2, r: f64, fill: &str, stroke: &str, width: f64) {
        let _ = writeln!(
            self.body,
            r#"<circle cx="{:.2}" cy="{:.2}" r="{r:.2}" fill="{fill}" stroke="{stroke}" stroke-width="{width}"/>"#,
            c.0, c.1
        );
    }

    /// A filled dot of radius `r`.
    pub fn dot(&mut self, c: P2, r: f64, fill: &str) {
        let _ = writeln!(
            self.body,
            r#"<circle cx="{:.2}" cy="{:.2}" r="{r:.2}" fill="{fill}"/>"#,
            c.0, c.1
        );
    }

    /// An arrow from `a` to `b` with a filled head at `b`.
    pub fn arrow(&mut self, a: P2, b: P2, stroke: &str, width: f64) {
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let len = (dx * dx + dy * dy).sqrt().max(1e-9);
        let (ux, uy) = (dx / len, dy / len);
        let head = (4.0 * width + 6.0).min(len * 0.5);
        let base = (b.0 - ux * head, b.1 - uy * head);
        let half = head * 0.42;
        self.line(a, base, stroke, width);
        self.polygon(
            &[
                b,
                (base.0 - uy * half, base.1 + ux * half),
                (base.0 + uy * half, base.1 - ux * half),
            ],
            stroke,
            1.0,
            "none",
            0.0,
        );
    }

    /// Text of `size` px at `p`; `style` is extra SVG attributes (e.g. `font-style="italic"`).
    pub fn text(&mut self, p: P2, s: &str, size: f64, anchor: Anchor, fill: &str) {
        self.text_styled(p, s, size, anchor, fill, "");
    }

    pub fn text_styled(
        &mut self,
        p: P2,
        s: &str,
        size: f64,
        anchor: Anchor,
        fill: &str,
        style: &str,
    ) {
        let a = match anchor {
            Anchor::Start => "start",
            Anchor::Middle => "middle",
            Anchor::End => "end",
        };
        let _ = writeln!(
            self.body,
            r#"<text x="{:.2}" y="{:.2}" font-size="{size}" text-anchor="{a}" fill="{fill}" {style}>{}</text>"#,
            p.0,
            p.1,
            esc(s)
        );
    }

    /// The document as text.
    pub fn finish(&self) -> String {
        format!(
            concat!(
                r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" "#,
                r#"font-family="DejaVu Sans, Verdana, Arial, sans-serif">"#,
                "\n",
                r#"<rect width="100%" height="100%" fill="white"/>"#,
                "\n{body}</svg>\n"
            ),
            w = self.width,
            h = self.height,
            body = self.body
        )
    }

    pub fn save(&self, path: &Path) -> anyhow::Result<()> {
        std::fs::write(path, self.finish())
            .map_err(|e| anyhow::anyhow!("writing {}: {e}", path.display()))
    }
}

/// A 2D plot frame: data coordinates `x0..x1`, `y0..y1` mapped into the page rectangle at `left, top`
/// of size `w` x `h`.
#[derive(Clone, Copy)]
pub struct Frame {
    pub left: f64,
    pub top: f64,
    pub w: f64,
    pub h: f64,
    pub x0: f64,
    pub x1: f64,
    pub y0: f64,
    pub y1: f64,
}

impl Frame {
    pub fn at(&self, x: f64, y: f64) -> P2 {
        (
            self.left + (x - self.x0) / (self.x1 - self.x0) * self.w,
            self.top + self.h - (y - self.y0) / (self.y1 - self.y0) * self.h,
        )
    }

    /// Axes with ticks at `xticks` and `yticks`, and axis labels set apart from the tick labels.
    pub fn axes(&self, svg: &mut Svg, xticks: &[f64], yticks: &[f64], xlabel: &str, ylabel: &str) {
        let bottom = self.top + self.h;
        for &x in xticks {
            let p = self.at(x, self.y0);
            svg.line((p.0, self.top), (p.0, bottom), colour::LIGHT, 0.8);
            svg.line(p, (p.0, bottom + 5.0), colour::INK, 1.0);
            svg.text(
                (p.0, bottom + 19.0),
                &tick(x),
                12.0,
                Anchor::Middle,
                colour::INK,
            );
        }
        for &y in yticks {
            let p = self.at(self.x0, y);
            svg.line(
                (self.left, p.1),
                (self.left + self.w, p.1),
                colour::LIGHT,
                0.8,
            );
            svg.line((self.left - 5.0, p.1), p, colour::INK, 1.0);
            svg.text(
                (self.left - 8.0, p.1 + 4.0),
                &tick(y),
                12.0,
                Anchor::End,
                colour::INK,
            );
        }
        svg.line(
            (self.left, bottom),
            (self.left + self.w, bottom),
            colour::INK,
            1.2,
        );
        svg.line((self.left, self.top), (self.left, bottom), colour::INK, 1.2);
        svg.text(
            (self.left + self.w / 2.0, bottom + 40.0),
            xlabel,
            14.0,
            Anchor::Middle,
            colour::INK,
        );
        let (lx, ly) = (self.left - 46.0, self.top + self.h / 2.0);
        svg.text_styled(
            (lx, ly),
            ylabel,
            14.0,
            Anchor::Middle,
            colour::INK,
            &format!(r#"transform="rotate(-90 {lx:.1} {ly:.1})""#),
        );
    }

    /// A function drawn as a polyline over `n` points of `x0..x1`.
    pub fn curve(&self, svg: &mut Svg, f: impl Fn(f64) -> f64, n: usize, stroke: &str, width: f64) {
        let pts: Vec<P2> = (0..=n)
            .map(|i| {
                let x = self.x0 + (self.x1 - self.x0) * i as f64 / n as f64;
                self.at(x, f(x).clamp(self.y0, self.y1))
            })
            .collect();
        svg.polyline(&pts, stroke, width);
    }
}

/// A tick label: short, without trailing zeros.
pub fn tick(v: f64) -> String {
    if v == 0.0 {
        return "0".into();
    }
    let s = format!("{v:.3}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    s.to_string()
}

/// A legend: one coloured swatch and label per entry, from `p` downwards.
pub fn legend(svg: &mut Svg, p: P2, entries: &[(&str, &str)]) {
    for (i, (c, label)) in entries.iter().enumerate() {
        let y = p.1 + 20.0 * i as f64;
        svg.line((p.0, y), (p.0 + 22.0, y), c, 3.0);
        svg.text(
            (p.0 + 28.0, y + 4.5),
            label,
            13.0,
            Anchor::Start,
            colour::INK,
        );
    }
}

/// An orthographic view of right-handed 3D space (z up), seen from azimuth `az` and elevation `el`
/// (radians), `scale` pixels per unit, world origin at page point `origin`.
#[derive(Clone, Copy)]
pub struct View {
    right: DVec3,
    up: DVec3,
    towards_viewer: DVec3,
    scale: f64,
    origin: P2,
}

impl View {
    pub fn new(az: f64, el: f64, scale: f64, origin: P2) -> View {
        let (sa, ca) = az.sin_cos();
        let (se, ce) = el.sin_cos();
        let right = DVec3::new(-sa, ca, 0.0);
        let up = DVec3::new(-se * ca, -se * sa, ce);
        let towards_viewer = DVec3::new(ce * ca, ce * sa, se);
        debug_assert!((right.cross(up) - towards_viewer).length() < 1e-12);
        View {
            right,
            up,
            towards_viewer,
            scale,
            origin,
        }
    }

    /// Page position of the world point `p`.
    pub fn at(&self, p: DVec3) -> P2 {
        (
            self.origin.0 + self.scale * p.dot(self.right),
            self.origin.1 - self.scale * p.dot(self.up),
        )
    }

    /// Whether the unit-sphere point `p` faces the viewer (is on the visible half of a sphere).
    pub fn faces(&self, p: DVec3) -> bool {
        p.dot(self.towards_viewer) >= 0.0
    }

    /// The world direction drawn to the right on the page.
    pub fn right(&self) -> DVec3 {
        self.right
    }

    /// The world direction drawn upwards on the page.
    pub fn up(&self) -> DVec3 {
        self.up
    }

    /// The direction towards the viewer.
    pub fn towards_viewer(&self) -> DVec3 {
        self.towards_viewer
    }

    /// Page points of a circle of `radius` about `center` in the plane spanned by `a` and `b`
    /// (orthonormal), from angle `t0` to `t1`.
    pub fn arc(&self, center: DVec3, a: DVec3, b: DVec3, radius: f64, t0: f64, t1: f64) -> Vec<P2> {
        let n = 96;
        (0..=n)
            .map(|i| {
                let t = t0 + (t1 - t0) * i as f64 / n as f64;
                self.at(center + radius * (t.cos() * a + t.sin() * b))
            })
            .collect()
    }

    /// The outline of a sphere of `radius` about `center`, as seen by this view.
    pub fn sphere_outline(&self, center: DVec3, radius: f64) -> Vec<P2> {
        self.arc(
            center,
            self.right,
            self.up,
            radius,
            0.0,
            std::f64::consts::TAU,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn view_is_right_handed_and_z_is_up() {
        let v = View::new(0.7, 0.3, 100.0, (0.0, 0.0));
        // z up: the tip of +z is drawn above the origin (smaller page y).
        assert!(v.at(DVec3::Z).1 < 0.0);
        // right-handed: x, y, z seen counter-clockwise from above means x cross y = z.
        let (x, y) = (v.at(DVec3::X), v.at(DVec3::Y));
        // page y points down, so a counter-clockwise turn on the page has a negative cross product
        assert!(x.0 * y.1 - x.1 * y.0 < 0.0);
    }

    #[test]
    fn text_is_escaped() {
        let mut s = Svg::new(10.0, 10.0);
        s.text((0.0, 0.0), "a < b & c", 10.0, Anchor::Start, "black");
        assert!(s.finish().contains("a &lt; b &amp; c"));
    }
}
