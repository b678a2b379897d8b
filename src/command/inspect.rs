//! The `inspect` command's entry point: what the compiler sees in a model.
//!
//! Loads and evaluates the model, finds the relations that hold on it and returns them as
//! one [`Inspection`] (tables or JSON are its methods), with the warnings loading gave.
//! Prints nothing.

use crate::analysis::find_candidates;
pub use crate::back::inspect::Inspection;
use crate::back::inspect::inspect as present;
use crate::front::diag::{DResult, Diagnostic};
use crate::front::load_model_calling;
use crate::front::source::SourceMap;
use std::path::PathBuf;

/// What the `inspect` command is asked.
#[derive(Debug, Clone, Default)]
pub struct InspectOptions {
    /// The OpenSCAD model to read.
    pub model: PathBuf,
    /// A module call to draw at the end of the model (`--call`).
    pub call: Option<String>,
}

/// What it finds.
#[derive(Debug)]
pub struct InspectOutput {
    pub inspection: Inspection,
    pub warnings: Vec<Diagnostic>,
}

/// The `inspect` command: the model's parameters, parts, frozen numbers and relations.
pub fn inspect(options: &InspectOptions, sources: &mut SourceMap) -> DResult<InspectOutput> {
    let evaluated = load_model_calling(sources, &options.model, options.call.as_deref())?;
    let candidates = find_candidates(&evaluated.model);
    Ok(InspectOutput {
        inspection: present(sources, &evaluated.model, &candidates),
        warnings: evaluated.warnings,
    })
}
