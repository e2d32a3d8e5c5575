//! Plots for the studies: log-log charts of error against samples or time, as PNG.
//!
//! Text is drawn with `ab_glyph` and an embedded DejaVu Sans, so no font library of the system is needed.

use anyhow::{Context, Result, anyhow};
use plotters::prelude::*;
use std::path::Path;
use std::sync::Once;

/// One line of a chart: a label and its (x, y) points, both positive. A label that contains
/// "biased" is drawn dashed, so that an estimator that does not converge to the answer stands out.
pub struct Series {
    pub label: String,
    pub points: Vec<(f64, f64)>,
}

/// Least-squares slope of log10(y) against log10(x): the convergence rate on a log-log chart
/// (-0.5 for plain Monte Carlo error against N). `None` with fewer than two usable points.
pub fn loglog_slope(points: &[(f64, f64)]) -> Option<f64> {
    let logs: Vec<(f64, f64)> = points
        .iter()
        .filter(|(x, y)| *x > 0.0 && *y > 0.0 && x.is_finite() && y.is_finite())
        .map(|(x, y)| (x.log10(), y.log10()))
        .collect();
    if logs.len() < 2 {
        return None;
    }
    let n = logs.len() as f64;
    let mx = logs.iter().map(|p| p.0).sum::<f64>() / n;
    let my = logs.iter().map(|p| p.1).sum::<f64>() / n;
    let sxx: f64 = logs.iter().map(|p| (p.0 - mx) * (p.0 - mx)).sum();
    let sxy: f64 = logs.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    (sxx > 0.0).then(|| sxy / sxx)
}

/// A tick label of a log axis: only 1, 2 and 5 times a power of ten are labelled (the other grid lines
/// stay unlabelled, so neighbouring labels never run together), written plainly between 0.001 and
/// 10 000 and as `1e-5` outside.
pub fn log_tick(v: f64) -> String {
    if !(v > 0.0 && v.is_finite()) {
        return String::new();
    }
    let e = v.log10().floor();
    let m = v / 10f64.powf(e);
    let m = [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .find(|k| (m - k).abs() < 1e-6 * k);
    let Some(m) = m else {
        return String::new();
    };
    let (m, e) = if m == 10.0 { (1.0, e + 1.0) } else { (m, e) };
    if (-3.0..=4.0).contains(&e) {
        let v = m * 10f64.powf(e);
        let digits = (-e).max(0.0) as usize;
        format!("{v:.digits$}")
    } else {
        format!("{m}e{e}")
    }
}

fn register_fonts() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        // The bytes are a valid TrueType font shipped by the `dejavu` crate.
        let _ = plotters::style::register_font(
            "sans-serif",
            FontStyle::Normal,
            dejavu::sans::regular(),
        );
        let _ = plotters::style::register_font("sans-serif", FontStyle::Bold, dejavu::sans::bold());
    });
}

/// Draws `series` on log-log axes into a PNG at `path`. With `with_slope`, each legend entry also
/// gives the fitted log-log slope.
pub fn loglog(
    path: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
    with_slope: bool,
) -> Result<()> {
    register_fonts();
    let all = series
        .iter()
        .flat_map(|s| s.points.iter())
        .filter(|(x, y)| *x > 0.0 && *y > 0.0 && x.is_finite() && y.is_finite());
    let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, 0.0f64, f64::INFINITY, 0.0f64);
    for &(x, y) in all {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    if x0 >= x1 || y0 > y1 {
        return Err(anyhow!("nothing positive to plot in {title}"));
    }
    if y0 == y1 {
        y0 /= 2.0;
        y1 *= 2.0;
    }
    let root = BitMapBackend::new(path, (960, 640)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| anyhow!("{e}"))?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 22))
        .margin(12)
        .x_label_area_size(60)
        .y_label_area_size(84)
        .build_cartesian_2d(
            (x0 / 1.5..x1 * 1.5).log_scale(),
            (y0 / 1.5..y1 * 1.5).log_scale(),
        )
        .map_err(|e| anyhow!("{e}"))?;
    chart
        .configure_mesh()
        .x_desc(x_label)
        .y_desc(y_label)
        .x_label_formatter(&|v| log_tick(*v))
        .y_label_formatter(&|v| log_tick(*v))
        .x_label_style(("sans-serif", 15))
        .y_label_style(("sans-serif", 15))
        .axis_desc_style(("sans-serif", 17))
        .draw()
        .map_err(|e| anyhow!("{e}"))?;
    for (i, s) in series.iter().enumerate() {
        let color = Palette99::pick(i).to_rgba();
        let pts: Vec<(f64, f64)> = s
            .points
            .iter()
            .copied()
            .filter(|(x, y)| *x > 0.0 && *y > 0.0 && x.is_finite() && y.is_finite())
            .collect();
        let label = match (with_slope, loglog_slope(&pts)) {
            (true, Some(k)) => format!("{} (slope {k:.2})", s.label),
            _ => s.label.clone(),
        };
        if s.label.contains("biased") {
            chart
                .draw_series(DashedLineSeries::new(
                    pts.clone(),
                    10,
                    6,
                    color.stroke_width(3),
                ))
                .map_err(|e| anyhow!("{e}"))?
                .label(label)
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 8, y)], color.stroke_width(3))
                });
        } else {
            chart
                .draw_series(LineSeries::new(pts.clone(), color.stroke_width(2)))
                .map_err(|e| anyhow!("{e}"))?
                .label(label)
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
                });
        }
        chart
            .draw_series(pts.iter().map(|&p| Circle::new(p, 3, color.filled())))
            .map_err(|e| anyhow!("{e}"))?;
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .position(SeriesLabelPosition::LowerLeft)
        .draw()
        .map_err(|e| anyhow!("{e}"))?;
    root.present()
        .with_context(|| format!("writing plot {}", path.display()))?;
    Ok(())
}

/// One picture of an image grid: width, height, RGB bytes (row-major) and the label under it.
pub struct Panel {
    pub width: usize,
    pub height: usize,
    pub rgb: Vec<u8>,
    pub label: String,
}

/// Pictures in a grid of `cols` columns, each enlarged `scale` times (nearest neighbour, so that
/// noise stays visible as noise), each labelled underneath, under a `title`; written as PNG.
pub fn image_grid(
    path: &Path,
    title: &str,
    panels: &[Panel],
    scale: usize,
    cols: usize,
) -> Result<()> {
    register_fonts();
    let (gap, label_h, title_h) = (12usize, 30usize, 40usize);
    let cols = cols.clamp(1, panels.len().max(1));
    let rows = panels.len().div_ceil(cols);
    let cw = panels.iter().map(|p| p.width).max().unwrap_or(1) * scale;
    let ch = panels.iter().map(|p| p.height).max().unwrap_or(1) * scale;
    let w = cols * cw + (cols + 1) * gap;
    let h = title_h + rows * (ch + label_h) + rows * gap;
    let root = BitMapBackend::new(path, (w as u32, h as u32)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| anyhow!("{e}"))?;
    let text = |size: u32| TextStyle::from(("sans-serif", size).into_font()).color(&BLACK);
    let centred = |size: u32| {
        text(size).pos(plotters::style::text_anchor::Pos::new(
            plotters::style::text_anchor::HPos::Center,
            plotters::style::text_anchor::VPos::Top,
        ))
    };
    root.draw_text(title, &centred(20), ((w / 2) as i32, 10))
        .map_err(|e| anyhow!("{e}"))?;
    for (i, p) in panels.iter().enumerate() {
        let (c, r) = (i % cols, i / cols);
        let x0 = gap + c * (cw + gap);
        let y0 = title_h + r * (ch + label_h + gap);
        for y in 0..p.height * scale {
            for x in 0..p.width * scale {
                let k = 3 * ((y / scale) * p.width + x / scale);
                root.draw_pixel(
                    ((x0 + x) as i32, (y0 + y) as i32),
                    &RGBColor(p.rgb[k], p.rgb[k + 1], p.rgb[k + 2]),
                )
                .map_err(|e| anyhow!("{e}"))?;
            }
        }
        root.draw_text(
            &p.label,
            &centred(17),
            (
                (x0 + p.width * scale / 2) as i32,
                (y0 + p.height * scale + 6) as i32,
            ),
        )
        .map_err(|e| anyhow!("{e}"))?;
    }
    root.present()
        .with_context(|| format!("writing {}", path.display()))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slope_of_a_power_law_is_its_exponent() {
        let pts: Vec<(f64, f64)> = (1..10)
            .map(|i| {
                let x = 2f64.powi(i);
                (x, 3.0 * x.powf(-0.5))
            })
            .collect();
        assert!((loglog_slope(&pts).unwrap() + 0.5).abs() < 1e-12);
    }

    #[test]
    fn log_ticks_label_only_1_2_5_and_never_twice_a_decade_apart() {
        assert_eq!(log_tick(1.0), "1");
        assert_eq!(log_tick(0.2), "0.2");
        assert_eq!(log_tick(0.05), "0.05");
        assert_eq!(log_tick(0.3), "");
        assert_eq!(log_tick(0.9), "");
        assert_eq!(log_tick(1e-5), "1e-5");
        assert_eq!(log_tick(2e6), "2e6");
        assert_eq!(log_tick(0.999_999_999_9), "1");
    }

    #[test]
    fn a_plot_is_written_as_png() {
        let dir = std::env::temp_dir().join(format!("rtl-plot-test-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("p.png");
        let s = Series {
            label: "a".into(),
            points: vec![(1.0, 1.0), (10.0, 0.3), (100.0, 0.1)],
        };
        loglog(&path, "test", "N", "error", &[s], true).unwrap();
        let bytes = std::fs::read(&path).unwrap();
        assert_eq!(&bytes[1..4], b"PNG");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
