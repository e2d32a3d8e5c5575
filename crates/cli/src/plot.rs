//! Plots for the studies: log-log charts of error against samples or time, and grids of images, as
//! PNG; and the reading back of a study's CSV, so that `--replot` draws the same charts from a
//! committed run without measuring again.
//!
//! Text is drawn with `ab_glyph` and an embedded DejaVu Sans, so no font library of the system is needed.
//! The charts are 960 x 640 pixels, about the width of the book's column, and their text is sized to stay
//! readable when a phone shows them at half that.

use anyhow::{Context, Result, anyhow};
use plotters::coord::Shift;
use plotters::element::MultiLineText;
use plotters::prelude::*;
use std::path::Path;
use std::sync::Once;

/// The colours of the series of a chart, in order: Okabe and Ito's colour-blind-safe palette
/// (M. Okabe and K. Ito, "Color Universal Design (CUD): how to make figures and presentations that are
/// friendly to colorblind people", 2008, <https://jfly.uni-koeln.de/color/>), without its yellow
/// (#F0E442), which can hardly be seen on white, and with a mid grey after its black. Every colour is
/// darker than [`MAX_LUMINANCE`]; a chart with more series than colours starts again at the first.
pub const PALETTE: [RGBColor; 8] = [
    RGBColor(0xD5, 0x5E, 0x00), // vermilion
    RGBColor(0x00, 0x72, 0xB2), // blue
    RGBColor(0x00, 0x9E, 0x73), // bluish green
    RGBColor(0xE6, 0x9F, 0x00), // orange
    RGBColor(0xCC, 0x79, 0xA7), // reddish purple
    RGBColor(0x56, 0xB4, 0xE9), // sky blue
    RGBColor(0x00, 0x00, 0x00), // black
    RGBColor(0x77, 0x77, 0x77), // grey
];

/// The colour of the `i`-th series of a chart.
pub fn series_colour(i: usize) -> RGBColor {
    PALETTE[i % PALETTE.len()]
}

/// The relative luminance of an sRGB colour (0 for black, 1 for white): each channel linearised by
/// the sRGB transfer function, then weighted 0.2126, 0.7152, 0.0722 (IEC 61966-2-1; the formula of
/// WCAG 2's contrast ratio).
pub fn relative_luminance(c: RGBColor) -> f64 {
    let linear = |v: u8| {
        let v = f64::from(v) / 255.0;
        if v <= 0.040_45 {
            v / 12.92
        } else {
            ((v + 0.055) / 1.055).powf(2.4)
        }
    };
    0.2126 * linear(c.0) + 0.7152 * linear(c.1) + 0.0722 * linear(c.2)
}

/// The lightest a line on the charts' white may be: relative luminance 0.45, a contrast with white of
/// at least 2.1 : 1 (`(1 + 0.05) / (L + 0.05)`). Okabe and Ito's orange (0.42) and sky blue (0.41),
/// drawn 3 pixels wide with markers, pass; their yellow (0.74) and the yellow of plotters' `Palette99`
/// (0.75), which this palette replaces, do not.
pub const MAX_LUMINANCE: f64 = 0.45;

/// Whether a colour is too light to draw a line with on white.
pub fn too_light(c: RGBColor) -> bool {
    relative_luminance(c) > MAX_LUMINANCE
}

/// Text sizes of a chart, in pixels.
const CAPTION_PX: u32 = 26;
const TICK_PX: u32 = 18;
const AXIS_DESC_PX: u32 = 20;
const LEGEND_PX: u32 = 18;
/// Text sizes of an image grid, in pixels.
const GRID_TITLE_PX: u32 = 22;
const GRID_LABEL_PX: u32 = 20;
/// Line widths and marker radius of a series, in pixels.
const LINE_PX: u32 = 3;
const MARKER_PX: u32 = 4;
/// A chart's size in pixels, and the space around its plotting area.
const CHART_SIZE: (u32, u32) = (960, 640);
const MARGIN_PX: u32 = 14;

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

/// The labels [`log_tick`] gives on a log axis over `lo..hi`.
fn log_ticks_in(lo: f64, hi: f64) -> Vec<String> {
    let (a, b) = (lo.log10().floor() as i32, hi.log10().ceil() as i32);
    (a..=b)
        .flat_map(|e| [1.0, 2.0, 5.0].map(|m| m * 10f64.powi(e)))
        .filter(|v| (lo..=hi).contains(v))
        .map(log_tick)
        .collect()
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

/// Width and height in pixels of `text` at `px` pixels (fonts registered).
fn text_size(text: &str, px: u32) -> (u32, u32) {
    ("sans-serif", px)
        .into_font()
        .box_size(text)
        .unwrap_or((px * text.chars().count() as u32 / 2, px))
}

/// `text` broken at spaces into as few lines no wider than `width` (as `measure` measures them) as
/// it needs, and those lines as even as they can be: not one long line and a last word alone. A word
/// wider than `width` gets a line of its own.
fn wrap(text: &str, width: u32, measure: impl Fn(&str) -> u32) -> Vec<String> {
    let greedy = |width: u32| {
        let mut lines: Vec<String> = Vec::new();
        for word in text.split(' ') {
            match lines.last_mut() {
                Some(line) if measure(&format!("{line} {word}")) <= width => {
                    line.push(' ');
                    line.push_str(word);
                }
                _ => lines.push(word.to_string()),
            }
        }
        lines
    };
    let lines = greedy(width);
    // The narrowest width that still needs no more lines.
    let (mut lo, mut hi) = (0, width);
    while lo < hi {
        let mid = lo + (hi - lo) / 2;
        if greedy(mid).len() <= lines.len() {
            hi = mid;
        } else {
            lo = mid + 1;
        }
    }
    greedy(hi)
}

/// `title` in lines that fit a picture `width` pixels wide with room to spare on either side.
/// A line break in `title` is kept.
fn title_lines(title: &str, width: u32, px: u32) -> Vec<String> {
    title
        .lines()
        .flat_map(|t| {
            wrap(t, width.saturating_sub(4 * MARGIN_PX), |s| {
                text_size(s, px).0
            })
        })
        .collect()
}

/// Draws `title` centred at the top of `area`, in as many lines as its width needs; returns the part
/// of `area` below it.
fn draw_title<'a>(
    area: &DrawingArea<BitMapBackend<'a>, Shift>,
    title: &str,
    px: u32,
) -> Result<DrawingArea<BitMapBackend<'a>, Shift>> {
    let (w, _) = area.dim_in_pixel();
    let lines = title_lines(title, w, px);
    let line_h = px * 5 / 4;
    let style = centred(px);
    for (k, line) in lines.iter().enumerate() {
        area.draw_text(
            line,
            &style,
            ((w / 2) as i32, (MARGIN_PX / 2 + k as u32 * line_h) as i32),
        )
        .map_err(|e| anyhow!("{e}"))?;
    }
    Ok(area.split_vertically(title_height(title, w, px)).1)
}

/// The height [`draw_title`] takes for `title` at `px` pixels in a width of `w`.
fn title_height(title: &str, w: u32, px: u32) -> u32 {
    MARGIN_PX / 2 + title_lines(title, w, px).len() as u32 * (px * 5 / 4)
}

/// Text of `px` pixels, black, centred on its position and hanging below it.
fn centred(px: u32) -> TextStyle<'static> {
    TextStyle::from(("sans-serif", px).into_font())
        .color(&BLACK)
        .pos(plotters::style::text_anchor::Pos::new(
            plotters::style::text_anchor::HPos::Center,
            plotters::style::text_anchor::VPos::Top,
        ))
}

/// Space in a legend box before each label, where the series' line and marker are drawn.
const LEGEND_GLYPH_PX: i32 = 26;
const LEGEND_AREA_PX: i32 = LEGEND_GLYPH_PX + 10;
const LEGEND_MARGIN_PX: i32 = 10;

/// The legend box's size for `labels`, as plotters lays it out.
fn legend_size(labels: &[String]) -> (i32, i32) {
    let font = ("sans-serif", LEGEND_PX).into_font();
    let mut text = MultiLineText::<_, &str>::new((0, 0), font);
    for l in labels {
        text.push_line(l.as_str());
    }
    let (w, h) = text
        .estimate_dimension()
        .unwrap_or((0, labels.len() as i32 * LEGEND_PX as i32 * 5 / 4));
    (
        w + LEGEND_AREA_PX + 2 * LEGEND_MARGIN_PX,
        h + 2 * LEGEND_MARGIN_PX,
    )
}

/// Where to put a legend box of `size` in a plotting area of `area` pixels so that it covers as little
/// of `lines` (polylines in the area's pixels, taken at every pixel along each segment) as it can: a
/// corner or the middle of an edge if one is free (the lower left first, where error against N is
/// empty), else any free place, else the place that covers least. The box's upper left corner.
fn legend_corner(size: (i32, i32), area: (i32, i32), lines: &[Vec<(i32, i32)>]) -> (i32, i32) {
    let gap = 6;
    let (left, centre, right) = (gap, (area.0 - size.0) / 2, area.0 - size.0 - gap);
    let (top, middle, bottom) = (gap, (area.1 - size.1) / 2, area.1 - size.1 - gap);
    let named = [
        (left, bottom),
        (right, top),
        (right, bottom),
        (left, top),
        (centre, bottom),
        (centre, top),
        (right, middle),
        (left, middle),
    ];
    let step = 8;
    let anywhere = (0..=(right - left).max(0) / step).flat_map(|i| {
        (0..=(bottom - top).max(0) / step).map(move |j| (left + i * step, top + j * step))
    });
    let mut points = Vec::new();
    for line in lines {
        if let [only] = line.as_slice() {
            points.push((f64::from(only.0), f64::from(only.1)));
        }
        for w in line.windows(2) {
            let (a, b) = (w[0], w[1]);
            let (dx, dy) = (f64::from(b.0 - a.0), f64::from(b.1 - a.1));
            let steps = dx.abs().max(dy.abs()).ceil().max(1.0) as usize;
            points.extend((0..=steps).map(|s| {
                let t = s as f64 / steps as f64;
                (f64::from(a.0) + t * dx, f64::from(a.1) + t * dy)
            }));
        }
    }
    // a few pixels around the box count too: a line just along its border would be hidden as well
    let covered = |(x0, y0): (i32, i32)| {
        let (x0, y0) = (f64::from(x0 - 4), f64::from(y0 - 4));
        let (x1, y1) = (x0 + f64::from(size.0 + 8), y0 + f64::from(size.1 + 8));
        points
            .iter()
            .filter(|(x, y)| *x >= x0 && *x <= x1 && *y >= y0 && *y <= y1)
            .count()
    };
    // `min_by_key` keeps the first of equals: the named places before the others
    named
        .into_iter()
        .chain(anywhere)
        .min_by_key(|&c| covered(c))
        .expect("candidates")
}

/// Draws `series` on log-log axes into a PNG at `path`, under `title` (broken into lines where it
/// holds a line break, and where it is too wide). With `with_slope`, each legend entry also
/// gives the fitted log-log slope. Series `i` is drawn in [`series_colour`]`(i)`, with markers at its
/// points, dashed if its label contains "biased"; the legend goes where it hides least of the lines.
pub fn loglog(
    path: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
    with_slope: bool,
) -> Result<()> {
    register_fonts();
    let usable = |(x, y): &(f64, f64)| *x > 0.0 && *y > 0.0 && x.is_finite() && y.is_finite();
    let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, 0.0f64, f64::INFINITY, 0.0f64);
    for &(x, y) in series
        .iter()
        .flat_map(|s| s.points.iter())
        .filter(|p| usable(p))
    {
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
    let (x_range, y_range) = ((x0 / 1.5, x1 * 1.5), (y0 / 1.5, y1 * 1.5));

    // Label areas wide enough for the widest tick label and the axis description beside it: plotters
    // puts a tick label 10 px (twice the tick mark) from the axis and the description at the far edge.
    let tick_w = log_ticks_in(y_range.0, y_range.1)
        .iter()
        .map(|t| text_size(t, TICK_PX).0)
        .max()
        .unwrap_or(0);
    let tick_h = text_size("0123456789e-", TICK_PX).1;
    let desc_h = text_size(&format!("{x_label}{y_label}Ag"), AXIS_DESC_PX).1;
    let y_area = 10 + tick_w + 14 + desc_h + 4;
    let x_area = 10 + tick_h + 14 + desc_h + 4;

    let root = BitMapBackend::new(path, CHART_SIZE).into_drawing_area();
    root.fill(&WHITE).map_err(|e| anyhow!("{e}"))?;
    let body = draw_title(&root, title, CAPTION_PX)?;
    let mut chart = ChartBuilder::on(&body)
        .margin(MARGIN_PX)
        .margin_right(2 * MARGIN_PX)
        .x_label_area_size(x_area)
        .y_label_area_size(y_area)
        .build_cartesian_2d(
            (x_range.0..x_range.1).log_scale(),
            (y_range.0..y_range.1).log_scale(),
        )
        .map_err(|e| anyhow!("{e}"))?;
    chart
        .configure_mesh()
        .x_desc(x_label)
        .y_desc(y_label)
        .x_label_formatter(&|v| log_tick(*v))
        .y_label_formatter(&|v| log_tick(*v))
        .x_label_style(("sans-serif", TICK_PX))
        .y_label_style(("sans-serif", TICK_PX))
        .axis_desc_style(("sans-serif", AXIS_DESC_PX))
        .draw()
        .map_err(|e| anyhow!("{e}"))?;

    let base = chart.plotting_area().get_base_pixel();
    let mut labels = Vec::new();
    let mut lines = Vec::new();
    for (i, s) in series.iter().enumerate() {
        let colour = series_colour(i);
        debug_assert!(!too_light(colour), "{colour:?} on white");
        let line = ShapeStyle::from(colour).stroke_width(LINE_PX);
        let pts: Vec<(f64, f64)> = s.points.iter().copied().filter(usable).collect();
        let label = match (with_slope, loglog_slope(&pts)) {
            (true, Some(k)) => format!("{} (slope {k:.2})", s.label),
            _ => s.label.clone(),
        };
        let mid = LEGEND_GLYPH_PX / 2;
        let marker = move || Circle::new((mid, 0), MARKER_PX, colour.filled());
        if s.label.contains("biased") {
            chart
                .draw_series(DashedLineSeries::new(pts.clone(), 12, 7, line))
                .map_err(|e| anyhow!("{e}"))?
                .label(label.clone())
                .legend(move |p| {
                    EmptyElement::at(p)
                        + PathElement::new(vec![(0, 0), (mid - 5, 0)], line)
                        + PathElement::new(vec![(mid + 5, 0), (LEGEND_GLYPH_PX, 0)], line)
                        + marker()
                });
        } else {
            chart
                .draw_series(LineSeries::new(pts.clone(), line))
                .map_err(|e| anyhow!("{e}"))?
                .label(label.clone())
                .legend(move |p| {
                    EmptyElement::at(p)
                        + PathElement::new(vec![(0, 0), (LEGEND_GLYPH_PX, 0)], line)
                        + marker()
                });
        }
        chart
            .draw_series(
                pts.iter()
                    .map(|&p| Circle::new(p, MARKER_PX, colour.filled())),
            )
            .map_err(|e| anyhow!("{e}"))?;
        labels.push(label);
        lines.push(
            pts.iter()
                .map(|p| {
                    let (x, y) = chart.backend_coord(p);
                    (x - base.0, y - base.1)
                })
                .collect(),
        );
    }
    let (w, h) = chart.plotting_area().dim_in_pixel();
    let (lx, ly) = legend_corner(legend_size(&labels), (w as i32, h as i32), &lines);
    chart
        .configure_series_labels()
        .label_font(("sans-serif", LEGEND_PX))
        .legend_area_size(LEGEND_AREA_PX)
        .margin(LEGEND_MARGIN_PX)
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK)
        .position(SeriesLabelPosition::Coordinate(lx, ly))
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
/// noise stays visible as noise), each labelled underneath, under a `title` (in two lines or more
/// if the grid is narrower than it); written as PNG.
pub fn image_grid(
    path: &Path,
    title: &str,
    panels: &[Panel],
    scale: usize,
    cols: usize,
) -> Result<()> {
    register_fonts();
    let gap = 12usize;
    let cols = cols.clamp(1, panels.len().max(1));
    let rows = panels.len().div_ceil(cols);
    let cw = panels.iter().map(|p| p.width).max().unwrap_or(1) * scale;
    let ch = panels.iter().map(|p| p.height).max().unwrap_or(1) * scale;
    // Each label in lines no wider than its picture (a long one would run into its neighbour's),
    // and the band under every row as tall as its most lines.
    let label_lines: Vec<Vec<String>> = panels
        .iter()
        .map(|p| wrap(&p.label, cw as u32, |s| text_size(s, GRID_LABEL_PX).0))
        .collect();
    let line_h = (GRID_LABEL_PX * 5 / 4) as usize;
    let most = label_lines.iter().map(Vec::len).max().unwrap_or(1);
    let label_h = most * line_h + 14 - (line_h - GRID_LABEL_PX as usize);
    let w = cols * cw + (cols + 1) * gap;
    // the title, and 11 pixels more above the pictures than a chart leaves
    let title_h = title_height(title, w as u32, GRID_TITLE_PX) as usize + 11;
    let h = title_h + rows * (ch + label_h) + rows * gap;
    let root = BitMapBackend::new(path, (w as u32, h as u32)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| anyhow!("{e}"))?;
    draw_title(&root, title, GRID_TITLE_PX)?;
    let label_style = centred(GRID_LABEL_PX);
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
        for (k, line) in label_lines[i].iter().enumerate() {
            root.draw_text(
                line,
                &label_style,
                (
                    (x0 + p.width * scale / 2) as i32,
                    (y0 + p.height * scale + 6 + k * line_h) as i32,
                ),
            )
            .map_err(|e| anyhow!("{e}"))?;
        }
    }
    root.present()
        .with_context(|| format!("writing {}", path.display()))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_grid_label_longer_than_its_picture_wraps_under_it() {
        let dir = std::env::temp_dir().join(format!("rtl-grid-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let panel = |label: &str| Panel {
            width: 40,
            height: 40,
            rgb: vec![128; 40 * 40 * 3],
            label: label.to_string(),
        };
        let height = |label: &str| {
            let path = dir.join("grid.png");
            image_grid(&path, "t", &[panel("a"), panel(label)], 4, 2).unwrap();
            image::image_dimensions(&path).unwrap()
        };
        let (w, short) = height("short");
        let long =
            "noise without connections (--no-manifold): c = 0.222, a label wider than 160 px";
        let (w2, tall) = height(long);
        // The same width (nothing runs into the neighbour), and a taller band for the extra lines.
        assert_eq!(w, w2);
        assert!(tall >= short + GRID_LABEL_PX, "{short} -> {tall}");
        let lines = wrap(long, 160, |s| text_size(s, GRID_LABEL_PX).0);
        assert!(lines.len() >= 2, "{lines:?}");
        assert!(
            lines.iter().all(|l| text_size(l, GRID_LABEL_PX).0 <= 160),
            "{lines:?}"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }

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
        assert_eq!(
            log_ticks_in(0.15, 12.0),
            ["0.2", "0.5", "1", "2", "5", "10"]
        );
    }

    /// The indices of two series of one chart that would be drawn in the same colour, among the
    /// first `n`.
    fn shared_colours(n: usize, colour: impl Fn(usize) -> RGBColor) -> Option<(usize, usize)> {
        (0..n).find_map(|i| (0..i).find(|&j| colour(j) == colour(i)).map(|j| (j, i)))
    }

    #[test]
    fn no_two_series_share_a_colour_up_to_the_palettes_length() {
        assert_eq!(shared_colours(PALETTE.len(), series_colour), None);
        // the checker sees a repeat
        assert_eq!(
            shared_colours(PALETTE.len() + 1, series_colour),
            Some((0, PALETTE.len()))
        );
    }

    #[test]
    fn no_palette_colour_is_too_light_on_white() {
        for (i, &c) in PALETTE.iter().enumerate() {
            assert!(
                !too_light(c),
                "colour {i} {c:?}: luminance {:.3} > {MAX_LUMINANCE}",
                relative_luminance(c)
            );
        }
        // The checker against known values: white 1, black 0, sRGB mid grey 0.216, and the yellows
        // this palette leaves out: plotters' Palette99 (its third colour, drawn for series 2 before)
        // and Okabe and Ito's own.
        assert!((relative_luminance(WHITE) - 1.0).abs() < 1e-12);
        assert_eq!(relative_luminance(BLACK), 0.0);
        assert!((relative_luminance(RGBColor(128, 128, 128)) - 0.2159).abs() < 1e-3);
        let palette99_yellow = Palette99::pick(2).to_rgba();
        let palette99_yellow = RGBColor(palette99_yellow.0, palette99_yellow.1, palette99_yellow.2);
        assert_eq!(palette99_yellow, RGBColor(255, 225, 25));
        assert!(too_light(palette99_yellow));
        assert!(too_light(RGBColor(0xF0, 0xE4, 0x42)));
    }

    #[test]
    fn titles_wrap_at_spaces_to_the_width() {
        let chars = |s: &str| s.len() as u32;
        assert_eq!(wrap("a bb ccc dddd", 6, chars), ["a bb", "ccc", "dddd"]);
        assert_eq!(wrap("short", 60, chars), ["short"]);
        assert_eq!(wrap("toolongword x", 4, chars), ["toolongword", "x"]);
        // two even lines, not a full one and a word
        assert_eq!(
            wrap("aaa bbb ccc ddd eee", 16, chars),
            ["aaa bbb ccc", "ddd eee"]
        );
    }

    #[test]
    fn the_legend_goes_where_no_line_is() {
        // a line from the upper left to the lower right of a 400 x 300 area, and one along the bottom:
        // the lower left and right are taken, the upper right is free
        let lines = vec![vec![(0, 0), (400, 300)], vec![(0, 290), (400, 290)]];
        let (x, y) = legend_corner((100, 60), (400, 300), &lines);
        assert_eq!((x, y), (400 - 100 - 6, 6));
        // nothing drawn: the lower left
        assert_eq!(legend_corner((100, 60), (400, 300), &[]), (6, 300 - 60 - 6));
        // every named place taken (a frame just inside the edges, and a cross through the middle): a
        // free place between them
        let frame = vec![(3, 3), (397, 3), (397, 297), (3, 297), (3, 3)];
        let cross = vec![vec![(200, 0), (200, 300)], vec![(0, 150), (400, 150)]];
        let mut lines = vec![frame];
        lines.extend(cross);
        let (x, y) = legend_corner((100, 60), (400, 300), &lines);
        assert!(
            x >= 8 && x + 100 <= 196 && (y >= 8 && y + 60 <= 146 || y >= 154 && y + 60 <= 292),
            "{x} {y}"
        );
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
        let b = Series {
            label: "b (biased)".into(),
            points: vec![(1.0, 0.5), (10.0, 0.4), (100.0, 0.35)],
        };
        loglog(&path, "test", "N", "error", &[s, b], true).unwrap();
        let bytes = std::fs::read(&path).unwrap();
        assert_eq!(&bytes[1..4], b"PNG");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
