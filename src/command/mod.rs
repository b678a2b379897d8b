//! The library's entry points: one per command of the `reparamc` binary.
//!
//! Each takes an options struct (plain data, no flags) and the [`SourceMap`] that will
//! hold every file it reads, and returns its results (texts, pictures, reports as data) or
//! the diagnostics that stopped it. Nothing here parses flags, prints or writes files: the
//! CLI is flags in, diagnostics out, and writes the results with [`crate::output`]. A
//! program that wants what a command does calls the same function.
//!
//! [`SourceMap`]: crate::front::source::SourceMap

pub mod compile;
pub mod fit;
pub mod inspect;
pub mod render;
