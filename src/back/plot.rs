//! A small PNG line chart of the distortion curve, with the cutoff marked.
//!
//! Plain pixels, no plotting dependency: a white canvas, axes, the curve in blue, a red
//! vertical line at the cutoff step. Good enough to see where the jump is.

use crate::tolerance::MIN_PLOT_SCALE;
use std::io::Write;

const W: usize = 640;
const H: usize = 360;
const MARGIN: usize = 40;

struct Canvas {
    px: Vec<[u8; 3]>,
}

impl Canvas {
    fn new() -> Self {
        Canvas {
            px: vec![[255, 255, 255]; W * H],
        }
    }

    fn set(&mut self, x: i64, y: i64, c: [u8; 3]) {
        if (0..W as i64).contains(&x) && (0..H as i64).contains(&y) {
            self.px[y as usize * W + x as usize] = c;
        }
    }

    /// A line by Bresenham's algorithm, `width` pixels thick.
    fn line(&mut self, (x0, y0): (i64, i64), (x1, y1): (i64, i64), c: [u8; 3], width: i64) {
        let (dx, dy) = ((x1 - x0).abs(), -(y1 - y0).abs());
        let (sx, sy) = (if x0 < x1 { 1 } else { -1 }, if y0 < y1 { 1 } else { -1 });
        let (mut x, mut y, mut err) = (x0, y0, dx + dy);
        loop {
            for ox in 0..width {
                for oy in 0..width {
                    self.set(x + ox - width / 2, y + oy - width / 2, c);
                }
            }
            if x == x1 && y == y1 {
                break;
            }
            let e2 = 2 * err;
            if e2 >= dy {
                err += dy;
                x += sx;
            }
            if e2 <= dx {
                err += dx;
                y += sy;
            }
        }
    }
}

/// The chart as PNG bytes: `curve[s]` against step `s`, the cutoff at `keep`.
pub fn distortion_png(curve: &[f64], keep: usize) -> Vec<u8> {
    let mut c = Canvas::new();
    let grey = [120, 120, 120];
    let (x0, y0, x1, y1) = (
        MARGIN as i64,
        (H - MARGIN) as i64,
        (W - MARGIN / 2) as i64,
        (MARGIN / 2) as i64,
    );
    c.line((x0, y0), (x1, y0), grey, 1);
    c.line((x0, y0), (x0, y1), grey, 1);
    let n = curve.len().max(2) - 1;
    let top = curve
        .iter()
        .copied()
        .fold(0.0, f64::max)
        .max(MIN_PLOT_SCALE);
    let at = |i: usize, v: f64| {
        let x = x0 + ((x1 - x0) as f64 * i as f64 / n as f64).round() as i64;
        let y = y0 - ((y0 - y1) as f64 * (v / top).clamp(0.0, 1.0)).round() as i64;
        (x, y)
    };
    let cut = at(keep.min(n), 0.0).0;
    c.line((cut, y0), (cut, y1), [220, 40, 40], 2);
    for i in 1..curve.len() {
        c.line(at(i - 1, curve[i - 1]), at(i, curve[i]), [30, 90, 200], 2);
    }
    let mut out = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut out, W as u32, H as u32);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        if let Ok(mut w) = enc.write_header() {
            let data: Vec<u8> = c.px.iter().flatten().copied().collect();
            let _ = w.write_image_data(&data);
        }
    }
    let mut v = Vec::new();
    let _ = v.write_all(&out);
    v
}
