//! Anchors: where a re-parameterized model is pinned, and variations read in its frame.
//!
//! A model's sliders say nothing about where it stands, so three anchor rows pin it: the
//! centre of its extreme faces in x and y and its floor in z ([`anchor_rows`]). A variation
//! is projected keeping its own place (anchors at its own centre and floor), then moved
//! rigidly so its anchors are where the input has them ([`moved_to_input_anchor`]): sliders
//! are read in the input's frame. Invariant: a move is applied only when some slot change
//! translates every face alike (to the tolerance); otherwise the point is left as it is.

use super::linalg::least_norm_solve;
use super::project::{Faces, project_onto};
use crate::ir::feature::world_intervals;
use crate::ir::{Affine, Model, SlotId};
use crate::tolerance::RELATIVE_EPSILON;

/// Rows that pin the model in place: its centre in x and y and its floor in z, at the
/// input. The faces used are the input's extremes.
pub fn anchor_rows(model: &Model) -> Vec<Affine> {
    anchor_rows_at(model, &model.slot_values())
}

/// The anchor rows with their constants taken at `at` instead of the input: the same
/// faces, held where `at` has them (a variation keeps its own place while projected).
pub fn anchor_rows_at(model: &Model, at: &[f64]) -> Vec<Affine> {
    let values = model.slot_values();
    let mut lo: [Option<(f64, Affine)>; 3] = Default::default();
    let mut hi: [Option<(f64, Affine)>; 3] = Default::default();
    for p in model.parts.iter().filter(|p| p.misaligned.is_none()) {
        let Some(iv) = world_intervals(p) else {
            continue;
        };
        for a in 0..3 {
            if let (Some(l), Some(h)) = (iv[a].0.affine(), iv[a].1.affine()) {
                let (lv, hv) = (l.eval(&values), h.eval(&values));
                if lo[a].as_ref().is_none_or(|(v, _)| lv < *v) {
                    lo[a] = Some((lv, l.clone()));
                }
                if hi[a].as_ref().is_none_or(|(v, _)| hv > *v) {
                    hi[a] = Some((hv, h.clone()));
                }
            }
        }
    }
    let mut rows = Vec::new();
    for a in 0..2 {
        if let (Some((_, l)), Some((_, h))) = (&lo[a], &hi[a]) {
            let centre = l.add(h).scale(0.5);
            rows.push(centre.sub(&Affine::constant(centre.eval(at))));
        }
    }
    if let Some((_, l)) = &lo[2] {
        rows.push(l.sub(&Affine::constant(l.eval(at))));
    }
    rows
}

/// `x` moved rigidly (in slot space) so the model's anchors — centre in x and y, floor in
/// z — are where the input has them: the smallest slot change that shifts every face by
/// the same amount along its axis. Sliders are read in the input's frame; where no slot
/// change translates the whole model, `x` is returned as it is.
pub fn moved_to_input_anchor(model: &Model, x: &[f64]) -> Vec<f64> {
    let at_input = anchor_rows_at(model, &model.slot_values());
    let here = anchor_rows_at(model, x);
    // anchor(x) − anchor(x0) per axis (x and y centres, z floor).
    let shift: Vec<f64> = here
        .iter()
        .zip(&at_input)
        .map(|(h, i)| h.constant - i.constant)
        .collect();
    if shift.len() != 3 || shift.iter().all(|s| *s == 0.0) {
        return x.to_vec();
    }
    let mut rows: Vec<(Vec<(SlotId, f64)>, f64)> = Vec::new();
    for p in model.parts.iter().filter(|p| p.misaligned.is_none()) {
        let Some(iv) = world_intervals(p) else {
            continue;
        };
        for (a, (lo, hi)) in iv.iter().enumerate() {
            for n in [lo, hi] {
                if let Some(f) = n.affine() {
                    rows.push((f.terms.clone(), shift[a]));
                }
            }
        }
    }
    let (delta, residual) = least_norm_solve(&rows, model.slots.len());
    if residual > RELATIVE_EPSILON * model.size().max(1.0) {
        return x.to_vec();
    }
    x.iter().zip(delta.iter()).map(|(a, b)| a + b).collect()
}

/// Each variation (slot values, with the parts it does without) projected onto `rows` and
/// its own anchors, then moved into the input's frame. Rigid moves are not what the sliders
/// express, and the free sizes do not depend on them.
pub fn project_variations(
    model: &Model,
    faces: &Faces,
    rows: &[Affine],
    values: &[Vec<f64>],
    optional: &[Vec<usize>],
) -> Vec<Vec<f64>> {
    values
        .iter()
        .zip(optional)
        .map(|(v, o)| {
            let anchors = anchor_rows_at(model, v);
            let all_rows: Vec<&Affine> = rows.iter().chain(anchors.iter()).collect();
            let p = project_onto(faces, v, &all_rows, o);
            moved_to_input_anchor(model, &p)
        })
        .collect()
}
