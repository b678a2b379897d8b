//! Non-finite numbers: where one is made, and the error when one reaches geometry.
//!
//! OpenSCAD programs may compute with `1/0` (a comparison, a `min`), so an infinite or NaN
//! number is a value like any other until it shapes a part: a size, radius, height,
//! translation, scale, angle or matrix entry. There it is an error located at the number's
//! source. Evaluation remembers where the latest non-finite number was made (a literal
//! like `1e999`, or an operation on finite numbers like `0/0` or `1e308 * 10`); the error
//! points there when it lies inside the argument, and names it as a secondary place
//! otherwise (a variable assigned elsewhere). A part whose composed transform overflows
//! although every argument is finite is an error at the part.

use super::Eval;
use super::value::Value;
use crate::front::ast::{Expr, ExprKind};
use crate::front::diag::{DResult, Diagnostic};
use crate::ir::{Num, Part};
use crate::span::Span;

/// The diagnostic code of a non-finite number in geometry.
const CODE: &str = "E0109";

const NOTE: &str = "sizes, radii, heights, positions, scales and angles must be finite numbers; check for a division by zero or a number too large for a double (above about 1.8e308)";

/// What a non-finite number is, in words.
fn kind(value: f64) -> &'static str {
    if value.is_nan() {
        "this is not a number (NaN), like 0/0"
    } else {
        "this is infinite"
    }
}

impl Eval<'_> {
    /// Records `e` as where a non-finite number was made, when `v` is one and `e` computes
    /// it (a literal, an operator or a call) rather than passing on one made inside it.
    pub(super) fn note_nonfinite(&mut self, e: &Expr, v: &Value) {
        let Value::Num(n) = v else {
            return;
        };
        if n.value.is_finite() {
            return;
        }
        let computes = matches!(
            e.kind,
            ExprKind::Number { .. }
                | ExprKind::Binary(..)
                | ExprKind::Unary(..)
                | ExprKind::Call { .. }
        );
        let made_inside = self.nonfinite_origin.is_some_and(|o| e.span.contains(o));
        if computes && !made_inside {
            self.nonfinite_origin = Some(e.span);
        }
    }

    /// `n`, given at `span` as `what` of a part, must be finite.
    pub(super) fn finite(&self, n: &Num, span: Span, what: &str) -> DResult<()> {
        if n.value.is_finite() {
            return Ok(());
        }
        let d = match self.nonfinite_origin {
            Some(o) if span.contains(o) => self.nonfinite_at(o, n.value),
            origin => {
                let d = Diagnostic::error(CODE, format!("the {what} is not a finite number"))
                    .at(span, kind(n.value));
                match origin {
                    Some(o) => d.with_secondary(o, "the non-finite number was made here"),
                    None => d,
                }
            }
        };
        Err(Box::new(d.with_note(NOTE)))
    }

    fn nonfinite_at(&self, at: Span, value: f64) -> Diagnostic {
        let text = self.sources.snippet(at);
        let shown = if text.chars().count() > 40 || text.contains('\n') {
            "this number".to_string()
        } else {
            format!("`{text}`")
        };
        Diagnostic::error(CODE, format!("{shown} is not a finite number")).at(at, kind(value))
    }

    /// Every number of a part made from finite arguments must still be finite (a chain of
    /// large translations or scales can overflow).
    pub(super) fn finite_part(&self, part: &Part) -> DResult<()> {
        let Some(bad) = super::part_nums(part)
            .into_iter()
            .find(|n| !n.value.is_finite())
        else {
            return Ok(());
        };
        Err(Box::new(
            Diagnostic::error(CODE, "this part's size or position is not a finite number")
                .at(part.span, kind(bad.value))
                .with_note("its arguments are finite, but the transforms around it multiply or add them past the largest double (about 1.8e308)"),
        ))
    }
}
