//! Names from the source: which comment names a statement, which context names a literal,
//! and which of the author's identifiers name a literal.
//!
//! The source is read in the order a person would trust it: the author's variables (a
//! literal assigned to `seat_h` is `seat_h`), then module names with their argument names
//! (`leg(h = 5)` and `module leg(h = 5)` give `leg.h`), then comments, then `color()` names.
//! A statement is named by a comment on its own line (the last comment line directly above
//! it) or at the end of its first line; its words up to the first punctuation or function
//! word become an identifier (`// left front leg` → `left_front_leg`), transliterated to
//! ASCII first (`// спинка` → `spinka`). Invariant: every name given has a letter, only
//! ASCII letters, digits and `_`, and does not start with a digit.
//!
//! A variable is *kept* (the output keeps it by name, [`Naming::variable`]) when its whole
//! value is one literal of the model's file, one statement assigns it, and (inside a
//! module) it is no parameter or loop variable anywhere: then `name = name;` in the output
//! reads the slider. Other source names ([`Naming::source_name`]) are an owner and, for a
//! single literal, a role.

use super::ast::{Arg, Expr, ExprKind, InstanceKind, Program, Stmt, StmtKind, UnaryOp, VecElem};
use super::source::SourceMap;
use super::walk::{Visitor, visit_stmts};
use crate::span::{FileId, Span};
use std::collections::{HashMap, HashSet};

/// A literal named by the author's identifiers: `owner.role`, or `owner` and the role the
/// literal plays where it is used (`None`: an element of a vector such as `size = [1, 2, 3]`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SourceName {
    pub owner: String,
    pub role: Option<String>,
}

/// Names found in the source, computed once per run.
#[derive(Debug, Default)]
pub struct Naming {
    statements: HashMap<Span, String>,
    colors: HashMap<Span, String>,
    literal_contexts: HashMap<Span, String>,
    variables: HashMap<Span, String>,
    source_names: HashMap<Span, SourceName>,
}

impl Naming {
    /// Indexes every file's comments, statements and identifiers. `main` is the model itself.
    pub fn new(sources: &SourceMap, programs: &HashMap<FileId, Program>, main: FileId) -> Self {
        let mut naming = Naming::default();
        for (&file, program) in programs {
            let comments = CommentIndex::new(sources.text(file), program);
            let mut walker = Walker {
                comments: &comments,
                stack: Vec::new(),
                naming: &mut naming,
            };
            visit_stmts(&program.stmts, &mut walker);
        }
        let idents = Identifiers::of(programs);
        let mut files: Vec<&FileId> = programs.keys().collect();
        files.sort();
        for file in files {
            let mut names = SourceNames {
                idents: &idents,
                main: *file == main,
                naming: &mut naming,
            };
            names.stmts(&programs[file].stmts, None);
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

    /// The kept variable whose whole value is this literal (see the module doc).
    pub fn variable(&self, span: Span) -> Option<&str> {
        self.variables.get(&span).map(String::as_str)
    }

    /// The author's identifiers naming a literal that is not a kept variable.
    pub fn source_name(&self, span: Span) -> Option<&SourceName> {
        self.source_names.get(&span)
    }

    /// The colour a `color("name")` statement gives what it draws (none for `#rrggbb`).
    pub fn color_name(&self, span: Span) -> Option<String> {
        self.colors.get(&span).cloned()
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

/// Words that end a name: a name is the noun phrase before the first of them ("rungs on
/// all four sides", "cuerpo del carro"). Articles and prepositions of the languages models
/// are commonly commented in.
const FUNCTION_WORDS: &[&str] = &[
    // English
    "on", "at", "in", "of", "by", "with", "for", "to", "from", "and", "is", "are", "that", "which",
    "placed", "turned", "into", "under", "over", // Spanish, Italian, Portuguese, French
    "de", "del", "la", "el", "los", "las", "en", "con", "para", "por", "y", "di", "della", "dello",
    "dei", "delle", "il", "lo", "per", "e", "da", "do", "dos", "das", "du", "des", "le", "les",
    "et", "sur", "avec", "pour", // German, Dutch
    "der", "die", "das", "den", "dem", "von", "vom", "mit", "und", "auf", "im", "zum", "zur",
    "fur", "het", "van", "een", "op",
];

/// Articles a name may start with, which it drops.
const ARTICLES: &[&str] = &["the", "a", "an", "un", "una", "uno", "une", "ein", "eine"];

/// Lower-case ASCII words of `text`, transliterated (`спинка` → `spinka`), split at every
/// other character and between a lower-case letter and an upper-case one (`PowderBlue`).
pub fn ascii_words(text: &str) -> Vec<String> {
    let ascii = deunicode::deunicode(text);
    let mut words = Vec::new();
    let mut cur = String::new();
    let mut prev_lower = false;
    for c in ascii.chars() {
        if !c.is_ascii_alphanumeric() {
            if !cur.is_empty() {
                words.push(std::mem::take(&mut cur));
            }
            prev_lower = false;
            continue;
        }
        if c.is_ascii_uppercase() && prev_lower && !cur.is_empty() {
            words.push(std::mem::take(&mut cur));
        }
        prev_lower = c.is_ascii_lowercase() || c.is_ascii_digit();
        cur.push(c.to_ascii_lowercase());
    }
    if !cur.is_empty() {
        words.push(cur);
    }
    words
}

/// `words` as an identifier: the words with a letter, joined by `_`; `None` when no word
/// has one (a name is never only digits) or the first would start with a digit.
fn identifier(words: &[String]) -> Option<String> {
    let kept: Vec<&str> = words
        .iter()
        .filter(|w| w.chars().any(|c| c.is_ascii_alphabetic()))
        .map(String::as_str)
        .collect();
    let first = kept.first()?;
    if first.starts_with(|c: char| c.is_ascii_digit()) {
        return None;
    }
    Some(kept.join("_"))
}

/// Turns comment text into an identifier, or `None` if it does not name anything.
pub fn identifier_from_comment(text: &str) -> Option<String> {
    let text = text.trim();
    if text.starts_with('[') || text.is_empty() {
        return None;
    }
    let head = text
        .split([',', '.', ':', ';', '(', '[', '—', '–', '/', '='])
        .next()
        .unwrap_or("")
        .split(" - ")
        .next()
        .unwrap_or("");
    let words = ascii_words(head);
    let skip = words
        .iter()
        .take_while(|w| ARTICLES.contains(&w.as_str()))
        .count();
    let end = words
        .iter()
        .skip(skip)
        .position(|w| FUNCTION_WORDS.contains(&w.as_str()))
        .map_or(words.len(), |p| p + skip);
    let words = &words[skip..end];
    if words.is_empty() || words.len() > 5 {
        return None;
    }
    identifier(words)
}

/// The name of a `color()` argument: a colour name (`"PowderBlue"` → `powder_blue`), not a
/// number or `#rrggbb`.
fn color_name(args: &[Arg]) -> Option<String> {
    let arg = args
        .iter()
        .find(|a| a.name.as_ref().is_none_or(|n| n.name == "c"))?;
    match &arg.value.kind {
        ExprKind::Str(s) if !s.trim_start().starts_with('#') => identifier(&ascii_words(s)),
        _ => None,
    }
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
    /// Context names of the statements we are inside; `None` for unnamed ones.
    stack: Vec<Option<String>>,
    naming: &'n mut Naming,
}

impl<'a> Visitor<'a> for Walker<'_, '_> {
    fn enter(&mut self, stmt: &'a Stmt) {
        if let StmtKind::Instance(i) = &stmt.kind
            && let InstanceKind::Call { name, args, .. } = &i.kind
            && name.name == "color"
            && let Some(c) = color_name(args)
        {
            self.naming.colors.insert(stmt.span, c);
        }
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

/// What the programs say about identifiers: how often each is assigned, which are
/// parameters or loop variables, and each user module's parameter names.
struct Identifiers {
    assigned: HashMap<String, usize>,
    bound: HashSet<String>,
    modules: HashMap<String, Vec<String>>,
}

impl Identifiers {
    fn of(programs: &HashMap<FileId, Program>) -> Self {
        struct Count(Identifiers);
        impl<'a> Visitor<'a> for Count {
            fn enter(&mut self, s: &'a Stmt) {
                let ids = &mut self.0;
                match &s.kind {
                    StmtKind::Assign { name, .. } => {
                        *ids.assigned.entry(name.name.clone()).or_default() += 1;
                    }
                    StmtKind::ModuleDef { name, params, .. } => {
                        let names: Vec<String> =
                            params.iter().map(|p| p.name.name.clone()).collect();
                        ids.bound.extend(names.iter().cloned());
                        ids.modules.entry(name.name.clone()).or_insert(names);
                    }
                    StmtKind::FunctionDef { params, .. } => {
                        ids.bound.extend(params.iter().map(|p| p.name.name.clone()));
                    }
                    StmtKind::Instance(i) => match &i.kind {
                        InstanceKind::For { bindings, .. }
                        | InstanceKind::IntersectionFor { bindings, .. }
                        | InstanceKind::Let { bindings, .. } => {
                            ids.bound
                                .extend(bindings.iter().map(|b| b.name.name.clone()));
                        }
                        _ => {}
                    },
                    _ => {}
                }
            }
        }
        let mut c = Count(Identifiers {
            assigned: HashMap::new(),
            bound: HashSet::new(),
            modules: HashMap::new(),
        });
        for p in programs.values() {
            visit_stmts(&p.stmts, &mut c);
        }
        c.0
    }

    /// Whether `name = literal;` can be kept by name: one assignment, and inside a module
    /// a name that is no parameter or loop variable anywhere (`w = w;` must read the slider).
    fn keeps(&self, name: &str, top_level: bool) -> bool {
        self.assigned.get(name) == Some(&1)
            && (top_level || !self.bound.contains(name))
            && !name.starts_with('$')
    }
}

/// The literals of a flat vector (`[1, -2, 3]`), if every element is one.
fn vector_literals(e: &Expr) -> Option<Vec<Span>> {
    let ExprKind::Vector(items) = &e.kind else {
        return None;
    };
    items
        .iter()
        .map(|i| match i {
            VecElem::Expr(x) => bare_literal(x),
            _ => None,
        })
        .collect()
}

/// The pass that names literals after the identifiers they are assigned or passed to.
struct SourceNames<'i, 'n> {
    idents: &'i Identifiers,
    /// Whether this is the model's own file (only its variables can be kept).
    main: bool,
    naming: &'n mut Naming,
}

impl SourceNames<'_, '_> {
    /// `value` given to `owner.role`: a single literal is named so, a vector's literals
    /// are owned by `owner_role` (by `role` alone for a variable: `size = [1, 2, 3]`).
    fn value(&mut self, owner: &str, role: &str, value: &Expr) {
        self.value_as(owner, role, value, false);
    }

    fn value_as(&mut self, owner: &str, role: &str, value: &Expr, variable: bool) {
        if let Some(span) = bare_literal(value) {
            let name = SourceName {
                owner: owner.to_string(),
                role: Some(role.to_string()),
            };
            self.naming.source_names.entry(span).or_insert(name);
        } else if let Some(spans) = vector_literals(value) {
            let owner = if owner.is_empty() || variable {
                role.to_string()
            } else {
                format!("{owner}_{role}")
            };
            for span in spans {
                let name = SourceName {
                    owner: owner.clone(),
                    role: None,
                };
                self.naming.source_names.entry(span).or_insert(name);
            }
        }
    }

    fn stmts(&mut self, stmts: &[Stmt], module: Option<&str>) {
        for s in stmts {
            self.stmt(s, module);
        }
    }

    fn stmt(&mut self, s: &Stmt, module: Option<&str>) {
        match &s.kind {
            StmtKind::Assign { name, value } => {
                let n = &name.name;
                match bare_literal(value) {
                    Some(span) if self.main && self.idents.keeps(n, module.is_none()) => {
                        self.naming.variables.insert(span, n.clone());
                    }
                    _ => self.value_as(module.unwrap_or(""), n, value, true),
                }
            }
            StmtKind::ModuleDef { name, params, body } => {
                for p in params {
                    if let Some(d) = &p.default {
                        self.value(&name.name, &p.name.name, d);
                    }
                }
                self.stmts(body, Some(&name.name));
            }
            StmtKind::Block(b) => self.stmts(b, module),
            StmtKind::Instance(i) => match &i.kind {
                InstanceKind::Call {
                    name,
                    args,
                    children,
                } => {
                    if let Some(params) = self.idents.modules.get(&name.name) {
                        let params = params.clone();
                        let mut position = 0;
                        for a in args {
                            let param = match &a.name {
                                Some(n) => Some(n.name.clone()),
                                None => {
                                    position += 1;
                                    params.get(position - 1).cloned()
                                }
                            };
                            if let Some(p) = param {
                                self.value(&name.name, &p, &a.value);
                            }
                        }
                    }
                    self.stmts(children, module);
                }
                InstanceKind::If {
                    then, otherwise, ..
                } => {
                    self.stmts(then, module);
                    if let Some(o) = otherwise {
                        self.stmts(o, module);
                    }
                }
                InstanceKind::For { body, .. }
                | InstanceKind::IntersectionFor { body, .. }
                | InstanceKind::Let { body, .. } => self.stmts(body, module),
            },
            _ => {}
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

    #[test]
    fn comments_in_other_scripts_and_languages_are_transliterated() {
        assert_eq!(id("спинка").as_deref(), Some("spinka"));
        assert_eq!(id("ножка стула").as_deref(), Some("nozhka_stula"));
        assert_eq!(id("Cuerpo del carro").as_deref(), Some("cuerpo"));
        assert_eq!(
            id("Llanta delantera Izquierda").as_deref(),
            Some("llanta_delantera_izquierda")
        );
        assert_eq!(
            id("Tischplatte für die Küche").as_deref(),
            Some("tischplatte")
        );
    }

    #[test]
    fn names_always_have_a_letter() {
        for text in ["1", "2 3", "---", "ℵ₀", "12.5 mm"] {
            if let Some(n) = id(text) {
                assert!(n.chars().any(|c| c.is_ascii_alphabetic()), "{text} → {n}");
                assert!(!n.starts_with(|c: char| c.is_ascii_digit()), "{text} → {n}");
            }
        }
        assert_eq!(id("cylinder 1").as_deref(), Some("cylinder"));
        assert_eq!(id("1"), None);
    }

    #[test]
    fn colour_names_split_into_words() {
        assert_eq!(super::ascii_words("PowderBlue"), vec!["powder", "blue"]);
        assert_eq!(super::ascii_words("white"), vec!["white"]);
    }
}
