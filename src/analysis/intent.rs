//! Which relations are intent: discovery as one sequential test against the noise model.
//!
//! Every candidate's evidence is what projecting the variations onto it costs in the noise
//! model's metric (`noise`): the squared displacement that makes it hold, summed over
//! the variations that keep both its parts. The noise `σ` is estimated from that evidence,
//! and so is how often each class of relation is intent (`classes`). A candidate's log
//! posterior odds of being intent are its class's prior odds plus its evidence's likelihood
//! ratio (noise against a change of unknown scale). Step by step, the candidate most likely
//! intent is taken and every variation is moved onto it, so later evidence is measured from
//! points that satisfy everything taken before: a chain of relations that are each within
//! the noise but together are not stops where the chain breaks. The first step whose odds
//! are not in favour is the cutoff; steps go on past it only to draw the distortion curve
//! (1 − mean IoU of the moved variations to the originals) for the report, and the paper's
//! change points on that curve are reported beside the test's answer.
//!
//! What keeps it fast: candidates every variation already satisfies (within the tolerance
//! relations hold within) are taken together without scoring; a candidate's evidence is
//! scored again only when a slot of it moved or a row was chosen on one of its slots, and
//! the best one is always scored afresh before it is taken; projections factor only the
//! slot blocks they touch (`project`).

use super::candidates::Candidates;
use super::chosen::{Chosen, candidates_by_slot, forget, rows_of};
use super::classes::prior_log_odds;
use super::discover::{Sample, Similarity, fidelity};
use super::noise::{Evidence, LikelihoodRatio, NoiseModel, figures};
use super::pool::Pool;
use super::project::{Faces, Projection, Projector, RowCosts};
use super::rowbasis::RowBasis;
use crate::ir::{Affine, Model, SlotId};
use crate::tolerance::{NOISE_CANCELLATION_SHARE, RELATIVE_ROUNDOFF, Tolerance, noise_ceiling};

/// The order the test took the candidates in, its statistics and its answer.
#[derive(Debug, Clone)]
pub struct Selection {
    /// Candidate indices in the order taken.
    pub order: Vec<usize>,
    /// Each step's χ² statistic in standard normal units (how far the variations are from
    /// keeping it, against their noise).
    pub z: Vec<f64>,
    /// Each step's log posterior odds that it is intent (positive: intent).
    pub log_odds: Vec<f64>,
    /// `curve[s]` = 1 − mean IoU of the variations moved onto the first `s` steps to the
    /// originals (`curve[0]` = 0); empty when no similarity was given to measure it.
    pub curve: Vec<f64>,
    /// For each step, the candidates that became implied.
    pub implied: Vec<Vec<usize>>,
    /// The first `accepted` steps are intent.
    pub accepted: usize,
    pub noise: NoiseModel,
    /// Per candidate: its largest residual over the variations that keep both its parts
    /// (world units).
    pub residual: Vec<f64>,
}

/// One variation during the selection: where it is and which projector is its own.
struct Point<'a, R> {
    sample: &'a Sample,
    /// Its projector among the selection's: variations that do without the same parts share
    /// the noise metric, so they share one projector and each projection is made once.
    group: usize,
    current: Vec<f64>,
    /// The original variation prepared for IoU (made when it first moves).
    original: Option<R>,
    fidelity: f64,
}

/// What a selection step looks at: the model's faces, the candidates and what is fixed
/// about them for the whole selection.
struct Context<'a> {
    faces: &'a Faces,
    candidates: &'a Candidates,
    by_slot: Vec<Vec<u32>>,
    /// Per candidate, per variation: whether the variation keeps both its parts.
    seen: Vec<Vec<bool>>,
    /// Per candidate: its degrees of freedom (independent moving rows × variations that
    /// keep both parts, [`noisy_rows`]).
    dof: Vec<usize>,
    /// Moves below this are round-off; residuals below `holds` mean the relation holds.
    roundoff: f64,
    holds: f64,
    /// Per candidate: the log prior odds that it is intent (its class's learned share).
    prior: Vec<f64>,
    /// The model's size: the largest residual scale a broken relation may have.
    size: f64,
    /// The input's slot values, from which the variations' changes are measured.
    input: Vec<f64>,
}

impl Context<'_> {
    /// Whether every variation that keeps the candidate's parts satisfies it already (for a
    /// candidate no variation speaks of: whether the prior keeps it).
    fn exact<R>(&self, c: usize, points: &[Point<'_, R>]) -> bool {
        if self.dof[c] == 0 {
            return self.prior[c] > 0.0;
        }
        let rows = rows_of(self.candidates, c);
        points
            .iter()
            .zip(&self.seen[c])
            .filter(|(_, seen)| **seen)
            .all(|(p, _)| rows.iter().all(|r| r.eval(&p.current).abs() <= self.holds))
    }

    /// The candidate's evidence at the variations' current points.
    fn evidence<R>(
        &self,
        c: usize,
        points: &[Point<'_, R>],
        projectors: &mut [Projector],
        chosen: &mut Chosen,
    ) -> Evidence {
        let rows = rows_of(self.candidates, c);
        let mut made: Vec<Option<RowCosts>> = projectors.iter().map(|_| None).collect();
        let (mut cost, mut change) = (0.0, 0.0);
        for (p, &seen) in points.iter().zip(&self.seen[c]) {
            if seen {
                let projector = &mut projectors[p.group];
                let costs =
                    made[p.group].get_or_insert_with(|| chosen.costs(projector, self.faces, &rows));
                cost += costs.cost_at(&p.current, &rows);
                let terms: Vec<f64> = rows
                    .iter()
                    .map(|r| terms_change(r, &p.current, &self.input))
                    .collect();
                change += costs.cost(&terms);
            }
        }
        Evidence {
            cost,
            dof: self.dof[c],
            change,
        }
    }
}

/// The scores kept between steps: each candidate's evidence, the step it was scored at,
/// and its log odds with the evidence they were worked out from.
struct Scores {
    evidence: Vec<Option<Evidence>>,
    scored_at: Vec<usize>,
    odds: Vec<Option<(Evidence, f64)>>,
}

impl Scores {
    /// Candidate `c`'s log posterior odds at its evidence (`None` without evidence),
    /// worked out again only when the evidence changed.
    fn odds(&mut self, cx: &Context<'_>, ratio: &LikelihoodRatio, c: usize) -> Option<f64> {
        let e = self.evidence[c]?;
        match self.odds[c] {
            Some((seen, odds)) if seen == e => Some(odds),
            _ => {
                let odds = log_odds(cx, ratio, c, e);
                self.odds[c] = Some((e, odds));
                Some(odds)
            }
        }
    }
}

/// The evidence that can tell the noise. A relation whose slots every variation leaves at
/// the input's values (numbers no one changed, noised or not) is kept exactly whatever `σ`
/// is, and pooling it would pull the estimate to the floor. And the variations tell their
/// noise only if some relation they move cancels most of its numbers' own changes in every
/// variation (`NOISE_CANCELLATION_SHARE`): that is what an intent relation under noise
/// looks like.
/// Where none does (every number of the model varies apart), every relation they move is
/// a change of design, and pooling them would make those changes pass for the noise:
/// nothing is pooled, and `σ` stays at the floor.
///
/// Returns the evidence to pool and, of it, the relations that cancel (the tellers).
fn informative(
    cx: &Context<'_>,
    input: &[f64],
    samples: &[Sample],
    evidence: &[Evidence],
) -> (Vec<Evidence>, Vec<Evidence>) {
    let Some(first) = samples.first() else {
        return (Vec::new(), Vec::new());
    };
    let moved: Vec<bool> = (0..first.values.len())
        .map(|s| samples.iter().any(|v| v.values[s] != first.values[s]))
        .collect();
    let moving: Vec<usize> = (0..cx.candidates.list.len())
        .filter(|&c| {
            rows_of(cx.candidates, c)
                .iter()
                .any(|r| r.slots().any(|s| moved[s as usize]))
        })
        .collect();
    let tells: Vec<bool> = moving
        .iter()
        .map(|&c| cancels(&rows_of(cx.candidates, c), input, samples, &cx.seen[c]))
        .collect();
    if !tells.contains(&true) {
        return (Vec::new(), Vec::new());
    }
    // A number no variation moved carries no noise: rows over such numbers add none.
    let pooled: Vec<Evidence> = moving
        .into_iter()
        .map(|c| {
            let seen = cx.seen[c].iter().filter(|s| **s).count();
            let rows = rows_of(cx.candidates, c);
            let dof = noisy_rows(rows.iter().copied(), |s| moved[s as usize]) * seen;
            Evidence { dof, ..evidence[c] }
        })
        .collect();
    let tellers = pooled
        .iter()
        .zip(&tells)
        .filter(|(_, t)| **t)
        .map(|(e, _)| *e)
        .collect();
    (pooled, tellers)
}

/// How far a row's terms moved from the `input` at `x`, as one residual: the root sum of
/// squares of each term's change (what the row would be off by had they not cancelled).
fn terms_change(row: &Affine, x: &[f64], input: &[f64]) -> f64 {
    row.terms
        .iter()
        .map(|&(s, a)| (a * (x[s as usize] - input[s as usize])).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// Whether `rows`' residuals cancel most of their terms' changes from the `input` in every
/// variation that keeps their parts (`seen`), and some variation keeps them. An intent
/// relation under noise cancels in each variation that moves its numbers by more than the
/// noise; a broken one may cancel in one by chance (its terms moved alike), but in every one
/// only by a chance as small as the product. Among hundreds of candidates, one summed over
/// the variations cancelling by chance is likely, and it made the noise "told" in families
/// whose every number varies apart.
fn cancels(rows: &[&Affine], input: &[f64], samples: &[Sample], seen: &[bool]) -> bool {
    let mut kept = samples.iter().zip(seen).filter(|(_, s)| **s).peekable();
    kept.peek().is_some()
        && kept.all(|(v, _)| {
            let (mut residual, mut change) = (0.0, 0.0);
            for r in rows {
                residual += (r.eval(&v.values) - r.eval(input)).powi(2);
                change += terms_change(r, &v.values, input).powi(2);
            }
            residual <= NOISE_CANCELLATION_SHARE * change
        })
}

/// Every variation at its own values, and one projector in the noise model's metric per
/// set of parts variations do without; a variation with a precision of its own (fitted to
/// pictures) has its own projector.
fn start_points<'a, R>(
    faces: &Faces,
    samples: &'a [Sample],
) -> (Vec<Point<'a, R>>, Vec<Projector>) {
    let mut sets: Vec<Option<&[usize]>> = Vec::new();
    let mut projectors = Vec::new();
    let points = samples
        .iter()
        .map(|s| {
            // Typed variations doing without the same parts share a metric.
            let key = s.precision.is_none().then_some(s.optional.as_slice());
            let group = sets
                .iter()
                .position(|o| key.is_some() && *o == key)
                .unwrap_or_else(|| {
                    sets.push(key);
                    projectors.push(Projector::new(s.metric(faces)));
                    sets.len() - 1
                });
            Point {
                sample: s,
                group,
                current: s.values.clone(),
                original: None,
                fidelity: 1.0,
            }
        })
        .collect();
    (points, projectors)
}

/// Runs the test to the end (every candidate taken or implied). With `sim`, the distortion
/// curve is measured along the way (exact IoU after every step, most of the time taken);
/// the decisions do not depend on it. `step` is told, before the first step and after each,
/// how many candidates are decided (taken or implied) of how many there are; the last call
/// is `(n, n)`.
pub fn select<S: Similarity>(
    model: &Model,
    faces: &Faces,
    candidates: &Candidates,
    samples: &[Sample],
    sim: Option<&S>,
    step: &mut dyn FnMut(usize, usize),
) -> Selection {
    let n = candidates.list.len();
    let floor = Tolerance::for_size(model.size()).epsilon;
    let mut cx = context(faces, candidates, samples);
    cx.size = model.size();
    cx.input = model.slot_values();
    let mut chosen = Chosen::new(faces);
    let mut pool = Pool::new(&vec![0; n], |i| !chosen.implies(&rows_of(candidates, i)));
    let (mut points, mut projectors) = start_points::<S::Reference>(faces, samples);
    let mut scores = first_scores(&cx, &pool, &points, &mut projectors, &mut chosen);
    let all: Vec<Evidence> = (0..n)
        .map(|c| scores.evidence[c].unwrap_or(Evidence::new(0.0, 0)))
        .collect();
    let ceiling = noise_ceiling(model.size());
    let (pooled, tellers) = informative(&cx, &cx.input, samples, &all);
    let noise = NoiseModel::estimate_told(&pooled, &tellers, floor, ceiling);
    cx.prior = prior_log_odds(model, candidates, &all, &noise, cx.size);
    let ratio = noise.likelihood_ratio(cx.size);
    let mut out = Selection {
        order: Vec::new(),
        z: Vec::new(),
        log_odds: Vec::new(),
        curve: if sim.is_some() { vec![0.0] } else { Vec::new() },
        implied: Vec::new(),
        accepted: 0,
        noise,
        residual: (0..n).map(|c| largest_residual(&cx, c, samples)).collect(),
    };
    let mut cut: Option<usize> = None;
    let mut exact: Vec<bool> = (0..n)
        .map(|c| pool.is_alive(c) && cx.exact(c, &points))
        .collect();
    step(n - pool.alive_count(), n);
    while pool.lowest_tier().is_some() && !samples.is_empty() {
        let at = out.order.len() + 1;
        let mut gone = Vec::new();
        let batch: Vec<usize> = (0..n).filter(|&c| pool.is_alive(c) && exact[c]).collect();
        if !batch.is_empty() {
            for c in batch {
                pool.kill(c);
                let rows = rows_of(candidates, c);
                if chosen.implies(&rows) {
                    gone.push(c);
                    continue;
                }
                chosen.add(&rows, &mut each(&mut projectors));
                forget(&mut scores.evidence, &cx.by_slot, slots_of(&rows));
                let same = out.curve.last().copied();
                out.push(c, f64::NEG_INFINITY, f64::INFINITY, same);
            }
        } else {
            let mut state = State {
                points: &mut points,
                projectors: &mut projectors,
                chosen: &mut chosen,
            };
            let Some((c, odds, z)) = best(
                &cx,
                (&noise, &ratio),
                &mut pool,
                &mut state,
                &mut scores,
                at,
            ) else {
                break;
            };
            if odds <= 0.0 && cut.is_none() {
                cut = Some(out.order.len());
            }
            let rows = rows_of(candidates, c);
            let moved = move_points(&cx, &mut state, &rows, sim);
            for &s in &moved {
                for &k in &cx.by_slot[s as usize] {
                    let k = k as usize;
                    exact[k] = pool.is_alive(k) && cx.exact(k, &points);
                }
            }
            forget(
                &mut scores.evidence,
                &cx.by_slot,
                moved.into_iter().chain(slots_of(&rows)),
            );
            chosen.add(&rows, &mut each(&mut projectors));
            pool.kill(c);
            let mean = points.iter().map(|p| p.fidelity).sum::<f64>() / points.len() as f64;
            out.push(c, z, odds, sim.map(|_| 1.0 - mean));
        }
        chosen.refresh_members();
        chosen.drop_implied(candidates, &cx.by_slot, &mut pool, &mut gone);
        gone.sort_unstable();
        if let Some(last) = out.implied.last_mut() {
            last.extend(gone);
        }
        step(n - pool.alive_count(), n);
    }
    step(n, n);
    out.accepted = cut.unwrap_or(out.order.len());
    out
}

/// Every candidate's evidence at the variations' own values (none for those out of play).
fn first_scores<R>(
    cx: &Context<'_>,
    pool: &Pool,
    points: &[Point<'_, R>],
    projectors: &mut [Projector],
    chosen: &mut Chosen,
) -> Scores {
    let n = cx.candidates.list.len();
    let mut scores = Scores {
        evidence: vec![None; n],
        scored_at: vec![0; n],
        odds: vec![None; n],
    };
    for c in (0..n).filter(|&c| pool.is_alive(c)) {
        scores.evidence[c] = Some(cx.evidence(c, points, projectors, chosen));
    }
    scores
}

impl Selection {
    /// Why the test cut where it did, in words (`describe` names a candidate). With exact
    /// variations (`NoiseModel::exact`) the odds and deviations measure nothing but the
    /// float tolerance, so the reason gives the residual in world units instead.
    pub fn cutoff_reason(&self, describe: &dyn Fn(usize) -> String) -> String {
        let keep = self.accepted;
        let noise = self.noise.describe();
        let Some(&c) = self.order.get(keep) else {
            return if self.noise.exact() {
                format!("every relation holds in the variations ({noise})")
            } else {
                format!(
                    "every relation is more likely intent than not under the variations' noise ({noise})"
                )
            };
        };
        let what = format!("relation {} ({})", keep + 1, describe(c));
        let odds = self.log_odds[keep].exp();
        if !self.z[keep].is_finite() {
            format!(
                "{what} is in no variation that keeps both its parts, and relations of its kind are more often accidental than intent (odds {odds:.3} to 1)"
            )
        } else if self.noise.exact() {
            format!(
                "{what} does not hold in the variations: they leave it off by up to {} world units ({noise})",
                figures(self.residual[c])
            )
        } else {
            format!(
                "{what} is more likely broken than intent (odds {odds:.3} to 1, its residuals {:.1} noise deviations off; noise {noise})",
                self.z[keep]
            )
        }
    }

    fn push(&mut self, c: usize, z: f64, log_odds: f64, curve: Option<f64>) {
        self.order.push(c);
        self.z.push(z);
        self.log_odds.push(log_odds);
        self.curve.extend(curve);
        self.implied.push(Vec::new());
    }
}

/// What the selection knows before its first step.
fn context<'a>(faces: &'a Faces, candidates: &'a Candidates, samples: &[Sample]) -> Context<'a> {
    let scale = samples
        .iter()
        .flat_map(|s| s.values.iter())
        .fold(1.0f64, |m, v| m.max(v.abs()));
    let roundoff = RELATIVE_ROUNDOFF * scale;
    let seen: Vec<Vec<bool>> = candidates
        .list
        .iter()
        .map(|c| {
            let parts: Vec<usize> = c.parts(&candidates.features).collect();
            samples
                .iter()
                .map(|s| parts.iter().all(|&p| s.sees(p)))
                .collect()
        })
        .collect();
    let dof = candidates
        .list
        .iter()
        .zip(&seen)
        .map(|(c, seen)| noisy_rows(&c.rows, |_| true) * seen.iter().filter(|s| **s).count())
        .collect();
    Context {
        faces,
        candidates,
        by_slot: candidates_by_slot(candidates, faces.slots()),
        seen,
        dof,
        roundoff,
        holds: candidates.tolerance.epsilon.max(roundoff),
        prior: vec![0.0; candidates.list.len()],
        size: 1.0,
        input: Vec::new(),
    }
}

/// How many independent directions the variations' noise moves `rows` in: the rank of
/// their linear parts over the slots `noisy` says carry noise. A row the program holds
/// identically (a corner's coordinate that both parts take from the same numbers) is zero in
/// every variation whatever the noise, and a row that repeats others adds no residual of
/// its own; counting either as a degree of freedom would spread one residual over several
/// and pull `σ` below the noise.
fn noisy_rows<'r>(
    rows: impl IntoIterator<Item = &'r Affine>,
    noisy: impl Fn(SlotId) -> bool,
) -> usize {
    let mut basis = RowBasis::default();
    rows.into_iter()
        .filter(|r| {
            let terms: Vec<(SlotId, f64)> =
                r.terms.iter().copied().filter(|&(s, _)| noisy(s)).collect();
            basis.add_terms(&terms)
        })
        .count()
}

/// The alive candidate most likely intent, scored afresh at this step, with its log
/// posterior odds and test statistic (the first in list order among equals, odds that
/// differ by round-off, [`RELATIVE_ROUNDOFF`] of their size, being equal).
fn best<R>(
    cx: &Context<'_>,
    (noise, ratio): (&NoiseModel, &LikelihoodRatio),
    pool: &mut Pool,
    state: &mut State<'_, '_, R>,
    scores: &mut Scores,
    step: usize,
) -> Option<(usize, f64, f64)> {
    let alive: Vec<usize> = pool.members(0).collect();
    for &c in &alive {
        if scores.evidence[c].is_none() {
            scores.evidence[c] = Some(state.evidence(cx, c));
            scores.scored_at[c] = step;
        }
    }
    // A score kept from an earlier step may be stale (rows chosen elsewhere in its block
    // change its conditional variance): the winner is scored again until it is fresh.
    loop {
        let scored: Vec<(usize, f64)> = alive
            .iter()
            .filter_map(|&c| Some((c, scores.odds(cx, ratio, c)?)))
            .collect();
        let top = scored
            .iter()
            .copied()
            .min_by(|a, b| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0)))?;
        // Odds equal but for round-off are equal: equivalent candidates (one implied by
        // another and the rows chosen) must not be told apart by the order of a sum.
        let within = RELATIVE_ROUNDOFF * top.1.abs().max(1.0);
        let (c, odds) = scored
            .iter()
            .copied()
            .filter(|&(c, o)| c < top.0 && (o - top.1).abs() <= within)
            .min_by_key(|&(c, _)| c)
            .unwrap_or(top);
        if scores.scored_at[c] == step {
            let z = scores.evidence[c].map_or(f64::NAN, |e| noise.z(e));
            return Some((c, odds, z));
        }
        scores.evidence[c] = Some(state.evidence(cx, c));
        scores.scored_at[c] = step;
    }
}

/// The log posterior odds that candidate `c` with evidence `e` is intent: its class's prior
/// odds plus the evidence's likelihood ratio (the prior alone when no variation has both
/// its parts).
fn log_odds(cx: &Context<'_>, ratio: &LikelihoodRatio, c: usize, e: Evidence) -> f64 {
    cx.prior[c] + ratio.of(e)
}

/// What a step changes: the variations' points, their projectors and the chosen rows.
struct State<'s, 'a, R> {
    points: &'s mut [Point<'a, R>],
    projectors: &'s mut [Projector],
    chosen: &'s mut Chosen,
}

impl<R> State<'_, '_, R> {
    fn evidence(&mut self, cx: &Context<'_>, c: usize) -> Evidence {
        cx.evidence(c, self.points, self.projectors, self.chosen)
    }
}

/// Moves every variation onto the chosen rows plus `rows` and updates its IoU to the
/// original. Returns the slots that moved beyond round-off in some variation.
fn move_points<S: Similarity>(
    cx: &Context<'_>,
    state: &mut State<'_, '_, S::Reference>,
    rows: &[&Affine],
    sim: Option<&S>,
) -> Vec<u32> {
    let mut made: Vec<Option<Projection>> = state.projectors.iter().map(|_| None).collect();
    let mut moved_any: Vec<u32> = Vec::new();
    for p in state.points.iter_mut() {
        let projector = &mut state.projectors[p.group];
        let projection =
            made[p.group].get_or_insert_with(|| state.chosen.projection(projector, cx.faces, rows));
        let (shift, _) = projector.shift_and_cost_at(projection, &p.current, rows);
        let mut moved = false;
        for (s, delta) in shift {
            p.current[s as usize] += delta;
            if delta.abs() > cx.roundoff {
                moved = true;
                moved_any.push(s);
            }
        }
        if let (true, Some(sim)) = (moved, sim) {
            p.fidelity = fidelity(sim, p.sample, &p.current, &mut p.original);
        }
    }
    moved_any.sort_unstable();
    moved_any.dedup();
    moved_any
}

/// Every projector, for [`Chosen::add`].
fn each(projectors: &mut [Projector]) -> Vec<&mut Projector> {
    projectors.iter_mut().collect()
}

/// The slots `rows` hold.
fn slots_of(rows: &[&Affine]) -> Vec<u32> {
    let mut slots: Vec<u32> = rows.iter().flat_map(|r| r.slots()).collect();
    slots.sort_unstable();
    slots.dedup();
    slots
}

/// The largest residual of candidate `c` over the variations that keep both its parts.
fn largest_residual(cx: &Context<'_>, c: usize, samples: &[Sample]) -> f64 {
    samples
        .iter()
        .zip(&cx.seen[c])
        .filter(|(_, seen)| **seen)
        .flat_map(|(s, _)| {
            cx.candidates.list[c]
                .rows
                .iter()
                .map(|r| r.eval(&s.values).abs())
        })
        .fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two corners that take `x` from the same numbers, `y` apart by `a − b` and `z` by
    /// twice that: one residual, so one degree of freedom, not three.
    #[test]
    fn rows_the_program_holds_or_repeats_add_no_degree_of_freedom() {
        let (a, b) = (Affine::slot(0), Affine::slot(1));
        let x = Affine::slot(2).sub(&Affine::slot(2));
        let y = a.sub(&b);
        let z = y.scale(2.0);
        assert_eq!(noisy_rows(&[x.clone(), y.clone(), z], |_| true), 1);
        assert_eq!(
            noisy_rows(&[x.clone(), y.clone(), Affine::slot(2)], |_| true),
            2
        );
        // Slot 2 no variation moved: no noise in it.
        assert_eq!(noisy_rows(&[x, y, Affine::slot(2)], |s| s != 2), 1);
    }

    #[test]
    fn a_relation_tells_the_noise_only_when_it_cancels_its_numbers_changes() {
        // `a = b`, both 10 at the input.
        let row = Affine {
            constant: 0.0,
            terms: vec![(0, 1.0), (1, -1.0)],
        };
        let input = [10.0, 10.0];
        let at = |values: &[[f64; 2]]| -> Vec<Sample> {
            values
                .iter()
                .map(|v| Sample::new(v.to_vec(), Vec::new()))
                .collect()
        };
        let seen = [true, true];
        // The design moved both by 10 and 5; the relation is off by a few tenths: noise.
        let kept = at(&[[20.0, 20.3], [5.0, 4.8]]);
        assert!(cancels(&[&row], &input, &kept, &seen));
        // The two moved apart as much as they moved at all: nothing tells noise here.
        let apart = at(&[[20.0, 12.0], [5.0, 9.0]]);
        assert!(!cancels(&[&row], &input, &apart, &seen));
        // A variation that does not keep the relation's parts says nothing.
        assert!(cancels(
            &[&row],
            &input,
            &at(&[[20.0, 20.3], [5.0, 9.0]]),
            &[true, false]
        ));
    }

    /// Three steps taking candidates 2, 0 and 1; the third is off by 0.25 world units.
    fn selection(sigma: f64, accepted: usize) -> Selection {
        Selection {
            order: vec![2, 0, 1],
            z: vec![-1.0, 0.5, 40.0],
            log_odds: vec![5.0, 2.0, -30.0],
            curve: Vec::new(),
            implied: vec![Vec::new(); 3],
            accepted,
            noise: NoiseModel {
                sigma,
                floor: 1e-6,
                pooled: 10,
                critical_z: 3.09,
                told: true,
            },
            residual: vec![0.0, 0.25, 0.0],
        }
    }

    fn name(c: usize) -> String {
        format!("candidate {c}")
    }

    #[test]
    fn the_cutoff_reason_of_exact_variations_gives_the_residual_not_a_zero_sigma() {
        let cut = selection(1e-6, 2).cutoff_reason(&name);
        assert!(
            cut.starts_with("relation 3 (candidate 1) does not hold in the variations"),
            "{cut}"
        );
        assert!(cut.contains("up to 0.250 world units (exact variations, no noise)"));
        assert!(!cut.contains('σ') && !cut.contains("odds"), "{cut}");
        assert_eq!(
            selection(1e-6, 3).cutoff_reason(&name),
            "every relation holds in the variations (exact variations, no noise)"
        );
    }

    #[test]
    fn the_cutoff_reason_of_noisy_variations_keeps_sigma_and_the_odds() {
        let cut = selection(0.2, 2).cutoff_reason(&name);
        assert!(
            cut.contains("more likely broken than intent")
                && cut.contains("40.0 noise deviations off")
                && cut.ends_with("noise σ = 0.200 world units)"),
            "{cut}"
        );
        let all = selection(0.2, 3).cutoff_reason(&name);
        assert!(all.contains("(σ = 0.200 world units)"), "{all}");
        // A relation no variation sees is cut by its kind's prior, not by deviations.
        let unseen = Selection {
            z: vec![-1.0, 0.5, f64::NEG_INFINITY],
            ..selection(0.2, 2)
        };
        let cut = unseen.cutoff_reason(&name);
        assert!(
            cut.contains("in no variation that keeps both its parts") && !cut.contains("inf"),
            "{cut}"
        );
    }
}
