//! Diagnostics: what went wrong, where, and how to print it.
//!
//! Every user-facing error is a [`Diagnostic`] with a primary span, optional secondary
//! labels and notes, rendered by codespan-reporting with file, line, column and a caret.
//! Nothing in the front end panics on bad input; it returns one of these.

use super::source::SourceMap;
use crate::span::Span;
use codespan_reporting::diagnostic::{Diagnostic as CsDiagnostic, Label};
use codespan_reporting::term::{self, termcolor::WriteColor};

/// A compiler error (or warning) attached to source.
#[derive(Debug, Clone, PartialEq)]
pub struct Diagnostic {
    pub severity: Severity,
    /// A short stable code, e.g. `E0101`; documents the kind of problem.
    pub code: &'static str,
    pub message: String,
    pub primary: Option<(Span, String)>,
    pub secondary: Vec<(Span, String)>,
    pub notes: Vec<String>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Severity {
    Error,
    Warning,
}

impl Diagnostic {
    pub fn error(code: &'static str, message: impl Into<String>) -> Self {
        Diagnostic {
            severity: Severity::Error,
            code,
            message: message.into(),
            primary: None,
            secondary: Vec::new(),
            notes: Vec::new(),
        }
    }

    pub fn warning(code: &'static str, message: impl Into<String>) -> Self {
        Diagnostic {
            severity: Severity::Warning,
            ..Self::error(code, message)
        }
    }

    /// The place the problem is, with a short label under the caret.
    pub fn at(mut self, span: Span, label: impl Into<String>) -> Self {
        self.primary = Some((span, label.into()));
        self
    }

    pub fn with_secondary(mut self, span: Span, label: impl Into<String>) -> Self {
        self.secondary.push((span, label.into()));
        self
    }

    pub fn with_note(mut self, note: impl Into<String>) -> Self {
        self.notes.push(note.into());
        self
    }

    fn to_codespan(&self) -> CsDiagnostic<usize> {
        let base = match self.severity {
            Severity::Error => CsDiagnostic::error(),
            Severity::Warning => CsDiagnostic::warning(),
        };
        let mut labels = Vec::new();
        if let Some((span, text)) = &self.primary {
            labels.push(Label::primary(span.file, span.range()).with_message(text.clone()));
        }
        for (span, text) in &self.secondary {
            labels.push(Label::secondary(span.file, span.range()).with_message(text.clone()));
        }
        base.with_code(self.code)
            .with_message(self.message.clone())
            .with_labels(labels)
            .with_notes(self.notes.clone())
    }

    /// Writes the diagnostic, rustc style, to `out`.
    pub fn emit(&self, sources: &SourceMap, out: &mut dyn WriteColor) {
        let config = term::Config::default();
        // A failure to write to the terminal has nowhere better to be reported.
        let _ = term::emit_to_write_style(out, &config, sources.files(), &self.to_codespan());
    }

    /// The rendered text without colours (for tests and logs).
    pub fn render_plain(&self, sources: &SourceMap) -> String {
        let config = term::Config::default();
        term::emit_into_string(&config, sources.files(), &self.to_codespan()).unwrap_or_default()
    }
}

/// Result type of the front end.
pub type DResult<T> = Result<T, Box<Diagnostic>>;
