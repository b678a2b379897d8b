//! How well the pictures determine each number: the loss's curvature at the fit's point.
//!
//! The judge's loss (area coverage, [`super::loss::residuals`]) is a sum of squared
//! residuals `e(x)`, one per pixel and channel of every view. Near the point `x*` a fit
//! returns, `e(x* + d) ≈ e(x*) + J d` (Gauss–Newton), so the loss's curvature is `JᵀJ`.
//! The noise model: every residual carries independent Gaussian noise of variance `τ²`,
//! estimated from what the fit leaves, `τ² = L(x*) / (m − p)` (`m` residuals, `p` numbers),
//! never below the quantisation of an 8-bit picture. Then the Fisher information of the
//! numbers is `F = JᵀJ / τ²` and their covariance is `F⁻¹` where `F` is regular; a
//! direction `F` does not see (a part no camera shows, two numbers of which only the sum
//! shows) is not determined at all ([`crate::variation::uncertainty`]).
//!
//! `J` is taken by central differences of the renders with exact area coverage per pixel,
//! which is continuous in the numbers, with a step of `tolerance::UNCERTAINTY_STEP` of the
//! model's size, for hard-edged pictures too (their judge compares hard edges, whose
//! derivative is zero almost everywhere; a pixel's area coverage is the point sample
//! averaged over where the edge falls inside it, so its curvature is the same information)
//! (one-sided where the other side would make a part undrawable). A column holds only the
//! pixels a number moves, so columns are kept sparse. Pixels are not independent (edges
//! are lines of pixels; the sharpening couples neighbours), so `τ` is a floor on the truth:
//! the numbers' standard deviations are relative measures first (which numbers the
//! pictures see better than others), and that is how discovery weighs them.

use super::loss::{LossSpec, Target, residuals};
use super::parametric::Parametric;
use crate::ir::Model;
use crate::render::Backend;
use crate::render::camera::Camera;
use crate::render::scene::{BOX_FILTER, NSHADE};
use crate::render::soft::prepare_view;
use crate::tolerance::{PIXEL_QUANTISATION, UNCERTAINTY_STEP};
use crate::variation::Uncertainty;
use nalgebra::DMatrix;

/// The Fisher information of the numbers the pictures can show.
#[derive(Debug, Clone, PartialEq)]
pub struct Information {
    /// The slots it is over (every slot that reaches some part's geometry), ascending.
    pub slots: Vec<usize>,
    /// `JᵀJ / τ²` over `slots`, in their order.
    pub matrix: DMatrix<f64>,
    /// The residuals' standard deviation `τ` it was scaled by.
    pub tau: f64,
}

impl Information {
    /// The uncertainty of `model`'s numbers at the fitted values `x`, as a variation
    /// carries it.
    pub fn uncertainty(&self, model: &Model, x: &[f64]) -> Uncertainty {
        let listed: Vec<(usize, String, f64)> = self
            .slots
            .iter()
            .map(|&s| (s, model.slots[s].name.clone(), x[s]))
            .collect();
        Uncertainty::new(model.slots.len(), &listed, self.matrix.clone())
    }
}

/// What the residuals are measured against at the fit's point: the problem (its rings
/// fixed for these cameras), the views and their targets, and the look the fit ended with.
pub struct AtPoint<'a> {
    pub problem: &'a Parametric,
    pub cameras: &'a [Camera],
    pub targets: &'a [Target],
    pub shades: &'a [[f64; NSHADE]],
    pub albedo: &'a [f64],
    pub spec: &'a LossSpec,
}

impl AtPoint<'_> {
    /// Every view's residuals at `x`, one after the other.
    fn residuals(&self, backend: &mut dyn Backend, x: &[f64]) -> Vec<f32> {
        let scene = self.problem.scene(x).with_albedo(self.albedo);
        let n = self
            .cameras
            .len()
            .min(self.targets.len())
            .min(self.shades.len());
        let views: Vec<_> = self.cameras[..n]
            .iter()
            .map(|c| prepare_view(&scene, c, Some(BOX_FILTER)))
            .collect();
        backend
            .soft(&scene, &views, Some(BOX_FILTER), &self.shades[..n])
            .iter()
            .zip(self.targets)
            .flat_map(|(soft, t)| residuals(soft, t, self.spec))
            .collect()
    }

    /// The floor on `τ²`: quantisation noise in the units of the residuals (a pixel's
    /// difference over the root of its view's pixel count), the views' mean.
    fn tau_floor(&self) -> f64 {
        let k = self.targets.len().max(1) as f64;
        let inv_n: f64 = self
            .targets
            .iter()
            .map(|t| 1.0 / ((t.width * t.height) as f64 * t.picture_share()).max(1.0))
            .sum();
        PIXEL_QUANTISATION * PIXEL_QUANTISATION * inv_n / k
    }
}

/// The information at `x`; `valid` says whether a point keeps every part drawable.
pub fn information(
    at: &AtPoint<'_>,
    backend: &mut dyn Backend,
    x: &[f64],
    valid: &dyn Fn(&[f64]) -> bool,
) -> Information {
    let slots: Vec<usize> = at
        .problem
        .live_slots()
        .iter()
        .enumerate()
        .filter_map(|(s, live)| live.then_some(s))
        .collect();
    let e0 = at.residuals(backend, x);
    let h = UNCERTAINTY_STEP * at.problem.scale;
    let columns: Vec<Vec<(u32, f32)>> = slots
        .iter()
        .map(|&s| column(at, backend, x, s, h, &e0, valid))
        .collect();
    let p = slots.len();
    let m = e0.len();
    let rss: f64 = e0.iter().map(|&v| (v as f64) * (v as f64)).sum();
    let tau2 = (rss / (m.saturating_sub(p).max(1)) as f64).max(at.tau_floor());
    let matrix = DMatrix::from_fn(p, p, |i, j| sparse_dot(&columns[i], &columns[j]) / tau2);
    Information {
        slots,
        matrix,
        tau: tau2.sqrt(),
    }
}

/// `∂e/∂x[s]` by differences (central where both sides are drawable), its nonzero entries.
fn column(
    at: &AtPoint<'_>,
    backend: &mut dyn Backend,
    x: &[f64],
    s: usize,
    h: f64,
    e0: &[f32],
    valid: &dyn Fn(&[f64]) -> bool,
) -> Vec<(u32, f32)> {
    let moved = |d: f64| {
        let mut y = x.to_vec();
        y[s] += d;
        y
    };
    let (up, down) = (moved(h), moved(-h));
    let (a, b, span) = match (valid(&up), valid(&down)) {
        (true, true) => (
            at.residuals(backend, &up),
            at.residuals(backend, &down),
            2.0 * h,
        ),
        (true, false) => (at.residuals(backend, &up), e0.to_vec(), h),
        (false, true) => (e0.to_vec(), at.residuals(backend, &down), h),
        (false, false) => return Vec::new(),
    };
    a.iter()
        .zip(&b)
        .enumerate()
        .filter(|(_, (p, q))| p != q)
        .map(|(k, (p, q))| (k as u32, ((*p as f64 - *q as f64) / span) as f32))
        .collect()
}

/// The dot product of two sparse columns (entries in ascending index order).
fn sparse_dot(a: &[(u32, f32)], b: &[(u32, f32)]) -> f64 {
    let (mut i, mut j, mut sum) = (0, 0, 0.0f64);
    while i < a.len() && j < b.len() {
        match a[i].0.cmp(&b[j].0) {
            std::cmp::Ordering::Less => i += 1,
            std::cmp::Ordering::Greater => j += 1,
            std::cmp::Ordering::Equal => {
                sum += a[i].1 as f64 * b[j].1 as f64;
                i += 1;
                j += 1;
            }
        }
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::sparse_dot;

    #[test]
    fn sparse_columns_multiply_where_both_have_entries() {
        let a = [(1, 2.0), (4, 1.0), (9, 3.0)];
        let b = [(0, 5.0), (4, 2.0), (9, -1.0), (11, 7.0)];
        assert_eq!(sparse_dot(&a, &b), 2.0 - 3.0);
        assert_eq!(sparse_dot(&a, &[]), 0.0);
    }
}
