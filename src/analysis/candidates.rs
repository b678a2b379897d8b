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
#[derive(Debug, Clone)]
pub struct Candidate {
    pub kind: RelationKind,
    pub a: usize,
    pub b: usize,
    pub rows: Vec<Affine>,
}

/// Every candidate of a model, with the features they speak of.
#[derive(Debug, Clone)]
pub struct Candidates {
    pub features: Vec<AffineFeature>,
    pub list: Vec<Candidate>,
    pub tolerance: Tolerance,
}

impl Candidates {
    /// "seat.bottom is coplanar with left_front_leg.top"
    pub fn describe(&self, c: &Candidate) -> String {
        format!(
            "{} {} {}",
            self.features[c.a].label,
            c.kind.verb(),
            self.features[c.b].label
        )
    }

    pub fn count(&self, kind: RelationKind) -> usize {
        self.list.iter().filter(|c| c.kind == kind).count()
    }
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
    let features = affine_features(model);
    let mut groups: std::collections::BTreeMap<(RelationKind, u8), Vec<usize>> = Default::default();
    for (i, f) in features.iter().enumerate() {
        groups.entry(relation_of(f.kind)).or_default().push(i);
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
                    list.push(Candidate { kind, a, b, rows });
                }
            }
        }
    }
    list.sort_by_key(|c| (c.kind, c.a, c.b));
    Candidates {
        features,
        list,
        tolerance,
    }
}
