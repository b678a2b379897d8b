//! The paper's image loss and its per-pixel derivatives.
//!
//! `L(x) = Σ_views ‖sharpen(R(x)) − sharpen(I)‖² + λ‖x − x₀‖²` with
//! `sharpen(I) = I − 0.2·blur(I)`. Here `R` and `I` have two channels that can be compared
//! between a render and a picture of anything on a plain background: coverage (the
//! foreground mask) and premultiplied shade (grey level times coverage). Each view's squared
//! norm is a mean over its pixels, so image size does not change the step size; the shade
//! channel has weight [`LossSpec::shading`].
//!
//! `sharpen` is linear and symmetric (a Gaussian blur with zero padding), so the derivative
//! of `‖sharpen(r)‖²` with respect to `r` is `2·sharpen(sharpen(r))`. With
//! [`LossSpec::smooth`] both images are blurred before they are sharpened, and the
//! derivative runs the two steps in the other order (the transpose).
//!
//! The loss is the fit's, not the renderer's: [`ImageLoss`] is the
//! [`ImageFunction`] the renderer evaluates and differentiates, and [`image_loss`] asks a
//! backend for it.

use super::coverage::{Rim, colour_distance};
use crate::render::image::Rgb;
use crate::render::scene::{NSHADE, Scene};
use crate::render::soft::{SoftImage, ViewPrep};
use crate::render::{Backend, ImageFunction, ImageValue, ImageValues};
use crate::tolerance::COVERAGE_FLOOR;
use rayon::prelude::*;

/// How images are compared.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LossSpec {
    /// The `0.2` in `I − 0.2·blur(I)`.
    pub sharpen: f64,
    /// Standard deviation of the blur, pixels.
    pub blur: f64,
    /// Weight of the shade channel (the coverage channel has weight 1).
    pub shading: f64,
    /// Compare after this many 2×2 average poolings (0: at full resolution). Coarse levels
    /// see parts that are far from where they should be.
    pub level: u32,
    /// Standard deviation, in pixels of the compared images, of a Gaussian blur of both
    /// images before they are sharpened; 0: none. A blur of the difference of two exact
    /// coverages is least where they are equal, at any width: the soft rounds of a fit
    /// with [`super::SoftEdges::Blurred`] compare so.
    pub smooth: f64,
}

impl Default for LossSpec {
    fn default() -> Self {
        LossSpec {
            sharpen: 0.2,
            blur: 1.0,
            shading: 1.0,
            level: 0,
            smooth: 0.0,
        }
    }
}

/// A target picture as channels: foreground coverage and premultiplied grey.
#[derive(Debug, Clone, PartialEq)]
pub struct Target {
    pub width: u32,
    pub height: u32,
    pub m: Vec<f32>,
    /// `m · grey`.
    pub s: Vec<f32>,
    /// Grey level (luminance) everywhere.
    pub grey: Vec<f32>,
    /// The background colour found at the border.
    pub background: [f32; 3],
    /// Pixels of background the fit put around the picture on every side
    /// ([`super::FitOptions::border`]); 0 for a picture as given.
    pub border: u32,
    /// Whether the picture was drawn with hard edges, each pixel sampled at one point
    /// (OpenSCAD's; [`super::coverage`] tells them): a loss on area coverage is then not
    /// least at the truth, a hard-edged render's is. False for antialiased pictures, our
    /// renders and pooled targets.
    pub hard_edges: bool,
}

/// Colour distance below which a pixel is background, and above which it is foreground,
/// for a noiseless background; a noisy border raises both.
const FG_LO: f32 = 0.012;
const FG_HI: f32 = 0.03;
/// How many times the background's noise (the 90th percentile of its colour distances)
/// the thresholds are at least.
const FG_LO_NOISE: f32 = 3.0;
const FG_HI_NOISE: f32 = 6.0;

impl Target {
    /// Channels of a picture on a plain background: the background colour is the most
    /// common colour along the border; a pixel's coverage is how much of it the object
    /// covers, unmixed from the background ([`super::coverage`]); told hard-edged or
    /// antialiased by its own silhouette alone.
    pub fn from_rgb(img: &Rgb) -> Target {
        Target::set_from_rgb(std::slice::from_ref(img)).remove(0)
    }

    /// Channels of pictures from one renderer (a fit's views), each read as
    /// [`Target::from_rgb`] reads one, but whether they were drawn with hard edges told
    /// from all their silhouettes together: a renderer draws every view alike, and a view
    /// of pale faces whose facets look like mixes on their own is read as its renderer
    /// drew it.
    pub fn set_from_rgb(imgs: &[Rgb]) -> Vec<Target> {
        let found: Vec<([f32; 3], f32, f32, Rim)> = imgs
            .par_iter()
            .map(|img| {
                let (background, lo, hi) = foreground_thresholds(img);
                (background, lo, hi, Rim::of(img, background, lo, hi))
            })
            .collect();
        let hard = found
            .iter()
            .fold(Rim::default(), |all, f| all.and(f.3))
            .hard_edges();
        imgs.par_iter()
            .zip(&found)
            .map(|(img, &(background, lo, hi, _))| Target::read(img, background, lo, hi, hard))
            .collect()
    }

    /// The picture's channels with its background and thresholds found, read whole where
    /// it was drawn with `hard` edges.
    fn read(img: &Rgb, background: [f32; 3], lo: f32, hi: f32, hard: bool) -> Target {
        let grey = img.luminance();
        let (m, s) = super::coverage::read(img, background, lo, hi, hard);
        let grey = grey
            .iter()
            .zip(m.iter().zip(&s))
            .map(|(&g, (&m, &s))| if m > COVERAGE_FLOOR { s / m } else { g })
            .collect();
        Target {
            width: img.width,
            height: img.height,
            m,
            s,
            grey,
            background,
            border: 0,
            hard_edges: hard,
        }
    }

    /// Channels straight from a render (for tests and synthetic targets).
    pub fn from_soft(img: &SoftImage) -> Target {
        let grey = img
            .m
            .iter()
            .zip(&img.s)
            .map(|(&m, &s)| if m > COVERAGE_FLOOR { s / m } else { 0.0 })
            .collect();
        Target {
            width: img.width,
            height: img.height,
            m: img.m.clone(),
            s: img.s.clone(),
            grey,
            background: [1.0; 3],
            border: 0,
            hard_edges: false,
        }
    }

    /// The target at half the size (2×2 average pooling of its channels, which antialiases
    /// it).
    pub fn pooled(&self) -> Target {
        let (m, w, h) = pool(&self.m, self.width, self.height);
        let s = pool(&self.s, self.width, self.height).0;
        let grey = m
            .iter()
            .zip(&s)
            .map(|(&m, &s)| if m > COVERAGE_FLOOR { s / m } else { 0.0 })
            .collect();
        Target {
            width: w,
            height: h,
            m,
            s,
            grey,
            background: self.background,
            border: self.border / 2,
            hard_edges: false,
        }
    }

    /// The target inside a frame of background `px` pixels wide on every side.
    pub fn with_border(&self, px: u32) -> Target {
        if px == 0 {
            return self.clone();
        }
        let (w, h) = (self.width + 2 * px, self.height + 2 * px);
        let pad = |c: &[f32]| -> Vec<f32> {
            let mut out = vec![0.0; (w * h) as usize];
            for (y, row) in c.chunks(self.width as usize).enumerate() {
                let at = ((y as u32 + px) * w + px) as usize;
                out[at..at + row.len()].copy_from_slice(row);
            }
            out
        };
        Target {
            width: w,
            height: h,
            m: pad(&self.m),
            s: pad(&self.s),
            grey: pad(&self.grey),
            background: self.background,
            border: self.border + px,
            hard_edges: self.hard_edges,
        }
    }

    /// The share of the image that is the picture itself (1 without a border).
    pub fn picture_share(&self) -> f64 {
        let inner = |n: u32| n.saturating_sub(2 * self.border) as f64;
        inner(self.width) * inner(self.height) / (self.width * self.height) as f64
    }

    /// Number of foreground pixels (coverage above one half).
    pub fn foreground(&self) -> usize {
        self.m.iter().filter(|&&m| m > 0.5).count()
    }
}

/// A picture's background colour and the colour distances from it below which a pixel is
/// background and above which it is foreground (raised above [`FG_LO`], [`FG_HI`] by the
/// noise of the border's background pixels).
///
/// The noise is read on the background alone: an object the frame cuts (a picture of
/// something larger than the view, as a diffusion sample may draw) puts foreground pixels
/// on the border, and were they read as noise the thresholds would rise above every
/// foreground colour and the picture would read as empty. A border pixel further from the
/// background than [`FG_HI`] and than the foreground threshold the border's median would
/// give is not background.
fn foreground_thresholds(img: &Rgb) -> ([f32; 3], f32, f32) {
    let background = border_colour(img);
    let mut border: Vec<f32> = border_pixels(img)
        .iter()
        .map(|c| colour_distance(c, &background))
        .collect();
    border.sort_by(f32::total_cmp);
    let median = border.get(border.len() / 2).copied().unwrap_or(0.0);
    let cap = FG_HI.max(FG_HI_NOISE * median);
    let own = border.partition_point(|&d| d <= cap);
    let noise = border[..own].get(own * 9 / 10).copied().unwrap_or(0.0);
    (
        background,
        FG_LO.max(FG_LO_NOISE * noise),
        FG_HI.max(FG_HI_NOISE * noise),
    )
}

/// A quick reading of a picture for comparing pictures with each other, not for fitting:
/// each pixel's foreground share by its colour's distance from the background alone (no
/// unmixing of edge pixels) and its grey level times that share.
pub fn quick_channels(img: &Rgb) -> (Vec<f32>, Vec<f32>) {
    let (background, lo, hi) = foreground_thresholds(img);
    img.data
        .iter()
        .map(|c| {
            let t = ((colour_distance(c, &background) - lo) / (hi - lo)).clamp(0.0, 1.0);
            let m = t * t * (3.0 - 2.0 * t);
            (m, m * (0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]))
        })
        .unzip()
}

fn border_pixels(img: &Rgb) -> Vec<[f32; 3]> {
    let (w, h) = (img.width, img.height);
    let mut border = Vec::new();
    for x in 0..w {
        border.push(img.get(x, 0));
        border.push(img.get(x, h - 1));
    }
    for y in 0..h {
        border.push(img.get(0, y));
        border.push(img.get(w - 1, y));
    }
    border
}

/// The most common colour of the border pixels (quantised to 1/32), averaged.
fn border_colour(img: &Rgb) -> [f32; 3] {
    let border = border_pixels(img);
    let key = |c: &[f32; 3]| c.map(|v| (v * 32.0).round() as i32);
    let mut counts: std::collections::HashMap<[i32; 3], (usize, [f64; 3])> = Default::default();
    for c in &border {
        let e = counts.entry(key(c)).or_insert((0, [0.0; 3]));
        e.0 += 1;
        for (sum, v) in e.1.iter_mut().zip(c) {
            *sum += f64::from(*v);
        }
    }
    let best = counts
        .into_iter()
        .max_by(|a, b| a.1.0.cmp(&b.1.0).then(b.0.cmp(&a.0)))
        .map(|(_, v)| v);
    match best {
        Some((n, sum)) => sum.map(|v| (v / n as f64) as f32),
        None => [1.0; 3],
    }
}

/// A normalised Gaussian kernel of standard deviation `sigma` (radius `⌈3σ⌉`).
pub fn gaussian_kernel(sigma: f64) -> Vec<f32> {
    if sigma <= 0.0 {
        return vec![1.0];
    }
    let r = (3.0 * sigma).ceil() as i32;
    let mut k: Vec<f64> = (-r..=r)
        .map(|i| (-(i * i) as f64 / (2.0 * sigma * sigma)).exp())
        .collect();
    let sum: f64 = k.iter().sum();
    k.iter_mut().for_each(|v| *v /= sum);
    k.into_iter().map(|v| v as f32).collect()
}

/// `img − amount·blur(img)` with a separable Gaussian and zero padding. The blur runs
/// only on the rectangle within the kernel's reach of a non-zero pixel (a residual is zero
/// wherever neither picture shows the object); outside it the blur is exactly zero.
pub fn sharpen(img: &[f32], width: u32, height: u32, spec: &LossSpec) -> Vec<f32> {
    let mut out = img.to_vec();
    if spec.sharpen == 0.0 {
        return out;
    }
    let kernel = gaussian_kernel(spec.blur);
    let (w, h) = (width as usize, height as usize);
    let Some([x0, y0, x1, y1]) = support(img, w, h, kernel.len() / 2) else {
        return out;
    };
    let cw = x1 - x0;
    let crop: Vec<f32> = (y0..y1)
        .flat_map(|y| img[y * w + x0..y * w + x1].iter().copied())
        .collect();
    let blurred = blur(&crop, cw, y1 - y0, &kernel);
    let a = spec.sharpen as f32;
    for (y, row) in blurred.chunks(cw).enumerate() {
        let dst = &mut out[(y0 + y) * w + x0..(y0 + y) * w + x1];
        for (v, b) in dst.iter_mut().zip(row) {
            *v -= a * b;
        }
    }
    out
}

/// The rectangle `[x0, y0, x1, y1)` of the non-zero pixels of a `w`×`h` image grown by
/// `reach` on every side (clipped to the image); `None` when every pixel is zero.
fn support(img: &[f32], w: usize, h: usize, reach: usize) -> Option<[usize; 4]> {
    support_where(w, h, reach, &[(img, None)])
}

/// Separable convolution with zero padding.
pub fn blur(img: &[f32], w: usize, h: usize, kernel: &[f32]) -> Vec<f32> {
    let r = (kernel.len() / 2) as isize;
    let mut tmp = vec![0.0f32; w * h];
    // Tap by tap over whole rows (each pixel still sums its taps in order), so the inner
    // loop is a plain multiply-add over a slice.
    for y in 0..h {
        let row = &img[y * w..(y + 1) * w];
        let dst = &mut tmp[y * w..(y + 1) * w];
        for (k, &kv) in kernel.iter().enumerate() {
            let shift = k as isize - r;
            let lo = (-shift).clamp(0, w as isize) as usize;
            let hi = (w as isize - shift).clamp(0, w as isize) as usize;
            if lo >= hi {
                continue;
            }
            let src = &row[(lo as isize + shift) as usize..(hi as isize + shift) as usize];
            for (d, v) in dst[lo..hi].iter_mut().zip(src) {
                *d += kv * v;
            }
        }
    }
    let mut out = vec![0.0f32; w * h];
    for y in 0..h {
        for (k, &kv) in kernel.iter().enumerate() {
            let yy = y as isize + k as isize - r;
            if yy < 0 || yy as usize >= h {
                continue;
            }
            let src = &tmp[yy as usize * w..(yy as usize + 1) * w];
            let dst = &mut out[y * w..(y + 1) * w];
            for x in 0..w {
                dst[x] += kv * src[x];
            }
        }
    }
    out
}

/// 2×2 average pooling (a last odd row or column is averaged on its own).
pub fn pool(img: &[f32], w: u32, h: u32) -> (Vec<f32>, u32, u32) {
    let (w2, h2) = (w.div_ceil(2), h.div_ceil(2));
    let mut out = vec![0.0f32; (w2 * h2) as usize];
    for y in 0..h2 {
        for x in 0..w2 {
            let mut acc = 0.0;
            let mut n = 0.0;
            for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                let (xx, yy) = (2 * x + dx, 2 * y + dy);
                if xx < w && yy < h {
                    acc += img[(yy * w + xx) as usize];
                    n += 1.0;
                }
            }
            out[(y * w2 + x) as usize] = acc / n;
        }
    }
    (out, w2, h2)
}

/// The transpose of [`pool`]: each coarse value spread back over the pixels it averaged.
pub fn unpool(img: &[f32], w: u32, h: u32) -> Vec<f32> {
    let w2 = w.div_ceil(2);
    let mut out = vec![0.0f32; (w * h) as usize];
    for y in 0..h {
        for x in 0..w {
            let (cx, cy) = (x / 2, y / 2);
            let nx = if 2 * cx + 1 < w { 2.0 } else { 1.0 };
            let ny = if 2 * cy + 1 < h { 2.0 } else { 1.0 };
            out[(y * w + x) as usize] = img[(cy * w2 + cx) as usize] / (nx * ny);
        }
    }
    out
}

/// The sharpened differences of one view from its target (after `spec.level` poolings),
/// kept only on `rect` (`[x0, y0, x1, y1)` of the `w`×`h` image, `None` when the render
/// equals the target): outside it both the differences and everything sharpened from them
/// (twice, for a gradient) are zero. Also the image sizes they were pooled through and the
/// pixel count their means are over.
struct Sharpened {
    qm: Vec<f32>,
    qs: Vec<f32>,
    rect: Option<[usize; 4]>,
    w: u32,
    h: u32,
    sizes: Vec<(u32, u32)>,
    n: f64,
}

fn sharpened(render: &SoftImage, target: &Target, spec: &LossSpec) -> Sharpened {
    let (w0, h0) = (render.width, render.height);
    // Comparing twice (the gradient) reaches twice the kernels' radii beyond the differences.
    let reach = 2 * operator_radius(spec);
    let n_at = |w: u32, h: u32| (w * h) as f64 * target.picture_share();
    if spec.level == 0 {
        // At full size the differences are taken on their rectangle alone.
        let (w, h) = (w0 as usize, h0 as usize);
        let pairs = [
            (&render.m[..], Some(&target.m[..])),
            (&render.s[..], Some(&target.s[..])),
        ];
        let rect = support_where(w, h, reach, &pairs);
        let (qm, qs) = match rect {
            Some(r) => (
                compare_rect(&crop_difference(&render.m, &target.m, w, r), r, spec),
                compare_rect(&crop_difference(&render.s, &target.s, w, r), r, spec),
            ),
            None => (Vec::new(), Vec::new()),
        };
        return Sharpened {
            qm,
            qs,
            rect,
            w: w0,
            h: h0,
            sizes: vec![(w0, h0)],
            n: n_at(w0, h0),
        };
    }
    let mut rm: Vec<f32> = render.m.iter().zip(&target.m).map(|(a, b)| a - b).collect();
    let mut rs: Vec<f32> = render.s.iter().zip(&target.s).map(|(a, b)| a - b).collect();
    let mut sizes = vec![(w0, h0)];
    let (mut w, mut h) = (w0, h0);
    for _ in 0..spec.level {
        if w < 4 || h < 4 {
            break;
        }
        let (pm, w2, h2) = pool(&rm, w, h);
        rm = pm;
        rs = pool(&rs, w, h).0;
        (w, h) = (w2, h2);
        sizes.push((w, h));
    }
    let (wu, hu) = (w as usize, h as usize);
    let rect = support_where(wu, hu, reach, &[(&rm, None), (&rs, None)]);
    let (qm, qs) = match rect {
        Some(r) => (
            compare_rect(&crop(&rm, wu, r), r, spec),
            compare_rect(&crop(&rs, wu, r), r, spec),
        ),
        None => (Vec::new(), Vec::new()),
    };
    Sharpened {
        qm,
        qs,
        rect,
        w,
        h,
        sizes,
        n: n_at(w, h),
    }
}

/// The rectangle `[x0, y0, x1, y1)` of the pixels of `w`×`h` images where any pair of
/// `pairs` differs (an image paired with `None` differs from zero), grown by `reach` on
/// every side (clipped to the image); `None` when every pair is equal.
fn support_where(
    w: usize,
    h: usize,
    reach: usize,
    pairs: &[(&[f32], Option<&[f32]>)],
) -> Option<[usize; 4]> {
    let mut rect: Option<[usize; 4]> = None;
    for y in 0..h {
        let Some((first, last)) = row_span(pairs, y * w, w) else {
            continue;
        };
        let r = rect.get_or_insert([first, y, last + 1, y + 1]);
        r[0] = r[0].min(first);
        r[2] = r[2].max(last + 1);
        r[3] = y + 1;
    }
    rect.map(|[x0, y0, x1, y1]| {
        [
            x0.saturating_sub(reach),
            y0.saturating_sub(reach),
            (x1 + reach).min(w),
            (y1 + reach).min(h),
        ]
    })
}

/// Pixels [`row_span`] compares at once: a run this long is compared without an early
/// exit, which the compiler turns into vector compares (most rows of a fit's difference
/// are zero, so the scan over them was most of the loss's own time).
const SPAN_RUN: usize = 32;

/// The first and last `x < w` where a pair of `pairs` differs at `row + x`, or `None`.
fn row_span(pairs: &[(&[f32], Option<&[f32]>)], row: usize, w: usize) -> Option<(usize, usize)> {
    let differs = |x0: usize, x1: usize| {
        pairs.iter().any(|(a, b)| {
            let a = &a[row + x0..row + x1];
            match b {
                Some(b) => {
                    let b = &b[row + x0..row + x1];
                    a.iter().zip(b).fold(false, |d, (p, q)| d | (p != q))
                }
                None => a.iter().fold(false, |d, p| d | (*p != 0.0)),
            }
        })
    };
    let runs = (0..w).step_by(SPAN_RUN);
    let first_run = runs
        .clone()
        .find(|&x0| differs(x0, (x0 + SPAN_RUN).min(w)))?;
    let last_run = runs
        .rev()
        .find(|&x0| differs(x0, (x0 + SPAN_RUN).min(w)))
        .unwrap_or(first_run);
    let first = (first_run..w).find(|&x| differs(x, x + 1))?;
    let last = (first..(last_run + SPAN_RUN).min(w))
        .rev()
        .find(|&x| differs(x, x + 1))
        .unwrap_or(first);
    Some((first, last))
}

/// `a − b` (images with rows `w` long) inside `rect`, row by row.
fn crop_difference(a: &[f32], b: &[f32], w: usize, [x0, y0, x1, y1]: [usize; 4]) -> Vec<f32> {
    let mut out = Vec::with_capacity((x1 - x0) * (y1 - y0));
    for y in y0..y1 {
        let (ra, rb) = (&a[y * w + x0..y * w + x1], &b[y * w + x0..y * w + x1]);
        out.extend(ra.iter().zip(rb).map(|(p, q)| p - q));
    }
    out
}

/// The pixels of `img` (rows `w` long) inside `rect`, row by row.
fn crop(img: &[f32], w: usize, [x0, y0, x1, y1]: [usize; 4]) -> Vec<f32> {
    (y0..y1)
        .flat_map(|y| img[y * w + x0..y * w + x1].iter().copied())
        .collect()
}

/// `values` (the pixels of `rect`) placed in a `w`×`h` image of zeros.
fn uncrop(values: &[f32], w: u32, h: u32, rect: Option<[usize; 4]>) -> Vec<f32> {
    let mut out = vec![0.0f32; (w * h) as usize];
    if let Some([x0, y0, x1, _]) = rect {
        let cw = x1 - x0;
        for (y, row) in values.chunks(cw).enumerate() {
            let at = (y0 + y) * w as usize + x0;
            out[at..at + cw].copy_from_slice(row);
        }
    }
    out
}

/// How far the compare operator ([`compare_rect`]) reaches from a non-zero pixel.
fn operator_radius(spec: &LossSpec) -> usize {
    let radius = |sigma: f64| gaussian_kernel(sigma).len() / 2;
    let sharpening = if spec.sharpen == 0.0 {
        0
    } else {
        radius(spec.blur)
    };
    sharpening + radius(spec.smooth)
}

/// Both images' operator on their difference: [`smooth`] then [`sharpen`], of an image
/// that is zero outside `rect`, given and returned on `rect`.
fn compare_rect(values: &[f32], [x0, y0, x1, y1]: [usize; 4], spec: &LossSpec) -> Vec<f32> {
    let (w, h) = (x1 - x0, y1 - y0);
    sharpen(&smooth(values, w, h, spec), w as u32, h as u32, spec)
}

/// The transpose of [`compare_rect`] (each of its two steps is symmetric): [`sharpen`]
/// then [`smooth`].
fn compare_rect_transposed(
    values: &[f32],
    [x0, y0, x1, y1]: [usize; 4],
    spec: &LossSpec,
) -> Vec<f32> {
    let (w, h) = (x1 - x0, y1 - y0);
    smooth(&sharpen(values, w as u32, h as u32, spec), w, h, spec)
}

/// `img` blurred by a Gaussian of `spec.smooth` pixels (zero padding); `img` itself when
/// that is 0.
fn smooth(img: &[f32], w: usize, h: usize, spec: &LossSpec) -> Vec<f32> {
    if spec.smooth <= 0.0 {
        return img.to_vec();
    }
    blur(img, w, h, &gaussian_kernel(spec.smooth))
}

/// One view's residuals: the elements whose squares sum to [`view_loss`] (the sharpened
/// coverage differences over `√n`, then the shade differences times `√(w / n)`).
pub fn residuals(render: &SoftImage, target: &Target, spec: &LossSpec) -> Vec<f32> {
    let q = sharpened(render, target, spec);
    let km = (1.0 / q.n.sqrt()) as f32;
    let ks = (spec.shading / q.n).sqrt() as f32;
    let qm = uncrop(&q.qm, q.w, q.h, q.rect);
    let qs = uncrop(&q.qs, q.w, q.h, q.rect);
    qm.iter()
        .map(|v| v * km)
        .chain(qs.iter().map(|v| v * ks))
        .collect()
}

/// `mean(sharpen(M − M_T)²) + w·mean(sharpen(S − S_T)²)` (after `spec.level` poolings) and
/// its derivatives with respect to the rendered channels. The means are over the picture's own pixels: a border the fit added
/// around it does not dilute the loss against the regulariser.
pub fn view_loss(render: &SoftImage, target: &Target, spec: &LossSpec, grad: bool) -> ImageValue {
    let Sharpened {
        qm,
        qs,
        rect,
        w,
        h,
        sizes,
        n,
    } = sharpened(render, target, spec);
    let sm: f64 = qm.iter().map(|&v| (v as f64) * (v as f64)).sum();
    let ss: f64 = qs.iter().map(|&v| (v as f64) * (v as f64)).sum();
    let loss = sm / n + spec.shading * ss / n;
    if !grad {
        return ImageValue {
            value: loss,
            dm: Vec::new(),
            ds: Vec::new(),
        };
    }
    let km = (2.0 / n) as f32;
    let ks = (2.0 * spec.shading / n) as f32;
    let scaled = |q: &[f32], k: f32| -> Vec<f32> {
        let g: Vec<f32> = match rect {
            Some(r) => compare_rect_transposed(q, r, spec)
                .into_iter()
                .map(|v| v * k)
                .collect(),
            None => Vec::new(),
        };
        uncrop(&g, w, h, rect)
    };
    let mut gm = scaled(&qm, km);
    let mut gs = scaled(&qs, ks);
    for k in (0..sizes.len() - 1).rev() {
        let (wk, hk) = sizes[k];
        gm = unpool(&gm, wk, hk);
        gs = unpool(&gs, wk, hk);
    }
    ImageValue {
        value: loss,
        dm: gm,
        ds: gs,
    }
}

/// The image loss against one target per view, as a function the renderer differentiates.
#[derive(Debug, Clone, Copy)]
pub struct ImageLoss<'a> {
    /// One per view, in view order (at least as many as the views evaluated).
    pub targets: &'a [Target],
    pub spec: &'a LossSpec,
}

impl ImageFunction for ImageLoss<'_> {
    fn eval(&self, view: usize, image: &SoftImage, grad: bool) -> ImageValue {
        view_loss(image, &self.targets[view], self.spec, grad)
    }
}

/// The image loss of a scene's views against `targets` (edges of width `sigma`) and, with
/// `grad`, its gradient per part parameter. Views beyond the targets (or the shades) are
/// not rendered.
#[allow(clippy::too_many_arguments)]
pub fn image_loss(
    backend: &mut dyn Backend,
    scene: &Scene,
    views: &[ViewPrep],
    sigma: f64,
    shades: &[[f64; NSHADE]],
    targets: &[Target],
    spec: &LossSpec,
    grad: bool,
) -> ImageValues {
    let n = views.len().min(shades.len()).min(targets.len());
    let f = ImageLoss { targets, spec };
    backend.evaluate(scene, &views[..n], sigma, &shades[..n], &f, grad)
}

#[cfg(test)]
mod tests;
