//! The paper's plain published method, composed from the analysis directly: candidates
//! that hold on the input, the greedy search with every candidate in one tier (IoU product
//! against the previous step), the paper's change point on the distortion curve's
//! derivative, the Gauss–Jordan solve with anchors. No noise gate, no tiers, no held-back
//! slots of dropped parts: the row the benchmark compares the main job against.

use crate::analysis::anchors::{Anchors, project_variations};
use crate::analysis::cutoff::change_points;
use crate::analysis::discover::{Sample, discover};
use crate::analysis::find_candidates;
use crate::analysis::optional::{optional_parts, toggles};
use crate::analysis::project::Faces;
use crate::analysis::ranges::ranges;
use crate::analysis::reparam::solve;
use crate::analysis::similarity::VolumeSimilarity;
use crate::ir::{Affine, Model};

use super::score::Output;

/// The paper's method on `model` with training variations `raw` (slot values).
pub fn paper_method(model: &Model, raw: &[Vec<f64>]) -> Output {
    let start = std::time::Instant::now();
    let candidates = find_candidates(model);
    let sim = VolumeSimilarity::new(model);
    // The paper's own test: a part is optional when removing it changes nothing.
    let optional = optional_parts(model, raw, &sim);
    let samples: Vec<Sample> = raw
        .iter()
        .zip(&optional)
        .map(|(v, o)| Sample::new(v.clone(), o.clone()))
        .collect();
    let faces = Faces::of(model);
    let tiers = vec![0u8; candidates.list.len()];
    let disc = discover(
        &faces,
        &candidates,
        &samples,
        model.slots.len(),
        &sim,
        &tiers,
    );
    let (paper, _) = change_points(&disc.curve);
    let kept: Vec<Affine> = disc.order[..paper.min(disc.order.len())]
        .iter()
        .flat_map(|&i| candidates.list[i].rows.iter().cloned())
        .collect();
    let anchors = Anchors::of(model);
    let solution = solve(model, &anchors, &kept);
    let projected = project_variations(&anchors, &faces, &kept, raw, &optional);
    let free_at = |x: &[f64]| solution.free_values(x);
    let input = free_at(&model.slot_values());
    let variation_free: Vec<Vec<f64>> = projected.iter().map(|p| free_at(p)).collect();
    // Sizes kept positive, no contacts (the paper has no ranges of its own).
    let slider_ranges = ranges(model, &solution, &input, &variation_free, &[], 0.0);
    Output {
        kept,
        solution,
        ranges: slider_ranges,
        toggles: toggles(model.parts.len(), &optional)
            .into_iter()
            .map(|t| t.parts)
            .collect(),
        presets: variation_free.into_iter().map(Some).collect(),
        projected,
        seconds: start.elapsed().as_secs_f64(),
        sigma: None,
    }
}
