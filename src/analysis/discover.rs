//! Constraint discovery: which relations of the input do the variations share?
//!
//! The paper's greedy selection (`algorithms.md` §3): from the empty set, score every
//! remaining candidate by projecting each variation's current point onto the chosen set plus
//! that candidate and measuring how similar the projection stays (IoU, or image loss); keep
//! the best (product over variations), drop candidates the chosen rows now imply (rank test),
//! and record the distortion curve against the original variations. The cutoff is decided
//! afterwards (`cutoff`).
//!
//! What keeps it fast on large models without changing its answer: a candidate every
//! variation already satisfies (within the tolerance that decides whether relations hold)
//! scores 1 without a projection, and such candidates are taken together in list order;
//! scoring stops at the first candidate scoring 1 (nothing beats it); candidates equal
//! modulo the chosen rows with equal residuals share one score; cached scores are forgotten
//! only for candidates holding a slot that moved or whose chosen rows changed; implied
//! candidates are looked for only around changed pivots; projections factor only the slot
//! blocks they touch (`project`), and IoU integrates only around the parts that moved.

use super::candidates::Candidates;
use super::chosen::{Chosen, candidates_by_slot, forget, rows_of};
use super::pool::Pool;
use super::precision::Precision;
use super::project::{Faces, Metric, Projector};
use super::rowbasis::RowBasis;
use crate::ir::Affine;
use crate::tolerance::RELATIVE_ROUNDOFF;
use std::collections::{HashMap, HashSet};

/// How alike settings of the model are (1 = identical): IoU, or an image-based measure.
pub trait Similarity: Sync {
    /// What is worth computing once about a reference setting (e.g. its volume).
    type Reference;
    /// Prepares the model at `b` without the `skip` parts as a reference.
    fn reference(&self, b: &[f64], skip: &[usize]) -> Self::Reference;
    /// Between the model at `a` (without the reference's `skip` parts) and the reference.
    fn similarity_to(&self, a: &[f64], reference: &Self::Reference) -> f64;
    /// Between the model at slot values `a` and at `b`, both without the `skip` parts.
    fn similarity(&self, a: &[f64], b: &[f64], skip: &[usize]) -> f64 {
        self.similarity_to(a, &self.reference(b, skip))
    }
    /// [`Similarity::similarity_to`] when `a` differs from the reference's point only in the
    /// `changed` slots (what an implementation may use to look at less of the model).
    fn similarity_changed(&self, a: &[f64], changed: &[u32], reference: &Self::Reference) -> f64 {
        let _ = changed;
        self.similarity_to(a, reference)
    }
    /// Moves the reference to `a`, which differs from its point only in the `changed` slots.
    fn update_reference(&self, reference: &mut Self::Reference, a: &[f64], changed: &[u32]);
    /// How much removing `part` changes the reference (prepared with no part skipped),
    /// relative to the part's own size in the input: 0 when nothing changes (the part is
    /// hidden inside others, or shrunk to nothing), about 1 when all of it shows.
    fn removal_loss(&self, reference: &Self::Reference, part: usize) -> f64;
    /// A lower bound on [`Similarity::removal_loss`], cheap (0: no bound known): a part
    /// it already shows present needs no exact loss.
    fn removal_loss_lower_bound(&self, _reference: &Self::Reference, _part: usize) -> f64 {
        0.0
    }
}

/// The similarity of `current` to the variation `sample` it was moved from, preparing the
/// original as a reference (`original`) the first time it is needed. Only the slots that
/// moved away from the sample are looked at again.
pub fn fidelity<S: Similarity>(
    sim: &S,
    sample: &Sample,
    current: &[f64],
    original: &mut Option<S::Reference>,
) -> f64 {
    let away: Vec<u32> = (0..current.len() as u32)
        .filter(|&s| current[s as usize] != sample.values[s as usize])
        .collect();
    let original = original.get_or_insert_with(|| sim.reference(&sample.values, &sample.optional));
    sim.similarity_changed(current, &away, original)
}

/// One variation as discovery sees it: its slot values and the parts it does without.
#[derive(Debug, Clone)]
pub struct Sample {
    pub values: Vec<f64>,
    pub optional: Vec<usize>,
    /// How much each face counts, for a variation fitted to pictures (`None`: every face
    /// as the noise model says).
    pub precision: Option<Precision>,
}

impl Sample {
    /// A variation whose faces all count alike.
    pub fn new(values: Vec<f64>, optional: Vec<usize>) -> Sample {
        Sample {
            values,
            optional,
            precision: None,
        }
    }

    /// Whether the variation says anything about part `p`: it has the part, and its
    /// pictures show it.
    pub fn sees(&self, p: usize) -> bool {
        !self.optional.contains(&p)
            && self
                .precision
                .as_ref()
                .is_none_or(|pr| !pr.unseen.contains(&p))
    }

    /// The noise model's metric for this variation: the numbers' for a typed one, the faces'
    /// weighed by how well its pictures show them for a fitted one.
    pub fn metric(&self, faces: &Faces) -> Metric {
        match &self.precision {
            Some(p) => faces.face_metric(&self.optional, &p.weights),
            None => faces.number_metric(&self.optional),
        }
    }

    /// The parts the variation says nothing about (those it does not [`Sample::sees`]).
    pub fn unshown(&self) -> Vec<usize> {
        let unseen = self.precision.iter().flat_map(|p| p.unseen.iter().copied());
        self.optional.iter().copied().chain(unseen).collect()
    }
}

/// The greedy order, its scores and the distortion after each step.
#[derive(Debug, Clone)]
pub struct Discovery {
    /// Candidate indices in the order they were chosen.
    pub order: Vec<usize>,
    /// The product of similarities that won each step.
    pub scores: Vec<f64>,
    /// `curve[s]` = 1 − mean similarity of the variations projected onto the first `s`
    /// chosen candidates to the original variations (`curve[0]` = 0).
    pub curve: Vec<f64>,
    /// For each step, the candidates that became implied (dropped by the rank test).
    pub implied: Vec<Vec<usize>>,
    /// The tier of each step's choice (see [`discover`]).
    pub tiers: Vec<u8>,
    /// For each step, the largest loss of similarity it caused in one variation
    /// (1 − similarity of its projection to the previous step's point).
    pub worst: Vec<f64>,
}

/// Whether a point already satisfies every row within `tolerance`, the one that decides
/// whether a relation holds at all: projecting onto them would move it by no more.
fn satisfied(rows: &[&Affine], x: &[f64], tolerance: f64) -> bool {
    rows.iter().all(|r| r.eval(x).abs() <= tolerance)
}

/// One variation during the greedy: where it is, and what projecting it needs.
struct Variation<'a, R> {
    sample: &'a Sample,
    projector: Projector,
    current: Vec<f64>,
    /// The current point prepared as a reference (made when a projection first needs it).
    reference: Option<R>,
    /// The original variation prepared as a reference (made when it first moves).
    original: Option<R>,
    /// Similarity of the current point to the original variation.
    fidelity: f64,
}

impl<'a, R> Variation<'a, R> {
    /// A variation at its own values, before any relation is chosen.
    fn start(sample: &'a Sample, faces: &Faces) -> Self {
        Variation {
            sample,
            projector: Projector::new(faces.metric(&sample.values, &sample.optional)),
            current: sample.values.clone(),
            reference: None,
            original: None,
            fidelity: 1.0,
        }
    }
}

impl Discovery {
    /// No step yet: the curve starts at 0.
    fn start() -> Discovery {
        Discovery {
            order: Vec::new(),
            scores: Vec::new(),
            curve: vec![0.0],
            implied: Vec::new(),
            tiers: Vec::new(),
            worst: Vec::new(),
        }
    }

    /// Records a step: candidate `c` chosen with `score` in `tier`, its worst loss, and the
    /// curve's value after it (the candidates it made implied follow).
    fn push_step(&mut self, c: usize, score: f64, tier: u8, worst: f64, curve: f64) {
        self.order.push(c);
        self.scores.push(score);
        self.tiers.push(tier);
        self.worst.push(worst);
        self.curve.push(curve);
        self.implied.push(Vec::new());
    }
}

/// Moves every variation onto the chosen rows plus `rows`, updating its prepared reference
/// and its fidelity to the original. Returns the slots to look at again (`rows`' own and
/// those moved beyond `roundoff`) and every slot that moved at all.
fn move_variations<S: Similarity>(
    vars: &mut [Variation<'_, S::Reference>],
    faces: &Faces,
    chosen: &mut Chosen,
    rows: &[&Affine],
    sim: &S,
    roundoff: f64,
) -> (HashSet<u32>, HashSet<u32>) {
    let mut dirty: HashSet<u32> = rows.iter().flat_map(|r| r.slots()).collect();
    let mut moved_any: HashSet<u32> = HashSet::new();
    for v in vars.iter_mut() {
        let (shift, _) = chosen.shift(&mut v.projector, faces, &v.current, rows);
        let mut moved: Vec<u32> = Vec::new();
        for (s, delta) in shift {
            v.current[s as usize] += delta;
            moved_any.insert(s);
            if delta.abs() > roundoff {
                dirty.insert(s);
                moved.push(s);
            }
        }
        if !moved.is_empty() {
            if let Some(r) = v.reference.as_mut() {
                sim.update_reference(r, &v.current, &moved);
            }
            v.fidelity = fidelity(sim, v.sample, &v.current, &mut v.original);
        }
    }
    (dirty, moved_any)
}

/// Runs the greedy selection to the end (every candidate chosen or implied).
///
/// `tiers[c]` ranks candidate `c` by prior plausibility (0 first): each step takes the best
/// score among the remaining candidates of the lowest tier, so a relation the variations
/// break beyond their noise (`noise`) waits until every plausible one is taken, whatever its
/// IoU. With every tier equal this is the paper's greedy.
///
/// A candidate every variation already satisfies scores 1 (nothing moves), the best there
/// is: such candidates are taken together, in list order, which is the order the greedy
/// would take them one by one, without scoring the rest in between.
pub fn discover<S: Similarity>(
    faces: &Faces,
    candidates: &Candidates,
    samples: &[Sample],
    slots: usize,
    sim: &S,
    tiers: &[u8],
) -> Discovery {
    debug_assert_eq!(faces.slots(), slots);
    let mut chosen = Chosen::new(faces);
    let mut pool = Pool::new(tiers, |i| !chosen.implies(&rows_of(candidates, i)));
    let by_slot = candidates_by_slot(candidates, slots);
    let mut vars: Vec<Variation<'_, S::Reference>> =
        samples.iter().map(|s| Variation::start(s, faces)).collect();
    let mut out = Discovery::start();
    let bounds = Bounds::of(samples, candidates);
    let holds = bounds.holds;
    // Per candidate, each variation's similarity after projecting onto it (1 when the
    // variation already satisfies it); the score is their product.
    // Scores of candidates away from what moved are kept (algorithms.md §3): an entry is
    // forgotten when a slot of the candidate moves or the chosen rows change around it.
    let mut cache: Vec<Option<Vec<f64>>> = vec![None; candidates.list.len()];
    // Whether every variation satisfies the candidate (then it scores 1 without a projection).
    let exact_now = |c: usize, vars: &[Variation<'_, S::Reference>]| {
        let rows = rows_of(candidates, c);
        vars.iter().all(|v| satisfied(&rows, &v.current, holds))
    };
    for c in 0..candidates.list.len() {
        if pool.is_alive(c) && exact_now(c, &vars) {
            pool.set_exact(c, true);
        }
    }
    while let Some(tier) = pool.lowest_tier().filter(|_| !samples.is_empty()) {
        let batch = pool.exact_in(tier);
        let mut gone: Vec<usize> = Vec::new();
        if !batch.is_empty() {
            for c in batch {
                let rows = rows_of(candidates, c);
                pool.kill(c);
                if chosen.implies(&rows) {
                    gone.push(c);
                    continue;
                }
                chosen.add(&rows, &mut projectors(&mut vars));
                forget(&mut cache, &by_slot, rows.iter().flat_map(|r| r.slots()));
                let same = *out.curve.last().unwrap_or(&0.0);
                out.push_step(c, 1.0, tier, 0.0, same);
            }
        } else {
            let Some((score, c)) = best_candidate(
                faces,
                candidates,
                tier,
                &mut pool,
                &mut vars,
                &mut chosen,
                sim,
                bounds,
                &mut cache,
            ) else {
                break;
            };
            let rows = rows_of(candidates, c);
            let sims = cache[c].take().unwrap_or_default();
            let (dirty, moved_any) =
                move_variations(&mut vars, faces, &mut chosen, &rows, sim, bounds.roundoff);
            for &s in &moved_any {
                for &k in &by_slot[s as usize] {
                    let k = k as usize;
                    if pool.is_alive(k) {
                        pool.set_exact(k, exact_now(k, &vars));
                    }
                }
            }
            forget(&mut cache, &by_slot, dirty);
            let worst = sims.iter().fold(0.0, |w, s| f64::max(w, 1.0 - s));
            chosen.add(&rows, &mut projectors(&mut vars));
            pool.kill(c);
            let mean = vars.iter().map(|v| v.fidelity).sum::<f64>() / vars.len() as f64;
            out.push_step(c, score, tier, worst, 1.0 - mean);
        }
        chosen.refresh_members();
        chosen.drop_implied(candidates, &by_slot, &mut pool, &mut gone);
        gone.sort_unstable();
        if let Some(last) = out.implied.last_mut() {
            *last = gone;
        }
    }
    out
}

/// Every variation's projector, for [`Chosen::add`].
fn projectors<'v, R>(vars: &'v mut [Variation<'_, R>]) -> Vec<&'v mut Projector> {
    vars.iter_mut().map(|v| &mut v.projector).collect()
}

/// What counts as no change (a move or residual below the round-off of the model's numbers)
/// and as a relation holding (ε, at least the round-off).
#[derive(Debug, Clone, Copy)]
struct Bounds {
    roundoff: f64,
    holds: f64,
}

impl Bounds {
    /// The round-off of the variations' largest number, and the tolerance a relation holds
    /// within (the candidates' own, never below that round-off).
    fn of(samples: &[Sample], candidates: &Candidates) -> Bounds {
        let scale = samples
            .iter()
            .flat_map(|s| s.values.iter())
            .fold(1.0f64, |m, v| m.max(v.abs()));
        Bounds {
            roundoff: RELATIVE_ROUNDOFF * scale,
            holds: candidates.tolerance.epsilon.max(RELATIVE_ROUNDOFF * scale),
        }
    }
}

/// Scores the remaining candidates of `tier` (reusing cached scores) and returns the best:
/// (score, candidate), the first in list order among equals. Similarities are at most 1, so
/// the first candidate scoring 1 is the answer and the rest need no scoring.
#[allow(clippy::too_many_arguments)]
fn best_candidate<S: Similarity>(
    faces: &Faces,
    candidates: &Candidates,
    tier: u8,
    pool: &mut Pool,
    vars: &mut [Variation<'_, S::Reference>],
    chosen: &mut Chosen,
    sim: &S,
    bounds: Bounds,
    cache: &mut [Option<Vec<f64>>],
) -> Option<(f64, usize)> {
    let mut best: Option<(f64, usize)> = None;
    // Candidates equal modulo the chosen rows, with equal residuals, project every variation
    // to the same point: they are scored once.
    let mut by_class: HashMap<Vec<i64>, Vec<f64>> = HashMap::new();
    for c in pool.members(tier) {
        if cache[c].is_none() {
            let rows = rows_of(candidates, c);
            let class = projection_class(&chosen.basis, &rows, vars, bounds.roundoff);
            let sims = match class.as_ref().and_then(|k| by_class.get(k)) {
                Some(sims) => sims.clone(),
                None => {
                    let sims = similarities(faces, vars, chosen, sim, bounds, &rows);
                    if let Some(k) = class {
                        by_class.insert(k, sims.clone());
                    }
                    sims
                }
            };
            cache[c] = Some(sims);
        }
        let score: f64 = cache[c].iter().flatten().product();
        if best.is_none_or(|(b, _)| score > b) {
            best = Some((score, c));
        }
        if score >= 1.0 {
            break;
        }
    }
    best
}

/// Each variation's similarity after projecting it onto the chosen rows plus `rows`.
fn similarities<S: Similarity>(
    faces: &Faces,
    vars: &mut [Variation<'_, S::Reference>],
    chosen: &mut Chosen,
    sim: &S,
    bounds: Bounds,
    rows: &[&Affine],
) -> Vec<f64> {
    let Bounds { roundoff, holds } = bounds;
    let mut sims = Vec::with_capacity(vars.len());
    for v in vars.iter_mut() {
        if satisfied(rows, &v.current, holds) {
            sims.push(1.0);
            continue;
        }
        let (shift, _) = chosen.shift(&mut v.projector, faces, &v.current, rows);
        // A variation that already satisfies the candidate does not move.
        if shift.iter().all(|(_, d)| d.abs() <= roundoff) {
            sims.push(1.0);
            continue;
        }
        let mut y = v.current.clone();
        // Moves below round-off of the model's numbers change no volume worth integrating:
        // only parts with a slot moved beyond it are measured again.
        let changed: Vec<u32> = shift
            .iter()
            .filter(|(_, d)| d.abs() > roundoff)
            .map(|&(s, _)| s)
            .collect();
        for (s, d) in shift {
            y[s as usize] += d;
        }
        let reference = v
            .reference
            .get_or_insert_with(|| sim.reference(&v.current, &v.sample.optional));
        sims.push(sim.similarity_changed(&y, &changed, reference));
    }
    sims
}

/// A key shared by candidates whose projections coincide: each row reduced modulo the chosen
/// rows and scaled to a largest coefficient of 1, with its residual at every variation's
/// point, all quantised far below what changes a projection. `None` when a number does not
/// fit a key (then the candidate is scored on its own).
fn projection_class<R>(
    basis: &RowBasis,
    rows: &[&Affine],
    vars: &[Variation<'_, R>],
    roundoff: f64,
) -> Option<Vec<i64>> {
    let quantum = |v: f64, unit: f64| -> Option<i64> {
        let q = (v / unit).round();
        (q.is_finite() && q.abs() < 9e15).then_some(q as i64)
    };
    let mut key = Vec::new();
    for r in rows {
        let reduced = basis.reduced(&r.terms);
        let Some(&(_, lead)) = reduced
            .iter()
            .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()).then(b.0.cmp(&a.0)))
        else {
            key.push(-1);
            continue;
        };
        key.push(reduced.len() as i64);
        for &(s, a) in &reduced {
            key.push(i64::from(s));
            key.push(quantum(a / lead, RELATIVE_ROUNDOFF)?);
        }
        for v in vars {
            key.push(quantum(r.eval(&v.current) / lead, roundoff)?);
        }
    }
    Some(key)
}
