//! One block of slots factored for projections ([`Block`]): the null space `N` of the
//! chosen rows inside it, the Cholesky factor of `NᵀHN`, rows chosen since as rank-one
//! corrections, and (once worth it) the dense `K = N (NᵀHN)⁻¹ Nᵀ`. It serves `K nᵀ` for a
//! row and a row pair's share of `n K nᵀ`; [`super::Projector`] decides which blocks a
//! projection reads and when a block is factored afresh.
//!
//! Invariant: every way of reading `K` (columns by solving, the dense `K`, forward
//! substitutions for a Gram matrix) is the same matrix up to round-off, with the
//! corrections not folded into it subtracted.

use super::{Faces, Metric};
use crate::analysis::rowbasis::RowBasis;
use crate::ir::{Affine, SlotId};
use crate::tolerance::{CHOLESKY_RETRY_RIDGE, SCALE_FLOOR};
use nalgebra::{DMatrix, DVector};
use std::collections::HashMap;

/// One block factored for projections: its null-space basis and `NᵀHN`.
pub(super) struct Block {
    /// Row of `null` for each slot of the block.
    pub(super) index: HashMap<SlotId, usize>,
    pub(super) slots: Vec<SlotId>,
    /// `|slots| × r`, row by row as sparse (column, value) lists: a basis of the chosen
    /// rows' null space inside the block. A free slot's row is its own unit column; a
    /// pivot's row holds its row-echelon coefficients, so `N` has the rows' fill, no more.
    pub(super) null: Vec<Vec<(usize, f64)>>,
    /// `r`, the block's free dimension.
    pub(super) rank: usize,
    /// Cholesky factor of `NᵀHN` (`None` when the rows fix the block: `r = 0`).
    pub(super) gram: Option<nalgebra::Cholesky<f64, nalgebra::Dyn>>,
    /// Rows chosen since the factorisation, as rank-one corrections `K ← K − u uᵀ / s`
    /// (`u = K nᵀ` over the block's slots, `s = n K nᵀ`), while there is no dense `K` to
    /// fold them into (the sum is the same in any order).
    pub(super) corrections: Vec<(Vec<f64>, f64)>,
    /// `K = N (NᵀHN)⁻¹ Nᵀ` over the block's slots, dense: made once the factorisation has
    /// served as many columns as the block has slots (by then the solves it saves cost as
    /// much as making it), for blocks of at most [`DENSE_MAX_SLOTS`] slots.
    pub(super) dense: std::cell::OnceCell<DMatrix<f64>>,
    /// Columns served by solving since the factorisation.
    pub(super) served: std::cell::Cell<usize>,
    /// Rows absorbed since the factorisation: corrections, or folded into the dense `K`.
    pub(super) absorbed: usize,
}

/// Largest block kept as a dense `K` (its square, in floats, per variation's metric).
const DENSE_MAX_SLOTS: usize = 1024;

/// A block is factored afresh once this many rows were absorbed (as corrections or folded
/// into its dense `K`), which bounds the round-off the updates gather.
pub(super) const MAX_CORRECTIONS: usize = 32;

/// `Σ a·v` over the sparse rows `v` (of `N`) picked by a sparse combination: a sparse
/// combination of `N`'s rows, merged by column.
fn combine<'a>(
    parts: impl IntoIterator<Item = (f64, &'a [(usize, f64)])>,
    out: &mut Vec<(usize, f64)>,
) {
    out.clear();
    for (a, row) in parts {
        for &(j, v) in row {
            out.push((j, a * v));
        }
    }
    out.sort_unstable_by_key(|&(j, _)| j);
    out.dedup_by(|next, kept| {
        if next.0 == kept.0 {
            kept.1 += next.1;
            true
        } else {
            false
        }
    });
}

impl Block {
    pub(super) fn build(
        faces: &Faces,
        metric: &Metric,
        basis: &RowBasis,
        slots: Vec<SlotId>,
    ) -> Block {
        let index: HashMap<SlotId, usize> =
            slots.iter().enumerate().map(|(i, &s)| (s, i)).collect();
        let free: Vec<SlotId> = slots
            .iter()
            .copied()
            .filter(|&s| basis.row_with_pivot(s).is_none())
            .collect();
        let column: HashMap<SlotId, usize> =
            free.iter().enumerate().map(|(j, &s)| (s, j)).collect();
        let null: Vec<Vec<(usize, f64)>> = slots
            .iter()
            .map(|&s| match basis.row_with_pivot(s) {
                None => vec![(column[&s], 1.0)],
                Some(row) => row
                    .terms
                    .iter()
                    .filter(|&&(t, _)| t != s)
                    .filter_map(|&(t, a)| Some((*column.get(&t)?, -a)))
                    .collect(),
            })
            .collect();
        let r = free.len();
        let gram = (r > 0).then(|| {
            let mut entries: Vec<u32> = slots
                .iter()
                .flat_map(|&s| faces.parts_of_slot[s as usize].iter().copied())
                .collect();
            entries.sort_unstable();
            entries.dedup();
            // NᵀHN = Σ area² (Nᵀq)(Nᵀq)ᵀ + ridge·NᵀN, each term a sparse outer product.
            let mut m = DMatrix::<f64>::zeros(r, r);
            let mut outer = |w2: f64, g: &[(usize, f64)]| {
                for &(i, a) in g {
                    for &(j, b) in g {
                        m[(i, j)] += w2 * a * b;
                    }
                }
            };
            let mut g = Vec::new();
            for (w2, q) in faces.weighted_faces(metric, &entries) {
                combine(
                    q.terms
                        .iter()
                        .filter_map(|&(s, a)| Some((a, null[*index.get(&s)?].as_slice()))),
                    &mut g,
                );
                outer(w2, &g);
            }
            for (row, &s) in null.iter().zip(&slots) {
                let own = metric.slots.get(s as usize).copied().unwrap_or(0.0);
                outer(metric.ridge + own, row);
            }
            positive_definite_factor(m)
        });
        Block {
            index,
            slots,
            null,
            rank: r,
            gram,
            corrections: Vec::new(),
            dense: std::cell::OnceCell::new(),
            served: std::cell::Cell::new(0),
            absorbed: 0,
        }
    }

    /// The dense `K`, when it is made or now worth making (see [`Block::dense`]).
    pub(super) fn dense_k(
        &self,
        gram: &nalgebra::Cholesky<f64, nalgebra::Dyn>,
    ) -> Option<&DMatrix<f64>> {
        if let Some(k) = self.dense.get() {
            return Some(k);
        }
        let n = self.slots.len();
        self.served.set(self.served.get() + 1);
        if n > DENSE_MAX_SLOTS || self.served.get() < n {
            return None;
        }
        // K = N G⁻¹ Nᵀ = YᵀY with L Y = Nᵀ (G = L Lᵀ): one forward substitution per slot
        // and a product, where solving G X = Nᵀ takes two and then N X.
        let mut y = DMatrix::<f64>::zeros(self.rank, n);
        for (i, row) in self.null.iter().enumerate() {
            for &(j, v) in row {
                y[(j, i)] = v;
            }
        }
        let l = gram.l_dirty();
        for mut column in y.column_iter_mut() {
            forward(l, column.as_mut_slice());
        }
        let k = y.tr_mul(&y);
        Some(self.dense.get_or_init(|| k))
    }

    /// `K nᵀ` over the block's slots, for the part of `row` inside the block.
    pub(super) fn k_column(&self, row: &Affine) -> Vec<f64> {
        let mut col = match &self.gram {
            Some(gram) => match self.dense_k(gram) {
                Some(k) => {
                    let mut col = vec![0.0; self.slots.len()];
                    for &(s, a) in &row.terms {
                        if let Some(&i) = self.index.get(&s) {
                            for (c, v) in col.iter_mut().zip(k.column(i).iter()) {
                                *c += a * v;
                            }
                        }
                    }
                    col
                }
                None => self.expand(&gram.solve(&self.reduced(row))),
            },
            None => vec![0.0; self.slots.len()],
        };
        for (u, s) in &self.corrections {
            let d = self.dot(row, u);
            if d != 0.0 {
                for (c, v) in col.iter_mut().zip(u) {
                    *c -= v * d / s;
                }
            }
        }
        col
    }

    /// Adds the block's share of `n K nᵀ` for `rows` to `m` without columns over the
    /// block's slots, when it has a factor and no dense `K` (counting the rows as served,
    /// as [`Block::k_column`] would, and leaving the block to the dense path once that makes
    /// `K`): with `w = Nᵀnᵀ` and `NᵀHN = L Lᵀ`, `n K n'ᵀ = (L⁻¹w)·(L⁻¹w')`, a forward
    /// substitution per row that starts at its first entry, where a column needs both
    /// substitutions and `N`. Whether it did.
    pub(super) fn forward_gram(&self, rows: &[&Affine], m: &mut DMatrix<f64>) -> bool {
        let Some(gram) = &self.gram else {
            return false;
        };
        if self.dense.get().is_some() || rows.iter().any(|_| self.dense_k(gram).is_some()) {
            return false;
        }
        let l = gram.l_dirty();
        let z: Vec<(usize, DVector<f64>)> = rows
            .iter()
            .map(|r| {
                let mut w = self.reduced(r);
                (forward(l, w.as_mut_slice()), w)
            })
            .collect();
        let inside: Vec<RowInBlock> = rows.iter().map(|r| self.row_in_block(r)).collect();
        for i in 0..rows.len() {
            for j in i..rows.len() {
                let from = z[i].0.max(z[j].0);
                let v = z[i].1.rows_range(from..).dot(&z[j].1.rows_range(from..));
                let v = self.less_corrections(v, &inside[i], &inside[j]);
                m[(i, j)] += v;
                if j != i {
                    m[(j, i)] += v;
                }
            }
        }
        true
    }

    /// Takes `row` into `K` as a rank-one correction, folded into the dense `K` where there
    /// is one (a column then costs the row's terms, not one pass per correction).
    pub(super) fn absorb(&mut self, row: &Affine) {
        let u = self.k_column(row);
        let s = self.dot(row, &u);
        if s > 0.0 && s.is_finite() {
            self.absorbed += 1;
            match self.dense.get_mut() {
                Some(k) => {
                    let u = DVector::from_column_slice(&u);
                    k.ger(-1.0 / s, &u, &u, 1.0);
                }
                None => self.corrections.push((u, s)),
            }
        }
    }

    /// `row`'s terms inside this block, as `(position in the block, coefficient)` in the
    /// row's order: what [`dot_of`] reads, so a Gram matrix looks each slot up once per
    /// row, not once per pair of rows.
    pub(super) fn terms_in_block(&self, row: &Affine) -> Vec<(usize, f64)> {
        row.terms
            .iter()
            .filter_map(|&(s, a)| Some((*self.index.get(&s)?, a)))
            .collect()
    }

    /// A row taken into the block with its dot with every correction, what
    /// [`Block::k_form_of`] reads.
    pub(super) fn row_in_block(&self, row: &Affine) -> RowInBlock {
        let terms = self.terms_in_block(row);
        let corrections = self
            .corrections
            .iter()
            .map(|(u, _)| dot_of(&terms, u))
            .collect();
        RowInBlock { terms, corrections }
    }

    /// `a K bᵀ` for the parts of two rows inside the block (taken in by
    /// [`Block::row_in_block`]), read off the dense `K` and the corrections not folded into
    /// it, when there is one: it needs `K` only at the rows' own slots, where
    /// [`Block::dot`] of a column needs the whole column.
    pub(super) fn k_form_of(&self, k: &DMatrix<f64>, a: &RowInBlock, b: &RowInBlock) -> f64 {
        let mut v = 0.0;
        for &(i, x) in &a.terms {
            for &(j, y) in &b.terms {
                v += x * y * k[(i, j)];
            }
        }
        self.less_corrections(v, a, b)
    }

    /// `v` (a share of `a K₀ bᵀ` before the corrections) less the corrections not folded
    /// into `K`: `Σ (a·u)(b·u) / s`, in their order.
    fn less_corrections(&self, mut v: f64, a: &RowInBlock, b: &RowInBlock) -> f64 {
        for ((da, db), (_, s)) in a
            .corrections
            .iter()
            .zip(&b.corrections)
            .zip(&self.corrections)
        {
            v -= da * db / s;
        }
        v
    }

    /// `n · v` for the part of `row` inside the block and `v` over its slots.
    pub(super) fn dot(&self, row: &Affine, v: &[f64]) -> f64 {
        row.terms
            .iter()
            .filter_map(|&(s, a)| Some(a * v[*self.index.get(&s)?]))
            .sum()
    }

    /// `Nᵀ nᵀ` for the part of `row` inside this block.
    pub(super) fn reduced(&self, row: &Affine) -> DVector<f64> {
        let mut w = DVector::zeros(self.rank);
        for &(s, a) in &row.terms {
            if let Some(&i) = self.index.get(&s) {
                for &(j, v) in &self.null[i] {
                    w[j] += a * v;
                }
            }
        }
        w
    }

    /// `N z`, slot by slot of the block.
    pub(super) fn expand(&self, z: &DVector<f64>) -> Vec<f64> {
        self.null
            .iter()
            .map(|row| row.iter().map(|&(j, v)| v * z[j]).sum())
            .collect()
    }
}

/// `w ← L⁻¹ w` for a lower-triangular `L` (read below its diagonal only), by columns from
/// `w`'s first non-zero entry, which it returns (the entries before it stay zero).
fn forward(l: &DMatrix<f64>, w: &mut [f64]) -> usize {
    let r = w.len();
    let first = w.iter().position(|v| *v != 0.0).unwrap_or(r);
    let cells = l.as_slice();
    for k in first..r {
        let zk = w[k] / cells[k * r + k];
        w[k] = zk;
        if zk != 0.0 {
            let col = &cells[k * r + k + 1..(k + 1) * r];
            for (wi, lik) in w[k + 1..].iter_mut().zip(col) {
                *wi -= lik * zk;
            }
        }
    }
    first
}

/// The Cholesky factor of the symmetric `m`. `NᵀHN` is positive definite (N has full column
/// rank and the ridge is positive); should round-off say otherwise, a larger ridge is added.
fn positive_definite_factor(m: DMatrix<f64>) -> nalgebra::Cholesky<f64, nalgebra::Dyn> {
    let r = m.nrows();
    let scale = (0..r)
        .map(|i| m[(i, i)].abs())
        .fold(0.0f64, f64::max)
        .max(SCALE_FLOOR);
    let mut ridge = 0.0;
    loop {
        if ridge > 1e6 * scale || m.iter().any(|v| !v.is_finite()) {
            // Nothing sensible to factor: an identity metric on the null space.
            // The identity is its own Cholesky factor (I = I·Iᵀ).
            return nalgebra::Cholesky::pack_dirty(DMatrix::identity(r, r));
        }
        let shifted = &m + DMatrix::identity(r, r) * ridge;
        if let Some(c) = shifted.cholesky() {
            return c;
        }
        ridge = if ridge == 0.0 {
            CHOLESKY_RETRY_RIDGE * scale
        } else {
            ridge * 100.0
        };
    }
}

/// A row's terms inside one block and its dots with the block's corrections
/// ([`Block::row_in_block`]).
pub(super) struct RowInBlock {
    terms: Vec<(usize, f64)>,
    corrections: Vec<f64>,
}

/// [`Block::dot`] of a row taken into the block, to the bit.
pub(super) fn dot_of(terms: &[(usize, f64)], v: &[f64]) -> f64 {
    terms.iter().map(|&(i, a)| a * v[i]).sum()
}
