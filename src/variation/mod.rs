//! Where variations come from.
//!
//! `files`: variant `.scad` files matched to the model slot by slot. (Fitted images and the
//! zero-shot loop produce the same [`Variation`] values.)

pub mod files;

pub use files::{Variation, load_variation};
