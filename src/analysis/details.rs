//! Details: the literals an author left beside the variables they named.
//!
//! An author who names some numbers (`desk_width = 120;`, `deck = [60, 100, 4];`,
//! `module drawer(w, h, knob_r = 1.5)`; see `Slot::authored`) and types others in place (a
//! foot's 1-unit post, a hole's radius) has said which numbers are the design's.
//! Without variations to say otherwise, the author's variables are the sliders, and of the
//! literals the structural prior leaves free only the [`LITERAL_SLIDERS`] that move the most
//! material join them; the other literals stay as typed (pinned at the input, like the
//! gauge's slots). A model that names none of its numbers keeps every free literal: there
//! the literals are the whole design.
//!
//! "Material moved" is the model's own similarity (`similarity`: exact volumes, holes
//! included): each free literal in turn moves as far as its slider would reach (`ranges`:
//! a place by a tenth of the model's size, a size by half its value), and one minus the IoU
//! with the input is its weight: what dragging that slider end to end would change. Ties
//! go to the earlier slot, so the choice is deterministic.

use super::anchors::Anchors;
use super::discover::Similarity;
use super::ranges::reach;
use super::reparam::solve;
use super::similarity::VolumeSimilarity;
use crate::ir::{Affine, Model};

/// How many free literals may join the author's variables as sliders.
pub const LITERAL_SLIDERS: usize = 3;

/// `rows` plus a pin (`slot − value = 0`) for every free literal past the
/// [`LITERAL_SLIDERS`] that move the most material, when the author names some of the
/// numbers; `rows` unchanged otherwise.
pub fn pin_details(model: &Model, anchors: &Anchors, rows: Vec<Affine>) -> Vec<Affine> {
    if model.slots.iter().all(|s| !s.authored) {
        return rows;
    }
    let sol = solve(model, anchors, &rows);
    let literals: Vec<usize> = (0..sol.free.len())
        .filter(|&i| !model.slots[sol.free[i] as usize].authored)
        .collect();
    if literals.len() <= LITERAL_SLIDERS {
        return rows;
    }
    let input = model.slot_values();
    if model.parts_at(&input).is_none() {
        return rows;
    }
    let sim = VolumeSimilarity::new(model);
    let reference = sim.reference(&input, &[]);
    let free_input: Vec<f64> = sol.free.iter().map(|&f| input[f as usize]).collect();
    let moved = |i: usize| {
        let slot = &model.slots[sol.free[i] as usize];
        let mut free = free_input.clone();
        free[i] += reach(slot.position, slot.value, model.size());
        let after = sol.slot_values(&free);
        let changed: Vec<u32> = (0..after.len() as u32)
            .filter(|&s| after[s as usize] != input[s as usize])
            .collect();
        1.0 - sim.similarity_changed(&after, &changed, &reference)
    };
    let mut ranked: Vec<(f64, usize)> = literals.iter().map(|&i| (moved(i), i)).collect();
    ranked.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
    let mut out = rows;
    for &(_, i) in &ranked[LITERAL_SLIDERS..] {
        let slot = sol.free[i];
        out.push(Affine::slot(slot).sub(&Affine::constant(input[slot as usize])));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::front::test_model as model;

    #[test]
    fn the_literals_that_move_most_join_the_authors_variables() {
        // Two named sizes; five literals: a big shade's three numbers, a small knob's two.
        let m = model(
            "w = 40; h = 5;\ncube([w, w, h]);\n\
             translate([0, 0, 5]) cylinder(h = 30, r1 = 20, r2 = 8);\n\
             translate([50, 0, 0]) cube([1.5, 1.5, 1]);\n",
        );
        let anchors = Anchors::of(&m);
        let rows = pin_details(&m, &anchors, Vec::new());
        let sol = solve(&m, &anchors, &rows);
        let free: Vec<&str> = sol
            .free
            .iter()
            .map(|&f| m.slots[f as usize].name.as_str())
            .collect();
        let literals = sol
            .free
            .iter()
            .filter(|&&f| !m.slots[f as usize].authored)
            .count();
        assert!(literals <= LITERAL_SLIDERS, "{free:?}");
        assert!(free.iter().any(|n| n.contains("radius")), "{free:?}");
        // With no named variable, nothing is pinned.
        let plain = model("cube([40, 40, 5]);\ntranslate([50, 0, 0]) cube([1.5, 1.5, 1]);\n");
        let rows = pin_details(&plain, &Anchors::of(&plain), Vec::new());
        assert!(rows.is_empty());
    }
}
