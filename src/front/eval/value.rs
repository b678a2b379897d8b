//! Run-time values of the OpenSCAD language.
//!
//! Numbers are [`Num`]s, so every value that reaches geometry still knows which slots it
//! depends on. Vectors and strings are reference counted: OpenSCAD values are immutable and
//! copied freely.

use crate::front::ast::{Expr, Param};
use crate::ir::Num;
use crate::tolerance::RANGE_STEP_SLACK;
use std::fmt;
use std::rc::Rc;

use super::scope::Scope;

#[derive(Debug, Clone)]
pub enum Value {
    Undef,
    Bool(bool),
    Num(Num),
    Str(Rc<str>),
    Vector(Rc<Vec<Value>>),
    Range(Rc<RangeValue>),
    Function(Rc<Closure>),
}

/// `[start : step : end]` with its numbers.
#[derive(Debug, Clone)]
pub struct RangeValue {
    pub start: Num,
    pub step: Num,
    pub end: Num,
}

impl RangeValue {
    /// The values a `for` loop visits: `start + k·step` while within `end`; OpenSCAD visits
    /// nothing when the step points away from `end` and limits ranges to 10,000,000 steps.
    pub fn count(&self) -> usize {
        let (s, st, e) = (self.start.value, self.step.value, self.end.value);
        if st == 0.0 || !s.is_finite() || !st.is_finite() || !e.is_finite() {
            return 0;
        }
        if (st > 0.0 && s > e) || (st < 0.0 && s < e) {
            return 0;
        }
        // Float-to-int casts saturate, so a huge range is capped, never wrapped.
        let steps = ((e - s) / st + RANGE_STEP_SLACK).floor();
        if steps >= 10_000_000.0 {
            return 10_000_000;
        }
        steps as usize + 1
    }
}

/// A function value: parameters, body and the scope it was defined in.
#[derive(Debug)]
pub struct Closure {
    pub name: String,
    pub params: Vec<Param>,
    pub body: Expr,
    pub scope: Rc<Scope>,
}

impl Value {
    pub fn num(n: Num) -> Value {
        Value::Num(n)
    }

    pub fn constant(v: f64) -> Value {
        Value::Num(Num::constant(v))
    }

    pub fn type_name(&self) -> &'static str {
        match self {
            Value::Undef => "undef",
            Value::Bool(_) => "a boolean",
            Value::Num(_) => "a number",
            Value::Str(_) => "a string",
            Value::Vector(_) => "a vector",
            Value::Range(_) => "a range",
            Value::Function(_) => "a function",
        }
    }

    pub fn as_num(&self) -> Option<&Num> {
        match self {
            Value::Num(n) => Some(n),
            _ => None,
        }
    }

    pub fn as_vec(&self) -> Option<&[Value]> {
        match self {
            Value::Vector(v) => Some(v),
            _ => None,
        }
    }

    pub fn is_undef(&self) -> bool {
        matches!(self, Value::Undef)
    }
}

impl fmt::Display for Value {
    /// OpenSCAD's `str()` rendering.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Value::Undef => write!(f, "undef"),
            Value::Bool(b) => write!(f, "{b}"),
            Value::Num(n) => write!(f, "{}", format_number(n.value)),
            Value::Str(s) => write!(f, "{s}"),
            Value::Vector(v) => {
                write!(f, "[")?;
                for (i, x) in v.iter().enumerate() {
                    if i > 0 {
                        write!(f, ", ")?;
                    }
                    match x {
                        Value::Str(s) => write!(f, "\"{s}\"")?,
                        other => write!(f, "{other}")?,
                    }
                }
                write!(f, "]")
            }
            Value::Range(r) => write!(
                f,
                "[{} : {} : {}]",
                format_number(r.start.value),
                format_number(r.step.value),
                format_number(r.end.value)
            ),
            Value::Function(_) => write!(f, "function"),
        }
    }
}

/// Numbers as OpenSCAD prints them: shortest round-trip form, `inf`, `nan`.
pub fn format_number(v: f64) -> String {
    if v.is_nan() {
        "nan".into()
    } else if v.is_infinite() {
        if v > 0.0 { "inf".into() } else { "-inf".into() }
    } else if v == v.trunc() && v.abs() < 1e15 {
        format!("{}", v as i64)
    } else {
        format!("{v}")
    }
}
