//! The lexer: OpenSCAD's tokens, in one linear pass over the text.
//!
//! pest is scannerless (the grammar reads characters), so this is not a fast path for it:
//! it is the one place that knows where tokens, comments and blanks are. Three passes use
//! it:
//!
//! - the pre-scan, before pest runs ([`scan`]): it collects every comment in source order
//!   (the grammar skips them), rejects unterminated strings, block comments and `include`
//!   paths with a precise diagnostic (pest alone would report a confusing position), and
//!   stops brackets nested deeper than [`MAX_DEPTH`] before pest recurses into them;
//! - the error messages ([`context_at`]): run up to an error position, it tells which
//!   bracket is open there and where the statement being written starts;
//! - the token stream ([`tokens`]): the same pass, recording each token, for comparing two
//!   texts token by token (variant files against their model). It never fails: what the
//!   pre-scan rejects runs to the end of the text instead.
//!
//! Tokens are read as the grammar reads them: a number is `1`, `1.5`, `.5`, `1e-3`; a word
//! starting with a digit is a name when it is longer than any number reading of it (`2d`);
//! `<=`, `>=`, `==`, `!=`, `&&` and `||` are one token; blanks are the grammar's
//! (` `, tab, CR, LF and the no-break space).

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

/// One token of OpenSCAD text: what it is and its byte range. Comments and blanks are not
/// tokens.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Token {
    pub kind: TokenKind,
    pub start: usize,
    pub end: usize,
}

impl Token {
    /// The token's text in the `text` it was read from.
    pub fn text<'t>(&self, text: &'t str) -> &'t str {
        text.get(self.start..self.end).unwrap_or("")
    }
}

/// What a [`Token`] is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TokenKind {
    /// A number literal, with its value.
    Number(f64),
    /// A name or a keyword.
    Word,
    /// A string literal, quotes included.
    Str,
    /// The `<path>` of an `include` or `use`.
    Path,
    /// An operator or punctuation mark (two characters for `<=`, `>=`, `==`, `!=`, `&&`,
    /// `||`), or a character that has no place outside strings and comments.
    Punct,
}

/// The tokens of `text`, in order, for comparing texts token by token. Never fails: an
/// unterminated string or block comment runs to the end of the text, an unterminated
/// `include` path is read as ordinary tokens, and nesting is not limited.
pub fn tokens(text: &str) -> Vec<Token> {
    let mut scanner = Scanner::new(0, text, text.len());
    scanner.tokens = Some(Vec::new());
    // In token mode every error is recovered from where it is found (see above).
    let _ = scanner.run();
    scanner.tokens.unwrap_or_default()
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
    /// The first character of the last token before `pos` (`;` at the start). An
    /// `include`/`use` word starts an include only after `;`, `{`, `}` or `)`, outside
    /// brackets: anywhere else it is a name.
    previous: u8,
    /// The tokens read, when [`tokens`] runs the scanner (which then recovers from every
    /// error instead of reporting it).
    tokens: Option<Vec<Token>>,
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
            tokens: None,
        }
    }

    /// Whether the scanner records tokens and recovers from errors (see [`tokens`]).
    fn lenient(&self) -> bool {
        self.tokens.is_some()
    }

    /// Records the token `start..self.pos` when recording.
    fn push(&mut self, kind: TokenKind, start: usize) {
        let end = self.pos;
        if let Some(tokens) = &mut self.tokens {
            tokens.push(Token { kind, start, end });
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
            self.non_ascii();
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
            b'0'..=b'9' => self.number_or_word(),
            b'.' if self.peek(1).is_some_and(|b| b.is_ascii_digit()) => self.number(),
            b'$' | b'_' | b'a'..=b'z' | b'A'..=b'Z' => self.word(previous)?,
            b';' => {
                self.end_statement();
                self.punct(1);
            }
            _ => {
                let pair = self.bytes.get(self.pos..self.pos + 2);
                let two = matches!(pair, Some(b"<=" | b">=" | b"==" | b"!=" | b"&&" | b"||"));
                self.punct(if two { 2 } else { 1 });
            }
        }
        Ok(())
    }

    /// An operator or punctuation mark `len` bytes long.
    fn punct(&mut self, len: usize) {
        let start = self.pos;
        self.pos += len;
        self.push(TokenKind::Punct, start);
    }

    /// A byte that is not ASCII: the pre-scan steps over it; the token stream skips a
    /// no-break space and makes any other character a token of its own.
    fn non_ascii(&mut self) {
        if !self.lenient() {
            self.pos += 1;
            return;
        }
        let start = self.pos;
        let c = self.text.get(start..).and_then(|t| t.chars().next());
        self.pos += c.map_or(1, char::len_utf8);
        if c != Some('\u{a0}') {
            self.push(TokenKind::Punct, start);
        }
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
            if self.lenient() {
                self.pos = self.bytes.len();
                return Ok(());
            }
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
        if self.lenient() {
            // The token stream has no use for comments.
            return;
        }
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
                None if self.lenient() => break,
                None => return Err(self.unterminated_string(start)),
                Some(b'\\') => at += 2,
                Some(b'"') => break,
                Some(_) => at += 1,
            }
        }
        self.pos = (at + 1).min(self.bytes.len());
        self.push(TokenKind::Str, start);
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
        if self.open.len() > MAX_DEPTH && !self.lenient() {
            return Err(too_deep(self.file, self.text, self.pos));
        }
        if byte == b'{' {
            self.statements.push(None);
        }
        self.punct(1);
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
        self.punct(1);
    }

    /// A number, or a name that starts with a digit: the grammar reads a name when the
    /// text is longer than any number reading of it (`2d`, `1e5x`), unless the digits go
    /// on as a number would (`1.`, `1e-`, `1e+`), which is then a number.
    fn number_or_word(&mut self) {
        let start = self.pos;
        let digits = self.digits(start);
        let number_goes_on = match self.bytes.get(digits) {
            Some(b'.') => true,
            Some(b'e' | b'E') => {
                matches!(self.bytes.get(digits + 1), Some(b'+' | b'-'))
                    && self.bytes.get(digits + 2).is_some_and(u8::is_ascii_digit)
            }
            _ => false,
        };
        let number_end = self.number_end(start);
        let name_follows = self
            .bytes
            .get(number_end)
            .is_some_and(|&b| b.is_ascii_alphanumeric() || b == b'_');
        if number_goes_on || !name_follows {
            self.number();
        } else {
            self.pos = self.word_end(start);
            self.push(TokenKind::Word, start);
        }
    }

    /// A number literal: `1`, `1.`, `1.5`, `.5`, each with an optional exponent.
    fn number(&mut self) {
        let start = self.pos;
        self.pos = self.number_end(start);
        let text = &self.text[start..self.pos];
        let value = text.parse().unwrap_or(f64::NAN);
        self.push(TokenKind::Number(value), start);
    }

    /// The end of the digits from `at` on.
    fn digits(&self, mut at: usize) -> usize {
        while self.bytes.get(at).is_some_and(u8::is_ascii_digit) {
            at += 1;
        }
        at
    }

    /// The end of the number reading from `start`: digits, a fraction, an exponent (only
    /// when digits follow its `e` and sign).
    fn number_end(&self, start: usize) -> usize {
        let mut at = self.digits(start);
        if self.bytes.get(at) == Some(&b'.') {
            at = self.digits(at + 1);
        }
        if matches!(self.bytes.get(at), Some(b'e' | b'E')) {
            let sign = usize::from(matches!(self.bytes.get(at + 1), Some(b'+' | b'-')));
            let exponent = self.digits(at + 1 + sign);
            if exponent > at + 1 + sign {
                at = exponent;
            }
        }
        at
    }

    /// The end of the word from `start`: letters, digits, `_` and `$`.
    fn word_end(&self, mut at: usize) -> usize {
        while matches!(self.bytes.get(at), Some(b) if b.is_ascii_alphanumeric() || *b == b'_' || *b == b'$')
        {
            at += 1;
        }
        at
    }

    /// A name, keyword or number; `include <...>` and `use <...>` skip their path, which
    /// may contain anything but `>`, tabs and line breaks (even `//`).
    fn word(&mut self, previous: u8) -> DResult<()> {
        let start = self.pos;
        self.pos = self.word_end(start);
        self.push(TokenKind::Word, start);
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
            if self.lenient() {
                // Read on as ordinary tokens, from the `<`.
                return Ok(());
            }
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
        self.push(TokenKind::Path, open);
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
