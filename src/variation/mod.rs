//! Where variations come from.
//!
//! `files`: variant `.scad` files matched to the model slot by slot, token by token with
//! the front end's token stream; `diff` shows where a variant's structure leaves the
//! model's. (Fitted images and the zero-shot loop produce the same [`Variation`] values.)

mod diff;
pub mod files;
pub mod uncertainty;

pub use files::{Variation, load_variation, load_variation_calling};
pub use uncertainty::Uncertainty;
