//! The renderer: explicit cameras, exact hard images and soft silhouettes with gradients.
//!
//! One interface ([`Backend`]), two implementations: [`CpuBackend`] (the reference, in Rust)
//! and, with the `gpu` feature, `gpu::GpuBackend` (wgpu with the WGSL in `shaders/`; Mesa's
//! lavapipe runs it on a CPU). Both compute the same soft channels from the same prepared
//! views ([`soft::ViewPrep`]) and, for any [`ImageFunction`] of those images (the fit's
//! image loss, say), its values and its gradient with respect to every part parameter,
//! summed in view order by the one accumulation both share. `cpu` holds an independent
//! hard ray caster over `geom`'s exact ray intervals, used as the reference picture.
//!
//! The renderer knows no optimiser: it imports only `geom` and `ir` (and the crate-root
//! `tolerance`); what an image is compared with belongs to `fit`. Vector and matrix maths
//! is `glam`'s (`DVec3`, `DMat3`), written so every float is the same as before.

pub mod camera;
pub mod cpu;
#[cfg(feature = "gpu")]
pub mod gpu;
pub mod image;
pub mod openscad;
pub mod scene;
pub mod soft;

use scene::{NSHADE, NTHETA, Scene};
use soft::{Entries, HardImage, SoftImage, ViewPrep};

/// A scalar function of each view's soft image (an image loss, say) with its derivatives
/// with respect to the image's channels. The renderer evaluates it on the images it
/// renders and chains the derivatives to every part parameter; what the function compares
/// the images with is its own business.
pub trait ImageFunction: Sync {
    /// The value at view `view`'s soft image and, with `grad`, its derivatives with respect
    /// to the channels `M` and `S` of every pixel (empty without `grad`).
    fn eval(&self, view: usize, image: &SoftImage, grad: bool) -> ImageValue;
}

/// An [`ImageFunction`]'s value at one image and its per-pixel derivatives.
#[derive(Debug, Clone, PartialEq)]
pub struct ImageValue {
    pub value: f64,
    /// `∂value/∂M` per pixel (empty when no gradient was asked for).
    pub dm: Vec<f32>,
    /// `∂value/∂S` per pixel (empty when no gradient was asked for).
    pub ds: Vec<f32>,
}

/// An [`ImageFunction`]'s value per view and, when asked, the gradient of their sum per
/// part parameter.
#[derive(Debug, Clone, PartialEq)]
pub struct ImageValues {
    pub per_view: Vec<f64>,
    /// `∂(Σ per_view)/∂θ` per part (empty when no gradient was asked for).
    pub dtheta: Vec<[f64; NTHETA]>,
}

impl ImageValues {
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

    /// The soft channels alone of each view (hard edges when `sigma` is `None`): what a
    /// loss compares. The default renders whole views; a backend may redraw only what
    /// changed since its last call, with the same result.
    fn soft(
        &mut self,
        scene: &Scene,
        views: &[ViewPrep],
        sigma: Option<f64>,
        shades: &[[f64; NSHADE]],
    ) -> Vec<SoftImage> {
        self.render(scene, views, sigma, shades)
            .into_iter()
            .map(|(s, _)| s)
            .collect()
    }

    /// `f` at every view's soft image (edges of width `sigma`) and, with `grad`, the
    /// gradient of its sum with respect to every part parameter.
    fn evaluate(
        &mut self,
        scene: &Scene,
        views: &[ViewPrep],
        sigma: f64,
        shades: &[[f64; NSHADE]],
        f: &dyn ImageFunction,
        grad: bool,
    ) -> ImageValues;
}

/// `f` at view `k`'s image and (with `grad`) its `∂/∂θ` per part through the view's
/// gradient entries.
fn view_value(
    scene: &Scene,
    prep: &ViewPrep,
    k: usize,
    image: &SoftImage,
    entries: &Entries,
    f: &dyn ImageFunction,
    grad: bool,
) -> (f64, Vec<[f64; NTHETA]>) {
    let v = f.eval(k, image, grad);
    let g = if grad {
        soft::theta_gradient(scene, prep, entries, &v.dm, &v.ds)
    } else {
        Vec::new()
    };
    (v.value, g)
}

/// Per-view values and gradients summed in view order (the one accumulation both backends
/// use, so they add in the same order).
fn sum_views(
    parts: usize,
    grad: bool,
    views: impl IntoIterator<Item = (f64, Vec<[f64; NTHETA]>)>,
) -> ImageValues {
    let mut per_view = Vec::new();
    let mut dtheta = if grad {
        vec![[0.0; NTHETA]; parts]
    } else {
        Vec::new()
    };
    for (value, g) in views {
        per_view.push(value);
        for (acc, gp) in dtheta.iter_mut().zip(g) {
            for k in 0..NTHETA {
                acc[k] += gp[k];
            }
        }
    }
    ImageValues { per_view, dtheta }
}

/// The reference backend. It keeps each view's last soft render ([`soft::SoftCache`]): a
/// loss without gradient at a scene that differs in a few parts (a fit's single moves)
/// renders only where those parts are or were, with the same result.
#[derive(Debug, Default, Clone)]
pub struct CpuBackend {
    last: soft::SoftCache,
}

impl CpuBackend {
    pub fn new() -> CpuBackend {
        CpuBackend::default()
    }
}

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

    fn soft(
        &mut self,
        scene: &Scene,
        views: &[ViewPrep],
        sigma: Option<f64>,
        shades: &[[f64; NSHADE]],
    ) -> Vec<SoftImage> {
        let images = self.last.render(scene, views, sigma, shades);
        images.into_iter().cloned().collect()
    }

    fn evaluate(
        &mut self,
        scene: &Scene,
        views: &[ViewPrep],
        sigma: f64,
        shades: &[[f64; NSHADE]],
        f: &dyn ImageFunction,
        grad: bool,
    ) -> ImageValues {
        use rayon::prelude::*;
        // Without a gradient the cache redraws only what changed since the last call.
        let cached = (!grad).then(|| self.last.render(scene, views, Some(sigma), shades));
        // Views in parallel (each also renders its rows in parallel); summed in view order.
        let outs: Vec<(f64, Vec<[f64; NTHETA]>)> = views
            .par_iter()
            .zip(shades.par_iter())
            .enumerate()
            .map(|(k, (v, &sh))| match &cached {
                Some(images) => {
                    view_value(scene, v, k, images[k], &soft::Entries::default(), f, false)
                }
                None => {
                    let (img, entries) = soft::render_soft(scene, v, Some(sigma), sh, grad);
                    view_value(scene, v, k, &img, &entries, f, grad)
                }
            })
            .collect();
        sum_views(scene.parts.len(), grad, outs)
    }
}
