//! The back end: what the compiler writes for people and tools.
//!
//! `inspect` presents a model's parameters, parts and relations.

pub mod inspect;
