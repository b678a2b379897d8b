//! The candidates still in play during discovery, by tier, in list order.
//!
//! Invariants: a candidate is *alive* until it is chosen or implied, and never comes back;
//! `count[t]` is the number of alive candidates of tier `t`; `exact` holds exactly the alive
//! candidates marked as satisfied by every variation, keyed by (tier, index) so each tier's
//! come out in list order. Dead entries leave the per-tier lists lazily (a list is compacted
//! when most of it is dead), so removing a candidate costs O(log n), not a pass over all.

use std::collections::BTreeSet;

pub struct Pool {
    alive: Vec<bool>,
    tier: Vec<u8>,
    by_tier: Vec<Vec<usize>>,
    dead_in: Vec<usize>,
    count: Vec<usize>,
    exact: BTreeSet<(u8, usize)>,
}

impl Pool {
    /// The candidates `c` with `keep(c)`, each of tier `tiers[c]`.
    pub fn new(tiers: &[u8], keep: impl Fn(usize) -> bool) -> Pool {
        let levels = tiers.iter().map(|&t| t as usize + 1).max().unwrap_or(0);
        let mut pool = Pool {
            alive: vec![false; tiers.len()],
            tier: tiers.to_vec(),
            by_tier: vec![Vec::new(); levels],
            dead_in: vec![0; levels],
            count: vec![0; levels],
            exact: BTreeSet::new(),
        };
        for c in (0..tiers.len()).filter(|&c| keep(c)) {
            pool.alive[c] = true;
            pool.by_tier[tiers[c] as usize].push(c);
            pool.count[tiers[c] as usize] += 1;
        }
        pool
    }

    pub fn is_alive(&self, c: usize) -> bool {
        self.alive[c]
    }

    /// How many candidates are still in play.
    pub fn alive_count(&self) -> usize {
        self.count.iter().sum()
    }

    pub fn is_empty(&self) -> bool {
        self.count.iter().all(|&n| n == 0)
    }

    /// The lowest tier with an alive candidate.
    pub fn lowest_tier(&self) -> Option<u8> {
        self.count.iter().position(|&n| n > 0).map(|t| t as u8)
    }

    /// Takes `c` out of play (chosen or implied).
    pub fn kill(&mut self, c: usize) {
        if !self.alive[c] {
            return;
        }
        let t = self.tier[c];
        self.alive[c] = false;
        self.count[t as usize] -= 1;
        self.dead_in[t as usize] += 1;
        self.exact.remove(&(t, c));
    }

    /// Marks whether every variation satisfies the alive candidate `c`.
    pub fn set_exact(&mut self, c: usize, exact: bool) {
        if !self.alive[c] {
            return;
        }
        if exact {
            self.exact.insert((self.tier[c], c));
        } else {
            self.exact.remove(&(self.tier[c], c));
        }
    }

    /// The alive candidates of `tier` every variation satisfies, in list order.
    pub fn exact_in(&self, tier: u8) -> Vec<usize> {
        self.exact
            .range((tier, 0)..=(tier, usize::MAX))
            .map(|&(_, c)| c)
            .collect()
    }

    /// The alive candidates of `tier`, in list order.
    pub fn members(&mut self, tier: u8) -> impl Iterator<Item = usize> + '_ {
        let t = tier as usize;
        if self.dead_in[t] * 2 > self.by_tier[t].len() {
            let alive = &self.alive;
            self.by_tier[t].retain(|&c| alive[c]);
            self.dead_in[t] = 0;
        }
        let alive = &self.alive;
        self.by_tier[t].iter().copied().filter(move |&c| alive[c])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tiers_empty_in_order_and_exact_candidates_leave_with_their_owners() {
        let tiers = [1, 0, 2, 0, 1];
        let mut p = Pool::new(&tiers, |c| c != 4);
        assert_eq!(p.alive_count(), 4);
        assert_eq!(p.lowest_tier(), Some(0));
        p.set_exact(3, true);
        p.set_exact(0, true);
        assert_eq!(p.exact_in(0), vec![3]);
        p.kill(1);
        p.kill(3);
        p.kill(3);
        assert_eq!(p.alive_count(), 2, "a candidate leaves play once");
        assert!(p.exact_in(0).is_empty());
        assert_eq!(p.lowest_tier(), Some(1));
        assert_eq!(p.members(1).collect::<Vec<_>>(), vec![0]);
        p.kill(0);
        assert_eq!(p.lowest_tier(), Some(2));
        p.kill(2);
        assert!(p.is_empty());
        assert_eq!(p.alive_count(), 0);
        assert_eq!(p.lowest_tier(), None);
    }
}
