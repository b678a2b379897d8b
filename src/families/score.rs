//! What a user relies on, measured on one family's output: held-out variations reached,
//! contacts and sizes kept at random slider settings, the number of sliders against the
//! family's intent dimension, toggles, presets.
//!
//! A method's output is an [`Output`] (kept rows, the solve, slider ranges, toggles,
//! presets as free values); [`Truth`] is what the generator knows, read back through the
//! loaded model: held-out slot values, the contacts the family's variations share (the
//! input and every exact draw: training, held-out and a dozen more), the parts some
//! training variation drops. Contacts are world boxes that touch or overlap within the
//! model's tolerance.

use crate::analysis::anchors::Anchors;
use crate::analysis::discover::Similarity;
use crate::analysis::optional::optional_parts;
use crate::analysis::project::{Faces, project_onto};
use crate::analysis::ranges::{Range, size_forms};
use crate::analysis::reparam::Solution;
use crate::analysis::similarity::VolumeSimilarity;
use crate::ir::feature::world_intervals;
use crate::ir::{Affine, Model, Num};
use crate::tolerance::Tolerance;

use super::rng::Rng;

/// Held-out variations count as reached at this IoU with their projection.
pub const REACH_IOU: f64 = 0.98;

/// Random slider settings at which coherence is checked.
pub const SETTINGS: usize = 200;

/// What a method made of a family, in the terms the scores need.
#[derive(Debug, Clone)]
pub struct Output {
    pub kept: Vec<Affine>,
    pub solution: Solution,
    pub ranges: Vec<Range>,
    /// Each toggle's parts (model part indices).
    pub toggles: Vec<Vec<usize>>,
    /// Each preset's free values, in slider order (`None`: it does not name every slider).
    pub presets: Vec<Option<Vec<f64>>>,
    /// Each training variation projected onto the kept relations (slot values): what its
    /// preset is before the sliders' box holds it.
    pub projected: Vec<Vec<f64>>,
    pub seconds: f64,
    /// The noise the method estimated (world units), if it estimates one.
    pub sigma: Option<f64>,
}

/// What the generator knows about a family, read on its loaded model.
pub struct Truth<'m> {
    pub model: &'m Model,
    pub d: usize,
    /// Held-out slot values (exact).
    pub held_out: Vec<Vec<f64>>,
    /// Parts some training variation drops.
    pub dropped: Vec<usize>,
    /// Part pairs in contact at the input and in every exact variation of the family drawn
    /// (training, held-out and [`super::Family::contact_draws`]): the family's contacts.
    pub contacts: Vec<(usize, usize)>,
}

/// One method's scores on one family.
#[derive(Debug, Clone, Default)]
pub struct Score {
    pub d: usize,
    pub dimension: usize,
    /// The worst held-out IoU with its projection.
    pub worst_iou: f64,
    /// Settings (of [`SETTINGS`]) that break a contact or a size, and the first break.
    pub broken_settings: usize,
    pub first_break: Option<String>,
    /// Toggles' parts every training variation has.
    pub false_toggles: Vec<usize>,
    /// Dropped parts in no toggle (`None`: no training variation drops a part).
    pub missed_optional: Option<Vec<usize>>,
    /// Why the presets are not valid, if they are not.
    pub bad_preset: Option<String>,
    /// How far the box moved a preset off its projection: the largest change of a number,
    /// as a share of the model's size ([`preset_moved`]).
    pub preset_moved: f64,
    pub seconds: f64,
    /// The noise the method estimated (world units), if it estimates one.
    pub sigma: Option<f64>,
}

impl Score {
    pub fn reached(&self) -> bool {
        self.worst_iou >= REACH_IOU
    }
    pub fn coherent(&self) -> bool {
        self.broken_settings == 0
    }
}

/// Each part's world box at slot values `x` (`None` for a part off the axes).
pub struct Boxes(Vec<Option<[(Num, Num); 3]>>);

fn at(n: &Num, x: &[f64]) -> f64 {
    n.affine().map_or(n.value, |a| a.eval(x))
}

impl Boxes {
    pub fn of(model: &Model) -> Boxes {
        Boxes(model.parts.iter().map(world_intervals).collect())
    }

    pub fn at(&self, x: &[f64]) -> Vec<Option<[(f64, f64); 3]>> {
        self.0
            .iter()
            .map(|b| {
                b.as_ref()
                    .map(|iv| iv.each_ref().map(|(lo, hi)| (at(lo, x), at(hi, x))))
            })
            .collect()
    }
}

/// Whether two boxes touch or overlap, within `eps`.
pub fn touch(a: &[(f64, f64); 3], b: &[(f64, f64); 3], eps: f64) -> bool {
    (0..3).all(|k| a[k].0 <= b[k].1 + eps && b[k].0 <= a[k].1 + eps)
}

/// The part pairs touching in every one of `settings`, leaving out `skip`.
pub fn common_contacts(
    model: &Model,
    settings: &[Vec<f64>],
    skip: &[usize],
) -> Vec<(usize, usize)> {
    let eps = Tolerance::for_size(model.size()).epsilon;
    let boxes = Boxes::of(model);
    let at: Vec<_> = settings.iter().map(|x| boxes.at(x)).collect();
    let n = model.parts.len();
    let mut out = Vec::new();
    for i in 0..n {
        for j in i + 1..n {
            if skip.contains(&i) || skip.contains(&j) {
                continue;
            }
            let all = at.iter().all(|b| match (&b[i], &b[j]) {
                (Some(p), Some(q)) => touch(p, q, eps),
                _ => false,
            });
            if all {
                out.push((i, j));
            }
        }
    }
    out
}

/// Scores `out` against `truth`; `seed` draws the random slider settings.
pub fn score(truth: &Truth, out: &Output, seed: u64) -> Score {
    let model = truth.model;
    let sim = VolumeSimilarity::new(model);
    Score {
        d: truth.d,
        dimension: out.solution.free.len(),
        worst_iou: reach(model, &Anchors::of(model), &sim, &out.kept, &truth.held_out),
        false_toggles: out
            .toggles
            .iter()
            .flatten()
            .copied()
            .filter(|p| !truth.dropped.contains(p))
            .collect(),
        missed_optional: (!truth.dropped.is_empty()).then(|| {
            let on: Vec<usize> = out.toggles.iter().flatten().copied().collect();
            truth
                .dropped
                .iter()
                .copied()
                .filter(|p| !on.contains(p))
                .collect()
        }),
        bad_preset: bad_preset(model, out),
        preset_moved: preset_moved(model, out),
        seconds: out.seconds,
        sigma: out.sigma,
        ..coherence(truth, out, seed)
    }
}

/// The worst IoU of a held-out variation with its projection onto `kept` and its own
/// anchors (parts it does without left out); `anchors` are the model's.
pub fn reach(
    model: &Model,
    anchors: &Anchors,
    sim: &VolumeSimilarity,
    kept: &[Affine],
    held_out: &[Vec<f64>],
) -> f64 {
    let faces = Faces::of(model);
    // Held-out variations are exact: a part is dropped where a zero leaves it out.
    let optional = optional_parts(model, held_out, sim);
    held_out
        .iter()
        .zip(&optional)
        .map(|(v, skip)| {
            let own = anchors.rows_at(v);
            let rows: Vec<&Affine> = kept.iter().chain(own.iter()).collect();
            let p = project_onto(&faces, v, &rows, skip);
            sim.similarity(&p, v, skip)
        })
        .fold(1.0, f64::min)
}

/// Contacts and sizes at random in-range settings: how many settings break one.
fn coherence(truth: &Truth, out: &Output, seed: u64) -> Score {
    let model = truth.model;
    let eps = Tolerance::for_size(model.size()).epsilon;
    let boxes = Boxes::of(model);
    let sizes = size_forms(model);
    let mut rng = Rng::fork(seed, 77);
    let mut broken = 0;
    let mut first = None;
    for _ in 0..SETTINGS {
        let free: Vec<f64> = out.ranges.iter().map(|r| rng.range(r.min, r.max)).collect();
        let x = out.solution.slot_values(&free);
        let why = breaks(model, &boxes, &sizes, &truth.contacts, &x, eps);
        if let Some(w) = why {
            broken += 1;
            first.get_or_insert(w);
        }
    }
    Score {
        broken_settings: broken,
        first_break: first,
        ..Score::default()
    }
}

/// The first contact or size that slot values `x` break, in words.
fn breaks(
    model: &Model,
    boxes: &Boxes,
    sizes: &[Affine],
    contacts: &[(usize, usize)],
    x: &[f64],
    eps: f64,
) -> Option<String> {
    let b = boxes.at(x);
    for &(i, j) in contacts {
        if let (Some(p), Some(q)) = (&b[i], &b[j])
            && !touch(p, q, eps)
        {
            let (a, c) = (&model.parts[i].name, &model.parts[j].name);
            return Some(format!("{a} comes off {c}"));
        }
    }
    sizes
        .iter()
        .find(|s| s.eval(x) <= 0.0)
        .map(|s| format!("a size goes to {:.3}", s.eval(x)))
}

/// A preset counts as held by the box when no number of it moved off its projection by
/// more than this share of the model's size.
pub const PRESET_HELD_SHARE: f64 = 0.01;

/// The largest change of a number between a preset and its variation's projection, as a
/// share of the model's size (0 when there is no projection to compare with).
fn preset_moved(model: &Model, out: &Output) -> f64 {
    let size = model.size();
    out.presets
        .iter()
        .zip(&out.projected)
        .filter_map(|(p, q)| Some((out.solution.slot_values(p.as_ref()?), q)))
        .flat_map(|(x, q)| x.into_iter().zip(q).map(|(a, b)| (a - b).abs() / size))
        .fold(0.0, f64::max)
}

/// Why the presets are invalid: a slider missing, a value outside its range, a size not
/// positive there.
fn bad_preset(model: &Model, out: &Output) -> Option<String> {
    let sizes = size_forms(model);
    for (k, p) in out.presets.iter().enumerate() {
        let Some(free) = p else {
            return Some(format!("preset {k} does not set every slider"));
        };
        for (i, (v, r)) in free.iter().zip(&out.ranges).enumerate() {
            let slack = r.step * 0.5;
            if *v < r.min - slack || *v > r.max + slack {
                return Some(format!(
                    "preset {k} sets slider {i} to {v} outside [{}, {}]",
                    r.min, r.max
                ));
            }
        }
        let x = out.solution.slot_values(free);
        if let Some(s) = sizes.iter().find(|s| s.eval(&x) <= 0.0) {
            return Some(format!("preset {k} makes a size {:.3}", s.eval(&x)));
        }
    }
    None
}
