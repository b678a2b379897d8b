//! Fitting a model's numbers to pictures: the paper's image loss minimised over slots (or
//! inside a constraint subspace) with gradients from soft silhouettes.
//!
//! A fit runs in *rounds* of `iterations` optimiser steps (the paper: SGD, learning rate
//! 0.05, 30 iterations). At the start of each round the shading of every view is matched to
//! its target (least squares on the pixels both show as surface) and the silhouettes'
//! softness `σ` steps down geometrically from `sigma.0` to `sigma.1` pixels, so early rounds
//! see far and later rounds see sharp.

pub mod loss;
pub mod optimize;
pub mod targets;

use crate::ir::{Affine, Model};
use crate::render::camera::Camera;
use crate::render::scene::DEFAULT_SHADE as DEFAULT_SHADE_PRIOR;
use crate::render::scene::{Kind, NSHADE, NTHETA, PartGeom, Scene, theta_at, theta_forms};
use crate::render::soft::{ViewPrep, prepare_view};
use crate::render::{Backend, fit_shade};
use loss::{LossSpec, Target};
use optimize::{OptState, Optimizer, Space};

/// Settings of a fit; [`FitOptions::default`] is the paper's schedule.
#[derive(Debug, Clone, PartialEq)]
pub struct FitOptions {
    pub lr: f64,
    pub iterations: usize,
    pub rounds: usize,
    /// Weight of `‖x − x₀‖²` (slots in units of the model's size).
    pub lambda: f64,
    pub optimizer: Optimizer,
    /// Silhouette softness in pixels: first round, last round.
    pub sigma: (f64, f64),
    pub loss: LossSpec,
    /// Largest change of one variable in one step (units of the model's size).
    pub max_step: f64,
    /// Match each view's shading to its target at the start of every round.
    pub fit_shading: bool,
}

impl Default for FitOptions {
    fn default() -> Self {
        FitOptions {
            lr: 0.05,
            iterations: 30,
            rounds: 10,
            lambda: 0.001,
            optimizer: Optimizer::sgd(),
            sigma: (2.0, 0.5),
            loss: LossSpec::default(),
            max_step: 0.02,
            fit_shading: true,
        }
    }
}

/// What went wrong before fitting could start.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FitError {
    #[error("the model has no parts in view of any camera")]
    NothingInView,
    #[error("the model has no parts")]
    NoParts,
    #[error("{0} cameras but {1} target images")]
    Mismatch(usize, usize),
    #[error("camera `{camera}` is {cw}×{ch} but its target image is {tw}×{th}")]
    Size {
        camera: String,
        cw: u32,
        ch: u32,
        tw: u32,
        th: u32,
    },
    #[error("the subspace basis has {0} rows but the model has {1} slots")]
    Basis(usize, usize),
}

/// A model prepared for fitting: each part's kind and the slot forms of its parameters.
#[derive(Debug, Clone)]
pub struct Parametric {
    pub kinds: Vec<(Kind, bool)>,
    pub forms: Vec<[Option<Affine>; NTHETA]>,
    pub base: Vec<crate::ir::Part>,
    pub csg: crate::ir::CsgNode,
    pub x0: Vec<f64>,
    /// The model's size (longest side of its bounding box).
    pub scale: f64,
}

impl Parametric {
    pub fn new(model: &Model) -> Parametric {
        let kinds = model
            .parts
            .iter()
            .map(|p| {
                let g = PartGeom::from_part(p);
                (g.kind, g.centered)
            })
            .collect();
        let forms = model.parts.iter().map(theta_forms).collect();
        Parametric {
            kinds,
            forms,
            base: model.parts.clone(),
            csg: model.csg.clone(),
            x0: model.slot_values(),
            scale: model.size().max(1e-9),
        }
    }

    /// The parts' geometry at slot values `x`.
    pub fn geoms(&self, x: &[f64]) -> Vec<PartGeom> {
        self.base
            .iter()
            .zip(&self.forms)
            .zip(&self.kinds)
            .map(|((p, f), &(kind, centered))| {
                PartGeom::from_theta(kind, centered, theta_at(p, f, x))
            })
            .collect()
    }

    pub fn scene(&self, x: &[f64]) -> Scene {
        Scene::new(self.geoms(x), &self.csg)
    }

    /// `∂loss/∂x` from `∂loss/∂θ`.
    pub fn chain(&self, dtheta: &[[f64; NTHETA]]) -> Vec<f64> {
        let mut g = vec![0.0; self.x0.len()];
        for (forms, d) in self.forms.iter().zip(dtheta) {
            for (f, &dv) in forms.iter().zip(d) {
                if dv == 0.0 {
                    continue;
                }
                if let Some(f) = f {
                    for &(s, a) in &f.terms {
                        g[s as usize] += a * dv;
                    }
                }
            }
        }
        g
    }

    /// Slots that reach some part's geometry.
    pub fn live_slots(&self) -> Vec<bool> {
        let mut live = vec![false; self.x0.len()];
        for forms in &self.forms {
            for f in forms.iter().flatten() {
                for s in f.slots() {
                    live[s as usize] = true;
                }
            }
        }
        live
    }
}

/// One optimiser step's record.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Step {
    pub round: usize,
    pub iteration: usize,
    /// Image loss plus regulariser.
    pub loss: f64,
    pub image_loss: f64,
    pub sigma: f64,
}

/// The outcome of a fit.
#[derive(Debug, Clone, PartialEq)]
pub struct FitResult {
    pub x0: Vec<f64>,
    pub x: Vec<f64>,
    pub curve: Vec<Step>,
    /// Per view: the image loss at the start and at the end (final σ, final shading).
    pub start_loss: Vec<f64>,
    pub end_loss: Vec<f64>,
    pub shades: Vec<[f64; NSHADE]>,
}

/// Progress report, once per step.
pub struct Progress<'a> {
    pub step: &'a Step,
    pub total_steps: usize,
}

/// Checks targets against cameras and that something is in view.
pub fn check(
    problem: &Parametric,
    cameras: &[Camera],
    targets: &[Target],
    backend: &mut dyn Backend,
) -> Result<(), FitError> {
    if cameras.len() != targets.len() {
        return Err(FitError::Mismatch(cameras.len(), targets.len()));
    }
    for (c, t) in cameras.iter().zip(targets) {
        if c.width != t.width || c.height != t.height {
            return Err(FitError::Size {
                camera: c.name.clone(),
                cw: c.width,
                ch: c.height,
                tw: t.width,
                th: t.height,
            });
        }
    }
    if problem.base.is_empty() {
        return Err(FitError::NoParts);
    }
    let scene = problem.scene(&problem.x0);
    let views: Vec<ViewPrep> = cameras
        .iter()
        .map(|c| prepare_view(&scene, c, None))
        .collect();
    let shades = vec![DEFAULT_SHADE_PRIOR; views.len()];
    let seen = backend
        .render(&scene, &views, None, &shades)
        .iter()
        .any(|(_, h)| h.mask().any(|m| m));
    if !seen {
        return Err(FitError::NothingInView);
    }
    Ok(())
}

/// Fits slot values so renders from `cameras` match `targets`.
pub fn fit(
    problem: &Parametric,
    cameras: &[Camera],
    targets: &[Target],
    space: &Space,
    backend: &mut dyn Backend,
    opts: &FitOptions,
    progress: &mut dyn FnMut(&Progress),
) -> Result<FitResult, FitError> {
    check(problem, cameras, targets, backend)?;
    if space.x_base.len() != problem.x0.len() {
        return Err(FitError::Basis(space.x_base.len(), problem.x0.len()));
    }
    let dim = space.dim();
    let mut y = vec![0.0; dim];
    // In a subspace the start is the particular point's offset from x₀ projected away.
    let mut state = OptState::new(opts.optimizer, dim);
    let mut shades = vec![DEFAULT_SHADE_PRIOR; cameras.len()];
    let rounds = opts.rounds.max(1);
    let total_steps = rounds * opts.iterations;
    let mut curve = Vec::with_capacity(total_steps);
    let sigma_at = |r: usize| {
        if rounds == 1 {
            opts.sigma.1
        } else {
            let f = r as f64 / (rounds - 1) as f64;
            opts.sigma.0 * (opts.sigma.1 / opts.sigma.0).powf(f)
        }
    };
    let image_loss =
        |backend: &mut dyn Backend, x: &[f64], sigma: f64, shades: &[[f64; NSHADE]], grad: bool| {
            let scene = problem.scene(x);
            let views: Vec<ViewPrep> = cameras
                .iter()
                .map(|c| prepare_view(&scene, c, Some(sigma)))
                .collect();
            backend.loss(&scene, &views, sigma, shades, targets, &opts.loss, grad)
        };
    let refit_shades = |backend: &mut dyn Backend, x: &[f64], shades: &mut Vec<[f64; NSHADE]>| {
        if !opts.fit_shading {
            return;
        }
        let scene = problem.scene(x);
        let views: Vec<ViewPrep> = cameras
            .iter()
            .map(|c| prepare_view(&scene, c, None))
            .collect();
        let hard = backend.render(&scene, &views, None, shades);
        for ((sh, (_, h)), t) in shades.iter_mut().zip(&hard).zip(targets) {
            *sh = fit_shade(h, t, DEFAULT_SHADE_PRIOR);
        }
    };
    refit_shades(backend, &problem.x0, &mut shades);
    let start_loss = image_loss(backend, &space.x(&y), opts.sigma.1, &shades, false).per_view;
    let reg = |x: &[f64]| -> (f64, Vec<f64>) {
        let mut v = 0.0;
        let mut g = vec![0.0; x.len()];
        for i in 0..x.len() {
            let r = (x[i] - problem.x0[i]) / problem.scale;
            v += r * r;
            g[i] = 2.0 * opts.lambda * r / problem.scale;
        }
        (opts.lambda * v, g)
    };
    for round in 0..rounds {
        let sigma = sigma_at(round);
        if round > 0 {
            refit_shades(backend, &space.x(&y), &mut shades);
        }
        for it in 0..opts.iterations {
            let x = space.x(&y);
            let out = image_loss(backend, &x, sigma, &shades, true);
            let (rv, rg) = reg(&x);
            let mut gx = problem.chain(&out.dtheta);
            for (g, r) in gx.iter_mut().zip(&rg) {
                *g += r;
            }
            let gy = space.grad_y(&gx);
            let mut delta = state.step(&gy, opts.lr);
            let big = delta.iter().fold(0.0f64, |a, d| a.max(d.abs()));
            if big > opts.max_step && big.is_finite() {
                let k = opts.max_step / big;
                delta.iter_mut().for_each(|d| *d *= k);
            }
            // Never step to a degenerate part (non-positive size, singular transform).
            let mut tried = 0;
            loop {
                let cand: Vec<f64> = y.iter().zip(&delta).map(|(a, d)| a - d).collect();
                let geoms = problem.geoms(&space.x(&cand));
                if geoms.iter().all(|g| g.valid) && cand.iter().all(|v| v.is_finite()) {
                    y = cand;
                    break;
                }
                tried += 1;
                if tried > 10 {
                    break;
                }
                delta.iter_mut().for_each(|d| *d *= 0.5);
            }
            let step = Step {
                round,
                iteration: it,
                loss: out.total() + rv,
                image_loss: out.total(),
                sigma,
            };
            curve.push(step);
            progress(&Progress {
                step: &step,
                total_steps,
            });
        }
    }
    let x = space.x(&y);
    refit_shades(backend, &x, &mut shades);
    let end_loss = image_loss(backend, &x, opts.sigma.1, &shades, false).per_view;
    Ok(FitResult {
        x0: problem.x0.clone(),
        x,
        curve,
        start_loss,
        end_loss,
        shades,
    })
}
