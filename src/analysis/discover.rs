//! Constraint discovery: which relations of the input do the variations share?
//!
//! The paper's greedy selection (`algorithms.md` §3): from the empty set, score every
//! remaining candidate by projecting each variation's current point onto the chosen set plus
//! that candidate and measuring how similar the projection stays (IoU, or image loss); keep
//! the best (product over variations), drop candidates the chosen rows now imply (rank test),
//! and record the distortion curve against the original variations. The cutoff is decided
//! afterwards (`cutoff`).

use super::candidates::Candidates;
use super::project::{Faces, Projector, RowBasis};
use crate::ir::Affine;
use nalgebra::DVector;
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
    /// Between the model at `x` without `part` and the model at `x`.
    fn removal(&self, x: &[f64], part: usize) -> f64;
}

/// One variation as discovery sees it: its slot values and the parts it does without.
#[derive(Debug, Clone)]
pub struct Sample {
    pub values: Vec<f64>,
    pub optional: Vec<usize>,
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

/// All rows of a candidate.
fn rows_of(c: &Candidates, i: usize) -> Vec<&Affine> {
    c.list[i].rows.iter().collect()
}

/// Whether a projection moved a point by more than round-off.
fn moved(y: &DVector<f64>, x: &DVector<f64>, scale: f64) -> bool {
    y.iter()
        .zip(x.iter())
        .any(|(a, b)| (a - b).abs() > 1e-9 * scale)
}

/// Whether any row depends on a slot in `dirty`.
fn touches(rows: &[&Affine], dirty: &HashSet<u32>) -> bool {
    rows.iter().any(|r| r.slots().any(|s| dirty.contains(&s)))
}

fn implied(basis: &RowBasis, rows: &[&Affine]) -> bool {
    rows.iter().all(|r| basis.contains_terms(&r.terms))
}

/// Runs the greedy selection to the end (every candidate chosen or implied).
///
/// `tiers[c]` ranks candidate `c` by prior plausibility (0 first): each step takes the best
/// score among the remaining candidates of the lowest tier, so a relation the variations
/// break beyond their noise (`noise`) waits until every plausible one is taken, whatever its
/// IoU. With every tier equal this is the paper's greedy.
pub fn discover<S: Similarity>(
    faces: &Faces,
    candidates: &Candidates,
    samples: &[Sample],
    slots: usize,
    sim: &S,
    tiers: &[u8],
) -> Discovery {
    let d = slots;
    let mut basis = RowBasis::default();
    let mut remaining: Vec<usize> = (0..candidates.list.len())
        .filter(|&i| !implied(&basis, &rows_of(candidates, i)))
        .collect();
    let mut current: Vec<DVector<f64>> = samples
        .iter()
        .map(|s| DVector::from_column_slice(&s.values))
        .collect();
    let mut out = Discovery {
        order: Vec::new(),
        scores: Vec::new(),
        curve: vec![0.0],
        implied: Vec::new(),
        tiers: Vec::new(),
        worst: Vec::new(),
    };
    let scale = samples
        .iter()
        .flat_map(|s| s.values.iter())
        .fold(1.0f64, |m, v| m.max(v.abs()));
    // Per candidate, each variation's similarity after projecting onto it (1 when the
    // variation already satisfies it); the score is their product.
    let mut cache: HashMap<usize, Vec<f64>> = HashMap::new();
    let mut dirty: HashSet<u32> = HashSet::new();
    while !remaining.is_empty() && !samples.is_empty() {
        let projectors: Vec<Projector> = current
            .iter()
            .zip(samples)
            .map(|(x, s)| Projector::new(&faces.metric(x.as_slice(), &s.optional), &basis))
            .collect();
        let references: Vec<S::Reference> = current
            .iter()
            .zip(samples)
            .map(|(x, s)| sim.reference(x.as_slice(), &s.optional))
            .collect();
        let tier = remaining.iter().map(|&c| tiers[c]).min().unwrap_or(0);
        let mut best: Option<(f64, usize)> = None;
        for &c in remaining.iter().filter(|&&c| tiers[c] == tier) {
            let rows = rows_of(candidates, c);
            let fresh = cache.contains_key(&c) && !touches(&rows, &dirty);
            if !fresh {
                let sims = current
                    .iter()
                    .zip(&projectors)
                    .zip(&references)
                    .map(|((x, p), r)| {
                        let y = p.project(x, &rows);
                        // A variation that already satisfies the candidate does not move.
                        if moved(&y, x, scale) {
                            sim.similarity_to(y.as_slice(), r)
                        } else {
                            1.0
                        }
                    })
                    .collect();
                cache.insert(c, sims);
            }
            let score: f64 = cache[&c].iter().product();
            if best.is_none_or(|(b, _)| score > b) {
                best = Some((score, c));
            }
        }
        let Some((score, c)) = best else {
            break;
        };
        let rows = rows_of(candidates, c);
        let projected: Vec<DVector<f64>> = current
            .iter()
            .zip(&projectors)
            .map(|(x, p)| p.project(x, &rows))
            .collect();
        // Scores of candidates away from what moved are kept (algorithms.md §3).
        dirty = rows.iter().flat_map(|r| r.slots()).collect();
        for (y, x) in projected.iter().zip(&current) {
            for i in 0..d {
                if (y[i] - x[i]).abs() > 1e-9 * scale {
                    dirty.insert(i as u32);
                }
            }
        }
        out.worst
            .push(cache[&c].iter().fold(0.0, |w, s| f64::max(w, 1.0 - s)));
        for r in rows {
            basis.add_terms(&r.terms);
        }
        current = projected;
        let mean = current
            .iter()
            .zip(samples)
            .map(|(x, s)| sim.similarity(x.as_slice(), &s.values, &s.optional))
            .sum::<f64>()
            / samples.len() as f64;
        out.order.push(c);
        out.scores.push(score);
        out.tiers.push(tier);
        out.curve.push(1.0 - mean);
        let (gone, keep): (Vec<usize>, Vec<usize>) = remaining
            .into_iter()
            .filter(|&i| i != c)
            .partition(|&i| implied(&basis, &rows_of(candidates, i)));
        remaining = keep;
        out.implied.push(gone);
    }
    out
}
