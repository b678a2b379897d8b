//! `reparamc`: re-parameterize OpenSCAD models.
//!
//! The pipeline, stage by stage (`ARCHITECTURE.md` is the map): `front` parses and
//! evaluates a model into the `ir` (slots, parts, affine features); `analysis` finds the
//! geometric relations that hold on it; `back` presents and writes the results; `render`
//! and `fit` turn pictures into variations. Every stage is usable as a library; `main.rs` is
//! only the command line. The crate root only declares modules and re-exports the loaders.

// The lint policy (as naga has it): library code never unwraps, expects or panics; an
// invariant that cannot fail is written so a reader sees why, or returns an error. Tests
// may.
#![cfg_attr(
    not(test),
    deny(
        clippy::unwrap_used,
        clippy::expect_used,
        clippy::panic,
        clippy::todo,
        clippy::dbg_macro
    )
)]

/// Evaluation and analysis allocate many small vectors (affine forms, features); mimalloc
/// handles them much faster than the system allocator.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

pub mod analysis;
pub mod back;
pub mod command;
pub mod explore;
pub mod families;
pub mod fit;
pub mod front;
pub mod geom;
pub mod ir;
pub mod output;
pub mod render;
pub mod span;
pub mod tolerance;
pub mod variation;

pub use front::{load_model, load_model_parsed, load_model_text, with_large_stack};
