//! The quality benchmark of the main job (our Table 1), shared by `tests/quality.rs`
//! (which asserts it) and `benches/quality.rs` (which prints it).
//!
//! For each of the paper's five models and its five hand-made variations
//! (`examples/variations/paper_<model>/`): add Gaussian noise of 1% of the model's size (in
//! world units: a slot's noise is divided by how strongly it moves faces), run discovery on
//! the noisy set, and check that every clean variation stays reachable (its projection onto
//! the kept relations has IoU ≥ 0.98 with it) with a dimension at most one above the clean
//! truth (the null space of the relations every clean variation keeps, plus the anchors).

#![allow(dead_code)]

use reparamc::analysis::anchors::Anchors;
use reparamc::analysis::discover::Similarity;
use reparamc::analysis::optional::optional_parts;
use reparamc::analysis::project::{Faces, project_onto};
use reparamc::analysis::similarity::VolumeSimilarity;
use reparamc::analysis::{find_candidates, linalg};
use reparamc::command::compile::{Options, reparameterize};
use reparamc::front::source::SourceMap;
use reparamc::ir::Affine;
use reparamc::ir::feature::world_intervals;
use reparamc::variation::{Variation, load_variation};
use std::path::PathBuf;

pub const MODELS: [&str; 5] = ["chair", "table", "car", "camera", "bottle"];

#[derive(Debug, Clone)]
pub struct Row {
    pub model: String,
    pub parameters: usize,
    pub base_constraints: usize,
    pub chosen: usize,
    pub dimension: usize,
    pub clean_dimension: usize,
    /// The worst IoU of a clean variation with its projection onto the kept relations.
    pub reachability: f64,
    pub cutoff_step: usize,
}

struct Rng(u64);

impl Rng {
    fn uniform(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        ((self.0 >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }

    /// A standard normal sample (Box–Muller).
    fn normal(&mut self) -> f64 {
        let (u, v) = (self.uniform(), self.uniform());
        (-2.0 * u.ln()).sqrt() * (2.0 * std::f64::consts::PI * v).cos()
    }
}

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// How far each slot moves faces per unit (the largest coefficient over all face forms).
fn leverage(model: &reparamc::ir::Model) -> Vec<f64> {
    let mut lev = vec![0.0f64; model.slots.len()];
    for p in &model.parts {
        let Some(iv) = world_intervals(p) else {
            continue;
        };
        for (lo, hi) in iv.iter() {
            for n in [lo, hi] {
                if let Some(a) = n.affine() {
                    for &(s, c) in &a.terms {
                        lev[s as usize] = lev[s as usize].max(c.abs());
                    }
                }
            }
        }
    }
    lev
}

pub fn evaluate(name: &str, seed: u64) -> Row {
    let path = repo().join(format!("examples/paper/{name}.scad"));
    let mut sources = SourceMap::new();
    let (loaded, evaluated) =
        reparamc::load_model_parsed(&mut sources, &path).expect("model loads");
    let model = evaluated.model;
    let dir = format!("examples/variations/paper_{name}");
    let mut files: Vec<PathBuf> = std::fs::read_dir(repo().join(&dir))
        .expect("variations exist")
        .map(|e| e.unwrap().path())
        .collect();
    files.sort();
    let clean: Vec<Variation> = files
        .iter()
        .map(|f| load_variation(&mut sources, loaded.main, &model, f).expect("variation matches"))
        .collect();
    let size = model.size();
    let lev = leverage(&model);
    let mut rng = Rng(seed);
    let noisy: Vec<Variation> = clean
        .iter()
        .map(|v| Variation {
            name: v.name.clone(),
            uncertainty: None,
            values: v
                .values
                .iter()
                .enumerate()
                .map(|(s, &x)| {
                    let sigma = if lev[s] > 0.0 {
                        0.01 * size / lev[s]
                    } else {
                        0.01 * x.abs()
                    };
                    // A part a variation does without (zero size) stays without.
                    if x == 0.0 && !model.slots[s].position {
                        x
                    } else {
                        x + sigma * rng.normal()
                    }
                })
                .collect(),
        })
        .collect();
    // The trace prints the distortion curve, which is measured only when asked for.
    let options = Options {
        measure: std::env::var_os("TABLE1_TRACE").is_some(),
        ..Options::default()
    };
    let compiled = reparameterize(&sources, &loaded, &model, &noisy, &options);
    let candidates = find_candidates(&model);
    let sim = VolumeSimilarity::new(&model);
    let clean_values: Vec<Vec<f64>> = clean.iter().map(|v| v.values.clone()).collect();
    let optional = optional_parts(&model, &clean_values, &sim);
    let tol = 1e-6 * size;
    // The clean truth: relations every clean variation keeps (ignoring parts it does without).
    let common: Vec<&Affine> = candidates
        .list
        .iter()
        .filter(|c| {
            clean_values.iter().zip(&optional).all(|(v, skip)| {
                let parts = [candidates.features[c.a].part, candidates.features[c.b].part];
                parts.iter().any(|p| skip.contains(p))
                    || c.rows.iter().all(|r| r.eval(v).abs() <= tol)
            })
        })
        .flat_map(|c| c.rows.iter())
        .collect();
    let pins = Anchors::of(&model);
    let anchors = pins.rows();
    let mut truth = common.clone();
    truth.extend(anchors.iter());
    let clean_dimension = linalg::nullity(&truth, model.slots.len());
    let faces = Faces::of(&model);
    let reach = |kept: &[&Affine]| {
        clean_values
            .iter()
            .zip(&optional)
            .map(|(v, skip)| {
                let own = pins.rows_at(v);
                let rows: Vec<&Affine> = kept.iter().copied().chain(own.iter()).collect();
                let p = project_onto(&faces, v, &rows, skip);
                sim.similarity(&p, v, skip)
            })
            .fold(1.0, f64::min)
    };
    let kept: Vec<&Affine> = compiled.kept.iter().flat_map(|c| c.rows.iter()).collect();
    let reachability = reach(&kept);
    if std::env::var_os("TABLE1_TRACE").is_some() {
        trace(
            &compiled,
            &candidates,
            &clean_values,
            &optional,
            tol,
            &reach,
        );
    }
    Row {
        model: name.to_string(),
        parameters: model.slots.len(),
        base_constraints: candidates.total(),
        chosen: compiled.kept.len(),
        dimension: compiled.solution.free.len(),
        clean_dimension,
        reachability,
        cutoff_step: compiled.report.cutoff.as_ref().map_or(0, |c| c.keep),
    }
}

/// Prints every greedy step: whether the clean variations keep the relation, its residual in
/// the noisy ones, the step's worst loss and the curve (for studying the cutoff).
fn trace(
    compiled: &reparamc::command::compile::Compiled,
    candidates: &reparamc::analysis::candidates::Candidates,
    clean: &[Vec<f64>],
    optional: &[Vec<usize>],
    tol: f64,
    reach: &dyn Fn(&[&Affine]) -> f64,
) {
    let r = &compiled.report;
    if let Some(g) = &r.noise {
        eprintln!(
            "{}: noise sigma {:.4} (pooled over {} relations), critical z {:.2}",
            r.model, g.sigma, g.pooled, g.critical_z
        );
    }
    if let Some(c) = &r.cutoff {
        eprintln!(
            "cutoff keep {} paper {} published {}: {}",
            c.keep, c.paper, c.published, c.reason
        );
    }
    let by_text: std::collections::HashMap<String, usize> = candidates
        .list
        .iter()
        .enumerate()
        .map(|(i, c)| (candidates.describe(c), i))
        .collect();
    let mut prefix: Vec<&Affine> = Vec::new();
    for (s, ch) in r.chosen.iter().enumerate() {
        if let Some(&i) = by_text.get(&ch.relation) {
            prefix.extend(candidates.list[i].rows.iter());
        }
        let clean_residual = by_text.get(&ch.relation).map_or(0.0, |&i| {
            let c = &candidates.list[i];
            clean
                .iter()
                .flat_map(|v| c.rows.iter().map(|row| row.eval(v).abs()))
                .fold(0.0, f64::max)
        });
        let truth = by_text.get(&ch.relation).map(|&i| {
            let c = &candidates.list[i];
            let parts = [candidates.features[c.a].part, candidates.features[c.b].part];
            clean.iter().zip(optional).all(|(v, skip)| {
                parts.iter().any(|p| skip.contains(p))
                    || c.rows.iter().all(|row| row.eval(v).abs() <= tol)
            })
        });
        eprintln!(
            "{:>3} {:<6} {:<12} res {:>8.4} clean {:>8.4} curve {:>8.5} reach {:.4}  {}",
            s + 1,
            match truth {
                Some(true) => "true",
                Some(false) => "FALSE",
                None => "?",
            },
            ch.z.map_or(String::new(), |z| format!("z {z:.2}")),
            ch.residual.unwrap_or(0.0),
            clean_residual,
            r.distortion_curve[s + 1],
            reach(&prefix),
            ch.relation
        );
    }
}

pub fn table(rows: &[Row]) -> String {
    let mut s = String::from(
        "| model | parameters | base constraints | chosen | dimension | clean dimension | reachability (min IoU) | cutoff step |\n|---|---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        s.push_str(&format!(
            "| {} | {} | {} | {} | {} | {} | {:.4} | {} |\n",
            r.model,
            r.parameters,
            r.base_constraints,
            r.chosen,
            r.dimension,
            r.clean_dimension,
            r.reachability,
            r.cutoff_step
        ));
    }
    s
}
