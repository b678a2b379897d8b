//! What the main command changed in a file, as a unified diff (`--diff`).
//!
//! The `similar` crate's line diff from the input's text to the output's, with `---` and
//! `+++` headers naming the two files and three lines of context around each hunk.

use similar::TextDiff;

/// Lines of unchanged text shown around each hunk (as `diff -u`).
const CONTEXT_LINES: usize = 3;

/// The unified diff from `old` (the file `old_name`) to `new` (the file `new_name`); empty
/// when the texts are equal.
pub fn unified_diff(old: &str, new: &str, old_name: &str, new_name: &str) -> String {
    TextDiff::from_lines(old, new)
        .unified_diff()
        .context_radius(CONTEXT_LINES)
        .header(old_name, new_name)
        .to_string()
}
