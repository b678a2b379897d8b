//! What the main job draws besides the model: the distortion plot, the presets gallery and
//! the report page, and the [`Progress`] hook that tells a caller each stage as it starts
//! and each of discovery's steps.
//!
//! The pictures are made here, after the job, from what it decided ([`Compiled`]); the
//! drawing itself is `back`'s (`plot`, `gallery`, `page`). Nothing here prints.

use super::compile::{CompileOptions, Compiled};
use crate::back::gallery::{Gallery, gallery, tiles};
use crate::back::page::{PageInputs, report_page};
use crate::back::plot::{PlotFormat, distortion_plot};
use crate::front::diag::{DResult, Diagnostic};
use crate::ir::Model;
use std::sync::Arc;

/// Told each stage of the main job as it starts (its number from 1, how many there are, and
/// what it does), and, while discovery runs, how many candidate relations it has decided
/// of how many there are.
#[derive(Clone, Default)]
pub struct Progress {
    pub stage: Option<Arc<StageHook>>,
    pub step: Option<Arc<StepHook>>,
}

/// What [`Progress`] calls as a stage starts: (stage, stages, what it does).
pub type StageHook = dyn Fn(usize, usize, &str) + Send + Sync;

/// What [`Progress`] calls after each of discovery's steps: (relations decided, relations).
pub type StepHook = dyn Fn(usize, usize) + Send + Sync;

impl Progress {
    pub(super) fn tell(&self, stage: usize, stages: usize, what: &str) {
        if let Some(f) = &self.stage {
            f(stage, stages, what);
        }
    }

    pub(super) fn step(&self, done: usize, total: usize) {
        if let Some(f) = &self.step {
            f(done, total);
        }
    }
}

impl std::fmt::Debug for Progress {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Progress")
            .field("stage", &self.stage.is_some())
            .field("step", &self.step.is_some())
            .finish()
    }
}

/// The pictures and the page the options ask for.
pub(super) struct Pictures {
    pub plot: Option<Vec<u8>>,
    pub gallery: Option<Gallery>,
    pub page: Option<String>,
}

pub(super) fn pictures(
    options: &CompileOptions,
    model: &Model,
    compiled: &Compiled,
    tell: &mut dyn FnMut(&str),
) -> DResult<Pictures> {
    let fail = |e: String| {
        Box::new(Diagnostic::error(
            "E0801",
            format!("cannot draw the pictures: {e}"),
        ))
    };
    let report = &compiled.report;
    let plot = match options.plot {
        Some(format) => {
            tell("drawing the distortion plot");
            Some(distortion_plot(report, format).map_err(fail)?)
        }
        None => None,
    };
    let gallery = match options.gallery || options.page {
        true => {
            if options.gallery {
                tell("drawing the presets gallery");
            }
            Some(gallery(model, &tiles(&compiled.solution, &compiled.plan)).map_err(fail)?)
        }
        false => None,
    };
    let page = match options.page {
        true => {
            tell("writing the report page");
            let svg = distortion_plot(report, PlotFormat::Svg).map_err(fail)?;
            let svg = String::from_utf8_lossy(&svg);
            let page = report_page(&PageInputs {
                report,
                model,
                solution: &compiled.solution,
                plan: &compiled.plan,
                plot_svg: (!report.distortion_curve.is_empty()).then_some(&svg),
                gallery_png: gallery.as_ref().map(|g| g.png.as_slice()),
            });
            Some(page.map_err(fail)?)
        }
        false => None,
    };
    Ok(Pictures {
        plot,
        gallery: gallery.filter(|_| options.gallery),
        page,
    })
}
