//! Contacts the box of slider ranges cannot keep, made sliders of their own.
//!
//! A contact side (`contacts`) is an affine form of the free variables that must stay
//! `≥ −slack`. When it involves one free variable, the slider's range keeps it exactly. When
//! it involves several (a top's height and a leg's height, neither tied to the other by a
//! kept relation), a box of ranges that holds every preset has corners where the parts come
//! apart, and shrinking the box would cut presets off. The principled way out is a change
//! of basis: the side's form becomes a free variable itself (how far the two parts overlap
//! along that axis), in place of a free variable that only places one of the two parts;
//! then the box keeps it like any size. The model's numbers at every setting are the same
//! affine family as before: only the coordinates the sliders show change.
//!
//! The variable replaced is one that only moves parts (sets no size) where the side has
//! one; otherwise a size (the top's height, say). Through a size, the derived sizes must
//! stay positive over the new box, which can cut a preset off: [`keep_contacts`] keeps a
//! change of basis only when the new box holds as many of the input and the presets.
//!
//! A variable the contacts pin (its range no wider than the slack, a part held from both
//! sides) is no slider: [`fix_pinned`] fixes it at its input value.
//!
//! Invariants: a replaced variable is not already a contact variable; the substitution
//! keeps every slot's expression exact (coefficients are read back as small fractions like
//! the solve's); one side is made a variable per call; the box [`keep_contacts`] returns
//! holds at least as many of the input and the presets as the box it started from.

use super::contacts::ContactSide;
use super::ranges::{Range, at_free, in_free, min_over_box, size_forms};
use super::reparam::{ContactVariable, Frac, Solution};
use crate::ir::Model;
use crate::tolerance::COEFFICIENT_ZERO;

/// A form in the free variables: `(constant, coefficient per free variable)`.
type InFree = (f64, Vec<f64>);

/// Free variables that set no size of any part (they only move parts).
fn positions(model: &Model, sol: &Solution) -> Vec<bool> {
    let mut out = vec![true; sol.free.len()];
    for f in size_forms(model) {
        let (_, a) = in_free(&f, sol);
        for (o, k) in out.iter_mut().zip(a) {
            if k.abs() > COEFFICIENT_ZERO {
                *o = false;
            }
        }
    }
    out
}

/// Which of the side's two parts free variable `j` moves (the first that depends on it).
fn moved_part(model: &Model, sol: &Solution, side: &ContactSide, j: usize) -> Option<usize> {
    side.parts.into_iter().find(|&p| {
        model.parts[p]
            .slot_deps()
            .into_iter()
            .any(|s| sol.exprs[s as usize].terms.iter().any(|&(i, _)| i == j))
    })
}

/// The box of slider ranges for a solution: the free variables' values at the input and at
/// each preset, and the ranges.
pub type Boxed = (Vec<f64>, Vec<Vec<f64>>, Vec<Range>);

/// Makes contact sides the box breaks free variables, one at a time, most broken first. A
/// change of basis is kept only when the box it leads to (`box_of`) holds as many of the
/// input and the presets as the box before: through a size, the sizes' positivity can
/// shrink the box off a preset; and a change that mends one side may part others (fewer
/// sides must be parted over the box, or as many by less: [`parting`]). Then the side's
/// next variable is tried in its place (the box is a different one for each), and the side
/// is left as it was only when none does both.
/// Returns the last box.
pub fn keep_contacts(
    model: &Model,
    sol: &mut Solution,
    contacts: &[ContactSide],
    slack: f64,
    box_of: &mut dyn FnMut(&Solution) -> Boxed,
) -> Boxed {
    let mut refused = Vec::new();
    let mut current = box_of(sol);
    loop {
        let (input, _, ranges) = &current;
        let mut trial = sol.clone();
        let Some(made) =
            make_one_contact_variable(model, &mut trial, contacts, input, ranges, slack, &refused)
        else {
            return current;
        };
        let next = box_of(&trial);
        let mends =
            parting(&trial, contacts, &next, slack) < parting(sol, contacts, &current, slack);
        if held(&next) >= held(&current) && mends {
            *sol = trial;
            current = next;
        } else {
            refused.push(made);
        }
    }
}

/// Holds for good each free variable the kept contacts pin: one whose range, shrunk so no
/// setting parts two parts in contact, is no wider than the slack the contacts are kept
/// with on either side (`2·slack`). No slider can move it by more than the tolerance the
/// model is compared at, so it is an equality the contacts imply (two parts that touch
/// from both sides along an axis), not a slider: it is fixed at its input value and the
/// box is taken again, until no variable is pinned.
pub fn fix_pinned(
    sol: &mut Solution,
    slack: f64,
    current: Boxed,
    box_of: &mut dyn FnMut(&Solution) -> Boxed,
) -> Boxed {
    let mut current = current;
    loop {
        let (input, _, ranges) = &current;
        let pinned = ranges.iter().position(|r| r.max - r.min <= 2.0 * slack);
        let Some(j) = pinned else {
            return current;
        };
        sol.fix_free(j, input[j]);
        current = box_of(sol);
    }
}

/// How settings in the box part contacts: how many sides some setting parts (their least
/// value over the box below the input's, or zero if that is less, by more than the
/// slack), then by how much in all. Fewer sides parted is better, then less parting.
fn parting(
    sol: &Solution,
    contacts: &[ContactSide],
    (input, _, ranges): &Boxed,
    slack: f64,
) -> (usize, f64) {
    contacts
        .iter()
        .map(|side| {
            let (c, a) = in_free(&side.form, sol);
            deficit(c, &a, input, ranges, slack)
        })
        .filter(|&d| d > 0.0)
        .fold((0, 0.0), |(n, total), d| (n + 1, total + d))
}

/// How far a side (`c + a·free`) falls at its least over the box of `ranges` below
/// what it must keep: its value at `input`, or zero if that is less, less `slack`. Positive
/// when some setting parts it.
fn deficit(c: f64, a: &[f64], input: &[f64], ranges: &[Range], slack: f64) -> f64 {
    at_free(c, a, input).min(0.0) - slack - min_over_box(c, a, |i| (ranges[i].min, ranges[i].max))
}

/// How many of the input and the presets the ranges hold.
fn held((input, presets, ranges): &Boxed) -> usize {
    std::iter::once(input)
        .chain(presets)
        .filter(|v| {
            v.iter()
                .zip(ranges)
                .all(|(x, r)| r.min <= *x && *x <= r.max)
        })
        .count()
}

/// Makes the contact side most broken over the box of `ranges` (at values `input` of the
/// free variables, a side may start below zero by `slack`) a free variable, if one is
/// broken and has a free variable to replace that is not `refused` for it (pairs of side
/// and variable). Returns the pair made.
pub fn make_one_contact_variable(
    model: &Model,
    sol: &mut Solution,
    contacts: &[ContactSide],
    input: &[f64],
    ranges: &[Range],
    slack: f64,
    refused: &[(usize, usize)],
) -> Option<(usize, usize)> {
    let places = positions(model, sol);
    // (deficit, side, variable to replace, the side in the free variables)
    let mut worst: Option<(f64, usize, usize, InFree)> = None;
    for (k, side) in contacts.iter().enumerate() {
        let (c, a) = in_free(&side.form, sol);
        let live: Vec<usize> = (0..a.len())
            .filter(|&i| a[i].abs() > COEFFICIENT_ZERO)
            .collect();
        if live.len() < 2 {
            continue;
        }
        let deficit = deficit(c, &a, input, ranges, slack);
        // The variable to replace: one that only places a part, the last shown; failing
        // that, the last shown size (the family is the same either way).
        let free = |i: &&usize| sol.contact(**i).is_none() && !refused.contains(&(k, **i));
        let Some(&j) = live
            .iter()
            .rev()
            .filter(free)
            .find(|&&i| places[i])
            .or_else(|| live.iter().rev().find(free))
        else {
            continue;
        };
        if deficit > 0.0 && worst.as_ref().is_none_or(|w| deficit > w.0) {
            worst = Some((deficit, k, j, (c, a)));
        }
    }
    let (_, k, j, side_in_free) = worst?;
    let side = &contacts[k];
    let moved = moved_part(model, sol, side, j)?;
    let other = if side.parts[0] == moved {
        side.parts[1]
    } else {
        side.parts[0]
    };
    substitute(sol, &side_in_free, j);
    sol.contacts.push(ContactVariable {
        index: j,
        parts: [moved, other],
        axis: side.axis,
        form: side.form.clone(),
    });
    Some((k, j))
}

/// Rewrites every slot's expression with free variable `j` replaced by `w = c + a·u`:
/// `u_j = (w − c − Σ_{i≠j} a_i u_i) / a_j`.
pub(crate) fn substitute(sol: &mut Solution, (c, a): &(f64, Vec<f64>), j: usize) {
    let snap = |x: f64| Frac::near(x).map_or(x, |f| f.value());
    let aj = a[j];
    for e in &mut sol.exprs {
        let Some(t) = e.terms.iter().find(|&&(i, _)| i == j).map(|&(_, t)| t) else {
            continue;
        };
        let mut dense = vec![0.0; a.len()];
        for &(i, v) in &e.terms {
            if i != j {
                dense[i] = v;
            }
        }
        for (i, &ai) in a.iter().enumerate() {
            if i != j {
                dense[i] -= t * ai / aj;
            }
        }
        dense[j] = t / aj;
        e.constant -= t * c / aj;
        e.terms = dense
            .into_iter()
            .enumerate()
            .map(|(i, v)| (i, snap(v)))
            .filter(|&(_, v)| v.abs() > COEFFICIENT_ZERO)
            .collect();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::anchors::Anchors;
    use crate::analysis::ranges::ranges;
    use crate::analysis::ranges::tests::{parted_corners, sunk_top};
    use crate::analysis::reparam::solve;

    /// A variable whose range is within twice the slack is fixed at its input value and the
    /// box taken again; one wider is left a slider.
    #[test]
    fn a_variable_the_contacts_pin_is_fixed() {
        let var = |i: usize| crate::analysis::reparam::Expression {
            constant: 0.0,
            terms: vec![(i, 1.0)],
        };
        let mut sol = Solution {
            free: vec![0, 1, 2],
            exprs: vec![var(0), var(1), var(2)],
            anchors: 0,
            contacts: Vec::new(),
        };
        let slack = 0.01;
        // Variable 1 (at 3.0) may move by 0.015 in all: pinned. The others are sliders.
        let mut box_of = |sol: &Solution| {
            let input = sol.free_values(&[1.0, 3.0, 5.0]);
            let ranges = sol
                .free
                .iter()
                .map(|&f| match f {
                    1 => Range {
                        min: 2.995,
                        max: 3.01,
                        step: 0.001,
                    },
                    _ => Range {
                        min: 0.0,
                        max: 10.0,
                        step: 0.1,
                    },
                })
                .collect();
            (input, Vec::new(), ranges)
        };
        let start = box_of(&sol);
        let (input, _, ranges) = fix_pinned(&mut sol, slack, start, &mut box_of);
        assert_eq!(sol.free, vec![0, 2]);
        assert_eq!(input, vec![1.0, 5.0]);
        assert_eq!(ranges.len(), 2);
        assert_eq!(sol.slot_values(&[1.0, 5.0]), vec![1.0, 3.0, 5.0]);
    }

    /// A top sunk 1 unit into a leg, no relation kept between the leg's height and the
    /// top's place, and a variation with both 20 higher: a box holding the input and the
    /// variation has a corner where the top floats, until the overlap is a slider. Then at
    /// every corner the two touch, and the input and the variation are where they were.
    #[test]
    fn a_sunk_top_stays_on_its_leg_at_every_corner() {
        let (model, x0, x1, contacts, eps) = sunk_top();
        let mut sol = solve(&model, &Anchors::of(&model), &[]);
        let mut made = 0;
        let box_of = |sol: &Solution| {
            let input = sol.free_values(&x0);
            let v = sol.free_values(&x1);
            let r = ranges(&model, sol, &input, &[v], &contacts, eps);
            (input, r)
        };
        loop {
            let (input, r) = box_of(&sol);
            if make_one_contact_variable(&model, &mut sol, &contacts, &input, &r, eps, &[])
                .is_none()
            {
                break;
            }
            made += 1;
        }
        assert!(made >= 1, "no contact variable was made");
        let (_, r) = box_of(&sol);
        for x in [&x0, &x1] {
            let back = sol.slot_values(&sol.free_values(x));
            for (a, b) in back.iter().zip(x.iter()) {
                assert!((a - b).abs() < 1e-9, "a setting moved: {back:?} vs {x:?}");
            }
        }
        assert_eq!(parted_corners(&model, &sol, &r, (0, 1), eps), 0);
    }

    /// Refusing a side's change through one variable leaves the side to its others: the
    /// sunk top's side made through the top's place is made through the leg's height next.
    #[test]
    fn a_refused_variable_leaves_the_side_to_another() {
        let (model, x0, x1, contacts, eps) = sunk_top();
        let start = solve(&model, &Anchors::of(&model), &[]);
        let input = start.free_values(&x0);
        let r = ranges(
            &model,
            &start,
            &input,
            &[start.free_values(&x1)],
            &contacts,
            eps,
        );
        let make = |refused: &[(usize, usize)]| {
            let mut sol = start.clone();
            make_one_contact_variable(&model, &mut sol, &contacts, &input, &r, eps, refused)
        };
        let Some((side, first)) = make(&[]) else {
            panic!("no side was made a variable");
        };
        let Some((again, second)) = make(&[(side, first)]) else {
            panic!("refusing one variable refused the side");
        };
        assert_eq!(again, side);
        assert_ne!(second, first);
        assert!(
            make(&[(side, first), (side, second)]).is_none_or(|(s, _)| s != side),
            "a side was made through a refused variable"
        );
    }
}
