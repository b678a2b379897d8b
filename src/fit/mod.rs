//! Fitting a model's numbers to pictures: the paper's image loss minimised over slots (or
//! inside a constraint subspace) with gradients from soft silhouettes.
//!
//! A fit opens with a search over the model's stretch along each axis ([`proportions`]),
//! then runs its stages ([`stages`]) in *rounds* of `iterations` optimiser steps (the
//! paper: SGD, learning rate 0.05, 30 iterations). At the start of each round the shading
//! of every view and the albedo of every item are matched to the targets ([`albedo`]: least
//! squares on the pixels both show as surface) and the silhouettes' softness `σ` steps down
//! geometrically from `sigma.0` to `sigma.1` pixels, so early rounds see far and later
//! rounds see sharp. With Adam, each stage also runs damped from the same start and the
//! run with the lower loss goes on ([`FitOptions::damped_rerun`]). Optional finishing
//! passes, from the best point stood on so far (by the judge's loss), move whole parts
//! ([`part_moves`]: a jump onto a sibling judged in the lighting refitted where it lands)
//! and single faces ([`polish`]) and then single numbers and faces by a pixel or
//! less on hard edges or area coverage ([`polish::refine`]); pictures may be seen inside a
//! border of background ([`frame`]). With [`FitOptions::coverage`] the last round, the
//! refining moves and the judge compare exact area coverage per pixel; pictures are read
//! as coverage ([`coverage`]). The fit returns the best point it stood on by the loss it
//! ends with ([`best`]). [`Fitter::information`] then says how well the pictures determine
//! each number there ([`uncertainty`]: the loss's curvature).
//!
//! The module map: [`options`] holds the settings and the algorithm's constants;
//! [`parametric`] the model prepared for fitting (scenes and gradients at any slot values);
//! [`fitter`] the fit itself ([`fit`], a [`Fitter`]); [`check`] whether a fit can start;
//! [`revive`] the parts a stage lost, offered back; [`best`] the point it returns;
//! [`loss`] the image loss; [`coverage`] pictures read as coverage; [`optimize`]
//! the update rules and the spaces they move in; `descent` a stage's run as it goes (its
//! steps' trust region in pixels); [`stages`], [`proportions`], [`albedo`],
//! [`polish`], [`part_moves`], [`frame`] the pieces named above; [`prior`] the regulariser (the paper's
//! pull towards the model's numbers, a size prior, a tie prior); [`targets`] reads target folders; [`uncertainty`] the
//! numbers' Fisher information at the fit's point; [`memo`] keeps the lighting and the
//! judge's loss at recent points, so asking again at one does not render again.
//!
//! Layering: `fit` drives the renderer (`render`) and reads the analysis' relations; the
//! renderer knows nothing of it.

pub mod albedo;
pub mod best;
pub mod check;
pub mod coverage;
mod descent;
pub mod fitter;
pub mod frame;
pub mod loss;
pub mod memo;
pub mod optimize;
pub mod options;
pub mod parametric;
pub mod part_moves;
pub mod polish;
pub mod prior;
pub mod proportions;
pub mod revive;
pub mod stages;
pub mod targets;
pub mod uncertainty;

pub use check::{FitError, check};
pub use fitter::{FitResult, Fitter, Progress, Step, fit, fit_measured};
pub use options::{DAMPED_FLOOR, FitOptions, HARD_SIGMA, SIZE_PRIOR, SoftEdges, TIE_PRIOR};
pub use parametric::Parametric;
pub use polish::polish;
pub use stages::{
    Stage, basis_of, constraint_basis, scale_basis, staged, staged_with, structure_basis,
};

/// Among `candidates` that `ok` accepts, the one with the lowest loss below `best` (the
/// first in order among equals) and its loss; `None` when none improves.
pub(crate) fn best_improvement(
    candidates: impl IntoIterator<Item = Vec<f64>>,
    best: f64,
    loss: &mut dyn FnMut(&[f64]) -> f64,
    ok: &dyn Fn(&[f64]) -> bool,
) -> Option<(f64, Vec<f64>)> {
    let mut chosen: Option<(f64, Vec<f64>)> = None;
    for cand in candidates {
        if !ok(&cand) {
            continue;
        }
        let l = loss(&cand);
        if l < best && chosen.as_ref().is_none_or(|(b, _)| l < *b) {
            chosen = Some((l, cand));
        }
    }
    chosen
}
