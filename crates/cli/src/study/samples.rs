//! `rtl study samples`: each chapter's sampler, its samples drawn against the density it claims.
//!
//! One-dimensional samplers get a histogram of `x` over the density `p(x)`. Direction samplers get a
//! histogram of `z = cos theta` about an axis against the density of `z` that their `value` implies,
//! `g(z) = ∫ p(ω(z, φ)) dφ` (since `dω = dz dφ`), found by quadrature of `value` alone, next to a
//! point cloud of the directions seen along the axis. Each figure states a chi-square p-value of
//! its histogram against the claimed density (bins with fewer than 5 expected pooled), so a sampler
//! that disagreed with its density would show it in the picture and in the number.

use super::svg::{Anchor, Frame, P2, Svg, colour as c, legend};
use anyhow::Context as _;
use clap::Args;
use glam::DVec3;
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use rtl_pdf::{
    CosinePdf, HemispherePdf, HittablePdf, MixturePdf, Onb, Pdf, QuadTarget, SpherePdf,
    SphereTarget,
};
use rtl_sampling::TabulatedCdf;
use rtl_sampling::analytic::{Linear, Quadratic};
use rtl_sampling::targets::{BookSinSquared, TargetDensity as _};
use statrs::distribution::{ChiSquared, ContinuousCDF};
use std::cell::RefCell;
use std::f64::consts::TAU;
use std::path::PathBuf;

#[derive(Args)]
pub struct SamplesArgs {
    /// Directory for the SVG files (default: a scratch directory, printed; the book's figures are
    /// book/src/figures).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Samples per histogram (1,000 to 100,000,000).
    #[arg(long, default_value_t = 200_000)]
    pub samples: usize,
}

/// The most samples a histogram takes: about a minute for the page of them on one core.
const MAX_SAMPLES: usize = 100_000_000;

pub fn run(args: SamplesArgs) -> anyhow::Result<()> {
    anyhow::ensure!(
        (1000..=MAX_SAMPLES).contains(&args.samples),
        "--samples {}: must be 1,000 to 100,000,000 (2^64 - 1 ran for ever)",
        args.samples
    );
    let out = super::out_dir(args.out, "samples")?;
    let n = args.samples;
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(2026);
    let mut report = Vec::new();
    let mut save = |name: &str, svg: Svg, p: Option<f64>| -> anyhow::Result<()> {
        svg.save(&out.join(format!("{name}.svg")))?;
        match p {
            Some(p) => eprintln!("  {name}.svg  chi-square p = {p:.3}"),
            None => eprintln!("  {name}.svg"),
        }
        report.push((name.to_string(), p));
        Ok(())
    };

    // ch. 2: the pi estimator's points, plain and jittered
    save("samples-ch02-pi", pi_points(&mut rng)?, None)?;

    // ch. 3: analytic inverses and the tabulated book density
    let (svg, p) = histogram_1d(
        "Samples of p(x) = x / 2 by x = 2√u (rtl-sampling's Linear)",
        (0.0, 2.0),
        |x| Linear.pdf(x),
        (0..n).map(|_| Linear.sample(rng.random()).x),
        "p(x) = x / 2",
    );
    save("samples-ch03-linear", svg, Some(p))?;
    let (svg, p) = histogram_1d(
        "Samples of p(x) = 3x² / 8 by x = 2∛u (rtl-sampling's Quadratic)",
        (0.0, 2.0),
        |x| Quadratic.pdf(x),
        (0..n).map(|_| Quadratic.sample(rng.random()).x),
        "p(x) = 3x² / 8",
    );
    save("samples-ch03-quadratic", svg, Some(p))?;
    let book = BookSinSquared;
    let (a, b) = book.domain();
    let table = TabulatedCdf::from_density(|x| book.density(x), a, b, 64)
        .context("tabulating the book's density")?;
    let (svg, p) = histogram_1d(
        "The book's e^(−x/2π) sin² x sampled from a 64-bin table",
        (a, b),
        |x| table.pdf(x),
        (0..n).map(|_| table.sample(rng.random()).x),
        "the table's density (piecewise constant)",
    );
    save("samples-ch03-book-table", svg, Some(p))?;

    // ch. 4, 5, 7, 8: the sphere, the hemisphere, the cosine warp, and cosine about a tilted normal
    let cases: Vec<(&str, String, DirectionCase)> = vec![
        (
            "samples-ch04-sphere",
            "SpherePdf: uniform over the sphere, 1 / (4π)".into(),
            DirectionCase::new(DVec3::Z, -1.0, &SpherePdf, &mut rng, n),
        ),
        (
            "samples-ch05-hemisphere",
            "HemispherePdf: uniform over the hemisphere, 1 / (2π)".into(),
            DirectionCase::new(DVec3::Z, 0.0, &HemispherePdf::new(DVec3::Z), &mut rng, n),
        ),
        (
            "samples-ch07-cosine",
            "CosinePdf: cos θ / π about n = z".into(),
            DirectionCase::new(DVec3::Z, 0.0, &CosinePdf::new(DVec3::Z), &mut rng, n),
        ),
    ];
    for (name, t, case) in cases {
        let (svg, p) = case.draw(&t);
        save(name, svg, Some(p))?;
    }
    let tilted = DVec3::new(0.45, -0.3, 0.84).normalize();
    let case = DirectionCase::new(tilted, 0.0, &CosinePdf::new(tilted), &mut rng, n);
    let (svg, p) = case.draw("CosinePdf about a tilted normal n, through Onb::new(n)");
    save("samples-ch08-cosine-tilted", svg, Some(p))?;

    // ch. 9: towards a sphere (the cone) and towards a quad (area, and spherical rectangles)
    let sphere = [SphereTarget::new(DVec3::new(0.0, 0.0, 4.0), 1.5)];
    let towards = HittablePdf::new(DVec3::ZERO, &sphere).context("a sphere target")?;
    let cos_max = (1.0 - (1.5f64 / 4.0).powi(2)).sqrt();
    let case = DirectionCase::new(DVec3::Z, cos_max - 0.02, &towards, &mut rng, n);
    let (svg, p) = case.draw("HittablePdf towards a sphere: uniform in its cone");
    save("samples-ch09-sphere-cone", svg, Some(p))?;
    let q = DVec3::new(-1.0, -0.5, 1.5);
    let (u, v) = (DVec3::new(2.0, 0.0, 0.0), DVec3::new(0.0, 1.0, 0.0));
    let centre_dir = (q + 0.5 * u + 0.5 * v).normalize();
    for (name, t, sph) in [
        (
            "samples-ch09-quad-area",
            "HittablePdf towards a quad: uniform in area, d² / (A |cos θₗ|)",
            false,
        ),
        (
            "samples-ch09-quad-spherical-rectangle",
            "HittablePdf towards a quad: spherical rectangle, 1 / S",
            true,
        ),
    ] {
        let quad = [QuadTarget::new(q, u, v).with_spherical_rectangles(sph)];
        let towards = HittablePdf::new(DVec3::ZERO, &quad).context("a quad target")?;
        let zmin = quad_min_cos(q, u, v, centre_dir) - 0.02;
        let case = DirectionCase::new(centre_dir, zmin, &towards, &mut rng, n);
        let (svg, p) = case.draw(t);
        save(name, svg, Some(p))?;
    }

    // ch. 10: the book's mixture, half towards the quad light and half cosine
    let quad = [QuadTarget::new(q, u, v)];
    let light = HittablePdf::new(DVec3::ZERO, &quad).context("a quad target")?;
    let mix = MixturePdf::new(light, CosinePdf::new(DVec3::Z));
    let case = DirectionCase::new(DVec3::Z, 0.0, &mix, &mut rng, n);
    let (svg, p) = case.draw("MixturePdf: ½ towards the quad light + ½ cosine");
    save("samples-ch10-mixture", svg, Some(p))?;

    // ch. 11: several lights, each a target built once, chosen uniformly
    let lights = [
        QuadTarget::new(
            DVec3::new(-2.0, -0.6, 2.0),
            DVec3::new(1.2, 0.0, 0.0),
            DVec3::new(0.0, 1.2, 0.0),
        ),
        QuadTarget::new(
            DVec3::new(1.2, 0.4, 1.0),
            DVec3::new(0.6, 0.0, 0.0),
            DVec3::new(0.0, 0.6, 0.0),
        ),
    ];
    let towards = HittablePdf::new(DVec3::ZERO, &lights).context("two quad targets")?;
    let case = DirectionCase::new(DVec3::Z, 0.0, &towards, &mut rng, n);
    let (svg, p) = case.draw("HittablePdf over two quad lights, each picked with probability ½");
    save("samples-ch11-two-lights", svg, Some(p))?;

    // ch. 12: the mixture the renderer uses for a diffuse bounce next to a sphere and a quad
    let targets_sphere = [SphereTarget::new(DVec3::new(1.5, 0.0, 2.5), 0.8)];
    let to_sphere = HittablePdf::new(DVec3::ZERO, &targets_sphere).context("a sphere target")?;
    let mix = MixturePdf::new(to_sphere, CosinePdf::new(DVec3::Z));
    let case = DirectionCase::new(DVec3::Z, 0.0, &mix, &mut rng, n);
    let (svg, p) = case.draw("MixturePdf: ½ towards a glass sphere + ½ cosine");
    save("samples-ch12-mixture-sphere", svg, Some(p))?;

    let worst = report
        .iter()
        .filter_map(|(name, p)| p.map(|p| (name, p)))
        .fold(None::<(&String, f64)>, |acc, (name, p)| match acc {
            Some((_, q)) if q <= p => acc,
            _ => Some((name, p)),
        });
    if let Some((name, p)) = worst {
        eprintln!(
            "smallest p-value: {p:.3} ({name}); {} figures in {}",
            report.len(),
            out.display()
        );
    }
    Ok(())
}

/// The smallest `cos` between `axis` and a direction towards the parallelogram `q + s u + t v`.
fn quad_min_cos(q: DVec3, u: DVec3, v: DVec3, axis: DVec3) -> f64 {
    let mut m: f64 = 1.0;
    for i in 0..=16 {
        for j in 0..=16 {
            let p = q + u * (i as f64 / 16.0) + v * (j as f64 / 16.0);
            m = m.min(p.normalize().dot(axis));
        }
    }
    m.max(-1.0)
}

/// Chi-square p-value of `observed` counts against `expected` (same total), pooling neighbouring bins
/// until each has at least 5 expected.
fn chi_square_p(observed: &[f64], expected: &[f64]) -> f64 {
    let (mut o, mut e, mut stat, mut cells) = (0.0, 0.0, 0.0, 0usize);
    for (&ob, &ex) in observed.iter().zip(expected) {
        o += ob;
        e += ex;
        if e >= 5.0 {
            stat += (o - e) * (o - e) / e;
            cells += 1;
            o = 0.0;
            e = 0.0;
        }
    }
    if e > 0.0 {
        stat += (o - e) * (o - e) / e;
        cells += 1;
    } else if o > 0.0 {
        return 0.0; // samples where the density claims none
    }
    if cells < 2 {
        return 1.0;
    }
    ChiSquared::new((cells - 1) as f64).map_or(f64::NAN, |d| d.sf(stat))
}

/// The histogram of `samples` on `domain` against `density`, with its chi-square p-value.
fn histogram_1d(
    title: &str,
    (a, b): (f64, f64),
    density: impl Fn(f64) -> f64,
    samples: impl Iterator<Item = f64>,
    curve_label: &str,
) -> (Svg, f64) {
    const BINS: usize = 64;
    let mut counts = vec![0.0; BINS];
    let mut n = 0usize;
    for x in samples {
        n += 1;
        let i = ((x - a) / (b - a) * BINS as f64).floor();
        if (0.0..BINS as f64).contains(&i) {
            counts[i as usize] += 1.0;
        }
    }
    let width = (b - a) / BINS as f64;
    let expected: Vec<f64> = (0..BINS)
        .map(|i| {
            let m = 64;
            let mass: f64 = (0..m)
                .map(|k| density(a + width * (i as f64 + (k as f64 + 0.5) / m as f64)))
                .sum::<f64>()
                * width
                / m as f64;
            mass * n as f64
        })
        .collect();
    let p = chi_square_p(&counts, &expected);
    let peak = (0..400)
        .map(|k| density(a + (b - a) * (k as f64 + 0.5) / 400.0))
        .chain(counts.iter().map(|&k| k / (n as f64 * width)))
        .fold(0.0, f64::max);
    let (w, h) = (680.0, 400.0);
    let mut s = Svg::new(w, h);
    s.text((w / 2.0, 26.0), title, 16.0, Anchor::Middle, c::INK);
    let f = Frame {
        left: 80.0,
        top: 50.0,
        w: 560.0,
        h: 270.0,
        x0: a,
        x1: b,
        y0: 0.0,
        y1: nice_ceiling(peak * 1.08),
    };
    let xt = ticks(a, b, 5);
    let yt = ticks(0.0, f.y1, 4);
    f.axes(&mut s, &xt, &yt, "x", "density");
    for (i, &k) in counts.iter().enumerate() {
        let x0 = a + width * i as f64;
        s.rect(
            f.at(x0, 0.0),
            f.at(x0 + width, k / (n as f64 * width)),
            c::SKY,
            0.8,
            "white",
        );
    }
    f.curve(&mut s, &density, 800, c::RED, 2.5);
    legend(
        &mut s,
        (96.0, 66.0),
        &[
            (c::SKY, &format!("histogram of {n} samples")),
            (c::RED, curve_label),
        ],
    );
    s.text(
        (w / 2.0, h - 14.0),
        &format!("chi-square against the claimed density: p = {p:.3} ({BINS} bins, seed 2026)"),
        13.0,
        Anchor::Middle,
        c::INK,
    );
    (s, p)
}

/// Round up to 1, 2 or 5 times a power of ten.
fn nice_ceiling(x: f64) -> f64 {
    let e = 10f64.powf(x.log10().floor());
    for m in [1.0, 1.2, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0] {
        if m * e >= x {
            return m * e;
        }
    }
    10.0 * e
}

fn ticks(a: f64, b: f64, n: usize) -> Vec<f64> {
    (0..=n).map(|i| a + (b - a) * i as f64 / n as f64).collect()
}

/// Directions from one sampler, with the density its `value` claims, about an `axis`.
struct DirectionCase {
    zmin: f64,
    counts: Vec<f64>,
    /// Expected counts per bin from quadrature of `value`.
    expected: Vec<f64>,
    /// The claimed density of z, g(z) = ∫ p dφ, on a fine grid.
    g: Vec<(f64, f64)>,
    cloud: Vec<DVec3>,
    n: usize,
}

const ZBINS: usize = 40;

impl DirectionCase {
    fn new<P: Pdf>(
        axis: DVec3,
        zmin: f64,
        pdf: &P,
        rng: &mut Xoshiro256PlusPlus,
        n: usize,
    ) -> DirectionCase {
        let frame = Onb::new(axis);
        let zmin = zmin.max(-1.0);
        let mut counts = vec![0.0; ZBINS];
        let mut cloud = Vec::with_capacity(2000);
        let dz = (1.0 - zmin) / ZBINS as f64;
        for k in 0..n {
            let d = pdf.generate(rng);
            let z = d.dot(frame.w());
            let i = ((z - zmin) / dz).floor().clamp(0.0, ZBINS as f64 - 1.0);
            if z >= zmin {
                counts[i as usize] += 1.0;
            }
            if k < 2000 {
                cloud.push(frame.to_local(d));
            }
        }
        // g(z) = ∫ p dφ by the midpoint rule in φ; bin masses by the midpoint rule in z
        let g_at = |z: f64| -> f64 {
            let m = 1024;
            let r = (1.0 - z * z).max(0.0).sqrt();
            (0..m)
                .map(|k| {
                    let phi = TAU * (k as f64 + 0.5) / m as f64;
                    pdf.value(frame.transform(DVec3::new(r * phi.cos(), r * phi.sin(), z)))
                })
                .sum::<f64>()
                * TAU
                / m as f64
        };
        let sub = 24;
        let expected = (0..ZBINS)
            .map(|i| {
                (0..sub)
                    .map(|k| g_at(zmin + dz * (i as f64 + (k as f64 + 0.5) / sub as f64)))
                    .sum::<f64>()
                    * dz
                    / sub as f64
                    * n as f64
            })
            .collect();
        let g = (0..=400)
            .map(|k| {
                let z = zmin + (1.0 - zmin) * (k as f64 / 400.0).min(1.0 - 1e-9);
                (z, g_at(z))
            })
            .collect();
        DirectionCase {
            zmin,
            counts,
            expected,
            g,
            cloud,
            n,
        }
    }

    fn draw(&self, title: &str) -> (Svg, f64) {
        let p = chi_square_p(&self.counts, &self.expected);
        let dz = (1.0 - self.zmin) / ZBINS as f64;
        let n = self.n as f64;
        let peak = self
            .g
            .iter()
            .map(|&(_, g)| g)
            .chain(self.counts.iter().map(|&k| k / (n * dz)))
            .fold(0.0, f64::max);
        let (w, h) = (820.0, 400.0);
        let mut s = Svg::new(w, h);
        s.text((w / 2.0, 26.0), title, 16.0, Anchor::Middle, c::INK);
        let f = Frame {
            left: 80.0,
            top: 56.0,
            w: 400.0,
            h: 260.0,
            x0: self.zmin,
            x1: 1.0,
            y0: 0.0,
            y1: nice_ceiling(peak * 1.08),
        };
        f.axes(
            &mut s,
            &ticks(self.zmin, 1.0, 4),
            &ticks(0.0, f.y1, 4),
            "z = cos θ about the axis",
            "density of z",
        );
        for (i, &k) in self.counts.iter().enumerate() {
            let z0 = self.zmin + dz * i as f64;
            s.rect(
                f.at(z0, 0.0),
                f.at(z0 + dz, k / (n * dz)),
                c::SKY,
                0.8,
                "white",
            );
        }
        let pts: Vec<P2> = self.g.iter().map(|&(z, g)| f.at(z, g.min(f.y1))).collect();
        s.polyline(&pts, c::RED, 2.5);
        legend(
            &mut s,
            (96.0, 72.0),
            &[
                (c::SKY, &format!("histogram of {} samples", self.n)),
                (c::RED, "claimed: ∫ value dφ"),
            ],
        );
        // the point cloud, seen along the axis: the unit disc is the hemisphere's projection
        let (cx, cy, r) = (660.0, 190.0, 130.0);
        s.circle((cx, cy), r, "#f6f6f6", c::GREY, 1.0);
        s.line((cx - r, cy), (cx + r, cy), c::LIGHT, 0.8);
        s.line((cx, cy - r), (cx, cy + r), c::LIGHT, 0.8);
        for d in &self.cloud {
            let col = if d.z >= 0.0 { c::BLUE } else { c::ORANGE };
            s.dot((cx + r * d.x, cy - r * d.y), 1.3, col);
        }
        s.text(
            (cx, cy + r + 22.0),
            "2000 directions, seen along the axis",
            12.0,
            Anchor::Middle,
            c::INK,
        );
        let below = self.cloud.iter().any(|d| d.z < 0.0);
        if below {
            s.text(
                (cx, cy + r + 38.0),
                "(orange: below the horizon)",
                12.0,
                Anchor::Middle,
                c::ORANGE,
            );
        }
        s.text(
            (w / 2.0, h - 12.0),
            &format!(
                "chi-square of the histogram against the density value() claims: p = {p:.3} ({ZBINS} bins, seed 2026)"
            ),
            13.0,
            Anchor::Middle,
            c::INK,
        );
        (s, p)
    }
}

/// Chapter 2: points of the pi estimator in the square, plain uniform and jittered (rtl-mc's
/// `jittered_2d`), inside the quarter disc or not.
fn pi_points(rng: &mut Xoshiro256PlusPlus) -> anyhow::Result<Svg> {
    let (w, h) = (760.0, 420.0);
    let mut s = Svg::new(w, h);
    s.text(
        (w / 2.0, 26.0),
        "Estimating π: 400 points in the square, the fraction inside the disc is π / 4",
        16.0,
        Anchor::Middle,
        c::INK,
    );
    let plain: Vec<[f64; 2]> = (0..400)
        .map(|_| [rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0)])
        .collect();
    let jittered = RefCell::new(Vec::new());
    rtl_mc::jittered_2d(
        |p| {
            jittered.borrow_mut().push(p);
            0.0
        },
        rtl_mc::Rect::new(-1.0, 1.0, -1.0, 1.0).context("the square")?,
        (20, 20),
        2,
        rng,
    )
    .context("jittered points")?;
    // two replicates of 20 x 20 points (the fewest jittered_2d takes): draw the first
    let mut jittered = jittered.into_inner();
    jittered.truncate(400);
    for (k, (pts, label)) in [
        (&plain, "uniform: clumps and gaps"),
        (&jittered, "jittered: one point in each of 20 × 20 cells"),
    ]
    .into_iter()
    .enumerate()
    {
        let (x0, y0, side) = (60.0 + 370.0 * k as f64, 60.0, 300.0);
        let at = |p: [f64; 2]| -> P2 {
            (
                x0 + (p[0] + 1.0) / 2.0 * side,
                y0 + (1.0 - p[1]) / 2.0 * side,
            )
        };
        s.rect((x0, y0), (x0 + side, y0 + side), "white", 1.0, c::GREY);
        if k == 1 {
            for i in 1..20 {
                let t = i as f64 / 20.0 * side;
                s.line((x0 + t, y0), (x0 + t, y0 + side), "#eeeeee", 0.6);
                s.line((x0, y0 + t), (x0 + side, y0 + t), "#eeeeee", 0.6);
            }
        }
        s.circle(
            (x0 + side / 2.0, y0 + side / 2.0),
            side / 2.0,
            "none",
            c::INK,
            1.2,
        );
        let inside = pts
            .iter()
            .filter(|p| p[0] * p[0] + p[1] * p[1] < 1.0)
            .count();
        for &p in pts.iter() {
            let col = if p[0] * p[0] + p[1] * p[1] < 1.0 {
                c::BLUE
            } else {
                c::ORANGE
            };
            s.dot(at(p), 2.4, col);
        }
        s.text(
            (x0 + side / 2.0, y0 + side + 24.0),
            label,
            13.0,
            Anchor::Middle,
            c::INK,
        );
        s.text(
            (x0 + side / 2.0, y0 + side + 44.0),
            &format!(
                "{inside} of {} inside: π ≈ {:.3}",
                pts.len(),
                4.0 * inside as f64 / pts.len() as f64
            ),
            13.0,
            Anchor::Middle,
            c::INK,
        );
    }
    Ok(s)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec2;
    use rtl_pdf::warp;

    #[test]
    fn chi_square_accepts_a_right_sampler_and_rejects_a_wrong_one() {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(5);
        // right: the cosine pdf's own samples
        let right = DirectionCase::new(DVec3::Z, 0.0, &CosinePdf::new(DVec3::Z), &mut rng, 20_000);
        let (_, p) = right.draw("right");
        assert!(p > 1e-6, "a correct sampler failed: p = {p}");
        // wrong: uniform hemisphere samples claimed as cosine
        struct Liar;
        impl Pdf for Liar {
            fn pdf(&self, d: DVec3) -> f64 {
                warp::cosine_hemisphere_pdf(d.z)
            }
            fn sample(&self, u: DVec2) -> Option<rtl_pdf::DirectionSample> {
                let d = warp::sample_uniform_hemisphere(u);
                rtl_pdf::DirectionSample::new(d, self.pdf(d))
            }
        }
        let wrong = DirectionCase::new(DVec3::Z, 0.0, &Liar, &mut rng, 20_000);
        let (_, p) = wrong.draw("wrong");
        assert!(p < 1e-6, "a wrong sampler passed: p = {p}");
    }

    #[test]
    fn one_dimensional_histogram_rejects_a_wrong_density() {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(6);
        let (_, p) = histogram_1d(
            "t",
            (0.0, 2.0),
            |x| x / 2.0,
            (0..20_000).map(|_| 2.0 * rng.random::<f64>()),
            "",
        );
        assert!(p < 1e-6, "uniform samples passed as x/2: p = {p}");
    }
}
