//! The pre-scan: one linear pass over the text before pest runs.
//!
//! It knows just enough of OpenSCAD's lexer (strings, comments, `include <...>` paths) to
//! collect every comment in source order, to reject unterminated strings and block
//! comments with a precise diagnostic (pest alone would report a confusing position), to
//! stop brackets nested deeper than [`MAX_DEPTH`] before pest recurses into them. Run up
//! to an error position, it tells the error messages where that position sits.

use super::{MAX_DEPTH, SYNTAX_ERROR, too_deep};
use crate::front::ast::Comment;
use crate::front::diag::{DResult, Diagnostic};
use crate::span::{FileId, Span};

/// What the pre-scan learned.
pub(super) struct Scanned {
    /// Every comment, in source order.
    pub comments: Vec<Comment>,
}

/// Scans `text`; see the module documentation.
pub(super) fn scan(file: FileId, text: &str) -> DResult<Scanned> {
    let mut scanner = Scanner::new(file, text, text.len());
    scanner.run()?;
    Ok(Scanned {
        comments: scanner.comments,
    })
}

/// Where a byte offset sits, for the wording of a syntax error there.
#[derive(Debug, Default)]
pub(super) struct Context {
    /// The innermost bracket open at the offset: its offset and character.
    pub open: Option<(usize, u8)>,
    /// Where the statement being written at the offset starts, when the offset is at
    /// statement level (not inside `( )` or `[ ]`) and that statement has begun.
    pub statement: Option<usize>,
}

/// The [`Context`] at `offset` of a text [`scan`] accepted.
pub(super) fn context_at(text: &str, offset: usize) -> Context {
    let mut scanner = Scanner::new(0, text, offset.min(text.len()));
    if scanner.run().is_err() {
        return Context::default();
    }
    Context {
        open: scanner.open.last().copied(),
        statement: if scanner.in_expression() {
            None
        } else {
            scanner.statements.last().copied().flatten()
        },
    }
}

struct Scanner<'a> {
    file: FileId,
    text: &'a str,
    bytes: &'a [u8],
    pos: usize,
    /// Where to stop.
    limit: usize,
    comments: Vec<Comment>,
    /// Brackets open at `pos`: offset and character.
    open: Vec<(usize, u8)>,
    /// Per level of `{ }` (the file is the first): where its current statement starts,
    /// `None` between statements.
    statements: Vec<Option<usize>>,
    /// The last significant ASCII character before `pos` (`;` at the start). An
    /// `include`/`use` word starts an include only after `;`, `{`, `}` or `)`, outside
    /// brackets: anywhere else it is a name.
    previous: u8,
}

impl<'a> Scanner<'a> {
    fn new(file: FileId, text: &'a str, limit: usize) -> Self {
        Scanner {
            file,
            text,
            bytes: text.as_bytes(),
            pos: 0,
            limit,
            comments: Vec::new(),
            open: Vec::new(),
            statements: vec![None],
            previous: b';',
        }
    }

    fn run(&mut self) -> DResult<()> {
        while self.pos < self.limit {
            let byte = self.bytes[self.pos];
            match byte {
                b'/' if self.peek(1) == Some(b'/') => self.line_comment(),
                b'/' if self.peek(1) == Some(b'*') => self.block_comment()?,
                b' ' | b'\t' | b'\r' | b'\n' => self.pos += 1,
                _ => self.token(byte)?,
            }
        }
        Ok(())
    }

    fn token(&mut self, byte: u8) -> DResult<()> {
        // Non-ASCII bytes are either a no-break space (a blank) or a syntax error.
        if !byte.is_ascii() {
            self.pos += 1;
            return Ok(());
        }
        if !self.in_expression() {
            let pos = self.pos;
            if let Some(current) = self.statements.last_mut() {
                current.get_or_insert(pos);
            }
        }
        let previous = std::mem::replace(&mut self.previous, byte);
        match byte {
            b'"' => self.string()?,
            b'(' | b'[' | b'{' => self.open_bracket(byte)?,
            b')' | b']' | b'}' => self.close_bracket(),
            b'$' | b'_' | b'0'..=b'9' | b'a'..=b'z' | b'A'..=b'Z' => self.word(previous)?,
            b';' => {
                self.end_statement();
                self.pos += 1;
            }
            _ => self.pos += 1,
        }
        Ok(())
    }

    /// Whether `pos` is inside `( )` or `[ ]`, where statements do not start or end.
    fn in_expression(&self) -> bool {
        self.open.last().is_some_and(|&(_, b)| b != b'{')
    }

    fn end_statement(&mut self) {
        if !self.in_expression()
            && let Some(current) = self.statements.last_mut()
        {
            *current = None;
        }
    }

    fn peek(&self, ahead: usize) -> Option<u8> {
        self.bytes.get(self.pos + ahead).copied()
    }

    fn line_comment(&mut self) {
        let start = self.pos;
        let line_end = memchr(b'\n', &self.bytes[start..]).map_or(self.bytes.len(), |i| start + i);
        // The span stops at the last visible character, so that a span trimmed of trailing
        // blanks can still tell a comment ends there.
        let inner = self.text[start + 2..line_end].trim_end();
        let end = start + 2 + inner.len();
        self.push_comment(start, end, inner, false);
        self.pos = line_end;
    }

    fn block_comment(&mut self) -> DResult<()> {
        let start = self.pos;
        let body = start + 2;
        let Some(close) = self.text[body..].find("*/").map(|i| body + i) else {
            return Err(Box::new(
                Diagnostic::error(SYNTAX_ERROR, "unterminated block comment")
                    .at(
                        Span::new(self.file, start, body),
                        "this comment is never closed",
                    )
                    .with_note("a block comment ends with `*/`; they do not nest"),
            ));
        };
        self.push_comment(start, close + 2, &self.text[body..close], true);
        self.pos = close + 2;
        Ok(())
    }

    fn push_comment(&mut self, start: usize, end: usize, inner: &str, block: bool) {
        self.comments.push(Comment {
            span: Span::new(self.file, start, end),
            text: inner.trim().to_string(),
            block,
        });
    }

    /// Skips a string literal, honouring backslash escapes.
    fn string(&mut self) -> DResult<()> {
        let start = self.pos;
        let mut at = start + 1;
        loop {
            match self.bytes.get(at) {
                None => return Err(self.unterminated_string(start)),
                Some(b'\\') => at += 2,
                Some(b'"') => break,
                Some(_) => at += 1,
            }
        }
        self.pos = at + 1;
        Ok(())
    }

    fn unterminated_string(&self, start: usize) -> Box<Diagnostic> {
        Box::new(
            Diagnostic::error(SYNTAX_ERROR, "unterminated string")
                .at(
                    Span::new(self.file, start, start + 1),
                    "this string is never closed",
                )
                .with_note("a string ends with an unescaped `\"`"),
        )
    }

    fn open_bracket(&mut self, byte: u8) -> DResult<()> {
        self.open.push((self.pos, byte));
        if self.open.len() > MAX_DEPTH {
            return Err(too_deep(self.file, self.text, self.pos));
        }
        if byte == b'{' {
            self.statements.push(None);
        }
        self.pos += 1;
        Ok(())
    }

    /// Closes the innermost bracket, whichever it is: a mismatch is a syntax error pest
    /// reports, and popping anyway keeps garbage like `(]` from piling up depth.
    fn close_bracket(&mut self) {
        if let Some((_, opener)) = self.open.pop()
            && opener == b'{'
            && self.statements.len() > 1
        {
            self.statements.pop();
            // A block ends the statement it belongs to (an `else` may start another).
            self.end_statement();
        }
        self.pos += 1;
    }

    /// A name, keyword or number; `include <...>` and `use <...>` skip their path, which
    /// may contain anything but `>`, tabs and line breaks (even `//`).
    fn word(&mut self, previous: u8) -> DResult<()> {
        let start = self.pos;
        while matches!(self.bytes.get(self.pos), Some(b) if b.is_ascii_alphanumeric() || *b == b'_' || *b == b'$')
        {
            self.pos += 1;
        }
        let word = &self.text[start..self.pos];
        let may_include = !self.in_expression() && matches!(previous, b';' | b'{' | b'}' | b')');
        if may_include && (word == "include" || word == "use") {
            return self.include_path(start);
        }
        Ok(())
    }

    fn include_path(&mut self, keyword_start: usize) -> DResult<()> {
        let mut at = self.pos;
        while matches!(self.bytes.get(at), Some(b' ' | b'\t' | b'\r' | b'\n')) {
            at += 1;
        }
        if self.bytes.get(at) != Some(&b'<') {
            return Ok(());
        }
        let open = at;
        at += 1;
        while matches!(self.bytes.get(at), Some(b) if !matches!(b, b'>' | b'\t' | b'\r' | b'\n')) {
            at += 1;
        }
        if self.bytes.get(at) != Some(&b'>') {
            let keyword = &self.text[keyword_start..self.pos];
            return Err(Box::new(
                Diagnostic::error(SYNTAX_ERROR, format!("unterminated `{keyword}` path"))
                    .at(
                        Span::new(self.file, open, open + 1),
                        "this path is never closed",
                    )
                    .with_note("the path ends with `>` on the same line"),
            ));
        }
        self.pos = at + 1;
        // An include is a statement of its own: another may follow directly.
        self.end_statement();
        self.previous = b';';
        Ok(())
    }
}

/// Position of the first `needle` in `haystack`.
fn memchr(needle: u8, haystack: &[u8]) -> Option<usize> {
    haystack.iter().position(|&b| b == needle)
}
