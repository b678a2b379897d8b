//! The analysis: which geometric relations hold on a model.
//!
//! `candidates` finds every relation of the paper's four kinds that holds on the input, with
//! tangency, (`placement`) mirror symmetry and equal spacing, and (`inset`) equal insets;
//! `optional` the parts a variation does without; `noise` states the variations' noise
//! model, `classes` learns how often each class of relation is intent, and `intent` tests
//! every relation against both, which chooses the relations the
//! variations keep (`prior` without variations); `discover` is the paper's own greedy by
//! IoU and `cutoff` its change points on the distortion curve; `reparam` solves
//! them for a few free variables, `anchors` pins the model in place, `gauge` holds slot
//! changes that change no part, and `project` reads the
//! variations on the kept relations; `details` keeps the literals an author left beside named variables as typed (without
//! variations); `names` and `ranges` make the sliders, keeping the `contacts` the variations keep
//! (`contact_vars` makes a contact a slider of its own where a box of ranges cannot keep it,
//! `size_basis` exchanges free slots so the box can hold the presets with every size positive). `similarity` is
//! the model's IoU between two settings (exact volumes, from `geom`); `linalg`, `rowbasis`,
//! `slotblocks`, `chosen` and `pool` are the shared machinery. Floats are compared only against
//! `crate::tolerance`.

pub mod anchors;
pub mod candidates;
pub mod chosen;
pub mod classes;
pub mod contact_vars;
pub mod contacts;
pub mod cutoff;
pub mod details;
pub mod discover;
pub mod gauge;
pub mod inset;
pub mod intent;
pub mod linalg;
pub mod names;
pub mod noise;
pub mod optional;
pub mod placement;
pub mod pool;
pub mod precision;
pub mod prior;
pub mod project;
pub mod proportion;
pub mod ranges;
pub mod reparam;
pub mod rowbasis;
pub mod similarity;
pub mod size_basis;
pub mod slotblocks;

pub use candidates::{Candidate, Candidates, RelationKind, find_candidates, find_candidates_for};
