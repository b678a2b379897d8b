//! The back end: what the compiler writes for people and tools.
//!
//! `inspect` presents a model's parameters, parts and relations; `rewrite` writes a model
//! back with other slot values.

pub mod emit;
pub mod inspect;
pub mod plot;
pub mod rewrite;
