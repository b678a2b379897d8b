//! Slider ranges for the free variables.
//!
//! Start from each free variable's extremes over the input and the projected variations,
//! widen by a margin, then shrink by interval arithmetic until no setting in the box of
//! ranges makes any size (an extent, a radius, a length) zero or negative: every size is an
//! affine function of the free variables, so its minimum over the box is exact
//! (`c + Σ min(a·lo, a·hi)`). Steps are about a hundredth of a range, rounded to 1, 2 or
//! 5 × 10^k, and divide the default value where they can.

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

/// A size in terms of the free variables: `(constant, coefficient per free variable)`.
fn in_free(form: &Affine, sol: &Solution) -> (f64, Vec<f64>) {
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

/// Ranges for the free variables given their values at the input and at each variation.
pub fn ranges(model: &Model, sol: &Solution, input: &[f64], variations: &[Vec<f64>]) -> Vec<Range> {
    let n = sol.free.len();
    let mut lo: Vec<f64> = input.to_vec();
    let mut hi: Vec<f64> = input.to_vec();
    for v in variations {
        for i in 0..n {
            lo[i] = lo[i].min(v[i]);
            hi[i] = hi[i].max(v[i]);
        }
    }
    for i in 0..n {
        let span = hi[i] - lo[i];
        let margin = if span > 0.0 {
            0.25 * span
        } else {
            0.5 * input[i].abs().max(1.0)
        };
        lo[i] -= margin;
        hi[i] += margin;
    }
    let sizes: Vec<(f64, Vec<f64>, f64)> = size_forms(model)
        .iter()
        .map(|f| {
            let (c, a) = in_free(f, sol);
            let at_input = c + a.iter().zip(input).map(|(x, y)| x * y).sum::<f64>();
            (c, a, at_input)
        })
        .collect();
    for _ in 0..200 {
        let mut ok = true;
        for (c, a, at_input) in &sizes {
            let min = c
                + (0..n)
                    .map(|i| (a[i] * lo[i]).min(a[i] * hi[i]))
                    .sum::<f64>();
            if min > 0.02 * at_input {
                continue;
            }
            ok = false;
            for i in 0..n {
                if a[i] > 0.0 {
                    lo[i] = input[i] - 0.8 * (input[i] - lo[i]);
                } else if a[i] < 0.0 {
                    hi[i] = input[i] + 0.8 * (hi[i] - input[i]);
                }
            }
        }
        if ok {
            break;
        }
    }
    (0..n)
        .map(|i| {
            let step = nice_step(hi[i] - lo[i], input[i]);
            // Round outward to the step grid, but never past what keeps sizes positive.
            let min = (lo[i] / step).ceil() * step;
            let max = (hi[i] / step).floor() * step;
            Range {
                min: min.min(input[i]),
                max: max.max(input[i]),
                step,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::nice_step;

    #[test]
    fn steps_are_round_and_divide_the_value() {
        assert_eq!(nice_step(100.0, 40.0), 1.0);
        assert_eq!(nice_step(10.0, 7.5), 0.1);
        assert_eq!(nice_step(300.0, 100.0), 2.0);
        assert_eq!(nice_step(300.0, 15.0), 1.0);
    }
}
