//! The state a greedy selection over candidates shares between its steps: the chosen rows
//! (a row basis), how they couple slots into blocks, and which candidates to look at again
//! when rows are added or slots move.
//!
//! Used by the paper's greedy (`discover`) and by the noise model's sequential test
//! (`intent`). Invariants: `basis` spans exactly the rows added so far; `members` lists the
//! blocks of `blocks` whenever `joined` is false; a projector given to [`Chosen::add`] stays
//! consistent with the basis (a row inside one block is a rank-one correction of that
//! block's factor, a row joining blocks drops their factors).

use super::candidates::Candidates;
use super::pool::Pool;
use super::project::{Faces, Projection, Projector, RowCosts};
use super::rowbasis::RowBasis;
use super::slotblocks::SlotBlocks;
use crate::ir::{Affine, SlotId};
use std::collections::HashMap;

/// The chosen rows and how they couple slots, shared by every variation.
pub struct Chosen {
    pub basis: RowBasis,
    pub blocks: SlotBlocks,
    pub members: HashMap<SlotId, Vec<SlotId>>,
    /// Whether blocks were joined since `members` was listed.
    pub joined: bool,
}

impl Chosen {
    /// No row chosen: the blocks the faces alone make.
    pub fn new(faces: &Faces) -> Chosen {
        let mut blocks = SlotBlocks::of(faces);
        let members = blocks.members();
        Chosen {
            basis: RowBasis::default(),
            blocks,
            members,
            joined: false,
        }
    }

    /// Adds a candidate's rows, keeping every variation's projector consistent with them.
    pub fn add(&mut self, rows: &[&Affine], projectors: &mut [&mut Projector]) {
        for r in rows {
            let mut roots: Vec<u32> = r.slots().map(|s| self.blocks.find(s)).collect();
            roots.sort_unstable();
            roots.dedup();
            if !self.basis.add_terms(&r.terms) {
                continue;
            }
            if roots.len() == 1 {
                for p in projectors.iter_mut() {
                    p.absorb(roots[0], r);
                }
            } else {
                for p in projectors.iter_mut() {
                    p.forget(&roots);
                }
                self.blocks.join(r.slots());
                self.joined = true;
            }
        }
    }

    /// Lists the blocks again if rows joined some since they were last listed.
    pub fn refresh_members(&mut self) {
        if self.joined {
            self.members = self.blocks.members();
            self.joined = false;
        }
    }

    /// How the point `x` (satisfying the chosen rows) moves so that `rows` hold too, and
    /// what the move costs in the projector's metric.
    pub fn shift(
        &mut self,
        projector: &mut Projector,
        faces: &Faces,
        x: &[f64],
        rows: &[&Affine],
    ) -> (Vec<(SlotId, f64)>, f64) {
        projector.shift_and_cost(faces, &self.basis, &mut self.blocks, &self.members, x, rows)
    }

    /// What projecting any point onto `rows` with `projector` needs (see
    /// [`Projector::projection`]).
    pub fn projection(
        &mut self,
        projector: &mut Projector,
        faces: &Faces,
        rows: &[&Affine],
    ) -> Projection {
        projector.projection(faces, &self.basis, &mut self.blocks, &self.members, rows)
    }

    /// What projecting any point onto `rows` with `projector` costs, without the move (see
    /// [`Projector::costs`]).
    pub fn costs(
        &mut self,
        projector: &mut Projector,
        faces: &Faces,
        rows: &[&Affine],
    ) -> RowCosts {
        projector.costs(faces, &self.basis, &mut self.blocks, &self.members, rows)
    }

    /// Whether the chosen rows imply every one of `rows`.
    pub fn implies(&self, rows: &[&Affine]) -> bool {
        rows.iter().all(|r| self.basis.contains_terms(&r.terms))
    }

    /// Takes out of the pool the candidates the chosen rows now imply, into `gone` (in
    /// candidate order). Only candidates holding a pivot whose row changed can have become
    /// implied; each is tested once, however many of those pivots it holds.
    pub fn drop_implied(
        &mut self,
        candidates: &Candidates,
        by_slot: &[Vec<u32>],
        pool: &mut Pool,
        gone: &mut Vec<usize>,
    ) {
        let mut touched: Vec<usize> = self
            .basis
            .take_touched()
            .into_iter()
            .flat_map(|s| by_slot[s as usize].iter().map(|&k| k as usize))
            .filter(|&k| pool.is_alive(k))
            .collect();
        touched.sort_unstable();
        touched.dedup();
        for k in touched {
            if self.implies(&rows_of(candidates, k)) {
                pool.kill(k);
                gone.push(k);
            }
        }
    }
}

/// All rows of a candidate.
pub fn rows_of(c: &Candidates, i: usize) -> Vec<&Affine> {
    c.list[i].rows.iter().collect()
}

/// Which candidates hold each slot: what to look at again when slots move or the basis
/// changes around them.
pub fn candidates_by_slot(candidates: &Candidates, slots: usize) -> Vec<Vec<u32>> {
    let mut by_slot: Vec<Vec<u32>> = vec![Vec::new(); slots];
    for (i, c) in candidates.list.iter().enumerate() {
        let mut mine: Vec<u32> = c.rows.iter().flat_map(|r| r.slots()).collect();
        mine.sort_unstable();
        mine.dedup();
        for s in mine {
            by_slot[s as usize].push(i as u32);
        }
    }
    by_slot
}

/// Forgets the cached scores of every candidate holding one of `slots`.
pub fn forget<T>(
    cache: &mut [Option<T>],
    by_slot: &[Vec<u32>],
    slots: impl IntoIterator<Item = u32>,
) {
    for s in slots {
        for &k in &by_slot[s as usize] {
            cache[k as usize] = None;
        }
    }
}
