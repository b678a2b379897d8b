//! The loop for one prompt, as the paper runs it: each round samples cameras around the
//! model, renders the current numbers, asks the img2img servers for `k` pictures of each
//! view, keeps the picture closest to the render (the paper's selection, which keeps thin
//! legs from vanishing), and takes `iterations` steps of the image loss towards the kept
//! pictures with the project's [`Fitter`](crate::fit::Fitter) (one round of one stage, from
//! the current numbers, its steps bounded in pixels; the stages of the fit's default
//! schedule spread over the prompt's rounds, [`Plan`]). The prompt's variation is the mean
//! of the numbers after each round of the last stage ([`super::run::Tail`]).
//!
//! Invariants: a round is a function of the numbers it starts from, the run's seed, the
//! prompt's name, the round's number and the prompt's number of rounds (cameras and
//! request seeds come from them, the stage from the last two), so a
//! resumed run repeats an uninterrupted one given the same server answers; the state is
//! saved after every round, its images first ([`super::run`]).

use super::diffusion::{Pool, Request, Sampler, view_word};
use super::net::ServerError;
use super::run::{RunFolder, State};
use crate::fit::loss::{Target, quick_channels};
use crate::fit::uncertainty::Information;
use crate::fit::{FitOptions, Parametric, Progress, Stage, fit, fit_measured, staged};
use crate::ir::Model;
use crate::render::camera::{Camera, CameraSpec, OPENSCAD_FOV, Projection};
use crate::render::image::{Rgb, picture};
use crate::render::scene::DEFAULT_SHADE;
use crate::render::soft::{ViewPrep, prepare_view};
use crate::render::{Backend, CpuBackend};
use crate::span::FileId;
use crate::variation::uncertainty::sidecar_path;
use rayon::prelude::*;

/// Margin around the model's bounding sphere in the sampled views (room to grow).
const FRAME_MARGIN: f64 = 1.4;
/// OpenSCAD gimbal tilt of the sampled views, degrees: 90 looks level, 0 straight down.
const TILT: (f64, f64) = (50.0, 80.0);

/// The default bound on a round's steps, in edge softnesses (`--reach`). Measured on the
/// generator's families (`cargo bench --bench explore_families`, seeds 0..20, 30 rounds at
/// 64 px): variations at IoU >= 0.9 28% unbounded, 60% at 0.25 and at 0.5, 62% at 1, with
/// presets at IoU >= 0.95 10%, 42%, 43% and 40% (README).
pub const EXPLORE_REACH: f64 = 0.5;

/// How the loop runs.
#[derive(Debug, Clone, PartialEq)]
pub struct Settings {
    /// Rounds per prompt (the paper: 400).
    pub rounds: usize,
    /// Fit steps per round (the paper: 30).
    pub iterations: usize,
    /// Views per round (the paper: 5).
    pub views: usize,
    /// Side of the renders fitted, pixels.
    pub size: u32,
    /// Learning rate of the fit steps.
    pub lr: f64,
    /// How far a round's steps may move a face, in edge softnesses ([`FitOptions::reach`]):
    /// every round is a fresh fit whose optimiser would otherwise take its first step at the
    /// full rate on every number, several pixels, then spend the round coming back.
    pub reach: f64,
    pub seed: u64,
    pub sampler: Sampler,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            rounds: 400,
            iterations: 30,
            views: 5,
            size: 256,
            lr: FitOptions::default().lr,
            reach: EXPLORE_REACH,
            seed: 0,
            sampler: Sampler::default(),
        }
    }
}

/// What stopped a prompt's loop.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ExploreError {
    #[error("prompt `{prompt}`, round {round}: {error}")]
    Server {
        prompt: String,
        round: usize,
        error: ServerError,
    },
    #[error("{0}")]
    Run(String),
}

/// One round's outcome.
#[derive(Debug, Clone, PartialEq)]
pub struct RoundOutcome {
    /// The numbers after the round's steps.
    pub x: Vec<f64>,
    /// The image loss at the end of the round.
    pub loss: f64,
    /// Per view: the picture kept, and the render it was asked from.
    pub guides: Vec<Rgb>,
    pub renders: Vec<Rgb>,
    /// After the prompt's last round: how well its guidance determines each number.
    pub information: Option<Information>,
}

/// The loop set up for a model.
pub struct Explorer<'a> {
    problem: Parametric,
    /// Where the rounds move, as a fit's default schedule does (see [`Plan`]).
    plan: Plan,
    settings: &'a Settings,
    pool: &'a Pool,
    /// The main file's text and id, for writing variations.
    text: &'a str,
    main: FileId,
    model: &'a Model,
    /// Where the sampled cameras look and from how far.
    center: [f64; 3],
    distance: f64,
}

/// Where each round moves: the fit's default schedule spread over the prompt's rounds
/// ([`staged`]). The first half of the rounds are warm: the first of them moves the
/// model's proportions, the others move inside the structural subspace, so parts move
/// with what they touch; the rest move every slot. A face the pictures never show (a leg's
/// top inside the seat, an arm's underside on it) has no gradient in slot space, so it
/// stays where the warm rounds left it, on the faces it touches, instead of where the
/// model's own numbers happened to put it.
struct Plan {
    /// The stages, each with its rounds, in order.
    stages: Vec<Stage>,
}

impl Plan {
    fn new(model: &Model, rounds: usize) -> Plan {
        let rounds = rounds.max(1);
        Plan {
            stages: staged(model, rounds, rounds / 2),
        }
    }

    /// The round (from 0) the last stage starts at.
    fn last_from(&self) -> usize {
        let n = self.stages.len().saturating_sub(1);
        self.stages[..n].iter().map(|s| s.rounds).sum()
    }

    /// The stage of round `round` (from 0), for one round.
    fn stage(&self, round: usize) -> Stage {
        let mut first = 0;
        for s in &self.stages {
            if round < first + s.rounds {
                return Stage {
                    rounds: 1,
                    ..s.clone()
                };
            }
            first += s.rounds;
        }
        Stage::slots(1)
    }
}

/// splitmix64: the next value of a seeded sequence.
fn mix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// A number from a name (FNV-1a), so a prompt's seeds do not depend on the other prompts.
fn hash(name: &str) -> u64 {
    name.bytes().fold(0xcbf2_9ce4_8422_2325, |h, b| {
        (h ^ b as u64).wrapping_mul(0x100_0000_01b3)
    })
}

/// A uniform number in `[0, 1)` from `z`.
fn unit(z: u64) -> f64 {
    (mix(z) >> 11) as f64 / (1u64 << 53) as f64
}

/// How far two pictures of the same size are apart, given their [`quick_channels`]: the
/// mean squared difference of their foreground masks (each against its own background
/// colour) plus that of their premultiplied grey levels, so a sample lit or tinted
/// otherwise is not taken for another shape.
fn distance(a: &(Vec<f32>, Vec<f32>), b: &(Vec<f32>, Vec<f32>)) -> f64 {
    let mean = |x: &[f32], y: &[f32]| {
        let sum: f64 = x.iter().zip(y).map(|(p, q)| ((p - q) as f64).powi(2)).sum();
        sum / x.len().max(1) as f64
    };
    mean(&a.0, &b.0) + mean(&a.1, &b.1)
}

/// Of `images`, the one closest to `render` (at the render's size).
pub fn closest(images: Vec<Rgb>, render: &Rgb) -> Option<Rgb> {
    let seen = quick_channels(render);
    images
        .into_par_iter()
        .map(|i| i.resize(render.width, render.height))
        .map(|i| (distance(&quick_channels(&i), &seen), i))
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, i)| i)
}

impl<'a> Explorer<'a> {
    /// Sets the loop up for `model` (whose main file is `text`, id `main`).
    pub fn new(
        model: &'a Model,
        text: &'a str,
        main: FileId,
        settings: &'a Settings,
        pool: &'a Pool,
    ) -> Result<Explorer<'a>, String> {
        let (lo, hi) = model.bounds().ok_or("the model has no parts to explore")?;
        let center = std::array::from_fn(|a| (lo[a] + hi[a]) / 2.0);
        let radius = (0..3).map(|a| (hi[a] - lo[a]).powi(2)).sum::<f64>().sqrt() / 2.0;
        let half = (OPENSCAD_FOV.to_radians() / 2.0).tan().atan().sin();
        let distance = radius * FRAME_MARGIN / half;
        if !(distance.is_finite() && distance > 0.0) {
            return Err("the model is too small or too large to frame".into());
        }
        Ok(Explorer {
            problem: Parametric::new(model),
            plan: Plan::new(model, settings.rounds),
            settings,
            pool,
            text,
            main,
            model,
            center,
            distance,
        })
    }

    /// The model's own numbers.
    pub fn x0(&self) -> &[f64] {
        &self.problem.x0
    }

    /// The cameras of prompt `name`'s round `round`: random azimuths and tilts around the
    /// model, the same for the same seed, name and round.
    pub fn cameras(&self, name: &str, round: usize) -> Result<Vec<Camera>, String> {
        let base = mix(self.settings.seed ^ hash(name)) ^ mix(round as u64);
        let size = self.settings.size;
        (0..self.settings.views)
            .map(|v| {
                let z = mix(base.wrapping_add(v as u64));
                let azimuth = 360.0 * unit(z);
                let tilt = TILT.0 + (TILT.1 - TILT.0) * unit(z ^ 0x5555);
                let [cx, cy, cz] = self.center;
                let params = [cx, cy, cz, tilt, 0.0, azimuth, self.distance];
                let name = format!("view{}", v + 1);
                Camera::from_openscad(&name, &params, Projection::Perspective, size, size)
                    .map_err(|e| e.to_string())
            })
            .collect()
    }

    /// The views a variation is shown from: OpenSCAD's default direction, then front,
    /// side and rear, framed as the rounds' views are.
    pub fn final_cameras(&self) -> Result<Vec<Camera>, String> {
        let size = self.settings.size;
        [
            ("default", 55.0, 25.0),
            ("front", 75.0, 0.0),
            ("side", 75.0, 90.0),
            ("rear", 75.0, 180.0),
        ]
        .iter()
        .map(|&(name, tilt, azimuth)| {
            let [cx, cy, cz] = self.center;
            let params = [cx, cy, cz, tilt, 0.0, azimuth, self.distance];
            Camera::from_openscad(name, &params, Projection::Perspective, size, size)
                .map_err(|e| e.to_string())
        })
        .collect()
    }

    /// Pictures of the model at numbers `x` from `cameras` (hard edges, default shading).
    pub fn render(&self, x: &[f64], cameras: &[Camera]) -> Vec<Rgb> {
        let scene = self.problem.scene(x);
        let views: Vec<ViewPrep> = cameras
            .iter()
            .map(|c| prepare_view(&scene, c, None))
            .collect();
        let shades = vec![DEFAULT_SHADE; views.len()];
        CpuBackend::new()
            .render(&scene, &views, None, &shades)
            .iter()
            .map(|(s, _)| picture(s))
            .collect()
    }

    /// Round `round` (from 0) of `prompt` (named `name`) from numbers `x`.
    pub fn round(
        &self,
        prompt: &str,
        name: &str,
        round: usize,
        x: &[f64],
    ) -> Result<RoundOutcome, ExploreError> {
        let cameras = self.cameras(name, round).map_err(ExploreError::Run)?;
        let renders = self.render(x, &cameras);
        let base = mix(self.settings.seed ^ hash(name) ^ mix(round as u64 + 1));
        let requests: Vec<Request> = cameras
            .iter()
            .zip(&renders)
            .enumerate()
            .map(|(v, (c, r))| Request {
                prompt: format!("{prompt}, {} view", view_word(c)),
                seed: mix(base.wrapping_add(v as u64)) >> 33,
                init: r.clone(),
                camera: CameraSpec::of(c, None),
            })
            .collect();
        let answers = self
            .pool
            .run(&requests, &self.settings.sampler)
            .map_err(|error| ExploreError::Server {
                prompt: prompt.to_string(),
                round: round + 1,
                error,
            })?;
        self.take(x, round, &cameras, renders, answers)
    }

    /// The round's own work once the servers have answered: per view, the sample closest
    /// to the render (`renders`, from `cameras`), then the fit steps towards them from `x`.
    pub fn take(
        &self,
        x: &[f64],
        round: usize,
        cameras: &[Camera],
        renders: Vec<Rgb>,
        answers: Vec<Vec<Rgb>>,
    ) -> Result<RoundOutcome, ExploreError> {
        let guides: Vec<Rgb> = answers
            .into_par_iter()
            .zip(&renders)
            .filter_map(|(images, r)| closest(images, r))
            .collect();
        let (x, loss, information) = self.fit(x, cameras, &guides, round)?;
        Ok(RoundOutcome {
            x,
            loss,
            guides,
            renders,
            information,
        })
    }

    /// `iterations` steps of the image loss from `x` towards `guides`: the numbers after
    /// them, the loss there and, after the last round, the numbers' information there.
    fn fit(
        &self,
        x: &[f64],
        cameras: &[Camera],
        guides: &[Rgb],
        round: usize,
    ) -> Result<(Vec<f64>, f64, Option<Information>), ExploreError> {
        // Starts where the last round ended; the regulariser keeps pulling towards the
        // model's own numbers (`anchor`), as the paper's λ‖x − x₀‖² does.
        let mut problem = self.problem.clone();
        problem.x0 = x.to_vec();
        let targets = Target::set_from_rgb(guides);
        let last = round + 1 >= self.settings.rounds.max(1);
        // Each round is a one-round fit, so its one round is the last and compares area
        // coverage (`FitOptions::coverage`), as a fit ends. A schedule of soft edges over
        // the run's rounds (the paper's σ from 2 to 0.5 pixels) was measured against it on
        // the stand-in loop (three prompts, 20 rounds at 64 pixels): IoU with the targets
        // 0.815, 0.814, 0.873 against 0.882, 0.920, 0.892 with area coverage throughout.
        let opts = FitOptions {
            lr: self.settings.lr,
            iterations: self.settings.iterations.max(1),
            rounds: 1,
            proportions: false,
            damped_rerun: None,
            reach: self.settings.reach,
            ..FitOptions::default()
        };
        let stages = [self.plan.stage(round)];
        let (b, p): (&mut CpuBackend, &mut dyn FnMut(&Progress)) =
            (&mut CpuBackend::new(), &mut |_| {});
        let fitted = if last {
            fit_measured(&problem, cameras, &targets, &stages, b, &opts, p)
                .map(|(r, i)| (r, Some(i)))
        } else {
            fit(&problem, cameras, &targets, &stages, b, &opts, p).map(|r| (r, None))
        };
        match fitted {
            Ok((r, information)) => Ok((r.x, r.end_loss.iter().sum(), information)),
            Err(e) => Err(ExploreError::Run(format!("round {}: {e}", round + 1))),
        }
    }

    /// The model's text with numbers `x` written in: a `--vary` file.
    pub fn variation_text(&self, x: &[f64]) -> String {
        crate::back::rewrite::with_slot_values(self.text, self.main, &self.model.slots, x)
    }

    /// Runs prompt `index` of `state` to the end, saving after every round, and writes its
    /// variation (the mean of the last stage's rounds, with the uncertainty the last
    /// round's guidance gives); `progress` is told (rounds done, rounds, loss) after each
    /// round.
    pub fn run_prompt(
        &self,
        folder: &RunFolder,
        state: &mut State,
        index: usize,
        progress: &mut dyn FnMut(usize, usize, f64),
    ) -> Result<(), ExploreError> {
        let total = state.rounds;
        let mut information = None;
        while state.prompts[index].round < total {
            let p = &state.prompts[index];
            let (prompt, name, round) = (p.prompt.clone(), p.name.clone(), p.round);
            let out = self.round(&prompt, &name, round, &p.x)?;
            folder
                .save_round(&name, round + 1, &out.guides, &out.renders)
                .map_err(ExploreError::Run)?;
            let p = &mut state.prompts[index];
            p.round = round + 1;
            p.x = out.x;
            p.tally(round, self.plan.last_from());
            information = out.information;
            p.loss.push(out.loss);
            folder.save(state).map_err(ExploreError::Run)?;
            progress(round + 1, total, out.loss);
        }
        let p = &state.prompts[index];
        let at = p.variation();
        let path = folder.variation_path(&p.name);
        // The sidecar goes first: a variation file is only ever beside its own sidecar.
        // (A prompt finished by an earlier run keeps the sidecar that run wrote.)
        if let Some(info) = information {
            let u = info.uncertainty(self.model, &at);
            folder
                .write(&sidecar_path(&path), u.to_json().as_bytes())
                .map_err(ExploreError::Run)?;
        }
        let text = self.variation_text(&at);
        folder
            .write(&path, text.as_bytes())
            .map_err(ExploreError::Run)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A white picture with a square of `colour` from `at` to `at + 4`.
    fn square(size: u32, at: u32, colour: [f32; 3]) -> Rgb {
        let mut img = Rgb::new(size, size, [1.0; 3]);
        for y in at..at + 4 {
            for x in at..at + 4 {
                img.data[(y * size + x) as usize] = colour;
            }
        }
        img
    }

    #[test]
    fn the_rounds_follow_the_fits_schedule_proportions_then_structure_then_slots() {
        // A leg under a top: the structural subspace keeps the leg on the top's underside.
        let m = crate::front::test_model(
            "cube([10, 10, 20]);\n\
             translate([-5, -5, 20]) cube([20, 20, 2]);\n",
        );
        let plan = Plan::new(&m, 10);
        let scale = Some(crate::fit::scale_basis(&m));
        let structure = Some(crate::fit::structure_basis(&m));
        assert_ne!(structure.as_ref().map(|b| b.ncols()), Some(m.slots.len()));
        assert_eq!(plan.stage(0).basis, scale);
        for r in 1..5 {
            assert_eq!(plan.stage(r).basis, structure, "round {r}");
        }
        for r in 5..12 {
            assert_eq!(plan.stage(r), Stage::slots(1), "round {r}");
        }
        // A single round moves every slot, as a one-round fit's last round does.
        assert_eq!(Plan::new(&m, 1).stage(0), Stage::slots(1));
    }

    #[test]
    fn the_closest_shape_is_kept_whatever_its_colour() {
        let render = square(16, 4, [0.5, 0.5, 0.5]);
        // The same shape tinted is closer than another shape in the render's colour.
        let tinted = square(16, 4, [0.6, 0.4, 0.3]);
        let moved = square(16, 10, [0.5, 0.5, 0.5]);
        let kept = closest(vec![moved, tinted.clone()], &render).unwrap();
        assert_eq!(kept, tinted);
        // Pictures of another size are compared (and kept) at the render's size.
        let big = square(32, 8, [0.5, 0.5, 0.5]);
        assert_eq!(closest(vec![big], &render).unwrap().width, 16);
    }

    #[test]
    fn seeds_depend_on_name_and_round_only() {
        assert_eq!(mix(1), mix(1));
        assert_ne!(hash("bench"), hash("stool"));
        let u = unit(hash("bench"));
        assert!((0.0..1.0).contains(&u));
    }
}
