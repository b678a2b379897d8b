//! How far off a relation may be in the variations and still be intent: the noise gate.
//!
//! Variations are noisy (fitted to images, nudged by hand), so no relation holds exactly in
//! them. Volume IoU alone cannot tell noise from a real change: a leg's width jittered by a
//! pixel costs as much IoU as a leg made twice as tall, because the leg is thin. Noise,
//! though, lives in world units. A relation's residual in a variation (`a − b` of its two
//! features, world units) is noise-sized when the relation is intent and larger when the
//! variation changed it on purpose.
//!
//! The noise level is estimated from the data, robustly: the median over candidates of each
//! one's largest residual across the variations. Most candidates of a CAD model are intent
//! (repeated parts, contacts, alignments), so the median is a true relation's residual; up
//! to half of them may be accidents without moving it. A candidate whose residual exceeds
//! [`NOISE_FACTOR`] times that level in some variation is *deferred*: discovery takes it only
//! after every plausible one, so the curve jumps where the deferred ones start.
//!
//! Invariants: residuals ignore variations that do without either part (optional parts); the
//! threshold is never below the model's float tolerance, so with exact variations the gate
//! defers exactly the relations some variation breaks.

use super::candidates::Candidates;
use super::discover::Sample;
use crate::tolerance::Tolerance;
use serde::Serialize;

/// How many noise levels a residual may reach before its relation is deferred.
pub const NOISE_FACTOR: f64 = 3.0;

/// The gate's verdict for every candidate.
#[derive(Debug, Clone, Serialize)]
pub struct NoiseGate {
    /// The estimated noise level (world units): the median largest residual.
    pub level: f64,
    /// Residuals above this (world units) defer a relation.
    pub threshold: f64,
    /// Per candidate: its largest residual over the variations (world units).
    #[serde(skip)]
    pub residual: Vec<f64>,
    /// Per candidate: whether some variation breaks it beyond the noise.
    #[serde(skip)]
    pub deferred: Vec<bool>,
}

/// The largest residual of candidate `i` over the variations that keep both of its parts.
fn largest_residual(candidates: &Candidates, i: usize, samples: &[Sample]) -> f64 {
    let c = &candidates.list[i];
    let parts = [candidates.features[c.a].part, candidates.features[c.b].part];
    samples
        .iter()
        .filter(|s| !parts.iter().any(|p| s.optional.contains(p)))
        .flat_map(|s| c.rows.iter().map(|r| r.eval(&s.values).abs()))
        .fold(0.0, f64::max)
}

/// The median of `values` (0 for none).
pub fn median(values: &[f64]) -> f64 {
    if values.is_empty() {
        return 0.0;
    }
    let mut v = values.to_vec();
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

/// Estimates the variations' noise and decides which candidates they break beyond it.
pub fn noise_gate(candidates: &Candidates, samples: &[Sample], tolerance: Tolerance) -> NoiseGate {
    let residual: Vec<f64> = (0..candidates.list.len())
        .map(|i| largest_residual(candidates, i, samples))
        .collect();
    let level = median(&residual);
    let threshold = (NOISE_FACTOR * level).max(tolerance.epsilon);
    let deferred = residual.iter().map(|&r| r > threshold).collect();
    NoiseGate {
        level,
        threshold,
        residual,
        deferred,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn median_of_odd_and_even() {
        assert_eq!(median(&[3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(&[4.0, 1.0, 2.0, 3.0]), 2.5);
        assert_eq!(median(&[]), 0.0);
    }
}
