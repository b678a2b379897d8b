//! The back end: what the compiler writes for people and tools.
//!
//! `plan` decides what the re-parameterized file says (names, descriptions, the summary,
//! each literal's expression), `emit` writes it, `expr` prints expressions and `rewrite`
//! splices text (a model with other slot values, literals replaced by expressions).
//! `presets` writes the parameter sets, `report` the main job's report, `diff` the change
//! as a unified diff, `plot` the distortion curve, `gallery` the presets side by side
//! (`font` is the typeface both are lettered in), `page` the report as one HTML page, and
//! `inspect` presents a model's parameters, parts and relations. Nothing here decides an
//! analysis result.

pub mod diff;
pub mod emit;
pub mod expr;
pub mod font;
pub mod gallery;
pub mod inspect;
pub mod page;
pub mod plan;
pub mod plot;
pub mod presets;
pub mod report;
pub mod rewrite;
