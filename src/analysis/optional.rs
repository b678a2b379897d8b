//! Optional parts: parts a variation can do without.
//!
//! A part is optional in a variation when removing it leaves the variation's shape unchanged
//! within a threshold (it is hidden inside others, or shrunk to nothing). The threshold is
//! relative to the part's own volume in the input, not the model's: in a model of a
//! thousand parts every small part changes the whole by less than a thousandth. Parts optional in
//! exactly the same set of variations form one toggle (a Customizer checkbox, on by default).

use super::discover::Similarity;
use crate::ir::Model;

/// Volume changed by removing a part, as a fraction of its own volume in the input, below
/// which it is optional.
pub const OPTIONAL_THRESHOLD: f64 = crate::tolerance::OPTIONAL_PART_LOSS;

/// A group of parts switched together, and the variations that do without them.
#[derive(Debug, Clone, PartialEq)]
pub struct Toggle {
    pub parts: Vec<usize>,
    pub off_in: Vec<usize>,
}

/// For each variation, the parts it does without.
pub fn optional_parts<S: Similarity>(
    parts: usize,
    variations: &[Vec<f64>],
    sim: &S,
) -> Vec<Vec<usize>> {
    variations
        .iter()
        .map(|v| {
            let whole = sim.reference(v, &[]);
            (0..parts)
                .filter(|&p| sim.removal_loss(&whole, p) < OPTIONAL_THRESHOLD)
                .collect()
        })
        .collect()
}

/// The variations' slot values with every slot that shapes only parts a variation does
/// without set back to the input's: such a part keeps the model's own shape there, so
/// presets and blends never shrink it to nothing (its switch hides it instead).
pub fn held_where_skipped(
    model: &Model,
    variations: &[Vec<f64>],
    optional: &[Vec<usize>],
) -> Vec<Vec<f64>> {
    let x0 = model.slot_values();
    let owners = model.parts_by_slot();
    variations
        .iter()
        .zip(optional)
        .map(|(v, skip)| {
            v.iter()
                .enumerate()
                .map(|(s, &val)| {
                    let only_skipped =
                        !owners[s].is_empty() && owners[s].iter().all(|p| skip.contains(p));
                    if only_skipped { x0[s] } else { val }
                })
                .collect()
        })
        .collect()
}

/// Groups parts by the exact set of variations they are optional in.
pub fn toggles(parts: usize, optional: &[Vec<usize>]) -> Vec<Toggle> {
    let mut groups: Vec<Toggle> = Vec::new();
    for p in 0..parts {
        let off_in: Vec<usize> = (0..optional.len())
            .filter(|&j| optional[j].contains(&p))
            .collect();
        if off_in.is_empty() {
            continue;
        }
        match groups.iter_mut().find(|g| g.off_in == off_in) {
            Some(g) => g.parts.push(p),
            None => groups.push(Toggle {
                parts: vec![p],
                off_in,
            }),
        }
    }
    groups
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parts_optional_in_the_same_variations_share_a_toggle() {
        let optional = vec![vec![1, 2], vec![2], vec![1, 2]];
        let t = toggles(4, &optional);
        assert_eq!(
            t,
            vec![
                Toggle {
                    parts: vec![1],
                    off_in: vec![0, 2]
                },
                Toggle {
                    parts: vec![2],
                    off_in: vec![0, 1, 2]
                },
            ]
        );
    }
}
