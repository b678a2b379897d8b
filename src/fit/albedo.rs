//! Per-item albedo: the parts of a target picture may have colours of their own (black
//! tyres, a red cap, shelves in two woods), which no shading of one grey material explains.
//! Each scene item gets an albedo that multiplies its shade in our renders
//! ([`crate::render::scene::Scene::albedo`]), fitted by least squares over all views jointly
//! with each view's shading coefficients (a few alternations). Rendered with its albedo, a
//! dark tyre against a yellow box is an edge the gradient sees, not a shading error.
//!
//! Invariants: albedos have a pixel-weighted mean of 1 (each view's shading coefficients
//! carry the brightness); with per-item albedo off every albedo is 1 and shading is fitted
//! as before.

use super::loss::Target;
use crate::render::scene::{NSHADE, shade_features};
use crate::render::soft::HardImage;

/// Albedo below which an item's pixels say too little about the view's shading to fit it
/// (its grey divided by the albedo would mostly be noise).
const DARK: f64 = 0.3;
/// Alternations between shading and albedo fits.
const ALTERNATIONS: usize = 4;
/// Coverage above which a target pixel counts as surface for the fits.
const SOLID: f32 = 0.99;

/// Each view's shading and each item's albedo.
#[derive(Debug, Clone, PartialEq)]
pub struct Shading {
    pub shades: Vec<[f64; NSHADE]>,
    /// One per scene item (1 for items never seen).
    pub albedo: Vec<f64>,
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
    let mut albedo = vec![1.0; items];
    let mut shades = vec![prior; hards.len()];
    let alternations = if per_item { ALTERNATIONS } else { 1 };
    for round in 0..alternations {
        for ((sh, h), t) in shades.iter_mut().zip(hards).zip(targets) {
            *sh = fit_shade(h, t, &albedo, prior);
        }
        if round + 1 < alternations {
            albedo = fit_albedo(hards, targets, &shades, items);
        }
    }
    Shading { shades, albedo }
}

/// Least-squares albedo of each item given the views' shading, normalised to a
/// pixel-weighted mean of 1, lightly pulled towards 1.
fn fit_albedo(
    hards: &[HardImage],
    targets: &[Target],
    shades: &[[f64; NSHADE]],
    items: usize,
) -> Vec<f64> {
    let mut num = vec![0.0; items];
    let mut den = vec![0.0; items];
    let mut count = vec![0usize; items];
    for ((h, t), sh) in hards.iter().zip(targets).zip(shades) {
        for (i, &k) in h.item.iter().enumerate() {
            if k < 0 || t.m[i] < SOLID {
                continue;
            }
            let n = h.normal[i].map(f64::from);
            let f: f64 = shade_features(n).iter().zip(sh).map(|(a, b)| a * b).sum();
            let k = k as usize;
            num[k] += f64::from(t.grey[i]) * f;
            den[k] += f * f;
            count[k] += 1;
        }
    }
    let mut albedo: Vec<f64> = (0..items)
        .map(|k| {
            let mu = 1e-3 * count[k] as f64;
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

/// Fits one view's shading coefficients so that the rendered shade times each item's
/// albedo matches the target's grey where both show a surface (least squares on the grey
/// divided by the albedo, gently pulled towards `prior`). Items darker than [`DARK`] are
/// left out.
pub fn fit_shade(
    hard: &HardImage,
    target: &Target,
    albedo: &[f64],
    prior: [f64; NSHADE],
) -> [f64; NSHADE] {
    let mut a = nalgebra::SMatrix::<f64, NSHADE, NSHADE>::zeros();
    let mut b = nalgebra::SVector::<f64, NSHADE>::zeros();
    let mut count = 0usize;
    let mut grey_sum = 0.0;
    for (i, &k) in hard.item.iter().enumerate() {
        if k < 0 || target.m[i] < SOLID {
            continue;
        }
        let alb = albedo.get(k as usize).copied().unwrap_or(1.0);
        if alb < DARK {
            continue;
        }
        let n = hard.normal[i].map(f64::from);
        let f = nalgebra::SVector::<f64, NSHADE>::from(shade_features(n));
        // The grey stays an f32, like the target's channels.
        let g = f64::from((f64::from(target.grey[i]) / alb) as f32);
        a += f * f.transpose();
        b += f * g;
        grey_sum += g;
        count += 1;
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
    let mu = 1e-3 * count as f64;
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
        let a = fit_shade(&hard, &t, &albedo, DEFAULT_SHADE);
        let b = fit_shade(&hard, &other, &albedo, DEFAULT_SHADE);
        assert_eq!(a, b);
        // With a bright albedo those pixels count.
        let c = fit_shade(&hard, &other, &[1.0, 1.0], DEFAULT_SHADE);
        assert_ne!(a, c);
    }
}
