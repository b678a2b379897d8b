//! Candidate relations: every coplanarity, coaxiality, coincidence, equality and tangency
//! that holds on the input.
//!
//! Four kinds are the paper's (see `paper-models.md`): coplanar face planes with the same
//! normal axis, coaxial axis lines with the same direction, coincident key points, equal
//! extents. The fifth, tangency, pairs a round part's side plane with a face plane or
//! another round side normal to the same axis (a board on an axle, wheels on one floor); it
//! is offered to discovery but not counted among the paper's base constraints; so are mirror
//! symmetry and equal spacing of placements (`placement`), which speak of parts' mid-planes,
//! equal insets (`inset`, without variations only), which speak of margins between
//! touching parts' faces, and proportional extents (`proportion`: one twice another).
//! A candidate holds when each of its equations' residuals is within the model's
//! tolerance. Features are sorted by value and paired inside a sliding window, so the work is
//! O(n log n + pairs), never all pairs. Every holding pair is counted, redundant or not: that
//! count is the paper's "base constraints".

use super::inset::{FaceIndex, face_index, inset_candidates};
use super::proportion::proportion_candidates;
use crate::ir::{Affine, Feature, FeatureKind, Model};
use crate::tolerance::Tolerance;
use serde::Serialize;

#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum RelationKind {
    Coplanar,
    Coaxial,
    Coincident,
    Equal,
    /// A face plane (or another round part's side) touching a round part's curved side:
    /// not one of the paper's kinds, so not in its base constraint count.
    Tangent,
    /// Two repeated parts placed as mirror images about the model's centre plane, or one
    /// part centred on it (`placement`): not one of the paper's kinds.
    Symmetric,
    /// Three repeated parts in a row at equal gaps (`placement`): not one of the paper's
    /// kinds.
    Spaced,
    /// A part set in from a touching, wider part by equal margins on two axes (`inset`):
    /// not one of the paper's kinds.
    Inset,
    /// An extent twice another (`proportion`): not one of the paper's kinds.
    Proportional,
}

impl RelationKind {
    /// The paper's four kinds: what its base constraint count counts.
    pub const PAPER: [RelationKind; 4] = [
        RelationKind::Coplanar,
        RelationKind::Coaxial,
        RelationKind::Coincident,
        RelationKind::Equal,
    ];

    /// Every kind discovery knows.
    pub const ALL: [RelationKind; 9] = [
        RelationKind::Coplanar,
        RelationKind::Coaxial,
        RelationKind::Coincident,
        RelationKind::Equal,
        RelationKind::Tangent,
        RelationKind::Symmetric,
        RelationKind::Spaced,
        RelationKind::Inset,
        RelationKind::Proportional,
    ];

    pub fn name(self) -> &'static str {
        match self {
            RelationKind::Coplanar => "coplanar",
            RelationKind::Coaxial => "coaxial",
            RelationKind::Coincident => "coincident",
            RelationKind::Equal => "equal",
            RelationKind::Tangent => "tangent",
            RelationKind::Symmetric => "symmetric",
            RelationKind::Spaced => "spaced",
            RelationKind::Inset => "inset",
            RelationKind::Proportional => "proportional",
        }
    }

    fn verb(self) -> &'static str {
        match self {
            RelationKind::Coplanar => "is coplanar with",
            RelationKind::Coaxial => "is coaxial with",
            RelationKind::Coincident => "coincides with",
            RelationKind::Equal => "equals",
            RelationKind::Tangent => "is tangent to",
            RelationKind::Symmetric => "mirrors",
            RelationKind::Spaced => "is evenly spaced with",
            RelationKind::Inset => "is set in as far as",
            RelationKind::Proportional => "is a multiple of",
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

/// One relation between features: for the paper's kinds and tangency `rows[i] = a_i − b_i =
/// 0`, for a proportion `a − factor·b = 0`; a symmetric or spaced relation also speaks of
/// the features in `more` (the centre plane's bounds, the middle of three), and its rows
/// say how (`placement`).
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
    /// Further features the rows speak of, beyond `a` and `b`.
    pub more: Vec<usize>,
    /// How many times `b` makes `a`: the ratio of a proportion, 1 for every other kind.
    pub factor: f64,
}

impl Candidate {
    /// Every feature the relation speaks of: `a`, `b`, then `more`.
    pub fn feature_indices(&self) -> impl Iterator<Item = usize> + '_ {
        [self.a, self.b]
            .into_iter()
            .chain(self.more.iter().copied())
    }

    /// The relation's residuals given each feature's numbers (`value_of(feature index)`),
    /// measured anywhere (a slider setting, another program's export): zero where it holds.
    /// The same combination as `rows`, on values instead of forms.
    pub fn residuals(&self, value_of: impl Fn(usize) -> Vec<f64>) -> Vec<f64> {
        let (a, b) = (value_of(self.a), value_of(self.b));
        let first = |f: usize| value_of(f).first().copied().unwrap_or(f64::NAN);
        match self.kind {
            RelationKind::Symmetric => {
                let twice_centre = match self.more.as_slice() {
                    [c] => 2.0 * first(*c),
                    [lo, hi] => first(*lo) + first(*hi),
                    _ => f64::NAN,
                };
                vec![a[0] + b[0] - twice_centre]
            }
            RelationKind::Spaced => {
                let mid = self.more.first().map_or(f64::NAN, |&m| first(m));
                vec![a[0] - 2.0 * mid + b[0]]
            }
            RelationKind::Inset => match self.more.as_slice() {
                [oa, ob] => vec![a[0] - first(*oa) - b[0] + first(*ob)],
                _ => vec![f64::NAN],
            },
            _ => a.iter().zip(&b).map(|(x, y)| x - self.factor * y).collect(),
        }
    }

    /// The parts the relation speaks of (with repeats).
    pub fn parts<'a>(&'a self, features: &'a [AffineFeature]) -> impl Iterator<Item = usize> + 'a {
        self.feature_indices().map(|f| features[f].part)
    }
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
    /// Pairs that hold but are left out of `list` (see [`find_candidates_for`]), per kind:
    /// counted, not offered to discovery.
    pub unlisted: std::collections::BTreeMap<RelationKind, usize>,
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
        let (a, b) = (&self.features[c.a].label, &self.features[c.b].label);
        match c.kind {
            RelationKind::Symmetric if c.a == c.b => {
                let more = more.replace(" pairs like it", " like it");
                format!("{a} is on the model's centre plane{more}")
            }
            RelationKind::Symmetric => {
                format!("{a} mirrors {b} about the model's centre plane{more}")
            }
            RelationKind::Spaced => {
                let mid = c
                    .more
                    .first()
                    .map_or("", |&m| self.features[m].label.as_str());
                format!("{a}, {mid} and {b} are evenly spaced{more}")
            }
            RelationKind::Inset => {
                let label = |i: usize| {
                    c.more
                        .get(i)
                        .map_or("", |&m| self.features[m].label.as_str())
                };
                format!(
                    "{a} is as far from {} as {b} is from {}{more}",
                    label(0),
                    label(1)
                )
            }
            RelationKind::Proportional => format!("{a} is {} times {b}{more}", c.factor),
            _ => format!("{a} {} {b}{more}", c.kind.verb()),
        }
    }

    /// Candidates of one kind, counting every pair (the paper's count).
    pub fn count(&self, kind: RelationKind) -> usize {
        self.list
            .iter()
            .filter(|c| c.kind == kind)
            .map(|c| c.multiplicity)
            .sum::<usize>()
            + self.identical.get(&kind).copied().unwrap_or(0)
            + self.unlisted.get(&kind).copied().unwrap_or(0)
    }

    /// The paper's "base constraints": every holding pair of its four kinds, redundant or
    /// not.
    pub fn total(&self) -> usize {
        RelationKind::PAPER.iter().map(|&k| self.count(k)).sum()
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

/// Which relation two features of this kind can have, and the group they must share (a
/// round part's side shares the face planes' group: see [`pair_kind`]); `None` for a
/// part's mid-planes, which are never paired (see `placement`).
fn relation_of(kind: FeatureKind) -> Option<(RelationKind, u8)> {
    match kind {
        FeatureKind::Plane { axis, .. } | FeatureKind::Side { axis, .. } => {
            Some((RelationKind::Coplanar, axis))
        }
        FeatureKind::AxisLine { axis } => Some((RelationKind::Coaxial, axis)),
        FeatureKind::Point { .. } => Some((RelationKind::Coincident, 0)),
        FeatureKind::Extent { .. } => Some((RelationKind::Equal, 0)),
        FeatureKind::Centre { .. } => None,
    }
}

/// The relation between two features of one group: tangent when either is a round
/// part's side, else the group's kind.
fn pair_kind(group: RelationKind, a: &AffineFeature, b: &AffineFeature) -> RelationKind {
    let side = |f: &AffineFeature| matches!(f.kind, FeatureKind::Side { .. });
    if side(a) || side(b) {
        RelationKind::Tangent
    } else {
        group
    }
}

/// Finds every candidate that holds on the model.
pub fn find_candidates(model: &Model) -> Candidates {
    find_candidates_for(model, &[])
}

/// Runs of equal features longer than this are not paired all with all for discovery.
pub const LARGE_RUN: usize = 32;
/// In a large run, each feature is paired with this many neighbours (see below).
pub const RUN_NEIGHBOURS: usize = 8;

/// One feature per class of identical features (same relation group, same forms), with
/// each class's size, and which class holds each part's face planes (for `inset`).
fn feature_classes(model: &Model) -> (Vec<AffineFeature>, Vec<usize>, FaceIndex) {
    type Key = (Option<(RelationKind, u8)>, bool, Vec<u64>);
    let mut class_of: std::collections::HashMap<Key, usize> = Default::default();
    let mut features: Vec<AffineFeature> = Vec::new();
    let mut class_sizes: Vec<usize> = Vec::new();
    let raw = affine_features(model);
    let mut member_class = Vec::with_capacity(raw.len());
    for f in &raw {
        let side = matches!(f.kind, FeatureKind::Side { .. });
        let key = (relation_of(f.kind), side, form_key(&f.forms));
        let class = *class_of.entry(key).or_insert_with(|| {
            features.push(f.clone());
            class_sizes.push(0);
            features.len() - 1
        });
        class_sizes[class] += 1;
        member_class.push(class);
    }
    let faces = face_index(&raw, &member_class);
    (features, class_sizes, faces)
}

/// The relation of `kind` between features `a < b`: their forms' differences, zero.
fn candidate(
    kind: RelationKind,
    features: &[AffineFeature],
    class_sizes: &[usize],
    a: usize,
    b: usize,
) -> Candidate {
    let rows = features[a]
        .forms
        .iter()
        .zip(&features[b].forms)
        .map(|(p, q)| p.sub(q))
        .collect();
    Candidate {
        kind,
        a,
        b,
        rows,
        multiplicity: class_sizes[a] * class_sizes[b],
        more: Vec::new(),
        factor: 1.0,
    }
}

/// Finds every candidate that holds on the model, listing for discovery only what the
/// `variations` (slot values) can tell apart.
///
/// A run of many equal features (the same leg height in 125 chairs) holds n(n−1)/2 pairs,
/// nearly all redundant: relations among features that stay equal in every variation span
/// the same space as a chain through them. In a run longer than [`LARGE_RUN`], features are
/// ordered by their values in the variations (features equal in all of them become
/// neighbours) and each is paired with its next [`RUN_NEIGHBOURS`]; the other pairs are
/// counted in `unlisted`, so the paper's count stays the same. Without variations every
/// pair is listed.
pub fn find_candidates_for(model: &Model, variations: &[Vec<f64>]) -> Candidates {
    let tolerance = Tolerance::for_size(model.size());
    let (features, class_sizes, faces) = feature_classes(model);
    let mut identical: std::collections::BTreeMap<RelationKind, usize> = Default::default();
    let mut groups: std::collections::BTreeMap<(RelationKind, u8), Vec<usize>> = Default::default();
    for (i, f) in features.iter().enumerate() {
        let Some((kind, g)) = relation_of(f.kind) else {
            continue;
        };
        let k = class_sizes[i];
        *identical.entry(pair_kind(kind, f, f)).or_insert(0) += k * (k - 1) / 2;
        groups.entry((kind, g)).or_default().push(i);
    }
    let mut list = Vec::new();
    let mut unlisted: std::collections::BTreeMap<RelationKind, usize> = Default::default();
    let holds = |x: usize, y: usize| {
        features[x]
            .values
            .iter()
            .zip(&features[y].values)
            .all(|(&p, &q)| tolerance.equal(p, q))
    };
    let signature = |x: usize| -> Vec<i64> {
        variations
            .iter()
            .flat_map(|v| features[x].forms.iter().map(move |f| f.eval(v)))
            .map(|v| (v / tolerance.epsilon).round().clamp(-9e15, 9e15) as i64)
            .collect()
    };
    for ((kind, _), mut members) in groups {
        members.sort_by(|&x, &y| features[x].values[0].total_cmp(&features[y].values[0]));
        let mut pairs: Vec<(usize, usize)> = Vec::new();
        let mut start = 0;
        while start < members.len() {
            // A run: members whose first values chain within the tolerance.
            let mut end = start + 1;
            while end < members.len()
                && features[members[end]].values[0] - features[members[end - 1]].values[0]
                    <= tolerance.epsilon
            {
                end += 1;
            }
            let run = &members[start..end];
            if run.len() <= LARGE_RUN || variations.is_empty() {
                for (pos, &x) in run.iter().enumerate() {
                    for &y in &run[pos + 1..] {
                        if features[y].values[0] - features[x].values[0] > tolerance.epsilon {
                            break;
                        }
                        if holds(x, y) {
                            pairs.push((x, y));
                        }
                    }
                }
            } else {
                let mut all: std::collections::BTreeMap<RelationKind, usize> = Default::default();
                for (pos, &x) in run.iter().enumerate() {
                    for &y in &run[pos + 1..] {
                        if features[y].values[0] - features[x].values[0] > tolerance.epsilon {
                            break;
                        }
                        if holds(x, y) {
                            let k = pair_kind(kind, &features[x], &features[y]);
                            *all.entry(k).or_insert(0) += class_sizes[x] * class_sizes[y];
                        }
                    }
                }
                let mut order: Vec<(Vec<i64>, usize)> =
                    run.iter().map(|&x| (signature(x), x)).collect();
                order.sort();
                for (pos, (_, x)) in order.iter().enumerate() {
                    for (_, y) in order.iter().skip(pos + 1).take(RUN_NEIGHBOURS) {
                        if holds(*x, *y) {
                            pairs.push((*x, *y));
                            let k = pair_kind(kind, &features[*x], &features[*y]);
                            if let Some(n) = all.get_mut(&k) {
                                *n = n.saturating_sub(class_sizes[*x] * class_sizes[*y]);
                            }
                        }
                    }
                }
                for (k, n) in all {
                    *unlisted.entry(k).or_insert(0) += n;
                }
            }
            start = end;
        }
        list.extend(pairs.into_iter().map(|(x, y)| {
            let (a, b) = if x < y { (x, y) } else { (y, x) };
            let kind = pair_kind(kind, &features[a], &features[b]);
            candidate(kind, &features, &class_sizes, a, b)
        }));
    }
    list.extend(super::placement::placement_candidates(
        model,
        &features,
        &class_sizes,
        &tolerance,
    ));
    // Equal insets are offered only without variations (the structural prior, the fit's
    // stages). With variations, a kept inset makes a derived size a difference of free
    // variables (a shelf's depth = its width + the top's depth − the top's width), which
    // a box of ranges cannot keep positive at its corners without clamping presets off
    // their variations (the paper table's fell to IoU 0.04–0.44): it needs a slider of its
    // own first, as contacts have (`contact_vars`).
    if variations.is_empty() {
        list.extend(inset_candidates(model, &features, &faces, &tolerance));
    }
    let (proportional, left_out) =
        proportion_candidates(&features, &class_sizes, &tolerance, variations);
    list.extend(proportional);
    if left_out > 0 {
        *unlisted.entry(RelationKind::Proportional).or_insert(0) += left_out;
    }
    list.sort_by_key(|c| (c.kind, c.a, c.b));
    identical.retain(|_, n| *n > 0);
    unlisted.retain(|_, n| *n > 0);
    Candidates {
        features,
        class_sizes,
        list,
        identical,
        unlisted,
        tolerance,
    }
}
