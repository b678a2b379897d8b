//! Variations from variant files: the same program with other numbers.
//!
//! A variant file is matched to the model token by token (comments and layout ignored,
//! any number matching any number). The first place where anything else differs is a
//! diagnostic that points into both files. Each slot of the model then takes the variant's
//! number at the same place; a frozen literal (one that decides structure) must not differ.

use super::diff;
use super::uncertainty::{Uncertainty, load_sidecar, sidecar_path};
use crate::front::diag::{DResult, Diagnostic};
use crate::front::parse::{Token, TokenKind, tokens};
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
    /// How well each number is known, when the variant has a fit's sidecar (`None`: the
    /// numbers are as good as the noise model says).
    pub uncertainty: Option<Uncertainty>,
}

/// A text and its tokens (the front end's token stream).
pub(super) struct Lexed<'a> {
    pub text: &'a str,
    pub tokens: Vec<Token>,
}

impl<'a> Lexed<'a> {
    pub(super) fn new(text: &'a str) -> Self {
        Lexed {
            text,
            tokens: tokens(text),
        }
    }

    fn get(&self, k: usize) -> Option<&Token> {
        self.tokens.get(k)
    }

    fn is_number(&self, k: usize) -> bool {
        matches!(self.get(k), Some(t) if matches!(t.kind, TokenKind::Number(_)))
    }

    /// Whether token `k` is a unary minus directly in front of a number.
    pub(super) fn negated_number(&self, k: usize) -> bool {
        let is_minus = self
            .get(k)
            .is_some_and(|t| t.kind == TokenKind::Punct && t.text(self.text) == "-");
        let unary = match k.checked_sub(1).and_then(|p| self.get(p)) {
            None => true,
            Some(t) => match t.kind {
                TokenKind::Punct => !matches!(t.text(self.text), ")" | "]" | "}"),
                TokenKind::Path => true,
                TokenKind::Number(_) | TokenKind::Word | TokenKind::Str => false,
            },
        };
        is_minus && self.is_number(k + 1) && unary
    }

    /// Whether tokens `k..k + 4` are a parenthesised negative number, `(-0.23)`.
    fn parenthesised_negative(&self, k: usize) -> bool {
        let punct = |k: usize, p: &str| {
            self.get(k)
                .is_some_and(|t| t.kind == TokenKind::Punct && t.text(self.text) == p)
        };
        punct(k, "(") && punct(k + 1, "-") && self.is_number(k + 2) && punct(k + 3, ")")
    }

    /// How a diagnostic names token `k`.
    fn describe(&self, k: usize) -> String {
        match self.get(k) {
            None => "the end of the file".into(),
            Some(t) if matches!(t.kind, TokenKind::Number(_)) => "a number".into(),
            Some(t) => format!("`{}`", t.text(self.text)),
        }
    }

    /// The span of token `k` in `file`, or an empty one at the end.
    fn span(&self, k: usize, file: FileId) -> Span {
        let len = self.text.len();
        self.get(k).map_or(Span::new(file, len, len), |t| {
            Span::new(file, t.start, t.end)
        })
    }
}

/// Whether two tokens match: any number matches any number, anything else itself.
fn same(model: &Lexed<'_>, i: usize, variant: &Lexed<'_>, j: usize) -> bool {
    match (model.get(i), variant.get(j)) {
        (Some(a), Some(b)) => match (a.kind, b.kind) {
            (TokenKind::Number(_), TokenKind::Number(_)) => true,
            (x, y) => x == y && a.text(model.text) == b.text(variant.text),
        },
        _ => false,
    }
}

/// The variant's number at each number of the model: the model number's offset → the
/// variant's value and the offset where the variant writes it.
type Numbers = HashMap<usize, (f64, usize)>;

/// The value of the number token `k` (a negated number's when `negated`) with its offset.
fn number_at(lexed: &Lexed<'_>, k: usize, negated: bool) -> Option<(f64, usize)> {
    let t = lexed.get(k)?;
    let TokenKind::Number(v) = t.kind else {
        return None;
    };
    Some((if negated { -v } else { v }, t.start))
}

/// Matches the variant's tokens to the model's; on the first place where anything but a
/// number (or a sign in front of one, or a negative number in parentheses) differs, returns the indices of the two tokens there.
fn match_tokens(model: &Lexed<'_>, variant: &Lexed<'_>) -> Result<Numbers, (usize, usize)> {
    let mut numbers = Numbers::new();
    let (mut i, mut j) = (0, 0);
    while i < model.tokens.len() || j < variant.tokens.len() {
        // A number may become a parenthesised negative one (how `fit` writes a number that
        // went below zero, so that `x - 0` does not become `x - -0.23`): `0` → `(-0.23)`.
        if let Some(at) = model.get(i)
            && model.is_number(i)
            && variant.parenthesised_negative(j)
            && let Some(value) = number_at(variant, j + 2, true)
        {
            numbers.insert(at.start, value);
            (i, j) = (i + 1, j + 4);
            continue;
        }
        // A sign may appear or disappear in front of a number: `0` → `-22.5`.
        if let (Some(at), true) = (model.get(i), variant.negated_number(j))
            && model.is_number(i)
            && let Some(value) = number_at(variant, j + 1, true)
        {
            numbers.insert(at.start, value);
            (i, j) = (i + 1, j + 2);
            continue;
        }
        if model.negated_number(i)
            && let Some(at) = model.get(i + 1)
            && let Some(value) = number_at(variant, j, true)
        {
            numbers.insert(at.start, value);
            (i, j) = (i + 2, j + 1);
            continue;
        }
        if !same(model, i, variant, j) {
            return Err((i, j));
        }
        if let (Some(at), Some(value)) = (model.get(i), number_at(variant, j, false)) {
            numbers.insert(at.start, value);
        }
        (i, j) = (i + 1, j + 1);
    }
    Ok(numbers)
}

/// Matches the variant file `path` against the model's main file `base`.
pub fn load_variation(
    sources: &mut SourceMap,
    base: FileId,
    model: &Model,
    path: &Path,
) -> DResult<Variation> {
    load_variation_calling(sources, base, model, path, None)
}

/// Like [`load_variation`] for a model read with `--call`: the variant gets the same call
/// appended, as the model did.
pub fn load_variation_calling(
    sources: &mut SourceMap,
    base: FileId,
    model: &Model,
    path: &Path,
    call: Option<&str>,
) -> DResult<Variation> {
    let canonical = |p: &Path| std::fs::canonicalize(p).ok();
    if canonical(path).is_some_and(|v| Some(v) == canonical(sources.path(base))) {
        return Err(Box::new(
            Diagnostic::error(
                "E0603",
                format!("the variation `{}` is the model itself", path.display()),
            )
            .with_note("a variation is another file: the model with other numbers (a bench made from the chair)"),
        ));
    }
    let bytes = std::fs::read(path).map_err(|e| {
        Box::new(Diagnostic::error(
            "E0400",
            format!("cannot read variation `{}`: {e}", path.display()),
        ))
    })?;
    let mut text = String::from_utf8_lossy(&bytes).into_owned();
    if let Some(call) = call {
        text.push_str(&crate::front::call::appended(call));
    }
    let file = sources.add(path, text);
    let name = path.file_stem().map_or_else(
        || format!("variation{file}"),
        |s| s.to_string_lossy().into_owned(),
    );
    let ours = Lexed::new(sources.text(base));
    let theirs = Lexed::new(sources.text(file));
    let numbers = match_tokens(&ours, &theirs).map_err(|(i, j)| {
        let model = At {
            file: base,
            lexed: &ours,
            token: i,
        };
        let variant = At {
            file,
            lexed: &theirs,
            token: j,
        };
        mismatch(sources, &name, &model, &variant)
    })?;
    check_frozen(model, base, file, &name, &numbers)?;
    let values = model
        .slots
        .iter()
        .map(|s| {
            if s.span.file == base {
                numbers
                    .get(&(s.span.start as usize))
                    .map_or(s.value, |&(v, _)| v)
            } else {
                s.value
            }
        })
        .collect::<Vec<f64>>();
    let uncertainty = load_sidecar(path, &values).map_err(|why| {
        Box::new(Diagnostic::error(
            "E0604",
            format!(
                "the uncertainty sidecar `{}` of the variation `{}` cannot be used: {why}",
                sidecar_path(path).display(),
                path.display()
            ),
        ))
    })?;
    Ok(Variation {
        name,
        values,
        uncertainty,
    })
}

/// Where one side of the comparison (the model or the variant) stops matching the other.
struct At<'s, 'a> {
    file: FileId,
    lexed: &'s Lexed<'a>,
    /// The index of the token that differs (the number of tokens: the end of the file).
    token: usize,
}

impl At<'_, '_> {
    fn span(&self) -> Span {
        self.lexed.span(self.token, self.file)
    }

    fn describe(&self) -> String {
        self.lexed.describe(self.token)
    }

    /// The side as the diff of lines sees it.
    fn diff_side<'d>(&'d self, sources: &'d SourceMap) -> diff::Side<'d> {
        let at = self
            .lexed
            .get(self.token)
            .map_or(self.lexed.text.len(), |t| t.start);
        diff::Side {
            path: sources.path(self.file),
            lexed: self.lexed,
            at,
        }
    }
}

/// The diagnostic for a variant that stops matching the model, with the differing lines
/// as a diff.
fn mismatch(
    sources: &SourceMap,
    name: &str,
    model: &At<'_, '_>,
    variant: &At<'_, '_>,
) -> Box<Diagnostic> {
    let mut diag = Diagnostic::error(
        "E0601",
        format!("variation `{name}` is not the same program with other numbers"),
    )
    .at(
        variant.span(),
        format!("the variation has {} here", variant.describe()),
    )
    .with_secondary(
        model.span(),
        format!("the model has {} here", model.describe()),
    )
    .with_note(
        "a variation may change numbers only; statements, names and structure must match the model",
    );
    let sides = (model.diff_side(sources), variant.diff_side(sources));
    if let Some(lines) = diff::differing_lines(&sides.0, &sides.1) {
        diag = diag.with_note(lines);
    }
    Box::new(diag)
}

/// Refuses a variant that changes a frozen literal (one that decides structure).
fn check_frozen(
    model: &Model,
    base: FileId,
    file: FileId,
    name: &str,
    numbers: &Numbers,
) -> DResult<()> {
    for f in &model.frozen {
        if f.span.file != base {
            continue;
        }
        let Some(&(v, offset)) = numbers.get(&(f.span.start as usize)) else {
            continue;
        };
        if v == f.value {
            continue;
        }
        let why = match &f.reason {
            FreezeReason::Structural(w) => format!("it decides structure ({w})"),
            FreezeReason::Product(_) => {
                "it multiplies another parameter, so it is held constant".into()
            }
        };
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
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fitted_numbers_below_zero_load_back() {
        // What `fit` writes when a number goes below zero, wherever it stands.
        let model = "w = 2; translate([0, 5 - 1, 0]) cube([w, 3, 1]);";
        let fitted = "w = (-0.5); translate([(-0.23), 5 - (-1.5), 0]) cube([w, 3, 1]);";
        let numbers = match_tokens(&Lexed::new(model), &Lexed::new(fitted)).unwrap();
        let mut got: Vec<(usize, f64)> = numbers.iter().map(|(&k, &(v, _))| (k, v)).collect();
        got.sort_by_key(|g| g.0);
        let values: Vec<f64> = got.iter().map(|g| g.1).collect();
        assert_eq!(values, vec![-0.5, -0.23, 5.0, -1.5, 0.0, 3.0, 1.0]);
        // Anything else in parentheses is still a change of structure.
        assert!(
            match_tokens(
                &Lexed::new(model),
                &Lexed::new(&fitted.replace("(-0.23)", "(0.23)"))
            )
            .is_err()
        );
    }

    #[test]
    fn tokens_skip_comments_and_keep_numbers() {
        let text = "a = -1.5e2; // x\n/* y */ cube([a, .5]);";
        let t = tokens(text);
        let nums: Vec<f64> = t
            .iter()
            .filter_map(|k| {
                if let TokenKind::Number(v) = k.kind {
                    Some(v)
                } else {
                    None
                }
            })
            .collect();
        assert_eq!(nums, vec![150.0, 0.5]);
        assert!(t.iter().all(|k| k.text(text) != "/"));
    }
}
