//! pest failures as diagnostics.
//!
//! pest reports the furthest position it reached and what it tried there: rules (its
//! "positives") and, when error detail is on, literal tokens. This module boils both down
//! to a few human words (`` `;` ``, "an expression", "a statement"), says what was found
//! instead, and adds what a scan of the text knows: the statement being written ("expected
//! `;` after assignment"), the bracket still open, the line a missing `;` belongs to.

use super::scan::{Context, Scanned, context_at};
use super::{OpenScadParser, Rule, SYNTAX_ERROR, point, precedence, too_deep};
use crate::front::ast::Comment;
use crate::front::diag::Diagnostic;
use crate::span::{FileId, Span};
use pest::Parser;
use pest::error::{Error, ErrorVariant, InputLocation};
use pest::set_error_detail;
use std::sync::{Mutex, PoisonError};

type PestError = Error<Rule>;

/// The tokens worth naming in an "expected ..." message, in the order they are listed.
const TOKENS: [&str; 9] = [";", ",", ")", "]", "}", ":", "=", "(", "{"];

/// Converts a failed parse of `text` into a diagnostic.
pub(super) fn from_pest(
    file: FileId,
    text: &str,
    scanned: &Scanned,
    err: &PestError,
) -> Box<Diagnostic> {
    if let ErrorVariant::CustomError { .. } = err.variant {
        // pest's own guards ("stack limit reached", "call limit reached") only trip on
        // input nested far beyond what the depth check accepts.
        return too_deep(file, text, offset_of(err));
    }
    let detailed = detailed_error(text);
    let err = detailed.as_ref().unwrap_or(err);
    let (offset, context, expected) = expectation(text, err);
    let found = found(text, offset);

    let mut diag = expected
        .message(text, &context, &found)
        .at(point(file, text, offset), format!("unexpected {found}"));
    if let Some((at, bracket)) = context.open
        && (offset >= text.len() || expected.tokens.contains(&closer(bracket)))
    {
        let label = format!("this `{}` is still open", bracket as char);
        diag = diag.with_secondary(Span::new(file, at, at + 1), label);
    }
    if expected.only(";")
        && let Some(end) = previous_line_end(text, &scanned.comments, offset)
    {
        let start = floor_char(text, end - 1);
        diag = diag.with_secondary(Span::new(file, start, end), "expected `;` after this");
    }
    if let Some(note) = expected.note(&found) {
        diag = diag.with_note(note);
    }
    Box::new(diag)
}

/// Where the error is, and what was expected there. pest places its error at the
/// furthest rule it tried, and lists the literal tokens tried furthest, which may be
/// further on: that place is better when those tokens are worth naming.
fn expectation(text: &str, err: &PestError) -> (usize, Context, Expected) {
    let rule_offset = offset_of(err);
    if let Some(attempts) = err.parse_attempts()
        && attempts.max_position > rule_offset
    {
        let offset = attempts.max_position;
        let context = context_at(text, offset);
        let expected = Expected::from_error(err, false, &context);
        if !expected.items().is_empty() {
            return (offset, context, expected);
        }
    }
    let context = context_at(text, rule_offset);
    let expected = Expected::from_error(err, true, &context);
    (rule_offset, context, expected)
}

fn offset_of(err: &PestError) -> usize {
    match err.location {
        InputLocation::Pos(pos) => pos,
        InputLocation::Span((start, _)) => start,
    }
}

/// Parses `text` again with pest's error detail on, which lists the literal tokens it
/// tried. The switch is process-wide; a count keeps it on while any such parse runs.
fn detailed_error(text: &str) -> Option<PestError> {
    static USERS: Mutex<usize> = Mutex::new(0);
    {
        let mut users = USERS.lock().unwrap_or_else(PoisonError::into_inner);
        *users += 1;
        set_error_detail(true);
    }
    let err = OpenScadParser::parse(Rule::program, text).err();
    {
        let mut users = USERS.lock().unwrap_or_else(PoisonError::into_inner);
        *users = users.saturating_sub(1);
        if *users == 0 {
            set_error_detail(false);
        }
    }
    err.filter(|e| {
        e.parse_attempts().is_some() && matches!(e.variant, ErrorVariant::ParsingError { .. })
    })
}

/// What would have been accepted at the error position, in human categories.
#[derive(Debug, Default)]
struct Expected {
    tokens: Vec<&'static str>,
    expression: bool,
    statement: bool,
    name: bool,
    operator: bool,
    end: bool,
}

impl Expected {
    /// The rules pest tried at its error position (`at_rules`), or else the literal
    /// tokens it tried furthest, in human categories.
    fn from_error(err: &PestError, at_rules: bool, context: &Context) -> Self {
        let mut expected = Expected::default();
        let attempts = err.parse_attempts();
        if let ErrorVariant::ParsingError { positives, .. } = &err.variant
            && at_rules
        {
            for &rule in positives {
                expected.add_rule(rule);
            }
        }
        let tokens_here = attempts
            .as_ref()
            .is_some_and(|a| !at_rules || a.max_position == offset_of(err));
        if let Some(attempts) = attempts.filter(|_| tokens_here) {
            // Literal tokens display as themselves (ranges and case-insensitive ones never
            // match a listed token).
            for token in attempts.expected_tokens() {
                expected.add_token(&token.to_string());
            }
        }
        expected.tidy(context);
        expected
    }

    fn add_token(&mut self, token: &str) {
        if matches!(token, "module" | "include" | "use" | "#") {
            // Only a statement starts with these.
            self.statement = true;
        }
        if let Some(&known) = TOKENS.iter().find(|&&t| t == token)
            && !self.tokens.contains(&known)
        {
            self.tokens.push(known);
        }
    }

    fn add_rule(&mut self, rule: Rule) {
        match rule {
            Rule::empty_stmt => self.add_token(";"),
            Rule::block | Rule::child_block => self.add_token("{"),
            Rule::EOI => self.end = true,
            Rule::ident | Rule::param | Rule::params | Rule::binding | Rule::bindings => {
                self.name = true;
            }
            Rule::instance
            | Rule::call_stmt
            | Rule::if_stmt
            | Rule::modifier
            | Rule::module_id
            | Rule::assignment
            | Rule::module_def
            | Rule::function_def
            | Rule::include_stmt
            | Rule::include_kind
            | Rule::kw_module => self.statement = true,
            _ if precedence::binary_op(rule).is_some() => self.operator = true,
            _ if precedence::is_level(rule) => self.expression = true,
            Rule::prefix_op
            | Rule::paren
            | Rule::bracket
            | Rule::lit_true
            | Rule::lit_false
            | Rule::lit_undef
            | Rule::number
            | Rule::string
            | Rule::fn_literal
            | Rule::let_expr
            | Rule::assert_expr
            | Rule::echo_expr
            | Rule::lc_for
            | Rule::lc_if
            | Rule::lc_each
            | Rule::arg
            | Rule::args
            | Rule::kw_function
            | Rule::kw_let
            | Rule::kw_assert
            | Rule::kw_echo
            | Rule::kw_for
            | Rule::kw_if
            | Rule::kw_each => self.expression = true,
            // Continuations of what is already complete, or too vague to name.
            _ => {}
        }
    }

    /// Drops tokens that only continue or start an expression when those are implied.
    fn tidy(&mut self, context: &Context) {
        if self.statement {
            // Where a statement may start, a name or `function` starts one, not an expression.
            self.expression = false;
            self.name = false;
        }
        if self.statement
            && context.open.is_none_or(|(_, b)| b == b'{')
            && context.statement.is_none()
        {
            // Between statements, `;` and `{` are just statements.
            self.tokens.retain(|&t| t != ";" && t != "{");
        }
        let (operator, expression) = (self.operator, self.expression);
        self.tokens.retain(|&t| match t {
            "(" => !operator && !expression,
            "=" => !operator,
            _ => true,
        });
        self.tokens
            .sort_by_key(|t| TOKENS.iter().position(|k| k == t));
    }

    fn only(&self, token: &str) -> bool {
        self.tokens == [token] && !self.expression && !self.statement && !self.name
    }

    fn items(&self) -> Vec<String> {
        let mut items: Vec<String> = self.tokens.iter().map(|t| format!("`{t}`")).collect();
        if self.expression {
            items.push("an expression".into());
        } else if self.name {
            items.push("a name".into());
        }
        if self.statement {
            items.push("a statement".into());
        }
        if items.is_empty() && self.operator {
            items.push("an operator".into());
        }
        if items.is_empty() && self.end {
            items.push("end of file".into());
        }
        items
    }

    fn message(&self, text: &str, context: &Context, found: &str) -> Diagnostic {
        let closer = found.strip_prefix('`').and_then(|f| f.strip_suffix('`'));
        if let Some(c @ (")" | "]" | "}")) = closer
            && !self.tokens.contains(&c)
            && (self.statement || self.end)
        {
            return Diagnostic::error(SYNTAX_ERROR, format!("unmatched `{c}`"));
        }
        let items = self.items();
        if items.is_empty() {
            return Diagnostic::error(SYNTAX_ERROR, "syntax error");
        }
        let mut message = format!("expected {}", join_or(&items));
        if self.only(";")
            && let Some(what) = context.statement.and_then(|s| statement_kind(&text[s..]))
        {
            message = format!("{message} after {what}");
        }
        Diagnostic::error(SYNTAX_ERROR, message)
    }

    fn note(&self, found: &str) -> Option<String> {
        if found == "`=`" && self.operator {
            return Some("to compare two values, use `==`".into());
        }
        let word = found.strip_prefix('`')?.strip_suffix('`')?;
        if (self.name || self.expression) && is_keyword(word) {
            return Some(format!(
                "`{word}` is a keyword and cannot be used as a name"
            ));
        }
        None
    }
}

/// "a", "a or b", "a, b or c".
fn join_or(items: &[String]) -> String {
    match items {
        [] => String::new(),
        [one] => one.clone(),
        [init @ .., last] => format!("{} or {last}", init.join(", ")),
    }
}

fn closer(open: u8) -> &'static str {
    match open {
        b'(' => ")",
        b'[' => "]",
        _ => "}",
    }
}

fn is_keyword(word: &str) -> bool {
    matches!(
        word,
        "module"
            | "function"
            | "if"
            | "else"
            | "let"
            | "assert"
            | "echo"
            | "for"
            | "each"
            | "true"
            | "false"
            | "undef"
    )
}

/// What kind of statement `text` (from the statement's first token on) starts.
fn statement_kind(text: &str) -> Option<&'static str> {
    let word_len = text
        .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_' || c == '$'))
        .unwrap_or(text.len());
    let (word, rest) = text.split_at(word_len);
    let rest = rest.trim_start();
    match word {
        "function" => Some("function definition"),
        "module" => Some("module definition"),
        "" => None,
        _ if rest.starts_with('=') && !rest.starts_with("==") => Some("assignment"),
        _ => None,
    }
}

/// How to name what is at `offset`: a word, a string, a character, or the end.
fn found(text: &str, offset: usize) -> String {
    let rest = text.get(offset..).unwrap_or("");
    let Some(c) = rest.chars().next() else {
        return "end of file".into();
    };
    if c == '"' {
        return "a string".into();
    }
    let word: String = rest
        .chars()
        .take_while(|c| c.is_ascii_alphanumeric() || *c == '_' || *c == '$')
        .take(40)
        .collect();
    if word.is_empty() {
        format!("`{}`", c.escape_debug())
    } else {
        format!("`{word}`")
    }
}

/// The end of the last token before `offset`, when it is on an earlier line.
fn previous_line_end(text: &str, comments: &[Comment], offset: usize) -> Option<usize> {
    let offset = floor_char(text, offset.min(text.len()));
    let mut end = offset;
    loop {
        end = text[..end].trim_end().len();
        let i = comments.partition_point(|c| (c.span.end as usize) < end);
        match comments.get(i) {
            Some(c) if c.span.end as usize == end && (c.span.start as usize) < end => {
                end = c.span.start as usize;
            }
            _ => break,
        }
    }
    (end > 0 && text[end..offset].contains('\n')).then_some(end)
}

fn floor_char(text: &str, mut at: usize) -> usize {
    while !text.is_char_boundary(at) {
        at -= 1;
    }
    at
}
