//! Variations from variant files: the same program with other numbers.
//!
//! A variant file is matched to the model token by token (comments and layout ignored,
//! any number matching any number). The first place where anything else differs is a
//! diagnostic that points into both files. Each slot of the model then takes the variant's
//! number at the same place; a frozen literal (one that decides structure) must not differ.

use crate::front::diag::{DResult, Diagnostic};
use crate::front::source::SourceMap;
use crate::ir::{FreezeReason, Model};
use crate::span::{FileId, Span};
use std::collections::HashMap;
use std::path::Path;

/// One example variation of a model: a value for every slot.
#[derive(Debug, Clone)]
pub struct Variation {
    /// From the file name: `bench.scad` → `bench`.
    pub name: String,
    pub values: Vec<f64>,
}

#[derive(Debug, Clone, PartialEq)]
enum Tok {
    Num(f64),
    Word(String),
    Str(String),
    Punct(String),
}

/// Tokens of an OpenSCAD text with their byte ranges; comments and whitespace dropped.
fn tokens(text: &str) -> Vec<(Tok, usize, usize)> {
    let b = text.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        let start = i;
        if c.is_ascii_whitespace() {
            i += 1;
        } else if text[i..].starts_with("//") {
            i = text[i..].find('\n').map_or(b.len(), |n| i + n);
        } else if text[i..].starts_with("/*") {
            i = text[i + 2..].find("*/").map_or(b.len(), |n| i + 2 + n + 2);
        } else if c.is_ascii_digit() || (c == b'.' && b.get(i + 1).is_some_and(u8::is_ascii_digit))
        {
            while i < b.len() && (b[i].is_ascii_digit() || b[i] == b'.') {
                i += 1;
            }
            if i < b.len() && (b[i] == b'e' || b[i] == b'E') {
                let mut j = i + 1;
                if j < b.len() && (b[j] == b'+' || b[j] == b'-') {
                    j += 1;
                }
                if j < b.len() && b[j].is_ascii_digit() {
                    i = j;
                    while i < b.len() && b[i].is_ascii_digit() {
                        i += 1;
                    }
                }
            }
            let v = text[start..i].parse().unwrap_or(f64::NAN);
            out.push((Tok::Num(v), start, i));
        } else if c.is_ascii_alphabetic() || c == b'_' || c == b'$' {
            while i < b.len() && (b[i].is_ascii_alphanumeric() || b[i] == b'_' || b[i] == b'$') {
                i += 1;
            }
            out.push((Tok::Word(text[start..i].to_string()), start, i));
        } else if c == b'"' {
            i += 1;
            while i < b.len() && b[i] != b'"' {
                i += if b[i] == b'\\' { 2 } else { 1 };
            }
            i = (i + 1).min(b.len());
            out.push((Tok::Str(text[start..i].to_string()), start, i));
        } else {
            let two = text.get(i..i + 2).unwrap_or("");
            let n = if matches!(two, "<=" | ">=" | "==" | "!=" | "&&" | "||") {
                2
            } else {
                1
            };
            let n = text[i..]
                .chars()
                .next()
                .map_or(n, |ch| if n == 1 { ch.len_utf8() } else { n });
            i += n;
            out.push((Tok::Punct(text[start..i].to_string()), start, i));
        }
    }
    out
}

/// Whether `toks[k]` is a unary minus directly in front of a number.
fn negated_number(toks: &[(Tok, usize, usize)], k: usize) -> bool {
    let is_minus = matches!(toks.get(k), Some((Tok::Punct(p), ..)) if p == "-");
    let then_number = matches!(toks.get(k + 1), Some((Tok::Num(_), ..)));
    let unary = match k.checked_sub(1).and_then(|p| toks.get(p)) {
        None => true,
        Some((Tok::Punct(p), ..)) => !matches!(p.as_str(), ")" | "]" | "}"),
        Some(_) => false,
    };
    is_minus && then_number && unary
}

fn describe(t: Option<&(Tok, usize, usize)>) -> String {
    match t {
        None => "the end of the file".into(),
        Some((Tok::Num(_), ..)) => "a number".into(),
        Some((Tok::Word(w) | Tok::Str(w) | Tok::Punct(w), ..)) => format!("`{w}`"),
    }
}

/// Matches the variant file `path` against the model's main file `base`.
pub fn load_variation(
    sources: &mut SourceMap,
    base: FileId,
    model: &Model,
    path: &Path,
) -> DResult<Variation> {
    let bytes = std::fs::read(path).map_err(|e| {
        Box::new(Diagnostic::error(
            "E0400",
            format!("cannot read variation `{}`: {e}", path.display()),
        ))
    })?;
    let text = String::from_utf8_lossy(&bytes).into_owned();
    let file = sources.add(path, text);
    let name = path.file_stem().map_or_else(
        || format!("variation{file}"),
        |s| s.to_string_lossy().into_owned(),
    );
    let ours = tokens(sources.text(base));
    let theirs = tokens(sources.text(file));
    let mut at_number: HashMap<usize, f64> = HashMap::new();
    // Offsets in the variant of each model number, for pointing at them.
    let mut variant_offset: HashMap<usize, usize> = HashMap::new();
    let (mut i, mut j) = (0, 0);
    while i < ours.len() || j < theirs.len() {
        let (a, b) = (ours.get(i), theirs.get(j));
        // A sign may appear or disappear in front of a number: `0` → `-22.5`.
        if let (Some((Tok::Num(_), s, _)), true) = (a, negated_number(&theirs, j))
            && let Some((Tok::Num(v), vs, _)) = theirs.get(j + 1)
        {
            at_number.insert(*s, -v);
            variant_offset.insert(*s, *vs);
            (i, j) = (i + 1, j + 2);
            continue;
        }
        if let (true, Some((Tok::Num(v), vs, _))) = (negated_number(&ours, i), b)
            && let Some((Tok::Num(_), s, _)) = ours.get(i + 1)
        {
            at_number.insert(*s, -v);
            variant_offset.insert(*s, *vs);
            (i, j) = (i + 2, j + 1);
            continue;
        }
        let same = match (a, b) {
            (Some((Tok::Num(_), ..)), Some((Tok::Num(_), ..))) => true,
            (Some((x, ..)), Some((y, ..))) => x == y,
            _ => false,
        };
        if !same {
            let span_of = |t: Option<&(Tok, usize, usize)>, f: FileId, len: usize| {
                t.map_or(Span::new(f, len, len), |&(_, s, e)| Span::new(f, s, e))
            };
            let here = span_of(b, file, sources.text(file).len());
            let there = span_of(a, base, sources.text(base).len());
            return Err(Box::new(
                Diagnostic::error(
                    "E0601",
                    format!("variation `{name}` is not the same program with other numbers"),
                )
                .at(here, format!("the variation has {} here", describe(b)))
                .with_secondary(there, format!("the model has {} here", describe(a)))
                .with_note(
                    "a variation may change numbers only; statements, names and structure must match the model",
                ),
            ));
        }
        if let (Some((Tok::Num(_), s, _)), Some((Tok::Num(v), vs, _))) = (a, b) {
            at_number.insert(*s, *v);
            variant_offset.insert(*s, *vs);
        }
        (i, j) = (i + 1, j + 1);
    }
    for f in &model.frozen {
        if f.span.file != base {
            continue;
        }
        if let Some(&v) = at_number.get(&(f.span.start as usize))
            && v != f.value
        {
            let why = match &f.reason {
                FreezeReason::Structural(w) => format!("it decides structure ({w})"),
                FreezeReason::Product(_) => {
                    "it multiplies another parameter, so it is held constant".into()
                }
            };
            let offset = variant_offset
                .get(&(f.span.start as usize))
                .copied()
                .unwrap_or(0);
            return Err(Box::new(
                Diagnostic::error(
                    "E0602",
                    format!("variation `{name}` changes a number that must stay fixed"),
                )
                .at(
                    Span::new(file, offset, offset + 1),
                    format!("this is {v} here"),
                )
                .with_secondary(f.span, format!("but {} in the model", f.text))
                .with_note(format!("this number is not a parameter: {why}")),
            ));
        }
    }
    let values = model
        .slots
        .iter()
        .map(|s| {
            if s.span.file == base {
                at_number
                    .get(&(s.span.start as usize))
                    .copied()
                    .unwrap_or(s.value)
            } else {
                s.value
            }
        })
        .collect();
    Ok(Variation { name, values })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tokens_skip_comments_and_keep_numbers() {
        let t = tokens("a = -1.5e2; // x\n/* y */ cube([a, .5]);");
        let nums: Vec<f64> = t
            .iter()
            .filter_map(|(k, ..)| if let Tok::Num(v) = k { Some(*v) } else { None })
            .collect();
        assert_eq!(nums, vec![150.0, 0.5]);
        assert!(
            t.iter()
                .all(|(k, ..)| !matches!(k, Tok::Punct(p) if p == "/"))
        );
    }
}
