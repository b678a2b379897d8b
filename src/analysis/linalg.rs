//! Linear algebra over constraint rows.
//!
//! A constraint set is a matrix `C` whose rows are the linear parts of affine forms over the
//! model's slots; the constrained space is its null space. This module turns rows into
//! matrices and answers rank questions with a tolerance scaled to the rows' magnitude.

use super::slotblocks::SlotBlocks;
use crate::ir::{Affine, SlotId};
use crate::tolerance::{PSEUDO_INVERSE_CUTOFF, RELATIVE_ROUNDOFF};
use nalgebra::DMatrix;

/// The rows' linear parts as a dense `rows × slots` matrix.
pub fn matrix(rows: &[&Affine], slots: usize) -> DMatrix<f64> {
    let mut m = DMatrix::zeros(rows.len(), slots);
    for (i, r) in rows.iter().enumerate() {
        for &(s, a) in &r.terms {
            m[(i, s as usize)] = a;
        }
    }
    m
}

/// The rank of the rows (0 for no rows).
pub fn rank(rows: &[&Affine], slots: usize) -> usize {
    if rows.is_empty() || slots == 0 {
        return 0;
    }
    let m = matrix(rows, slots);
    let scale = m.iter().fold(0.0f64, |acc, v| acc.max(v.abs())).max(1.0);
    m.rank(RELATIVE_ROUNDOFF * scale * (rows.len().max(slots) as f64))
}

/// The dimension of the space the rows leave free.
pub fn nullity(rows: &[&Affine], slots: usize) -> usize {
    slots - rank(rows, slots)
}

/// The Moore–Penrose pseudo-inverse with a tolerance relative to the largest singular value.
pub fn pinv(m: &DMatrix<f64>) -> DMatrix<f64> {
    if m.is_empty() {
        return m.transpose();
    }
    // One number (a one-row relation's conditional variance, most of discovery's calls):
    // what the SVD gives, its inverse or 0, without the SVD.
    if m.nrows() == 1 && m.ncols() == 1 && m[(0, 0)].is_finite() {
        let v = m[(0, 0)];
        return DMatrix::from_element(1, 1, if v == 0.0 { 0.0 } else { 1.0 / v });
    }
    svd_pinv(m)
}

/// [`pinv`] through the SVD, whatever the shape.
fn svd_pinv(m: &DMatrix<f64>) -> DMatrix<f64> {
    let svd = m.clone().svd(true, true);
    let smax = svd.singular_values.iter().fold(0.0f64, |a, &s| a.max(s));
    let eps =
        PSEUDO_INVERSE_CUTOFF * smax.max(f64::MIN_POSITIVE) * (m.nrows().max(m.ncols()) as f64);
    svd.pseudo_inverse(eps)
        .unwrap_or_else(|_| DMatrix::zeros(m.ncols(), m.nrows()))
}

/// The least-norm least-squares solution of sparse equations `row · δ = rhs` over `slots`
/// unknowns, solved block by block (unknowns joined by a shared equation form one block, and
/// blocks do not interact), with the largest residual left.
pub fn least_norm_solve(rows: &[(Vec<(SlotId, f64)>, f64)], slots: usize) -> (Vec<f64>, f64) {
    let mut blocks = SlotBlocks::new(slots);
    for (terms, _) in rows {
        blocks.join(terms.iter().map(|&(s, _)| s));
    }
    let mut by_block: std::collections::HashMap<SlotId, Vec<usize>> = Default::default();
    for (i, (terms, _)) in rows.iter().enumerate() {
        if let Some(&(s, _)) = terms.first() {
            by_block.entry(blocks.find(s)).or_default().push(i);
        }
    }
    let mut delta = vec![0.0; slots];
    let mut residual = rows
        .iter()
        .filter(|(t, _)| t.is_empty())
        .fold(0.0f64, |m, (_, b)| m.max(b.abs()));
    for members in by_block.values() {
        let mut unknowns: Vec<SlotId> = members
            .iter()
            .flat_map(|&i| rows[i].0.iter().map(|&(s, _)| s))
            .collect();
        unknowns.sort_unstable();
        unknowns.dedup();
        let q = DMatrix::from_fn(members.len(), unknowns.len(), |i, j| {
            rows[members[i]]
                .0
                .iter()
                .filter(|&&(s, _)| s == unknowns[j])
                .map(|&(_, a)| a)
                .sum()
        });
        let b = nalgebra::DVector::from_fn(members.len(), |i, _| rows[members[i]].1);
        let x = pinv(&q) * &b;
        residual = residual.max((&q * &x - &b).amax());
        for (j, &s) in unknowns.iter().enumerate() {
            delta[s as usize] = x[j];
        }
    }
    (delta, residual)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_number_is_inverted_as_the_svd_inverts_it() {
        for v in [1.0, -1.0, 3.7, -0.25, 1e-300, -4e12, 0.0, 7.0 / 3.0] {
            let m = DMatrix::from_element(1, 1, v);
            let (fast, svd) = (pinv(&m)[(0, 0)], svd_pinv(&m)[(0, 0)]);
            assert_eq!(fast.to_bits(), svd.to_bits(), "{v}: {fast} against {svd}");
        }
    }
}
