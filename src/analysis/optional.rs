//! Optional parts: parts a variation does without.
//!
//! Variations are the same program with other numbers, so a variation leaves a part out by
//! typing a zero for one of its sizes (or a zero scale): the part then draws nothing. That
//! is the test: removing the part changes less than the float tolerance's share of its own
//! volume in the input, *and* one of its own extents is zero within the model's tolerance.
//! Both halves matter:
//! - A part that removing changes nothing because others cover it is still in the design:
//!   noise or the variation moved it inside a neighbour (a wheel inside an axle whose noisy
//!   radius came out larger), and its numbers still carry the design's relations. The
//!   geometry is explained as well with it as without, so the prior (no switch) decides.
//! - A size moved past zero (a negative radius that draws nothing) is a number noise moved,
//!   and the part is still meant.
//! - A zero extent alone does not say the part draws nothing: an axis-aligned cone's
//!   extent is taken at the radius larger at the input, and a variation may set that one
//!   to zero while the other still draws a cone. The removal says so.
//!
//! So a thin board whose numbers are noisy is still there. A part the input does not show
//! either (hidden inside others) is never optional: leaving it out changes no variation, so
//! there is nothing to switch. Parts optional in exactly the same set of variations form
//! one toggle (a Customizer checkbox, on by default). Fitted variations are judged the same
//! way: a part a picture no longer shows keeps its numbers, and its deviations weigh its
//! faces in discovery instead.

use super::discover::Similarity;
use crate::ir::feature::world_intervals;
use crate::ir::{Model, Num, Part, Primitive};

/// Volume changed by removing a part, as a fraction of its own volume in the input, below
/// which removing it changes nothing.
pub const OPTIONAL_THRESHOLD: f64 = crate::tolerance::OPTIONAL_PART_LOSS;

/// A group of parts switched together, and the variations that do without them.
#[derive(Debug, Clone, PartialEq)]
pub struct Toggle {
    pub parts: Vec<usize>,
    pub off_in: Vec<usize>,
}

/// The part's extents at the slot values `x`, signed: along the world axes when the part is
/// axis-aligned (so a zero scale counts), else its primitive's own sizes.
fn extents_at(part: &Part, x: &[f64]) -> Vec<f64> {
    let at = |n: &Num| n.affine().map_or(n.value, |a| a.eval(x));
    if let Some(iv) = world_intervals(part) {
        return iv.iter().map(|(lo, hi)| at(hi) - at(lo)).collect();
    }
    match &part.primitive {
        Primitive::Cube { size, .. } => size.iter().map(at).collect(),
        Primitive::Cylinder { h, r1, r2, .. } => vec![at(h), at(r1).max(at(r2))],
        Primitive::Sphere { r } => vec![at(r)],
    }
}

/// Whether one of the part's extents at `x` is zero within `eps`: a size typed as zero.
fn zero_sized(part: &Part, x: &[f64], eps: f64) -> bool {
    extents_at(part, x).iter().any(|e| e.abs() <= eps)
}

/// For each variation, the parts it does without.
///
/// Only a part with a zero extent is judged by its removal, so most parts cost nothing;
/// what the input shows of a part is integrated only for those.
pub fn optional_parts<S: Similarity>(
    model: &Model,
    variations: &[Vec<f64>],
    sim: &S,
) -> Vec<Vec<usize>> {
    let x0 = model.slot_values();
    let input = sim.reference(&x0, &[]);
    let eps = crate::tolerance::Tolerance::for_size(model.size()).epsilon;
    // Whether the input shows each part (cached over the variations).
    let mut shown: Vec<Option<bool>> = vec![None; model.parts.len()];
    let mut out = Vec::with_capacity(variations.len());
    for v in variations {
        let zeroed: Vec<usize> = (0..model.parts.len())
            .filter(|&p| zero_sized(&model.parts[p], v, eps))
            .collect();
        if zeroed.is_empty() {
            out.push(Vec::new());
            continue;
        }
        let whole = sim.reference(v, &[]);
        let mut off = Vec::new();
        for p in zeroed {
            let shows = *shown[p].get_or_insert_with(|| {
                sim.removal_loss_lower_bound(&input, p) >= OPTIONAL_THRESHOLD
                    || sim.removal_loss(&input, p) >= OPTIONAL_THRESHOLD
            });
            if shows && sim.removal_loss(&whole, p) < OPTIONAL_THRESHOLD {
                off.push(p);
            }
        }
        out.push(off);
    }
    out
}

/// The variations' slot values with every slot that shapes only parts a variation does
/// without set back to the input's: such a part keeps the model's own shape there, so
/// presets and blends never shrink it to nothing (its switch hides it instead).
pub fn held_where_skipped(
    model: &Model,
    variations: &[Vec<f64>],
    optional: &[Vec<usize>],
) -> Vec<Vec<f64>> {
    let x0 = model.slot_values();
    let owners = model.parts_by_slot();
    variations
        .iter()
        .zip(optional)
        .map(|(v, skip)| {
            v.iter()
                .enumerate()
                .map(|(s, &val)| {
                    let only_skipped =
                        !owners[s].is_empty() && owners[s].iter().all(|p| skip.contains(p));
                    if only_skipped { x0[s] } else { val }
                })
                .collect()
        })
        .collect()
}

/// Groups parts by the exact set of variations they are optional in.
pub fn toggles(parts: usize, optional: &[Vec<usize>]) -> Vec<Toggle> {
    let mut groups: Vec<Toggle> = Vec::new();
    for p in 0..parts {
        let off_in: Vec<usize> = (0..optional.len())
            .filter(|&j| optional[j].contains(&p))
            .collect();
        if off_in.is_empty() {
            continue;
        }
        match groups.iter_mut().find(|g| g.off_in == off_in) {
            Some(g) => g.parts.push(p),
            None => groups.push(Toggle {
                parts: vec![p],
                off_in,
            }),
        }
    }
    groups
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parts_optional_in_the_same_variations_share_a_toggle() {
        let optional = vec![vec![1, 2], vec![2], vec![1, 2]];
        let t = toggles(4, &optional);
        assert_eq!(
            t,
            vec![
                Toggle {
                    parts: vec![1],
                    off_in: vec![0, 2]
                },
                Toggle {
                    parts: vec![2],
                    off_in: vec![0, 1, 2]
                },
            ]
        );
    }
}
