//! Re-parameterization: the chosen constraints solved for a few free variables.
//!
//! Gauss–Jordan elimination on the chosen rows plus anchor rows, with the columns ordered so
//! the meaningful slots stay free (named variables, then sizes, larger parts first; positions
//! are eliminated first). Pivot columns become dependent slots, each an affine expression of
//! the free ones. The coefficients are small rationals (±1, ±½, …); elimination runs in `f64`
//! with partial pivoting and the results are read back as exact fractions (`Frac`).

use super::anchors::Anchors;
use super::linalg::rank;
use super::rowbasis::RowBasis;
use crate::ir::{Affine, Model, SlotId};
use crate::tolerance::{COEFFICIENT_ZERO, FRACTION_REMAINDER_ZERO, RELATIVE_ROUNDOFF};

/// A small exact fraction `num / den`, `den > 0`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Frac {
    pub num: i64,
    pub den: i64,
}

impl Frac {
    /// The fraction with denominator at most 1000 within round-off of `x` (relative), if
    /// there is one.
    pub fn near(x: f64) -> Option<Frac> {
        if !x.is_finite() || x.abs() > 1e12 {
            return None;
        }
        // Continued fractions: the best approximations with small denominators.
        let (mut h0, mut h1, mut k0, mut k1) = (0i64, 1i64, 1i64, 0i64);
        let mut v = x;
        for _ in 0..20 {
            let a = v.floor();
            let (h2, k2) = (a as i64 * h1 + h0, a as i64 * k1 + k0);
            if k2 > 1000 {
                break;
            }
            if ((h2 as f64) / (k2 as f64) - x).abs() <= RELATIVE_ROUNDOFF * x.abs().max(1.0) {
                return Some(Frac { num: h2, den: k2 });
            }
            (h0, h1, k0, k1) = (h1, h2, k1, k2);
            let f = v - a;
            if f.abs() < FRACTION_REMAINDER_ZERO {
                break;
            }
            v = 1.0 / f;
        }
        None
    }

    pub fn value(&self) -> f64 {
        self.num as f64 / self.den as f64
    }
}

/// A slot's value as `constant + Σ coeff · free[i]`.
#[derive(Debug, Clone, PartialEq)]
pub struct Expression {
    pub constant: f64,
    /// (index into the free variables, coefficient), by index.
    pub terms: Vec<(usize, f64)>,
}

impl Expression {
    pub fn eval(&self, free: &[f64]) -> f64 {
        self.terms
            .iter()
            .fold(self.constant, |acc, &(i, a)| acc + a * free[i])
    }
}

/// The solved system: which slots are free and how every slot follows from them.
#[derive(Debug, Clone)]
pub struct Solution {
    /// Free slots, in the order they will be shown.
    pub free: Vec<SlotId>,
    /// For every slot (by id), its expression in the free variables.
    pub exprs: Vec<Expression>,
    /// How many anchor rows were added (rigid moves removed).
    pub anchors: usize,
    /// Free variables that are a contact's depth rather than a slot (`contact_vars`); the
    /// slot at their index in `free` is the one they took the place of.
    pub contacts: Vec<ContactVariable>,
}

/// A free variable that measures how far two parts overlap along an axis: the contact
/// side's form (`form ≥ 0` keeps them touching), over slots.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactVariable {
    /// Its index among the free variables.
    pub index: usize,
    /// The part the replaced slot moved, then the other one.
    pub parts: [usize; 2],
    pub axis: u8,
    pub form: Affine,
}

impl Solution {
    /// Slot values for the free variables' values.
    pub fn slot_values(&self, free: &[f64]) -> Vec<f64> {
        self.exprs.iter().map(|e| e.eval(free)).collect()
    }

    /// The free variables' values at slot values `x`.
    pub fn free_values(&self, x: &[f64]) -> Vec<f64> {
        let mut out: Vec<f64> = self.free.iter().map(|&f| x[f as usize]).collect();
        for c in &self.contacts {
            out[c.index] = c.form.eval(x);
        }
        out
    }

    /// The contact variable at free index `i`, if it is one.
    pub fn contact(&self, i: usize) -> Option<&ContactVariable> {
        self.contacts.iter().find(|c| c.index == i)
    }

    /// Free variable `j` held at `value` for good: its terms become constants, it leaves
    /// the free variables (a slot it was becomes that constant), and the later ones move
    /// down by one. Every slot's value at the other variables is what it was with `j` at
    /// `value`.
    pub fn fix_free(&mut self, j: usize, value: f64) {
        for e in &mut self.exprs {
            if let Some(&(_, a)) = e.terms.iter().find(|&&(i, _)| i == j) {
                e.constant += a * value;
            }
            e.terms.retain(|&(i, _)| i != j);
            for (i, _) in &mut e.terms {
                if *i > j {
                    *i -= 1;
                }
            }
        }
        self.free.remove(j);
        self.contacts.retain(|c| c.index != j);
        for c in &mut self.contacts {
            if c.index > j {
                c.index -= 1;
            }
        }
    }
}

/// Each slot's place in [`column_order`]: the higher, the more it is wanted free.
pub(crate) fn wanted_rank(model: &Model) -> Vec<usize> {
    let mut rank = vec![0; model.slots.len()];
    for (k, s) in column_order(model).into_iter().enumerate() {
        rank[s] = k;
    }
    rank
}

/// Column order: least wanted as a free variable first.
fn column_order(model: &Model) -> Vec<usize> {
    let mut volume = vec![0.0f64; model.slots.len()];
    for p in &model.parts {
        let (lo, hi) = p.world_bounds();
        let v = (0..3).map(|a| (hi[a] - lo[a]).abs()).product::<f64>();
        for s in p.slot_deps() {
            volume[s as usize] = volume[s as usize].max(v);
        }
    }
    let mut order: Vec<usize> = (0..model.slots.len()).collect();
    let rank_of = |s: usize| {
        let slot = &model.slots[s];
        let kind = if slot.variable.is_some() {
            2
        } else if slot.position {
            0
        } else {
            1
        };
        (kind, volume[s])
    };
    order.sort_by(|&a, &b| {
        let (ka, va) = rank_of(a);
        let (kb, vb) = rank_of(b);
        ka.cmp(&kb).then(va.total_cmp(&vb)).then(b.cmp(&a))
    });
    order
}

/// One row of the elimination: coefficients by column position (in elimination order).
struct SparseRow {
    terms: std::collections::HashMap<usize, f64>,
    constant: f64,
}

/// Gauss–Jordan elimination of the affine `system` with columns taken in `order`, partial
/// pivoting (largest entry of the column among the rows not yet used) and every other row
/// cleared at each pivot: the reduced row-echelon form, row `k` pivoting on `pivots[k]`.
/// Sparse: a column index finds the rows to clear, so the cost follows the rows' fill.
fn gauss_jordan(system: &[Affine], order: &[usize]) -> (Vec<SparseRow>, Vec<usize>) {
    let mut position = vec![0usize; order.len()];
    for (p, &s) in order.iter().enumerate() {
        position[s] = p;
    }
    let mut rows: Vec<SparseRow> = system
        .iter()
        .map(|r| {
            let mut terms = std::collections::HashMap::new();
            for &(s, a) in &r.terms {
                *terms.entry(position[s as usize]).or_insert(0.0) += a;
            }
            terms.retain(|_, a: &mut f64| *a != 0.0);
            SparseRow {
                terms,
                constant: r.constant,
            }
        })
        .collect();
    let mut holders: Vec<std::collections::BTreeSet<usize>> = vec![Default::default(); order.len()];
    for (i, r) in rows.iter().enumerate() {
        for &c in r.terms.keys() {
            holders[c].insert(i);
        }
    }
    let m = rows.len();
    let mut used = vec![false; m];
    let mut pivot_rows: Vec<usize> = Vec::new();
    let mut pivots = Vec::new();
    for col in 0..order.len() {
        if pivot_rows.len() == m {
            break;
        }
        let Some(p) = holders[col]
            .iter()
            .copied()
            .filter(|&i| !used[i])
            .max_by(|&i, &j| {
                rows[i].terms[&col]
                    .abs()
                    .total_cmp(&rows[j].terms[&col].abs())
            })
        else {
            continue;
        };
        if rows[p].terms[&col].abs() < RELATIVE_ROUNDOFF {
            continue;
        }
        let pv = rows[p].terms[&col];
        for v in rows[p].terms.values_mut() {
            *v /= pv;
        }
        rows[p].constant /= pv;
        let pivot_terms: Vec<(usize, f64)> = rows[p].terms.iter().map(|(&c, &v)| (c, v)).collect();
        let pivot_constant = rows[p].constant;
        let others: Vec<usize> = holders[col].iter().copied().filter(|&i| i != p).collect();
        for i in others {
            let f = rows[i].terms[&col];
            for &(c, v) in &pivot_terms {
                let e = rows[i].terms.entry(c).or_insert(0.0);
                *e -= f * v;
                if *e == 0.0 || c == col {
                    rows[i].terms.remove(&c);
                    holders[c].remove(&i);
                } else {
                    holders[c].insert(i);
                }
            }
            rows[i].constant -= f * pivot_constant;
        }
        used[p] = true;
        pivot_rows.push(p);
        pivots.push(col);
    }
    // The pivot rows in the order they pivoted (each row pivots at most once).
    let mut rank_of: Vec<Option<usize>> = vec![None; m];
    for (k, &p) in pivot_rows.iter().enumerate() {
        rank_of[p] = Some(k);
    }
    let mut ordered: Vec<(usize, SparseRow)> = rows
        .into_iter()
        .zip(rank_of)
        .filter_map(|(r, k)| Some((k?, r)))
        .collect();
    ordered.sort_unstable_by_key(|&(k, _)| k);
    (ordered.into_iter().map(|(_, r)| r).collect(), pivots)
}

/// Solves `rows` (affine, each `= 0`) plus the gauge and the anchors (the model's own,
/// [`Anchors::of`]) for the free slots.
pub fn solve(model: &Model, anchors: &Anchors, rows: &[Affine]) -> Solution {
    let d = model.slots.len();
    let mut basis = RowBasis::default();
    let mut system: Vec<Affine> = Vec::new();
    for r in rows {
        if basis.add_terms(&r.terms) {
            system.push(r.clone());
        }
    }
    for r in &anchors.gauge {
        if basis.add_terms(&r.terms) {
            system.push(r.clone());
        }
    }
    let mut pinned = 0;
    for r in anchors.rows() {
        if basis.add_terms(&r.terms) {
            system.push(r);
            pinned += 1;
        }
    }
    let order = column_order(model);
    let (a, pivots) = gauss_jordan(&system, &order);
    let snap = |x: f64| Frac::near(x).map_or(x, |f| f.value());
    let mut is_pivot = vec![false; d];
    for &c in &pivots {
        is_pivot[c] = true;
    }
    let free_cols: Vec<usize> = (0..d).filter(|&c| !is_pivot[c]).collect();
    let mut free: Vec<SlotId> = free_cols.iter().map(|&c| order[c] as SlotId).collect();
    free.sort_unstable();
    let free_index = |slot: usize| free.iter().position(|&f| f as usize == slot);
    let mut exprs = vec![
        Expression {
            constant: 0.0,
            terms: Vec::new()
        };
        d
    ];
    for (k, &f) in free.iter().enumerate() {
        exprs[f as usize] = Expression {
            constant: 0.0,
            terms: vec![(k, 1.0)],
        };
    }
    for (r, &pc) in pivots.iter().enumerate() {
        let slot = order[pc];
        let mut terms: Vec<(usize, f64)> = a[r]
            .terms
            .iter()
            .filter(|&(&c, v)| c != pc && !is_pivot[c] && v.abs() > COEFFICIENT_ZERO)
            .filter_map(|(&c, &v)| Some((free_index(order[c])?, snap(-v))))
            .collect();
        terms.sort_by_key(|t| t.0);
        exprs[slot] = Expression {
            constant: -a[r].constant,
            terms,
        };
    }
    debug_assert_eq!(
        rank(&system.iter().collect::<Vec<_>>(), d),
        pivots.len(),
        "elimination and SVD disagree on the rank"
    );
    Solution {
        free,
        exprs,
        anchors: pinned,
        contacts: Vec::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::{ContactVariable, Expression, Frac, Solution};
    use crate::ir::Affine;

    /// Fixing a free variable leaves every slot where it was with that variable at the
    /// value it is fixed at, and the later variables (a contact variable among them) move
    /// down by one.
    #[test]
    fn a_fixed_variable_becomes_a_constant() {
        let var = |i: usize| Expression {
            constant: 0.0,
            terms: vec![(i, 1.0)],
        };
        let mut sol = Solution {
            free: vec![0, 1, 2],
            exprs: vec![
                var(0),
                var(1),
                var(2),
                Expression {
                    constant: 1.0,
                    terms: vec![(0, 2.0), (1, 3.0), (2, -1.0)],
                },
            ],
            anchors: 0,
            contacts: vec![ContactVariable {
                index: 2,
                parts: [0, 1],
                axis: 0,
                form: Affine::constant(0.0),
            }],
        };
        let before = sol.slot_values(&[4.0, 5.0, 6.0]);
        sol.fix_free(1, 5.0);
        assert_eq!(sol.free, vec![0, 2]);
        assert_eq!(sol.slot_values(&[4.0, 6.0]), before);
        assert_eq!(sol.contacts[0].index, 1);
        assert!(sol.exprs[1].terms.is_empty());
    }

    #[test]
    fn fractions_are_recovered() {
        assert_eq!(Frac::near(0.5), Some(Frac { num: 1, den: 2 }));
        assert_eq!(Frac::near(-1.5), Some(Frac { num: -3, den: 2 }));
        assert_eq!(Frac::near(1.0 / 3.0 + 1e-15), Some(Frac { num: 1, den: 3 }));
        assert_eq!(Frac::near(std::f64::consts::PI), None);
    }
}
