//! Per-item albedo: the parts of a target picture may have colours of their own (black
//! tyres, a red cap, shelves in two woods), which no shading of one grey material explains.
//! Each scene item gets an albedo that multiplies its shade in our renders
//! ([`crate::render::scene::Scene::albedo`]), fitted by least squares over all views jointly
//! with each view's shading coefficients. Rendered with its albedo, a dark tyre against a
//! yellow box is an edge the gradient sees, not a shading error.
//!
//! The joint fit alternates between the two linear problems (shading given albedos, albedos
//! given shading) until the albedos settle. Alternating converges slowly when items and
//! face orientations go together (a bookcase's yellow sides are mostly seen edge-on, its
//! shelves from the front): a bookcase needed about thirty alternations. So the pixels are
//! read once into per-view, per-item sums of the least-squares problems ([`Sums`]), and the
//! alternations run on those sums at no cost per pixel.
//!
//! Invariants: albedos have a pixel-weighted mean of 1 (each view's shading coefficients
//! carry the brightness); with per-item albedo off every albedo is 1 and shading is fitted
//! as before.

use super::loss::Target;
use crate::render::scene::{NSHADE, shade_features};
use crate::render::soft::HardImage;
use nalgebra::{SMatrix, SVector};

/// Albedo below which an item's pixels say too little about the view's shading to fit it
/// (its grey divided by the albedo would mostly be noise).
const DARK: f64 = 0.3;
/// At most this many alternations between shading and albedo fits.
const MAX_ALTERNATIONS: usize = 1000;
/// Alternations stop when no albedo changes by more than this (relative).
const SETTLED: f64 = crate::tolerance::ALBEDO_SETTLED;
/// Weight per pixel of the pulls towards the prior shading and towards albedo 1 (see
/// [`crate::tolerance::ALBEDO_PULL`]).
const PULL: f64 = crate::tolerance::ALBEDO_PULL;
/// Coverage above which a target pixel counts as surface for the fits.
const SOLID: f32 = 0.99;

type Features = SVector<f64, NSHADE>;

/// Each view's shading and each item's albedo.
#[derive(Debug, Clone, PartialEq)]
pub struct Shading {
    pub shades: Vec<[f64; NSHADE]>,
    /// One per scene item (1 for items never seen).
    pub albedo: Vec<f64>,
}

/// Sums over the surface pixels of one item in one view, with `f` a pixel's shading
/// features and `g` its target grey: all either least-squares fit needs.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Sums {
    /// `Σ f·fᵀ`.
    ff: SMatrix<f64, NSHADE, NSHADE>,
    /// `Σ f·g`.
    fg: Features,
    /// `Σ g`.
    g: f64,
    count: usize,
}

impl Default for Sums {
    fn default() -> Self {
        Sums {
            ff: SMatrix::zeros(),
            fg: Features::zeros(),
            g: 0.0,
            count: 0,
        }
    }
}

/// One view's sums per item (`items` long), over pixels where the hard render shows an
/// item and the target shows a surface.
fn view_sums(hard: &HardImage, target: &Target, items: usize) -> Vec<Sums> {
    let mut sums = vec![Sums::default(); items];
    for (i, &k) in hard.item.iter().enumerate() {
        if k < 0 || target.m[i] < SOLID {
            continue;
        }
        let Some(s) = sums.get_mut(k as usize) else {
            continue;
        };
        let f = Features::from(shade_features(hard.normal[i].map(f64::from)));
        let g = f64::from(target.grey[i]);
        s.ff += f * f.transpose();
        s.fg += f * g;
        s.g += g;
        s.count += 1;
    }
    sums
}

/// Fits each view's shading (and, with `per_item`, each item's albedo) to `targets` where
/// the hard renders `hards` show a surface.
pub fn fit_shading(
    hards: &[HardImage],
    targets: &[Target],
    prior: [f64; NSHADE],
    per_item: bool,
) -> Shading {
    let items = hards
        .iter()
        .flat_map(|h| h.item.iter().copied())
        .max()
        .map_or(0, |m| (m + 1).max(0) as usize);
    let sums: Vec<Vec<Sums>> = hards
        .iter()
        .zip(targets)
        .map(|(h, t)| view_sums(h, t, items))
        .collect();
    fit_shading_from(&sums, prior, per_item)
}

/// [`fit_shading`] on gathered sums (one `Vec` per view, one entry per item).
fn fit_shading_from(sums: &[Vec<Sums>], prior: [f64; NSHADE], per_item: bool) -> Shading {
    let items = sums.iter().map(Vec::len).max().unwrap_or(0);
    let mut albedo = vec![1.0; items];
    let fit_views = |albedo: &[f64]| -> Vec<[f64; NSHADE]> {
        sums.iter().map(|v| fit_shade(v, albedo, prior)).collect()
    };
    let mut shades = fit_views(&albedo);
    if per_item {
        for _ in 0..MAX_ALTERNATIONS {
            let next = fit_albedo(sums, &shades, items);
            let settled = next
                .iter()
                .zip(&albedo)
                .all(|(a, b)| (a - b).abs() <= SETTLED * a.abs().max(1.0));
            albedo = next;
            shades = fit_views(&albedo);
            if settled {
                break;
            }
        }
    }
    Shading { shades, albedo }
}

/// Least-squares albedo of each item given the views' shading, normalised to a
/// pixel-weighted mean of 1, faintly pulled towards 1.
fn fit_albedo(sums: &[Vec<Sums>], shades: &[[f64; NSHADE]], items: usize) -> Vec<f64> {
    let mut num = vec![0.0; items];
    let mut den = vec![0.0; items];
    let mut count = vec![0usize; items];
    for (view, sh) in sums.iter().zip(shades) {
        let c = Features::from(*sh);
        for (k, s) in view.iter().enumerate() {
            num[k] += c.dot(&s.fg);
            den[k] += (c.transpose() * s.ff * c)[(0, 0)];
            count[k] += s.count;
        }
    }
    let mut albedo: Vec<f64> = (0..items)
        .map(|k| {
            let mu = PULL * count[k] as f64;
            if den[k] + mu > 0.0 {
                ((num[k] + mu) / (den[k] + mu)).max(0.0)
            } else {
                1.0
            }
        })
        .collect();
    let total: usize = count.iter().sum();
    if total > 0 {
        let mean = albedo
            .iter()
            .zip(&count)
            .map(|(a, &c)| a * c as f64)
            .sum::<f64>()
            / total as f64;
        if mean > 0.0 {
            albedo.iter_mut().for_each(|a| *a /= mean);
        }
    }
    albedo
}

/// Fits one view's shading coefficients (from its sums per item) so that the rendered
/// shade times each item's albedo matches the target's grey where both show a surface
/// (least squares on the grey divided by the albedo, faintly pulled towards `prior`). Items
/// darker than [`DARK`] are left out.
fn fit_shade(view: &[Sums], albedo: &[f64], prior: [f64; NSHADE]) -> [f64; NSHADE] {
    let mut a = SMatrix::<f64, NSHADE, NSHADE>::zeros();
    let mut b = Features::zeros();
    let mut count = 0usize;
    let mut grey_sum = 0.0;
    for (k, s) in view.iter().enumerate() {
        let alb = albedo.get(k).copied().unwrap_or(1.0);
        if s.count == 0 || alb < DARK {
            continue;
        }
        a += s.ff;
        b += s.fg / alb;
        grey_sum += s.g / alb;
        count += s.count;
    }
    if count < 8 {
        return prior;
    }
    // Pull towards the prior rescaled to the target's mean grey.
    let mean = grey_sum / count as f64;
    let prior_mean = prior[0] + prior[4] * 0.5;
    let k = if prior_mean > 0.0 {
        mean / prior_mean
    } else {
        1.0
    };
    let mu = PULL * count as f64;
    for i in 0..NSHADE {
        a[(i, i)] += mu;
        b[i] += mu * prior[i] * k;
    }
    match a.cholesky() {
        Some(ch) => {
            let c = ch.solve(&b);
            std::array::from_fn(|i| c[i])
        }
        None => prior,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::scene::DEFAULT_SHADE;

    /// Two items side by side facing the viewer; the right one is half as bright.
    fn scene() -> (HardImage, Target) {
        let (w, h) = (30u32, 10u32);
        let n = (w * h) as usize;
        let mut item = vec![-1; n];
        for y in 2..8 {
            for x in 2..18 {
                item[y * w as usize + x] = if x < 10 { 0 } else { 1 };
            }
        }
        let normal = vec![[0.0, 0.0, 1.0]; n];
        let hard = HardImage {
            width: w,
            height: h,
            item: item.clone(),
            normal,
            depth: vec![1.0; n],
        };
        let lit: f64 = shade_features([0.0, 0.0, 1.0])
            .iter()
            .zip(&DEFAULT_SHADE)
            .map(|(a, b)| a * b)
            .sum();
        let m: Vec<f32> = item
            .iter()
            .map(|&k| if k >= 0 { 1.0 } else { 0.0 })
            .collect();
        let grey: Vec<f32> = item
            .iter()
            .map(|&k| match k {
                0 => lit as f32,
                1 => 0.5 * lit as f32,
                _ => 0.0,
            })
            .collect();
        let s = m.iter().zip(&grey).map(|(a, b)| a * b).collect();
        let t = Target {
            width: w,
            height: h,
            m,
            s,
            grey,
            background: [1.0; 3],
            border: 0,
            hard_edges: false,
        };
        (hard, t)
    }

    #[test]
    fn two_colours_get_two_albedos() {
        let (hard, t) = scene();
        let fit = fit_shading(
            std::slice::from_ref(&hard),
            std::slice::from_ref(&t),
            DEFAULT_SHADE,
            true,
        );
        let ratio = fit.albedo[1] / fit.albedo[0];
        assert!((ratio - 0.5).abs() < 0.02, "albedo ratio {ratio}");
        // The view's shading with each albedo reproduces both greys.
        let lit = |k: usize| -> f64 {
            let f = shade_features([0.0, 0.0, 1.0]);
            fit.albedo[k]
                * f.iter()
                    .zip(&fit.shades[0])
                    .map(|(a, b)| a * b)
                    .sum::<f64>()
        };
        for (k, px) in [(0, 5 * 30 + 5), (1, 5 * 30 + 15)] {
            let g = f64::from(t.grey[px]);
            assert!((lit(k) - g).abs() < 0.02 * g, "item {k}: {} vs {g}", lit(k));
        }
    }

    #[test]
    fn without_per_item_albedo_every_albedo_is_one() {
        let (hard, t) = scene();
        let fit = fit_shading(&[hard], std::slice::from_ref(&t), DEFAULT_SHADE, false);
        assert!(fit.albedo.iter().all(|&a| a == 1.0));
    }

    #[test]
    fn dark_items_do_not_steer_the_shading() {
        let (hard, t) = scene();
        // Whatever the dark item's pixels show, the shading fitted with its albedo below
        // DARK is the same.
        let mut other = t.clone();
        for (i, &k) in hard.item.iter().enumerate() {
            if k == 1 {
                other.grey[i] = 0.9;
                other.s[i] = 0.9;
            }
        }
        let albedo = [1.0, 0.1];
        let (t, other) = (view_sums(&hard, &t, 2), view_sums(&hard, &other, 2));
        let a = fit_shade(&t, &albedo, DEFAULT_SHADE);
        let b = fit_shade(&other, &albedo, DEFAULT_SHADE);
        assert_eq!(a, b);
        // With a bright albedo those pixels count.
        let c = fit_shade(&other, &[1.0, 1.0], DEFAULT_SHADE);
        assert_ne!(a, c);
    }

    /// Three items in three colours, each seen mostly in one orientation and a little in
    /// the next (as a bookcase's sides are seen mostly edge-on and its shelves from the
    /// front), in two views lit differently: the greys are exactly an albedo times a
    /// shading, and the joint fit must find that explanation, not stop halfway.
    #[test]
    fn items_seen_in_different_orientations_get_their_own_albedos() {
        let normals = [[0.0, 0.0, 1.0], [0.6, 0.0, 0.8], [0.0, 0.6, 0.8]];
        let truth = [1.2, 0.6, 0.9];
        let lights = [DEFAULT_SHADE, [0.5, 0.1, -0.1, 0.2, 0.2]];
        let (w, h) = (100u32, 3u32);
        let n = (w * h) as usize;
        // Item k: nine pixels in ten face orientation k, one in ten orientation k + 1.
        let item: Vec<i32> = (0..n).map(|i| (i % 3) as i32).collect();
        let orientation = |i: usize| (i % 3 + usize::from(i % 30 < 3)) % 3;
        let hard = HardImage {
            width: w,
            height: h,
            item: item.clone(),
            normal: (0..n).map(|i| normals[orientation(i)]).collect(),
            depth: vec![1.0; n],
        };
        let grey_of = |light: &[f64; NSHADE], i: usize| -> f64 {
            let f = shade_features(normals[orientation(i)].map(f64::from));
            truth[i % 3] * f.iter().zip(light).map(|(a, b)| a * b).sum::<f64>()
        };
        let targets: Vec<Target> = lights
            .iter()
            .map(|light| {
                let grey: Vec<f32> = (0..n).map(|i| grey_of(light, i) as f32).collect();
                Target {
                    width: w,
                    height: h,
                    m: vec![1.0; n],
                    s: grey.clone(),
                    grey,
                    background: [1.0; 3],
                    border: 0,
                    hard_edges: false,
                }
            })
            .collect();
        let hards = [hard.clone(), hard];
        let fit = fit_shading(&hards, &targets, DEFAULT_SHADE, true);
        // Albedo and shading share a scale: compare ratios.
        for k in 1..3 {
            let (ours, want) = (fit.albedo[k] / fit.albedo[0], truth[k] / truth[0]);
            assert!(
                (ours - want).abs() < 1e-2 * want,
                "albedo ratio {k}: {ours} vs {want}"
            );
        }
        for (v, light) in lights.iter().enumerate() {
            for i in 0..n {
                let f = shade_features(normals[orientation(i)].map(f64::from));
                let ours = fit.albedo[i % 3]
                    * f.iter()
                        .zip(&fit.shades[v])
                        .map(|(a, b)| a * b)
                        .sum::<f64>();
                let g = grey_of(light, i);
                assert!(
                    (ours - g).abs() < 2e-3 * g,
                    "view {v} pixel {i}: {ours} vs {g}"
                );
            }
        }
    }
}
