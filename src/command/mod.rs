//! The library's entry points: one per command of the `reparamc` binary.
//!
//! Each takes an options struct (plain data, no flags) and the [`SourceMap`] that will
//! hold every file it reads, and returns its results (texts, pictures, reports as data) or
//! the diagnostics that stopped it. Nothing here parses flags, prints or writes files: the
//! CLI is flags in, diagnostics out, and writes the results with [`crate::output`]. A
//! program that wants what a command does calls the same function. `render` and `fit`
//! report as a list of [`Message`]s in the order they arose (a [`Failure`] when they
//! stop); `compile` and `inspect` return their warnings beside their results.
//!
//! [`SourceMap`]: crate::front::source::SourceMap

pub mod compile;
pub mod explore;
pub mod fit;
pub mod inspect;
pub mod pictures;
pub mod render;

use crate::front::diag::Diagnostic;

/// A line for the user (standard error), in the order it arose.
#[derive(Debug, Clone, PartialEq)]
pub enum Message {
    /// A diagnostic, to be shown against the [`SourceMap`] the command filled.
    Diagnostic(Diagnostic),
    /// A line of plain text (`renderer: …`, `warning: …`).
    Line(String),
}

/// What stopped a command: everything it had to say, its last messages the errors.
#[derive(Debug, Clone, PartialEq)]
pub struct Failure {
    pub messages: Vec<Message>,
}

impl Failure {
    /// After `messages`, a problem with an input other than the model (no source span).
    pub fn input(mut messages: Vec<Message>, code: &'static str, text: String) -> Failure {
        messages.push(Message::Diagnostic(Diagnostic::error(code, text)));
        Failure { messages }
    }
}

impl From<Box<Diagnostic>> for Failure {
    /// A diagnostic that stopped a command before it had anything else to say (the
    /// model's loaders return theirs boxed).
    fn from(d: Box<Diagnostic>) -> Failure {
        Failure {
            messages: vec![Message::Diagnostic(*d)],
        }
    }
}

/// Diagnostics (a model's warnings) as messages, in their order.
pub(crate) fn as_messages(diagnostics: Vec<Diagnostic>) -> Vec<Message> {
    diagnostics.into_iter().map(Message::Diagnostic).collect()
}
