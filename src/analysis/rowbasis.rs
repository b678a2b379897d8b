//! A basis of the span of chosen constraint rows, kept sparse in reduced row-echelon form.
//!
//! Invariants: each stored row has a pivot slot where its coefficient is exactly 1, and every
//! other stored row is 0 there, so a stored row's other slots are all free (non-pivot).
//! Reducing a row is one pass over its pivot entries: the rank test costs the rows' fill, not
//! the number of slots times the number of rows. Rows carry their constants, so the basis
//! also says where a point satisfying them has its pivot slots ([`RowBasis::pivot_value`]).

use crate::ir::affine::terms_plus_scaled;
use crate::ir::{Affine, SlotId};
use crate::tolerance::{BASIS_UPDATE_ZERO, RELATIVE_ROUNDOFF};
use std::collections::HashMap;

/// One stored row: `Σ terms + constant = 0`, with coefficient 1 at its pivot.
#[derive(Debug, Clone)]
pub struct BasisRow {
    pub pivot: SlotId,
    pub terms: Vec<(SlotId, f64)>,
    pub constant: f64,
}

#[derive(Debug, Clone, Default)]
pub struct RowBasis {
    rows: Vec<BasisRow>,
    pivot_of: HashMap<SlotId, usize>,
    /// Pivots of the rows added or changed since [`RowBasis::take_touched`]: a row's
    /// reduction can only have changed if it holds one of them.
    touched: Vec<SlotId>,
}

impl RowBasis {
    pub fn len(&self) -> usize {
        self.rows.len()
    }

    pub fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }

    pub fn rows(&self) -> &[BasisRow] {
        &self.rows
    }

    /// The stored row whose pivot is `slot`, if `slot` is a pivot.
    pub fn row_with_pivot(&self, slot: SlotId) -> Option<&BasisRow> {
        self.pivot_of.get(&slot).map(|&k| &self.rows[k])
    }

    /// `row` minus its components along the stored rows (round-off dropped), with the
    /// constant reduced alike.
    fn reduce(&self, row: &[(SlotId, f64)], constant: f64) -> (Terms, f64) {
        let scale = row.iter().fold(0.0f64, |m, &(_, a)| m.max(a.abs()));
        let mut v = Terms::default();
        for &(s, a) in row.iter().filter(|&&(_, a)| a != 0.0) {
            *v.entry(s) = a;
        }
        let mut c = constant;
        for &(s, a) in row {
            if a == 0.0 {
                continue;
            }
            if let Some(&k) = self.pivot_of.get(&s) {
                let stored = &self.rows[k];
                for &(t, b) in &stored.terms {
                    *v.entry(t) -= a * b;
                }
                c -= a * stored.constant;
            }
        }
        v.retain(|a| a.abs() > RELATIVE_ROUNDOFF * scale);
        (v, c)
    }

    /// The representative of `row` modulo the span: zero at every pivot (so two rows that
    /// differ by a combination of stored rows reduce to the same terms), sorted by slot.
    pub fn reduced(&self, row: &[(SlotId, f64)]) -> Vec<(SlotId, f64)> {
        let mut v = self.reduce(row, 0.0).0.terms;
        v.sort_by_key(|&(s, _)| s);
        v
    }

    /// Whether the sparse `row` lies in the span (relative tolerance).
    pub fn contains_terms(&self, row: &[(SlotId, f64)]) -> bool {
        self.reduce(row, 0.0).0.is_empty()
    }

    /// Adds the linear `row` (constant 0) if it is independent; returns whether it was.
    pub fn add_terms(&mut self, row: &[(SlotId, f64)]) -> bool {
        self.add_row(row, 0.0)
    }

    /// Adds the affine row `form = 0` if its linear part is independent.
    pub fn add(&mut self, form: &Affine) -> bool {
        self.add_row(&form.terms, form.constant)
    }

    fn add_row(&mut self, row: &[(SlotId, f64)], constant: f64) -> bool {
        let (v, c) = self.reduce(row, constant);
        let Some(&(pivot, p)) = v
            .terms
            .iter()
            .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()).then(b.0.cmp(&a.0)))
        else {
            return false;
        };
        let mut terms: Vec<(SlotId, f64)> = v.terms.iter().map(|&(s, a)| (s, a / p)).collect();
        terms.sort_by_key(|&(s, _)| s);
        let new = BasisRow {
            pivot,
            terms,
            constant: c / p,
        };
        for stored in &mut self.rows {
            let Some(at) = stored.terms.iter().position(|&(s, _)| s == pivot) else {
                continue;
            };
            let f = stored.terms[at].1;
            let scale = stored
                .terms
                .iter()
                .fold(0.0f64, |m, &(_, a)| m.max(a.abs()));
            let zero = RELATIVE_ROUNDOFF * scale * BASIS_UPDATE_ZERO;
            // `x + (−f) y` is `x − f y` to the bit.
            stored.terms = terms_plus_scaled(&stored.terms, &new.terms, -f)
                .into_iter()
                .filter(|&(s, a)| s != pivot && a.abs() > zero)
                .collect();
            stored.constant -= f * new.constant;
            self.touched.push(stored.pivot);
        }
        self.touched.push(pivot);
        self.pivot_of.insert(pivot, self.rows.len());
        self.rows.push(new);
        true
    }

    /// The pivots of rows added or changed since the last call (see the field).
    pub fn take_touched(&mut self) -> Vec<SlotId> {
        std::mem::take(&mut self.touched)
    }

    /// The value the pivot row of `pivot` gives its pivot slot when the free slots are as in
    /// `x`: the point nearest `x` along pivot slots that satisfies every stored row.
    pub fn pivot_value(&self, row: &BasisRow, x: &[f64]) -> f64 {
        -(row.constant
            + row
                .terms
                .iter()
                .filter(|&&(s, _)| s != row.pivot)
                .map(|&(s, a)| a * x[s as usize])
                .sum::<f64>())
    }
}

/// A sparse row being reduced: its terms in the order their slots first came, looked up
/// by a scan while they are few (a reduced row has a handful; a hash costs more) and through
/// an index once they are many. Each slot's value is summed in the order its updates come,
/// whatever the lookup, so the result does not depend on it.
#[derive(Default)]
struct Terms {
    terms: Vec<(SlotId, f64)>,
    index: HashMap<SlotId, usize>,
}

/// Terms a row may have before [`Terms`] looks them up through an index.
const SCANNED_TERMS: usize = 24;

impl Terms {
    /// The value at `slot`, made 0 if there was none.
    fn entry(&mut self, slot: SlotId) -> &mut f64 {
        let at = if self.terms.len() <= SCANNED_TERMS {
            self.terms.iter().position(|&(s, _)| s == slot)
        } else {
            if self.index.is_empty() {
                self.index = (self.terms.iter().enumerate())
                    .map(|(i, &(s, _))| (s, i))
                    .collect();
            }
            self.index.get(&slot).copied()
        };
        let at = at.unwrap_or_else(|| {
            self.terms.push((slot, 0.0));
            if !self.index.is_empty() {
                self.index.insert(slot, self.terms.len() - 1);
            }
            self.terms.len() - 1
        });
        &mut self.terms[at].1
    }

    /// Keeps the terms whose value passes `keep`.
    fn retain(&mut self, keep: impl Fn(f64) -> bool) {
        self.terms.retain(|&(_, a)| keep(a));
        self.index.clear();
    }

    fn is_empty(&self) -> bool {
        self.terms.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn row_basis_answers_span_questions_exactly() {
        let mut b = RowBasis::default();
        assert!(b.add_terms(&[(0, 1.0), (1, -1.0)]));
        assert!(b.add_terms(&[(1, 1.0), (2, -1.0)]));
        // x0 − x2 = (x0 − x1) + (x1 − x2): implied, so not added.
        assert!(b.contains_terms(&[(0, 2.0), (2, -2.0)]));
        assert!(!b.add_terms(&[(0, 0.5), (2, -0.5)]));
        assert!(!b.contains_terms(&[(0, 1.0), (2, 1.0)]));
        assert!(!b.contains_terms(&[(3, 1.0)]));
        assert_eq!(b.len(), 2);
        // A half-coefficient row (a centre) mixed with the others.
        assert!(b.add_terms(&[(0, 1.0), (3, -0.5), (4, -0.5)]));
        assert!(b.contains_terms(&[(2, 2.0), (3, -1.0), (4, -1.0)]));
        assert_eq!(b.len(), 3);
        // Reduced echelon form: no stored row mentions another row's pivot.
        for r in b.rows() {
            for other in b.rows().iter().filter(|o| o.pivot != r.pivot) {
                assert!(other.terms.iter().all(|&(s, _)| s != r.pivot));
            }
        }
    }

    #[test]
    fn pivot_values_satisfy_every_row() {
        let rows = [
            Affine {
                constant: -3.0,
                terms: vec![(0, 1.0), (1, -1.0)],
            },
            Affine {
                constant: 1.0,
                terms: vec![(1, 2.0), (2, -1.0), (3, 1.0)],
            },
        ];
        let mut b = RowBasis::default();
        for r in &rows {
            assert!(b.add(r));
        }
        let mut x = vec![0.7, -2.0, 5.0, 1.25];
        for r in b.rows().to_vec() {
            x[r.pivot as usize] = b.pivot_value(&r, &x);
        }
        for r in &rows {
            assert!(r.eval(&x).abs() < 1e-12, "{}", r.eval(&x));
        }
    }
}
