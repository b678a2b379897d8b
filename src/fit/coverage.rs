//! Pictures read as coverage: how much of each pixel the object covers, unmixed from the
//! background and the colour of the surface nearby.
//!
//! An antialiased picture (our renders, a diffusion model's, a photo's) draws a pixel the
//! silhouette crosses as a mix `c = (1 − α)·b + α·f` of the background `b` and the
//! surface's own colour `f`. Reading every pixel that differs from the background as
//! foreground makes every part a pixel fatter; here `α` is the pixel's colour projected
//! onto the segment from `b` to the colour `f` of a nearby pixel the object covers whole
//! (one whose neighbours are all foreground) whose segment passes closest to `c`. That
//! reads the silhouette and a gap narrower than a pixel between two parts (seen from above,
//! a table top and its shelf). A hard picture (OpenSCAD's) reads as before: each pixel is a
//! surface colour, the same as its neighbours on that face, whose segment ends at it.
//!
//! The premultiplied grey follows without knowing `f`: luminance is linear, so the
//! surface's share of the pixel's luminance is `L(c) − (1 − α)·L(b)`.

use crate::render::image::Rgb;

/// Radius (pixels) of the square in which a silhouette pixel looks for covered pixels.
const REACH: i64 = 2;

/// Largest distance of a pixel's colour from the mix segment, as a fraction of the
/// segment's length, at which it still counts as a mix.
const MIX_RESIDUAL: f32 = 0.15;

/// Segments whose distance from a pixel's colour is within this (a fraction of their
/// length, about 8-bit rounding) of the closest count as passing through it alike.
const MIX_TIE: f32 = 0.02;

/// A picture's channels as coverage: `(m, s)`, foreground coverage and premultiplied grey.
/// `lo` and `hi` are the colour distances from `background` below which a pixel is
/// background and above which it is surely foreground (a noisy picture raises them).
pub fn unmix(img: &Rgb, background: [f32; 3], lo: f32, hi: f32) -> (Vec<f32>, Vec<f32>) {
    let (w, h) = (img.width as i64, img.height as i64);
    let dist = |c: &[f32; 3]| {
        (0..3)
            .map(|k| (c[k] - background[k]).abs())
            .fold(0.0f32, f32::max)
    };
    let d: Vec<f32> = img.data.iter().map(dist).collect();
    let at = |x: i64, y: i64| -> Option<usize> {
        (x >= 0 && y >= 0 && x < w && y < h).then(|| (y * w + x) as usize)
    };
    let fg = |x: i64, y: i64| at(x, y).is_some_and(|i| d[i] >= hi);
    let neighbours =
        |x: i64, y: i64| (-1..=1).flat_map(move |dy| (-1..=1).map(move |dx| (x + dx, y + dy)));
    let solid: Vec<bool> = (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .map(|(x, y)| neighbours(x, y).all(|(a, b)| fg(a, b)))
        .collect();
    let lum = |c: &[f32; 3]| 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
    let lb = lum(&background);
    let mut m = vec![0.0f32; d.len()];
    let mut s = vec![0.0f32; d.len()];
    for y in 0..h {
        for x in 0..w {
            let i = (y * w + x) as usize;
            let gate = smoothstep(lo, hi, d[i]);
            if gate == 0.0 {
                continue;
            }
            let covered = window(x, y)
                .filter_map(|(a, b)| at(a, b))
                .filter(|&j| solid[j]);
            let alpha =
                mix_share(img.data[i], background, covered.map(|j| img.data[j])).unwrap_or(1.0);
            m[i] = alpha * gate;
            s[i] = (lum(&img.data[i]) - (1.0 - m[i]) * lb).max(0.0);
        }
    }
    (m, s)
}

/// Pixels of the square of radius [`REACH`] around `(x, y)`, itself left out.
fn window(x: i64, y: i64) -> impl Iterator<Item = (i64, i64)> {
    (-REACH..=REACH)
        .flat_map(move |dy| (-REACH..=REACH).map(move |dx| (dx, dy)))
        .filter(|&(dx, dy)| (dx, dy) != (0, 0))
        .map(move |(dx, dy)| (x + dx, y + dy))
}

/// The share `α ∈ [0, 1]` of `c = (1 − α)·b + α·f` for the surface colour `f` among
/// `covered` whose segment from `b` passes closest to `c` (relative to its length); among
/// segments within [`MIX_TIE`] of the closest, the longest (pixels that are themselves
/// mixes lie on the same segment, nearer the background). `None` when none passes within
/// [`MIX_RESIDUAL`].
fn mix_share(c: [f32; 3], b: [f32; 3], covered: impl Iterator<Item = [f32; 3]>) -> Option<f32> {
    let v: [f32; 3] = std::array::from_fn(|k| c[k] - b[k]);
    // (relative residual, squared length, share) of every segment.
    let fits: Vec<(f32, f32, f32)> = covered
        .filter_map(|f| {
            let u: [f32; 3] = std::array::from_fn(|k| f[k] - b[k]);
            let uu: f32 = u.iter().map(|a| a * a).sum();
            if uu <= 0.0 {
                return None;
            }
            let t = (0..3).map(|k| v[k] * u[k]).sum::<f32>() / uu;
            let r2: f32 = (0..3).map(|k| (v[k] - t * u[k]).powi(2)).sum();
            Some(((r2 / uu).sqrt(), uu, t.clamp(0.0, 1.0)))
        })
        .collect();
    let closest = fits.iter().map(|f| f.0).fold(f32::INFINITY, f32::min);
    if closest > MIX_RESIDUAL {
        return None;
    }
    fits.iter()
        .filter(|f| f.0 <= closest + MIX_TIE)
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .map(|f| f.2)
}

fn smoothstep(a: f32, b: f32, x: f32) -> f32 {
    let t = ((x - a) / (b - a)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

#[cfg(test)]
mod tests {
    use super::*;

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
        let (m, s) = unmix(&img, [1.0; 3], 0.012, 0.03);
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
        let (m, _) = unmix(&img, [1.0; 3], 0.012, 0.03);
        for y in 0..10 {
            for x in 0..10 {
                let inside = (2..8).contains(&x) && (2..8).contains(&y);
                assert_eq!(m[y * 10 + x], if inside { 1.0 } else { 0.0 }, "({x}, {y})");
            }
        }
    }
}
