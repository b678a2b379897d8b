//! The analysis: which geometric relations hold on a model.
//!
//! `candidates` finds every relation of the paper's four kinds that holds on the input;
//! `linalg` answers rank questions over constraint rows; `tolerance` is the single place
//! floats are compared.

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
pub mod slotblocks;
pub mod tiers;

pub use candidates::{Candidate, Candidates, RelationKind, find_candidates, find_candidates_for};
