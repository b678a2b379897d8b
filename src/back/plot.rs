//! The distortion plot: how far the variations move from themselves as relations are kept.
//!
//! Drawn with `plotters`, as PNG or SVG ([`PlotFormat`], by the file's extension): relations
//! kept on x, the distortion (1 − mean IoU of the variations projected onto the relations
//! kept so far) on y, on a log scale when the curve spans more than [`LOG_SPAN`]. The kept
//! prefix is shaded, the cutoff is a red line whose step and reason are written under the
//! chart, and the paper's change point and the published mean-shift point are dashed lines
//! when they fall elsewhere. In SVG each step carries its relation in words as a tooltip
//! (`<title>`). Nothing here decides anything: the figures are the report's.

use super::font::{FAMILY, ready};
use super::report::Report;
use crate::tolerance::MIN_PLOT_SCALE;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

const W: u32 = 960;
const H: u32 = 540;
/// The ratio of the largest to the smallest positive distortion above which y is logarithmic.
pub const LOG_SPAN: f64 = 100.0;
/// The y axis's label.
pub const Y_LABEL: &str = "distortion (1 − mean IoU of the variations)";
/// The x axis's label.
pub const X_LABEL: &str = "relations kept (in the order chosen)";
/// The top of a linear y axis below which its labels are in scientific notation.
const SMALL_SCALE: f64 = 0.01;
/// The most characters of the cutoff's reason on one line under the chart.
const REASON_LINE: usize = 130;

/// The picture's file format.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PlotFormat {
    Png,
    Svg,
}

impl PlotFormat {
    /// SVG when the file's extension says so (any case), else PNG.
    pub fn of_path(path: &Path) -> PlotFormat {
        match path.extension() {
            Some(e) if e.eq_ignore_ascii_case("svg") => PlotFormat::Svg,
            _ => PlotFormat::Png,
        }
    }
}

/// The y axis: the values as drawn (log10 of the distortion on a log scale) and the range.
struct Scale {
    log: bool,
    lo: f64,
    hi: f64,
}

impl Scale {
    fn of(curve: &[f64]) -> Scale {
        let top = curve
            .iter()
            .copied()
            .fold(0.0, f64::max)
            .max(MIN_PLOT_SCALE);
        let least = curve
            .iter()
            .copied()
            .filter(|&v| v > MIN_PLOT_SCALE)
            .fold(top, f64::min);
        if top / least > LOG_SPAN {
            let lo = (least / 2.0).log10().floor();
            Scale {
                log: true,
                lo,
                hi: top.log10().ceil().max(lo + 1.0),
            }
        } else {
            Scale {
                log: false,
                lo: 0.0,
                hi: top * 1.1,
            }
        }
    }

    /// Where a distortion is drawn (zero sits on the axis of a log scale).
    fn y(&self, v: f64) -> f64 {
        if self.log {
            v.max(10f64.powf(self.lo)).log10()
        } else {
            v
        }
    }

    fn label(&self, y: f64) -> String {
        if self.log {
            format!("{:.0e}", 10f64.powf(y))
        } else if self.hi < SMALL_SCALE {
            format!("{y:.1e}")
        } else {
            format!("{y:.3}")
        }
    }
}

/// The distortion plot of `report` as PNG or SVG bytes.
pub fn distortion_plot(report: &Report, format: PlotFormat) -> Result<Vec<u8>, String> {
    ready()?;
    match format {
        PlotFormat::Svg => {
            let mut svg = String::new();
            let tips = {
                let root = SVGBackend::with_string(&mut svg, (W, H)).into_drawing_area();
                let tips = draw(&root, report).map_err(|e| e.to_string())?;
                root.present().map_err(|e| e.to_string())?;
                tips
            };
            Ok(with_tooltips(svg, &tips).into_bytes())
        }
        PlotFormat::Png => {
            let mut buf = vec![0u8; (W * H * 3) as usize];
            {
                let root = BitMapBackend::with_buffer(&mut buf, (W, H)).into_drawing_area();
                draw(&root, report).map_err(|e| e.to_string())?;
                root.present().map_err(|e| e.to_string())?;
            }
            encode_png(&buf, W, H)
        }
    }
}

/// RGB bytes as a PNG.
pub(crate) fn encode_png(rgb: &[u8], width: u32, height: u32) -> Result<Vec<u8>, String> {
    let mut out = Vec::new();
    let mut enc = png::Encoder::new(&mut out, width, height);
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    let mut w = enc.write_header().map_err(|e| e.to_string())?;
    w.write_image_data(rgb).map_err(|e| e.to_string())?;
    w.finish().map_err(|e| e.to_string())?;
    Ok(out)
}

/// One step's tooltip: the pixel columns it covers and its text.
struct Tip {
    x0: i32,
    x1: i32,
    y0: i32,
    y1: i32,
    text: String,
}

/// A step's relation and its evidence, in words.
fn step_text(report: &Report, step: usize, keep: usize) -> String {
    let Some(c) = report.chosen.get(step - 1) else {
        return format!("step {step}");
    };
    let s = format!(
        "step {step}: {}; {}",
        c.relation,
        c.evidence(report.noise.as_ref())
    );
    s + if step <= keep {
        " (kept)"
    } else {
        " (left out)"
    }
}

type DrawResult<T, DB> = Result<T, DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

/// Draws the chart on `root`; returns where each step's tooltip goes.
fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    report: &Report,
) -> DrawResult<Vec<Tip>, DB> {
    root.fill(&WHITE)?;
    let curve = &report.distortion_curve;
    let n = curve.len().saturating_sub(1);
    let keep = report.keep_step().min(n);
    let scale = Scale::of(curve);
    let (chart_area, notes) = root.split_vertically(H - 70);
    let title = if n == 0 {
        "Distortion: no variations, so no curve".to_string()
    } else {
        format!("Distortion as relations are kept: {keep} of the {n} tested kept")
    };
    let mut chart = ChartBuilder::on(&chart_area)
        .caption(title, (FAMILY, 22))
        .margin(12)
        .x_label_area_size(50)
        .y_label_area_size(80)
        .build_cartesian_2d(0..n.max(1) as i32, scale.lo..scale.hi)?;
    chart
        .configure_mesh()
        .x_desc(X_LABEL)
        .y_desc(if scale.log {
            format!("{Y_LABEL}, log scale")
        } else {
            Y_LABEL.to_string()
        })
        .light_line_style(TRANSPARENT)
        .x_labels((n + 1).min(21))
        .y_labels(8)
        .y_label_formatter(&|y| scale.label(*y))
        .axis_desc_style((FAMILY, 16))
        .label_style((FAMILY, 13))
        .draw()?;
    if n == 0 {
        let grey = RGBColor(110, 110, 110);
        let style = TextStyle::from((FAMILY, 18)).color(&grey);
        let (x, y) = chart.backend_coord(&(0, scale.hi));
        chart_area.draw_text(
            "the curve is measured on variations (--vary)",
            &style,
            (x + 40, y + 60),
        )?;
        return Ok(Vec::new());
    }
    let shade = RGBColor(60, 170, 90);
    chart
        .draw_series(std::iter::once(Rectangle::new(
            [(0, scale.lo), (keep as i32, scale.hi)],
            shade.mix(0.15).filled(),
        )))?
        .label(format!("kept prefix: the first {keep} relations"))
        .legend(move |(x, y)| {
            Rectangle::new([(x, y - 6), (x + 18, y + 6)], shade.mix(0.3).filled())
        });
    let blue = RGBColor(30, 90, 200);
    let points: Vec<(i32, f64)> = curve
        .iter()
        .enumerate()
        .map(|(s, &v)| (s as i32, scale.y(v)))
        .collect();
    chart
        .draw_series(LineSeries::new(points.clone(), blue.stroke_width(2)))?
        .label("distortion after each relation")
        .legend(move |(x, y)| PathElement::new([(x, y), (x + 18, y)], blue.stroke_width(2)));
    chart.draw_series(points.iter().map(|&p| Circle::new(p, 3, blue.filled())))?;
    marks(&mut chart, report, keep, n, &scale)?;
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .label_font((FAMILY, 13))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK.mix(0.4))
        .draw()?;
    reason_lines(&notes, report)?;
    let tips = (1..=n)
        .map(|s| {
            let (x0, y0) = chart.backend_coord(&(s as i32 - 1, scale.hi));
            let (x1, y1) = chart.backend_coord(&(s as i32, scale.lo));
            Tip {
                x0: (x0 + x1) / 2,
                x1: x1 + (x1 - x0) / 2,
                y0,
                y1,
                text: step_text(report, s, keep),
            }
        })
        .collect();
    Ok(tips)
}

type Chart<'a, DB> = ChartContext<
    'a,
    DB,
    Cartesian2d<plotters::coord::types::RangedCoordi32, plotters::coord::types::RangedCoordf64>,
>;

/// The cutoff, and the paper's and the published change points where they differ from it.
fn marks<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    report: &Report,
    keep: usize,
    n: usize,
    scale: &Scale,
) -> DrawResult<(), DB> {
    let Some(cut) = &report.cutoff else {
        return Ok(());
    };
    let red = RGBColor(210, 40, 40);
    let at = |s: usize| vec![(s as i32, scale.lo), (s as i32, scale.hi)];
    chart
        .draw_series(LineSeries::new(at(keep), red.stroke_width(3)))?
        .label(format!("cutoff: keep {keep} (the noise test)"))
        .legend(move |(x, y)| PathElement::new([(x, y), (x + 18, y)], red.stroke_width(3)));
    let others = [
        (
            cut.paper,
            RGBColor(230, 140, 20),
            "the paper's change point",
        ),
        (
            cut.published,
            RGBColor(130, 60, 170),
            "the published mean-shift point",
        ),
    ];
    for (step, color, what) in others {
        if step == keep || step > n {
            continue;
        }
        chart
            .draw_series(DashedLineSeries::new(at(step), 8, 6, color.stroke_width(2)))?
            .label(format!("{what}: keep {step}"))
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 18, y)], color.stroke_width(2)));
    }
    Ok(())
}

/// The cutoff's reason under the chart, wrapped.
fn reason_lines<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    report: &Report,
) -> DrawResult<(), DB> {
    let Some(cut) = &report.cutoff else {
        return Ok(());
    };
    let text = format!("Cutoff at {}: {}", cut.keep, cut.reason);
    let style = TextStyle::from((FAMILY, 13)).color(&BLACK);
    for (i, line) in wrap(&text, REASON_LINE).iter().take(4).enumerate() {
        area.draw_text(line, &style, (20, 4 + 16 * i as i32))?;
    }
    Ok(())
}

/// `text` in lines of at most `width` characters, broken at spaces.
pub(crate) fn wrap(text: &str, width: usize) -> Vec<String> {
    let mut lines = vec![String::new()];
    for word in text.split_whitespace() {
        let last = lines.last_mut().map_or(0, |l| l.chars().count());
        if last > 0 && last + 1 + word.chars().count() > width {
            lines.push(String::new());
        }
        if let Some(l) = lines.last_mut() {
            if !l.is_empty() {
                l.push(' ');
            }
            l.push_str(word);
        }
    }
    lines
}

/// Text safe inside XML and HTML.
pub fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The SVG with one transparent column per step whose `<title>` is the step in words.
fn with_tooltips(svg: String, tips: &[Tip]) -> String {
    let mut cols = String::from("<g class=\"steps\">\n");
    for t in tips {
        cols += &format!(
            "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"transparent\" pointer-events=\"all\"><title>{}</title></rect>\n",
            t.x0.min(t.x1),
            t.y0.min(t.y1),
            (t.x1 - t.x0).abs().max(1),
            (t.y1 - t.y0).abs().max(1),
            escape(&t.text)
        );
    }
    cols += "</g>\n</svg>";
    match svg.rfind("</svg>") {
        Some(i) => format!("{}{}{}", &svg[..i], cols, &svg[i + "</svg>".len()..]),
        None => svg,
    }
}
