//! How often each class of relation is intent in this model, learned from its variations.
//!
//! Under noise, a relation the variations change by less than their noise cannot be told
//! from an intent one by its own residuals: only how often relations *like it* are intent
//! can. Every candidate falls in a class by its structure: its kind, whether its two
//! features belong to one part, to parts that touch, or to parts apart, whether the parts
//! are repeats of each other, and, for equal extents, whether both are measured along the
//! same axis; and by whether the variations could test it at all (its terms' changes,
//! uncancelled, beyond what the noise explains), so that relations the variations cannot
//! see broken are not decided by the share of relations like them that they do test.
//! Each class's share of intent relations is estimated from this model's own evidence
//! (expectation–maximisation over the two-hypothesis likelihood of
//! `noise::NoiseModel::likelihood_ratio`), and becomes the prior odds every relation of the class
//! is tested with. The share's prior is what the model says with no variations: the
//! structural prior (`prior`) keeps or drops a relation by its class, and a class it keeps
//! starts from Beta(1.5, 0.5) (mean 3/4), one it drops from Beta(0.5, 1.5) — two relations'
//! worth, as much as the uniform Beta(1, 1), so a class with evidence is decided by it. A
//! relation no variation speaks of (no degree of freedom: a part the variations do without
//! or their pictures do not show) is decided by its class's share alone, which for a
//! class no variation speaks of is the structural prior's verdict.

use super::candidates::{Candidates, RelationKind};
use super::noise::{Evidence, NoiseModel};
use super::prior::{repeated, structural_prior, touching};
use crate::ir::{FeatureKind, Model};
use std::collections::HashMap;

/// Rounds of expectation–maximisation (the shares settle in a few).
const ROUNDS: usize = 50;

/// The structural class of a candidate (see the module doc).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
struct Class {
    kind: RelationKind,
    /// 0: one part; 1: parts that touch; 2: parts apart.
    parts: u8,
    repeated: bool,
    same_axis: bool,
    /// Whether the variations could have shown the relation broken: its terms' changes,
    /// uncancelled, would be more than the noise explains. A relation among numbers that
    /// move no more than the noise (a thin board's thickness under noise as large) learns
    /// nothing from its own residuals, so it must not take its share from relations like
    /// it that the variations do test.
    testable: bool,
}

fn class_of(model: &Model, candidates: &Candidates, i: usize, testable: bool) -> Class {
    let c = &candidates.list[i];
    let (fa, fb) = (&candidates.features[c.a], &candidates.features[c.b]);
    let tol = candidates.tolerance;
    let parts = if fa.part == fb.part {
        0
    } else if touching(model, fa.part, fb.part, &tol) {
        1
    } else {
        2
    };
    let same_axis = match (fa.kind, fb.kind) {
        (FeatureKind::Extent { axis: x }, FeatureKind::Extent { axis: y }) => x == y,
        _ => true,
    };
    Class {
        kind: c.kind,
        parts,
        repeated: fa.part != fb.part && repeated(model, fa.part, fb.part, &tol),
        same_axis,
        testable,
    }
}

/// Per candidate: the log prior odds that it is intent, from its class's learned share.
pub fn prior_log_odds(
    model: &Model,
    candidates: &Candidates,
    evidence: &[Evidence],
    noise: &NoiseModel,
    size: f64,
) -> Vec<f64> {
    let n = candidates.list.len();
    let mut index: HashMap<Class, usize> = HashMap::new();
    let class: Vec<usize> = (0..n)
        .map(|i| {
            let next = index.len();
            let e = evidence[i];
            let testable = e.dof > 0 && !noise.explains(Evidence::new(e.change, e.dof));
            *index
                .entry(class_of(model, candidates, i, testable))
                .or_insert(next)
        })
        .collect();
    let ratio = noise.likelihood_ratio(size);
    let llr: Vec<f64> = evidence.iter().map(|&e| ratio.of(e)).collect();
    // The structural prior's share of each class (it decides by class: 0 or 1).
    let mut kept = vec![0.0; index.len()];
    let mut members = vec![0.0; index.len()];
    for &i in &structural_prior(model, candidates) {
        kept[class[i]] += 1.0;
    }
    for &k in &class {
        members[k] += 1.0;
    }
    let alpha: Vec<f64> = kept
        .iter()
        .zip(&members)
        .map(|(k, m)| 0.5 + k / f64::max(*m, 1.0))
        .collect();
    let mut share: Vec<f64> = alpha.iter().map(|a| a / 2.0).collect();
    for _ in 0..ROUNDS {
        let mut intent = vec![0.0; share.len()];
        let mut count = vec![0.0; share.len()];
        for i in 0..n {
            let k = class[i];
            intent[k] += sigmoid(logit(share[k]) + llr[i]);
            count[k] += 1.0;
        }
        share = intent
            .iter()
            .zip(&count)
            .zip(&alpha)
            .map(|((w, c), a)| (w + a) / (c + 2.0))
            .collect();
    }
    class.iter().map(|&k| logit(share[k])).collect()
}

pub fn logit(p: f64) -> f64 {
    (p / (1.0 - p)).ln()
}

pub fn sigmoid(x: f64) -> f64 {
    if x >= 0.0 {
        1.0 / (1.0 + (-x).exp())
    } else {
        let e = x.exp();
        e / (1.0 + e)
    }
}

#[cfg(test)]
mod tests {
    use super::prior_log_odds;
    use crate::analysis::noise::{Evidence, INTENT_Z, NoiseModel};
    use crate::analysis::{RelationKind, find_candidates};
    use crate::front::test_model as model;

    /// Five boxes apart, of one width and other sizes: ten equal widths, a class the
    /// structural prior drops. Nine the variations show intent (their terms moved far, the
    /// residuals are noise); one whose terms moved no more than the noise must not borrow
    /// their share.
    #[test]
    fn a_relation_the_variations_cannot_test_keeps_the_prior_of_its_kind() {
        let text: String = (0..5)
            .map(|k| {
                format!(
                    "translate([{}, 0, 0]) cube([10, {}, {}]);\n",
                    100 * k,
                    20 + 7 * k,
                    30 + 11 * k
                )
            })
            .collect();
        let m = model(&text);
        let c = find_candidates(&m);
        let widths: Vec<usize> = (0..c.list.len())
            .filter(|&i| {
                let x = &c.list[i];
                x.kind == RelationKind::Equal
                    && c.features[x.a].label.ends_with(".width")
                    && c.features[x.b].label.ends_with(".width")
            })
            .collect();
        assert_eq!(widths.len(), 10, "{:?}", c.list);
        let untestable = widths[0];
        let evidence: Vec<Evidence> = (0..c.list.len())
            .map(|i| match i {
                i if i == untestable => Evidence {
                    cost: 0.5,
                    dof: 3,
                    change: 0.5,
                },
                i if widths.contains(&i) => Evidence {
                    cost: 0.5,
                    dof: 3,
                    change: 1e4,
                },
                _ => Evidence::new(0.0, 0),
            })
            .collect();
        let noise = NoiseModel {
            sigma: 1.0,
            floor: 1e-6,
            pooled: 0,
            critical_z: INTENT_Z,
            told: true,
        };
        let prior = prior_log_odds(&m, &c, &evidence, &noise, m.size());
        assert!(prior[widths[1]] > 1.0, "tested: {}", prior[widths[1]]);
        assert!(prior[untestable] < 0.0, "untested: {}", prior[untestable]);
    }
}
