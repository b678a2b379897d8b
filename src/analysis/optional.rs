//! Optional parts: parts a variation can do without.
//!
//! A part is optional in a variation when the variation's geometry is explained at least as
//! well without it, under the variations' noise model (`noise`): noise displaces the faces
//! of the parts a variation has, and a part it does without has no faces to displace, so
//! without the part, what removing it changes is nothing. What removing it changes, spread
//! over the part's largest side in the variation, is its *visible thickness*; the part is
//! dropped when that is within one noise deviation `σ` of nothing (a present part's faces
//! are rarely that close together by chance) and below half of what the input shows of it,
//! or, for exact variations (`sigma` 0: typed files, where a part is left out by typing a
//! zero or hidden inside others), when it changes less than the float tolerance's share of
//! the part's own volume and none of its extents is negative (a negative size that draws
//! nothing is noise past zero). So a thin board whose numbers are noisy is still there. A part the
//! input does not show either (hidden inside others) is never optional: leaving it out
//! changes no variation, so there is nothing to switch. Parts optional in exactly the same
//! set of variations form one toggle (a Customizer checkbox, on by default).

use super::discover::Similarity;
use crate::ir::feature::world_intervals;
use crate::ir::{Model, Part};

/// Volume changed by removing a part, as a fraction of its own volume in the input, below
/// which it is optional whatever the noise.
pub const OPTIONAL_THRESHOLD: f64 = crate::tolerance::OPTIONAL_PART_LOSS;

/// A group of parts switched together, and the variations that do without them.
#[derive(Debug, Clone, PartialEq)]
pub struct Toggle {
    pub parts: Vec<usize>,
    pub off_in: Vec<usize>,
}

/// A part's box at the slot values `x`: (thinnest extent, largest side's area), from its
/// world intervals when it has them, else its bounds at the input.
fn box_at(part: &Part, x: &[f64]) -> (f64, f64) {
    let extents: [f64; 3] = match world_intervals(part) {
        Some(iv) => std::array::from_fn(|k| {
            let at = |n: &crate::ir::Num| n.affine().map_or(n.value, |a| a.eval(x));
            (at(&iv[k].1) - at(&iv[k].0)).abs()
        }),
        None => {
            let (lo, hi) = part.world_bounds();
            std::array::from_fn(|k| hi[k] - lo[k])
        }
    };
    let thinnest = extents.iter().copied().fold(f64::INFINITY, f64::min);
    let area = (0..3)
        .map(|k| extents[(k + 1) % 3] * extents[(k + 2) % 3])
        .fold(0.0, f64::max);
    (thinnest, area)
}

/// Whether the part has a negative extent (beyond `eps`) at `x`: a size moved past zero.
fn negative_sized(part: &Part, x: &[f64], eps: f64) -> bool {
    let Some(iv) = world_intervals(part) else {
        return false;
    };
    let at = |n: &crate::ir::Num| n.affine().map_or(n.value, |a| a.eval(x));
    iv.iter().any(|(lo, hi)| at(hi) - at(lo) < -eps)
}

/// For each variation, the parts it does without, for variations whose faces carry noise
/// of `sigma` (world units; 0 for exact variations).
///
/// A part whose removal the similarity's cheap lower bound already shows too visible is
/// present without an exact removal integral, and what the input shows of a part is
/// integrated only when its bound cannot answer. The answer is the same either way.
pub fn optional_parts<S: Similarity>(
    model: &Model,
    variations: &[Vec<f64>],
    sim: &S,
    sigma: f64,
) -> Vec<Vec<usize>> {
    let x0 = model.slot_values();
    let input = sim.reference(&x0, &[]);
    let parts = model.parts.len();
    // What removing each part changes at the input: a cheap lower bound first, the exact
    // loss only when the bound cannot answer (both cached over the variations).
    let mut bound_at_input: Vec<Option<f64>> = vec![None; parts];
    let mut shown: Vec<Option<f64>> = vec![None; parts];
    let mut shows = |p: usize, past: &dyn Fn(f64) -> bool| -> bool {
        let bound =
            *bound_at_input[p].get_or_insert_with(|| sim.removal_loss_lower_bound(&input, p));
        past(bound) || past(*shown[p].get_or_insert_with(|| sim.removal_loss(&input, p)))
    };
    let at_input: Vec<(f64, f64)> = model.parts.iter().map(|p| box_at(p, &x0)).collect();
    let eps = crate::tolerance::Tolerance::for_size(model.size()).epsilon;
    let mut out = Vec::with_capacity(variations.len());
    for v in variations {
        let whole = sim.reference(v, &[]);
        let mut off = Vec::new();
        for (p, &(thickness, area)) in at_input.iter().enumerate() {
            // The visible thickness in `v` of a loss, relative to the input's thickness.
            let (_, area_v) = box_at(&model.parts[p], v);
            let relative = |loss: f64| {
                if area_v > 0.0 {
                    loss * area / area_v
                } else {
                    loss
                }
            };
            let bound = sim.removal_loss_lower_bound(&whole, p);
            let surely_present = bound >= OPTIONAL_THRESHOLD
                && (sigma <= 0.0 || relative(bound) * thickness > sigma);
            if surely_present || !shows(p, &|s| s >= OPTIONAL_THRESHOLD) {
                continue;
            }
            let loss = sim.removal_loss(&whole, p);
            let optional = if sigma <= 0.0 {
                // Exact variations: a part is left out by a zero or hidden inside others,
                // not by a size that only happens to draw nothing (a negative radius is a
                // number the noise moved past zero, and the part is still meant).
                loss < OPTIONAL_THRESHOLD && !negative_sized(&model.parts[p], v, eps)
            } else {
                loss < OPTIONAL_THRESHOLD
                    || (relative(loss) * thickness <= sigma
                        && shows(p, &|s| relative(loss) < 0.5 * s))
            };
            if optional {
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
