//! The `explore` command's entry point: the zero-shot loop, then the main job on the
//! variations it found.
//!
//! In two steps, like `fit`: [`prepare`] loads the model, gets the prompts (from the user,
//! from a language model, or from the run folder being resumed) and writes the run's first
//! state; [`Job::run`] runs each prompt's rounds ([`crate::explore::rounds`]), reporting
//! each round to a callback, then runs the main job ([`super::compile::compile`]) on the
//! prompts' variation files, so presets are named by prompt.
//!
//! Unlike the other commands, this one writes as it goes: the run folder is its record,
//! saved after every round so a run can stop and resume (every file through
//! `output::write_atomic`). The re-parameterized model itself is returned as data.

use super::compile::{CompileOptions, CompileOutput, Options as CompileJob, compile};
use super::{Failure, Message, as_messages};
pub use crate::explore::diffusion::Pool;
use crate::explore::gallery;
pub use crate::explore::llm::Llm;
use crate::explore::llm::{ask_kinds, pick};
pub use crate::explore::rounds::{EXPLORE_REACH, Settings};
use crate::explore::rounds::{ExploreError, Explorer};
use crate::explore::run::{PromptState, RunFolder, STATE_VERSION, State, names_of};
use crate::front::source::SourceMap;
use crate::ir::Model;
use crate::span::FileId;
use std::path::PathBuf;

pub use crate::explore::diffusion::Sampler;
pub use crate::explore::gallery::presets_path;
pub use crate::explore::llm::parse_pick;

/// The `explore` command's options.
#[derive(Debug, Clone, PartialEq)]
pub struct Options {
    pub model: PathBuf,
    /// What the model is (`chair`): the language model is asked for kinds of it.
    pub object: String,
    /// The user's own prompts (explored after the language model's).
    pub prompts: Vec<String>,
    /// Where to ask for kinds, if anywhere.
    pub llm: Option<Llm>,
    /// Which of the language model's items to take (from 1); `None`: the first five.
    pub pick: Option<Vec<usize>>,
    pub pool: Pool,
    pub settings: Settings,
    /// The run folder.
    pub run: PathBuf,
    /// Continue the run in `run` instead of starting one.
    pub resume: bool,
    /// The file name the parameter sets will have (for the output's comment).
    pub presets_name: Option<String>,
    /// Make the gallery page that will be written here.
    pub gallery: Option<PathBuf>,
}

/// Why the command stopped, which sets the exit code.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StopKind {
    /// The model, the flags or the run folder's state.
    Input,
    /// A server could not be reached or answered wrongly.
    Server,
    /// A file of the run folder could not be written.
    Output,
}

/// What stopped the command.
#[derive(Debug, Clone, PartialEq)]
pub struct Stopped {
    pub failure: Failure,
    pub kind: StopKind,
}

impl Stopped {
    fn input(messages: Vec<Message>, code: &'static str, text: String) -> Stopped {
        Stopped {
            failure: Failure::input(messages, code, text),
            kind: StopKind::Input,
        }
    }
}

/// Progress of the loop, told after every round.
#[derive(Debug, Clone, PartialEq)]
pub struct RoundDone<'a> {
    pub prompt: &'a str,
    /// Which prompt (from 0), of how many.
    pub index: usize,
    pub prompts: usize,
    /// Rounds done, of how many.
    pub round: usize,
    pub rounds: usize,
    pub loss: f64,
}

/// A run ready to go on.
pub struct Job {
    /// What preparing had to say (warnings, the language model's list), in order.
    pub messages: Vec<Message>,
    opts: Options,
    text: String,
    main: FileId,
    model: Model,
    folder: RunFolder,
    state: State,
}

/// What a finished run made.
#[derive(Debug)]
pub struct Explored {
    /// The main job's results on the variations.
    pub output: CompileOutput,
    /// The variation files, one per prompt, in the run folder.
    pub variations: Vec<PathBuf>,
    /// The gallery page and the presets picture it shows (to be written at
    /// [`crate::explore::gallery::presets_path`] of the page), when asked.
    pub gallery: Option<(String, Vec<u8>)>,
    pub messages: Vec<Message>,
}

/// Loads the model, finds the prompts and writes the run's first state (or reads the state
/// of the run to resume).
pub fn prepare(opts: &Options, sources: &mut SourceMap) -> Result<Job, Stopped> {
    let (parsed, evaluated) =
        crate::front::load_model_parsed(sources, &opts.model).map_err(|d| Stopped {
            failure: Failure::from(d),
            kind: StopKind::Input,
        })?;
    let mut messages = as_messages(evaluated.warnings);
    let model = evaluated.model;
    if model.parts.is_empty() {
        let text = format!(
            "{}: the model has no parts to explore",
            opts.model.display()
        );
        return Err(Stopped::input(messages, "E0801", text));
    }
    let folder = RunFolder::new(&opts.run);
    let state = if opts.resume {
        resumed(opts, &folder, &model, &mut messages)?
    } else {
        started(opts, &folder, &model, &mut messages)?
    };
    let names: Vec<String> = state.prompts.iter().map(|p| p.name.clone()).collect();
    let saved = folder.create(&names).and_then(|()| folder.save(&state));
    if let Err(text) = saved {
        return Err(Stopped {
            failure: Failure::input(messages, "E0804", text),
            kind: StopKind::Output,
        });
    }
    Ok(Job {
        messages,
        opts: opts.clone(),
        text: sources.text(parsed.main).to_string(),
        main: parsed.main,
        model,
        folder,
        state,
    })
}

/// A new run's state: the prompts asked for, each at round 0 with the model's numbers.
fn started(
    opts: &Options,
    folder: &RunFolder,
    model: &Model,
    messages: &mut Vec<Message>,
) -> Result<State, Stopped> {
    if folder.state_path().exists() {
        let text = format!(
            "`{}` already holds a run; continue it with --resume, or choose another --run",
            folder.dir.display()
        );
        return Err(Stopped::input(std::mem::take(messages), "E0803", text));
    }
    let mut items = Vec::new();
    if let Some(llm) = &opts.llm {
        let (list, _) = ask_kinds(llm, &opts.object).map_err(|e| Stopped {
            failure: Failure::input(
                std::mem::take(messages),
                "E0805",
                format!("asking for kinds of {}: {e}", opts.object),
            ),
            kind: StopKind::Server,
        })?;
        messages.push(Message::Line(format!("kinds of {}:", opts.object)));
        for (i, item) in list.iter().enumerate() {
            messages.push(Message::Line(format!("  {}. {item}", i + 1)));
        }
        items = list;
    }
    let prompts = pick(&items, opts.pick.as_deref(), &opts.prompts)
        .map_err(|text| Stopped::input(std::mem::take(messages), "E0802", text))?;
    if prompts.is_empty() {
        let text = "nothing to explore: give --prompt, or --llm to ask for kinds".to_string();
        return Err(Stopped::input(std::mem::take(messages), "E0802", text));
    }
    let x0 = model.slot_values();
    Ok(State {
        version: STATE_VERSION,
        model: opts.model.display().to_string(),
        object: opts.object.clone(),
        seed: opts.settings.seed,
        rounds: opts.settings.rounds,
        prompts: names_of(&prompts)
            .into_iter()
            .zip(prompts)
            .map(|(name, prompt)| PromptState::new(prompt, name, x0.clone()))
            .collect(),
    })
}

/// The state of the run to resume, checked against the model; `--rounds` may extend it
/// and `--prompt` add prompts to it.
fn resumed(
    opts: &Options,
    folder: &RunFolder,
    model: &Model,
    messages: &mut Vec<Message>,
) -> Result<State, Stopped> {
    let mut state = folder
        .load()
        .map_err(|text| Stopped::input(std::mem::take(messages), "E0803", text))?;
    let slots = model.slots.len();
    let numbers = |p: &PromptState| {
        p.x.len() != slots || !(p.tail.sum.is_empty() || p.tail.sum.len() == slots)
    };
    if let Some(p) = state.prompts.iter().find(|p| numbers(p)) {
        let text = format!(
            "`{}`: prompt `{}` has {} numbers but {} has {slots}; was the model changed?",
            folder.state_path().display(),
            p.prompt,
            p.x.len(),
            opts.model.display()
        );
        return Err(Stopped::input(std::mem::take(messages), "E0803", text));
    }
    state.rounds = opts.settings.rounds;
    let mut prompts: Vec<String> = state.prompts.iter().map(|p| p.prompt.clone()).collect();
    for p in &opts.prompts {
        if !prompts.iter().any(|q| q.eq_ignore_ascii_case(p)) {
            prompts.push(p.clone());
        }
    }
    let names = names_of(&prompts);
    for (prompt, name) in prompts.into_iter().zip(names).skip(state.prompts.len()) {
        state
            .prompts
            .push(PromptState::new(prompt, name, model.slot_values()));
    }
    let done: usize = state
        .prompts
        .iter()
        .map(|p| p.round.min(state.rounds))
        .sum();
    messages.push(Message::Line(format!(
        "resuming {}: {done} of {} rounds done",
        folder.dir.display(),
        state.rounds * state.prompts.len()
    )));
    Ok(state)
}

impl Job {
    /// The prompts, in the order they run.
    pub fn prompts(&self) -> Vec<String> {
        self.state
            .prompts
            .iter()
            .map(|p| p.prompt.clone())
            .collect()
    }

    /// Rounds each prompt runs to.
    pub fn rounds(&self) -> usize {
        self.state.rounds
    }

    /// Rounds each prompt has done so far.
    pub fn done(&self) -> Vec<usize> {
        self.state.prompts.iter().map(|p| p.round).collect()
    }

    /// Runs every prompt's rounds, then the main job on the variations (loading them into
    /// `sources`).
    pub fn run(
        mut self,
        sources: &mut SourceMap,
        progress: &mut dyn FnMut(&RoundDone),
    ) -> Result<Explored, Stopped> {
        let explorer = Explorer::new(
            &self.model,
            &self.text,
            self.main,
            &self.opts.settings,
            &self.opts.pool,
        )
        .map_err(|text| Stopped::input(Vec::new(), "E0801", text))?;
        let n = self.state.prompts.len();
        for i in 0..n {
            let prompt = self.state.prompts[i].prompt.clone();
            let mut tell = |round, rounds, loss| {
                progress(&RoundDone {
                    prompt: &prompt,
                    index: i,
                    prompts: n,
                    round,
                    rounds,
                    loss,
                })
            };
            explorer
                .run_prompt(&self.folder, &mut self.state, i, &mut tell)
                .map_err(stopped)?;
        }
        let variations: Vec<PathBuf> = self
            .state
            .prompts
            .iter()
            .map(|p| self.folder.variation_path(&p.name))
            .collect();
        let job = CompileOptions {
            model: self.opts.model.clone(),
            variations: variations.clone(),
            options: CompileJob {
                presets_name: self.opts.presets_name.clone(),
                ..CompileJob::default()
            },
            gallery: self.opts.gallery.is_some(),
            ..CompileOptions::default()
        };
        let output = compile(&job, sources).map_err(|d| Stopped {
            failure: Failure::from(d),
            kind: StopKind::Input,
        })?;
        let gallery = match &self.opts.gallery {
            Some(at) => Some(self.gallery(&explorer, at, &output)?),
            None => None,
        };
        Ok(Explored {
            output,
            variations,
            gallery,
            messages: std::mem::take(&mut self.messages),
        })
    }

    /// Renders each prompt's final views into the run folder and makes the page to be
    /// written at `at`, with the presets picture the main job drew.
    fn gallery(
        &self,
        explorer: &Explorer,
        at: &std::path::Path,
        output: &CompileOutput,
    ) -> Result<(String, Vec<u8>), Stopped> {
        let cameras = explorer
            .final_cameras()
            .map_err(|text| Stopped::input(Vec::new(), "E0801", text))?;
        for p in &self.state.prompts {
            for (v, img) in explorer.render(&p.variation(), &cameras).iter().enumerate() {
                let path = gallery::final_view_path(&self.folder, &p.name, v);
                self.folder
                    .write(&path, &img.encode_png())
                    .map_err(|text| Stopped {
                        failure: Failure::input(Vec::new(), "E0804", text),
                        kind: StopKind::Output,
                    })?;
            }
        }
        let png = output
            .gallery
            .as_ref()
            .map(|g| g.png.clone())
            .unwrap_or_default();
        let presets = (!png.is_empty()).then(|| gallery::presets_path(at));
        let html = gallery::page(
            at,
            &self.folder,
            &self.state,
            self.opts.settings.views,
            cameras.len(),
            presets.as_deref(),
        );
        Ok((html, png))
    }
}

/// The failure of a prompt's loop, as the user reads it.
fn stopped(e: ExploreError) -> Stopped {
    let kind = match &e {
        ExploreError::Server { .. } => StopKind::Server,
        ExploreError::Run(_) => StopKind::Output,
    };
    let code = match kind {
        StopKind::Server => "E0805",
        _ => "E0804",
    };
    let text = format!("{e}; the rounds done are kept (continue with --resume)");
    Stopped {
        failure: Failure::input(Vec::new(), code, text),
        kind,
    }
}
