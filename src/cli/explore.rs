//! `reparamc explore`: the zero-shot loop from a model and the name of its object.
//!
//! Flags in, [`reparamc::command::explore`] called (one progress bar per prompt, hidden
//! when standard error is not a terminal), the re-parameterized model and its parameter
//! sets written (each file whole or not at all), diagnostics out. A server that fails
//! exits with [`EXIT_SERVER_ERROR`]; the rounds done stay in the run folder.

use super::render::{input_error, say};
use super::{EXIT_IO_ERROR, EXIT_MODEL_ERROR, EXIT_SERVER_ERROR};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use reparamc::command::explore::{
    EXPLORE_REACH, Llm, Options, Pool, RoundDone, Sampler, Settings, StopKind, Stopped, parse_pick,
    prepare, presets_path,
};
use reparamc::front::source::SourceMap;
use reparamc::output::write_atomic;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Duration;

#[derive(clap::Args)]
pub struct Args {
    /// The OpenSCAD model to explore.
    model: PathBuf,
    /// What the model is (`chair`): the language model is asked "What are different types
    /// of chair?".
    #[arg(long)]
    object: String,
    /// Where to write the re-parameterized model; its parameter sets (one per prompt) go
    /// beside it as `<name>.json`.
    #[arg(short, long)]
    output: PathBuf,
    /// The run folder: the state after every round, each round's pictures and each
    /// prompt's variation (`<prompt>.scad`).
    #[arg(long, value_name = "DIR")]
    run: PathBuf,
    /// Continue the run in --run where it stopped.
    #[arg(long)]
    resume: bool,
    /// A prompt to explore (repeatable); added after the language model's.
    #[arg(long = "prompt", value_name = "TEXT")]
    prompts: Vec<String>,
    /// An OpenAI-compatible API to ask for kinds of the object (`http://localhost:8080/v1`;
    /// `OPENAI_API_KEY` is sent when set).
    #[arg(long, value_name = "URL")]
    llm: Option<String>,
    /// The model the language model server should use.
    #[arg(long, default_value = "gpt-4o-mini")]
    llm_model: String,
    /// Which of the language model's kinds to explore, by position: `1,3,5` (default: the
    /// first five).
    #[arg(long, value_name = "LIST")]
    pick: Option<String>,
    /// An AUTOMATIC1111 WebUI-compatible server (WebUI, Forge, SD.Next started with
    /// `--api`); repeatable: requests are spread over them.
    #[arg(long = "diffusion", value_name = "URL", required = true)]
    diffusion: Vec<String>,
    /// Rounds per prompt.
    #[arg(long, default_value_t = 400)]
    rounds: usize,
    /// Fit steps per round.
    #[arg(long, default_value_t = 30)]
    iterations: usize,
    /// Views per round.
    #[arg(long, default_value_t = 5)]
    views: usize,
    /// Side of the renders fitted, pixels.
    #[arg(long, default_value_t = 256)]
    size: u32,
    /// Side of the images asked of the diffusion servers, pixels.
    #[arg(long, default_value_t = 512)]
    diffusion_size: u32,
    /// Samples per view; the one closest to the render guides the fit.
    #[arg(long, default_value_t = 3)]
    batch: u32,
    /// How far img2img may move from the render (0 to 1).
    #[arg(long, default_value_t = 0.75)]
    denoise: f64,
    /// Sampler steps of each img2img request.
    #[arg(long, default_value_t = 50)]
    steps: u32,
    #[arg(long, default_value_t = 7.0)]
    cfg_scale: f64,
    #[arg(long)]
    negative_prompt: Option<String>,
    /// Learning rate of the fit steps.
    #[arg(long, default_value_t = 0.05)]
    lr: f64,
    /// Bound each round's steps: the first moves no face further than this many edge
    /// softnesses, and the bound grows while the loss falls and halves when a step raised
    /// it (0: no bound).
    #[arg(long, default_value_t = EXPLORE_REACH)]
    reach: f64,
    /// The run's seed (cameras and request seeds follow from it).
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Seconds to wait for one answer of a server.
    #[arg(long, default_value_t = 300.0)]
    timeout: f64,
    /// Further tries of a request when every server failed it for a reason that may pass.
    #[arg(long, default_value_t = 3)]
    retries: u32,
    /// Write a page (HTML) with each prompt's sampled rounds (guidance beside render), its
    /// final variation's views and the output's presets, rendered; the presets picture goes
    /// beside it as `<name>_presets.png`.
    #[arg(long, value_name = "FILE")]
    gallery: Option<PathBuf>,
}

/// The library's options from the flags, or the message for a bad flag.
fn options(args: &Args) -> Result<Options, String> {
    let timeout = Duration::try_from_secs_f64(args.timeout)
        .ok()
        .filter(|t| !t.is_zero())
        .ok_or_else(|| {
            format!(
                "`--timeout {}` must be a positive number of seconds",
                args.timeout
            )
        })?;
    if !(0.0..=1.0).contains(&args.denoise) {
        return Err(format!("`--denoise {}` must be from 0 to 1", args.denoise));
    }
    if args.size < 16 || args.diffusion_size < 16 || args.batch == 0 || args.views == 0 {
        return Err(
            "--size and --diffusion-size must be at least 16, --batch and --views at least 1"
                .into(),
        );
    }
    if !(args.lr.is_finite() && args.lr > 0.0) {
        return Err(format!("`--lr {}` must be positive", args.lr));
    }
    if !(args.reach.is_finite() && args.reach >= 0.0) {
        return Err(format!("`--reach {}` must be 0 or more", args.reach));
    }
    let pick = args.pick.as_deref().map(parse_pick).transpose()?;
    let mut sampler = Sampler {
        denoising_strength: args.denoise,
        steps: args.steps,
        cfg_scale: args.cfg_scale,
        size: args.diffusion_size,
        batch_size: args.batch,
        ..Sampler::default()
    };
    if let Some(n) = &args.negative_prompt {
        sampler.negative_prompt = n.clone();
    }
    Ok(Options {
        model: args.model.clone(),
        object: args.object.clone(),
        prompts: args.prompts.clone(),
        llm: args.llm.as_ref().map(|url| Llm {
            url: url.clone(),
            model: args.llm_model.clone(),
            key: std::env::var("OPENAI_API_KEY")
                .ok()
                .filter(|k| !k.is_empty()),
            timeout,
        }),
        pick,
        pool: Pool {
            servers: args.diffusion.clone(),
            timeout,
            retries: args.retries,
            backoff: Duration::from_millis(500),
            parallel: args.views.max(args.diffusion.len()),
        },
        settings: Settings {
            rounds: args.rounds.max(1),
            iterations: args.iterations.max(1),
            views: args.views,
            size: args.size,
            lr: args.lr,
            reach: args.reach,
            seed: args.seed,
            sampler,
        },
        run: args.run.clone(),
        resume: args.resume,
        presets_name: args
            .output
            .with_extension("json")
            .file_name()
            .map(|n| n.to_string_lossy().into_owned()),
        gallery: args.gallery.clone(),
    })
}

/// Prints what stopped the command and returns its exit code.
fn stopped(sources: &SourceMap, s: &Stopped) -> ExitCode {
    say(sources, &s.failure.messages);
    ExitCode::from(match s.kind {
        StopKind::Input => EXIT_MODEL_ERROR,
        StopKind::Server => EXIT_SERVER_ERROR,
        StopKind::Output => EXIT_IO_ERROR,
    })
}

/// One bar per prompt, made as its first round ends, left on screen when it is done.
struct Bars {
    shown: bool,
    current: Option<(usize, ProgressBar)>,
}

impl Bars {
    fn tell(&mut self, r: &RoundDone) {
        if self.current.as_ref().is_none_or(|(i, _)| *i != r.index) {
            if let Some((_, b)) = self.current.take() {
                b.finish();
            }
            let target = if self.shown {
                ProgressDrawTarget::stderr()
            } else {
                ProgressDrawTarget::hidden()
            };
            let bar = ProgressBar::with_draw_target(Some(r.rounds as u64), target);
            if let Ok(style) = ProgressStyle::with_template(
                "{prefix:>16} [{elapsed}] {bar:24} round {pos}/{len} loss {msg} eta {eta}",
            ) {
                bar.set_style(style);
            }
            bar.set_prefix(r.prompt.to_string());
            self.current = Some((r.index, bar));
        }
        if let Some((_, b)) = &self.current {
            b.set_position(r.round as u64);
            b.set_message(format!("{:.4}", r.loss));
        }
    }
}

pub fn run(args: Args) -> ExitCode {
    let presets = args.output.with_extension("json");
    let mut outputs = vec![args.output.as_path(), presets.as_path()];
    let gallery_png = args.gallery.as_deref().map(presets_path);
    outputs.extend(
        args.gallery
            .iter()
            .chain(&gallery_png)
            .map(PathBuf::as_path),
    );
    if let Err(code) = super::check_outputs(&outputs, std::slice::from_ref(&args.model)) {
        return code;
    }
    let opts = match options(&args) {
        Ok(o) => o,
        Err(text) => return input_error("E0802", text),
    };
    let _ = super::INTERRUPTED
        .set("no file half-written; the run folder keeps the rounds done (--resume)");
    let mut sources = SourceMap::new();
    let mut job = match prepare(&opts, &mut sources) {
        Ok(j) => j,
        Err(s) => return stopped(&sources, &s),
    };
    say(&sources, &std::mem::take(&mut job.messages));
    eprintln!("exploring {}", job.prompts().join(", "));
    let mut bars = Bars {
        shown: std::io::stderr().is_terminal(),
        current: None,
    };
    let result = job.run(&mut sources, &mut |r: &RoundDone| bars.tell(r));
    if let Some((_, b)) = bars.current.take() {
        b.finish();
    }
    let explored = match result {
        Ok(e) => e,
        Err(s) => return stopped(&sources, &s),
    };
    say(&sources, &explored.messages);
    super::report(&sources, &explored.output.warnings);
    let compiled = &explored.output.compiled;
    let mut files: Vec<(&Path, &[u8])> = vec![(&args.output, compiled.scad.as_bytes())];
    if let Some(p) = &compiled.presets {
        files.push((&presets, p.as_bytes()));
    }
    if let (Some(page), Some(png), Some((html, bytes))) =
        (&args.gallery, &gallery_png, &explored.gallery)
    {
        if !bytes.is_empty() {
            files.push((png, bytes));
        }
        files.push((page, html.as_bytes()));
    }
    for (path, bytes) in files {
        if let Err(e) = write_atomic(path, bytes) {
            eprintln!("error: cannot write `{}`: {e}", path.display());
            return ExitCode::from(EXIT_IO_ERROR);
        }
    }
    eprintln!(
        "{}",
        compiled
            .report
            .summary_line(&args.output.display().to_string())
    );
    ExitCode::SUCCESS
}
