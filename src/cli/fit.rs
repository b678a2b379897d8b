//! `reparamc fit`: fit a model's numbers to pictures of what it should become.
//!
//! Flags in, [`reparamc::command::fit`] called (a progress bar while it runs), the fitted
//! model, the report and the gallery written (each file whole or not at all), diagnostics
//! out.

use super::EXIT_IO_ERROR;
use super::render::{BackendArgs, failed, input_error, say};
use reparamc::command::fit::{
    Fitted, OptimizerChoice, Options, Progress, Settings, SoftEdges, prepare, sidecar_path,
};
use reparamc::front::source::SourceMap;
use reparamc::output::write_atomic;
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
    /// The schedule the other settings start from: `far`, the recipe that also reaches
    /// pictures far from the model (Adam at 0.01, settling, face moves and refining moves,
    /// a border of 1/8, soft rounds on blurred area coverage), or `paper` (the paper's: SGD
    /// at 0.05, sigmoid edges). Flags below override it.
    #[arg(long, value_enum, default_value_t = ScheduleArg::Far)]
    schedule: ScheduleArg,
    /// Compare sigmoid edges to the end instead of finishing on area coverage (the last
    /// round, the refining moves and the choice of the result).
    #[arg(long)]
    no_coverage: bool,
    /// Learning rate (slots in units of the model's size) [paper: 0.05, far: 0.01].
    #[arg(long)]
    lr: Option<f64>,
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
    /// Weight of the size prior: each part's size is pulled towards the model's by the
    /// square of its log ratio, so a part the pictures barely show keeps its proportions
    /// [paper: 0, far: 3e-5].
    #[arg(long)]
    size_prior: Option<f64>,
    /// Weight of the tie prior: the model's contacts and repeats hold unless the pictures
    /// pull them apart (a pull of one pixel is resisted most, a clear break costs a
    /// constant), so numbers the pictures barely show keep their relations [paper: 0,
    /// far: 1e-5].
    #[arg(long)]
    tie_prior: Option<f64>,
    /// The optimiser (the paper's: SGD; Adam moves far targets faster) [paper: sgd,
    /// far: adam].
    #[arg(long, value_enum)]
    optimizer: Option<OptimizerArg>,
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
    /// How the rounds soften edges: `sigmoid` silhouettes (the paper's; a part a few pixels
    /// thin is least thicker than it is), or `blurred`: exact area coverage with the render
    /// and the pictures blurred alike (least at the truth for parts of any width)
    /// [paper: sigmoid, far: blurred].
    #[arg(long, value_enum)]
    soft_edges: Option<SoftEdgesArg>,
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
    /// After the rounds, sweeps of single-face moves and of moves of the faces that share a
    /// plane in the model (a board thinned with the boards it holds), kept when the loss
    /// drops (reaches faces hidden behind other parts) [paper: 0, far: 2].
    #[arg(long)]
    polish: Option<usize>,
    /// After the face moves, sweeps of single-number and single-face moves of a pixel or
    /// less, judged on area coverage (hard edges with the paper's schedule) [paper: 0,
    /// far: 2].
    #[arg(long)]
    refine: Option<usize>,
    /// The pictures show the whole object: surround each with a border of background this
    /// fraction of its height wide, so parts that reach out of the pictures are drawn back
    /// [paper: 0, far: 0.125].
    #[arg(long, value_parser = fraction)]
    border: Option<f64>,
    /// In each stage's last round, lower the learning rate linearly by this fraction so
    /// the stage ends at rest (0: the paper's constant rate) [paper: 0, far: 0.9].
    #[arg(long, value_parser = fraction)]
    settle: Option<f64>,
    /// Bound each optimiser step: a stage's first step moves no face further than this
    /// many edge softnesses, and the bound grows while the loss falls and halves when a
    /// step raised it (0: no bound).
    #[arg(long)]
    reach: Option<f64>,
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
enum ScheduleArg {
    Paper,
    Far,
}

#[derive(Clone, Copy, clap::ValueEnum)]
enum SoftEdgesArg {
    Sigmoid,
    Blurred,
}

impl From<SoftEdgesArg> for SoftEdges {
    fn from(e: SoftEdgesArg) -> SoftEdges {
        match e {
            SoftEdgesArg::Sigmoid => SoftEdges::Sigmoid,
            SoftEdgesArg::Blurred => SoftEdges::Blurred,
        }
    }
}

#[derive(Clone, Copy, clap::ValueEnum)]
enum OptimizerArg {
    Sgd,
    Adam,
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

impl From<OptimizerArg> for OptimizerChoice {
    fn from(o: OptimizerArg) -> OptimizerChoice {
        match o {
            OptimizerArg::Sgd => OptimizerChoice::Sgd,
            OptimizerArg::Adam => OptimizerChoice::Adam,
        }
    }
}

/// The command's options from the flags, with `sigma` parsed.
fn options(args: &Args, sigma: (f64, f64)) -> Options {
    Options {
        model: args.model.clone(),
        target: args.target.clone(),
        subspace: args.subspace,
        max_size: args.max_size,
        gallery: args.gallery.is_some(),
        backend: args.backend.into(),
        settings: settings(args, sigma),
    }
}

/// The schedule's settings with every flag given put in.
fn settings(args: &Args, sigma: (f64, f64)) -> Settings {
    let base = match args.schedule {
        ScheduleArg::Paper => Settings::paper(),
        ScheduleArg::Far => Settings::far(),
    };
    Settings {
        lr: args.lr.unwrap_or(base.lr),
        iterations: args.iterations,
        rounds: args.rounds,
        warm: args.warm,
        lambda: args.lambda,
        size_prior: args.size_prior.unwrap_or(base.size_prior),
        tie_prior: args.tie_prior.unwrap_or(base.tie_prior),
        optimizer: args.optimizer.map_or(base.optimizer, Into::into),
        momentum: args.momentum,
        single_run: args.single_run,
        sigma,
        soft_edges: args.soft_edges.map_or(base.soft_edges, Into::into),
        sharpen: args.sharpen,
        blur: args.blur,
        shading: args.shading,
        levels: args.levels,
        relative_steps: args.relative_steps,
        polish: args.polish.unwrap_or(base.polish),
        refine: args.refine.unwrap_or(base.refine),
        border: args.border.unwrap_or(base.border),
        settle: args.settle.unwrap_or(base.settle),
        reach: args.reach.unwrap_or(base.reach),
        proportions: !args.no_proportions,
        per_item_albedo: !args.one_colour,
        coverage: base.coverage && !args.no_coverage,
    }
}

pub fn run(args: Args) -> ExitCode {
    let sidecar = sidecar_path(&args.output);
    if let Some(clash) = args
        .report
        .iter()
        .chain(&args.gallery)
        .find(|p| **p == sidecar)
    {
        eprintln!(
            "error: `{}` is where the fitted model's uncertainty goes (beside `{}`); \
             write the report or the gallery elsewhere",
            clash.display(),
            args.output.display()
        );
        return ExitCode::from(EXIT_IO_ERROR);
    }
    let mut outputs = vec![args.output.as_path(), sidecar.as_path()];
    outputs.extend(
        args.report
            .iter()
            .chain(&args.gallery)
            .map(PathBuf::as_path),
    );
    if let Err(code) = super::check_outputs(&outputs, std::slice::from_ref(&args.model)) {
        return code;
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
    let mut sources = SourceMap::new();
    let mut job = match prepare(&options(&args, sigma), &mut sources) {
        Ok(j) => j,
        Err(f) => return failed(&sources, &f),
    };
    say(&sources, &std::mem::take(&mut job.messages));
    // The target pictures and the model's includes are inputs too.
    let mut inputs = super::inputs_of(&sources);
    inputs.extend(target_files(&args.target));
    if let Err(code) = super::check_outputs(&outputs, &inputs) {
        return code;
    }
    let bar = indicatif::ProgressBar::new(job.planned_steps() as u64);
    bar.set_style(
        indicatif::ProgressStyle::with_template(
            "{spinner} [{elapsed_precise}] {bar:30} {pos}/{len} round {prefix} loss {msg}",
        )
        .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    let result = job.run(&mut |p: &Progress| {
        bar.set_length(p.total_steps as u64);
        bar.set_prefix(format!("{}", p.step.round + 1));
        bar.set_message(format!("{:.5}", p.step.loss));
        bar.set_position(p.done as u64);
    });
    bar.finish_and_clear();
    let fitted = match result {
        Ok(f) => f,
        Err(f) => return failed(&sources, &f),
    };
    say(&sources, &fitted.messages);
    write_results(&args, fitted)
}

/// The files of a target folder (pictures and `cameras.json`).
fn target_files(dir: &std::path::Path) -> Vec<PathBuf> {
    std::fs::read_dir(dir)
        .map(|d| d.filter_map(|e| e.ok().map(|e| e.path())).collect())
        .unwrap_or_default()
}

/// Writes the fitted model, its uncertainty sidecar, the report and the gallery (each file
/// whole or not at all)
/// and says what was fitted.
fn write_results(args: &Args, fitted: Fitted) -> ExitCode {
    let sidecar = sidecar_path(&args.output);
    let unseen = fitted
        .report
        .slots
        .iter()
        .filter(|s| s.std.is_none())
        .count();
    let summary = format!(
        "fitted {} of {} numbers to {} views: image loss {:.5} -> {:.5}; wrote {} and its \
         uncertainty {} ({unseen} numbers the pictures do not determine)",
        fitted.moved,
        fitted.numbers(),
        fitted.report.views.len(),
        fitted.start_loss(),
        fitted.end_loss(),
        args.output.display(),
        sidecar.display()
    );
    let mut outputs: Vec<(PathBuf, Vec<u8>)> = vec![
        (args.output.clone(), fitted.scad.into_bytes()),
        (sidecar, fitted.uncertainty.to_json().into_bytes()),
    ];
    if let Some(path) = &args.report {
        match serde_json::to_string_pretty(&fitted.report) {
            Ok(j) => outputs.push((path.clone(), (j + "\n").into_bytes())),
            Err(e) => {
                eprintln!("error: cannot write the report: {e}");
                return ExitCode::from(EXIT_IO_ERROR);
            }
        }
    }
    if let (Some(path), Some(png)) = (&args.gallery, fitted.gallery) {
        outputs.push((path.clone(), png));
    }
    for (path, bytes) in &outputs {
        if let Err(e) = write_atomic(path, bytes) {
            eprintln!("error: cannot write `{}`: {e}", path.display());
            return ExitCode::from(EXIT_IO_ERROR);
        }
    }
    eprintln!("{summary}");
    ExitCode::SUCCESS
}
