//! Writing a model back with other numbers.
//!
//! The same program text with each slot's literal replaced by a new value: what a variant
//! file is (the output of `fit`, the input of `--vary`). Only the literals' bytes change, so
//! comments, layout and structure survive exactly.

use crate::front::eval::format_number;
use crate::ir::Slot;
use crate::span::FileId;

/// `text` (the file `file`) with the literal of every slot in that file set to `values[slot]`.
/// A negative value replacing a literal is parenthesised so `-` signs in front stay right.
pub fn with_slot_values(text: &str, file: FileId, slots: &[Slot], values: &[f64]) -> String {
    let mut edits: Vec<(std::ops::Range<usize>, String)> = slots
        .iter()
        .filter(|s| s.span.file == file)
        .filter(|s| values[s.id as usize] != s.value)
        .map(|s| {
            let v = round_for_source(values[s.id as usize]);
            let t = format_number(v);
            (s.span.range(), if v < 0.0 { format!("({t})") } else { t })
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::span::Span;

    fn slot(id: u32, start: usize, end: usize, value: f64) -> Slot {
        Slot {
            id,
            name: format!("s{id}"),
            variable: None,
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
        assert_eq!(out, "cube([12.5, 20, (-3)]); // keep");
    }

    #[test]
    fn rounding_keeps_ten_digits() {
        assert_eq!(round_for_source(0.1 + 0.2), 0.3);
        assert_eq!(round_for_source(123456.78901234), 123456.789);
    }
}
