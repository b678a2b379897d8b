//! The lines where a variant file's structure leaves its model's, as a short unified diff.
//!
//! Lines are compared as the matching in `files` compares tokens: by their tokens, with
//! every number alike and a sign in front of a number ignored, so a line that changes only
//! numbers, blanks or comments is unchanged here and the diff shows only what a variation
//! may not change. The lines within [`WINDOW`] of the first mismatch are diffed; the note
//! shows the run of changed lines that holds the mismatch (at most [`MOST_CHANGED`] of
//! them) with [`CONTEXT`] unchanged lines either side, so it stays a few lines long
//! whatever the files' sizes.

use super::files::Lexed;
use crate::front::parse::TokenKind;
use similar::{Algorithm, DiffTag};
use std::fmt::Write as _;
use std::ops::Range;
use std::path::Path;

/// Lines either side of the mismatch that are diffed.
const WINDOW: usize = 40;

/// Unchanged lines shown either side of the changes.
const CONTEXT: usize = 2;

/// Most changed lines shown.
const MOST_CHANGED: usize = 12;

/// Longest line shown, in characters; a longer one is cut with `…`.
const LINE_CHARS: usize = 120;

/// One file of the comparison: its path, its tokens and the byte offset of the mismatch.
pub(super) struct Side<'a> {
    pub path: &'a Path,
    pub lexed: &'a Lexed<'a>,
    pub at: usize,
}

/// A file's lines, each with the key it is compared by.
struct Lines<'a> {
    lines: Vec<&'a str>,
    keys: Vec<String>,
    /// The line of the mismatch.
    at: usize,
}

impl<'a> Lines<'a> {
    fn new(side: &Side<'a>) -> Self {
        let text = side.lexed.text;
        let lines: Vec<&str> = text.lines().collect();
        let mut starts = vec![0];
        starts.extend(text.match_indices('\n').map(|(i, _)| i + 1));
        let line_of = |offset: usize| {
            let line = starts.partition_point(|&s| s <= offset).saturating_sub(1);
            line.min(lines.len().saturating_sub(1))
        };
        let mut keys = vec![String::new(); lines.len()];
        for (k, token) in side.lexed.tokens.iter().enumerate() {
            if side.lexed.negated_number(k) {
                continue;
            }
            let Some(key) = keys.get_mut(line_of(token.start)) else {
                continue;
            };
            if !key.is_empty() {
                key.push(' ');
            }
            match token.kind {
                TokenKind::Number(_) => key.push('0'),
                _ => key.push_str(token.text(text)),
            }
        }
        Lines {
            at: line_of(side.at),
            lines,
            keys,
        }
    }

    /// The lines compared: [`WINDOW`] either side of the mismatch.
    fn window(&self) -> Range<usize> {
        self.at.saturating_sub(WINDOW)..(self.at + WINDOW + 1).min(self.lines.len())
    }

    /// Line `i` as shown: cut to [`LINE_CHARS`] with `…`.
    fn line(&self, i: usize) -> String {
        let line = self.lines.get(i).map_or("", |l| l.trim_end());
        match line.char_indices().nth(LINE_CHARS) {
            Some((cut, _)) => format!("{} …", &line[..cut]),
            None => line.to_string(),
        }
    }
}

/// One line of a unified diff: unchanged (` `), only in the model (`-`) or only in the
/// variant (`+`), with where it is in each file (for a line only in one file, where it
/// would be in the other).
#[derive(Debug, Clone, Copy)]
struct Row {
    mark: char,
    old: usize,
    new: usize,
}

/// The rows of a diff of line ranges.
fn rows(old: &Lines<'_>, new: &Lines<'_>) -> Vec<Row> {
    let ops = similar::capture_diff(
        Algorithm::Myers,
        &old.keys[..],
        old.window(),
        &new.keys[..],
        new.window(),
    );
    let mut rows = Vec::new();
    for op in ops {
        let (tag, o, n) = op.as_tag_tuple();
        if tag == DiffTag::Equal {
            rows.extend(o.zip(n).map(|(old, new)| Row {
                mark: ' ',
                old,
                new,
            }));
            continue;
        }
        let (old_end, new_start) = (o.end, n.start);
        rows.extend(o.map(|old| Row {
            mark: '-',
            old,
            new: new_start,
        }));
        rows.extend(n.map(|new| Row {
            mark: '+',
            old: old_end,
            new,
        }));
    }
    rows
}

/// The rows shown: the run of changed rows holding the mismatch (or else the first run),
/// at most [`MOST_CHANGED`] of it, with [`CONTEXT`] unchanged rows either side.
fn shown(rows: &[Row], old_at: usize, new_at: usize) -> Option<Range<usize>> {
    let mut runs = Vec::new();
    let mut k = 0;
    while k < rows.len() {
        if rows[k].mark == ' ' {
            k += 1;
            continue;
        }
        let start = k;
        while k < rows.len() && rows[k].mark != ' ' {
            k += 1;
        }
        runs.push(start..k);
    }
    let holds = |run: &&Range<usize>| {
        rows[run.start..run.end]
            .iter()
            .any(|r| (r.mark == '-' && r.old == old_at) || (r.mark == '+' && r.new == new_at))
    };
    let run = runs.iter().find(holds).or(runs.first())?;
    let end = run.end.min(run.start + MOST_CHANGED);
    Some(run.start.saturating_sub(CONTEXT)..(end + CONTEXT).min(rows.len()))
}

/// A hunk header's range, as unified diffs write it: `start,len` counted from 1, `start`
/// alone for one line, and the line before for none.
fn range(start: usize, len: usize) -> String {
    match len {
        0 => format!("{start},0"),
        1 => format!("{}", start + 1),
        _ => format!("{},{len}", start + 1),
    }
}

/// The unified diff of the lines around the mismatch of `model` and `variant` (model
/// first), headed by a sentence; `None` when those lines compare equal.
pub(super) fn differing_lines(model: &Side<'_>, variant: &Side<'_>) -> Option<String> {
    let old = Lines::new(model);
    let new = Lines::new(variant);
    let rows = rows(&old, &new);
    let shown = &rows[shown(&rows, old.at, new.at)?];
    let first = shown.first()?;
    let old_len = shown.iter().filter(|r| r.mark != '+').count();
    let new_len = shown.iter().filter(|r| r.mark != '-').count();
    let mut out = String::from("the lines that differ, model (-) and variation (+):\n");
    let _ = writeln!(out, "--- {}", model.path.display());
    let _ = writeln!(out, "+++ {}", variant.path.display());
    let _ = writeln!(
        out,
        "@@ -{} +{} @@",
        range(first.old, old_len),
        range(first.new, new_len)
    );
    for row in shown {
        let line = match row.mark {
            '+' => new.line(row.new),
            _ => old.line(row.old),
        };
        let _ = writeln!(out, "{}{line}", row.mark);
    }
    Some(out.trim_end().to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The diff of `model` and `variant` at their first tokens that differ.
    fn diff(model: &str, variant: &str) -> Option<String> {
        let (old, new) = (Lexed::new(model), Lexed::new(variant));
        let k = (0..)
            .find(|&k| {
                old.tokens.get(k).map(|t| t.text(model))
                    != new.tokens.get(k).map(|t| t.text(variant))
            })
            .unwrap_or(0);
        let at = |l: &Lexed<'_>| l.tokens.get(k).map_or(l.text.len(), |t| t.start);
        differing_lines(
            &Side {
                path: Path::new("m.scad"),
                lexed: &old,
                at: at(&old),
            },
            &Side {
                path: Path::new("v.scad"),
                lexed: &new,
                at: at(&new),
            },
        )
    }

    #[test]
    fn only_the_lines_that_change_structure_differ() {
        let model = "a = 1;\nb = -2; // b\n\nc = 3;\ncube(a);\nd = 4;\ne = 5;\nf = 6;\ng = 7;\n";
        let variant = "a = 10;\nb = 20;\n\nc = 30;\nsphere(a);\nd = 4;\ne = 5;\nf = 6;\ng = 7;\n";
        assert_eq!(
            diff(model, variant).as_deref(),
            Some(
                "the lines that differ, model (-) and variation (+):\n--- m.scad\n+++ v.scad\n\
                 @@ -3,5 +3,5 @@\n \n c = 3;\n-cube(a);\n+sphere(a);\n d = 4;\n e = 5;"
            )
        );
    }

    #[test]
    fn a_line_only_one_side_has_is_shown_with_its_place() {
        let text = diff("a = 1;\n", "a = 1;\ncube(a);\n").unwrap_or_default();
        assert!(
            text.ends_with("@@ -1 +1,2 @@\n a = 1;\n+cube(a);"),
            "{text}"
        );
        let text = diff("a = 1;\ncube(a);\n", "a = 2;\n").unwrap_or_default();
        assert!(
            text.ends_with("@@ -1,2 +1 @@\n a = 1;\n-cube(a);"),
            "{text}"
        );
    }

    #[test]
    fn long_lines_are_cut_and_equal_lines_give_no_diff() {
        let long = format!("x = [{}];\n", "1, ".repeat(100));
        let text = diff("x = 1;\n", &long).unwrap_or_default();
        assert!(
            text.lines()
                .any(|l| l.starts_with("+x = [1, ") && l.ends_with(" …")),
            "{text}"
        );
        assert_eq!(diff("a = 1; // one\n", "a = -2;\n"), None);
    }
}
