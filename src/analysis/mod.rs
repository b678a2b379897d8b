//! The analysis: which geometric relations hold on a model.
//!
//! `candidates` finds every relation of the paper's four kinds that holds on the input;
//! `optional` the parts a variation does without; `noise`, `tiers`, `discover` and `cutoff`
//! choose the relations the variations keep (`prior` without variations); `reparam` solves
//! them for a few free variables, `anchors` pins the model in place and `project` reads the
//! variations on the kept relations; `names` and `ranges` make the sliders. `similarity` is
//! the model's IoU between two settings (exact volumes, from `geom`); `linalg`, `rowbasis`,
//! `slotblocks` and `pool` are the shared machinery. Floats are compared only against
//! `crate::tolerance`.

pub mod anchors;
pub mod candidates;
pub mod cutoff;
pub mod discover;
pub mod linalg;
pub mod names;
pub mod noise;
pub mod optional;
pub mod pool;
pub mod prior;
pub mod project;
pub mod ranges;
pub mod reparam;
pub mod rowbasis;
pub mod similarity;
pub mod slotblocks;
pub mod tiers;

pub use candidates::{Candidate, Candidates, RelationKind, find_candidates, find_candidates_for};
