//! The fit itself: [`fit`] checks its inputs ([`check`]) and runs a [`Fitter`], which holds
//! everything a fit fixes at its start (the bordered cameras and targets, the coarse levels,
//! the size guards, the step scales) and runs the schedule as methods: the proportions
//! search, each stage's rounds of optimiser steps (twice with a damped rerun), the
//! finishing passes from the best point stood on so far. Once per fit, where a stage lost a part ([`super::revive`]), the rest
//! of the schedule runs from the stage's end and from that point with the part put back,
//! and the fit goes on from the one its judge prefers.
//!
//! Invariants: every image loss goes through `Fitter::loss_at`, the one call of
//! [`Backend::loss`]; a step never leaves a size guard nor makes a part that started
//! drawable degenerate; the lighting (`Look`) is refitted at the start of every round and
//! after every pass, always on the hard surface at full size.

use super::best::Best;
use super::check::{FitError, check};
use super::descent::Descent;
use super::loss::{LossSpec, Target};
use super::memo::Memo;
use super::optimize::{self, OptState, Optimizer, Space};
use super::options::{
    FitOptions, GUARD_SWEEPS, HARD_SIGMA, PROPORTIONS_POOLING, RELATIVE_FLOOR, STEP_HALVINGS,
    SoftEdges,
};
use super::part_moves::{Edges, Judge};
use super::prior::Prior;
use super::uncertainty::{AtPoint, Information};
use super::{Parametric, Stage, albedo, frame, polish, proportions, revive, stages};
use crate::ir::Affine;
use crate::render::camera::Camera;
use crate::render::scene::{BOX_FILTER, DEFAULT_SHADE, NSHADE, is_box};
use crate::render::soft::{ViewPrep, prepare_view};
use crate::render::{Backend, ImageValues};
use crate::tolerance::GUARD_MARGIN;
use rayon::prelude::*;
use std::borrow::Cow;

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

/// Moves `y` onto `{y : f(x(y)) ≥ min}` for every guard it violates (a few sweeps of
/// half-space projections).
fn project_guards(guards: &[(Affine, f64)], space: &Space, y: &mut [f64]) {
    for _ in 0..GUARD_SWEEPS {
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
            let k = (min - v) * GUARD_MARGIN / n2;
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
    let fitter = Fitter::new(problem, cameras, targets, stages, opts)?;
    Ok(fitter.run(backend, progress))
}

/// [`fit`], then how well the pictures determine each number at its result
/// ([`Fitter::information`]).
pub fn fit_measured(
    problem: &Parametric,
    cameras: &[Camera],
    targets: &[Target],
    stages: &[Stage],
    backend: &mut dyn Backend,
    opts: &FitOptions,
    progress: &mut dyn FnMut(&Progress),
) -> Result<(FitResult, Information), FitError> {
    check(problem, cameras, targets, backend)?;
    let fitter = Fitter::new(problem, cameras, targets, stages, opts)?;
    let result = fitter.run(backend, progress);
    let information = fitter.information(backend, &result);
    Ok((result, information))
}

/// A fit set up: what its start fixes. [`Fitter::run`] runs it.
pub struct Fitter<'a> {
    opts: &'a FitOptions,
    stages: &'a [Stage],
    /// The problem with its silhouettes' rings fixed for these cameras.
    problem: Cow<'a, Parametric>,
    /// The cameras and targets at full size, bordered when [`FitOptions::border`] asks.
    cameras: Cow<'a, [Camera]>,
    targets: Cow<'a, [Target]>,
    /// The finest camera's pixel, world units at its centre of view.
    pixel: f64,
    /// Levels 1 to `max_level` of rendering small (halved cameras, pooled targets); empty
    /// when coarse levels are pooled at full size ([`FitOptions::pooled`]).
    halved: Vec<(Vec<Camera>, Vec<Target>)>,
    /// The coarsest level every camera allows, at most [`FitOptions::levels`].
    max_level: u32,
    /// Rounds of all stages (at least 1).
    rounds: usize,
    /// Per part: whether it is drawable at the start (it must stay so).
    drawable: Vec<bool>,
    /// Lower bounds `f(x) ≥ min` that keep every part a solid.
    guards: Vec<(Affine, f64)>,
    /// The regulariser: what the fit believes before the pictures.
    prior: Prior,
    /// How far one unit of an optimiser variable moves each slot.
    scales: Vec<f64>,
    /// The damped optimiser each stage reruns with, if any.
    rerun: Option<Optimizer>,
    /// The lighting refitted at recent points, and the judge's loss there (both depend on
    /// the point alone; the schedule asks at the same point several times).
    looks: Memo<Look>,
    judged: Memo<ImageValues>,
}

/// Where a stage starts: its stage, its point and the number of its first round.
struct Leg<'s> {
    stage: &'s Stage,
    start: &'s [f64],
    round0: usize,
}

/// Steps counted across every run of a fit (reruns included), reported as they are taken.
struct Tally<'p> {
    done: usize,
    total_steps: usize,
    report: &'p mut dyn FnMut(&Progress),
}

impl Tally<'_> {
    fn record(&mut self, step: &Step) {
        self.done += 1;
        (self.report)(&Progress {
            step,
            done: self.done,
            total_steps: self.total_steps,
        });
    }
}

/// What one loss evaluation compares: images of which level (0: full size), how soft, and
/// the loss's settings (its pooling included).
struct Compare {
    level: usize,
    sigma: f64,
    spec: LossSpec,
}

impl<'a> Fitter<'a> {
    /// Sets a fit up. The inputs must have passed [`check`]; fails when a stage's basis
    /// does not match the model's slots.
    pub fn new(
        problem: &'a Parametric,
        cameras: &'a [Camera],
        targets: &'a [Target],
        stages: &'a [Stage],
        opts: &'a FitOptions,
    ) -> Result<Fitter<'a>, FitError> {
        let (cameras, targets): (Cow<[Camera]>, Cow<[Target]>) = if opts.border > 0.0 {
            let (c, t) = frame::bordered(cameras, targets, opts.border);
            (Cow::Owned(c), Cow::Owned(t))
        } else {
            (Cow::Borrowed(cameras), Cow::Borrowed(targets))
        };
        let problem = if problem.rings.is_empty() {
            let mut fixed = problem.clone();
            fixed.fix_rings(&cameras);
            Cow::Owned(fixed)
        } else {
            Cow::Borrowed(problem)
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
        let drawable = problem.geoms(&problem.x0).iter().map(|g| g.valid).collect();
        let guards = problem.guards(opts.min_extent * problem.scale);
        let max_level = frame::coarsest_level(&cameras, opts.levels);
        let halved = if opts.pooled {
            Vec::new()
        } else {
            frame::halved_levels(&cameras, &targets, max_level)
        };
        let pixel = cameras
            .iter()
            .map(Camera::pixel_size)
            .fold(f64::INFINITY, f64::min);
        let prior = Prior::new(&problem, opts, pixel);
        Ok(Fitter {
            opts,
            pixel,
            stages,
            scales: step_scales(&problem, opts),
            rounds: stages.iter().map(|s| s.rounds).sum::<usize>().max(1),
            rerun: opts.damped_rerun.and_then(|f| opts.optimizer.damped(f)),
            problem,
            cameras,
            targets,
            halved,
            max_level,
            drawable,
            guards,
            prior,
            looks: Memo::default(),
            judged: Memo::default(),
        })
    }

    /// Runs the fit: the proportions search, the stages, the finishing passes. Returns the
    /// best point it stood on by the loss the schedule ends with ([`Fitter::judge`]): the
    /// start, or where the proportions search, a stage or a pass ended.
    pub fn run(&self, backend: &mut dyn Backend, progress: &mut dyn FnMut(&Progress)) -> FitResult {
        let mut tally = Tally {
            done: 0,
            total_steps: self.rounds * self.opts.iterations * self.runs(),
            report: progress,
        };
        let problem = &*self.problem;
        let mut look = Look {
            shades: vec![DEFAULT_SHADE; self.cameras.len()],
            albedo: Vec::new(),
        };
        let start_loss = self.judge(backend, &problem.x0, &mut look).per_view;
        let start = start_loss.iter().sum::<f64>() + self.reg(&problem.x0).0;
        let mut best = Best::new(problem.x0.clone(), start);
        let mut x = problem.x0.clone();
        if self.opts.proportions {
            x = self.proportions(backend, x, &look);
            self.offer(backend, &mut best, &x, &mut look);
        }
        let curve = self.run_from(backend, &mut tally, 0, x, &mut look, &mut best);
        let end_loss = self.judge(backend, &best.x, &mut look).per_view;
        FitResult {
            x0: problem.x0.clone(),
            x: best.x,
            curve,
            start_loss,
            end_loss,
            shades: look.shades,
            albedo: look.albedo,
        }
    }

    /// Whether the fit compares area coverage where [`FitOptions::coverage`] asks: unless
    /// every picture was drawn with hard edges (point-sampled, as OpenSCAD draws). A
    /// point-sampled picture is not the area coverage of the truth, so a loss on coverage
    /// is least off the truth (edges moved by a fraction of a pixel, a 2-pixel board
    /// thinned by a third); compared with a hard-edged render, the truth is its optimum.
    fn area_coverage(&self) -> bool {
        self.opts.coverage && !self.targets.iter().all(|t| t.hard_edges)
    }

    /// The loss a fit is judged by, per view, at `x` (the lighting refitted there first):
    /// the loss of the schedule's last pass: area coverage where [`Fitter::area_coverage`],
    /// else hard-edged with [`FitOptions::refine`], else at the last round's softness; plus the regulariser, counted in the first view.
    fn judge(&self, backend: &mut dyn Backend, x: &[f64], look: &mut Look) -> ImageValues {
        self.refit_shades(backend, x, look);
        let sigma = if self.area_coverage() {
            BOX_FILTER
        } else if self.opts.refine > 0 {
            HARD_SIGMA
        } else {
            self.opts.sigma.1
        };
        self.judged
            .get_or(x, || self.image_loss(backend, 0, x, sigma, look, false))
    }

    /// [`Fitter::judge`]'s loss plus the regulariser at `x` (refitting `look` there): what
    /// `best` and every choice between two runs compare.
    fn score(&self, backend: &mut dyn Backend, x: &[f64], look: &mut Look) -> f64 {
        self.judge(backend, x, look).total() + self.reg(x).0
    }

    /// Offers `x` to `best` by [`Fitter::score`] (refitting `look` at `x`).
    fn offer(&self, backend: &mut dyn Backend, best: &mut Best, x: &[f64], look: &mut Look) {
        let loss = self.score(backend, x, look);
        best.offer(x, loss);
    }

    /// How many times each stage runs: twice with a damped rerun.
    fn runs(&self) -> usize {
        if self.rerun.is_some() { 2 } else { 1 }
    }

    /// The Fisher information of the numbers at the fit's result, from the judge's loss
    /// with the look the fit ended with ([`super::uncertainty`]).
    pub fn information(&self, backend: &mut dyn Backend, result: &FitResult) -> Information {
        let at = AtPoint {
            problem: &self.problem,
            cameras: &self.cameras,
            targets: &self.targets,
            shades: &result.shades,
            albedo: &result.albedo,
            spec: &self.opts.loss,
        };
        super::uncertainty::information(&at, backend, &result.x, &|x| self.valid(x))
    }

    /// The cameras and targets of level `level` (0: full size). Only levels up to
    /// `max_level` exist, and levels above 0 only when they are not pooled.
    fn level(&self, level: usize) -> (&[Camera], &[Target]) {
        match level {
            0 => (&self.cameras, &self.targets),
            k => {
                let (cams, tgts) = &self.halved[k - 1];
                (cams, tgts)
            }
        }
    }

    /// Silhouette softness of round `r`: geometric from `sigma.0` to `sigma.1`; the box
    /// filter in the last round where [`Fitter::area_coverage`].
    fn sigma_at(&self, r: usize) -> f64 {
        let (first, last) = self.opts.sigma;
        if self.area_coverage() && r + 1 == self.rounds {
            BOX_FILTER
        } else if self.rounds == 1 {
            last
        } else {
            let f = r as f64 / (self.rounds - 1) as f64;
            first * (last / first).powf(f)
        }
    }

    /// Coarse level of round `r`: the first half of the rounds walks down the levels; the
    /// rest is full resolution.
    fn level_at(&self, r: usize) -> usize {
        if self.max_level == 0 {
            return 0;
        }
        let half = (self.rounds / 2).max(1);
        let per = (half as f64 / self.max_level as f64).max(1.0);
        self.max_level.saturating_sub((r as f64 / per) as u32) as usize
    }

    /// The image loss of slot values `x` as `at` says (with `grad`, its gradient too): the
    /// one place a fit asks the renderer for a loss.
    fn loss_at(
        &self,
        backend: &mut dyn Backend,
        x: &[f64],
        look: &Look,
        at: &Compare,
        grad: bool,
    ) -> ImageValues {
        let (cams, tgts) = self.level(at.level);
        let scene = self.problem.scene(x).with_albedo(&look.albedo);
        let views: Vec<ViewPrep> = cams
            .par_iter()
            .map(|c| prepare_view(&scene, c, Some(at.sigma)))
            .collect();
        super::loss::image_loss(
            backend,
            &scene,
            &views,
            at.sigma,
            &look.shades,
            tgts,
            &at.spec,
            grad,
        )
    }

    /// The image loss at coarse level `level` and edge softness `sigma`, rendered as
    /// `sigma` says ([`Fitter::compare`]).
    fn image_loss(
        &self,
        backend: &mut dyn Backend,
        level: usize,
        x: &[f64],
        sigma: f64,
        look: &Look,
        grad: bool,
    ) -> ImageValues {
        self.loss_at(backend, x, look, &self.compare(level, sigma), grad)
    }

    /// What a loss at coarse level `level` and softness `sigma` compares: pooled levels
    /// render at full size and compare pooled residuals; otherwise small images against
    /// pooled targets.
    fn compare(&self, level: usize, sigma: f64) -> Compare {
        let (render_level, pool) = if self.opts.pooled {
            (0, level as u32)
        } else {
            (level, 0)
        };
        Compare {
            level: render_level,
            sigma,
            spec: LossSpec {
                level: self.opts.loss.level + pool,
                ..self.opts.loss
            },
        }
    }

    /// What a round of softness `sigma` compares ([`FitOptions::soft_edges`]): sigmoid
    /// edges, or exact area coverage with both pictures blurred as wide as that sigmoid.
    /// The rounds, the face moves after them and the proportions search soften so.
    fn round_compare(&self, level: usize, sigma: f64) -> Compare {
        let mut at = self.compare(level, sigma);
        if self.opts.soft_edges == SoftEdges::Blurred && !is_box(sigma) {
            let pooled = at.spec.level - self.opts.loss.level;
            at.sigma = BOX_FILTER;
            at.spec.smooth = SoftEdges::blur_of(sigma) / f64::from(1u32 << pooled);
        }
        at
    }

    /// Refits each view's shading and each item's albedo to the targets at `x` (at full
    /// size, on the hard surface), when the options ask for it.
    fn refit_shades(&self, backend: &mut dyn Backend, x: &[f64], look: &mut Look) {
        if !self.opts.fit_shading {
            return;
        }
        *look = self.looks.get_or(x, || self.fitted_look(backend, x, look));
    }

    /// Each view's shading and each item's albedo fitted to the targets at `x`.
    fn fitted_look(&self, backend: &mut dyn Backend, x: &[f64], look: &Look) -> Look {
        let scene = self.problem.scene(x);
        let views: Vec<ViewPrep> = self
            .cameras
            .iter()
            .map(|c| prepare_view(&scene, c, None))
            .collect();
        let hard: Vec<_> = backend
            .render(&scene, &views, None, &look.shades)
            .into_iter()
            .map(|(_, h)| h)
            .collect();
        let fitted = albedo::fit_shading(
            &hard,
            &self.targets,
            DEFAULT_SHADE,
            self.opts.per_item_albedo,
        );
        Look {
            shades: fitted.shades,
            albedo: fitted.albedo,
        }
    }

    /// The regulariser at `x` ([`Prior`]) and its gradient.
    fn reg(&self, x: &[f64]) -> (f64, Vec<f64>) {
        self.prior.at(x)
    }

    /// Every part that started drawable is drawable at `x`.
    fn keeps_drawable(&self, x: &[f64]) -> bool {
        self.problem
            .geoms(x)
            .iter()
            .zip(&self.drawable)
            .all(|(g, &was)| g.valid || !was)
    }

    /// `x` is a point a fit may stand on: finite, inside the guards, no part degenerate.
    fn valid(&self, x: &[f64]) -> bool {
        x.iter().all(|v| v.is_finite())
            && self.guards.iter().all(|(f, min)| f.eval(x) >= *min)
            && self.keeps_drawable(x)
    }

    /// The proportions search from `x`, compared coarsely (pooled twice, the first round's
    /// softness) so that far edges still count.
    fn proportions(&self, backend: &mut dyn Backend, x: Vec<f64>, look: &Look) -> Vec<f64> {
        let mut at = self.round_compare(0, self.opts.sigma.0);
        at.spec.level += PROPORTIONS_POOLING;
        at.spec.smooth /= f64::from(1u32 << PROPORTIONS_POOLING);
        let weights = stages::axis_weights(&self.problem.base, self.problem.x0.len());
        let mut coarse = |x: &[f64]| self.loss_at(backend, x, look, &at, false).total();
        proportions::search(x, &weights, &mut coarse, &|x| self.valid(x))
    }

    /// The stages from the `first` on, from `x`, then the finishing passes: each stage
    /// from where the previous one ended; with a damped rerun, the run with the lower final
    /// loss goes on. Every stage's end is offered to `best`. The run from the first stage
    /// branches where a stage lost a part ([`Fitter::revived`]): the rest of the schedule,
    /// finishing passes included, runs from the stage's end and from the point with the
    /// part put back (neither branches again), each with its own `best`, and the branch
    /// whose best is lower is what the fit returns. The finishing passes decide: a branch
    /// behind at the stage's end can finish well ahead (a shelf thinned by the stage comes
    /// back where a board had grown over it). The kept runs' steps.
    fn run_from(
        &self,
        backend: &mut dyn Backend,
        tally: &mut Tally,
        first: usize,
        mut x: Vec<f64>,
        look: &mut Look,
        best: &mut Best,
    ) -> Vec<Step> {
        let mut curve = Vec::with_capacity(tally.total_steps);
        let mut round: usize = self.stages[..first].iter().map(|s| s.rounds).sum();
        for (i, stage) in self.stages.iter().enumerate().skip(first) {
            let leg = Leg {
                stage,
                start: &x,
                round0: round,
            };
            let start_look = look.clone();
            let (mut best_x, mut best_steps) =
                self.run_stage(backend, tally, &leg, self.opts.optimizer, look);
            if let Some(damped) = self.rerun {
                let mut look_b = start_look;
                let (xb, steps_b) = self.run_stage(backend, tally, &leg, damped, &mut look_b);
                let la = self.score(backend, &best_x, look);
                let lb = self.score(backend, &xb, &mut look_b);
                if lb < la {
                    (*look, best_x, best_steps) = (look_b, xb, steps_b);
                }
            }
            curve.extend(best_steps);
            let revived = if first == 0 && i + 1 < self.stages.len() {
                self.revived(&x, &best_x)
            } else {
                None
            };
            x = best_x;
            round += stage.rounds;
            let mut judged = look.clone();
            self.offer(backend, best, &x, &mut judged);
            if let Some(alt) = revived {
                // The branch's steps are more work than the fit announced: the total grows.
                let rest: usize = self.stages[i + 1..].iter().map(|s| s.rounds).sum();
                tally.total_steps += rest * self.opts.iterations * self.runs();
                let (mut look_b, mut best_b) = (look.clone(), best.clone());
                let cb = self.run_from(backend, tally, i + 1, alt, &mut look_b, &mut best_b);
                let ca = self.run_from(backend, tally, i + 1, x, look, best);
                if best_b.loss < best.loss {
                    (*look, *best) = (look_b, best_b);
                    curve.extend(cb);
                } else {
                    curve.extend(ca);
                }
                return curve;
            }
        }
        // The finishing passes refine the best point stood on, not the last stage's end:
        // a stage can leave a point its judge prefers (a fresh optimiser's first steps
        // move every number by about the rate, even at a minimum).
        let x = best.x.clone();
        self.refit_shades(backend, &x, look);
        self.finish(backend, x, look, best);
        curve
    }

    /// `end` with every part lost since `start` ([`revive::lost_parts`]) put back as it
    /// stood there; `None` when none was lost or the point is not one a fit may stand on.
    fn revived(&self, start: &[f64], end: &[f64]) -> Option<Vec<f64>> {
        let lost = revive::lost_parts(&self.problem, start, end, self.pixel);
        let mut x = end.to_vec();
        for &p in &lost {
            x = revive::restored(&self.problem, &x, start, p)?;
        }
        (!lost.is_empty() && self.valid(&x)).then_some(x)
    }

    /// One stage from `leg.start` with `optimizer`, its steps numbered from `leg.round0`.
    fn run_stage(
        &self,
        backend: &mut dyn Backend,
        tally: &mut Tally,
        leg: &Leg,
        optimizer: Optimizer,
        look: &mut Look,
    ) -> (Vec<f64>, Vec<Step>) {
        let space = match &leg.stage.basis {
            None => Space::slots(leg.start, &self.scales),
            Some(n) => Space::subspace(leg.start, n.clone(), &self.scales),
        };
        let state = OptState::new(optimizer, space.dim());
        let mut descent = Descent::new(space, state, self.opts.reach);
        let iterations = self.opts.iterations;
        let mut steps = Vec::with_capacity(leg.stage.rounds * iterations);
        let end = leg.round0 + leg.stage.rounds;
        for round in leg.round0..end {
            let sigma = self.sigma_at(round);
            let level = self.level_at(round);
            let last = round + 1 == end;
            self.refit_shades(backend, &descent.x(), look);
            descent.last_loss = None;
            for it in 0..iterations {
                let lr = optimize::round_rate(self.opts.lr, self.opts.settle, last, it, iterations);
                let (image, reg) = self.descend(backend, &mut descent, level, sigma, lr, look);
                let step = Step {
                    round,
                    iteration: it,
                    loss: image + reg,
                    image_loss: image,
                    sigma,
                };
                steps.push(step);
                tally.record(&step);
            }
        }
        (descent.x(), steps)
    }

    /// One optimiser step at coarse level `level`, softness `sigma` and rate `lr`: the
    /// image loss and the regulariser where it stood.
    fn descend(
        &self,
        backend: &mut dyn Backend,
        descent: &mut Descent,
        level: usize,
        sigma: f64,
        lr: f64,
        look: &Look,
    ) -> (f64, f64) {
        let xs = descent.x();
        let out = self.loss_at(backend, &xs, look, &self.round_compare(level, sigma), true);
        let (rv, rg) = self.reg(&xs);
        let mut gx = self.problem.chain(&out.dtheta);
        for (g, r) in gx.iter_mut().zip(&rg) {
            *g += r;
        }
        let gy = descent.space.grad_y(&gx);
        descent.adapt_reach(out.total() + rv);
        let mut delta = descent.state.step(&gy, lr);
        descent.bound_reach(&self.problem, &mut delta, self.softness(sigma, level));
        self.take_step(descent, delta);
        (out.total(), rv)
    }

    /// The world distance of the edge softness `sigma` at coarse level `level` (the last
    /// round's softness at least), on the finest camera.
    fn softness(&self, sigma: f64, level: usize) -> f64 {
        sigma.max(self.opts.sigma.1) * self.pixel * (1u32 << level) as f64
    }

    /// Moves the descent by `−delta`, made safe: at most [`FitOptions::max_step`] per
    /// variable, projected back onto the size guards it would leave, and halved until no
    /// part that started drawable degenerates (not moved at all if that never happens).
    fn take_step(&self, descent: &mut Descent, mut delta: Vec<f64>) {
        let big = delta.iter().fold(0.0f64, |a, d| a.max(d.abs()));
        if big > self.opts.max_step && big.is_finite() {
            let k = self.opts.max_step / big;
            delta.iter_mut().for_each(|d| *d *= k);
        }
        let y = &descent.y;
        let mut cand: Vec<f64> = y.iter().zip(&delta).map(|(a, d)| a - d).collect();
        project_guards(&self.guards, &descent.space, &mut cand);
        for (d, (a, c)) in delta.iter_mut().zip(y.iter().zip(&cand)) {
            *d = a - c;
        }
        for _ in 0..STEP_HALVINGS {
            let cand: Vec<f64> = y.iter().zip(&delta).map(|(a, d)| a - d).collect();
            let ok =
                cand.iter().all(|v| v.is_finite()) && self.keeps_drawable(&descent.space.x(&cand));
            if ok {
                descent.y = cand;
                return;
            }
            delta.iter_mut().for_each(|d| *d *= 0.5);
        }
    }

    /// The finishing passes the options ask for: face moves ([`polish`]), then moves of a
    /// pixel or less on hard edges ([`polish::refine`]), each followed by a refit of the
    /// lighting and offered to `best`.
    fn finish(&self, backend: &mut dyn Backend, mut x: Vec<f64>, look: &mut Look, best: &mut Best) {
        let problem = &*self.problem;
        let valid = |x: &[f64]| self.valid(x);
        if self.opts.polish > 0 {
            let mut judge = FinishJudge {
                fitter: self,
                backend: &mut *backend,
                kept: look.clone(),
                look: &mut *look,
                fine: self.round_compare(0, self.opts.sigma.1),
                coarse: self.round_compare(0, self.opts.sigma.0),
            };
            x = polish(problem, x, self.opts.polish, &mut judge, &valid);
            self.offer(backend, best, &x, look);
        }
        if self.opts.refine > 0 {
            let pixel = self.pixel;
            let edges = if self.area_coverage() {
                BOX_FILTER
            } else {
                HARD_SIGMA
            };
            let mut eval = |x: &[f64]| {
                self.image_loss(backend, 0, x, edges, look, false).total() + self.reg(x).0
            };
            x = polish::refine(problem, x, pixel, self.opts.refine, &mut eval, &valid);
            self.offer(backend, best, &x, look);
        }
    }
}

/// The finishing passes' loss ([`Judge`]): the rounds' comparison at the last round's
/// softness ([`Edges::Fine`]) or the first's ([`Edges::Coarse`]), plus the regulariser,
/// in the lighting `look`; `kept` is the lighting the passes last kept a move in.
struct FinishJudge<'a, 'f> {
    fitter: &'a Fitter<'f>,
    backend: &'a mut dyn Backend,
    look: &'a mut Look,
    kept: Look,
    fine: Compare,
    coarse: Compare,
}

impl Judge for FinishJudge<'_, '_> {
    fn loss(&mut self, x: &[f64], edges: Edges) -> f64 {
        let at = match edges {
            Edges::Fine => &self.fine,
            Edges::Coarse => &self.coarse,
        };
        let image = self.fitter.loss_at(self.backend, x, self.look, at, false);
        image.total() + self.fitter.reg(x).0
    }

    fn light_at(&mut self, x: Option<&[f64]>) {
        match x {
            Some(x) => self.fitter.refit_shades(self.backend, x, self.look),
            None => *self.look = self.kept.clone(),
        }
    }

    fn keep_light(&mut self) {
        self.kept = self.look.clone();
    }
}

/// Step scale per slot: the model's size, or (relative steps) the slot's own magnitude
/// with a floor, so thin parts move in proportion.
fn step_scales(problem: &Parametric, opts: &FitOptions) -> Vec<f64> {
    problem
        .x0
        .iter()
        .map(|&v| {
            if opts.relative_steps {
                v.abs().max(RELATIVE_FLOOR * problem.scale)
            } else {
                problem.scale
            }
        })
        .collect()
}
