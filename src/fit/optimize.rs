//! Optimisers and the space they move in.
//!
//! The variables are `y`, with slots `x = x_base + scale·B·y`: in slot space `B` is the
//! identity (so `y` is each slot's offset in units of the model's size, as the paper's
//! unit-sized models have it); in a constraint subspace `B` is a basis `N` (d × d′) of the
//! constraints' null space and `x_base` a particular point that satisfies them.

use nalgebra::{DMatrix, DVector};

/// Which update rule.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Optimizer {
    /// Gradient descent, with optional heavy-ball momentum (0 is the paper's plain SGD).
    Sgd {
        momentum: f64,
    },
    Adam {
        beta1: f64,
        beta2: f64,
        eps: f64,
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
            eps: 1e-8,
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
            Optimizer::Adam { beta1, beta2, eps } => {
                let t = self.t as i32;
                let c1 = 1.0 - beta1.powi(t);
                let c2 = 1.0 - beta2.powi(t);
                self.m
                    .iter_mut()
                    .zip(self.v.iter_mut())
                    .zip(g)
                    .map(|((m, v), &gi)| {
                        *m = beta1 * *m + (1.0 - beta1) * gi;
                        *v = beta2 * *v + (1.0 - beta2) * gi * gi;
                        lr * (*m / c1) / ((*v / c2).sqrt() + eps)
                    })
                    .collect()
            }
        }
    }
}

/// Where the optimiser moves: `x = x_base + scale·B·y`.
#[derive(Debug, Clone, PartialEq)]
pub struct Space {
    pub x_base: DVector<f64>,
    /// `None`: the identity (slot space).
    pub basis: Option<DMatrix<f64>>,
    pub scale: f64,
}

impl Space {
    /// Every slot free.
    pub fn slots(x0: &[f64], scale: f64) -> Space {
        Space {
            x_base: DVector::from_column_slice(x0),
            basis: None,
            scale,
        }
    }

    /// Inside `x = particular + N·y'`: `basis` is `N` (d × d′), `particular` a point.
    pub fn subspace(particular: &[f64], basis: DMatrix<f64>, scale: f64) -> Space {
        Space {
            x_base: DVector::from_column_slice(particular),
            basis: Some(basis),
            scale,
        }
    }

    /// Number of variables.
    pub fn dim(&self) -> usize {
        self.basis.as_ref().map_or(self.x_base.len(), |b| b.ncols())
    }

    pub fn x(&self, y: &[f64]) -> Vec<f64> {
        let y = DVector::from_column_slice(y) * self.scale;
        let x = match &self.basis {
            None => &self.x_base + y,
            Some(b) => &self.x_base + b * y,
        };
        x.iter().copied().collect()
    }

    /// `∂/∂y` from `∂/∂x`.
    pub fn grad_y(&self, gx: &[f64]) -> Vec<f64> {
        let g = DVector::from_column_slice(gx) * self.scale;
        match &self.basis {
            None => g.iter().copied().collect(),
            Some(b) => (b.transpose() * g).iter().copied().collect(),
        }
    }
}

/// An orthonormal basis of the null space of `c` (m × d): d × (d − rank).
pub fn null_space(c: &DMatrix<f64>) -> DMatrix<f64> {
    let d = c.ncols();
    if c.nrows() == 0 {
        return DMatrix::identity(d, d);
    }
    // Eigenvectors of CᵀC with (near) zero eigenvalues.
    let ctc = c.transpose() * c;
    let eig = ctc.symmetric_eigen();
    let max = eig.eigenvalues.iter().fold(0.0f64, |a, &v| a.max(v.abs()));
    let tol = 1e-10 * max.max(1e-300) * d as f64;
    let cols: Vec<DVector<f64>> = (0..d)
        .filter(|&i| eig.eigenvalues[i].abs() <= tol)
        .map(|i| eig.eigenvectors.column(i).into_owned())
        .collect();
    if cols.is_empty() {
        return DMatrix::zeros(d, 0);
    }
    DMatrix::from_columns(&cols)
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
    fn null_space_of_equal_slots() {
        // x0 − x1 = 0 in three slots: a 2-dimensional null space orthogonal to (1, −1, 0).
        let c = DMatrix::from_row_slice(1, 3, &[1.0, -1.0, 0.0]);
        let n = null_space(&c);
        assert_eq!(n.ncols(), 2);
        assert!((&c * &n).norm() < 1e-12);
        assert!((n.transpose() * &n - DMatrix::identity(2, 2)).norm() < 1e-12);
    }
}
