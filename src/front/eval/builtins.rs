//! OpenSCAD's built-in functions.
//!
//! Math follows OpenSCAD 2021.01 exactly where models can see it: trigonometry is in
//! degrees and exact at multiples of 30° and 45° (OpenSCAD's `sin_degrees`), `round` rounds
//! half away from zero. Non-linear results keep their slots as `NonAffine` dependencies, so
//! a size computed with `sqrt` is exact in value and freezes what it needs if a relation
//! uses it.

use super::Eval;
use super::scope::Scope;
use super::value::Value;
use crate::front::ast::Arg;
use crate::front::diag::{DResult, Diagnostic};
use crate::ir::Num;
use crate::span::Span;
use std::rc::Rc;

/// `sin` of an angle in degrees, exact at multiples of 30° and 45° (OpenSCAD's rule).
pub fn sin_degrees(x: f64) -> f64 {
    if !x.is_finite() {
        return f64::NAN;
    }
    let mut x = x % 360.0;
    if x < 0.0 {
        x += 360.0;
    }
    let oppose = x >= 180.0;
    if oppose {
        x -= 180.0;
    }
    if x > 90.0 {
        x = 180.0 - x;
    }
    let r = if x < 45.0 {
        if x == 30.0 { 0.5 } else { x.to_radians().sin() }
    } else if x == 45.0 {
        std::f64::consts::FRAC_1_SQRT_2
    } else if x == 60.0 {
        3f64.sqrt() / 2.0
    } else {
        (90.0 - x).to_radians().cos()
    };
    if oppose { -r } else { r }
}

/// `cos` of an angle in degrees, exact at multiples of 30° and 45°.
pub fn cos_degrees(x: f64) -> f64 {
    if !x.is_finite() {
        return f64::NAN;
    }
    let mut x = x % 360.0;
    if x < 0.0 {
        x += 360.0;
    }
    let mut oppose = x >= 180.0;
    if oppose {
        x -= 180.0;
    }
    if x > 90.0 {
        x = 180.0 - x;
        oppose = !oppose;
    }
    let r = if x > 45.0 {
        if x == 60.0 {
            0.5
        } else {
            (90.0 - x).to_radians().sin()
        }
    } else if x == 45.0 {
        std::f64::consts::FRAC_1_SQRT_2
    } else if x == 30.0 {
        3f64.sqrt() / 2.0
    } else {
        x.to_radians().cos()
    };
    if oppose { -r } else { r }
}

impl Eval<'_> {
    /// Evaluates a built-in function call; `None` if `name` is not a built-in.
    pub fn builtin_function(
        &mut self,
        name: &str,
        args: &[Arg],
        span: Span,
        scope: &Rc<Scope>,
    ) -> DResult<Option<Value>> {
        if !is_builtin_function(name) {
            return Ok(None);
        }
        let mut vals = Vec::with_capacity(args.len());
        for a in args {
            vals.push(self.expr(&a.value, scope)?);
        }
        if let Some(v) = math_function(name, &vals) {
            return Ok(Some(v));
        }
        if let Some(v) = self.value_function(name, &vals) {
            return Ok(Some(v));
        }
        if matches!(name, "rands" | "search") {
            return Err(Box::new(
                Diagnostic::error("E0201", format!("`{name}` is not supported yet"))
                    .at(span, "unsupported built-in function")
                    .with_note(if name == "rands" {
                        "random numbers make the model differ from run to run; write the numbers out"
                    } else {
                        "`search` is not implemented in reparamc's evaluator"
                    }),
            ));
        }
        Ok(None)
    }

    /// The built-in functions of lists, text and types; `None` for any other name.
    fn value_function(&mut self, name: &str, vals: &[Value]) -> Option<Value> {
        Some(match name {
            "len" => match vals.first() {
                Some(Value::Vector(v)) => Value::constant(v.len() as f64),
                Some(Value::Str(s)) => Value::constant(s.chars().count() as f64),
                _ => Value::Undef,
            },
            "concat" => {
                let mut out = Vec::new();
                for v in vals {
                    match v {
                        Value::Vector(items) => out.extend(items.iter().cloned()),
                        other => out.push(other.clone()),
                    }
                }
                Value::Vector(Rc::new(out))
            }
            "str" => {
                let mut s = String::new();
                for v in vals {
                    self.freeze_value(v, "text made with `str`");
                    s.push_str(&v.to_string());
                }
                Value::Str(s.into())
            }
            "chr" => {
                let mut s = String::new();
                for v in vals {
                    if let Value::Num(n) = v {
                        s.extend(char::from_u32(n.value as u32));
                    }
                }
                Value::Str(s.into())
            }
            "ord" => match vals.first() {
                Some(Value::Str(s)) if s.chars().count() == 1 => {
                    Value::constant(s.chars().next().map_or(0.0, |c| c as u32 as f64))
                }
                _ => Value::Undef,
            },
            "norm" => match vals.first() {
                Some(Value::Vector(v)) => {
                    let nums: Vec<&Num> = v.iter().filter_map(Value::as_num).collect();
                    let s = nums.iter().map(|n| n.value * n.value).sum::<f64>().sqrt();
                    Value::Num(Num::opaque_of(&nums, s))
                }
                _ => Value::Undef,
            },
            "cross" => cross(self, vals),
            "lookup" => lookup(vals),
            "is_undef" => Value::Bool(matches!(vals.first(), Some(Value::Undef) | None)),
            "is_num" => {
                Value::Bool(matches!(vals.first(), Some(Value::Num(n)) if !n.value.is_nan()))
            }
            "is_bool" => Value::Bool(matches!(vals.first(), Some(Value::Bool(_)))),
            "is_string" => Value::Bool(matches!(vals.first(), Some(Value::Str(_)))),
            "is_list" => Value::Bool(matches!(vals.first(), Some(Value::Vector(_)))),
            "is_function" => Value::Bool(matches!(vals.first(), Some(Value::Function(_)))),
            "version" => Value::Vector(Rc::new(vec![
                Value::constant(2021.0),
                Value::constant(1.0),
                Value::constant(0.0),
            ])),
            "version_num" => Value::constant(20210100.0),
            _ => return None,
        })
    }
}

/// The built-in functions of numbers; `None` for any other name.
fn math_function(name: &str, vals: &[Value]) -> Option<Value> {
    let num = |i: usize| vals.get(i).and_then(Value::as_num).cloned();
    let unary = |f: fn(f64) -> f64| -> Value {
        num(0).map_or(Value::Undef, |n| Value::Num(n.opaque(f(n.value))))
    };
    Some(match name {
        "sqrt" => unary(f64::sqrt),
        "abs" => unary(f64::abs),
        "floor" => unary(f64::floor),
        "ceil" => unary(f64::ceil),
        "round" => unary(f64::round),
        "exp" => unary(f64::exp),
        "ln" => unary(f64::ln),
        "log" => match (num(0), num(1)) {
            (Some(b), Some(x)) => {
                Value::Num(Num::opaque_of(&[&b, &x], x.value.ln() / b.value.ln()))
            }
            (Some(x), None) => Value::Num(x.opaque(x.value.log10())),
            _ => Value::Undef,
        },
        "sign" => unary(|x| {
            if x > 0.0 {
                1.0
            } else if x < 0.0 {
                -1.0
            } else {
                0.0
            }
        }),
        "sin" => unary(sin_degrees),
        "cos" => unary(cos_degrees),
        "tan" => unary(|x| sin_degrees(x) / cos_degrees(x)),
        "asin" => unary(|x| x.asin().to_degrees()),
        "acos" => unary(|x| x.acos().to_degrees()),
        "atan" => unary(|x| x.atan().to_degrees()),
        "atan2" => match (num(0), num(1)) {
            (Some(y), Some(x)) => Value::Num(Num::opaque_of(
                &[&y, &x],
                y.value.atan2(x.value).to_degrees(),
            )),
            _ => Value::Undef,
        },
        "pow" => match (num(0), num(1)) {
            (Some(b), Some(e)) => Value::Num(Num::opaque_of(&[&b, &e], b.value.powf(e.value))),
            _ => Value::Undef,
        },
        "min" | "max" => min_max(name == "max", vals),
        _ => return None,
    })
}

fn is_builtin_function(name: &str) -> bool {
    matches!(
        name,
        "sqrt"
            | "abs"
            | "floor"
            | "ceil"
            | "round"
            | "exp"
            | "ln"
            | "log"
            | "sign"
            | "sin"
            | "cos"
            | "tan"
            | "asin"
            | "acos"
            | "atan"
            | "atan2"
            | "pow"
            | "min"
            | "max"
            | "len"
            | "concat"
            | "str"
            | "chr"
            | "ord"
            | "norm"
            | "cross"
            | "lookup"
            | "is_undef"
            | "is_num"
            | "is_bool"
            | "is_string"
            | "is_list"
            | "is_function"
            | "version"
            | "version_num"
            | "rands"
            | "search"
    )
}

/// `min`/`max` of numbers, or of one vector of numbers.
fn min_max(max: bool, vals: &[Value]) -> Value {
    let list: Vec<&Num> = match vals {
        [Value::Vector(v)] => v.iter().filter_map(Value::as_num).collect(),
        _ => vals.iter().filter_map(Value::as_num).collect(),
    };
    let Some(best) = list.iter().copied().reduce(|a, b| {
        let take_b = if max {
            b.value > a.value
        } else {
            b.value < a.value
        };
        if take_b { b } else { a }
    }) else {
        return Value::Undef;
    };
    Value::Num(Num::opaque_of(&list, best.value))
}

fn cross(ev: &mut Eval<'_>, vals: &[Value]) -> Value {
    let (Some(Value::Vector(a)), Some(Value::Vector(b))) = (vals.first(), vals.get(1)) else {
        return Value::Undef;
    };
    let nums =
        |v: &[Value]| -> Option<Vec<Num>> { v.iter().map(|x| x.as_num().cloned()).collect() };
    let (Some(a), Some(b)) = (nums(a), nums(b)) else {
        return Value::Undef;
    };
    if a.len() != 3 || b.len() != 3 {
        return Value::Undef;
    }
    let c = |i: usize, j: usize| ev.mul_nums(&a[i], &b[j]).sub(&ev.mul_nums(&a[j], &b[i]));
    Value::Vector(Rc::new(vec![
        Value::Num(c(1, 2)),
        Value::Num(c(2, 0)),
        Value::Num(c(0, 1)),
    ]))
}

/// Piecewise-linear `lookup(key, [[k, v], ...])`.
fn lookup(vals: &[Value]) -> Value {
    let (Some(Value::Num(key)), Some(Value::Vector(table))) = (vals.first(), vals.get(1)) else {
        return Value::Undef;
    };
    let points: Vec<(f64, f64)> = table
        .iter()
        .filter_map(|row| {
            let r = row.as_vec()?;
            Some((r.first()?.as_num()?.value, r.get(1)?.as_num()?.value))
        })
        .collect();
    let Some(&first) = points.first() else {
        return Value::Undef;
    };
    let k = key.value;
    let mut result = first.1;
    if k >= first.0 {
        result = points.last().map_or(first.1, |p| p.1);
        for w in points.windows(2) {
            let ((k0, v0), (k1, v1)) = (w[0], w[1]);
            if k >= k0 && k <= k1 {
                result = v0 + (k - k0) * (v1 - v0) / (k1 - k0);
                break;
            }
        }
    }
    let deps: Vec<&Num> = std::iter::once(key).collect();
    Value::Num(Num::opaque_of(&deps, result))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_trig_at_special_angles() {
        assert_eq!(sin_degrees(90.0), 1.0);
        assert_eq!(sin_degrees(180.0), 0.0);
        assert_eq!(sin_degrees(30.0), 0.5);
        assert_eq!(sin_degrees(-90.0), -1.0);
        assert_eq!(cos_degrees(90.0), 0.0);
        assert_eq!(cos_degrees(180.0), -1.0);
        assert_eq!(cos_degrees(60.0), 0.5);
        assert_eq!(cos_degrees(270.0), 0.0);
        assert!((sin_degrees(10.0) - 10f64.to_radians().sin()).abs() < 1e-15);
    }
}
