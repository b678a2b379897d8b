//! The `fit` command's entry point: fit a model's numbers to pictures of what it should
//! become.
//!
//! In two steps, so that a caller can tell the user what was found before the long part
//! starts: [`prepare`] checks the settings, loads the model and the target folder and picks
//! a renderer (a [`Job`], with what the user should read so far); [`Job::run`] fits,
//! reporting each optimiser step to a callback, and returns the fitted model's text, the
//! report as data and, when asked, the gallery (before / target / after for every view) as
//! PNG bytes.
//!
//! Invariant: nothing here prints or writes a file; every line the user is to read is a
//! [`Message`], in the order it arose.

use super::render::{BackendChoice, choose_backend, draw};
use super::{Failure, Message, as_messages};
pub use crate::fit::SoftEdges;
use crate::fit::loss::{LossSpec, Target};
use crate::fit::optimize::Optimizer;
use crate::fit::targets::{TargetSet, load_target_dir};
use crate::fit::{
    DAMPED_FLOOR, FitError, FitOptions, FitResult, Parametric, SIZE_PRIOR, Stage, TIE_PRIOR,
    constraint_basis, fit_measured, staged,
};
use crate::front::source::SourceMap;
use crate::ir::Model;
use crate::render::Backend;
use crate::render::image::{Rgb, grid, picture};
use crate::span::FileId;
use crate::tolerance::RELATIVE_ROUNDOFF;
use crate::variation::Uncertainty;
/// Where a fitted model's uncertainty goes: `fitted.scad` → `fitted.json`.
pub use crate::variation::uncertainty::sidecar_path;
use std::path::PathBuf;

pub use crate::fit::{Progress, Step};

/// The update rule.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OptimizerChoice {
    /// The paper's: gradient descent (with [`Settings::momentum`]).
    Sgd,
    /// Adam: moves far targets faster.
    Adam,
}

/// How the fit runs; [`Settings::default`] is the command line's defaults.
#[derive(Debug, Clone, PartialEq)]
pub struct Settings {
    /// Learning rate (slots in units of the model's size); positive.
    pub lr: f64,
    /// Optimiser steps per round (0 counts as 1).
    pub iterations: usize,
    /// Rounds (0 counts as 1); the shading is matched and the edges sharpened between them.
    pub rounds: usize,
    /// Rounds spent first in the structural subspace; `None`: half of the rounds. Ignored
    /// with [`Options::subspace`].
    pub warm: Option<usize>,
    /// Weight of the pull towards the model's own numbers; not negative.
    pub lambda: f64,
    /// Weight of the size prior ([`FitOptions::size_prior`]); not negative.
    pub size_prior: f64,
    /// Weight of the tie prior ([`FitOptions::tie_prior`]); not negative.
    pub tie_prior: f64,
    pub optimizer: OptimizerChoice,
    /// Momentum of SGD; not negative.
    pub momentum: f64,
    /// With Adam, run each stage once (no damped rerun).
    pub single_run: bool,
    /// Edge softness in pixels, first and last round.
    pub sigma: (f64, f64),
    /// How rounds soften edges: sigmoid silhouettes or blurred area coverage.
    pub soft_edges: SoftEdges,
    /// The `0.2` of `sharpen(I) = I − 0.2·blur(I)`; not negative.
    pub sharpen: f64,
    /// Standard deviation of that blur, pixels; not negative.
    pub blur: f64,
    /// Weight of shading against the foreground mask; not negative.
    pub shading: f64,
    /// Coarse-to-fine levels.
    pub levels: u32,
    /// Step each number in proportion to its own size.
    pub relative_steps: bool,
    /// Sweeps of single-face and shared-plane moves after the rounds.
    pub polish: usize,
    /// Sweeps of moves of a pixel or less on hard edges after the face moves.
    pub refine: usize,
    /// Border of background around each picture, a fraction of its height.
    pub border: f64,
    /// How far the learning rate falls in each stage's last round (a fraction).
    pub settle: f64,
    /// Largest move of a face in one step, in edge softnesses (0: no bound).
    pub reach: f64,
    /// Open with the search over the model's stretch along each axis.
    pub proportions: bool,
    /// Fit a brightness per part (`false`: one grey per surface).
    pub per_item_albedo: bool,
    /// Finish on area coverage (the last round, the refine pass and the judge of the
    /// best point).
    pub coverage: bool,
}

/// The default is the recipe that also reaches pictures far from the model
/// ([`Settings::far`]); [`Settings::paper`] is the paper's schedule.
impl Default for Settings {
    fn default() -> Self {
        Settings::far()
    }
}

impl Settings {
    /// The default: the recipe for pictures far from the model (and near ones; started at
    /// the truth it stays there): Adam at 0.01, settling, two sweeps of face moves and of
    /// refining moves, a border of an eighth of the picture, soft rounds on blurred area
    /// coverage (least at the truth for parts of any width), the size and tie priors.
    pub fn far() -> Settings {
        Settings {
            lr: 0.01,
            optimizer: OptimizerChoice::Adam,
            settle: 0.9,
            polish: 2,
            refine: 2,
            border: 0.125,
            soft_edges: SoftEdges::Blurred,
            size_prior: SIZE_PRIOR,
            tie_prior: TIE_PRIOR,
            ..Settings::paper()
        }
    }

    /// The paper's schedule (SGD at 0.05, ten rounds of 30 steps), opened by the
    /// proportions search, with an albedo per item, finished on area coverage.
    pub fn paper() -> Settings {
        let fit = FitOptions::default();
        let loss = LossSpec::default();
        Settings {
            lr: fit.lr,
            iterations: fit.iterations,
            rounds: fit.rounds,
            warm: None,
            lambda: fit.lambda,
            size_prior: fit.size_prior,
            tie_prior: fit.tie_prior,
            optimizer: OptimizerChoice::Sgd,
            momentum: 0.0,
            single_run: false,
            sigma: fit.sigma,
            soft_edges: fit.soft_edges,
            sharpen: loss.sharpen,
            blur: loss.blur,
            shading: loss.shading,
            levels: fit.levels,
            relative_steps: fit.relative_steps,
            polish: fit.polish,
            refine: fit.refine,
            border: fit.border,
            settle: fit.settle,
            reach: fit.reach,
            proportions: fit.proportions,
            per_item_albedo: fit.per_item_albedo,
            coverage: fit.coverage,
        }
    }

    /// The fit's options for these settings.
    pub fn fit_options(&self) -> FitOptions {
        FitOptions {
            lr: self.lr,
            iterations: self.iterations.max(1),
            rounds: self.rounds.max(1),
            lambda: self.lambda,
            size_prior: self.size_prior,
            tie_prior: self.tie_prior,
            optimizer: match self.optimizer {
                OptimizerChoice::Sgd => Optimizer::Sgd {
                    momentum: self.momentum,
                },
                OptimizerChoice::Adam => Optimizer::adam(),
            },
            sigma: self.sigma,
            soft_edges: self.soft_edges,
            loss: LossSpec {
                sharpen: self.sharpen,
                blur: self.blur,
                shading: self.shading,
                ..LossSpec::default()
            },
            levels: self.levels,
            relative_steps: self.relative_steps,
            polish: self.polish,
            settle: self.settle,
            reach: self.reach,
            refine: self.refine,
            border: self.border,
            proportions: self.proportions,
            per_item_albedo: self.per_item_albedo,
            coverage: self.coverage,
            damped_rerun: (!self.single_run).then_some(DAMPED_FLOOR),
            ..FitOptions::default()
        }
    }

    /// Whether the numbers are in range (the message names the flags).
    fn check(&self) -> Result<(), String> {
        let numbers = [
            self.lr,
            self.lambda,
            self.size_prior,
            self.tie_prior,
            self.blur,
            self.shading,
            self.sharpen,
            self.momentum,
            self.reach,
        ];
        let bad = numbers.iter().any(|v| !v.is_finite() || *v < 0.0);
        if bad || self.lr == 0.0 {
            return Err("--lr must be positive; --lambda, --size-prior, --tie-prior, --blur, --shading, --sharpen, --momentum and --reach must not be negative".into());
        }
        Ok(())
    }
}

/// The `fit` command's options.
#[derive(Debug, Clone, PartialEq)]
pub struct Options {
    /// The OpenSCAD model whose numbers to fit.
    pub model: PathBuf,
    /// The folder of target pictures with their `cameras.json`.
    pub target: PathBuf,
    /// Fit inside the model's constraint subspace.
    pub subspace: bool,
    /// Shrink target pictures so their longer side is at most this (at least 8).
    pub max_size: Option<u32>,
    /// Draw the gallery.
    pub gallery: bool,
    pub backend: BackendChoice,
    pub settings: Settings,
}

/// A fit ready to run: the model, the pictures, the renderer.
pub struct Job {
    /// What preparing had to say (the model's warnings, pictures without foreground, the
    /// renderer), for the user before the fit runs.
    pub messages: Vec<Message>,
    model_path: PathBuf,
    target_path: PathBuf,
    /// The main file's text and id, to write the fitted numbers into.
    text: String,
    main: FileId,
    model: Model,
    set: TargetSet,
    targets: Vec<Target>,
    backend: Box<dyn Backend>,
    opts: FitOptions,
    subspace: bool,
    warm: Option<usize>,
    gallery: bool,
}

/// One number of the model, before and after.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct SlotReport {
    pub name: String,
    pub before: f64,
    pub after: f64,
    /// How well the pictures determine it: one standard deviation (`None`: not at all).
    pub std: Option<f64>,
}

/// The fit's report (`--report`): the inputs, the loss per view at the start and the end,
/// every number before and after, and the loss curve.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Report {
    pub model: String,
    pub target: String,
    pub renderer: String,
    pub views: Vec<String>,
    pub start_loss: Vec<f64>,
    pub end_loss: Vec<f64>,
    pub slots: Vec<SlotReport>,
    pub curve: Vec<Step>,
}

/// What a fit produced.
#[derive(Debug, Clone)]
pub struct Fitted {
    /// The main file with the fitted numbers written in.
    pub scad: String,
    /// How well the pictures determine each number (the sidecar beside `scad`).
    pub uncertainty: Uncertainty,
    /// What the user should read about the result.
    pub messages: Vec<Message>,
    pub report: Report,
    /// Before / target / after for every view, three to a row (PNG), when asked for.
    pub gallery: Option<Vec<u8>>,
    /// Numbers that moved (by more than round-off), of all the model's numbers.
    pub moved: usize,
}

impl Fitted {
    /// How many numbers the model has (every one is in the report).
    pub fn numbers(&self) -> usize {
        self.report.slots.len()
    }

    /// The image loss summed over the views, at the start.
    pub fn start_loss(&self) -> f64 {
        self.report.start_loss.iter().sum()
    }

    /// The image loss summed over the views, at the end.
    pub fn end_loss(&self) -> f64 {
        self.report.end_loss.iter().sum()
    }
}

/// Checks the settings, loads the model (into `sources`) and the targets, and picks the
/// renderer.
pub fn prepare(opts: &Options, sources: &mut SourceMap) -> Result<Job, Failure> {
    if let Err(text) = opts.settings.check() {
        return Err(Failure::input(Vec::new(), "E0703", text));
    }
    let (parsed, evaluated) =
        crate::front::load_model_parsed(sources, &opts.model).map_err(Failure::from)?;
    let mut messages = as_messages(evaluated.warnings);
    if evaluated.model.parts.is_empty() {
        let text = format!("{}: the model has no parts to fit", opts.model.display());
        return Err(Failure::input(messages, "E0704", text));
    }
    let (set, targets) = match load_targets(opts, &mut messages) {
        Ok(t) => t,
        Err((code, text)) => return Err(Failure::input(messages, code, text)),
    };
    let backend = choose_backend(opts.backend, &mut messages);
    Ok(Job {
        messages,
        model_path: opts.model.clone(),
        target_path: opts.target.clone(),
        text: sources.text(parsed.main).to_string(),
        main: parsed.main,
        model: evaluated.model,
        set,
        targets,
        backend,
        opts: opts.settings.fit_options(),
        subspace: opts.subspace,
        warm: opts.settings.warm,
        gallery: opts.gallery,
    })
}

/// The target folder, shrunk as asked, and its pictures as targets; a warning for each
/// picture without foreground. On failure, the diagnostic's code and text.
fn load_targets(
    opts: &Options,
    messages: &mut Vec<Message>,
) -> Result<(TargetSet, Vec<Target>), (&'static str, String)> {
    let mut set = load_target_dir(&opts.target).map_err(|e| ("E0701", e.to_string()))?;
    if let Some(m) = opts.max_size {
        if m < 8 {
            return Err(("E0703", "`--max-size` must be at least 8".into()));
        }
        set = set.downsized(m);
    }
    let targets = Target::set_from_rgb(&set.images);
    for (t, f) in targets.iter().zip(&set.files) {
        if t.foreground() == 0 {
            messages.push(Message::Line(format!(
                "warning: {}: no foreground found (the picture is all background colour)",
                f.display()
            )));
        }
    }
    Ok((set, targets))
}

impl Job {
    /// Optimiser steps of one run of every stage (reruns may add as many again, and a
    /// branch where a stage lost a part the rest of the schedule again; each [`Progress`]
    /// says the true total).
    pub fn planned_steps(&self) -> usize {
        self.opts.rounds * self.opts.iterations
    }

    /// Fits, calling `progress` after every optimiser step.
    pub fn run(mut self, progress: &mut dyn FnMut(&Progress)) -> Result<Fitted, Failure> {
        let model = &self.model;
        let stages: Vec<Stage> = if self.subspace {
            vec![Stage {
                basis: Some(constraint_basis(model)),
                rounds: self.opts.rounds,
            }]
        } else {
            let warm = self.warm.unwrap_or(self.opts.rounds / 2);
            staged(model, self.opts.rounds, warm)
        };
        let problem = Parametric::new(model);
        let run = fit_measured(
            &problem,
            &self.set.cameras,
            &self.targets,
            &stages,
            self.backend.as_mut(),
            &self.opts,
            progress,
        );
        let (result, information) = match run {
            Ok(r) => r,
            Err(e) => return Err(self.fit_failure(&e)),
        };
        let uncertainty = information.uncertainty(model, &result.x);
        let gallery = self.gallery.then(|| self.gallery_png(&problem, &result));
        Ok(self.fitted(&problem, result, uncertainty, gallery))
    }

    /// The diagnostic for a fit that could not start.
    fn fit_failure(&self, e: &FitError) -> Failure {
        let text = match e {
            FitError::NothingInView => {
                let text = format!(
                    "{}: no part of the model is in view of any camera in {}",
                    self.model_path.display(),
                    self.target_path.join("cameras.json").display()
                );
                return Failure::input(Vec::new(), "E0702", text);
            }
            e => format!("{}: {e}", self.target_path.display()),
        };
        Failure::input(Vec::new(), "E0701", text)
    }

    /// Before, target and after for every view (with the fitted albedos, so parts show
    /// the targets' light and dark), three to a row.
    fn gallery_png(&mut self, problem: &Parametric, result: &FitResult) -> Vec<u8> {
        let mut cells: Vec<Rgb> = Vec::new();
        for (cam, img) in self.set.cameras.iter().zip(&self.set.images) {
            for x in [&result.x0, &result.x] {
                let scene = problem.scene(x).with_albedo(&result.albedo);
                let soft = draw(self.backend.as_mut(), &scene, std::slice::from_ref(cam));
                cells.extend(soft.iter().map(picture));
            }
            cells.insert(cells.len() - 1, img.clone());
        }
        grid(&cells, 3).encode_png()
    }

    /// The fitted text, the report and the summary.
    fn fitted(
        self,
        problem: &Parametric,
        result: FitResult,
        uncertainty: Uncertainty,
        gallery: Option<Vec<u8>>,
    ) -> Fitted {
        let model = &self.model;
        let scad =
            crate::back::rewrite::with_slot_values(&self.text, self.main, &model.slots, &result.x);
        let mut messages = Vec::new();
        let elsewhere = model
            .slots
            .iter()
            .filter(|s| s.span.file != self.main && result.x[s.id as usize] != s.value)
            .count();
        if elsewhere > 0 {
            messages.push(Message::Line(format!(
                "warning: {elsewhere} fitted numbers are in included files and were not written"
            )));
        }
        let moved = model
            .slots
            .iter()
            .filter(|s| {
                (result.x[s.id as usize] - s.value).abs() > RELATIVE_ROUNDOFF * problem.scale
            })
            .count();
        let report = Report {
            model: self.model_path.display().to_string(),
            target: self.target_path.display().to_string(),
            renderer: self.backend.name(),
            views: self.set.cameras.iter().map(|c| c.name.clone()).collect(),
            slots: model
                .slots
                .iter()
                .map(|s| SlotReport {
                    name: s.name.clone(),
                    before: s.value,
                    after: result.x[s.id as usize],
                    std: uncertainty.std(s.id as usize),
                })
                .collect(),
            start_loss: result.start_loss,
            end_loss: result.end_loss,
            curve: result.curve,
        };
        Fitted {
            scad,
            uncertainty,
            messages,
            gallery,
            moved,
            report,
        }
    }
}
