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
use scene::{NSHADE, NTHETA, Scene};
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
