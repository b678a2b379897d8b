//! Expressions of the free variables as readable OpenSCAD.
//!
//! A solved slot is `constant + Σ coeff · free[i]` ([`Expression`]); here it becomes text
//! such as `seat_width / 2 - leg_size + 7.5`. Coefficients that are small fractions are
//! written as fractions; every other number as the emitter writes numbers.

use super::emit::number;
use crate::analysis::reparam::{Expression, Frac};

/// An expression as readable OpenSCAD: `seat_width / 2 - leg_size + 7.5`. `names` are the
/// free variables' names, by index.
pub fn format_expression(e: &Expression, names: &[String]) -> String {
    let mut out = String::new();
    for &(i, a) in &e.terms {
        let name = &names[i];
        let neg = a < 0.0;
        let m = a.abs();
        let term = match Frac::near(m) {
            Some(f) if f.den == 1 && f.num == 1 => name.clone(),
            Some(f) if f.den == 1 => format!("{} * {name}", f.num),
            Some(f) if f.num == 1 => format!("{name} / {}", f.den),
            Some(f) => format!("{name} * {} / {}", f.num, f.den),
            None => format!("{} * {name}", number(m)),
        };
        if out.is_empty() {
            out = if neg { format!("-{term}") } else { term };
        } else {
            out.push_str(if neg { " - " } else { " + " });
            out.push_str(&term);
        }
    }
    let c = e.constant;
    if out.is_empty() {
        return number(c);
    }
    if number(c) != "0" {
        out.push_str(if c < 0.0 { " - " } else { " + " });
        out.push_str(&number(c.abs()));
    }
    out
}
