//! Names from the source: which comment names a statement, which context names a literal.
//!
//! A statement is named by a comment on its own line (the last comment line directly above
//! it) or at the end of its first line. The words up to the first punctuation become an
//! identifier (`// left front leg` → `left_front_leg`). A literal's naming context is the
//! innermost named statement around it, or the module it is written in; top-level variables
//! name their own literal.

use super::ast::{Expr, ExprKind, Program, Stmt, StmtKind, UnaryOp};
use super::source::SourceMap;
use super::walk::{Visitor, visit_stmts};
use crate::span::{FileId, Span};
use std::collections::HashMap;

/// Names found in the source, computed once per run.
#[derive(Debug, Default)]
pub struct Naming {
    statements: HashMap<Span, String>,
    literal_contexts: HashMap<Span, String>,
    variables: HashMap<Span, String>,
}

impl Naming {
    /// Indexes every file's comments and statements. `main` is the model itself.
    pub fn new(sources: &SourceMap, programs: &HashMap<FileId, Program>, main: FileId) -> Self {
        let mut naming = Naming::default();
        for (&file, program) in programs {
            let comments = CommentIndex::new(sources.text(file), program);
            let mut walker = Walker {
                comments: &comments,
                text: sources.text(file),
                stack: Vec::new(),
                naming: &mut naming,
            };
            visit_stmts(&program.stmts, &mut walker);
        }
        if let Some(p) = programs.get(&main) {
            for s in &p.stmts {
                if let StmtKind::Assign { name, value } = &s.kind
                    && let Some(span) = bare_literal(value)
                {
                    naming.variables.insert(span, name.name.clone());
                }
            }
        }
        naming
    }

    /// The name a comment gives this statement.
    pub fn statement_name(&self, span: Span) -> Option<String> {
        self.statements.get(&span).cloned()
    }

    /// The innermost named statement or module around a literal.
    pub fn literal_context(&self, span: Span) -> Option<&str> {
        self.literal_contexts.get(&span).map(String::as_str)
    }

    /// The top-level variable whose whole value is this literal.
    pub fn variable(&self, span: Span) -> Option<&str> {
        self.variables.get(&span).map(String::as_str)
    }
}

/// The span of `5` in `5` or `-5`.
fn bare_literal(e: &Expr) -> Option<Span> {
    match &e.kind {
        ExprKind::Number { .. } => Some(e.span),
        ExprKind::Unary(UnaryOp::Neg | UnaryOp::Plus, x) => bare_literal(x),
        _ => None,
    }
}

/// Turns comment text into an identifier, or `None` if it does not name anything.
pub fn identifier_from_comment(text: &str) -> Option<String> {
    let text = text.trim();
    if text.starts_with('[') || text.is_empty() {
        return None;
    }
    let head = text
        .split([',', '.', ':', ';', '(', '[', '—', '–'])
        .next()
        .unwrap_or("")
        .split(" - ")
        .next()
        .unwrap_or("");
    let words: Vec<String> = head
        .split(|c: char| !c.is_alphanumeric())
        .filter(|w| !w.is_empty())
        .map(str::to_lowercase)
        .collect();
    let skip = words
        .iter()
        .take_while(|w| matches!(w.as_str(), "the" | "a" | "an"))
        .count();
    // A name is the noun phrase before the first preposition: "rungs on all four sides".
    let end = words
        .iter()
        .skip(skip)
        .position(|w| {
            matches!(
                w.as_str(),
                "on" | "at"
                    | "in"
                    | "of"
                    | "by"
                    | "with"
                    | "for"
                    | "to"
                    | "from"
                    | "and"
                    | "is"
                    | "are"
                    | "that"
                    | "which"
                    | "placed"
                    | "turned"
            )
        })
        .map_or(words.len(), |p| p + skip);
    let words = &words[skip..end];
    if words.is_empty() || words.len() > 5 {
        return None;
    }
    let id = words.join("_");
    Some(if id.starts_with(|c: char| c.is_ascii_digit()) {
        format!("part_{id}")
    } else {
        id
    })
}

/// Comments of one file by line.
struct CommentIndex {
    line_starts: Vec<usize>,
    /// Standalone comments (only whitespace before them on their line), by end line.
    standalone_by_end_line: HashMap<usize, String>,
    /// Comments after code, by start line.
    trailing_by_line: HashMap<usize, (usize, String)>,
}

impl CommentIndex {
    fn new(text: &str, program: &Program) -> Self {
        let line_starts: Vec<usize> = std::iter::once(0)
            .chain(text.match_indices('\n').map(|(i, _)| i + 1))
            .collect();
        let mut idx = CommentIndex {
            line_starts,
            standalone_by_end_line: HashMap::new(),
            trailing_by_line: HashMap::new(),
        };
        for c in &program.comments {
            let start = c.span.start as usize;
            let line = idx.line_of(start);
            let before = text.get(idx.line_starts[line]..start).unwrap_or("");
            if before.trim().is_empty() {
                let end_line = idx.line_of((c.span.end as usize).saturating_sub(1));
                idx.standalone_by_end_line.insert(end_line, c.text.clone());
            } else {
                idx.trailing_by_line
                    .entry(line)
                    .or_insert((start, c.text.clone()));
            }
        }
        idx
    }

    fn line_of(&self, offset: usize) -> usize {
        self.line_starts
            .partition_point(|&s| s <= offset)
            .saturating_sub(1)
    }

    fn name_for(&self, span: Span) -> Option<String> {
        let line = self.line_of(span.start as usize);
        if let Some((at, text)) = self.trailing_by_line.get(&line)
            && *at > span.start as usize
            && let Some(id) = identifier_from_comment(text)
        {
            return Some(id);
        }
        let above = line.checked_sub(1)?;
        identifier_from_comment(self.standalone_by_end_line.get(&above)?)
    }
}

struct Walker<'n, 'c> {
    comments: &'c CommentIndex,
    text: &'c str,
    /// Context names of the statements we are inside; `None` for unnamed ones.
    stack: Vec<Option<String>>,
    naming: &'n mut Naming,
}

impl<'a> Visitor<'a> for Walker<'_, '_> {
    fn enter(&mut self, stmt: &'a Stmt) {
        let _ = self.text;
        let name = match &stmt.kind {
            StmtKind::ModuleDef { name, .. } => self
                .comments
                .name_for(stmt.span)
                .or_else(|| Some(name.name.clone())),
            StmtKind::Instance(_) | StmtKind::Block(_) => self.comments.name_for(stmt.span),
            _ => None,
        };
        if let (Some(n), false) = (&name, matches!(stmt.kind, StmtKind::ModuleDef { .. })) {
            self.naming.statements.insert(stmt.span, n.clone());
        }
        self.stack.push(name);
    }

    fn leave(&mut self, _stmt: &'a Stmt) {
        self.stack.pop();
    }

    fn expr(&mut self, e: &'a Expr) {
        if matches!(e.kind, ExprKind::Number { .. })
            && let Some(ctx) = self.stack.iter().rev().flatten().next()
        {
            self.naming.literal_contexts.insert(e.span, ctx.clone());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::identifier_from_comment as id;

    #[test]
    fn comments_become_identifiers() {
        assert_eq!(id("left front leg").as_deref(), Some("left_front_leg"));
        assert_eq!(id("The seat").as_deref(), Some("seat"));
        assert_eq!(
            id("A chair, typed in part by part.").as_deref(),
            Some("chair")
        );
        assert_eq!(id("[Shape]"), None);
        assert_eq!(id("legs, one at each corner").as_deref(), Some("legs"));
        assert_eq!(
            id("very long winding sentence naming nothing much here"),
            None
        );
        assert_eq!(
            id("footrest rungs on all four sides").as_deref(),
            Some("footrest_rungs")
        );
    }
}
