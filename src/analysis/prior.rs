//! The structural prior: which relations to keep when there are no variations.
//!
//! The paper's symbolic baseline keeps every base constraint, which freezes a chair into a
//! scaled box. Without variations we keep what holds a design together and drop accidents:
//! coplanar faces, tangent sides and coincident points between parts that touch (their
//! bounding boxes meet),
//! every coaxiality, every mirror symmetry and equal spacing of repeated parts (`placement`),
//! and equal extents along the same axis between repeated parts (same kind,
//! same sizes: four legs). Equal sizes of unrelated parts, or of one part's own sides, go.

use super::candidates::{Candidates, RelationKind};
use crate::ir::{FeatureKind, Model};
use crate::tolerance::Tolerance;

/// Whether two parts' bounding boxes touch or overlap.
pub(crate) fn touching(model: &Model, a: usize, b: usize, tol: &Tolerance) -> bool {
    let (alo, ahi) = model.parts[a].world_bounds();
    let (blo, bhi) = model.parts[b].world_bounds();
    (0..3).all(|k| alo[k] <= bhi[k] + tol.epsilon && blo[k] <= ahi[k] + tol.epsilon)
}

/// Parts that are repeats of each other: same primitive kind and the same sorted extents.
pub(crate) fn repeated(model: &Model, a: usize, b: usize, tol: &Tolerance) -> bool {
    let (pa, pb) = (&model.parts[a], &model.parts[b]);
    if pa.primitive.kind_name() != pb.primitive.kind_name() {
        return false;
    }
    let ext = |p: &crate::ir::Part| {
        let (lo, hi) = p.world_bounds();
        let mut e: Vec<f64> = (0..3).map(|k| hi[k] - lo[k]).collect();
        e.sort_by(f64::total_cmp);
        e
    };
    ext(pa)
        .iter()
        .zip(ext(pb).iter())
        .all(|(x, y)| tol.equal(*x, *y))
}

/// Indices of the candidates the prior keeps.
pub fn structural_prior(model: &Model, c: &Candidates) -> Vec<usize> {
    let tol = c.tolerance;
    (0..c.list.len())
        .filter(|&i| {
            let cand = &c.list[i];
            let (fa, fb) = (&c.features[cand.a], &c.features[cand.b]);
            match cand.kind {
                RelationKind::Coaxial | RelationKind::Symmetric | RelationKind::Spaced => true,
                RelationKind::Coplanar | RelationKind::Coincident | RelationKind::Tangent => {
                    fa.part != fb.part && touching(model, fa.part, fb.part, &tol)
                }
                RelationKind::Equal => {
                    let same_axis = matches!((fa.kind, fb.kind),
                        (FeatureKind::Extent { axis: x }, FeatureKind::Extent { axis: y }) if x == y);
                    fa.part != fb.part && same_axis && repeated(model, fa.part, fb.part, &tol)
                }
            }
        })
        .collect()
}
