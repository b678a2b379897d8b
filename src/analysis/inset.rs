//! Equal insets: a part set in from a touching, wider part by the same margin on two axes
//! (a leg set 3 units in from the seat's left side and 3 from its front, a drawer front
//! inset equally from its frame). Not one of the paper's four kinds; with mirror symmetry it
//! is what lets one slider move the four legs of a chair in from the corners.
//!
//! A part `p` lies inside a part `q` on an axis when `q.lo ≤ p.lo` and `p.hi ≤ q.hi`; its
//! margin there is the gap to `q`'s nearer face on that axis (the low one on a tie), written
//! as `inner − outer` of two face planes (`p.lo − q.lo` or `q.hi − p.hi`) so it is positive.
//! Two margins of the same pair on different axes that are equal (within the model's
//! tolerance) and not zero (a zero margin is a coplanarity, already a candidate) give
//! `(inner₁ − outer₁) − (inner₂ − outer₂) = 0`. Only touching pairs are looked at, so the
//! work is the contact pairs times three axis pairs.

use super::candidates::{AffineFeature, Candidate, RelationKind};
use super::prior::touching;
use crate::ir::{FeatureKind, Model};
use crate::tolerance::Tolerance;
use std::collections::HashMap;

/// Which feature class holds a part's face plane (or a round part's side plane) on one
/// axis and side: `(part, axis, high) → class`.
pub type FaceIndex = HashMap<(usize, u8, bool), usize>;

/// The face index of the model's raw features, given each raw feature's class.
pub fn face_index(raw: &[AffineFeature], class_of: &[usize]) -> FaceIndex {
    raw.iter()
        .zip(class_of)
        .filter_map(|(f, &c)| match f.kind {
            FeatureKind::Plane { axis, high } | FeatureKind::Side { axis, high } => {
                Some(((f.part, axis, high), c))
            }
            _ => None,
        })
        .collect()
}

/// One margin: the two face classes whose difference it is, and its value.
struct Margin {
    inner: usize,
    outer: usize,
    value: f64,
}

/// The margin of `p` inside `q` on `axis`, if `p` lies inside `q` there and is not flush.
fn margin(
    model: &Model,
    faces: &FaceIndex,
    p: usize,
    q: usize,
    axis: u8,
    tol: &Tolerance,
) -> Option<Margin> {
    let k = usize::from(axis);
    let (plo, phi) = model.parts[p].world_bounds();
    let (qlo, qhi) = model.parts[q].world_bounds();
    let (low, high) = (plo[k] - qlo[k], qhi[k] - phi[k]);
    if low < -tol.epsilon || high < -tol.epsilon {
        return None;
    }
    let high_side = high < low - tol.epsilon;
    let value = if high_side { high } else { low };
    if value <= tol.epsilon {
        return None;
    }
    let face = |part: usize| faces.get(&(part, axis, high_side)).copied();
    let (pf, qf) = (face(p)?, face(q)?);
    Some(if high_side {
        Margin {
            inner: qf,
            outer: pf,
            value,
        }
    } else {
        Margin {
            inner: pf,
            outer: qf,
            value,
        }
    })
}

/// Every equal-inset relation that holds on the model.
pub fn inset_candidates(
    model: &Model,
    features: &[AffineFeature],
    faces: &FaceIndex,
    tol: &Tolerance,
) -> Vec<Candidate> {
    let mut out = Vec::new();
    let n = model.parts.len();
    for p in 0..n {
        for q in 0..n {
            if p == q || !touching(model, p, q, tol) {
                continue;
            }
            let margins: Vec<Option<Margin>> = (0..3u8)
                .map(|axis| margin(model, faces, p, q, axis, tol))
                .collect();
            for i in 0..3 {
                for j in i + 1..3 {
                    let (Some(m1), Some(m2)) = (&margins[i], &margins[j]) else {
                        continue;
                    };
                    if !tol.equal(m1.value, m2.value) {
                        continue;
                    }
                    let row = features[m1.inner].forms[0]
                        .sub(&features[m1.outer].forms[0])
                        .sub(&features[m2.inner].forms[0])
                        .add(&features[m2.outer].forms[0]);
                    if row.is_constant() {
                        continue;
                    }
                    out.push(Candidate {
                        kind: RelationKind::Inset,
                        a: m1.inner,
                        b: m2.inner,
                        rows: vec![row],
                        multiplicity: 1,
                        more: vec![m1.outer, m2.outer],
                        factor: 1.0,
                    });
                }
            }
        }
    }
    dedup(&mut out);
    out
}

/// Candidates with the same four features (parts made of one class, like a loop's legs)
/// are one relation.
fn dedup(out: &mut Vec<Candidate>) {
    out.sort_by(|x, y| (x.a, x.b, &x.more).cmp(&(y.a, y.b, &y.more)));
    let mut merged: Vec<Candidate> = Vec::with_capacity(out.len());
    for c in out.drain(..) {
        match merged.last_mut() {
            Some(last) if (last.a, last.b, &last.more) == (c.a, c.b, &c.more) => {
                last.multiplicity += 1
            }
            _ => merged.push(c),
        }
    }
    *out = merged;
}

#[cfg(test)]
mod tests {
    use crate::analysis::RelationKind;
    use crate::analysis::find_candidates;
    use crate::front::test_model as model;

    fn insets(text: &str) -> Vec<String> {
        let c = find_candidates(&model(text));
        c.list
            .iter()
            .filter(|x| x.kind == RelationKind::Inset)
            .map(|x| c.describe(x))
            .collect()
    }

    #[test]
    fn legs_set_in_equally_from_a_seat_are_inset() {
        let seat = "translate([0, 0, 45]) cube([44, 42, 3]);\n";
        let legs =
            "translate([3, 3, 0]) cube([4, 4, 45]);\ntranslate([37, 35, 0]) cube([4, 4, 45]);\n";
        let found = insets(&format!("{seat}{legs}"));
        assert_eq!(found.len(), 2, "{found:?}");
        // Unequal margins, flush legs and parts that do not touch give none.
        let uneven = "translate([3, 5, 0]) cube([4, 4, 45]);\n";
        assert!(insets(&format!("{seat}{uneven}")).is_empty());
        assert!(insets(&format!("{seat}cube([4, 4, 45]);\n")).is_empty());
        assert!(insets(&format!("{seat}translate([3, 3, 0]) cube([4, 4, 40]);\n")).is_empty());
    }
}
