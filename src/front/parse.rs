//! Parsing: OpenSCAD (2021.01) text to the [`ast`](super::ast).
//!
//! Owns the pest grammar `grammar/openscad.pest` and every step between text and tree:
//!
//! 1. `scan`, the lexer, walks the text once, collecting the comments (the grammar skips
//!    them) and rejecting unterminated strings and block comments, and brackets nested
//!    absurdly deep, with specific diagnostics. The same pass is the front end's token
//!    stream ([`tokens`]), which variant files are matched with;
//! 2. pest parses; `errors` turns its failures into readable diagnostics;
//! 3. the nesting of the parse tree is measured without recursion and refused beyond
//!    [`MAX_DEPTH`];
//! 4. `build` turns the pairs into the AST, with tight spans and decoded literals
//!    (`strings`), folding operator chains by the one precedence table (`precedence`),
//!    which `errors` also reads.
//!
//! Stack safety: pest and the builder recurse once per nesting level. pest checks its own
//! stack and fails cleanly when it runs short; the builder runs on the caller's stack only
//! for trees at most `INLINE_DEPTH` (100) deep. Deeper trees, and inputs pest ran short of
//! stack on, are parsed and built again on a helper thread with a stack sized for
//! [`MAX_DEPTH`] (real models never get there). So any input, on any thread, gives the
//! same AST or diagnostic, and nesting beyond [`MAX_DEPTH`] is "nesting too deep".
//!
//! Every failure is a [`Diagnostic`] with code [`SYNTAX_ERROR`]; nothing here panics.

mod build;
mod errors;
mod precedence;
mod scan;
mod strings;
#[cfg(test)]
mod tests;

use super::ast::{Program, Stmt};
use super::diag::{DResult, Diagnostic};
use crate::span::{FileId, Span};
use pest::Parser;
use pest::error::ErrorVariant;
use pest::iterators::Pairs;
use scan::Scanned;
pub use scan::{Token, TokenKind, tokens};

/// Code of every diagnostic the parser produces.
pub const SYNTAX_ERROR: &str = "E0001";

/// Deepest nesting accepted: of brackets, of expressions inside expressions, of statements
/// inside statements, and of the resulting tree. OpenSCAD models stay far below it.
pub const MAX_DEPTH: usize = 500;

/// Parse trees up to this deep are built on the caller's stack (a few hundred KiB at
/// most, even unoptimised).
const INLINE_DEPTH: usize = 100;

/// Stack reserved per nesting level on the helper thread: ample for pest and the
/// builder together, even unoptimised. Only touched pages cost memory.
const STACK_PER_LEVEL: usize = 64 * 1024;

#[derive(pest_derive::Parser)]
#[grammar = "../grammar/openscad.pest"]
struct OpenScadParser;

/// Parses one file's text. `file` is the SourceMap id used in every Span.
pub fn parse_program(file: FileId, text: &str) -> DResult<Program> {
    let scanned = scan::scan(file, text)?;
    let stmts = parse_and_build(file, text, &scanned, true)?;
    Ok(Program {
        stmts,
        comments: scanned.comments,
    })
}

/// Runs pest and the builder; a tree deeper than [`INLINE_DEPTH`] is handed to
/// [`on_big_stack`] when `may_spawn`.
fn parse_and_build(
    file: FileId,
    text: &str,
    scanned: &Scanned,
    may_spawn: bool,
) -> DResult<Vec<Stmt>> {
    let pairs = match OpenScadParser::parse(Rule::program, text) {
        Ok(pairs) => pairs,
        // pest ran short of stack (its only custom error): retry where there is plenty.
        Err(err) if may_spawn && matches!(err.variant, ErrorVariant::CustomError { .. }) => {
            return on_big_stack(MAX_DEPTH, || parse_and_build(file, text, scanned, false));
        }
        Err(err) => return Err(errors::from_pest(file, text, scanned, &err)),
    };
    let depth = check_depth(file, text, &pairs)?;
    if depth > INLINE_DEPTH && may_spawn {
        // pest's pairs cannot cross threads: the helper parses again.
        drop(pairs);
        return on_big_stack(depth, || parse_and_build(file, text, scanned, false));
    }
    build::Builder::new(file, text, &scanned.comments).program(pairs)
}

/// Runs `work` on a scoped thread whose stack fits a tree `depth` deep. If no thread can
/// be started, the input is refused rather than risked on the current stack.
fn on_big_stack<T: Send>(depth: usize, work: impl FnOnce() -> DResult<T> + Send) -> DResult<T> {
    let stack = (depth + 32).saturating_mul(STACK_PER_LEVEL);
    std::thread::scope(|scope| {
        let spawned = std::thread::Builder::new()
            .name("openscad-parse".into())
            .stack_size(stack)
            .spawn_scoped(scope, work);
        match spawned {
            Ok(handle) => handle.join().unwrap_or_else(|_| {
                Err(Box::new(Diagnostic::error(
                    SYNTAX_ERROR,
                    "internal parser error: the parser thread failed",
                )))
            }),
            Err(err) => Err(Box::new(Diagnostic::error(
                SYNTAX_ERROR,
                format!("nesting too deep: cannot start a parser thread ({err})"),
            ))),
        }
    })
}

/// Rules whose nesting is counted against [`MAX_DEPTH`]: each level of them costs a
/// bounded amount of stack in pest, in the builder and in any pass over the tree.
fn counts_as_nesting(rule: Rule) -> bool {
    matches!(
        rule,
        Rule::expr
            | Rule::paren
            | Rule::lc_for
            | Rule::lc_if
            | Rule::lc_each
            | Rule::instance
            | Rule::block
            | Rule::child_block
            | Rule::module_def
    )
}

/// The nesting depth of the parse tree, walking pest's flat token queue; refused beyond
/// [`MAX_DEPTH`].
fn check_depth(file: FileId, text: &str, pairs: &Pairs<'_, Rule>) -> DResult<usize> {
    use pest::Token;
    let (mut depth, mut deepest) = (0usize, 0usize);
    for token in pairs.clone().tokens() {
        match token {
            Token::Start { rule, pos } if counts_as_nesting(rule) => {
                depth += 1;
                if depth > MAX_DEPTH {
                    return Err(too_deep(file, text, pos.pos()));
                }
                deepest = deepest.max(depth);
            }
            Token::End { rule, .. } if counts_as_nesting(rule) => depth = depth.saturating_sub(1),
            _ => {}
        }
    }
    Ok(deepest)
}

/// The "nesting too deep" diagnostic, pointing at `offset`.
pub(crate) fn too_deep(file: FileId, text: &str, offset: usize) -> Box<Diagnostic> {
    Box::new(
        Diagnostic::error(SYNTAX_ERROR, "nesting too deep")
            .at(point(file, text, offset), "nested too deeply here")
            .with_note(format!(
                "at most {MAX_DEPTH} levels of brackets, nested expressions or nested \
                 statements are accepted"
            )),
    )
}

/// The span of the character at byte `offset` of `text`, or an empty one at the end.
pub(crate) fn point(file: FileId, text: &str, offset: usize) -> Span {
    let mut start = offset.min(text.len());
    while !text.is_char_boundary(start) {
        start -= 1;
    }
    let width = text[start..].chars().next().map_or(0, char::len_utf8);
    Span::new(file, start, start + width)
}
