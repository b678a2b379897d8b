//! Whether a fit can start: the targets match the cameras and something is in view
//! ([`check`]), and what went wrong when not ([`FitError`]).

use super::Parametric;
use super::loss::Target;
use crate::render::Backend;
use crate::render::camera::Camera;
use crate::render::scene::DEFAULT_SHADE;
use crate::render::soft::{ViewPrep, prepare_view};

/// What went wrong before fitting could start.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FitError {
    #[error("the model has no parts in view of any camera")]
    NothingInView,
    #[error("the model has no parts")]
    NoParts,
    #[error("{0} cameras but {1} target images")]
    Mismatch(usize, usize),
    #[error("camera `{camera}` is {cw}×{ch} but its target image is {tw}×{th}")]
    Size {
        camera: String,
        cw: u32,
        ch: u32,
        tw: u32,
        th: u32,
    },
    #[error("the subspace basis has {0} rows but the model has {1} slots")]
    Basis(usize, usize),
}

/// Checks targets against cameras and that something is in view.
pub fn check(
    problem: &Parametric,
    cameras: &[Camera],
    targets: &[Target],
    backend: &mut dyn Backend,
) -> Result<(), FitError> {
    if cameras.len() != targets.len() {
        return Err(FitError::Mismatch(cameras.len(), targets.len()));
    }
    for (c, t) in cameras.iter().zip(targets) {
        if c.width != t.width || c.height != t.height {
            return Err(FitError::Size {
                camera: c.name.clone(),
                cw: c.width,
                ch: c.height,
                tw: t.width,
                th: t.height,
            });
        }
    }
    if problem.base.is_empty() {
        return Err(FitError::NoParts);
    }
    let scene = problem.scene(&problem.x0);
    let views: Vec<ViewPrep> = cameras
        .iter()
        .map(|c| prepare_view(&scene, c, None))
        .collect();
    let shades = vec![DEFAULT_SHADE; views.len()];
    let seen = backend
        .render(&scene, &views, None, &shades)
        .iter()
        .any(|(_, h)| h.mask().any(|m| m));
    if !seen {
        return Err(FitError::NothingInView);
    }
    Ok(())
}
