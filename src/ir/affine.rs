//! Exact affine forms over slots: `c + Σ aᵢ·slotᵢ`.
//!
//! Invariants: `terms` is sorted by slot id, has no duplicate ids and no zero coefficients,
//! so two forms are equal exactly when their fields are equal. Coefficients come from the
//! program's own arithmetic (±1, ½, products of constants) and are kept as `f64`; the analysis
//! rationalises them where it needs exact fractions.

use serde::Serialize;

/// Identifies a slot (a constructive parameter). During evaluation it identifies a literal;
/// the finished IR renumbers live slots densely from zero.
pub type SlotId = u32;

/// `constant + Σ coeff·slot`.
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct Affine {
    pub constant: f64,
    pub terms: Vec<(SlotId, f64)>,
}

impl Affine {
    pub fn constant(c: f64) -> Self {
        Affine {
            constant: c,
            terms: Vec::new(),
        }
    }

    /// The form `1·slot`.
    pub fn slot(id: SlotId) -> Self {
        Affine {
            constant: 0.0,
            terms: vec![(id, 1.0)],
        }
    }

    pub fn is_constant(&self) -> bool {
        self.terms.is_empty()
    }

    pub fn slots(&self) -> impl Iterator<Item = SlotId> + '_ {
        self.terms.iter().map(|&(s, _)| s)
    }

    pub fn coeff(&self, slot: SlotId) -> f64 {
        self.terms
            .binary_search_by_key(&slot, |&(s, _)| s)
            .map_or(0.0, |i| self.terms[i].1)
    }

    pub fn scale(&self, k: f64) -> Self {
        if k == 0.0 {
            return Affine::constant(0.0);
        }
        Affine {
            constant: self.constant * k,
            terms: self
                .terms
                .iter()
                .map(|&(s, a)| (s, a * k))
                .filter(|&(_, a)| a != 0.0)
                .collect(),
        }
    }

    /// `self + k·other`, merging the sorted term lists.
    pub fn add_scaled(&self, other: &Affine, k: f64) -> Self {
        Affine {
            constant: self.constant + k * other.constant,
            terms: terms_plus_scaled(&self.terms, &other.terms, k),
        }
    }

    pub fn add(&self, other: &Affine) -> Self {
        self.add_scaled(other, 1.0)
    }

    pub fn sub(&self, other: &Affine) -> Self {
        self.add_scaled(other, -1.0)
    }

    /// Value at the given slot values (indexed by slot id).
    pub fn eval(&self, values: &[f64]) -> f64 {
        self.terms
            .iter()
            .fold(self.constant, |acc, &(s, a)| acc + a * values[s as usize])
    }

    /// Renames slots through `map` (slots mapped to `None` must not occur).
    pub fn remap(&self, map: &dyn Fn(SlotId) -> Option<SlotId>) -> Self {
        let mut terms: Vec<(SlotId, f64)> = self
            .terms
            .iter()
            .filter_map(|&(s, a)| map(s).map(|t| (t, a)))
            .collect();
        terms.sort_by_key(|&(s, _)| s);
        Affine {
            constant: self.constant,
            terms,
        }
    }
}

/// `a + k·b` for two term lists sorted by slot, sorted by slot (a merge), without the terms
/// that come out exactly zero.
pub fn terms_plus_scaled(
    a_terms: &[(SlotId, f64)],
    b_terms: &[(SlotId, f64)],
    k: f64,
) -> Vec<(SlotId, f64)> {
    let mut terms = Vec::with_capacity(a_terms.len() + b_terms.len());
    let (mut i, mut j) = (0, 0);
    loop {
        let a = a_terms.get(i);
        let b = b_terms.get(j);
        let (slot, coeff) = match (a, b) {
            (Some(&(sa, ca)), Some(&(sb, cb))) if sa == sb => {
                i += 1;
                j += 1;
                (sa, ca + k * cb)
            }
            (Some(&(sa, ca)), Some(&(sb, _))) if sa < sb => {
                i += 1;
                (sa, ca)
            }
            (Some(&(sa, ca)), None) => {
                i += 1;
                (sa, ca)
            }
            (_, Some(&(sb, cb))) => {
                j += 1;
                (sb, k * cb)
            }
            (None, None) => break,
        };
        if coeff != 0.0 {
            terms.push((slot, coeff));
        }
    }
    terms
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn add_merges_and_cancels() {
        let a = Affine::slot(1)
            .add(&Affine::slot(3))
            .add(&Affine::constant(2.0));
        let b = Affine::slot(3).add(&Affine::slot(0));
        let d = a.sub(&b);
        assert_eq!(d.terms, vec![(0, -1.0), (1, 1.0)]);
        assert_eq!(d.constant, 2.0);
        assert_eq!(d.eval(&[10.0, 20.0, 0.0, 5.0]), 12.0);
    }

    #[test]
    fn scale_by_zero_is_constant_zero() {
        let a = Affine::slot(2).scale(0.0);
        assert!(a.is_constant());
        assert_eq!(a.constant, 0.0);
    }
}
