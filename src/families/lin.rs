//! Affine forms over a family's intent parameters: every number of a family's model is one.
//!
//! `Lin` is `c + Σ kᵢ·θᵢ` with sparse terms kept sorted by parameter and without zero
//! coefficients, so two forms are the same relation exactly when their terms are equal.

/// `constant + Σ coefficient · θ[parameter]`.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Lin {
    pub constant: f64,
    pub terms: Vec<(usize, f64)>,
}

impl Lin {
    pub fn zero() -> Lin {
        Lin::default()
    }

    /// The parameter `i` itself.
    pub fn param(i: usize) -> Lin {
        Lin {
            constant: 0.0,
            terms: vec![(i, 1.0)],
        }
    }

    pub fn eval(&self, theta: &[f64]) -> f64 {
        self.terms
            .iter()
            .fold(self.constant, |acc, &(i, k)| acc + k * theta[i])
    }

    pub fn add(&self, other: &Lin) -> Lin {
        let mut terms = self.terms.clone();
        for &(i, k) in &other.terms {
            match terms.iter_mut().find(|(j, _)| *j == i) {
                Some(t) => t.1 += k,
                None => terms.push((i, k)),
            }
        }
        terms.retain(|&(_, k)| k != 0.0);
        terms.sort_by_key(|&(i, _)| i);
        Lin {
            constant: self.constant + other.constant,
            terms,
        }
    }

    pub fn scale(&self, k: f64) -> Lin {
        let mut terms: Vec<(usize, f64)> = self.terms.iter().map(|&(i, c)| (i, c * k)).collect();
        terms.retain(|&(_, c)| c != 0.0);
        Lin {
            constant: self.constant * k,
            terms,
        }
    }

    pub fn sub(&self, other: &Lin) -> Lin {
        self.add(&other.scale(-1.0))
    }

    /// `self + k · other`.
    pub fn plus(&self, k: f64, other: &Lin) -> Lin {
        self.add(&other.scale(k))
    }

    /// The coefficient of parameter `i`.
    pub fn coefficient(&self, i: usize) -> f64 {
        self.terms
            .iter()
            .find(|(j, _)| *j == i)
            .map_or(0.0, |t| t.1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn forms_add_and_cancel_exactly() {
        let w = Lin::param(0);
        let t = Lin::param(1);
        let inner = w.plus(-2.0, &t);
        assert_eq!(inner.eval(&[80.0, 3.0]), 74.0);
        assert_eq!(inner.add(&t.scale(2.0)), w);
        assert_eq!(inner.coefficient(1), -2.0);
    }
}
