//! Parsing: OpenSCAD (2021.01) text to the [`ast`](super::ast).
//!
//! Owns the pest grammar `grammar/openscad.pest` and every step between text and tree:
//!
//! 1. [`scan`] walks the text once, collecting comments (the grammar skips them) and
//!    rejecting unterminated strings and block comments, and brackets nested absurdly deep,
//!    with specific diagnostics;
//! 2. pest parses; its failures become readable diagnostics in [`errors`];
//! 3. the nesting of the parse tree is measured without recursion and refused beyond
//!    [`MAX_DEPTH`], so neither the builder nor later passes can overflow the stack;
//! 4. [`build`] turns the pairs into the AST with tight spans.
//!
//! Every failure is a [`Diagnostic`] with code [`SYNTAX_ERROR`]; nothing here panics.

mod build;
mod errors;
mod scan;
#[cfg(test)]
mod tests;

use super::ast::Program;
use super::diag::{DResult, Diagnostic};
use super::source::{FileId, Span};
use pest::Parser;
use pest::iterators::Pairs;

/// Code of every diagnostic the parser produces.
pub const SYNTAX_ERROR: &str = "E0001";

/// Deepest nesting accepted: of brackets, of expressions inside expressions, of statements
/// inside statements, and of the resulting tree. OpenSCAD models stay far below it.
pub const MAX_DEPTH: usize = 500;

#[derive(pest_derive::Parser)]
#[grammar = "../grammar/openscad.pest"]
struct OpenScadParser;

/// Parses one file's text. `file` is the SourceMap id used in every Span.
pub fn parse_program(file: FileId, text: &str) -> DResult<Program> {
    let scanned = scan::scan(file, text)?;
    let pairs = OpenScadParser::parse(Rule::program, text)
        .map_err(|err| errors::from_pest(file, text, &scanned, &err))?;
    check_depth(file, text, &pairs)?;
    let stmts = build::Builder::new(file, text, &scanned.comments).program(pairs)?;
    Ok(Program {
        stmts,
        comments: scanned.comments,
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

/// Refuses parse trees nested deeper than [`MAX_DEPTH`], walking pest's flat token queue.
fn check_depth(file: FileId, text: &str, pairs: &Pairs<'_, Rule>) -> DResult<()> {
    use pest::Token;
    let mut depth = 0usize;
    for token in pairs.clone().tokens() {
        match token {
            Token::Start { rule, pos } if counts_as_nesting(rule) => {
                depth += 1;
                if depth > MAX_DEPTH {
                    return Err(too_deep(file, text, pos.pos()));
                }
            }
            Token::End { rule, .. } if counts_as_nesting(rule) => depth = depth.saturating_sub(1),
            _ => {}
        }
    }
    Ok(())
}

/// The "nesting too deep" diagnostic, pointing at `offset`.
pub(crate) fn too_deep(file: FileId, text: &str, offset: usize) -> Box<Diagnostic> {
    Box::new(
        Diagnostic::error(SYNTAX_ERROR, "nesting too deep")
            .at(point(file, text, offset), "nested too deeply here")
            .with_note(format!(
                "the parser accepts at most {MAX_DEPTH} levels of nested brackets, expressions or statements"
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
