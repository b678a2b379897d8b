//! The front end: OpenSCAD text in, evaluated geometry out.
//!
//! `source` owns files and spans, `diag` the diagnostics, `parse` turns text into the
//! `ast` with the pest grammar in `grammar/openscad.pest`, `load` reads a model and its
//! includes, `naming` finds the names comments and variables give, and `eval` runs the
//! program into an IR [`Model`](crate::ir::Model) whose features are affine forms.

pub mod ast;
pub mod diag;
pub mod eval;
pub mod load;
pub mod naming;
pub mod parse;
pub mod source;
pub mod walk;
