//! Candidate relations: every coplanarity, coaxiality, coincidence and equality that holds
//! on the input.
//!
//! The four kinds are the paper's (see `paper-models.md`): coplanar face planes with the same
//! normal axis, coaxial axis lines with the same direction, coincident key points, equal
//! extents. A candidate holds when each of its equations' residuals is within the model's
//! tolerance. Features are sorted by value and paired inside a sliding window, so the work is
//! O(n log n + pairs), never all pairs. Every holding pair is counted, redundant or not: that
//! count is the paper's "base constraints".

use super::tolerance::Tolerance;
use crate::ir::{Affine, Feature, FeatureKind, Model};
use serde::Serialize;

#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum RelationKind {
    Coplanar,
    Coaxial,
    Coincident,
    Equal,
}

impl RelationKind {
    pub const ALL: [RelationKind; 4] = [
        RelationKind::Coplanar,
        RelationKind::Coaxial,
        RelationKind::Coincident,
        RelationKind::Equal,
    ];

    pub fn name(self) -> &'static str {
        match self {
            RelationKind::Coplanar => "coplanar",
            RelationKind::Coaxial => "coaxial",
            RelationKind::Coincident => "coincident",
            RelationKind::Equal => "equal",
        }
    }

    fn verb(self) -> &'static str {
        match self {
            RelationKind::Coplanar => "is coplanar with",
            RelationKind::Coaxial => "is coaxial with",
            RelationKind::Coincident => "coincides with",
            RelationKind::Equal => "equals",
        }
    }
}

/// A feature with affine forms (one per coordinate).
#[derive(Debug, Clone)]
pub struct AffineFeature {
    pub part: usize,
    pub kind: FeatureKind,
    /// `part_name.role`
    pub label: String,
    pub forms: Vec<Affine>,
    pub values: Vec<f64>,
}

/// One relation between two features: `rows[i] = a_i − b_i = 0`.
///
/// Features with identical affine forms (the legs of one module, the instances of a loop)
/// form a class; a relation between two classes stands for every pair of their members,
/// all with the same rows, so it is stored once with its `multiplicity`.
#[derive(Debug, Clone)]
pub struct Candidate {
    pub kind: RelationKind,
    pub a: usize,
    pub b: usize,
    pub rows: Vec<Affine>,
    pub multiplicity: usize,
}

/// Every candidate of a model, with the features they speak of.
#[derive(Debug, Clone)]
pub struct Candidates {
    /// Representatives of the feature classes.
    pub features: Vec<AffineFeature>,
    /// How many features each representative stands for.
    pub class_sizes: Vec<usize>,
    pub list: Vec<Candidate>,
    /// Pairs inside one class, per kind: they hold for every setting (same forms), so they
    /// are counted but constrain nothing.
    pub identical: std::collections::BTreeMap<RelationKind, usize>,
    pub tolerance: Tolerance,
}

impl Candidates {
    /// "seat.bottom is coplanar with left_front_leg.top"
    pub fn describe(&self, c: &Candidate) -> String {
        let more = if c.multiplicity > 1 {
            format!(" (and {} more pairs like it)", c.multiplicity - 1)
        } else {
            String::new()
        };
        format!(
            "{} {} {}{more}",
            self.features[c.a].label,
            c.kind.verb(),
            self.features[c.b].label
        )
    }

    /// Candidates of one kind, counting every pair (the paper's count).
    pub fn count(&self, kind: RelationKind) -> usize {
        self.list
            .iter()
            .filter(|c| c.kind == kind)
            .map(|c| c.multiplicity)
            .sum::<usize>()
            + self.identical.get(&kind).copied().unwrap_or(0)
    }

    /// The paper's "base constraints": every holding pair, redundant or not.
    pub fn total(&self) -> usize {
        RelationKind::ALL.iter().map(|&k| self.count(k)).sum()
    }
}

/// An exact key for an affine form (bit patterns of its numbers).
fn form_key(forms: &[Affine]) -> Vec<u64> {
    let mut k = Vec::new();
    for f in forms {
        k.push(f.constant.to_bits());
        k.push(f.terms.len() as u64);
        for &(s, a) in &f.terms {
            k.push(u64::from(s));
            k.push(a.to_bits());
        }
    }
    k
}

/// The model's features whose numbers are all affine.
pub fn affine_features(model: &Model) -> Vec<AffineFeature> {
    model
        .features()
        .into_iter()
        .filter_map(|f: Feature| {
            let forms: Option<Vec<Affine>> = f.nums.iter().map(|n| n.affine().cloned()).collect();
            Some(AffineFeature {
                part: f.part,
                kind: f.kind,
                label: format!("{}.{}", model.parts[f.part].name, f.role),
                values: f.nums.iter().map(|n| n.value).collect(),
                forms: forms?,
            })
        })
        .collect()
}

/// Which relation two features of this kind can have, and the group they must share.
fn relation_of(kind: FeatureKind) -> (RelationKind, u8) {
    match kind {
        FeatureKind::Plane { axis, .. } => (RelationKind::Coplanar, axis),
        FeatureKind::AxisLine { axis } => (RelationKind::Coaxial, axis),
        FeatureKind::Point { .. } => (RelationKind::Coincident, 0),
        FeatureKind::Extent { .. } => (RelationKind::Equal, 0),
    }
}

/// Finds every candidate that holds on the model.
pub fn find_candidates(model: &Model) -> Candidates {
    let tolerance = Tolerance::for_size(model.size());
    let all = affine_features(model);
    // Classes of identical features (same relation group, same forms).
    let mut class_of: std::collections::HashMap<((RelationKind, u8), Vec<u64>), usize> =
        Default::default();
    let mut features: Vec<AffineFeature> = Vec::new();
    let mut class_sizes: Vec<usize> = Vec::new();
    for f in all {
        let key = (relation_of(f.kind), form_key(&f.forms));
        match class_of.get(&key) {
            Some(&i) => class_sizes[i] += 1,
            None => {
                class_of.insert(key, features.len());
                features.push(f);
                class_sizes.push(1);
            }
        }
    }
    let mut identical: std::collections::BTreeMap<RelationKind, usize> = Default::default();
    let mut groups: std::collections::BTreeMap<(RelationKind, u8), Vec<usize>> = Default::default();
    for (i, f) in features.iter().enumerate() {
        let (kind, g) = relation_of(f.kind);
        let k = class_sizes[i];
        *identical.entry(kind).or_insert(0) += k * (k - 1) / 2;
        groups.entry((kind, g)).or_default().push(i);
    }
    let mut list = Vec::new();
    for ((kind, _), mut members) in groups {
        members.sort_by(|&x, &y| features[x].values[0].total_cmp(&features[y].values[0]));
        for (pos, &x) in members.iter().enumerate() {
            let fx = &features[x];
            for &y in &members[pos + 1..] {
                let fy = &features[y];
                if fy.values[0] - fx.values[0] > tolerance.epsilon {
                    break;
                }
                let holds = fx
                    .values
                    .iter()
                    .zip(&fy.values)
                    .all(|(&p, &q)| tolerance.equal(p, q));
                if holds {
                    let (a, b) = if x < y { (x, y) } else { (y, x) };
                    let rows = features[a]
                        .forms
                        .iter()
                        .zip(&features[b].forms)
                        .map(|(p, q)| p.sub(q))
                        .collect();
                    let multiplicity = class_sizes[a] * class_sizes[b];
                    list.push(Candidate {
                        kind,
                        a,
                        b,
                        rows,
                        multiplicity,
                    });
                }
            }
        }
    }
    list.sort_by_key(|c| (c.kind, c.a, c.b));
    identical.retain(|_, n| *n > 0);
    Candidates {
        features,
        class_sizes,
        list,
        identical,
        tolerance,
    }
}
