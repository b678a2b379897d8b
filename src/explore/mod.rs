//! The zero-shot loop (`reparamc explore`): from a model and the name of its object to
//! variations of it, with no examples in hand (the paper's title and headline).
//!
//! A language model proposes kinds of the object ([`llm`]); for each kind, rounds of
//! text-guided img2img on renders of the current numbers ([`diffusion`]) give pictures
//! that a few fit steps move the numbers towards ([`rounds`]); a run folder keeps every
//! round's state so a run can stop and resume ([`run`]). The variations it leaves are
//! ordinary `--vary` files, which the main job then reads.
//!
//! Layering: above `fit` and `render` (it drives them) and `back` (it writes variations),
//! below `command`. Unlike the layers below it, it writes files as it goes (the run
//! folder), always through [`crate::output::write_atomic`]; HTTP is `ureq`'s ([`net`]).

pub mod diffusion;
pub mod gallery;
pub mod llm;
pub mod net;
pub mod rounds;
pub mod run;
