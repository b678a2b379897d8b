//! Pictures read as coverage: how much of each pixel the object covers, unmixed from the
//! background and the colour of the surface nearby.
//!
//! An antialiased picture (our renders, a diffusion model's, a photo's) draws a pixel the
//! silhouette crosses as a mix `c = (1 − α)·b + α·f` of the background `b` and the
//! surface's own colour `f`. Reading every pixel that differs from the background as
//! foreground makes every part a pixel fatter; here `c` is unmixed as `(1 − α)·b + μ·f`
//! with `f` the colour of a nearby pixel the object covers whole (one whose neighbours are
//! all foreground) that explains `c` best, at a brightness of its own (`μ / α`): the surface
//! in a silhouette pixel is often another face of the same material, lit differently (a
//! thin leg's dark side beside a lit top; two faces sharing a corner pixel), and reading it
//! at its neighbour's shade biases `α`. A part with no such pixel nearby (thinner than the
//! window) reads against the colours the picture covers whole anywhere. That reads the
//! silhouette and a gap narrower than a pixel between two parts (seen from above, a table
//! top and its shelf).
//!
//! A picture drawn with hard edges (OpenSCAD's) has no mixed pixels at all, and unmixing
//! it can only err: with a free brightness a pale face or a cylinder's lighter facet is also
//! a mix of a darker face and the background. Such a picture shows itself by its
//! silhouette: few of its pixels read as a mix of the background and the colour further
//! in, where any antialiasing mixes half of them or more. It reads whole wherever it is
//! foreground. The views of one fit come from one renderer and are told together, by the
//! silhouettes of all of them ([`Rim`]): alone, a view of pale facets can look mixed (a
//! soup mug's five OpenSCAD views: one read as antialiased, its pale facets as partly
//! background, and the loss at the truth was higher than at a fit 0.1 IoU off it). (Inside an antialiased picture the same ambiguity stays: a
//! lighter facet one or two pixels wide reads as partly background, and only its place,
//! not its colour, could tell it from a gap narrower than a pixel.)
//!
//! The premultiplied grey follows without knowing `f`: luminance is linear, so the
//! surface's share of the pixel's luminance is `L(c) − (1 − α)·L(b)`.

use crate::render::image::Rgb;
use rayon::prelude::*;

/// Radius (pixels) of the square in which a silhouette pixel looks for covered pixels.
const REACH: i64 = 2;

/// Largest residual of a pixel's colour unmixed against a surface colour `f`, as a fraction
/// of `|f − b|`, at which it still counts as a mix of `f` and the background.
const MIX_RESIDUAL: f32 = 0.15;

/// Colours of the palette closer than this in every channel count as one.
const PALETTE_STEP: f32 = 1.0 / 64.0;

/// Largest share of a hard picture's silhouette pixels that may read as mixed. Any
/// antialiasing mixes about half of them or more (2×2 samples a pixel leave whole only
/// those where the edge falls on a sample boundary; OpenSCAD's pictures pooled from 4×
/// their size: 62–96% mixed); a hard picture only by coincidence, where a face one pixel
/// wide has the colour of a mix (OpenSCAD's views of the quality table's models: 0–28%,
/// 48 of 50 views under a quarter; of generated families, under 1%). Pictures above it,
/// told together ([`Rim`]), are unmixed.
const MIXED_RIM_SHARE: f64 = 0.25;

/// Shares of a pixel between which a silhouette pixel explained as a mix of the
/// background and the surface further in counts as mixed, when telling a hard picture.
const MIXED_SHARE: (f32, f32) = (0.1, 0.9);

/// How many of a picture's silhouette pixels read as mixed, of how many: the evidence of
/// antialiasing. Pictures from one renderer are told together by their sums
/// ([`Rim::hard_edges`]): a view of pale faces can look mixed on its own where its
/// renderer's other views show hard edges plainly.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Rim {
    pub mixed: usize,
    pub pixels: usize,
}

impl Rim {
    /// The silhouette of one picture.
    pub fn of(img: &Rgb, background: [f32; 3], lo: f32, hi: f32) -> Rim {
        Pixels::new(img, background, lo, hi).rim()
    }

    /// Two pictures' silhouettes together.
    pub fn and(self, other: Rim) -> Rim {
        Rim {
            mixed: self.mixed + other.mixed,
            pixels: self.pixels + other.pixels,
        }
    }

    /// Whether pictures with this silhouette were drawn with hard edges: few of its pixels
    /// mixed ([`MIXED_RIM_SHARE`]).
    pub fn hard_edges(&self) -> bool {
        (self.mixed as f64) < MIXED_RIM_SHARE * self.pixels as f64
    }
}

/// A picture's channels as coverage, `(m, s)`: read whole wherever it is foreground when it
/// was drawn with `hard` edges, else unmixed.
pub fn read(img: &Rgb, background: [f32; 3], lo: f32, hi: f32, hard: bool) -> (Vec<f32>, Vec<f32>) {
    let px = Pixels::new(img, background, lo, hi);
    if hard {
        return whole(img, &px.d, background, lo, hi);
    }
    let solid: Vec<bool> = (0..px.d.len())
        .map(|i| px.neighbours(i).all(|j| j.is_some_and(|j| px.fg(j))))
        .collect();
    let palette = palette(img, &solid);
    let lb = luminance(&background);
    let w = img.width as usize;
    let mut m = vec![0.0f32; px.d.len()];
    let mut s = vec![0.0f32; px.d.len()];
    // Rows in parallel, each writing its own slices.
    m.par_chunks_mut(w)
        .zip(s.par_chunks_mut(w))
        .enumerate()
        .for_each(|(y, (m, s))| {
            for x in 0..w {
                let i = y * w + x;
                let gate = smoothstep(lo, hi, px.d[i]);
                if gate == 0.0 {
                    continue;
                }
                let c = img.data[i];
                let covered = px.window(i).filter(|&j| solid[j]).map(|j| img.data[j]);
                let alpha = mix_share(c, background, covered, lo)
                    .or_else(|| mix_share(c, background, palette.iter().copied(), lo))
                    .unwrap_or(1.0);
                m[x] = alpha * gate;
                s[x] = (luminance(&c) - (1.0 - m[x]) * lb).max(0.0);
            }
        });
    (m, s)
}

/// The channels of a picture with hard edges: every pixel is background or covered whole
/// (but for the noise gate between `lo` and `hi`).
fn whole(img: &Rgb, d: &[f32], background: [f32; 3], lo: f32, hi: f32) -> (Vec<f32>, Vec<f32>) {
    let lb = luminance(&background);
    let m: Vec<f32> = d.iter().map(|&d| smoothstep(lo, hi, d)).collect();
    let s = img
        .data
        .iter()
        .zip(&m)
        .map(|(c, &m)| {
            if m == 0.0 {
                0.0
            } else {
                (luminance(c) - (1.0 - m) * lb).max(0.0)
            }
        })
        .collect();
    (m, s)
}

fn luminance(c: &[f32; 3]) -> f32 {
    0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]
}

/// A picture's pixels with their distances from the background, for the neighbourhood
/// tests of [`read`] and [`Rim`]. Pixels are indices `y · width + x`.
struct Pixels<'a> {
    img: &'a Rgb,
    background: [f32; 3],
    /// Colour distance of every pixel from the background.
    d: Vec<f32>,
    lo: f32,
    hi: f32,
}

impl<'a> Pixels<'a> {
    fn new(img: &'a Rgb, background: [f32; 3], lo: f32, hi: f32) -> Self {
        let d = img
            .data
            .iter()
            .map(|c| colour_distance(c, &background))
            .collect();
        Pixels {
            img,
            background,
            d,
            lo,
            hi,
        }
    }

    /// The pixel `(dx, dy)` away from `i`, if inside the picture.
    fn offset(&self, i: usize, dx: i64, dy: i64) -> Option<usize> {
        let (w, h) = (self.img.width as i64, self.img.height as i64);
        let (x, y) = ((i as i64) % w + dx, (i as i64) / w + dy);
        (x >= 0 && y >= 0 && x < w && y < h).then(|| (y * w + x) as usize)
    }

    /// The 3×3 block around `i` (itself included); `None` outside the picture.
    fn neighbours(&self, i: usize) -> impl Iterator<Item = Option<usize>> + '_ {
        (-1..=1).flat_map(move |dy| (-1..=1).map(move |dx| self.offset(i, dx, dy)))
    }

    /// Pixels of the square of radius [`REACH`] around `i`, itself left out.
    fn window(&self, i: usize) -> impl Iterator<Item = usize> + '_ {
        (-REACH..=REACH)
            .flat_map(move |dy| (-REACH..=REACH).map(move |dx| (dx, dy)))
            .filter(|&(dx, dy)| (dx, dy) != (0, 0))
            .filter_map(move |(dx, dy)| self.offset(i, dx, dy))
    }

    fn fg(&self, i: usize) -> bool {
        self.d[i] >= self.hi
    }

    /// Two pixels of one colour, to the picture's noise.
    fn same(&self, i: usize, j: usize) -> bool {
        colour_distance(&self.img.data[i], &self.img.data[j]) <= self.lo
    }

    /// The picture's silhouette pixels (foreground beside background), and how many of
    /// them are mixed. Each is pure, of the colour of a pixel next to it further in; mixed,
    /// explained as that colour and the background at a share within [`MIXED_SHARE`]; or
    /// neither (a face one pixel wide of another shade). A hard picture has few mixed ones
    /// ([`Rim::hard_edges`]).
    fn rim(&self) -> Rim {
        let bg = |j: Option<usize>| j.is_none_or(|j| self.d[j] < self.lo);
        let rim = |i: usize| {
            self.fg(i)
                && [(1, 0), (-1, 0), (0, 1), (0, -1)]
                    .iter()
                    .any(|&(dx, dy)| bg(self.offset(i, dx, dy)))
        };
        let mut out = Rim::default();
        for i in (0..self.d.len()).filter(|&i| rim(i)) {
            out.pixels += 1;
            let inner: Vec<usize> = self
                .neighbours(i)
                .flatten()
                .filter(|&j| self.fg(j) && !rim(j))
                .collect();
            let pure = inner.iter().any(|&j| self.same(i, j));
            if !pure && inner.iter().any(|&j| self.mix_of(i, j)) {
                out.mixed += 1;
            }
        }
        out
    }

    /// Whether pixel `i` is a mix of the background and pixel `j`'s colour at a share
    /// within [`MIXED_SHARE`].
    fn mix_of(&self, i: usize, j: usize) -> bool {
        let (c, f, b) = (self.img.data[i], self.img.data[j], self.background);
        let v: [f32; 3] = std::array::from_fn(|k| c[k] - b[k]);
        unmix_one(v, b, f).is_some_and(|u| {
            u.residual <= (MIX_RESIDUAL * u.length).max(self.lo)
                && (MIXED_SHARE.0..=MIXED_SHARE.1).contains(&u.alpha)
        })
    }
}

/// The largest difference of two colours over the channels.
pub(super) fn colour_distance(p: &[f32; 3], q: &[f32; 3]) -> f32 {
    (0..3).map(|k| (p[k] - q[k]).abs()).fold(0.0f32, f32::max)
}

/// The distinct colours (to [`PALETTE_STEP`]) of the pixels the object covers whole: the
/// surfaces a pixel with none nearby (a part thinner than the window, seen nowhere whole)
/// may be a mix of, at a brightness of their own.
fn palette(img: &Rgb, solid: &[bool]) -> Vec<[f32; 3]> {
    let key = |c: &[f32; 3]| c.map(|v| (v / PALETTE_STEP).round() as i32);
    let mut seen = std::collections::HashSet::new();
    img.data
        .iter()
        .zip(solid)
        .filter(|(c, s)| **s && seen.insert(key(c)))
        .map(|(c, _)| *c)
        .collect()
}

/// The share `α ∈ [0, 1]` of `c = (1 − α)·b + μ·f` for the surface colour `f` among
/// `covered` that explains `c` best; `None` when none passes within [`MIX_RESIDUAL`].
/// Fits whose residuals differ by less than `noise` (a colour difference the picture's
/// noise makes) explain `c` alike, and the smallest share among them is taken: a covered
/// pixel that is itself a mix of its surface and the background (inside a gap narrower
/// than a pixel, all its neighbours are foreground) explains `c` as well as the pure
/// surface does, with a larger share (`f` carries background in itself).
///
/// The surface in the pixel is `f` at any brightness `μ / α`: the face there may be another
/// face of the same material, lit differently (a thin leg's dark side next to a lit top, a
/// silhouette corner where two faces share the pixel), and reading it at `f`'s own shade
/// makes a darker face look like more coverage. Only when `b` and `f` are nearly parallel
/// (grey on white) does colour not tell coverage from brightness; then `f`'s own shade is
/// assumed (`μ = α`, the projection onto the segment from `b` to `f`).
fn mix_share(
    c: [f32; 3],
    b: [f32; 3],
    covered: impl Iterator<Item = [f32; 3]>,
    noise: f32,
) -> Option<f32> {
    let v: [f32; 3] = std::array::from_fn(|k| c[k] - b[k]);
    let fits: Vec<Unmixed> = covered.filter_map(|f| unmix_one(v, b, f)).collect();
    let closest = fits
        .iter()
        .map(|f| f.residual)
        .fold(f32::INFINITY, f32::min);
    let explained = fits
        .iter()
        .any(|f| f.residual == closest && f.residual <= MIX_RESIDUAL * f.length);
    if !explained {
        return None;
    }
    fits.iter()
        .filter(|f| f.residual <= closest + noise)
        .map(|f| f.alpha.clamp(0.0, 1.0))
        .reduce(f32::min)
}

/// A pixel's colour unmixed against one surface colour `f`: `c − b ≈ −α·b + μ·f`.
struct Unmixed {
    /// The residual's length.
    residual: f32,
    /// `|f − b|`.
    length: f32,
    alpha: f32,
}

/// Sine of the angle between the background's colour and a surface's below which the two
/// are taken as parallel: an 8-bit rounding of the pixel (1/255) then moves the free
/// brightness fit's share by more than about 1/255 / (|b|·sin), too much to trust.
const MIN_HUE_SINE: f32 = 0.2;

/// The fit of `v = c − b` by the colour `f`: `v ≈ −α·b + μ·f` (`μ` free when `b` and `f`
/// are far from parallel, else `μ = α`); `None` when `f` is the background.
fn unmix_one(v: [f32; 3], b: [f32; 3], f: [f32; 3]) -> Option<Unmixed> {
    let dot = |p: &[f32; 3], q: &[f32; 3]| (0..3).map(|k| p[k] * q[k]).sum::<f32>();
    let u: [f32; 3] = std::array::from_fn(|k| f[k] - b[k]);
    let uu = dot(&u, &u);
    if uu <= 0.0 {
        return None;
    }
    let (bb, ff, bf) = (dot(&b, &b), dot(&f, &f), dot(&b, &f));
    let det = bb * ff - bf * bf;
    let (alpha, mu) = if det > MIN_HUE_SINE * MIN_HUE_SINE * bb * ff {
        // Normal equations of v = α·(−b) + μ·f.
        let (vb, vf) = (dot(&v, &b), dot(&v, &f));
        ((vf * bf - vb * ff) / det, (bb * vf - bf * vb) / det)
    } else {
        let t = dot(&v, &u) / uu;
        (t, t)
    };
    let r2: f32 = (0..3)
        .map(|k| (v[k] - mu * f[k] + alpha * b[k]).powi(2))
        .sum();
    Some(Unmixed {
        residual: r2.sqrt(),
        length: uu.sqrt(),
        alpha,
    })
}

fn smoothstep(a: f32, b: f32, x: f32) -> f32 {
    let t = ((x - a) / (b - a)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One picture's channels as coverage, `(m, s, hard)`, told hard-edged on its own.
    fn unmix(img: &Rgb, background: [f32; 3], lo: f32, hi: f32) -> (Vec<f32>, Vec<f32>, bool) {
        let hard = Rim::of(img, background, lo, hi).hard_edges();
        let (m, s) = read(img, background, lo, hi, hard);
        (m, s, hard)
    }

    /// The length of `[a, b)` inside pixel `p`'s span `[p, p + 1)`.
    fn overlap(p: u32, a: f32, b: f32) -> f32 {
        (b.min(p as f32 + 1.0) - a.max(p as f32)).max(0.0)
    }

    /// A 12×12 picture of a square covering `[2.5, 8.25)` on both axes in colour `f` on
    /// white, drawn with exact area coverage, and that coverage.
    fn square(f: [f32; 3]) -> (Rgb, Vec<f32>) {
        let cover = |p: u32| -> f32 {
            let (a, b) = (p as f32, p as f32 + 1.0);
            (b.min(8.25) - a.max(2.5)).max(0.0)
        };
        let mut img = Rgb::new(12, 12, [1.0; 3]);
        let mut want = vec![0.0; 144];
        for y in 0..12 {
            for x in 0..12 {
                let a = cover(x) * cover(y);
                want[(y * 12 + x) as usize] = a;
                img.data[(y * 12 + x) as usize] = std::array::from_fn(|k| 1.0 - a + a * f[k]);
            }
        }
        (img, want)
    }

    #[test]
    fn an_antialiased_edge_reads_as_its_coverage() {
        let (img, want) = square([0.6, 0.4, 0.1]);
        let (m, s, _) = unmix(&img, [1.0; 3], 0.012, 0.03);
        for (i, (&a, &b)) in m.iter().zip(&want).enumerate() {
            // Pixels covered less than the noise gate read as background.
            let tol = if b < 0.05 { 0.05 } else { 1e-4 };
            assert!((a - b).abs() <= tol, "pixel {i}: {a} vs {b}");
        }
        // The shade is the surface's grey times coverage.
        let g = 0.2126 * 0.6 + 0.7152 * 0.4 + 0.0722 * 0.1;
        let i = 5 * 12 + 2;
        assert!((s[i] - 0.5 * g).abs() < 1e-4, "{} vs {}", s[i], 0.5 * g);
    }

    #[test]
    fn a_darker_face_of_the_same_surface_reads_as_its_coverage() {
        // Rectangles `[x0, x1) × [y0, y1)` of one surface colour at different shades, drawn
        // with exact area coverage on white: a lit square split by a gap 0.3 px wide (the
        // pixels across it have only foreground around them), a dark face 0.4 px wide
        // sharing the square's right column with the background, and a dark strip 1.3 px
        // wide that nothing covers whole nearby (it reads against the lit colours far away).
        let f = [0.98f32, 0.82, 0.25];
        let rects = [
            ([2.3f32, 8.0, 2.4, 5.0], 0.9f32),
            ([2.3, 8.0, 5.3, 7.7], 0.9),
            ([8.0, 8.4, 2.4, 7.7], 0.35),
            ([13.3, 14.6, 2.5, 9.25], 0.3),
        ];
        let (w, h) = (18u32, 12u32);
        let mut img = Rgb::new(w, h, [1.0; 3]);
        let mut want = vec![0.0f32; (w * h) as usize];
        for y in 0..h {
            for x in 0..w {
                let i = (y * w + x) as usize;
                let (mut a, mut shade) = (0.0, 0.0);
                for ([x0, x1, y0, y1], g) in rects {
                    let c = overlap(x, x0, x1) * overlap(y, y0, y1);
                    a += c;
                    shade += c * g;
                }
                want[i] = a;
                img.data[i] = std::array::from_fn(|k| 1.0 - a + shade * f[k]);
            }
        }
        let (m, _, _) = unmix(&img, [1.0; 3], 0.012, 0.03);
        for (i, (&a, &b)) in m.iter().zip(&want).enumerate() {
            let tol = if b < 0.05 { 0.05 } else { 1e-3 };
            assert!((a - b).abs() <= tol, "pixel {i}: {a} vs {b}");
        }
    }

    /// A grey cylinder's facets, one pixel wide, on OpenSCAD's cream background, covering
    /// `[x0, x1) × [y0, y1)` with exact area coverage: facet `k` is a shade lighter than the
    /// last, so every facet but the first is also a mix of a darker one and the cream.
    fn pale_facets(x0: f32, x1: f32, y0: f32, y1: f32) -> (Rgb, Vec<f32>) {
        let b = [1.0f32, 1.0, 0.9];
        let g0 = [0.45f32, 0.45, 0.42];
        let (w, h) = (18u32, 14u32);
        let mut img = Rgb::new(w, h, b);
        let mut want = vec![0.0f32; (w * h) as usize];
        for y in 0..h {
            for x in 0..w {
                let a = overlap(x, x0, x1) * overlap(y, y0, y1);
                let t = 0.05 * (x as f32 - x0.floor()).max(0.0);
                let facet: [f32; 3] = std::array::from_fn(|k| (1.0 - t) * g0[k] + t * b[k]);
                let i = (y * w + x) as usize;
                want[i] = a;
                img.data[i] = std::array::from_fn(|k| (1.0 - a) * b[k] + a * facet[k]);
            }
        }
        (img, want)
    }

    #[test]
    fn a_hard_picture_of_pale_facets_reads_whole() {
        let (img, want) = pale_facets(2.0, 15.0, 2.0, 11.0);
        let (m, _, _) = unmix(&img, [1.0, 1.0, 0.9], 0.012, 0.03);
        assert_eq!(m, want);
    }

    #[test]
    fn a_hard_picture_reads_whole() {
        // Two faces of different shades meeting at the silhouette, no mixing.
        let mut img = Rgb::new(10, 10, [1.0; 3]);
        for y in 2..8 {
            for x in 2..8 {
                img.data[y * 10 + x] = if x < 5 {
                    [0.9, 0.7, 0.2]
                } else {
                    [0.5, 0.4, 0.1]
                };
            }
        }
        let (m, _, _) = unmix(&img, [1.0; 3], 0.012, 0.03);
        for y in 0..10 {
            for x in 0..10 {
                let inside = (2..8).contains(&x) && (2..8).contains(&y);
                assert_eq!(m[y * 10 + x], if inside { 1.0 } else { 0.0 }, "({x}, {y})");
            }
        }
    }
}
