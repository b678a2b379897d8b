//! The renderer: explicit cameras, exact hard images and soft silhouettes with gradients.
//!
//! One interface ([`Backend`]), two implementations: [`CpuBackend`] (the reference, in Rust)
//! and, with the `gpu` feature, `gpu::GpuBackend` (wgpu with the WGSL in `shaders/`; Mesa's
//! lavapipe runs it on a CPU). Both compute the same soft channels from the same prepared
//! views ([`soft::ViewPrep`]), the same loss, and the gradient of the loss with respect to
//! every part parameter. `cpu` holds an independent hard ray caster over `geom`'s exact
//! ray intervals, used as the reference picture.

pub mod camera;
pub mod cpu;
#[cfg(feature = "gpu")]
pub mod gpu;
pub mod image;
pub mod openscad;
pub mod scene;
pub mod soft;

use crate::fit::loss::{LossSpec, Target, view_loss};
use scene::{NSHADE, NTHETA, Scene, shade_features};
use soft::{HardImage, SoftImage, ViewPrep};

/// A loss value per view and, when asked, its gradient per part parameter.
#[derive(Debug, Clone, PartialEq)]
pub struct LossOut {
    pub per_view: Vec<f64>,
    /// `∂loss/∂θ` per part (empty when no gradient was asked for).
    pub dtheta: Vec<[f64; NTHETA]>,
}

impl LossOut {
    pub fn total(&self) -> f64 {
        self.per_view.iter().sum()
    }
}

/// A renderer.
pub trait Backend {
    /// A short description, printed when a command starts.
    fn name(&self) -> String;

    /// Soft channels (hard edges when `sigma` is `None`) and the hard surface of each view.
    fn render(
        &mut self,
        scene: &Scene,
        views: &[ViewPrep],
        sigma: Option<f64>,
        shades: &[[f64; NSHADE]],
    ) -> Vec<(SoftImage, HardImage)>;

    /// The image loss against `targets` and (with `grad`) its gradient.
    #[allow(clippy::too_many_arguments)]
    fn loss(
        &mut self,
        scene: &Scene,
        views: &[ViewPrep],
        sigma: f64,
        shades: &[[f64; NSHADE]],
        targets: &[Target],
        spec: &LossSpec,
        grad: bool,
    ) -> LossOut;
}

/// The reference backend.
#[derive(Debug, Default, Clone, Copy)]
pub struct CpuBackend;

impl Backend for CpuBackend {
    fn name(&self) -> String {
        format!("CPU ({} threads)", rayon::current_num_threads())
    }

    fn render(
        &mut self,
        scene: &Scene,
        views: &[ViewPrep],
        sigma: Option<f64>,
        shades: &[[f64; NSHADE]],
    ) -> Vec<(SoftImage, HardImage)> {
        views
            .iter()
            .zip(shades)
            .map(|(v, &sh)| {
                let (s, h, _) = soft::render_view(scene, v, sigma, sh, false);
                (s, h)
            })
            .collect()
    }

    fn loss(
        &mut self,
        scene: &Scene,
        views: &[ViewPrep],
        sigma: f64,
        shades: &[[f64; NSHADE]],
        targets: &[Target],
        spec: &LossSpec,
        grad: bool,
    ) -> LossOut {
        use rayon::prelude::*;
        // Views in parallel (each also renders its rows in parallel); summed in view order.
        let outs: Vec<(f64, Vec<[f64; NTHETA]>)> = views
            .par_iter()
            .zip(shades.par_iter())
            .zip(targets.par_iter())
            .map(|((v, &sh), t)| {
                let (img, _, entries) = soft::render_view(scene, v, Some(sigma), sh, grad);
                let l = view_loss(&img, t, spec, grad);
                let g = if grad {
                    soft::theta_gradient(scene, v, &entries, &l.gm, &l.gs)
                } else {
                    Vec::new()
                };
                (l.loss, g)
            })
            .collect();
        let mut per_view = Vec::with_capacity(views.len());
        let mut dtheta = if grad {
            vec![[0.0; NTHETA]; scene.parts.len()]
        } else {
            Vec::new()
        };
        for (loss, g) in outs {
            per_view.push(loss);
            for (acc, gp) in dtheta.iter_mut().zip(g) {
                for k in 0..NTHETA {
                    acc[k] += gp[k];
                }
            }
        }
        LossOut { per_view, dtheta }
    }
}

/// Fits shading coefficients so that rendered shade matches the target's grey levels where
/// both show a surface (least squares, gently pulled towards `prior`).
pub fn fit_shade(hard: &HardImage, target: &Target, prior: [f64; NSHADE]) -> [f64; NSHADE] {
    let mut a = nalgebra::SMatrix::<f64, NSHADE, NSHADE>::zeros();
    let mut b = nalgebra::SVector::<f64, NSHADE>::zeros();
    let mut count = 0usize;
    let mut grey_sum = 0.0;
    for i in 0..hard.item.len() {
        let w = f64::from(target.shade_weight_at(i));
        if hard.item[i] < 0 || target.m[i] < 0.99 || w <= 0.0 {
            continue;
        }
        let n = hard.normal[i].map(|v| v as f64);
        let f = nalgebra::SVector::<f64, NSHADE>::from(shade_features(n));
        let g = target.grey[i] as f64;
        a += w * f * f.transpose();
        b += w * f * g;
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
