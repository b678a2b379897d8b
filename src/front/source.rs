//! Source files.
//!
//! Owns every file the compiler read (the model and whatever it includes), so that spans
//! stay valid for the whole run and diagnostics can quote any of them. A
//! [`Span`](crate::span::Span) is a byte range in one file; its
//! [`FileId`](crate::span::FileId) indexes the [`SourceMap`].

use crate::span::{FileId, Span};
use codespan_reporting::files::SimpleFiles;
use std::path::{Path, PathBuf};

/// Every file read during one run, with its path and text.
#[derive(Default)]
pub struct SourceMap {
    files: SimpleFiles<String, String>,
    paths: Vec<PathBuf>,
}

impl SourceMap {
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds a file; `path` is what diagnostics print.
    pub fn add(&mut self, path: impl AsRef<Path>, text: String) -> FileId {
        let path = path.as_ref().to_path_buf();
        self.paths.push(path.clone());
        self.files.add(path.display().to_string(), text)
    }

    pub fn text(&self, file: FileId) -> &str {
        self.files
            .get(file)
            .map(|f| f.source().as_str())
            .unwrap_or("")
    }

    pub fn path(&self, file: FileId) -> &Path {
        &self.paths[file]
    }

    pub fn snippet(&self, span: Span) -> &str {
        self.text(span.file).get(span.range()).unwrap_or("")
    }

    /// 1-based line and column of a byte offset (column counts characters).
    pub fn line_col(&self, file: FileId, offset: usize) -> (usize, usize) {
        let text = self.text(file);
        let offset = offset.min(text.len());
        let before = &text[..floor_char_boundary(text, offset)];
        let line = before.matches('\n').count() + 1;
        let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
        (line, col)
    }

    /// `path:line:col` of a span's start.
    pub fn location(&self, span: Span) -> String {
        let (line, col) = self.line_col(span.file, span.start as usize);
        format!("{}:{}:{}", self.path(span.file).display(), line, col)
    }

    pub fn files(&self) -> &SimpleFiles<String, String> {
        &self.files
    }

    pub fn len(&self) -> usize {
        self.paths.len()
    }

    pub fn is_empty(&self) -> bool {
        self.paths.is_empty()
    }
}

fn floor_char_boundary(s: &str, mut i: usize) -> usize {
    while i > 0 && !s.is_char_boundary(i) {
        i -= 1;
    }
    i
}
