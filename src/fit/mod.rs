//! Fitting a model's numbers to pictures: the paper's image loss minimised over slots (or
//! inside a constraint subspace) with gradients from soft silhouettes.
//!
//! A fit opens with a search over the model's stretch along each axis ([`proportions`]),
//! then runs its stages ([`stages`]) in *rounds* of `iterations` optimiser steps (the
//! paper: SGD, learning rate 0.05, 30 iterations). At the start of each round the shading
//! of every view and the albedo of every item are matched to the targets ([`albedo`]: least
//! squares on the pixels both show as surface) and the silhouettes' softness `σ` steps down
//! geometrically from `sigma.0` to `sigma.1` pixels, so early rounds see far and later
//! rounds see sharp. With Adam, each stage also runs damped from the same start and the
//! run with the lower loss goes on ([`FitOptions::damped_rerun`]). Optional finishing
//! passes move single faces ([`polish`]) and then single numbers and faces by a pixel or
//! less on hard edges ([`polish::refine`]); pictures may be seen inside a border of
//! background ([`frame`]).

pub mod albedo;
pub mod frame;
pub mod loss;
pub mod optimize;
pub mod polish;
pub mod proportions;
pub mod stages;
pub mod targets;

pub use polish::polish;
pub use stages::{
    Stage, basis_of, constraint_basis, scale_basis, staged, staged_with, structure_basis,
};

use crate::ir::{Affine, Model};
use crate::render::Backend;
use crate::render::camera::Camera;
use crate::render::scene::DEFAULT_SHADE as DEFAULT_SHADE_PRIOR;
use crate::render::scene::{Kind, NSHADE, NTHETA, PartGeom, Scene, theta_at, theta_forms};
use crate::render::soft::{ViewPrep, prepare_view};
use loss::{LossSpec, Target};
use optimize::{OptState, Optimizer, Space};

/// Settings of a fit; [`FitOptions::default`] is the paper's loss and schedule, opened by our
/// proportions search and with an albedo per item (both can be turned off).
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
    /// With `fit_shading`: fit an albedo per item too, so parts of other colours in the
    /// targets (black tyres, two woods) do not read as shading (see [`albedo`]).
    pub per_item_albedo: bool,
    /// Step each slot in units of its own magnitude (at least 5% of the model's size)
    /// instead of the model's size.
    pub relative_steps: bool,
    /// Open with a search over the model's stretch along each axis (see [`proportions`]).
    pub proportions: bool,
    /// Sweeps of face moves after the gradient rounds (see [`polish`]); 0: none.
    pub polish: usize,
    /// Sweeps of slot and face moves on hard edges after the face moves (see
    /// [`polish::refine`]); 0: none.
    pub refine: usize,
    /// The pictures show the whole object: the fit sees each picture inside a frame of
    /// background this fraction of its height wide, so that parts reaching out of the
    /// pictures are drawn back in rather than left unseen. 0: only the pictures.
    pub border: f64,
    /// In the last round of each stage the learning rate falls linearly by this fraction
    /// of `lr` over the round (see [`optimize::round_rate`]), so the stage ends almost at
    /// rest rather than wherever constant steps left it (Adam's steps stay near `lr`
    /// however close it is; on a 2.5 mm desk top that is a visible error). 0: the paper's
    /// constant rate.
    pub settle: f64,
    /// With Adam: every stage runs a second time from the same start with Adam's `floor`
    /// at this value, and the run with the lower final loss goes on to the next stage.
    /// Plain Adam gives a slot whose gradient is noise (a hollow seen only at a hard crease
    /// inside its box) full-size steps and can walk it out of the model, where nothing
    /// brings it back; damped Adam keeps such a slot still but moves small parts slowly.
    /// `None`: one run per stage.
    pub damped_rerun: Option<f64>,
    /// Smallest world extent of a part, in units of the model's size.
    pub min_extent: f64,
    /// Coarse-to-fine: the first rounds render at `1/2^levels` of the targets' size and
    /// compare with pooled targets, one level finer every `rounds / (2·levels)` rounds, so
    /// parts far from their place in the target still feel it (and early rounds are cheap).
    /// 0: the paper's single resolution.
    pub levels: u32,
    /// Coarse levels render at full size and pool the difference (slower, but thin parts
    /// keep their true weight) instead of rendering small images.
    pub pooled: bool,
}

impl Default for FitOptions {
    fn default() -> Self {
        FitOptions {
            lr: 0.05,
            iterations: 30,
            rounds: 10,
            lambda: 0.001,
            optimizer: Optimizer::sgd(),
            sigma: (2.0, 0.25),
            loss: LossSpec::default(),
            max_step: 0.02,
            fit_shading: true,
            per_item_albedo: true,
            min_extent: 0.002,
            relative_steps: false,
            polish: 0,
            refine: 0,
            border: 0.0,
            settle: 0.0,
            damped_rerun: Some(DAMPED_FLOOR),
            proportions: true,
            levels: 0,
            pooled: true,
        }
    }
}

/// Adam's `floor` in the damped rerun of every stage ([`FitOptions::damped_rerun`]).
pub const DAMPED_FLOOR: f64 = 0.05;

/// Silhouette softness of [`polish::refine`]'s loss, in pixels: hard but for a sliver.
pub const HARD_SIGMA: f64 = 0.02;

/// Floor of relative step scales, in units of the model's size.
const RELATIVE_FLOOR: f64 = 0.05;

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
    /// Fixed points per circle of each curved part's silhouette (see [`Parametric::fix_rings`]).
    pub rings: Vec<u32>,
    /// Each part's face planes (axis, high side, affine form), for face moves.
    pub faces: Vec<Vec<(u8, bool, Affine)>>,
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
            rings: Vec::new(),
            faces: {
                let mut faces = vec![Vec::new(); model.parts.len()];
                for f in crate::analysis::candidates::affine_features(model) {
                    if let crate::ir::FeatureKind::Plane { axis, high } = f.kind
                        && let Some(form) = f.forms.first()
                    {
                        faces[f.part].push((axis, high, form.clone()));
                    }
                }
                faces
            },
        }
    }

    /// Fixes each curved part's silhouette polygon to the finest count any camera needs at
    /// the start, so the loss stays smooth as radii change.
    pub fn fix_rings(&mut self, cameras: &[Camera]) {
        let geoms = self.geoms(&self.x0);
        self.rings = geoms
            .iter()
            .map(|g| {
                cameras
                    .iter()
                    .map(|c| {
                        let r = g.r1.max(g.r2);
                        crate::render::scene::ring_count(g, &c.frame(), r) as u32
                    })
                    .max()
                    .unwrap_or(0)
            })
            .collect();
    }

    /// The parts' geometry at slot values `x`.
    pub fn geoms(&self, x: &[f64]) -> Vec<PartGeom> {
        self.base
            .iter()
            .zip(&self.forms)
            .zip(&self.kinds)
            .enumerate()
            .map(|(i, ((p, f), &(kind, centered)))| {
                let mut g = PartGeom::from_theta(kind, centered, theta_at(p, f, x));
                g.ring = self.rings.get(i).copied().unwrap_or(0);
                g
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

    /// Lower bounds that keep every part a solid: each size (and each scale factor of an
    /// axis-aligned transform) stays at least `min_extent` in world units, radii stay
    /// non-negative. Only bounds that hold at `x₀` are returned.
    pub fn guards(&self, min_extent: f64) -> Vec<(Affine, f64)> {
        let mut out: Vec<(Affine, f64)> = Vec::new();
        let x0 = &self.x0;
        for (i, (forms, &(kind, _))) in self.forms.iter().zip(&self.kinds).enumerate() {
            let g = PartGeom::from_part(&self.base[i]);
            let col = |j: usize| -> f64 {
                (0..3)
                    .map(|r| g.theta[4 * r + j].powi(2))
                    .sum::<f64>()
                    .sqrt()
                    .max(1e-300)
            };
            let local = [g.hi[0] - g.lo[0], g.hi[1] - g.lo[1], g.hi[2] - g.lo[2]];
            let mut push = |f: &Option<Affine>, sign: f64, min: f64| {
                if let Some(f) = f {
                    let f = f.scale(sign);
                    if f.eval(x0) >= min {
                        out.push((f, min));
                    }
                }
            };
            match kind {
                Kind::Box => {
                    for a in 0..3 {
                        push(&forms[12 + a], 1.0, min_extent / col(a));
                    }
                }
                Kind::Frustum => {
                    push(&forms[12], 1.0, min_extent / col(2));
                    push(&forms[13], 1.0, 0.0);
                    push(&forms[14], 1.0, 0.0);
                    if let (Some(a), Some(b)) = (&forms[13], &forms[14]) {
                        push(&Some(a.add(b)), 1.0, min_extent / col(0).max(col(1)));
                    }
                }
                Kind::Sphere => push(&forms[12], 1.0, min_extent / col(0)),
            }
            // Scale factors of an axis-aligned map keep their sign and some size.
            let aligned =
                (0..3).all(|r| (0..3).filter(|&c| g.theta[4 * r + c] != 0.0).count() == 1);
            if aligned {
                for r in 0..3 {
                    for c in 0..3 {
                        let v = g.theta[4 * r + c];
                        if v != 0.0 && local[c] > 0.0 {
                            push(&forms[4 * r + c], v.signum(), min_extent / local[c]);
                        }
                    }
                }
            }
        }
        out
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

/// Among `candidates` that `ok` accepts, the one with the lowest loss below `best` (the
/// first in order among equals) and its loss; `None` when none improves.
fn best_improvement(
    candidates: impl IntoIterator<Item = Vec<f64>>,
    best: f64,
    loss: &mut dyn FnMut(&[f64]) -> f64,
    ok: &dyn Fn(&[f64]) -> bool,
) -> Option<(f64, Vec<f64>)> {
    let mut chosen: Option<(f64, Vec<f64>)> = None;
    for cand in candidates {
        if !ok(&cand) {
            continue;
        }
        let l = loss(&cand);
        if l < best && chosen.as_ref().is_none_or(|(b, _)| l < *b) {
            chosen = Some((l, cand));
        }
    }
    chosen
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
    /// Per scene item: the albedo fitted last (empty without shading fits).
    pub albedo: Vec<f64>,
}

/// How the pictures are lit and coloured, refitted each round: each view's shading
/// coefficients and each item's albedo.
#[derive(Clone)]
struct Look {
    shades: Vec<[f64; NSHADE]>,
    albedo: Vec<f64>,
}

/// Progress report, once per step.
pub struct Progress<'a> {
    pub step: &'a Step,
    /// Steps taken so far, this one included (reruns count).
    pub done: usize,
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

/// Moves `y` onto `{y : f(x(y)) ≥ min}` for every guard it violates (a few sweeps of
/// half-space projections).
fn project_guards(guards: &[(Affine, f64)], space: &Space, y: &mut [f64]) {
    for _ in 0..8 {
        let x = space.x(y);
        let mut moved = false;
        for (f, min) in guards {
            let v = f.eval(&x);
            if v >= *min {
                continue;
            }
            // ∂f/∂y = scale·Bᵀ·a.
            let mut a = vec![0.0; x.len()];
            for &(s, c) in &f.terms {
                a[s as usize] = c;
            }
            let g = space.grad_y(&a);
            let n2: f64 = g.iter().map(|v| v * v).sum();
            if n2 <= 0.0 {
                continue;
            }
            // Aim a little inside so rounding does not leave it violated.
            let k = (min - v) * 1.000001 / n2;
            for (yi, gi) in y.iter_mut().zip(&g) {
                *yi += k * gi;
            }
            moved = true;
        }
        if !moved {
            break;
        }
    }
}

/// Fits slot values so renders from `cameras` match `targets`, stage after stage.
pub fn fit(
    problem: &Parametric,
    cameras: &[Camera],
    targets: &[Target],
    stages: &[Stage],
    backend: &mut dyn Backend,
    opts: &FitOptions,
    progress: &mut dyn FnMut(&Progress),
) -> Result<FitResult, FitError> {
    check(problem, cameras, targets, backend)?;
    let bordered;
    let (cameras, targets) = if opts.border > 0.0 {
        bordered = frame::bordered(cameras, targets, opts.border);
        (&bordered.0[..], &bordered.1[..])
    } else {
        (cameras, targets)
    };
    let mut fixed;
    let problem = if problem.rings.is_empty() {
        fixed = problem.clone();
        fixed.fix_rings(cameras);
        &fixed
    } else {
        problem
    };
    let d = problem.x0.len();
    for st in stages {
        if let Some(b) = &st.basis
            && b.nrows() != d
        {
            return Err(FitError::Basis(b.nrows(), d));
        }
    }
    // Parts that start out drawable must stay so.
    let drawable: Vec<bool> = problem.geoms(&problem.x0).iter().map(|g| g.valid).collect();
    let guards = problem.guards(opts.min_extent * problem.scale);
    let mut look = Look {
        shades: vec![DEFAULT_SHADE_PRIOR; cameras.len()],
        albedo: Vec::new(),
    };
    let rounds: usize = stages.iter().map(|s| s.rounds).sum::<usize>().max(1);
    let rerun = opts.damped_rerun.and_then(|f| opts.optimizer.damped(f));
    let total_steps = rounds * opts.iterations * if rerun.is_some() { 2 } else { 1 };
    let mut done = 0;
    let mut curve = Vec::with_capacity(total_steps);
    let sigma_at = |r: usize| {
        if rounds == 1 {
            opts.sigma.1
        } else {
            let f = r as f64 / (rounds - 1) as f64;
            opts.sigma.0 * (opts.sigma.1 / opts.sigma.0).powf(f)
        }
    };
    // Coarse levels render smaller images and compare with pooled targets.
    let mut max_level = 0u32;
    while max_level < opts.levels
        && cameras.iter().all(|c| {
            let k = 1u32 << (max_level + 1);
            c.width % k == 0 && c.height % k == 0 && c.width / k >= 16 && c.height / k >= 16
        })
    {
        max_level += 1;
    }
    let mut pyramid: Vec<(Vec<Camera>, Vec<Target>)> = vec![(cameras.to_vec(), targets.to_vec())];
    for k in 1..=max_level as usize {
        let (cams, tgts) = &pyramid[k - 1];
        let next = (
            cams.iter()
                .map(|c| c.with_size(c.width / 2, c.height / 2))
                .collect(),
            tgts.iter().map(Target::pooled).collect(),
        );
        pyramid.push(next);
    }
    let level_at = |r: usize| -> usize {
        if max_level == 0 {
            return 0;
        }
        // The first half of the rounds walks down the levels; the rest is full resolution.
        let half = (rounds / 2).max(1);
        let per = (half as f64 / max_level as f64).max(1.0);
        max_level.saturating_sub((r as f64 / per) as u32) as usize
    };
    let image_loss = |backend: &mut dyn Backend,
                      level: usize,
                      x: &[f64],
                      sigma: f64,
                      look: &Look,
                      grad: bool| {
        // Pooled levels render at full size and compare pooled residuals.
        let (render_level, pool) = if opts.pooled {
            (0, level as u32)
        } else {
            (level, 0)
        };
        let (cams, tgts) = &pyramid[render_level];
        let scene = problem.scene(x).with_albedo(&look.albedo);
        let views: Vec<ViewPrep> = cams
            .iter()
            .map(|c| prepare_view(&scene, c, Some(sigma)))
            .collect();
        let spec = LossSpec {
            level: opts.loss.level + pool,
            ..opts.loss
        };
        loss::image_loss(
            backend,
            &scene,
            &views,
            sigma,
            &look.shades,
            tgts,
            &spec,
            grad,
        )
    };
    // Shading and albedos are fitted at full size, on the hard surface.
    let refit_shades = |backend: &mut dyn Backend, x: &[f64], look: &mut Look| {
        if !opts.fit_shading {
            return;
        }
        let scene = problem.scene(x);
        let views: Vec<ViewPrep> = cameras
            .iter()
            .map(|c| prepare_view(&scene, c, None))
            .collect();
        let hard: Vec<_> = backend
            .render(&scene, &views, None, &look.shades)
            .into_iter()
            .map(|(_, h)| h)
            .collect();
        let fitted = albedo::fit_shading(&hard, targets, DEFAULT_SHADE_PRIOR, opts.per_item_albedo);
        look.shades = fitted.shades;
        look.albedo = fitted.albedo;
    };
    refit_shades(backend, &problem.x0, &mut look);
    let start_loss = image_loss(backend, 0, &problem.x0, opts.sigma.1, &look, false).per_view;
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
    // Step scale per slot: the model's size, or (relative steps) the slot's own magnitude
    // with a floor, so thin parts move in proportion.
    let scales: Vec<f64> = problem
        .x0
        .iter()
        .map(|&v| {
            if opts.relative_steps {
                v.abs().max(RELATIVE_FLOOR * problem.scale)
            } else {
                problem.scale
            }
        })
        .collect();
    let valid = |x: &[f64]| {
        x.iter().all(|v| v.is_finite())
            && guards.iter().all(|(f, min)| f.eval(x) >= *min)
            && problem
                .geoms(x)
                .iter()
                .zip(&drawable)
                .all(|(g, &was)| g.valid || !was)
    };
    let mut x = problem.x0.clone();
    if opts.proportions {
        // Compared coarsely (pooled twice, the first round's softness) so that far edges
        // still count.
        let spec = LossSpec {
            level: opts.loss.level + 2,
            ..opts.loss
        };
        let sigma = opts.sigma.0;
        let weights = stages::axis_weights(&problem.base, d);
        let mut coarse = |x: &[f64]| {
            let scene = problem.scene(x).with_albedo(&look.albedo);
            let views: Vec<ViewPrep> = cameras
                .iter()
                .map(|c| prepare_view(&scene, c, Some(sigma)))
                .collect();
            loss::image_loss(
                backend,
                &scene,
                &views,
                sigma,
                &look.shades,
                targets,
                &spec,
                false,
            )
            .total()
        };
        x = proportions::search(x, &weights, &mut coarse, &valid);
        refit_shades(backend, &x, &mut look);
    }
    // One stage from `start` with `optimizer`, its steps numbered from `round0`.
    let mut run_stage = |backend: &mut dyn Backend,
                         progress: &mut dyn FnMut(&Progress),
                         stage: &Stage,
                         start: &[f64],
                         optimizer: Optimizer,
                         round0: usize,
                         look: &mut Look|
     -> (Vec<f64>, Vec<Step>) {
        let space = match &stage.basis {
            None => Space::slots(start, &scales),
            Some(n) => Space::subspace(start, n.clone(), &scales),
        };
        let dim = space.dim();
        let mut y = vec![0.0; dim];
        let mut state = OptState::new(optimizer, dim);
        let mut steps = Vec::with_capacity(stage.rounds * opts.iterations);
        for round in round0..round0 + stage.rounds {
            let sigma = sigma_at(round);
            let level = level_at(round);
            let last = round + 1 == round0 + stage.rounds;
            refit_shades(backend, &space.x(&y), look);
            for it in 0..opts.iterations {
                let xs = space.x(&y);
                let out = image_loss(backend, level, &xs, sigma, look, true);
                let (rv, rg) = reg(&xs);
                let mut gx = problem.chain(&out.dtheta);
                for (g, r) in gx.iter_mut().zip(&rg) {
                    *g += r;
                }
                let gy = space.grad_y(&gx);
                let lr = optimize::round_rate(opts.lr, opts.settle, last, it, opts.iterations);
                let mut delta = state.step(&gy, lr);
                let big = delta.iter().fold(0.0f64, |a, d| a.max(d.abs()));
                if big > opts.max_step && big.is_finite() {
                    let k = opts.max_step / big;
                    delta.iter_mut().for_each(|d| *d *= k);
                }
                // Sizes stay above their guards: project the step onto the violated bounds.
                let mut cand: Vec<f64> = y.iter().zip(&delta).map(|(a, d)| a - d).collect();
                project_guards(&guards, &space, &mut cand);
                for (d, (a, c)) in delta.iter_mut().zip(y.iter().zip(&cand)) {
                    *d = a - c;
                }
                // Never step to a degenerate part (non-positive size, singular transform).
                for _ in 0..10 {
                    let cand: Vec<f64> = y.iter().zip(&delta).map(|(a, d)| a - d).collect();
                    let ok = cand.iter().all(|v| v.is_finite())
                        && problem
                            .geoms(&space.x(&cand))
                            .iter()
                            .zip(&drawable)
                            .all(|(g, &was)| g.valid || !was);
                    if ok {
                        y = cand;
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
                steps.push(step);
                done += 1;
                progress(&Progress {
                    step: &step,
                    done,
                    total_steps,
                });
            }
        }
        (space.x(&y), steps)
    };
    // The final loss of a candidate, on the hard surface's shading as the fit ends.
    let final_loss = |backend: &mut dyn Backend, x: &[f64], look: &mut Look| -> f64 {
        refit_shades(backend, x, look);
        image_loss(backend, 0, x, opts.sigma.1, look, false).total() + reg(x).0
    };
    let mut round = 0;
    for stage in stages {
        let start_look = look.clone();
        let (mut best_x, mut best_steps) = run_stage(
            backend,
            progress,
            stage,
            &x,
            opts.optimizer,
            round,
            &mut look,
        );
        if let Some(damped) = rerun {
            let mut look_b = start_look;
            let (xb, steps_b) = run_stage(backend, progress, stage, &x, damped, round, &mut look_b);
            let la = final_loss(backend, &best_x, &mut look);
            let lb = final_loss(backend, &xb, &mut look_b);
            if lb < la {
                (look, best_x, best_steps) = (look_b, xb, steps_b);
            }
        }
        curve.extend(best_steps);
        x = best_x;
        round += stage.rounds;
    }
    refit_shades(backend, &x, &mut look);
    if opts.polish > 0 {
        let eval = |backend: &mut dyn Backend, x: &[f64]| -> f64 {
            image_loss(backend, 0, x, opts.sigma.1, &look, false).total() + reg(x).0
        };
        x = polish(problem, x, opts.polish, &mut |x| eval(backend, x), &valid);
        refit_shades(backend, &x, &mut look);
    }
    if opts.refine > 0 {
        let pixel = cameras
            .iter()
            .map(Camera::pixel_size)
            .fold(f64::INFINITY, f64::min);
        let eval = |backend: &mut dyn Backend, x: &[f64]| -> f64 {
            image_loss(backend, 0, x, HARD_SIGMA, &look, false).total() + reg(x).0
        };
        x = polish::refine(
            problem,
            x,
            pixel,
            opts.refine,
            &mut |x| eval(backend, x),
            &valid,
        );
        refit_shades(backend, &x, &mut look);
    }
    let end_loss = image_loss(backend, 0, &x, opts.sigma.1, &look, false).per_view;
    Ok(FitResult {
        x0: problem.x0.clone(),
        x,
        curve,
        start_loss,
        end_loss,
        shades: look.shades,
        albedo: look.albedo,
    })
}
