//! `reparamc fit`: fit a model's numbers to pictures of what it should become.

use super::render::{BackendArgs, choose_backend, input_error};
use super::{EXIT_IO_ERROR, EXIT_MODEL_ERROR, report};
use reparamc::fit::loss::{LossSpec, Target};
use reparamc::fit::optimize::Optimizer;
use reparamc::fit::targets::load_target_dir;
use reparamc::fit::{FitError, FitOptions, Parametric, Stage, constraint_basis, fit, staged};
use reparamc::front::source::SourceMap;
use reparamc::output::{same_file, write_atomic};
use reparamc::render::image::{Rgb, grid, picture};
use reparamc::render::scene::DEFAULT_SHADE;
use reparamc::render::soft::prepare_view;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(clap::Args)]
pub struct Args {
    /// The OpenSCAD model whose numbers to fit.
    model: PathBuf,
    /// A folder with the target pictures (PNG) and a `cameras.json` saying where each was
    /// taken from (`reparamc render model.scad -o DIR` writes one).
    #[arg(long)]
    target: PathBuf,
    /// Where to write the fitted model (the same program with new numbers).
    #[arg(short, long)]
    output: PathBuf,
    /// Fit inside the base model's constraint subspace: every relation that holds on the
    /// model keeps holding.
    #[arg(long)]
    subspace: bool,
    /// Write the loss curve and the slot values (JSON).
    #[arg(long)]
    report: Option<PathBuf>,
    /// Write before / target / after pictures side by side (PNG).
    #[arg(long)]
    gallery: Option<PathBuf>,
    /// Learning rate (slots in units of the model's size).
    #[arg(long, default_value_t = 0.05)]
    lr: f64,
    /// Optimiser steps per round.
    #[arg(long, default_value_t = 30)]
    iterations: usize,
    /// Rounds (the shading is matched and the edges sharpened between rounds).
    #[arg(long, default_value_t = 10)]
    rounds: usize,
    /// Rounds spent first in the structural subspace (parts move with what they touch);
    /// default: half of the rounds. Ignored with --subspace.
    #[arg(long)]
    warm: Option<usize>,
    /// Weight of the pull towards the model's own numbers.
    #[arg(long, default_value_t = 0.001)]
    lambda: f64,
    /// The optimiser (the paper's: SGD; Adam moves far targets faster).
    #[arg(long, value_enum, default_value_t = OptimizerArg::Sgd)]
    optimizer: OptimizerArg,
    /// With Adam, run each stage once: without it, each stage also runs with Adam damped
    /// for numbers whose gradient is faint (it keeps a hollow inside its box) and the run
    /// with the lower loss goes on, at twice the time.
    #[arg(long)]
    single_run: bool,
    /// Momentum of SGD.
    #[arg(long, default_value_t = 0.0)]
    momentum: f64,
    /// Edge softness in pixels, first and last round: `START,END`.
    #[arg(long, default_value = "2,0.25")]
    sigma: String,
    /// The `0.2` of `sharpen(I) = I − 0.2·blur(I)`.
    #[arg(long, default_value_t = 0.2)]
    sharpen: f64,
    /// Standard deviation of that blur, pixels.
    #[arg(long, default_value_t = 1.0)]
    blur: f64,
    /// Weight of shading against the foreground mask (boards, drawer fronts and creases
    /// inside the outline show only by shading).
    #[arg(long, default_value_t = 1.0)]
    shading: f64,
    /// Coarse-to-fine levels: the first half of the rounds compares images pooled 2× per
    /// level, one level finer at a time, so parts far from their place still feel it.
    #[arg(long, default_value_t = 0)]
    levels: u32,
    /// Step each number in proportion to its own size (thin parts move in proportion)
    /// instead of in units of the model's size.
    #[arg(long)]
    relative_steps: bool,
    /// After the rounds, sweeps of single-face moves kept when the loss drops (reaches
    /// faces hidden behind other parts).
    #[arg(long, default_value_t = 0)]
    polish: usize,
    /// After the face moves, sweeps of single-number and single-face moves of a pixel or
    /// less, judged with hard edges (brings edges onto the pictures' own pixels).
    #[arg(long, default_value_t = 0)]
    refine: usize,
    /// The pictures show the whole object: surround each with a border of background this
    /// fraction of its height wide, so parts that reach out of the pictures are drawn back.
    #[arg(long, default_value_t = 0.0, value_parser = fraction)]
    border: f64,
    /// In each stage's last round, lower the learning rate linearly by this fraction so
    /// the stage ends at rest (0: the paper's constant rate; the quality table uses 0.9).
    #[arg(long, default_value_t = 0.0, value_parser = fraction)]
    settle: f64,
    /// Skip the opening search over the model's stretch along each axis (it brings a
    /// model that is far from the pictures' proportions within reach of the gradients).
    #[arg(long)]
    no_proportions: bool,
    /// Fit one grey per surface for shading instead of a brightness per part (parts of
    /// other colours in the pictures then read as shading).
    #[arg(long)]
    one_colour: bool,
    /// Shrink target pictures so their longer side is at most this many pixels.
    #[arg(long)]
    max_size: Option<u32>,
    #[command(flatten)]
    backend: BackendArgs,
}

#[derive(Clone, Copy, clap::ValueEnum)]
enum OptimizerArg {
    Sgd,
    Adam,
}

#[derive(serde::Serialize)]
struct SlotReport {
    name: String,
    before: f64,
    after: f64,
}

#[derive(serde::Serialize)]
struct Report<'a> {
    model: String,
    target: String,
    renderer: String,
    views: Vec<String>,
    start_loss: &'a [f64],
    end_loss: &'a [f64],
    slots: Vec<SlotReport>,
    curve: &'a [reparamc::fit::Step],
}

/// A number from 0 to 1 (clap reports the error with the flag's name).
fn fraction(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(v) if (0.0..=1.0).contains(&v) => Ok(v),
        _ => Err(format!("`{text}` is not a number from 0 to 1")),
    }
}

fn parse_pair(text: &str) -> Option<(f64, f64)> {
    let (a, b) = text.split_once(',')?;
    let a: f64 = a.trim().parse().ok()?;
    let b: f64 = b.trim().parse().ok()?;
    (a > 0.0 && b > 0.0 && a.is_finite() && b.is_finite()).then_some((a, b))
}

pub fn run(args: Args) -> ExitCode {
    if same_file(&args.output, &args.model) {
        eprintln!(
            "error: the output `{}` is the input model; choose another file with -o",
            args.output.display()
        );
        return ExitCode::from(2);
    }
    let Some(sigma) = parse_pair(&args.sigma) else {
        return input_error(
            "E0703",
            format!(
                "`--sigma {}` must be two positive numbers START,END",
                args.sigma
            ),
        );
    };
    let bad_number = [
        args.lr,
        args.lambda,
        args.blur,
        args.shading,
        args.sharpen,
        args.momentum,
    ]
    .iter()
    .any(|v| !v.is_finite() || *v < 0.0);
    if bad_number || args.lr == 0.0 {
        return input_error(
            "E0703",
            "--lr must be positive; --lambda, --blur, --shading, --sharpen and --momentum must not be negative".into(),
        );
    }
    // The model.
    let mut sources = SourceMap::new();
    let loaded = match reparamc::load_model_parsed(&mut sources, &args.model) {
        Ok(l) => l,
        Err(d) => {
            report(&sources, &[*d]);
            return ExitCode::from(EXIT_MODEL_ERROR);
        }
    };
    let (parsed, evaluated) = loaded;
    report(&sources, &evaluated.warnings);
    let model = &evaluated.model;
    if model.parts.is_empty() {
        return input_error(
            "E0704",
            format!("{}: the model has no parts to fit", args.model.display()),
        );
    }
    // The targets.
    let mut set = match load_target_dir(&args.target) {
        Ok(s) => s,
        Err(e) => return input_error("E0701", e.to_string()),
    };
    if let Some(m) = args.max_size {
        if m < 8 {
            return input_error("E0703", "`--max-size` must be at least 8".into());
        }
        set = set.downsized(m);
    }
    let targets: Vec<Target> = set.images.iter().map(Target::from_rgb).collect();
    for (t, f) in targets.iter().zip(&set.files) {
        if t.foreground() == 0 {
            eprintln!(
                "warning: {}: no foreground found (the picture is all background colour)",
                f.display()
            );
        }
    }
    let mut backend = choose_backend(args.backend);
    let opts = FitOptions {
        lr: args.lr,
        iterations: args.iterations.max(1),
        rounds: args.rounds.max(1),
        lambda: args.lambda,
        optimizer: match args.optimizer {
            OptimizerArg::Sgd => Optimizer::Sgd {
                momentum: args.momentum,
            },
            OptimizerArg::Adam => Optimizer::adam(),
        },
        sigma,
        loss: LossSpec {
            sharpen: args.sharpen,
            blur: args.blur,
            shading: args.shading,
            ..LossSpec::default()
        },
        levels: args.levels,
        relative_steps: args.relative_steps,
        polish: args.polish,
        settle: args.settle,
        refine: args.refine,
        border: args.border,
        proportions: !args.no_proportions,
        per_item_albedo: !args.one_colour,
        damped_rerun: (!args.single_run).then_some(reparamc::fit::DAMPED_FLOOR),
        ..FitOptions::default()
    };
    let stages: Vec<Stage> = if args.subspace {
        vec![Stage {
            basis: Some(constraint_basis(model)),
            rounds: opts.rounds,
        }]
    } else {
        staged(model, opts.rounds, args.warm.unwrap_or(opts.rounds / 2))
    };
    let problem = Parametric::new(model);
    let bar = indicatif::ProgressBar::new((opts.rounds * opts.iterations) as u64);
    bar.set_style(
        indicatif::ProgressStyle::with_template(
            "{spinner} [{elapsed_precise}] {bar:30} {pos}/{len} round {prefix} loss {msg}",
        )
        .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    let result = fit(
        &problem,
        &set.cameras,
        &targets,
        &stages,
        backend.as_mut(),
        &opts,
        &mut |p| {
            bar.set_length(p.total_steps as u64);
            bar.set_prefix(format!("{}", p.step.round + 1));
            bar.set_message(format!("{:.5}", p.step.loss));
            bar.set_position(p.done as u64);
        },
    );
    bar.finish_and_clear();
    let result = match result {
        Ok(r) => r,
        Err(FitError::NothingInView) => {
            return input_error(
                "E0702",
                format!(
                    "{}: no part of the model is in view of any camera in {}",
                    args.model.display(),
                    args.target.join("cameras.json").display()
                ),
            );
        }
        Err(e) => return input_error("E0701", format!("{}: {e}", args.target.display())),
    };
    // Everything is computed; now write, each file whole or not at all.
    let text = sources.text(parsed.main).to_string();
    let fitted =
        reparamc::back::rewrite::with_slot_values(&text, parsed.main, &model.slots, &result.x);
    let elsewhere = model
        .slots
        .iter()
        .filter(|s| s.span.file != parsed.main && result.x[s.id as usize] != s.value)
        .count();
    if elsewhere > 0 {
        eprintln!("warning: {elsewhere} fitted numbers are in included files and were not written");
    }
    let mut outputs: Vec<(PathBuf, Vec<u8>)> = vec![(args.output.clone(), fitted.into_bytes())];
    if let Some(path) = &args.report {
        let rep = Report {
            model: args.model.display().to_string(),
            target: args.target.display().to_string(),
            renderer: backend.name(),
            views: set.cameras.iter().map(|c| c.name.clone()).collect(),
            start_loss: &result.start_loss,
            end_loss: &result.end_loss,
            slots: model
                .slots
                .iter()
                .map(|s| SlotReport {
                    name: s.name.clone(),
                    before: s.value,
                    after: result.x[s.id as usize],
                })
                .collect(),
            curve: &result.curve,
        };
        match serde_json::to_string_pretty(&rep) {
            Ok(j) => outputs.push((path.clone(), (j + "\n").into_bytes())),
            Err(e) => {
                eprintln!("error: cannot write the report: {e}");
                return ExitCode::from(EXIT_IO_ERROR);
            }
        }
    }
    if let Some(path) = &args.gallery {
        let mut cells: Vec<Rgb> = Vec::new();
        for (cam, img) in set.cameras.iter().zip(&set.images) {
            for x in [&result.x0, &result.x] {
                // With the fitted albedos, parts show the targets' light and dark.
                let scene = problem.scene(x).with_albedo(&result.albedo);
                let v = prepare_view(&scene, cam, Some(super::render::EDGE_SOFTNESS));
                let r = backend.render(
                    &scene,
                    std::slice::from_ref(&v),
                    Some(super::render::EDGE_SOFTNESS),
                    &[DEFAULT_SHADE],
                );
                cells.push(picture(&r[0].0));
            }
            cells.insert(cells.len() - 1, img.clone());
        }
        outputs.push((path.clone(), grid(&cells, 3).encode_png()));
    }
    for (path, bytes) in &outputs {
        if let Err(e) = write_atomic(path, bytes) {
            eprintln!("error: cannot write `{}`: {e}", path.display());
            return ExitCode::from(EXIT_IO_ERROR);
        }
    }
    let start: f64 = result.start_loss.iter().sum();
    let end: f64 = result.end_loss.iter().sum();
    let moved = model
        .slots
        .iter()
        .filter(|s| (result.x[s.id as usize] - s.value).abs() > 1e-9 * problem.scale)
        .count();
    eprintln!(
        "fitted {} of {} numbers to {} views: image loss {start:.5} -> {end:.5}; wrote {}",
        moved,
        model.slots.len(),
        set.cameras.len(),
        args.output.display()
    );
    ExitCode::SUCCESS
}
