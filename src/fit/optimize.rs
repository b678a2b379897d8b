//! Optimisers and the space they move in.
//!
//! The variables are `y`, with slots `x = x_base + D·B·y`: `D` scales each slot's step (the
//! model's size for every slot, as the paper's unit-sized models have it, or each slot's own
//! magnitude so a 2 mm board and a 150 mm height move alike in relative terms); in slot
//! space `B` is the identity, in a constraint subspace an orthonormal basis of `D⁻¹·N` for
//! `N` (d × d′) a basis of the constraints' null space, and `x_base` a point that satisfies
//! them.

use crate::tolerance::{FIT_DIVISOR_FLOOR, FIT_RANK_RELATIVE};
use nalgebra::{DMatrix, DVector};

/// Which update rule.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Optimizer {
    /// Gradient descent, with optional heavy-ball momentum (0 is the paper's plain SGD).
    Sgd { momentum: f64 },
    Adam {
        beta1: f64,
        beta2: f64,
        eps: f64,
        /// `eps` relative to the largest coordinate's gradient scale: a coordinate whose
        /// gradient is this much smaller than the largest steps in proportion instead of
        /// at the full rate (0: plain Adam).
        floor: f64,
    },
}

impl Optimizer {
    pub fn sgd() -> Self {
        Optimizer::Sgd { momentum: 0.0 }
    }

    pub fn adam() -> Self {
        Optimizer::Adam {
            beta1: 0.9,
            beta2: 0.999,
            eps: crate::tolerance::ADAM_EPSILON,
            floor: 0.0,
        }
    }

    /// This Adam with its `floor` at `floor`, if that changes it (`None` for SGD, whose
    /// steps are already in proportion to the gradient).
    pub fn damped(self, floor: f64) -> Option<Optimizer> {
        match self {
            Optimizer::Adam {
                beta1,
                beta2,
                eps,
                floor: f,
            } if f != floor => Some(Optimizer::Adam {
                beta1,
                beta2,
                eps,
                floor,
            }),
            _ => None,
        }
    }
}

/// State carried between steps.
#[derive(Debug, Clone, PartialEq)]
pub struct OptState {
    pub optimizer: Optimizer,
    m: Vec<f64>,
    v: Vec<f64>,
    t: u32,
}

impl OptState {
    pub fn new(optimizer: Optimizer, n: usize) -> Self {
        OptState {
            optimizer,
            m: vec![0.0; n],
            v: vec![0.0; n],
            t: 0,
        }
    }

    /// The step to subtract from the variables for gradient `g` and learning rate `lr`.
    pub fn step(&mut self, g: &[f64], lr: f64) -> Vec<f64> {
        self.t += 1;
        match self.optimizer {
            Optimizer::Sgd { momentum } => {
                for (m, &gi) in self.m.iter_mut().zip(g) {
                    *m = momentum * *m + gi;
                }
                self.m.iter().map(|m| lr * m).collect()
            }
            Optimizer::Adam {
                beta1,
                beta2,
                eps,
                floor,
            } => {
                let t = self.t as i32;
                let c1 = 1.0 - beta1.powi(t);
                let c2 = 1.0 - beta2.powi(t);
                for ((m, v), &gi) in self.m.iter_mut().zip(self.v.iter_mut()).zip(g) {
                    *m = beta1 * *m + (1.0 - beta1) * gi;
                    *v = beta2 * *v + (1.0 - beta2) * gi * gi;
                }
                let top = self.v.iter().fold(0.0f64, |a, &v| a.max(v)) / c2;
                let eps = eps.max(floor * top.sqrt());
                self.m
                    .iter()
                    .zip(&self.v)
                    .map(|(m, v)| lr * (m / c1) / ((v / c2).sqrt() + eps))
                    .collect()
            }
        }
    }
}

/// Where the optimiser moves: `x = x_base + D·B·y`, with `D` a diagonal of per-slot step
/// scales.
#[derive(Debug, Clone, PartialEq)]
pub struct Space {
    pub x_base: DVector<f64>,
    /// `None`: the identity (slot space); otherwise orthonormal columns.
    pub basis: Option<DMatrix<f64>>,
    /// `D`: how far one unit of `y` moves each slot.
    pub scales: DVector<f64>,
}

impl Space {
    /// Every slot free, each moving `scales[i]` per unit of its variable.
    pub fn slots(x0: &[f64], scales: &[f64]) -> Space {
        Space {
            x_base: DVector::from_column_slice(x0),
            basis: None,
            scales: DVector::from_column_slice(scales),
        }
    }

    /// Every slot free, all moving `scale` per unit.
    pub fn uniform(x0: &[f64], scale: f64) -> Space {
        Space::slots(x0, &vec![scale; x0.len()])
    }

    /// Inside `x = particular + N·z`: `basis` is `N` (d × d′) in slot units; the variables
    /// are coordinates of an orthonormal basis of `D⁻¹·N`, so steps are even in scaled units.
    pub fn subspace(particular: &[f64], basis: DMatrix<f64>, scales: &[f64]) -> Space {
        let d = DVector::from_column_slice(scales);
        let mut m = basis;
        for (i, mut row) in m.row_iter_mut().enumerate() {
            row /= d[i];
        }
        let q = if m.ncols() == 0 {
            m
        } else {
            orthonormal_columns(&m)
        };
        Space {
            x_base: DVector::from_column_slice(particular),
            basis: Some(q),
            scales: d,
        }
    }

    /// Number of variables.
    pub fn dim(&self) -> usize {
        self.basis.as_ref().map_or(self.x_base.len(), |b| b.ncols())
    }

    pub fn x(&self, y: &[f64]) -> Vec<f64> {
        let y = DVector::from_column_slice(y);
        let step = match &self.basis {
            None => y,
            Some(b) => b * y,
        };
        (&self.x_base + step.component_mul(&self.scales))
            .iter()
            .copied()
            .collect()
    }

    /// `∂/∂y` from `∂/∂x`.
    pub fn grad_y(&self, gx: &[f64]) -> Vec<f64> {
        let g = DVector::from_column_slice(gx).component_mul(&self.scales);
        match &self.basis {
            None => g.iter().copied().collect(),
            Some(b) => (b.transpose() * g).iter().copied().collect(),
        }
    }
}

/// The learning rate of step `it` (from 0) of the `iterations` in a round: `lr`, except in
/// a stage's last round, where it falls linearly, `lr·(1 − settle·it/iterations)`, so the
/// stage ends almost at rest.
pub fn round_rate(lr: f64, settle: f64, last_round: bool, it: usize, iterations: usize) -> f64 {
    if last_round {
        lr * (1.0 - settle * it as f64 / iterations.max(1) as f64)
    } else {
        lr
    }
}

/// An orthonormal basis of the column space of `m` (Gram–Schmidt via SVD's left vectors).
fn orthonormal_columns(m: &DMatrix<f64>) -> DMatrix<f64> {
    let svd = m.clone().svd(true, false);
    let Some(u) = svd.u else {
        return m.clone();
    };
    let smax = svd.singular_values.iter().fold(0.0f64, |a, &v| a.max(v));
    let keep: Vec<usize> = (0..svd.singular_values.len())
        .filter(|&i| svd.singular_values[i] > FIT_RANK_RELATIVE * smax.max(FIT_DIVISOR_FLOOR))
        .collect();
    let cols: Vec<DVector<f64>> = keep.iter().map(|&i| u.column(i).into_owned()).collect();
    if cols.is_empty() {
        return DMatrix::zeros(m.nrows(), 0);
    }
    DMatrix::from_columns(&cols)
}

/// An orthonormal basis of the null space of `c` (m × d): d × (d − rank).
///
/// The basis depends only on the null space itself and the slots' order, never on how the
/// rows that cut it out were written: relations that add nothing (a redundant row) or the
/// same relations in another order give the same basis, so they cannot change a fit's
/// path. It is Gram–Schmidt over the projections of the slots' unit vectors onto the null
/// space, in slot order: the first vector is as close to slot 0 as the space allows.
pub fn null_space(c: &DMatrix<f64>) -> DMatrix<f64> {
    let d = c.ncols();
    if c.nrows() == 0 {
        return DMatrix::identity(d, d);
    }
    // Eigenvectors of CᵀC with (near) zero eigenvalues: some basis of the null space.
    let ctc = c.transpose() * c;
    let eig = ctc.symmetric_eigen();
    let max = eig.eigenvalues.iter().fold(0.0f64, |a, &v| a.max(v.abs()));
    let tol = FIT_RANK_RELATIVE * max.max(FIT_DIVISOR_FLOOR) * d as f64;
    let cols: Vec<DVector<f64>> = (0..d)
        .filter(|&i| eig.eigenvalues[i].abs() <= tol)
        .map(|i| eig.eigenvectors.column(i).into_owned())
        .collect();
    if cols.is_empty() {
        return DMatrix::zeros(d, 0);
    }
    canonical_basis(&DMatrix::from_columns(&cols))
}

/// The canonical orthonormal basis of the span of `n`'s orthonormal columns (see
/// [`null_space`]): the projector `N Nᵀ` is the same for every basis of the span, and its
/// columns taken in order and orthonormalised give the same vectors.
fn canonical_basis(n: &DMatrix<f64>) -> DMatrix<f64> {
    let k = n.ncols();
    let projector = n * n.transpose();
    let mut out: Vec<DVector<f64>> = Vec::with_capacity(k);
    // A slot whose unit vector is (nearly) orthogonal to the span, or to what is already
    // taken, adds no direction: well above round-off, well below a unit column's share.
    let cut = FIT_RANK_RELATIVE.sqrt();
    for j in 0..projector.ncols() {
        if out.len() == k {
            break;
        }
        let mut v = projector.column(j).into_owned();
        for u in &out {
            v -= u * u.dot(&v);
        }
        let norm = v.norm();
        if norm > cut {
            out.push(v / norm);
        }
    }
    if out.len() < k {
        return n.clone();
    }
    DMatrix::from_columns(&out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn adam_first_step_is_lr() {
        let mut s = OptState::new(Optimizer::adam(), 2);
        let d = s.step(&[3.0, -0.5], 0.1);
        assert!((d[0] - 0.1).abs() < 1e-6 && (d[1] + 0.1).abs() < 1e-6);
    }

    #[test]
    fn damped_adam_steps_a_faint_gradient_in_proportion() {
        // Plain Adam moves a coordinate whose gradient is 10⁻⁴ of the largest as far as the
        // largest; with a floor of 0.05 it moves about 10⁻⁴ / 0.05 as far.
        let g = [1.0, 1e-4];
        let mut plain = OptState::new(Optimizer::adam(), 2);
        let mut damped = OptState::new(Optimizer::adam().damped(0.05).unwrap(), 2);
        let (mut p, mut d) = (vec![0.0; 2], vec![0.0; 2]);
        for _ in 0..10 {
            for (a, s) in p.iter_mut().zip(plain.step(&g, 0.1)) {
                *a += s;
            }
            for (a, s) in d.iter_mut().zip(damped.step(&g, 0.1)) {
                *a += s;
            }
        }
        assert!((p[1] / p[0] - 1.0).abs() < 1e-3, "{p:?}");
        assert!((d[0] / p[0] - 1.0).abs() < 0.06, "{d:?} vs {p:?}");
        let ratio = d[1] / d[0];
        assert!(ratio > 1e-3 && ratio < 3e-3, "{ratio}");
        assert_eq!(Optimizer::sgd().damped(0.05), None);
        assert_eq!(Optimizer::adam().damped(0.0), None);
    }

    #[test]
    fn a_settling_round_ends_at_the_settled_rate() {
        let rates: Vec<f64> = (0..30)
            .map(|it| round_rate(0.01, 0.9, true, it, 30))
            .collect();
        assert_eq!(rates[0], 0.01);
        assert!((rates[29] - 0.01 * (1.0 - 0.9 * 29.0 / 30.0)).abs() < 1e-12);
        assert!(rates.windows(2).all(|w| w[1] < w[0]));
        // Other rounds, and no settling, keep the rate.
        assert!((0..30).all(|it| round_rate(0.01, 0.9, false, it, 30) == 0.01));
        assert!((0..30).all(|it| round_rate(0.01, 0.0, true, it, 30) == 0.01));
    }

    #[test]
    fn null_space_of_equal_slots() {
        // x0 − x1 = 0 in three slots: a 2-dimensional null space orthogonal to (1, −1, 0).
        let c = DMatrix::from_row_slice(1, 3, &[1.0, -1.0, 0.0]);
        let n = null_space(&c);
        assert_eq!(n.ncols(), 2);
        assert!((&c * &n).norm() < 1e-12);
        assert!((n.transpose() * &n - DMatrix::identity(2, 2)).norm() < 1e-12);
    }

    #[test]
    fn null_space_basis_ignores_redundant_rows() {
        // The same space cut out by one row, or by it and a redundant multiple of it
        // beside another: the same basis, vector for vector.
        let one = DMatrix::from_row_slice(2, 4, &[1.0, -1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0]);
        let more = DMatrix::from_row_slice(
            3,
            4,
            &[0.0, 0.0, 2.0, 2.0, 1.0, -1.0, 0.0, 0.0, 3.0, -3.0, 1.0, 1.0],
        );
        let (a, b) = (null_space(&one), null_space(&more));
        assert_eq!(a.ncols(), 2);
        assert!((a - b).norm() < 1e-9);
    }
}
