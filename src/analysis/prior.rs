//! The structural prior: which relations to keep when there are no variations.
//!
//! The paper's symbolic baseline keeps every base constraint, which freezes a chair into a
//! scaled box. Without variations we keep what holds a design together and drop accidents:
//! coplanar faces, tangent sides and coincident points between parts that touch (their
//! bounding boxes meet),
//! every coaxiality, every mirror symmetry and equal spacing of repeated parts (`placement`),
//! equal insets (`inset`), equal extents along the same axis between repeated parts (same kind,
//! same sizes: four legs), and a bar's square profile (its two short sides equal, as a
//! cylinder's radius is one number). Equal sizes of unrelated parts, or of a board's or
//! block's own sides, go, and so do proportional sizes (one of many chances too: among
//! round numbers, halves are everywhere).
//!
//! Why these and not every equality: among n numbers some pair is equal by chance, and
//! the more pairs one looks at the likelier. The kept kinds are pairs the structure singles
//! out, one per contact, repeat or part (these two faces meet; this leg repeats that one;
//! this bar's cross-section), so an equality there is not one of many chances. A board's
//! footprint (a square seat) is singled out too, but it is what a designer stretches first
//! (a bench from a chair), so it is left to variations.

use super::candidates::{Candidates, RelationKind};
use crate::ir::{Affine, FeatureKind, Model};
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

/// How many times longer than its cross-section a part is to count as a bar (and a board
/// wider than its thickness: `names` calls that side the part's thickness).
pub(crate) const BAR_ELONGATION: f64 = 3.0;

/// Whether extents `a` and `b` of `part` are the cross-section of a bar: across its long
/// axis, which is at least [`BAR_ELONGATION`] times either.
fn square_profile(model: &Model, part: usize, a: FeatureKind, b: FeatureKind) -> bool {
    let (FeatureKind::Extent { axis: i }, FeatureKind::Extent { axis: j }) = (a, b) else {
        return false;
    };
    if i == j {
        return false;
    }
    let (lo, hi) = model.parts[part].world_bounds();
    let extent = |k: u8| hi[usize::from(k)] - lo[usize::from(k)];
    let long = extent(3 - i - j);
    long >= BAR_ELONGATION * extent(i).max(extent(j))
}

/// Indices of the candidates the prior keeps.
pub fn structural_prior(model: &Model, c: &Candidates) -> Vec<usize> {
    let tol = c.tolerance;
    (0..c.list.len())
        .filter(|&i| {
            let cand = &c.list[i];
            let (fa, fb) = (&c.features[cand.a], &c.features[cand.b]);
            match cand.kind {
                RelationKind::Coaxial
                | RelationKind::Symmetric
                | RelationKind::Spaced
                | RelationKind::Inset => true,
                RelationKind::Coplanar | RelationKind::Coincident | RelationKind::Tangent => {
                    fa.part != fb.part && touching(model, fa.part, fb.part, &tol)
                }
                RelationKind::Proportional => false,
                RelationKind::Equal => {
                    let same_axis = matches!((fa.kind, fb.kind),
                        (FeatureKind::Extent { axis: x }, FeatureKind::Extent { axis: y }) if x == y);
                    if fa.part == fb.part {
                        square_profile(model, fa.part, fa.kind, fb.kind)
                    } else {
                        same_axis && repeated(model, fa.part, fb.part, &tol)
                    }
                }
            }
        })
        .collect()
}

/// The rows of every relation the prior keeps on `model` (each zero there, to tolerance).
pub fn structural_rows(model: &Model) -> Vec<Affine> {
    let c = super::find_candidates(model);
    structural_prior(model, &c)
        .into_iter()
        .flat_map(|i| c.list[i].rows.iter().cloned())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::structural_prior;
    use crate::analysis::{RelationKind, find_candidates};
    use crate::front::test_model as model;

    /// The prior's equalities of one part's own sides: `(kept, dropped)`.
    fn own_sides(text: &str) -> (usize, usize) {
        let m = model(text);
        let c = find_candidates(&m);
        let kept = structural_prior(&m, &c);
        let own: Vec<usize> = (0..c.list.len())
            .filter(|&i| {
                let x = &c.list[i];
                x.kind == RelationKind::Equal && c.features[x.a].part == c.features[x.b].part
            })
            .collect();
        let k = own.iter().filter(|i| kept.contains(i)).count();
        (k, own.len() - k)
    }

    #[test]
    fn a_bars_square_profile_is_kept_and_a_boards_square_footprint_is_not() {
        assert_eq!(own_sides("cube([4, 4, 45]);\n"), (1, 0));
        assert_eq!(own_sides("cube([40, 40, 3]);\n"), (0, 1));
        // Not elongated enough to be a bar: a block.
        assert_eq!(own_sides("cube([10, 10, 20]);\n"), (0, 1));
    }
}
