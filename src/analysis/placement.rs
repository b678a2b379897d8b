//! Placement relations beyond the paper's four kinds: mirror symmetry and equal spacing.
//!
//! Both speak of parts' mid-planes (`FeatureKind::Centre`), so both are invariant under a
//! move of the whole model and hold whatever the parts' sizes.
//!
//! - **Symmetric.** The model's centre plane on an axis is the mid-plane of the largest part
//!   centred in the model's bounding box on that axis (a seat, a car's body), or, where no
//!   part is, the middle of the two faces that bound the model. Two repeated parts (same
//!   primitive, same sizes) whose centres sit at opposite offsets from it mirror each other:
//!   `a + b − 2·centre = 0`; one part whose centre is on it is centred: `a − centre = 0`.
//! - **Spaced.** Three repeated parts at consecutive distinct positions along an axis with
//!   equal gaps: `a − 2·mid + b = 0` (shelves, slats, rungs).
//!
//! A candidate holds on the input within the model's tolerance, as every other kind does.
//! Positions shared by many parts are paired with at most `RUN_NEIGHBOURS` partners, so the
//! work stays O(n log n + pairs).

use super::candidates::{AffineFeature, Candidate, RUN_NEIGHBOURS, RelationKind};
use super::prior::repeated;
use crate::ir::{Affine, FeatureKind, Model};
use crate::tolerance::Tolerance;

/// Every symmetric and spaced relation that holds on the model.
pub fn placement_candidates(
    model: &Model,
    features: &[AffineFeature],
    class_sizes: &[usize],
    tol: &Tolerance,
) -> Vec<Candidate> {
    let mut out = Vec::new();
    for axis in 0..3u8 {
        let centres: Vec<usize> = (0..features.len())
            .filter(|&i| features[i].kind == FeatureKind::Centre { axis })
            .collect();
        if centres.is_empty() {
            continue;
        }
        if let Some(plane) = centre_plane(model, features, &centres, axis, tol) {
            symmetric(
                model,
                features,
                class_sizes,
                &centres,
                &plane,
                tol,
                &mut out,
            );
        }
        spaced(model, features, class_sizes, &centres, tol, &mut out);
    }
    out
}

/// The model's centre plane on one axis: twice its form (so no halves), its value, and the
/// features it is made of.
struct CentrePlane {
    twice: Affine,
    value: f64,
    made_of: Vec<usize>,
}

/// The mid-plane of the widest part centred in the model's box on `axis`, else the middle
/// of the two faces that bound the model.
fn centre_plane(
    model: &Model,
    features: &[AffineFeature],
    centres: &[usize],
    axis: u8,
    tol: &Tolerance,
) -> Option<CentrePlane> {
    let k = usize::from(axis);
    let extent = |f: usize| {
        let (lo, hi) = model.parts[features[f].part].world_bounds();
        hi[k] - lo[k]
    };
    let bound = |high: bool| {
        (0..features.len())
            .filter(|&i| {
                matches!(features[i].kind,
                    FeatureKind::Plane { axis: a, high: h } | FeatureKind::Side { axis: a, high: h }
                    if a == axis && h == high)
            })
            .min_by(|&x, &y| {
                let (vx, vy) = (features[x].values[0], features[y].values[0]);
                let (vx, vy) = if high { (-vx, -vy) } else { (vx, vy) };
                vx.total_cmp(&vy).then(extent(y).total_cmp(&extent(x)))
            })
    };
    let (lo, hi) = (bound(false)?, bound(true)?);
    let middle = 0.5 * (features[lo].values[0] + features[hi].values[0]);
    let framed = centres
        .iter()
        .copied()
        .filter(|&c| tol.equal(features[c].values[0], middle))
        .max_by(|&x, &y| extent(x).total_cmp(&extent(y)).then(y.cmp(&x)));
    Some(match framed {
        Some(c) => CentrePlane {
            twice: features[c].forms[0].scale(2.0),
            value: features[c].values[0],
            made_of: vec![c],
        },
        None => CentrePlane {
            twice: features[lo].forms[0].add(&features[hi].forms[0]),
            value: middle,
            made_of: vec![lo, hi],
        },
    })
}

/// Mirror pairs of repeated parts about `plane`, and parts centred on it.
fn symmetric(
    model: &Model,
    features: &[AffineFeature],
    class_sizes: &[usize],
    centres: &[usize],
    plane: &CentrePlane,
    tol: &Tolerance,
    out: &mut Vec<Candidate>,
) {
    let offset = |f: usize| features[f].values[0] - plane.value;
    let mut by_offset: Vec<usize> = centres.to_vec();
    by_offset.sort_by(|&x, &y| offset(x).total_cmp(&offset(y)));
    let offsets: Vec<f64> = by_offset.iter().map(|&f| offset(f)).collect();
    for (pos, &a) in by_offset.iter().enumerate() {
        let d = offsets[pos];
        if d.abs() <= tol.epsilon {
            // Centred: 2a − 2·centre = 0, unless that is the plane itself.
            let row = features[a].forms[0].scale(2.0).sub(&plane.twice);
            if !row.is_constant() {
                out.push(relation(
                    RelationKind::Symmetric,
                    a,
                    a,
                    row,
                    class_sizes,
                    plane,
                ));
            }
            continue;
        }
        if d > 0.0 {
            break;
        }
        // Partners at offset −d (within the tolerance), in order of offset.
        let from = offsets.partition_point(|&o| o < -d - tol.epsilon);
        let partners = by_offset[from..]
            .iter()
            .zip(&offsets[from..])
            .take_while(|(_, o)| **o <= -d + tol.epsilon)
            .map(|(&b, _)| b)
            .filter(|&b| repeated(model, features[a].part, features[b].part, tol))
            .take(RUN_NEIGHBOURS);
        for b in partners.collect::<Vec<_>>() {
            let row = features[a].forms[0]
                .add(&features[b].forms[0])
                .sub(&plane.twice);
            if !row.is_constant() {
                let (x, y) = if a < b { (a, b) } else { (b, a) };
                out.push(relation(
                    RelationKind::Symmetric,
                    x,
                    y,
                    row,
                    class_sizes,
                    plane,
                ));
            }
        }
    }
}

fn relation(
    kind: RelationKind,
    a: usize,
    b: usize,
    row: Affine,
    class_sizes: &[usize],
    plane: &CentrePlane,
) -> Candidate {
    Candidate {
        kind,
        a,
        b,
        rows: vec![row],
        multiplicity: if a == b {
            class_sizes[a]
        } else {
            class_sizes[a] * class_sizes[b]
        },
        more: plane.made_of.clone(),
        factor: 1.0,
    }
}

/// Evenly spaced triples of repeated parts along one axis.
fn spaced(
    model: &Model,
    features: &[AffineFeature],
    class_sizes: &[usize],
    centres: &[usize],
    tol: &Tolerance,
    out: &mut Vec<Candidate>,
) {
    for group in repeat_groups(model, features, centres, tol) {
        // One feature per distinct position, in order along the axis.
        let mut row: Vec<usize> = group;
        row.sort_by(|&x, &y| features[x].values[0].total_cmp(&features[y].values[0]));
        row.dedup_by(|y, x| tol.equal(features[*x].values[0], features[*y].values[0]));
        for w in row.windows(3) {
            let v: Vec<f64> = w.iter().map(|&f| features[f].values[0]).collect();
            if !tol.equal(v[1] - v[0], v[2] - v[1]) {
                continue;
            }
            let form = features[w[0]].forms[0]
                .add_scaled(&features[w[1]].forms[0], -2.0)
                .add(&features[w[2]].forms[0]);
            if form.is_constant() {
                continue;
            }
            out.push(Candidate {
                kind: RelationKind::Spaced,
                a: w[0].min(w[2]),
                b: w[0].max(w[2]),
                rows: vec![form],
                multiplicity: class_sizes[w[0]] * class_sizes[w[1]] * class_sizes[w[2]],
                more: vec![w[1]],
                factor: 1.0,
            });
        }
    }
}

/// The centre features grouped by repeated parts: same primitive, and sizes that round to
/// the same multiple of the tolerance (a sort by sizes would interleave parts whose sizes
/// differ by round-off with others).
fn repeat_groups(
    model: &Model,
    features: &[AffineFeature],
    centres: &[usize],
    tol: &Tolerance,
) -> Vec<Vec<usize>> {
    type Key = (&'static str, Vec<i64>);
    let mut groups: std::collections::BTreeMap<Key, Vec<usize>> = Default::default();
    for &f in centres {
        let part = &model.parts[features[f].part];
        let (lo, hi) = part.world_bounds();
        let mut e: Vec<f64> = (0..3).map(|k| hi[k] - lo[k]).collect();
        e.sort_by(f64::total_cmp);
        let sizes = e.iter().map(|x| (x / tol.epsilon).round() as i64).collect();
        groups
            .entry((part.primitive.kind_name(), sizes))
            .or_default()
            .push(f);
    }
    groups.into_values().filter(|g| g.len() >= 3).collect()
}

#[cfg(test)]
mod tests {
    use crate::analysis::RelationKind;
    use crate::analysis::find_candidates;
    use crate::front::test_model as model;

    #[test]
    fn shelves_at_equal_gaps_are_spaced() {
        let m = model(
            "cube([2, 30, 80]);\nfor (z = [0, 15, 30, 45]) translate([2, 0, z]) cube([40, 30, 2]);\n",
        );
        let c = find_candidates(&m);
        let spaced: Vec<String> = c
            .list
            .iter()
            .filter(|x| x.kind == RelationKind::Spaced)
            .map(|x| c.describe(x))
            .collect();
        assert_eq!(spaced.len(), 2, "{spaced:?}");
    }
}
