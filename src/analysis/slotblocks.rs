//! Slots grouped by what couples them (a union-find over slot ids): projections solve block
//! by block, and so does the least-norm solve of the anchor shift.
//!
//! Invariant: a block's representative is its smallest slot id, so blocks do not depend on
//! the order slots were joined in.

use crate::ir::SlotId;
use std::collections::HashMap;

/// Slots grouped by what couples them in a projection (a union-find over slots): a face form
/// joins its slots, and so does every chosen row.
#[derive(Debug, Clone)]
pub struct SlotBlocks {
    parent: Vec<u32>,
}

impl SlotBlocks {
    /// Every slot in a block of its own.
    pub fn new(slots: usize) -> SlotBlocks {
        SlotBlocks {
            parent: (0..slots as u32).collect(),
        }
    }

    /// The block of `slot` (its representative slot).
    pub fn find(&mut self, slot: SlotId) -> SlotId {
        let mut r = slot;
        while self.parent[r as usize] != r {
            r = self.parent[r as usize];
        }
        let mut s = slot;
        while self.parent[s as usize] != r {
            let next = self.parent[s as usize];
            self.parent[s as usize] = r;
            s = next;
        }
        r
    }

    /// Puts all `slots` in one block.
    pub fn join(&mut self, slots: impl IntoIterator<Item = SlotId>) {
        let mut first: Option<SlotId> = None;
        for s in slots {
            let r = self.find(s);
            match first {
                None => first = Some(r),
                Some(f) if f != r => {
                    // Smaller id as representative keeps the result independent of order.
                    let (keep, gone) = if f < r { (f, r) } else { (r, f) };
                    self.parent[gone as usize] = keep;
                    first = Some(keep);
                }
                Some(_) => {}
            }
        }
    }

    /// The slots of every block, by representative.
    pub fn members(&mut self) -> HashMap<SlotId, Vec<SlotId>> {
        let mut m: HashMap<SlotId, Vec<SlotId>> = HashMap::new();
        for s in 0..self.parent.len() as SlotId {
            let r = self.find(s);
            m.entry(r).or_default().push(s);
        }
        m
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blocks_join_transitively_with_the_smallest_representative() {
        let mut b = SlotBlocks::new(6);
        b.join([4, 2]);
        b.join([5, 4]);
        b.join([1, 0]);
        assert_eq!(b.find(5), 2);
        assert_eq!(b.find(2), 2);
        assert_eq!(b.find(1), 0);
        assert_eq!(b.find(3), 3);
        assert_eq!(b.members().len(), 3);
    }
}
