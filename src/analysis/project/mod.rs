//! Projection of a variation onto a constraint set (Algorithm 1 of the paper's supplement).
//!
//! The cost of a projection is the squared volume its face shifts sweep: every axis-aligned
//! face (a box's six, a frustum's two ends and four side extremes, and a cone's smaller
//! cap's four extremes, which its box does not show) is an affine form `q·x`,
//! weighted by its area (×π/4 for frustums). With `H = Σ area² q qᵀ + ridge`, projecting `x`
//! onto `{x : B x = b}` is the `H`-metric projection. The areas are read once per variation
//! ([`Metric`]), so projections onto growing constraint sets nest exactly: projecting a point
//! that satisfies `B` onto `B` plus a row equals projecting the variation onto both at once.
//!
//! Slots fall into blocks: two slots share a block when one face form or one chosen row holds
//! both ([`SlotBlocks`]). `H` and the rows are block-diagonal, so a projection solves only in
//! the blocks a candidate's rows touch, in null-space form: with `N` a basis of the chosen
//! rows' null space inside the block, `K = N (NᵀHN)⁻¹ Nᵀ`, and adding a candidate's rows `n`
//! moves `x` by `−K nᵀ (n K nᵀ)⁺ (n x + c)`. A block is factored only when a projection
//! needs it; a row chosen inside a factored block enters it as a rank-one correction
//! `K ← K − K nᵀ n K / (n K nᵀ)` (up to `MAX_CORRECTIONS`, then it is factored afresh), and
//! a row joining blocks drops their factors.

use super::rowbasis::RowBasis;
use super::slotblocks::SlotBlocks;
use crate::analysis::linalg;
use crate::ir::feature::world_intervals;
use crate::ir::{Affine, Model, Primitive, SlotId};
use crate::tolerance::PROJECTION_RIDGE;
mod block;

use block::{Block, MAX_CORRECTIONS, RowInBlock, dot_of};
use nalgebra::{DMatrix, DVector};
use std::collections::HashMap;

/// The faces of a model's axis-aligned parts, as affine forms, with what sizes them.
#[derive(Debug, Clone)]
pub struct Faces {
    parts: Vec<PartFaces>,
    slots: usize,
    /// For each slot, the entries of `parts` with a face depending on it.
    parts_of_slot: Vec<Vec<u32>>,
}

#[derive(Debug, Clone)]
struct PartFaces {
    part: usize,
    /// (low, high) face form along each world axis.
    intervals: [(Affine, Affine); 3],
    /// A cone's (or a two-radius cylinder's) smaller cap across its axis: `(axis, low,
    /// high)` faces the box does not show, weighed like the box's faces on that axis.
    cap: Vec<(usize, Affine, Affine)>,
    round: bool,
}

impl PartFaces {
    /// Every face form with the world axis it is normal to: the box's, then the cap's.
    fn forms(&self) -> impl Iterator<Item = (usize, &Affine)> {
        let boxed =
            (0..3).flat_map(move |a| [(a, &self.intervals[a].0), (a, &self.intervals[a].1)]);
        boxed.chain(self.cap.iter().flat_map(|(a, lo, hi)| [(*a, lo), (*a, hi)]))
    }
}

/// Squared face areas of every part at one point: the weights of the projection metric.
#[derive(Debug, Clone)]
pub struct Metric {
    /// Per entry of `Faces::parts`, the squared area of its faces normal to each axis
    /// (0 for parts the variation does without).
    weights: Vec<[f64; 3]>,
    /// Per slot, a weight of its own (`H += w eₛeₛᵀ`): the number metric's (empty for a
    /// metric of faces alone).
    slots: Vec<f64>,
    /// The ridge added to every slot: keeps slots no face depends on where they are.
    ridge: f64,
}

impl Faces {
    pub fn of(model: &Model) -> Faces {
        let parts: Vec<PartFaces> = model
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
                let cap = crate::ir::feature::smaller_cap(p)
                    .iter()
                    .map(|(a, lo, hi)| Some((*a, form(lo)?, form(hi)?)))
                    .collect::<Option<Vec<_>>>()
                    .unwrap_or_default();
                Some(PartFaces {
                    part: i,
                    intervals,
                    cap,
                    round: !matches!(p.primitive, Primitive::Cube { .. }),
                })
            })
            .collect();
        let slots = model.slots.len();
        let mut parts_of_slot = vec![Vec::new(); slots];
        for (k, pf) in parts.iter().enumerate() {
            for (_, f) in pf.forms() {
                for s in f.slots() {
                    let list: &mut Vec<u32> = &mut parts_of_slot[s as usize];
                    if list.last() != Some(&(k as u32)) {
                        list.push(k as u32);
                    }
                }
            }
        }
        Faces {
            parts,
            slots,
            parts_of_slot,
        }
    }

    pub fn slots(&self) -> usize {
        self.slots
    }

    /// The metric's weights at the point `x`, ignoring parts in `skip`.
    pub fn metric(&self, x: &[f64], skip: &[usize]) -> Metric {
        let mut diagonal = vec![0.0f64; self.slots];
        let weights: Vec<[f64; 3]> = self
            .parts
            .iter()
            .map(|pf| {
                if skip.contains(&pf.part) {
                    return [0.0; 3];
                }
                let ext: [f64; 3] = std::array::from_fn(|a| {
                    (pf.intervals[a].1.eval(x) - pf.intervals[a].0.eval(x)).abs()
                });
                let w: [f64; 3] = std::array::from_fn(|a| {
                    let mut area = ext[(a + 1) % 3] * ext[(a + 2) % 3];
                    if pf.round {
                        area *= std::f64::consts::FRAC_PI_4;
                    }
                    area * area
                });
                for (a, f) in pf.forms() {
                    for &(s, c) in &f.terms {
                        diagonal[s as usize] += w[a] * c * c;
                    }
                }
                w
            })
            .collect();
        Metric {
            weights,
            slots: Vec::new(),
            ridge: ridge(&diagonal),
        }
    }

    /// The noise model's metric for a variation whose numbers were typed (`noise`): every
    /// number the variation has is off by noise that moves the face it moves most by `σ`
    /// world units, so a number weighs its leverage squared (the largest coefficient it has
    /// in a face of a part the variation keeps). The metric's distance is then the numbers'
    /// displacement in world units, however many faces a number drives.
    pub fn number_metric(&self, skip: &[usize]) -> Metric {
        let mut leverage = vec![0.0f64; self.slots];
        for pf in self.parts.iter().filter(|pf| !skip.contains(&pf.part)) {
            for (_, f) in pf.forms() {
                for &(s, c) in &f.terms {
                    leverage[s as usize] = leverage[s as usize].max(c.abs());
                }
            }
        }
        let slots: Vec<f64> = leverage.iter().map(|l| l * l).collect();
        Metric {
            weights: vec![[0.0; 3]; self.parts.len()],
            ridge: ridge(&slots),
            slots,
        }
    }

    /// The noise model's metric for a variation fitted to pictures (`noise`), which see
    /// faces: every face of a part the variation keeps weighs 1, so the metric's distance
    /// is the faces' displacement in world units. The variation's `precision` (per entry of
    /// the parts, per axis, in `[0, 1]`) scales that down where its pictures determine the
    /// faces less well (`precision`).
    pub fn face_metric(&self, skip: &[usize], precision: &[[f64; 3]]) -> Metric {
        let weights: Vec<[f64; 3]> = self
            .parts
            .iter()
            .enumerate()
            .map(|(k, pf)| {
                if skip.contains(&pf.part) {
                    [0.0; 3]
                } else {
                    precision[k]
                }
            })
            .collect();
        let mut diagonal = vec![0.0f64; self.slots];
        for pf in &self.parts {
            for (_, f) in pf.forms() {
                for &(s, c) in &f.terms {
                    diagonal[s as usize] += c * c;
                }
            }
        }
        Metric {
            weights,
            slots: Vec::new(),
            ridge: ridge(&diagonal),
        }
    }

    /// Every face form: (entry of the parts, the model's part, the axis it is normal to,
    /// the form).
    pub fn face_forms(&self) -> impl Iterator<Item = (usize, usize, usize, &Affine)> {
        self.parts
            .iter()
            .enumerate()
            .flat_map(|(k, pf)| pf.forms().map(move |(a, f)| (k, pf.part, a, f)))
    }

    /// How many entries the parts have (the length of a precision's list).
    pub fn entries(&self) -> usize {
        self.parts.len()
    }

    /// Every weighted face form of the parts in `entries`: (squared area, form).
    fn weighted_faces<'a>(
        &'a self,
        metric: &'a Metric,
        entries: &'a [u32],
    ) -> impl Iterator<Item = (f64, &'a Affine)> + 'a {
        // A typed variation's number metric weighs no face: its parts are not walked.
        let weighed = move |k: &&u32| metric.weights[**k as usize] != [0.0; 3];
        entries.iter().filter(weighed).flat_map(move |&k| {
            let pf = &self.parts[k as usize];
            let w = metric.weights[k as usize];
            pf.forms()
                .map(move |(a, f)| (w[a], f))
                .filter(|(w2, _)| *w2 != 0.0)
        })
    }
}

/// The metric's ridge for a diagonal of `H`: [`PROJECTION_RIDGE`] of its largest entry (of
/// 1 when every entry is smaller).
fn ridge(diagonal: &[f64]) -> f64 {
    PROJECTION_RIDGE * diagonal.iter().fold(0.0f64, |m, &v| m.max(v)).max(1.0)
}

impl SlotBlocks {
    /// Blocks joined by the faces alone (no rows chosen yet).
    pub fn of(faces: &Faces) -> SlotBlocks {
        let mut b = SlotBlocks::new(faces.slots);
        for pf in &faces.parts {
            for (lo, hi) in &pf.intervals {
                b.join(lo.slots().chain(hi.slots()));
            }
            for (_, lo, hi) in &pf.cap {
                b.join(lo.slots().chain(hi.slots()));
            }
        }
        b
    }
}

/// Projections of one variation: its fixed metric and the blocks factored so far.
pub struct Projector {
    metric: Metric,
    blocks: HashMap<SlotId, Block>,
}

impl Projector {
    pub fn new(metric: Metric) -> Projector {
        Projector {
            metric,
            blocks: HashMap::new(),
        }
    }

    /// Takes a row newly added to the chosen basis, lying inside the block `root`, into that
    /// block's factorisation as a rank-one correction (or forgets the block when it has
    /// gathered enough of them, so it is factored afresh when next needed).
    pub fn absorb(&mut self, root: SlotId, row: &Affine) {
        let Some(block) = self.blocks.get_mut(&root) else {
            return;
        };
        if block.absorbed >= MAX_CORRECTIONS {
            self.blocks.remove(&root);
            return;
        }
        block.absorb(row);
    }

    /// Forgets the factored blocks of these representatives (blocks about to be joined).
    pub fn forget(&mut self, roots: &[SlotId]) {
        for r in roots {
            self.blocks.remove(r);
        }
    }

    /// How `x` (which satisfies `basis`) moves so that `rows` also hold, as sparse
    /// (slot, change) pairs (empty when nothing moves), and the move's squared length in the
    /// metric (`δᵀHδ`, which is `eᵀ (n K nᵀ)⁺ e` for the rows' residuals `e`): what
    /// projecting onto `rows` costs.
    pub fn shift_and_cost(
        &mut self,
        faces: &Faces,
        basis: &RowBasis,
        blocks: &mut SlotBlocks,
        members: &HashMap<SlotId, Vec<SlotId>>,
        x: &[f64],
        rows: &[&Affine],
    ) -> (Vec<(SlotId, f64)>, f64) {
        let projection = self.projection(faces, basis, blocks, members, rows);
        self.shift_and_cost_at(&projection, x, rows)
    }

    /// What projecting onto `rows` needs whatever the point: the columns `K nᵢᵀ` of every
    /// block the rows touch and `(n K nᵀ)⁺`. Variations with one metric share it, so it is
    /// worked out once for all of them ([`Projector::shift_and_cost_at`]).
    pub fn projection(
        &mut self,
        faces: &Faces,
        basis: &RowBasis,
        blocks: &mut SlotBlocks,
        members: &HashMap<SlotId, Vec<SlotId>>,
        rows: &[&Affine],
    ) -> Projection {
        let (costs, parts) = self.row_gram(faces, basis, blocks, members, rows, true);
        Projection { parts, costs }
    }

    /// The costs of projecting onto `rows` without the move ([`Projector::projection`]'s
    /// `(n K nᵀ)⁺` alone): where a block keeps a dense `K`, its share of `n K nᵀ` is read
    /// at the rows' own slots; elsewhere it comes from forward substitutions alone
    /// ([`Block::forward_gram`]), not through whole columns.
    pub fn costs(
        &mut self,
        faces: &Faces,
        basis: &RowBasis,
        blocks: &mut SlotBlocks,
        members: &HashMap<SlotId, Vec<SlotId>>,
        rows: &[&Affine],
    ) -> RowCosts {
        self.row_gram(faces, basis, blocks, members, rows, false).0
    }

    /// `(n K nᵀ)⁺` for `rows`, and (when `columns`) per touched block the columns `K nᵢᵀ`.
    fn row_gram(
        &mut self,
        faces: &Faces,
        basis: &RowBasis,
        blocks: &mut SlotBlocks,
        members: &HashMap<SlotId, Vec<SlotId>>,
        rows: &[&Affine],
        columns: bool,
    ) -> (RowCosts, BlockColumns) {
        let k = rows.len();
        let mut m = DMatrix::<f64>::zeros(k, k);
        let mut parts: BlockColumns = Vec::new();
        let mut touched: Vec<SlotId> = rows
            .iter()
            .flat_map(|r| r.slots())
            .map(|s| blocks.find(s))
            .collect();
        touched.sort_unstable();
        touched.dedup();
        for &root in &touched {
            let block = self.blocks.entry(root).or_insert_with(|| {
                Block::build(faces, &self.metric, basis, members[&root].clone())
            });
            // Only a `K` already made is read (making one is the columns' decision).
            let dense = block
                .dense
                .get()
                .filter(|_| !columns && block.gram.is_some());
            if let Some(dense) = dense {
                let inside: Vec<RowInBlock> = rows.iter().map(|r| block.row_in_block(r)).collect();
                for (i, a) in inside.iter().enumerate() {
                    for (j, b) in inside.iter().enumerate() {
                        m[(i, j)] += block.k_form_of(dense, a, b);
                    }
                }
                continue;
            }
            if !columns && block.forward_gram(rows, &mut m) {
                continue;
            }
            // Per touched block: the columns K nᵢᵀ over its slots.
            let cols: Vec<Vec<f64>> = rows.iter().map(|r| block.k_column(r)).collect();
            let inside: Vec<Vec<(usize, f64)>> =
                rows.iter().map(|r| block.terms_in_block(r)).collect();
            for (i, r) in inside.iter().enumerate() {
                for (j, col) in cols.iter().enumerate() {
                    m[(i, j)] += dot_of(r, col);
                }
            }
            if columns {
                parts.push((root, cols));
            }
        }
        let inverse = if k == 0 {
            DMatrix::zeros(0, 0)
        } else {
            linalg::pinv(&m)
        };
        (RowCosts { inverse }, parts)
    }

    /// [`Projector::shift_and_cost`] of `x` with the `projection` this projector made for
    /// `rows` (and no row chosen since).
    pub fn shift_and_cost_at(
        &self,
        projection: &Projection,
        x: &[f64],
        rows: &[&Affine],
    ) -> (Vec<(SlotId, f64)>, f64) {
        if rows.is_empty() {
            return (Vec::new(), 0.0);
        }
        let e = DVector::from_fn(rows.len(), |i, _| rows[i].eval(x));
        let lambda = &projection.costs.inverse * &e;
        let cost = e.dot(&lambda).max(0.0);
        let mut out = Vec::new();
        for (root, cols) in &projection.parts {
            let block = &self.blocks[root];
            for (i, &s) in block.slots.iter().enumerate() {
                let delta: f64 = cols.iter().zip(lambda.iter()).map(|(c, l)| c[i] * l).sum();
                if delta != 0.0 {
                    out.push((s, -delta));
                }
            }
        }
        (out, cost)
    }
}

/// Per block some rows touch (by representative): the columns `K nᵢᵀ` over its slots.
type BlockColumns = Vec<(SlotId, Vec<Vec<f64>>)>;

/// A projection onto some rows prepared for any point (see [`Projector::projection`]).
pub struct Projection {
    /// Per block the rows touch: the columns `K nᵢᵀ` over its slots.
    parts: BlockColumns,
    costs: RowCosts,
}

/// What projecting onto some rows costs, whatever the point: `(n K nᵀ)⁺`.
pub struct RowCosts {
    inverse: DMatrix<f64>,
}

impl RowCosts {
    /// The cost of projecting away residuals `e` of the rows (one per row, in their order,
    /// wherever they come from): `eᵀ (n K nᵀ)⁺ e`, the cost
    /// [`Projector::shift_and_cost_at`] gives.
    pub fn cost(&self, e: &[f64]) -> f64 {
        if e.is_empty() {
            return 0.0;
        }
        let e = DVector::from_column_slice(e);
        e.dot(&(&self.inverse * &e)).max(0.0)
    }

    /// The cost of projecting `x` onto `rows` (the rows these costs were made for):
    /// [`Projector::shift_and_cost_at`]'s cost without the move.
    pub fn cost_at(&self, x: &[f64], rows: &[&Affine]) -> f64 {
        let e: Vec<f64> = rows.iter().map(|r| r.eval(x)).collect();
        self.cost(&e)
    }
}

/// Projects `x` onto all of `rows` at once, weighting faces at `x`.
pub fn project_onto(faces: &Faces, x: &[f64], rows: &[&Affine], skip: &[usize]) -> Vec<f64> {
    let mut basis = RowBasis::default();
    let mut blocks = SlotBlocks::of(faces);
    for r in rows {
        if basis.add(r) {
            blocks.join(r.slots());
        }
    }
    // A point satisfying every row, equal to `x` on the free slots.
    let mut p = x.to_vec();
    for row in basis.rows() {
        p[row.pivot as usize] = basis.pivot_value(row, x);
    }
    // Then the metric-nearest point to `x` in the null space around it: z = −M⁻¹ Nᵀ H (p − x).
    let metric = faces.metric(x, skip);
    let offset: Vec<f64> = p.iter().zip(x).map(|(a, b)| a - b).collect();
    let members = blocks.members();
    for slots in members.into_values() {
        if slots.iter().all(|&s| offset[s as usize] == 0.0) {
            continue;
        }
        let block = Block::build(faces, &metric, &basis, slots);
        let Some(gram) = &block.gram else {
            continue;
        };
        // H (p − x) restricted to the block, then Nᵀ of it.
        let mut hv: HashMap<SlotId, f64> = HashMap::new();
        let mut entries: Vec<u32> = block
            .slots
            .iter()
            .flat_map(|&s| faces.parts_of_slot[s as usize].iter().copied())
            .collect();
        entries.sort_unstable();
        entries.dedup();
        for (w2, q) in faces.weighted_faces(&metric, &entries) {
            let qv: f64 = q.terms.iter().map(|&(s, a)| a * offset[s as usize]).sum();
            if qv != 0.0 {
                for &(s, a) in &q.terms {
                    *hv.entry(s).or_insert(0.0) += w2 * a * qv;
                }
            }
        }
        for &s in &block.slots {
            *hv.entry(s).or_insert(0.0) += metric.ridge * offset[s as usize];
        }
        let as_row = Affine {
            constant: 0.0,
            terms: hv.into_iter().collect(),
        };
        let z = gram.solve(&block.reduced(&as_row));
        let step = block.expand(&z);
        for (i, &s) in block.slots.iter().enumerate() {
            p[s as usize] -= step[i];
        }
    }
    p
}

#[cfg(test)]
mod tests;
