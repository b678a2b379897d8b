//! The crate's layering, as `ARCHITECTURE.md` states it, checked on the source text.
//!
//! Each top-level module of `src/` may import only the modules listed for it; the graph of
//! imports between top-level modules has no cycle; and no file outside `src/tolerance.rs`
//! writes a bare tolerance exponent (`1e-9`) in library code.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// What each top-level module may import (besides itself). The lowest layers come first.
const ALLOWED: &[(&str, &[&str])] = &[
    ("span", &[]),
    ("tolerance", &[]),
    ("output", &[]),
    ("ir", &["span", "tolerance"]),
    ("geom", &["ir", "span", "tolerance"]),
    ("front", &["ir", "span", "tolerance"]),
    ("variation", &["front", "ir", "span", "tolerance"]),
    (
        "analysis",
        &["front", "geom", "ir", "span", "tolerance", "variation"],
    ),
    ("render", &["geom", "ir", "span", "tolerance"]),
    (
        "fit",
        &[
            "analysis",
            "front",
            "geom",
            "ir",
            "render",
            "span",
            "tolerance",
            "variation",
        ],
    ),
    (
        "back",
        &[
            "analysis",
            "front",
            "geom",
            "ir",
            "render",
            "span",
            "tolerance",
            "variation",
        ],
    ),
    (
        "explore",
        &[
            "analysis",
            "back",
            "fit",
            "front",
            "geom",
            "ir",
            "output",
            "render",
            "span",
            "tolerance",
            "variation",
        ],
    ),
    (
        "command",
        &[
            "analysis",
            "back",
            "explore",
            "fit",
            "front",
            "geom",
            "ir",
            "output",
            "render",
            "span",
            "tolerance",
            "variation",
        ],
    ),
    (
        "families",
        &[
            "analysis",
            "back",
            "command",
            "explore",
            "fit",
            "front",
            "geom",
            "ir",
            "output",
            "render",
            "span",
            "tolerance",
            "variation",
        ],
    ),
];

fn src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let p = e.path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// The top-level module a file of `src/` belongs to (`None` for the crate root files).
fn top_module(file: &Path) -> Option<String> {
    let rel = file.strip_prefix(src()).ok()?;
    let first = rel.components().next()?.as_os_str().to_string_lossy();
    let name = first.trim_end_matches(".rs").to_string();
    (name != "lib" && name != "main" && name != "cli").then_some(name)
}

/// The text with comments removed (line comments and doc comments; block comments are not
/// used in this crate).
fn code_of(text: &str) -> String {
    text.lines()
        .map(|l| match l.find("//") {
            Some(i) => &l[..i],
            None => l,
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// Every top-level module named by a `crate::name` path in `code`.
fn crate_paths(code: &str) -> BTreeSet<String> {
    let mut found = BTreeSet::new();
    let mut rest = code;
    while let Some(i) = rest.find("crate::") {
        let tail = &rest[i + "crate::".len()..];
        let name: String = tail
            .chars()
            .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
            .collect();
        let before = rest[..i].chars().last();
        if !name.is_empty() && !before.is_some_and(|c| c.is_ascii_alphanumeric() || c == '_') {
            found.insert(name);
        }
        rest = tail;
    }
    found
}

/// Top-level module → the top-level modules its files import.
fn import_graph() -> BTreeMap<String, BTreeSet<String>> {
    let mut files = Vec::new();
    rust_files(&src(), &mut files);
    let modules: BTreeSet<String> = files.iter().filter_map(|f| top_module(f)).collect();
    let mut graph: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for f in &files {
        let Some(m) = top_module(f) else { continue };
        let text = std::fs::read_to_string(f).unwrap();
        let deps = graph.entry(m.clone()).or_default();
        for d in crate_paths(&code_of(&text)) {
            if d != m && modules.contains(&d) {
                deps.insert(d);
            }
        }
    }
    graph
}

#[test]
fn every_module_imports_only_its_lower_layers() {
    let allowed: BTreeMap<&str, &[&str]> = ALLOWED.iter().copied().collect();
    let mut wrong = Vec::new();
    for (m, deps) in import_graph() {
        let Some(ok) = allowed.get(m.as_str()) else {
            wrong.push(format!(
                "`{m}` is not in ARCHITECTURE.md's layers (tests/layering.rs)"
            ));
            continue;
        };
        for d in deps {
            if !ok.contains(&d.as_str()) {
                wrong.push(format!("`{m}` imports `{d}`"));
            }
        }
    }
    assert_none("layering broken", &wrong);
}

#[test]
fn top_level_modules_import_each_other_without_cycles() {
    let graph = import_graph();
    // Depth-first search with colours: 1 on the stack, 2 finished.
    fn visit(
        m: &str,
        graph: &BTreeMap<String, BTreeSet<String>>,
        colour: &mut BTreeMap<String, u8>,
        stack: &mut Vec<String>,
    ) -> Option<Vec<String>> {
        match colour.get(m) {
            Some(2) => return None,
            Some(1) => {
                let start = stack.iter().position(|s| s == m).unwrap_or(0);
                let mut cycle = stack[start..].to_vec();
                cycle.push(m.to_string());
                return Some(cycle);
            }
            _ => {}
        }
        colour.insert(m.to_string(), 1);
        stack.push(m.to_string());
        for d in graph.get(m).into_iter().flatten() {
            if let Some(c) = visit(d, graph, colour, stack) {
                return Some(c);
            }
        }
        stack.pop();
        colour.insert(m.to_string(), 2);
        None
    }
    let mut colour = BTreeMap::new();
    for m in graph.keys() {
        let cycle = visit(m, &graph, &mut colour, &mut Vec::new());
        assert!(
            cycle.is_none(),
            "import cycle: {}",
            cycle.unwrap().join(" → ")
        );
    }
}

/// Library code of a file: without its `#[cfg(test)]` tail, and nothing of a test file.
fn library_code(file: &Path, text: &str) -> Option<String> {
    let name = file.file_name()?.to_string_lossy();
    let in_tests_dir = file.components().any(|c| c.as_os_str() == "tests");
    if name == "tests.rs" || name.starts_with("tests_") || in_tests_dir {
        return None;
    }
    let cut = text.find("#[cfg(test)]").unwrap_or(text.len());
    Some(code_of(&text[..cut]))
}

/// Float literals with a negative exponent (`1e-9`, `2.5E-12`) in `code`.
fn negative_exponents(code: &str) -> Vec<String> {
    let bytes = code.as_bytes();
    let mut found = Vec::new();
    for (i, _) in code.match_indices(['e', 'E']) {
        let digit_before = i > 0 && bytes[i - 1].is_ascii_digit();
        let minus_digit =
            bytes.get(i + 1) == Some(&b'-') && bytes.get(i + 2).is_some_and(u8::is_ascii_digit);
        if !(digit_before && minus_digit) {
            continue;
        }
        let start = code[..i]
            .rfind(|c: char| !(c.is_ascii_digit() || c == '.' || c == '_'))
            .map_or(0, |s| s + 1);
        let word_before =
            start > 0 && (bytes[start - 1].is_ascii_alphabetic() || bytes[start - 1] == b'_');
        if !word_before {
            let end = code[i + 2..]
                .find(|c: char| !c.is_ascii_digit())
                .map_or(code.len(), |e| i + 2 + e);
            found.push(code[start..end].to_string());
        }
    }
    found
}

#[test]
fn tolerances_are_written_only_in_the_tolerance_module() {
    let mut files = Vec::new();
    rust_files(&src(), &mut files);
    let mut bare = Vec::new();
    for f in files {
        if f.ends_with("tolerance.rs") && top_module(&f).as_deref() == Some("tolerance") {
            continue;
        }
        let text = std::fs::read_to_string(&f).unwrap();
        let Some(code) = library_code(&f, &text) else {
            continue;
        };
        for lit in negative_exponents(&code) {
            bare.push(found_in(&f, &lit));
        }
    }
    assert_none(
        "bare tolerance exponents outside src/tolerance.rs (name them there)",
        &bare,
    );
}

/// `what` found in `file`, for a failure message.
fn found_in(file: &Path, what: &str) -> String {
    let rel = file.strip_prefix(src()).unwrap_or(file);
    format!("{}: {what}", rel.display())
}

fn assert_none(problem: &str, found: &[String]) {
    assert!(found.is_empty(), "{problem}:\n{}", found.join("\n"));
}

/// What the command line may use of the library: the entry points, diagnostics, the source
/// map that diagnostics quote, and the output writer.
const CLI_MAY_USE: &[&str] = &[
    "reparamc::command",
    "reparamc::front::diag",
    "reparamc::front::source::SourceMap",
    "reparamc::output",
];

#[test]
fn the_command_line_calls_only_the_entry_points() {
    let mut files = Vec::new();
    rust_files(&src().join("cli"), &mut files);
    files.push(src().join("main.rs"));
    let mut wrong = Vec::new();
    for f in files {
        let code = code_of(&std::fs::read_to_string(&f).unwrap());
        for (i, _) in code.match_indices("reparamc::") {
            let path: String = code[i..]
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '_' || *c == ':')
                .collect();
            let braced = code[i + path.len()..].starts_with('{');
            let ok = CLI_MAY_USE
                .iter()
                .any(|p| path.starts_with(p) || (braced && p.starts_with(path.as_str())));
            if !ok {
                wrong.push(found_in(&f, &path));
            }
        }
    }
    assert_none("the CLI reaches past the entry points", &wrong);
}

#[test]
fn the_checks_see_what_they_look_for() {
    assert_eq!(
        crate_paths("use crate::ir::Model; x = crate::geom::volume(); not_crate::fit"),
        ["geom", "ir"].iter().map(|s| s.to_string()).collect()
    );
    assert_eq!(
        negative_exponents("let a = 1e-9 * s; let b = 2.5E-12; let c = 1e6; let d = x1e-3;"),
        vec!["1e-9".to_string(), "2.5E-12".to_string()]
    );
    assert_eq!(code_of("a // crate::fit\nb"), "a \nb");
}
