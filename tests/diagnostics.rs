//! Snapshots of the diagnostic every bad input in `tests/bad/` gets.
//!
//! Each file is loaded by its relative path (`tests/bad/x.scad`; integration tests run in
//! the crate root) so the rendered text is the same on every machine, and its diagnostic is
//! snapshot to `snapshots/<file stem>.snap`. Beyond the snapshot, every error must say where
//! it is (`tests/bad/x.scad:LINE:COL`), underline it (`^`) and carry an `E0…` code, and the
//! line it points at must be one the file's first-line comment names as the culprit.
//!
//! A few bad files are valid OpenSCAD that only deserves a warning; their warnings are
//! snapshot instead, and they must load without an error.

mod common;

use common::snapshot;

use reparamc::front::diag::Severity;
use reparamc::front::source::SourceMap;
use std::path::{Path, PathBuf};

/// Bad inputs that are warnings, not errors, in OpenSCAD's sense.
/// (OpenSCAD warns about each and goes on; `tests/leniency.rs` checks that reparamc reads
/// them as it does.)
const WARNING_ONLY: &[&str] = &[
    "cube_string_size.scad",
    "cylinder_string_height.scad",
    "missing_include.scad",
    "missing_semicolon_statement.scad",
    "module_too_many_args.scad",
    "module_unknown_named_arg.scad",
    "rotate_string.scad",
    "translate_scalar.scad",
    "unknown_function.scad",
    "unknown_variable_size.scad",
];

/// Bad inputs whose diagnostic is about the whole file (nothing to draw): the line numbers
/// their comment mentions describe the file, not where the diagnostic must point.
const WHOLE_FILE: &[&str] = &[
    "comment_only.scad",
    "draws_nothing.scad",
    "empty.scad",
    "module_only.scad",
];

/// The bad files, as paths relative to the crate root.
fn bad_files() -> Vec<PathBuf> {
    common::scad_files("tests/bad")
        .into_iter()
        .map(|p| {
            let name = p.file_name().expect("a file name").to_owned();
            Path::new("tests/bad").join(name)
        })
        .collect()
}

fn file_name(path: &Path) -> String {
    path.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default()
}

/// The line numbers the first-line comment of a bad file names ("on line 3", "line 4").
fn lines_named_in_comment(text: &str) -> Vec<usize> {
    let first = text.lines().next().unwrap_or("");
    let words: Vec<&str> = first
        .split(|c: char| !c.is_alphanumeric())
        .filter(|w| !w.is_empty())
        .collect();
    words
        .windows(2)
        .filter(|w| w[0] == "line")
        .filter_map(|w| w[1].parse().ok())
        .collect()
}

/// The `LINE:COL` of the first `path:LINE:COL` in rendered output.
fn location(rendered: &str, path: &str) -> Option<(usize, usize)> {
    let at = rendered.find(&format!("{path}:"))? + path.len() + 1;
    let mut it = rendered[at..]
        .split(|c: char| !c.is_ascii_digit())
        .take(2)
        .map(|s| s.parse::<usize>().ok());
    Some((it.next()??, it.next()??))
}

#[test]
fn every_bad_input_has_a_good_diagnostic() {
    let files = bad_files();
    assert!(files.len() >= 20, "only {} bad inputs", files.len());
    let mut errors = 0;
    let mut problems = Vec::new();
    for path in &files {
        let name = file_name(path);
        let shown = path.to_string_lossy().into_owned();
        let stem = name.trim_end_matches(".scad");
        let text = std::fs::read_to_string(path).expect("bad input readable");
        let mut sources = SourceMap::new();
        let result = reparamc::load_model(&mut sources, path);
        let expect_warning = WARNING_ONLY.contains(&name.as_str());
        match result {
            Err(d) => {
                let rendered = d.render_plain(&sources);
                snapshot(stem, path, &rendered);
                errors += 1;
                if expect_warning {
                    problems.push(format!("{shown}: an error, expected only a warning"));
                }
                if d.severity != Severity::Error {
                    problems.push(format!("{shown}: failed with a non-error diagnostic"));
                }
                if !rendered.starts_with("error[E0") || !d.code.starts_with("E0") {
                    problems.push(format!("{shown}: no `error[E0…]` code:\n{rendered}"));
                }
                if !rendered.contains('^') {
                    problems.push(format!("{shown}: no caret:\n{rendered}"));
                }
                if location(&rendered, &shown).is_none() {
                    problems.push(format!("{shown}: no `{shown}:LINE:COL`:\n{rendered}"));
                }
                // Every line a label points at: the primary place and the secondary ones
                // (an unclosed `{` is reported at the end of the file, pointing back).
                let labelled: Vec<usize> = d
                    .primary
                    .iter()
                    .chain(&d.secondary)
                    .map(|(span, _)| sources.line_col(span.file, span.start as usize).0)
                    .collect();
                let named = lines_named_in_comment(&text);
                if !WHOLE_FILE.contains(&name.as_str())
                    && !named.is_empty()
                    && !labelled.iter().any(|l| named.contains(l))
                {
                    problems.push(format!(
                        "{shown}: points at lines {labelled:?}, its comment names {named:?}:\n{rendered}"
                    ));
                }
            }
            Ok(evaluated) => {
                let rendered: String = evaluated
                    .warnings
                    .iter()
                    .map(|w| w.render_plain(&sources))
                    .collect();
                snapshot(stem, path, &rendered);
                if !expect_warning {
                    problems.push(format!("{shown}: accepted, expected an error:\n{rendered}"));
                    continue;
                }
                if evaluated.warnings.is_empty() {
                    problems.push(format!("{shown}: accepted without a warning"));
                }
                for w in &evaluated.warnings {
                    if w.severity != Severity::Warning {
                        problems.push(format!("{shown}: an error among the warnings"));
                    }
                }
                if !rendered.contains(&format!("{shown}:")) || !rendered.contains('^') {
                    problems.push(format!("{shown}: warning without place:\n{rendered}"));
                }
            }
        }
    }
    assert!(errors >= 20, "only {errors} bad inputs are errors");
    assert!(problems.is_empty(), "{}", problems.join("\n\n"));
}

#[test]
fn comment_lines_are_read() {
    assert_eq!(
        lines_named_in_comment("// bad on line 3; the call on line 5 started it"),
        vec![3, 5]
    );
    assert_eq!(
        location("  ┌─ tests/bad/a.scad:12:7\n", "tests/bad/a.scad"),
        Some((12, 7))
    );
}

/// A variant file whose structure differs from its model's: the diagnostic points into both
/// files and shows the lines that differ as a unified diff, where lines that change only
/// numbers do not count.
#[test]
fn a_variant_of_another_structure_shows_the_differing_lines() {
    let model = Path::new("tests/bad/variation/shelf.scad");
    let variant = Path::new("tests/bad/variation/round_sides.scad");
    let mut sources = SourceMap::new();
    let (loaded, evaluated) = match reparamc::load_model_parsed(&mut sources, model) {
        Ok(x) => x,
        Err(d) => panic!("{}", d.render_plain(&sources)),
    };
    let result =
        reparamc::variation::load_variation(&mut sources, loaded.main, &evaluated.model, variant);
    let Err(d) = result else {
        panic!("a variant with round sides matched the model");
    };
    let rendered = d.render_plain(&sources);
    snapshot("variation_other_structure", variant, &rendered);
    assert!(rendered.starts_with("error[E0601]"), "{rendered}");
    for line in [
        "--- tests/bad/variation/shelf.scad",
        "+++ tests/bad/variation/round_sides.scad",
        "@@ -6,5 +6,5 @@",
        "-    translate([x, 0, 0]) cube([2, depth, height]);",
        "+    translate([x, 0, 0]) cylinder(r = 2, h = height);",
        "// the boards",
    ] {
        assert!(rendered.contains(line), "no `{line}` in:\n{rendered}");
    }
    assert!(!rendered.contains("+width"), "{rendered}");
}
