//! Slider ranges for the free variables.
//!
//! Start from each free variable's extremes over the input and the projected variations,
//! widen by a margin (without variations: a tenth of the model's size for a position,
//! half the value for a size), then shrink by interval arithmetic until
//! no setting in the box of ranges makes any size (an extent, a radius, a length) zero or
//! negative, or separates two parts the variations keep in contact (`contacts`): every size
//! and every contact side is
//! an affine function of the free variables, so its minimum over the box is exact
//! (`c + Σ min(a·lo, a·hi)`). Steps are about a hundredth of a range, rounded to 1, 2 or
//! 5 × 10^k, and divide the default value where they can.

use super::contacts::ContactSide;
use super::reparam::Solution;
use crate::ir::feature::world_intervals;
use crate::ir::{Affine, Model, Primitive};
use crate::tolerance::{MIN_SLIDER_STEP, RELATIVE_ROUNDOFF};
use serde::Serialize;

#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Range {
    pub min: f64,
    pub max: f64,
    pub step: f64,
}

/// Every size of the model (positive at the input) as an affine form over slots.
pub fn size_forms(model: &Model) -> Vec<Affine> {
    let values = model.slot_values();
    let mut out = Vec::new();
    for p in &model.parts {
        let mut nums: Vec<&crate::ir::Num> = match &p.primitive {
            Primitive::Cube { size, .. } => size.iter().collect(),
            Primitive::Cylinder { h, r1, r2, .. } => vec![h, r1, r2],
            Primitive::Sphere { r } => vec![r],
        };
        let extents;
        if let Some(iv) = world_intervals(p) {
            extents = iv.map(|(lo, hi)| hi.sub(&lo));
            nums.extend(extents.iter());
        }
        for n in nums {
            if let Some(a) = n.affine()
                && !a.is_constant()
                && a.eval(&values) > 0.0
            {
                out.push(a.clone());
            }
        }
    }
    out
}

/// Every size of the model less its floor ([`SIZE_FLOOR`] of its input value): the forms a
/// preset keeps `≥ 0`, as every setting of the sliders does.
pub fn size_floors(model: &Model) -> Vec<Affine> {
    let values = model.slot_values();
    size_forms(model)
        .into_iter()
        .map(|f| {
            let floor = SIZE_FLOOR * f.eval(&values);
            f.add(&Affine::constant(-floor))
        })
        .collect()
}

/// A size in terms of the free variables: `(constant, coefficient per free variable)`.
pub(crate) fn in_free(form: &Affine, sol: &Solution) -> (f64, Vec<f64>) {
    let mut c = form.constant;
    let mut coeffs = vec![0.0; sol.free.len()];
    for &(s, a) in &form.terms {
        let e = &sol.exprs[s as usize];
        c += a * e.constant;
        for &(i, b) in &e.terms {
            coeffs[i] += a * b;
        }
    }
    (c, coeffs)
}

/// A form in the free variables (from [`in_free`]) at the free variables' values `x`.
pub(crate) fn at_free(c: f64, a: &[f64], x: &[f64]) -> f64 {
    c + a.iter().zip(x).map(|(a, x)| a * x).sum::<f64>()
}

/// A step of about `span / 100` among 1, 2, 5 × 10^k that divides `value` if possible.
pub fn nice_step(span: f64, value: f64) -> f64 {
    let target = (span / 100.0).max(MIN_SLIDER_STEP);
    let mut step = 10f64.powf(target.log10().floor());
    for m in [5.0, 2.0] {
        if step * m <= target {
            step *= m;
            break;
        }
    }
    let divides = |s: f64| ((value / s) - (value / s).round()).abs() < RELATIVE_ROUNDOFF;
    let mut s = step;
    for _ in 0..12 {
        if divides(s) {
            return s;
        }
        s = if divides(s / 2.0) { s / 2.0 } else { s / 10.0 };
    }
    step
}

/// Without variations, a position slider reaches this fraction of the model's size to
/// either side of its value (a size reaches half its value).
const POSITION_RANGE: f64 = 0.1;

/// How far a slider reaches to either side of `value` without variations: a place moves
/// within the model's own scale (`size`), wherever its zero is; a size by half its value.
pub fn reach(position: bool, value: f64, size: f64) -> f64 {
    if position && size > 0.0 {
        POSITION_RANGE * size
    } else {
        0.5 * value.abs().max(1.0)
    }
}

/// Every size stays above this share of its input value at every setting of the sliders.
pub(crate) const SIZE_FLOOR: f64 = 0.02;

/// Passes over the bounds before the box is taken as settled (each pass meets every bound
/// broken at its start; later bounds can break earlier ones again only by round-off).
const MAX_SHRINK_PASSES: usize = 200;

/// A bound the sliders must keep: `c + a·free ≥ min` over the whole box of ranges.
struct Bound {
    c: f64,
    a: Vec<f64>,
    min: f64,
}

impl Bound {
    /// Whether any slider moves it (one none moves is what it is everywhere).
    fn moves(&self) -> bool {
        self.a.iter().any(|&x| x != 0.0)
    }
}

/// Ranges for the free variables given their values at the input and at each variation.
/// Every size stays above a fiftieth of its input value, and every contact side above
/// `−slack` (`contacts`; or above its input value less `slack`, where the input shows a
/// gap), at every setting in the box.
pub fn ranges(
    model: &Model,
    sol: &Solution,
    input: &[f64],
    variations: &[Vec<f64>],
    contacts: &[ContactSide],
    slack: f64,
) -> Vec<Range> {
    let n = sol.free.len();
    let mut lo: Vec<f64> = input.to_vec();
    let mut hi: Vec<f64> = input.to_vec();
    for v in variations {
        for i in 0..n {
            lo[i] = lo[i].min(v[i]);
            hi[i] = hi[i].max(v[i]);
        }
    }
    let sizes: Vec<Bound> = size_forms(model)
        .iter()
        .map(|f| {
            let (c, a) = in_free(f, sol);
            let min = SIZE_FLOOR * at_free(c, &a, input);
            Bound { c, a, min }
        })
        .filter(Bound::moves)
        .collect();
    let size = model.size();
    for i in 0..n {
        let span = hi[i] - lo[i];
        // A number that sets no size only moves things: a position.
        let position = sizes.iter().all(|b| b.a[i] == 0.0);
        let margin = if span > 0.0 {
            0.25 * span
        } else {
            reach(position, input[i], size)
        };
        lo[i] -= margin;
        hi[i] += margin;
    }
    let touching = contact_bounds(sol, input, contacts, slack);
    // Sizes stay positive everywhere, presets included (they are clamped to the ranges).
    shrink(&sizes, input, input, &mut lo, &mut hi);
    // Contacts give up the margin beyond the input and the variations, never a preset: a
    // contact two variations keep only with other settings of other sliders is the kept
    // relations' to hold, not the ranges' (shrinking into the presets' box broke the
    // presets of exact variations: the paper table's fell to IoU 0.16–0.59).
    let (hull_lo, hull_hi) = hull(input, variations, &lo, &hi);
    shrink(&touching, &hull_lo, &hull_hi, &mut lo, &mut hi);
    (0..n)
        .map(|i| {
            let step = nice_step(hi[i] - lo[i], input[i]);
            // Round inward to the step grid, never past what keeps sizes positive, but
            // keep the input and every preset inside.
            let min = (lo[i] / step).ceil() * step;
            let max = (hi[i] / step).floor() * step;
            Range {
                min: min.min(hull_lo[i]),
                max: max.max(hull_hi[i]),
                step,
            }
        })
        .collect()
}

/// Every moving contact side as a bound: never further apart than the input has them (a
/// contact seen through noise may show a small gap there), less the slack.
fn contact_bounds(
    sol: &Solution,
    input: &[f64],
    contacts: &[ContactSide],
    slack: f64,
) -> Vec<Bound> {
    contacts
        .iter()
        .map(|side| {
            let (c, a) = in_free(&side.form, sol);
            let min = at_free(c, &a, input).min(0.0) - slack;
            Bound { c, a, min }
        })
        .filter(Bound::moves)
        .collect()
}

/// Shrinks `ranges` (made by [`ranges`], which never gives up a preset for a contact)
/// towards the `input` until no setting in them parts a contact, but never by more than
/// `allowance` inside the hull of the input and the `presets` (what the variations' noise
/// explains, in the free variables' units: a preset is a noisy estimate, and moving it
/// within the noise contradicts no variation; 0 for exact variations, whose presets stay
/// where they are). Each end moved is rounded inward to its step, never past that inner
/// box. A preset outside is then clamped into the box.
pub fn close_contacts(
    sol: &Solution,
    (input, presets): (&[f64], &[Vec<f64>]),
    allowance: f64,
    contacts: &[ContactSide],
    slack: f64,
    ranges: &mut [Range],
) {
    let touching = contact_bounds(sol, input, contacts, slack);
    let mut lo: Vec<f64> = ranges.iter().map(|r| r.min).collect();
    let mut hi: Vec<f64> = ranges.iter().map(|r| r.max).collect();
    let (mut inner_lo, mut inner_hi) = hull(input, presets, &lo, &hi);
    for i in 0..input.len() {
        inner_lo[i] = (inner_lo[i] + allowance).min(input[i]);
        inner_hi[i] = (inner_hi[i] - allowance).max(input[i]);
    }
    shrink(&touching, &inner_lo, &inner_hi, &mut lo, &mut hi);
    for (i, r) in ranges.iter_mut().enumerate() {
        if lo[i] > r.min {
            r.min = ((lo[i] / r.step).ceil() * r.step).min(inner_lo[i]);
        }
        if hi[i] < r.max {
            r.max = ((hi[i] / r.step).floor() * r.step).max(inner_hi[i]);
        }
    }
}

/// The bound's smallest value over the box `[lo, hi]` (exact: it is affine).
fn box_min(b: &Bound, lo: &[f64], hi: &[f64]) -> f64 {
    min_over_box(b.c, &b.a, |i| (lo[i], hi[i]))
}

/// The smallest value of `c + a·x` over the box whose side `i` is `side(i)` = `(lo, hi)`.
pub(crate) fn min_over_box(c: f64, a: &[f64], side: impl Fn(usize) -> (f64, f64)) -> f64 {
    c + (0..a.len())
        .map(|i| {
            let (lo, hi) = side(i);
            (a[i] * lo).min(a[i] * hi)
        })
        .sum::<f64>()
}

/// The box of the input and the variations, inside the box `[lo, hi]`.
pub(crate) fn hull(
    input: &[f64],
    variations: &[Vec<f64>],
    lo: &[f64],
    hi: &[f64],
) -> (Vec<f64>, Vec<f64>) {
    let mut a = input.to_vec();
    let mut b = input.to_vec();
    for v in variations {
        for i in 0..a.len() {
            a[i] = a[i].min(v[i]).max(lo[i]);
            b[i] = b[i].max(v[i]).min(hi[i]);
        }
    }
    (a, b)
}

/// Shrinks the box `[lo, hi]` towards the box `[from_lo, from_hi]` inside it until every
/// bound holds at every setting in it, or the box is `[from_lo, from_hi]` along every side
/// that lowers a bound still broken. A bound's minimum over a box is exact
/// (`c + Σ min(a·lo, a·hi)`). A bound broken there by a deficit `d` pulls in the sides that
/// lower it, each in proportion to how far past `from` it reaches, by `d` together: no more
/// is given up than that bound needs. Passes repeat until nothing moves (sides only move
/// inwards, so this settles).
fn shrink(bounds: &[Bound], from_lo: &[f64], from_hi: &[f64], lo: &mut [f64], hi: &mut [f64]) {
    for _ in 0..MAX_SHRINK_PASSES {
        let mut moved = false;
        for b in bounds {
            let deficit = b.min - box_min(b, lo, hi);
            if deficit <= 0.0 {
                continue;
            }
            // How far each side lowers the bound past the inner box.
            let lowering: f64 = (0..lo.len())
                .map(|i| match b.a[i] {
                    a if a > 0.0 => a * (from_lo[i] - lo[i]),
                    a if a < 0.0 => a * (from_hi[i] - hi[i]),
                    _ => 0.0,
                })
                .sum();
            if lowering <= 0.0 {
                continue;
            }
            moved = true;
            let keep = (1.0 - deficit / lowering).max(0.0);
            for i in 0..lo.len() {
                if b.a[i] > 0.0 {
                    lo[i] = from_lo[i] - keep * (from_lo[i] - lo[i]);
                } else if b.a[i] < 0.0 {
                    hi[i] = from_hi[i] + keep * (hi[i] - from_hi[i]);
                }
            }
        }
        if !moved {
            return;
        }
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::analysis::anchors::Anchors;
    use crate::analysis::contacts::{Slack, common_contacts};
    use crate::analysis::reparam::solve;
    use crate::ir::feature::world_intervals;

    /// A top sunk 1 unit into a leg, no relation between them, a variation with both 20
    /// higher (the input's values, the variation's), the contacts the two share and the
    /// model's tolerance.
    pub(crate) fn sunk_top() -> (Model, Vec<f64>, Vec<f64>, Vec<ContactSide>, f64) {
        let model = crate::front::test_model(
            "cube([10, 10, 50]);\ntranslate([0, 0, 49]) cube([40, 40, 2]);\n",
        );
        let x0 = model.slot_values();
        let x1: Vec<f64> = x0
            .iter()
            .map(|&v| if v == 50.0 || v == 49.0 { v + 20.0 } else { v })
            .collect();
        let contacts = common_contacts(
            &model,
            std::slice::from_ref(&x1),
            &[vec![]],
            &mut Slack(0.0),
        );
        let eps = crate::tolerance::Tolerance::for_size(model.size()).epsilon;
        (model, x0, x1, contacts, eps)
    }

    /// How many corners of the box of `ranges` part parts `a` and `b` (their world boxes
    /// apart by more than `eps` along some axis).
    pub(crate) fn parted_corners(
        model: &Model,
        sol: &Solution,
        ranges: &[Range],
        (a, b): (usize, usize),
        eps: f64,
    ) -> usize {
        let n = ranges.len();
        (0..(1u32 << n))
            .filter(|corner| {
                let free: Vec<f64> = (0..n)
                    .map(|i| match corner >> i & 1 {
                        1 => ranges[i].max,
                        _ => ranges[i].min,
                    })
                    .collect();
                let x = sol.slot_values(&free);
                let at = |p: usize| {
                    world_intervals(&model.parts[p]).map(|iv| {
                        iv.map(|(lo, hi)| {
                            let f =
                                |n: &crate::ir::Num| n.affine().map_or(f64::NAN, |f| f.eval(&x));
                            (f(&lo), f(&hi))
                        })
                    })
                };
                let (Some(pa), Some(pb)) = (at(a), at(b)) else {
                    return true;
                };
                (0..3).any(|k| !(pa[k].1 >= pb[k].0 - eps && pb[k].1 >= pa[k].0 - eps))
            })
            .count()
    }

    /// A top sunk 1 unit into a leg, no relation between them, and a variation with both
    /// 20 higher: the box that holds the input and the variation has corners where the top
    /// floats. Closed with the variation as an exact preset, the preset stays inside; with
    /// a noisy one the noise explains 20 units of, no corner parts the two, and the input
    /// stays inside.
    #[test]
    fn closed_ranges_part_no_contact_unless_a_preset_forbids() {
        let (model, x0, x1, contacts, eps) = sunk_top();
        let sol = solve(&model, &Anchors::of(&model), &[]);
        let input = sol.free_values(&x0);
        let presets = [sol.free_values(&x1)];
        let open = ranges(&model, &sol, &input, &presets, &contacts, eps);
        assert!(
            parted_corners(&model, &sol, &open, (0, 1), eps) > 0,
            "the box held the contact already"
        );
        let inside =
            |r: &[Range], x: &[f64]| x.iter().zip(r).all(|(x, r)| r.min <= *x && *x <= r.max);
        let mut exact = open.clone();
        close_contacts(&sol, (&input, &presets), 0.0, &contacts, eps, &mut exact);
        assert!(inside(&exact, &presets[0]), "an exact preset was cut off");
        let mut noisy = open.clone();
        close_contacts(&sol, (&input, &presets), 20.0, &contacts, eps, &mut noisy);
        assert_eq!(parted_corners(&model, &sol, &noisy, (0, 1), eps), 0);
        assert!(inside(&noisy, &input));
    }

    #[test]
    fn steps_are_round_and_divide_the_value() {
        assert_eq!(nice_step(100.0, 40.0), 1.0);
        assert_eq!(nice_step(10.0, 7.5), 0.1);
        assert_eq!(nice_step(300.0, 100.0), 2.0);
        assert_eq!(nice_step(300.0, 15.0), 1.0);
    }
}
