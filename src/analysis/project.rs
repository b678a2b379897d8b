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

/// An orthonormal basis of the span of the chosen rows, with their right-hand sides.
#[derive(Debug, Clone, Default)]
pub struct RowBasis {
    rows: Vec<DVector<f64>>,
}

impl RowBasis {
    pub fn len(&self) -> usize {
        self.rows.len()
    }

    pub fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }

    fn residual(&self, r: &DVector<f64>) -> DVector<f64> {
        let mut v = r.clone();
        for _ in 0..2 {
            for b in &self.rows {
                let k = b.dot(&v);
                v.axpy(-k, b, 1.0);
            }
        }
        v
    }

    /// Whether `row` lies in the span (relative tolerance).
    pub fn contains(&self, row: &DVector<f64>) -> bool {
        let n = row.norm();
        n == 0.0 || self.residual(row).norm() <= 1e-9 * n
    }

    /// Adds `row` if it is independent; returns whether it was.
    pub fn add(&mut self, row: &DVector<f64>) -> bool {
        if self.contains(row) {
            return false;
        }
        let r = self.residual(row);
        let n = r.norm();
        self.rows.push(r / n);
        true
    }

    pub fn matrix(&self, d: usize) -> DMatrix<f64> {
        let mut m = DMatrix::zeros(self.rows.len(), d);
        for (i, r) in self.rows.iter().enumerate() {
            m.set_row(i, &r.transpose());
        }
        m
    }
}

/// The linear part of an affine row as a dense vector.
pub fn dense(row: &Affine, d: usize) -> DVector<f64> {
    let mut v = DVector::zeros(d);
    for &(s, a) in &row.terms {
        v[s as usize] = a;
    }
    v
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
        let k = &hinv - &hb * linalg::pinv(&m) * hb.transpose();
        Projector { k }
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
