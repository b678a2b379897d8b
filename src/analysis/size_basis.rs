//! Which slots are free, chosen so the sliders' box can hold the presets.
//!
//! The solve (`reparam`) makes the most wanted slots free (named ones, then the larger
//! parts' sizes). A kept relation that adds sizes up (a panel between two legs spans the
//! top less the legs) then leaves the least wanted of them dependent, and that can be a
//! small size written as the difference of large ones: a leg's thickness as the top's size
//! less the panel's width less the other leg. Each slider's range spans the input and the
//! presets, and every size must stay above its floor at every setting in the box of ranges
//! (`ranges`). A difference of large sizes falls below it at the box's corners as soon as
//! the large ones vary across the presets; the box then shrinks towards the input and the
//! presets are clamped into it (a generated table explored towards a 120-unit top got a
//! preset with a 174-unit one). The same family of models has other coordinates: with the
//! panel's width dependent (the top less both legs), every size is a sum of free ones and
//! the box holds every preset.
//!
//! [`exchange_for_sizes`] changes the basis one exchange at a time (a free slot leaves, a
//! dependent slot of a size short over the box takes its place) while that lowers the
//! sizes' shortfall: the sum over sizes of how far the least value over the box of the
//! input and the presets falls below the size's floor (`ranges::SIZE_FLOOR` of its input
//! value). Among exchanges that lower it alike, the one giving up the least wanted free
//! slot. An exchange only changes coordinates: the model's numbers over all settings are
//! the same affine family.
//!
//! It runs after the contacts have made their variables (`contact_vars`), which stay: only
//! a free variable that is a slot leaves. Invariant: each exchange lowers the shortfall by
//! more than the model's tolerance, so it ends.

use super::contact_vars::substitute;
use super::ranges::{hull, in_free, min_over_box, size_floors};
use super::reparam::{Solution, wanted_rank};
use crate::ir::{Affine, Model, SlotId};
use crate::tolerance::{COEFFICIENT_ZERO, Tolerance};

/// Exchanges free slots of `sol` for dependent ones while that lowers the sizes' shortfall
/// over the box of the input and the `projected` variations (slot values). Whether it
/// exchanged any.
pub fn exchange_for_sizes(model: &Model, sol: &mut Solution, projected: &[Vec<f64>]) -> bool {
    let mut exchanged = false;
    let sizes = size_floors(model);
    let points: Vec<Vec<f64>> = std::iter::once(model.slot_values())
        .chain(projected.iter().cloned())
        .collect();
    let rank = wanted_rank(model);
    let eps = Tolerance::for_size(model.size()).epsilon;
    let mut current = shortfall(sol, &sizes, &points);
    while current.iter().sum::<f64>() > eps {
        let mut best: Option<(f64, usize, Solution)> = None;
        for (j, s) in exchanges(sol, &sizes, &current) {
            let mut trial = sol.clone();
            exchange(&mut trial, j, s);
            let total: f64 = shortfall(&trial, &sizes, &points).iter().sum();
            let out = rank[sol.free[j] as usize];
            let better = best
                .as_ref()
                .is_none_or(|(t, r, _)| total < t - eps || (total <= t + eps && out < *r));
            if better {
                best = Some((total, out, trial));
            }
        }
        match best {
            Some((total, _, trial)) if total < current.iter().sum::<f64>() - eps => {
                *sol = trial;
                current = shortfall(sol, &sizes, &points);
                exchanged = true;
            }
            _ => break,
        }
    }
    exchanged
}

/// Per size, how far its least value over the box of `points` (slot values; the input
/// first) in `sol`'s free variables falls below its floor (`floors`: each size less its
/// floor, `ranges::size_floors`; 0 where it does not).
fn shortfall(sol: &Solution, floors: &[Affine], points: &[Vec<f64>]) -> Vec<f64> {
    let free: Vec<Vec<f64>> = points.iter().map(|x| sol.free_values(x)).collect();
    let n = sol.free.len();
    let (lo, hi) = hull(
        &free[0],
        &free[1..],
        &vec![f64::NEG_INFINITY; n],
        &vec![f64::INFINITY; n],
    );
    floors
        .iter()
        .map(|f| {
            let (c, a) = in_free(f, sol);
            (-min_over_box(c, &a, |i| (lo[i], hi[i]))).max(0.0)
        })
        .collect()
}

/// The exchanges worth trying: for each size short over the box, each dependent slot it
/// reads with each free variable that slot follows and that is a slot, not a contact's
/// depth (free index, dependent slot).
fn exchanges(sol: &Solution, sizes: &[Affine], short: &[f64]) -> Vec<(usize, SlotId)> {
    let mut out = Vec::new();
    for (f, _) in sizes.iter().zip(short).filter(|(_, d)| **d > 0.0) {
        for &(s, _) in &f.terms {
            if sol.free.contains(&s) {
                continue;
            }
            for &(j, b) in &sol.exprs[s as usize].terms {
                let slot = sol.contact(j).is_none();
                if slot && b.abs() > COEFFICIENT_ZERO && !out.contains(&(j, s)) {
                    out.push((j, s));
                }
            }
        }
    }
    out
}

/// Makes dependent slot `s` the free variable at index `j` in place of the slot there.
fn exchange(sol: &mut Solution, j: usize, s: SlotId) {
    let e = &sol.exprs[s as usize];
    let mut a = vec![0.0; sol.free.len()];
    for &(i, v) in &e.terms {
        a[i] = v;
    }
    let form = (e.constant, a);
    substitute(sol, &form, j);
    sol.free[j] = s;
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::anchors::Anchors;
    use crate::analysis::reparam::solve;
    use crate::ir::feature::world_intervals;

    /// Part `p`'s (low, high) faces along x.
    fn x_faces(model: &Model, p: usize) -> (Affine, Affine) {
        let [(lo, hi), _, _] = world_intervals(&model.parts[p]).unwrap();
        (lo.affine().unwrap().clone(), hi.affine().unwrap().clone())
    }

    /// A 100-unit top over a 10-unit leg at each end and a panel filling the span between
    /// the legs, kept flush with the top and the legs: the legs and the panel add up to the
    /// top, and the legs are the smallest parts, so the solve leaves a leg dependent.
    fn top_legs_panel() -> (Model, Vec<Affine>) {
        let model = crate::front::test_model(
            "translate([0, 0, 50]) cube([100, 20, 10]);\n\
             cube([10, 20, 50]);\n\
             translate([90, 0, 0]) cube([10, 20, 50]);\n\
             translate([10, 0, 0]) cube([80, 20, 50]);\n",
        );
        let [top, left, right, panel] = [0, 1, 2, 3].map(|p| x_faces(&model, p));
        let rows = vec![
            left.0.sub(&top.0),
            right.1.sub(&top.1),
            panel.0.sub(&left.1),
            panel.1.sub(&right.0),
        ];
        (model, rows)
    }

    #[test]
    fn a_leg_left_as_the_top_less_the_panel_is_exchanged_for_a_sum() {
        let (model, rows) = top_legs_panel();
        let mut sol = solve(&model, &Anchors::of(&model), &rows);
        let input = model.slot_values();
        let width = |p: usize| {
            let (lo, hi) = x_faces(&model, p);
            hi.sub(&lo)
        };
        // Free variables that set the top's and the panel's widths, the legs' kept.
        let top = sol.free.iter().position(|&f| width(0).terms == [(f, 1.0)]);
        let panel = sol.free.iter().position(|&f| width(3).terms == [(f, 1.0)]);
        let (Some(top), Some(panel)) = (top, panel) else {
            panic!("the solve left the top or the panel dependent: {sol:?}");
        };
        // A preset 40 units narrower: the top and the panel both.
        let mut free = sol.free_values(&input);
        free[top] -= 40.0;
        free[panel] -= 40.0;
        let narrow = sol.slot_values(&free);
        let points = [input.clone(), narrow.clone()];
        let sizes = size_floors(&model);
        let before: f64 = shortfall(&sol, &sizes, &points).iter().sum();
        assert!(
            before > 0.0,
            "the leg is not the top less the panel: {sol:?}"
        );
        let family = sol.clone();
        exchange_for_sizes(&model, &mut sol, std::slice::from_ref(&narrow));
        let after: f64 = shortfall(&sol, &sizes, &points).iter().sum();
        assert_eq!(after, 0.0, "{sol:?}");
        // The same family: every setting of the old sliders is one of the new.
        for free in [family.free_values(&input), family.free_values(&narrow)] {
            let mut moved = free.clone();
            moved
                .iter_mut()
                .enumerate()
                .for_each(|(i, v)| *v += i as f64);
            let x = family.slot_values(&moved);
            let back = sol.slot_values(&sol.free_values(&x));
            for (a, b) in x.iter().zip(&back) {
                assert!((a - b).abs() < 1e-9, "{x:?} became {back:?}");
            }
        }
    }

    #[test]
    fn a_box_that_holds_every_size_keeps_its_basis() {
        let (model, rows) = top_legs_panel();
        let mut sol = solve(&model, &Anchors::of(&model), &rows);
        let before = sol.free.clone();
        // A preset with the top 4 units narrower, one leg taking it all: no size short.
        let input = model.slot_values();
        let mut free = sol.free_values(&input);
        let top = sol.free.iter().position(|&f| {
            let (lo, hi) = x_faces(&model, 0);
            hi.sub(&lo).terms == [(f, 1.0)]
        });
        free[top.unwrap()] -= 4.0;
        let preset = sol.slot_values(&free);
        exchange_for_sizes(&model, &mut sol, &[preset]);
        assert_eq!(sol.free, before);
    }
}
