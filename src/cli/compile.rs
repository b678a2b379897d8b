//! The main command: `reparamc model.scad -o model_param.scad --vary a.scad …`.
//!
//! Flags in → [`CompileOptions`] → the library's `compile` → the outputs written atomically
//! (a temporary file renamed into place, never over the input), the diff printed when
//! asked, diagnostics and a one-line summary on standard error.

use super::{EXIT_IO_ERROR, check_outputs, inputs_of, or_report, print_stdout, report};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use reparamc::command::compile::{CompileOptions, CompileOutput, Options, PlotFormat, compile};
use reparamc::command::pictures::Progress;
use reparamc::front::source::SourceMap;
use reparamc::output::write_atomic;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Arc;
use std::time::Duration;

/// How long the job runs before its progress bar shows, unless [`QUIET_FOR_VAR`] says.
const QUIET_FOR: Duration = Duration::from_secs(1);

/// The environment variable that sets [`QUIET_FOR`] in seconds (0: at once; tests use it).
const QUIET_FOR_VAR: &str = "REPARAMC_PROGRESS_AFTER";

/// How long the job runs before its progress bar shows.
fn quiet_for() -> Duration {
    std::env::var(QUIET_FOR_VAR)
        .ok()
        .and_then(|s| s.trim().parse::<f64>().ok())
        .and_then(|s| Duration::try_from_secs_f64(s).ok())
        .unwrap_or(QUIET_FOR)
}

/// Whether `path` names an HTML page.
fn is_html(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("html") || e.eq_ignore_ascii_case("htm"))
}

/// What the bar shows before discovery: a spinner and the stage (cut to the terminal's width).
const STAGE_TEMPLATE: &str = "{spinner} [{elapsed}] {wide_msg}";

/// What it shows from discovery's first step on: the candidate relations decided, of all,
/// and the stage (on one line of 80 columns for the stages after discovery).
const STEP_TEMPLATE: &str =
    "{spinner} [{elapsed}] {bar:16} {pos}/{len} relations decided · {wide_msg}";

/// One bar over discovery's steps on standard error (a spinner with the stage before them),
/// shown once the job has run for [`quiet_for`] and never when standard error is not a
/// terminal.
fn progress_bar() -> (ProgressBar, Progress) {
    let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::hidden());
    if let Ok(style) = ProgressStyle::with_template(STAGE_TEMPLATE) {
        bar.set_style(style);
    }
    let quiet = quiet_for();
    if std::io::stderr().is_terminal() && quiet.is_zero() {
        // Told to show at once: drawn from the first stage on, not when a thread wakes.
        bar.set_draw_target(ProgressDrawTarget::stderr());
        bar.enable_steady_tick(Duration::from_millis(120));
    } else if std::io::stderr().is_terminal() {
        let later = bar.clone();
        std::thread::spawn(move || {
            std::thread::sleep(quiet);
            if !later.is_finished() {
                later.set_draw_target(ProgressDrawTarget::stderr());
                later.enable_steady_tick(Duration::from_millis(120));
            }
        });
    }
    let told = bar.clone();
    let stepped = bar.clone();
    let progress = Progress {
        stage: Some(Arc::new(move |_, _, what: &str| {
            told.set_message(what.to_string());
        })),
        step: Some(Arc::new(move |done: usize, total: usize| {
            if stepped.length().is_none()
                && let Ok(style) = ProgressStyle::with_template(STEP_TEMPLATE)
            {
                stepped.set_style(style);
            }
            stepped.set_length(total as u64);
            stepped.set_position(done as u64);
        })),
    };
    (bar, progress)
}

#[derive(clap::Args, Debug, Default)]
pub struct Args {
    /// The OpenSCAD model to re-parameterize.
    pub model: Option<PathBuf>,
    /// Where to write the re-parameterized model (`-` for standard output); the parameter
    /// sets go beside it as `<name>.json`. Default: `<model>_param.scad` beside the model.
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// A variation of the model: the same program with other numbers (repeatable).
    #[arg(long = "vary", value_name = "FILE")]
    pub vary: Vec<PathBuf>,
    /// Write the report here: a page to read in a browser when the name ends in `.html`,
    /// else machine-readable JSON.
    #[arg(long, value_name = "FILE")]
    pub report: Option<PathBuf>,
    /// Draw the distortion curve with the cutoff marked (SVG when the name ends in `.svg`,
    /// else PNG).
    #[arg(long, value_name = "FILE")]
    pub plot: Option<PathBuf>,
    /// Draw the model at its defaults, at each preset and at an even blend, side by side
    /// (PNG).
    #[arg(long, value_name = "FILE")]
    pub gallery: Option<PathBuf>,
    /// Without variations, keep every relation that holds (the paper's symbolic baseline)
    /// instead of the structural prior.
    #[arg(long)]
    pub all_constraints: bool,
    /// Also print what changed, as a unified diff from the model to the output.
    #[arg(long)]
    pub diff: bool,
    /// Draw this module call at the end of the model (for a file that only defines
    /// modules): `--call 'chair()'`, `--call 'chair(seat_h = 45)'`.
    #[arg(long, value_name = "CALL")]
    pub call: Option<String>,
}

fn io_error(what: &Path, e: std::io::Error) -> ExitCode {
    eprintln!("error: cannot write `{}`: {e}", what.display());
    ExitCode::from(EXIT_IO_ERROR)
}

/// Writes `bytes` to `path`, or says why it could not.
fn write(path: &Path, bytes: &[u8]) -> Result<(), ExitCode> {
    write_atomic(path, bytes).map_err(|e| io_error(path, e))
}

/// The report (the page or JSON), the plot and the gallery, where they were asked for.
fn write_reports(args: &Args, made: &CompileOutput) -> Result<(), ExitCode> {
    if let Some(r) = &args.report {
        let text = made
            .page
            .clone()
            .unwrap_or_else(|| made.compiled.report.to_json());
        write(r, text.as_bytes())?;
    }
    let gallery = made.gallery.as_ref().map(|g| g.png.as_slice());
    for (path, bytes) in [(&args.plot, made.plot.as_deref()), (&args.gallery, gallery)] {
        if let (Some(p), Some(b)) = (path, bytes) {
            write(p, b)?;
        }
    }
    Ok(())
}

/// What the flags ask the library for; `output` is where the model goes (`-` for stdout).
fn options_of(
    args: &Args,
    model_path: PathBuf,
    output: &Path,
    to_stdout: bool,
    progress: Progress,
) -> CompileOptions {
    CompileOptions {
        model: model_path,
        variations: args.vary.clone(),
        call: args.call.clone(),
        options: Options {
            all_constraints: args.all_constraints,
            presets_name: (!to_stdout)
                .then(|| {
                    output
                        .with_extension("json")
                        .file_name()
                        .map(|n| n.to_string_lossy().into_owned())
                })
                .flatten(),
            measure: args.report.is_some(),
        },
        plot: args.plot.as_deref().map(PlotFormat::of_path),
        gallery: args.gallery.is_some(),
        page: args.report.as_deref().is_some_and(is_html),
        progress,
        diff_to: args.diff.then(|| output.display().to_string()),
    }
}

pub fn run(args: Args) -> ExitCode {
    let Some(model_path) = args.model.clone() else {
        eprintln!(
            "error: no model given\n\nUsage: reparamc <MODEL> -o <OUTPUT> [--vary <FILE>]...\n       reparamc inspect <MODEL>\n\nFor more information, try '--help'."
        );
        return ExitCode::from(2);
    };
    let output = args.output.clone().unwrap_or_else(|| {
        let stem = model_path
            .file_stem()
            .map_or("model".into(), |s| s.to_string_lossy().into_owned());
        model_path.with_file_name(format!("{stem}_param.scad"))
    });
    let to_stdout = output.as_os_str() == "-";
    let presets = output.with_extension("json");
    let mut outputs: Vec<&Path> = Vec::new();
    if !to_stdout {
        outputs.extend([output.as_path(), presets.as_path()]);
    }
    outputs.extend(
        args.report
            .iter()
            .chain(&args.plot)
            .chain(&args.gallery)
            .map(PathBuf::as_path),
    );
    let mut inputs = vec![model_path.clone()];
    inputs.extend(args.vary.iter().cloned());
    if let Err(code) = check_outputs(&outputs, &inputs) {
        return code;
    }
    if to_stdout && args.diff {
        eprintln!(
            "error: --diff prints to standard output, where `-o -` writes the model; write the model to a file with -o"
        );
        return ExitCode::from(2);
    }
    let (bar, progress) = progress_bar();
    let options = options_of(&args, model_path, &output, to_stdout, progress);
    let mut sources = SourceMap::new();
    let result = compile(&options, &mut sources);
    bar.finish_and_clear();
    let made = match or_report(&sources, result) {
        Ok(made) => made,
        Err(code) => return code,
    };
    report(&sources, &made.warnings);
    // The model's includes are inputs too; they are known only now.
    if let Err(code) = check_outputs(&outputs, &inputs_of(&sources)) {
        return code;
    }
    let compiled = &made.compiled;
    if to_stdout {
        if print_stdout(&compiled.scad) != ExitCode::SUCCESS {
            return ExitCode::from(EXIT_IO_ERROR);
        }
    } else {
        if let Err(code) = write(&output, compiled.scad.as_bytes()) {
            return code;
        }
        if let Some(p) = &compiled.presets
            && let Err(code) = write(&presets, p.as_bytes())
        {
            return code;
        }
    }
    if let Err(code) = write_reports(&args, &made) {
        return code;
    }
    if let Some(diff) = &made.diff
        && print_stdout(diff) != ExitCode::SUCCESS
    {
        return ExitCode::from(EXIT_IO_ERROR);
    }
    let target = if to_stdout {
        "stdout".to_string()
    } else {
        output.display().to_string()
    };
    eprintln!("{}", compiled.report.summary_line(&target));
    ExitCode::SUCCESS
}
