//! Gauge: slot changes that change no part, held at the input.
//!
//! Some programs say one thing twice: a `.csg` export wraps the whole model in a
//! `multmatrix` whose translation adds to every part's own, and `translate([a, 0, 0])
//! translate([b, 0, 0])` only means `a + b`. A slot change that leaves every number of every
//! part as it is (each world-matrix entry and primitive argument) changes nothing a user
//! can see, so it must not become a slider. [`gauge_rows`] pins those directions by holding
//! some slots at their input values: slots shaping the most parts first (an outer wrapper's
//! translation is placement, which the anchors already own), until no such direction is
//! left. Invariant: the rows only remove directions that change no part; every geometric
//! freedom of the model survives them.

use super::slotblocks::SlotBlocks;
use crate::ir::{Affine, Model, SlotId};
use crate::tolerance::RELATIVE_ROUNDOFF;
use nalgebra::DMatrix;

/// Rows `slot = input value` that remove every slot direction changing no part.
pub fn gauge_rows(model: &Model) -> Vec<Affine> {
    let slots = model.slots.len();
    let (forms, pinned) = part_forms(model, slots);
    let mut blocks = SlotBlocks::new(slots);
    for f in &forms {
        blocks.join(f.slots());
    }
    let mut shaped = vec![0usize; slots];
    for p in &model.parts {
        let mut deps: Vec<SlotId> = p.slot_deps().collect();
        deps.sort_unstable();
        deps.dedup();
        deps.iter().for_each(|&s| shaped[s as usize] += 1);
    }
    let mut by_block: std::collections::HashMap<SlotId, Vec<usize>> = Default::default();
    for (i, f) in forms.iter().enumerate() {
        if let Some(s) = f.slots().next() {
            by_block.entry(blocks.find(s)).or_default().push(i);
        }
    }
    let positions = places_only(model, slots);
    let x0 = model.slot_values();
    let mut fixed: Vec<SlotId> = Vec::new();
    for members in by_block.values() {
        let mut unknowns: Vec<SlotId> = members.iter().flat_map(|&i| forms[i].slots()).collect();
        unknowns.sort_unstable();
        unknowns.dedup();
        unknowns.retain(|s| !pinned[*s as usize]);
        if unknowns.len() < 2 {
            continue;
        }
        let rows: Vec<&Affine> = members.iter().map(|&i| &forms[i]).collect();
        fixed.extend(fix_null_space(&rows, &unknowns, &shaped, &positions));
    }
    // Slots no part depends on at all change nothing either.
    fixed.extend((0..slots as SlotId).filter(|&s| shaped[s as usize] == 0));
    fixed.sort_unstable();
    fixed.dedup();
    fixed
        .into_iter()
        .map(|s| Affine::slot(s).sub(&Affine::constant(x0[s as usize])))
        .collect()
}

/// Per slot: whether it only places parts (it reaches world translations and no size, no
/// scale, no primitive argument). The slot's first use does not say: `h` in
/// `translate([0, 0, h - 4]) … cube([w, d, h - 4])` is first a position, yet a size.
fn places_only(model: &Model, slots: usize) -> Vec<bool> {
    let mut places = vec![false; slots];
    let mut shapes = vec![false; slots];
    for p in &model.parts {
        // The world matrix's rows are [a b c t]: every fourth number is a translation.
        for (k, n) in p.numbers().enumerate() {
            let translation = k < 12 && k % 4 == 3;
            for s in n.deps() {
                if translation {
                    places[s as usize] = true;
                } else {
                    shapes[s as usize] = true;
                }
            }
        }
    }
    places.iter().zip(&shapes).map(|(&p, &s)| p && !s).collect()
}

/// The affine part numbers (their linear parts are what a slot change moves), and which
/// slots some non-affine number depends on (any change of those changes a part).
fn part_forms(model: &Model, slots: usize) -> (Vec<Affine>, Vec<bool>) {
    let mut forms = Vec::new();
    let mut pinned = vec![false; slots];
    for p in &model.parts {
        for n in p.numbers() {
            match n.affine() {
                Some(a) if !a.is_constant() => forms.push(a.clone()),
                Some(_) => {}
                None => n.deps().into_iter().for_each(|s| pinned[s as usize] = true),
            }
        }
    }
    (forms, pinned)
}

/// The slots to hold so that no direction over `unknowns` leaves every row unchanged:
/// a basis of that null space, then, slot by slot (positions first, then most parts shaped
/// first), a slot the basis still moves is held and the basis reduced by it. A position
/// goes first because a size, or a number that is both (`h` in `translate([0, 0, h - 4])`
/// and `cube([w, d, h - 4])`), is what a user drags.
fn fix_null_space(
    rows: &[&Affine],
    unknowns: &[SlotId],
    shaped: &[usize],
    positions: &[bool],
) -> Vec<SlotId> {
    let k = unknowns.len();
    let col = |s: SlotId| unknowns.binary_search(&s).ok();
    let mut p = DMatrix::<f64>::zeros(rows.len(), k);
    for (i, r) in rows.iter().enumerate() {
        for &(s, a) in &r.terms {
            if let Some(j) = col(s) {
                p[(i, j)] += a;
            }
        }
    }
    let gram = p.transpose() * &p;
    let scale = gram
        .iter()
        .fold(0.0f64, |m, v| m.max(v.abs()))
        .max(f64::MIN_POSITIVE);
    let eigen = gram.symmetric_eigen();
    let cutoff = RELATIVE_ROUNDOFF * scale * k as f64;
    let mut basis: Vec<Vec<f64>> = (0..k)
        .filter(|&j| eigen.eigenvalues[j].abs() <= cutoff)
        .map(|j| eigen.eigenvectors.column(j).iter().copied().collect())
        .collect();
    let mut order: Vec<usize> = (0..k).collect();
    order.sort_by_key(|&j| {
        let s = unknowns[j];
        (
            !positions[s as usize],
            std::cmp::Reverse(shaped[s as usize]),
            s,
        )
    });
    let mut fixed = Vec::new();
    for j in order {
        if basis.is_empty() {
            break;
        }
        let Some((pick, lead)) = basis
            .iter()
            .enumerate()
            .map(|(c, v)| (c, v[j]))
            .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
        else {
            break;
        };
        if lead.abs() <= RELATIVE_ROUNDOFF.sqrt() {
            continue;
        }
        let pivot = basis.swap_remove(pick);
        for v in &mut basis {
            let t = v[j] / lead;
            v.iter_mut().zip(&pivot).for_each(|(x, y)| *x -= t * y);
        }
        fixed.push(unknowns[j]);
    }
    fixed
}

#[cfg(test)]
mod tests {
    use super::gauge_rows;
    use crate::front::test_model as model;

    /// The slots the gauge holds, by their values in the source.
    fn held(text: &str) -> Vec<f64> {
        let m = model(text);
        let rows = gauge_rows(&m);
        rows.iter()
            .filter_map(|r| r.slots().next())
            .map(|s| m.slots[s as usize].value)
            .collect()
    }

    #[test]
    fn a_number_that_sizes_parts_stays_free_over_one_that_only_places() {
        // `h + 1` and both `4`s + 1 change nothing; `h` (first used in a translate, but
        // sizing the legs) is the slider, the `4` that only places the top is held.
        let text = "module b(h = 45) {\n translate([0, 0, h - 4]) cube([90, 40, 3]);\n \
                    for (x = [0, 85]) translate([x, 0, 0]) cube([5, 5, h - 4]);\n}\nb(h = 50);\n";
        assert_eq!(held(text), vec![4.0]);
    }

    #[test]
    fn an_outer_translation_added_to_every_part_is_held() {
        let text = "translate([7, 0, 0]) { translate([3, 0, 0]) cube(5); translate([9, 0, 0]) cube(5); }\n";
        // One direction per axis changes nothing; the wrapper's numbers (7, 0, 0) are held,
        // each part's own placement (3, 9) stays.
        assert_eq!(held(text), vec![7.0, 0.0, 0.0]);
    }
}
