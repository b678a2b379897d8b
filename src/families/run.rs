//! One family through a method, black-box: the input and its variation files written in
//! the family's style, loaded as the `reparamc` command loads them, noise added to the
//! training files' numbers, the main job (or the paper's method) run, its output scored.
//!
//! Variation files go to a temporary folder of this process and are removed once loaded.

use super::baseline::paper_method;
use super::noise::noisy;
use super::rng::Rng;
use super::score::{Output, Score, Truth, common_contacts, score};
use super::style::Style;
use super::{Draw, Family};
use crate::command::compile::{Compiled, Options, reparameterize};
use crate::front::eval::evaluate;
use crate::front::load::{Loaded, load_bytes};
use crate::front::source::SourceMap;
use crate::front::with_large_stack;
use crate::ir::Model;
use crate::ir::feature::world_intervals;
use crate::variation::{Variation, load_variation};
use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};

/// A benchmark condition: noise (a fraction of the model's size) and training count.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Setup {
    pub noise: f64,
    pub training: usize,
}

/// A family loaded: its model and its variations as the command would read them.
pub struct Case {
    pub family: Family,
    pub style: Style,
    pub sources: SourceMap,
    pub loaded: Loaded,
    pub model: Model,
    pub training_exact: Vec<Variation>,
    pub training: Vec<Variation>,
    pub held_out: Vec<Variation>,
    /// [`Family::contact_draws`], exact: only the truth's contacts read them.
    pub contact_draws: Vec<Variation>,
}

/// A family's scores under both methods.
#[derive(Debug, Clone)]
pub struct FamilyResult {
    pub seed: u64,
    pub style: Style,
    pub parts: usize,
    /// The noise added to the training variations (world units).
    pub sigma: f64,
    pub ours: Score,
    pub paper: Score,
}

static FILES: AtomicUsize = AtomicUsize::new(0);

fn scratch() -> Result<PathBuf, String> {
    let dir = std::env::temp_dir().join(format!("reparamc-families-{}", std::process::id()));
    std::fs::create_dir_all(&dir).map_err(|e| e.to_string())?;
    let n = FILES.fetch_add(1, Ordering::Relaxed);
    Ok(dir.join(format!("v{n}.scad")))
}

/// Loads `text` as a variation of the case's model (through a temporary file).
fn variation(
    sources: &mut SourceMap,
    loaded: &Loaded,
    model: &Model,
    text: &str,
) -> Result<Variation, String> {
    let path = scratch()?;
    std::fs::write(&path, text).map_err(|e| e.to_string())?;
    let v = load_variation(sources, loaded.main, model, &path);
    std::fs::remove_file(&path).ok();
    v.map_err(|d| format!("variation does not load: {}", d.message))
}

impl Case {
    /// The family of `seed` written in its own style (or `style`), loaded, with noise of
    /// `setup.noise` × size on its training variations.
    pub fn load(seed: u64, setup: Setup, style: Option<Style>) -> Result<Case, String> {
        let family = Family::generate(seed, setup.training)
            .ok_or_else(|| format!("seed {seed}: no family"))?;
        let style = style.unwrap_or(family.style);
        let program = family.program(style);
        let input = program.render(&program.values(&family.params.base(), &[]));
        let mut sources = SourceMap::new();
        let path = PathBuf::from(format!("family{seed}.scad"));
        let (loaded, model) = with_large_stack(|| {
            let loaded = load_bytes(&mut sources, &path, input.into_bytes())?;
            let model = evaluate(&sources, &loaded)?.model;
            Ok::<_, Box<crate::front::diag::Diagnostic>>((loaded, model))
        })
        .map_err(|d| {
            format!(
                "seed {seed} ({}) does not load: {}",
                style.name(),
                d.message
            )
        })?;
        if model.parts.len() != family.parts.len() {
            return Err(format!(
                "seed {seed}: {} parts loaded of {}",
                model.parts.len(),
                family.parts.len()
            ));
        }
        let sigma = setup.noise * family.size;
        let mut rng = Rng::fork(
            seed,
            5000 + (setup.noise * 1e4) as u64 * 16 + setup.training as u64,
        );
        let mut load = |d: &Draw, sigma: f64, rng: &mut Rng| {
            let values = program.values(&d.theta, &d.dropped);
            let text = program.render(&noisy(&program.numbers, &values, sigma, rng));
            variation(&mut sources, &loaded, &model, &text)
        };
        let mut training_exact = Vec::new();
        let mut training = Vec::new();
        for d in &family.training {
            training_exact.push(load(d, 0.0, &mut rng)?);
            training.push(load(d, sigma, &mut rng)?);
        }
        let held_out = family
            .held_out
            .iter()
            .map(|d| load(d, 0.0, &mut rng))
            .collect::<Result<Vec<_>, _>>()?;
        let contact_draws = family
            .contact_draws()
            .iter()
            .map(|d| load(d, 0.0, &mut rng))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Case {
            family,
            style,
            sources,
            loaded,
            model,
            training_exact,
            training,
            held_out,
            contact_draws,
        })
    }

    /// What the generator knows, on the loaded model.
    pub fn truth(&self) -> Truth<'_> {
        let mut dropped: Vec<usize> = self
            .family
            .training
            .iter()
            .flat_map(|d| d.dropped.iter().copied())
            .collect();
        dropped.sort_unstable();
        dropped.dedup();
        let mut settings = vec![self.model.slot_values()];
        let exact = [&self.training_exact, &self.held_out, &self.contact_draws];
        settings.extend(
            exact
                .iter()
                .flat_map(|vs| vs.iter().map(|v| v.values.clone())),
        );
        Truth {
            model: &self.model,
            d: self.family.dimension(),
            held_out: self.held_out.iter().map(|v| v.values.clone()).collect(),
            contacts: common_contacts(&self.model, &settings, &dropped),
            dropped,
        }
    }

    /// The main job on the noisy training variations.
    pub fn ours(&self) -> (Compiled, Output) {
        let start = std::time::Instant::now();
        let compiled = with_large_stack(|| {
            reparameterize(
                &self.sources,
                &self.loaded,
                &self.model,
                &self.training,
                &Options::default(),
            )
        });
        let seconds = start.elapsed().as_secs_f64();
        let out = output_of(&self.model, &compiled, seconds);
        (compiled, out)
    }

    pub fn paper(&self) -> Output {
        let raw: Vec<Vec<f64>> = self.training.iter().map(|v| v.values.clone()).collect();
        paper_method(&self.model, &raw)
    }

    /// Where the loaded model's parts leave the generator's at slot values `x` (intent
    /// values `theta`, parts `dropped` left out): the first face that differs at all, if
    /// any. Written numbers are exact ([`super::intent::VALUE_GRID`]), so a face the
    /// family puts flush with another is flush in the text too.
    pub fn differs(&self, x: &[f64], theta: &[f64], dropped: &[usize]) -> Option<String> {
        let base = self.family.params.base();
        for (i, (p, q)) in self.model.parts.iter().zip(&self.family.parts).enumerate() {
            if dropped.contains(&i) {
                continue;
            }
            let iv = world_intervals(p)?;
            let want = q.world(&base);
            for a in 0..3 {
                let got = [&iv[a].0, &iv[a].1].map(|n| n.affine().map_or(n.value, |f| f.eval(x)));
                let exp = [want[a].0.eval(theta), want[a].1.eval(theta)];
                if got != exp {
                    return Some(format!("{} axis {a}: {got:?} ≠ {exp:?}", q.name));
                }
            }
        }
        None
    }
}

/// The main job's output in the scores' terms: sliders' ranges from its report, toggles
/// by part name, presets parsed from its parameter-set JSON.
pub fn output_of(model: &Model, compiled: &Compiled, seconds: f64) -> Output {
    let report = &compiled.report;
    let names: Vec<&str> = report
        .free_variables
        .iter()
        .map(|f| f.name.as_str())
        .collect();
    let toggles = report
        .toggles
        .iter()
        .map(|t| {
            (0..model.parts.len())
                .filter(|&p| t.contains(&model.parts[p].name))
                .collect()
        })
        .collect();
    let presets = compiled
        .presets
        .as_deref()
        .map_or_else(Vec::new, |json| parse_presets(json, &names));
    Output {
        kept: compiled
            .kept
            .iter()
            .flat_map(|c| c.rows.iter().cloned())
            .collect(),
        solution: compiled.solution.clone(),
        ranges: report.free_variables.iter().map(|f| f.range).collect(),
        toggles,
        presets,
        projected: compiled.projected.clone(),
        seconds,
        sigma: report.noise.map(|n| n.sigma),
    }
}

/// Each parameter set's slider values, in slider order.
fn parse_presets(json: &str, sliders: &[&str]) -> Vec<Option<Vec<f64>>> {
    let Ok(doc) = serde_json::from_str::<serde_json::Value>(json) else {
        return vec![None];
    };
    let Some(sets) = doc.get("parameterSets").and_then(|s| s.as_object()) else {
        return vec![None];
    };
    sets.values()
        .map(|set| {
            sliders
                .iter()
                .map(|name| {
                    let v = set.get(*name)?;
                    v.as_f64().or_else(|| v.as_str()?.parse().ok())
                })
                .collect()
        })
        .collect()
}

/// A family through the main job and (with `paper`) the paper's method, or why it could
/// not be run. Without `paper` its scores are the default (no sliders, nothing reached).
pub fn evaluate_family(seed: u64, setup: Setup, paper: bool) -> Result<FamilyResult, String> {
    let case = Case::load(seed, setup, None)?;
    let truth = case.truth();
    let (_, ours) = case.ours();
    let paper = if paper {
        score(&truth, &case.paper(), seed)
    } else {
        Score::default()
    };
    Ok(FamilyResult {
        seed,
        style: case.style,
        parts: case.model.parts.len(),
        sigma: setup.noise * case.family.size,
        ours: score(&truth, &ours, seed),
        paper,
    })
}
