//! Projection of a variation onto a constraint set (Algorithm 1 of the paper's supplement).
//!
//! The cost of a projection is the squared volume its face shifts sweep: every axis-aligned
//! face (a box's six, a frustum's two ends and four side extremes) is an affine form `q·x`,
//! weighted by its area at the point being projected (×π/4 for frustums). With
//! `H = Σ area² q qᵀ + μI`, projecting `x` onto `{x : B x = b}` is the `H`-metric projection.
//! A [`Projector`] holds `K = H⁻¹ − H⁻¹Bᵀ(BH⁻¹Bᵀ)⁻¹BH⁻¹` for the already-chosen rows `B`,
//! so adding one candidate's rows costs one small solve: `Δ = −K nᵀ (n K nᵀ)⁺ (n x + c)`.
//! Projecting a point that satisfies `B` in two steps equals projecting it at once (the
//! projections are nested in the same metric), which is what makes greedy scoring cheap.

use crate::analysis::linalg;
use crate::ir::feature::world_intervals;
use crate::ir::{Affine, Model, Primitive};
use nalgebra::{DMatrix, DVector};
use std::collections::HashMap;

/// The faces of a model's axis-aligned parts, as affine forms, with what sizes them.
#[derive(Debug, Clone)]
pub struct Faces {
    parts: Vec<PartFaces>,
    slots: usize,
}

#[derive(Debug, Clone)]
struct PartFaces {
    part: usize,
    /// (low, high) face form along each world axis.
    intervals: [(Affine, Affine); 3],
    round: bool,
}

impl Faces {
    pub fn of(model: &Model) -> Faces {
        let parts = model
            .parts
            .iter()
            .enumerate()
            .filter(|(_, p)| p.misaligned.is_none())
            .filter_map(|(i, p)| {
                let iv = world_intervals(p)?;
                let form = |n: &crate::ir::Num| n.affine().cloned();
                let intervals = [
                    (form(&iv[0].0)?, form(&iv[0].1)?),
                    (form(&iv[1].0)?, form(&iv[1].1)?),
                    (form(&iv[2].0)?, form(&iv[2].1)?),
                ];
                Some(PartFaces {
                    part: i,
                    intervals,
                    round: !matches!(p.primitive, Primitive::Cube { .. }),
                })
            })
            .collect();
        Faces {
            parts,
            slots: model.slots.len(),
        }
    }

    /// The projection metric `H` at the point `x`, ignoring parts in `skip`.
    pub fn metric(&self, x: &[f64], skip: &[usize]) -> DMatrix<f64> {
        let d = self.slots;
        let mut h = DMatrix::<f64>::zeros(d, d);
        for pf in self.parts.iter().filter(|pf| !skip.contains(&pf.part)) {
            let ext: [f64; 3] = std::array::from_fn(|a| {
                (pf.intervals[a].1.eval(x) - pf.intervals[a].0.eval(x)).abs()
            });
            for a in 0..3 {
                let mut area = ext[(a + 1) % 3] * ext[(a + 2) % 3];
                if pf.round {
                    area *= std::f64::consts::FRAC_PI_4;
                }
                let w2 = area * area;
                if w2 == 0.0 {
                    continue;
                }
                for f in [&pf.intervals[a].0, &pf.intervals[a].1] {
                    for &(i, ci) in &f.terms {
                        for &(j, cj) in &f.terms {
                            h[(i as usize, j as usize)] += w2 * ci * cj;
                        }
                    }
                }
            }
        }
        // A tiny ridge keeps slots no face depends on where they are.
        let scale = (0..d).map(|i| h[(i, i)]).fold(0.0, f64::max).max(1.0);
        for i in 0..d {
            h[(i, i)] += 1e-9 * scale;
        }
        h
    }
}

/// A basis of the span of the chosen rows, kept sparse in reduced row-echelon form: each
/// stored row has a pivot slot where it is 1 and every other stored row is 0. Reducing a
/// row is then one pass over its pivot entries, so the rank test costs the rows' fill, not
/// the number of slots times the number of chosen rows.
#[derive(Debug, Clone, Default)]
pub struct RowBasis {
    rows: Vec<Vec<(u32, f64)>>,
    pivot_of: HashMap<u32, usize>,
}

/// Entries below this (relative to the row's largest) are round-off.
const RELATIVE_ZERO: f64 = 1e-9;

impl RowBasis {
    pub fn len(&self) -> usize {
        self.rows.len()
    }

    pub fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }

    /// `row` minus its components along the stored rows (round-off dropped).
    fn reduce(&self, row: &[(u32, f64)]) -> HashMap<u32, f64> {
        let scale = row.iter().fold(0.0f64, |m, &(_, a)| m.max(a.abs()));
        let mut v: HashMap<u32, f64> = row.iter().copied().filter(|&(_, a)| a != 0.0).collect();
        for &(s, a) in row {
            if let Some(&k) = self.pivot_of.get(&s) {
                if a == 0.0 {
                    continue;
                }
                for &(t, b) in &self.rows[k] {
                    *v.entry(t).or_insert(0.0) -= a * b;
                }
            }
        }
        v.retain(|_, a| a.abs() > RELATIVE_ZERO * scale);
        v
    }

    /// Whether the sparse `row` lies in the span (relative tolerance).
    pub fn contains_terms(&self, row: &[(u32, f64)]) -> bool {
        self.reduce(row).is_empty()
    }

    /// Adds the sparse `row` if it is independent; returns whether it was.
    pub fn add_terms(&mut self, row: &[(u32, f64)]) -> bool {
        let v = self.reduce(row);
        let Some((&pivot, &p)) = v
            .iter()
            .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()).then(b.0.cmp(a.0)))
        else {
            return false;
        };
        let mut new: Vec<(u32, f64)> = v.iter().map(|(&s, &a)| (s, a / p)).collect();
        new.sort_by_key(|&(s, _)| s);
        for stored in &mut self.rows {
            let Some(at) = stored.iter().position(|&(s, _)| s == pivot) else {
                continue;
            };
            let f = stored[at].1;
            let scale = stored.iter().fold(0.0f64, |m, &(_, a)| m.max(a.abs()));
            let mut m: HashMap<u32, f64> = stored.iter().copied().collect();
            for &(s, a) in &new {
                *m.entry(s).or_insert(0.0) -= f * a;
            }
            m.remove(&pivot);
            m.retain(|_, a| a.abs() > RELATIVE_ZERO * scale * 1e-3);
            let mut r: Vec<(u32, f64)> = m.into_iter().collect();
            r.sort_by_key(|&(s, _)| s);
            *stored = r;
        }
        self.pivot_of.insert(pivot, self.rows.len());
        self.rows.push(new);
        true
    }

    pub fn matrix(&self, d: usize) -> DMatrix<f64> {
        let mut m = DMatrix::zeros(self.rows.len(), d);
        for (i, r) in self.rows.iter().enumerate() {
            for &(s, a) in r {
                m[(i, s as usize)] = a;
            }
        }
        m
    }
}

/// `K` for one point and one chosen basis (see the module docs).
pub struct Projector {
    k: DMatrix<f64>,
}

impl Projector {
    pub fn new(h: &DMatrix<f64>, basis: &RowBasis) -> Projector {
        let d = h.nrows();
        let hinv = h
            .clone()
            .cholesky()
            .map(|c| c.inverse())
            .unwrap_or_else(|| linalg::pinv(h));
        if basis.is_empty() {
            return Projector { k: hinv };
        }
        let b = basis.matrix(d);
        let hb = &hinv * b.transpose();
        let m = &b * &hb;
        // The basis has full row rank, so `m` is symmetric positive definite: a Cholesky
        // solve is exact and far cheaper than a pseudo-inverse.
        let correction = match m.clone().cholesky() {
            Some(c) => &hb * c.solve(&hb.transpose()),
            None => &hb * linalg::pinv(&m) * hb.transpose(),
        };
        Projector {
            k: hinv - correction,
        }
    }

    /// `x` moved (within the chosen constraints) so that the `rows` also hold. Rows are
    /// sparse (a few slots each), so `K nᵀ` is a combination of a few columns of `K`.
    pub fn project(&self, x: &DVector<f64>, rows: &[&Affine]) -> DVector<f64> {
        if rows.is_empty() {
            return x.clone();
        }
        let d = x.len();
        let mut kn = DMatrix::zeros(d, rows.len());
        for (i, r) in rows.iter().enumerate() {
            let mut col = kn.column_mut(i);
            for &(s, a) in &r.terms {
                col.axpy(a, &self.k.column(s as usize), 1.0);
            }
        }
        let m = DMatrix::from_fn(rows.len(), rows.len(), |i, j| {
            rows[i]
                .terms
                .iter()
                .map(|&(s, a)| a * kn[(s as usize, j)])
                .sum::<f64>()
        });
        let e = DVector::from_fn(rows.len(), |i, _| rows[i].eval(x.as_slice()));
        x - kn * (linalg::pinv(&m) * e)
    }
}

/// Projects `x` onto all of `rows` at once (the basis is empty), weighting faces at `x`.
pub fn project_onto(faces: &Faces, x: &[f64], rows: &[&Affine], skip: &[usize]) -> Vec<f64> {
    let h = faces.metric(x, skip);
    let p = Projector::new(&h, &RowBasis::default());
    let mut v = p.project(&DVector::from_column_slice(x), rows);
    // One refinement step absorbs round-off in the constraint residuals.
    v = p.project(&v, rows);
    v.as_slice().to_vec()
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
        // The dense matrix spans the same rows: every stored row is in the span of the input.
        let m = b.matrix(5);
        assert_eq!(m.nrows(), 3);
        assert_eq!(linalg_rank(&m), 3);
    }

    fn linalg_rank(m: &DMatrix<f64>) -> usize {
        m.clone().svd(false, false).rank(1e-9)
    }
}
