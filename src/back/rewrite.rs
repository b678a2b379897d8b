//! Writing a model back with other numbers.
//!
//! The same program text with each slot's literal replaced by a new value: what a variant
//! file is (the output of `fit`, the input of `--vary`). Only the literals' bytes change, so
//! comments, layout and structure survive exactly. The re-parameterized output is
//! spliced alike: each literal becomes its expression ([`replacement`]) and the statements
//! of a part switch are found for their guards ([`guard_statements`]).

use super::expr::format_expression;
use crate::analysis::reparam::Expression;
use crate::front::eval::format_number;
use crate::ir::{Model, Slot};
use crate::span::{FileId, Span};
use std::collections::{BTreeSet, HashMap};

/// `text` (the file `file`) with the literal of every slot in that file set to `values[slot]`.
/// A negative value replacing a literal is parenthesised so `-` signs in front stay right,
/// unless the literal stands alone (a vector element, an argument, an assignment's value):
/// there a plain `-` reads the same, and the file stays the same program token for token
/// (a `--vary` file).
pub fn with_slot_values(text: &str, file: FileId, slots: &[Slot], values: &[f64]) -> String {
    let alone = |at: usize| {
        prev_char(text, at).is_none_or(|(_, c)| matches!(c, '[' | '(' | ',' | '=' | '{' | ';'))
    };
    let mut edits: Vec<(std::ops::Range<usize>, String)> = slots
        .iter()
        .filter(|s| s.span.file == file)
        .filter(|s| values[s.id as usize] != s.value)
        .map(|s| {
            let v = round_for_source(values[s.id as usize]);
            let t = format_number(v);
            let r = s.span.range();
            let t = if v < 0.0 && !alone(r.start) {
                format!("({t})")
            } else {
                t
            };
            (r, t)
        })
        .collect();
    edits.sort_by_key(|(r, _)| r.start);
    let mut out = String::with_capacity(text.len() + 16 * edits.len());
    let mut at = 0;
    for (r, t) in edits {
        out.push_str(&text[at..r.start]);
        out.push_str(&t);
        at = r.end;
    }
    out.push_str(&text[at..]);
    out
}

/// Rounds to 10 significant digits, so written files read well and re-read exactly.
pub fn round_for_source(v: f64) -> f64 {
    if v == 0.0 || !v.is_finite() {
        return v;
    }
    let digits = 10 - 1 - v.abs().log10().floor() as i32;
    let k = 10f64.powi(digits.clamp(-300, 300));
    (v * k).round() / k
}

/// The previous non-space character before byte `at`, and its offset.
fn prev_char(text: &str, at: usize) -> Option<(usize, char)> {
    text[..at]
        .char_indices()
        .rev()
        .find(|(_, c)| !c.is_whitespace())
}

/// The next non-space character from byte `at`.
fn next_char(text: &str, at: usize) -> Option<char> {
    text[at..].chars().find(|c| !c.is_whitespace())
}

/// The text replacing a slot's literal: its expression, taking in a unary minus written in
/// front of the literal, and parenthesised unless the literal stands alone (a vector
/// element, an argument, an assignment's value). Returns the span replaced (the literal,
/// or the literal and its minus) and the text.
pub fn replacement(text: &str, span: Span, e: &Expression, names: &[String]) -> (Span, String) {
    let (start, end) = (span.start as usize, span.end as usize);
    let opens = |c: Option<(usize, char)>| {
        c.is_none_or(|(_, c)| matches!(c, '[' | '(' | ',' | '=' | '?' | ':' | '{' | ';'))
    };
    let (from, expr) = match prev_char(text, start) {
        Some((p, '-')) if opens(prev_char(text, p)) => {
            let neg = Expression {
                constant: -e.constant,
                terms: e.terms.iter().map(|&(i, a)| (i, -a)).collect(),
            };
            (p, format_expression(&neg, names))
        }
        _ => (start, format_expression(e, names)),
    };
    let alone = matches!(prev_char(text, from), Some((_, '[' | '(' | ',' | '=')))
        && matches!(next_char(text, end), Some(',' | ']' | ')' | ';'));
    let simple = expr
        .chars()
        .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '.');
    let body = if alone || simple {
        expr
    } else {
        format!("({expr})")
    };
    (Span::new(span.file, from, end), body)
}

/// The outermost statements (in the file `main`) that make only parts of `group`: what an
/// `if` guards to switch the group off. `None` when some part of the group is made only by
/// statements that make other parts too.
pub fn guard_statements(model: &Model, group: &[usize], main: FileId) -> Option<Vec<Span>> {
    let mut makers: HashMap<Span, BTreeSet<usize>> = HashMap::new();
    for (i, p) in model.parts.iter().enumerate() {
        for s in &p.statements {
            makers.entry(*s).or_default().insert(i);
        }
    }
    let makes_only_group = |s: &Span| {
        makers
            .get(s)
            .is_some_and(|m| m.iter().all(|q| group.contains(q)))
    };
    let mut out = BTreeSet::new();
    for &p in group {
        let s = model.parts[p]
            .statements
            .iter()
            .find(|s| s.file == main && makes_only_group(s))?;
        out.insert(*s);
    }
    Some(out.into_iter().collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::span::Span;

    fn slot(id: u32, start: usize, end: usize, value: f64) -> Slot {
        Slot {
            id,
            name: format!("s{id}"),
            variable: None,
            authored: false,
            position: false,
            value,
            span: Span::new(0, start, end),
            text: String::new(),
        }
    }

    #[test]
    fn replaces_only_changed_literals() {
        let text = "cube([10, 20, 30]); // keep";
        let slots = [
            slot(0, 6, 8, 10.0),
            slot(1, 10, 12, 20.0),
            slot(2, 14, 16, 30.0),
        ];
        let out = with_slot_values(text, 0, &slots, &[12.5, 20.0, -3.0]);
        assert_eq!(out, "cube([12.5, 20, -3]); // keep");
        // After an operator, a negative value keeps its sign apart.
        let text = "x = 2 - 10;";
        let out = with_slot_values(
            text,
            0,
            &[slot(0, 4, 5, 2.0), slot(1, 8, 10, 10.0)],
            &[-1.0, -3.0],
        );
        assert_eq!(out, "x = -1 - (-3);");
    }

    #[test]
    fn rounding_keeps_ten_digits() {
        assert_eq!(round_for_source(0.1 + 0.2), 0.3);
        assert_eq!(round_for_source(123456.78901234), 123456.789);
    }
}
