//! The `reparamc inspect` command line, run as a user would: tables, JSON, exit codes,
//! diagnostics on standard error. The text output of two examples is snapshot to
//! `snapshots/inspect_*.snap`.

mod common;

use std::process::{Command, Output};

/// Runs the built binary in the crate root (so paths in its output are relative and stable).
fn reparamc(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_reparamc"))
        .args(args)
        .current_dir(common::repo())
        .env("NO_COLOR", "1")
        .output()
        .expect("the reparamc binary runs")
}

fn stdout(o: &Output) -> String {
    String::from_utf8(o.stdout.clone()).expect("stdout is UTF-8")
}

fn stderr(o: &Output) -> String {
    String::from_utf8(o.stderr.clone()).expect("stderr is UTF-8")
}

fn snapshot(name: &str, text: &str) {
    let mut settings = insta::Settings::clone_current();
    settings.set_snapshot_path("../snapshots");
    settings.set_prepend_module_to_snapshot(false);
    settings.bind(|| insta::assert_snapshot!(name, text));
}

#[test]
fn chair_tables() {
    let out = reparamc(&["inspect", "examples/paper/chair.scad"]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert_eq!(stderr(&out), "", "no warnings on the chair");
    let text = stdout(&out);
    assert!(
        text.starts_with(
            "examples/paper/chair.scad: 48 parameters, 8 parts, 172 base constraints ("
        ),
        "summary line:\n{text}"
    );
    for heading in [
        "\nParameters\n",
        "\nParts\n",
        "\nFrozen numbers",
        "\nRelations that hold (",
    ] {
        assert!(text.contains(heading), "no `{}` table", heading.trim());
    }
    assert!(
        text.contains("seat.bottom is coplanar with")
            || text.contains("is coplanar with seat.bottom")
    );
    assert!(text.contains("left_front_leg.top is coplanar with seat.bottom"));
    assert!(
        text.contains("examples/paper/chair.scad:4:"),
        "slots say where they are"
    );
    snapshot("inspect_chair", &text);
}

#[test]
fn stool_tables() {
    let out = reparamc(&["inspect", "examples/stool.scad"]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let text = stdout(&out);
    assert!(text.starts_with("examples/stool.scad: "), "{text}");
    snapshot("inspect_stool", &text);
}

#[test]
fn chair_json() {
    let out = reparamc(&["inspect", "examples/paper/chair.scad", "--json"]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let v: serde_json::Value = serde_json::from_str(&stdout(&out)).expect("inspect --json is JSON");
    assert_eq!(v["parameter_count"], 48);
    assert_eq!(v["base_constraint_count"], 172);
    let list = |key: &str| {
        v[key]
            .as_array()
            .unwrap_or_else(|| panic!("`{key}` is not a list"))
            .clone()
    };
    let (slots, parts, constraints) = (list("slots"), list("parts"), list("constraints"));
    assert_eq!(slots.len(), 48);
    assert_eq!(parts.len(), 8);
    // Every relation that holds is listed: the paper's base constraints, then the kinds
    // beyond them (tangency, symmetry, spacing, proportion), each counted on its own.
    let beyond = ["tangent_count", "placement_count", "proportion_count"]
        .iter()
        .map(|k| v[k].as_u64().unwrap_or(0))
        .sum::<u64>();
    assert!(beyond > 0, "the chair's legs mirror each other");
    assert_eq!(constraints.len() as u64, 172 + beyond);
    let paper = constraints
        .iter()
        .filter(|c| {
            ["coplanar", "coaxial", "coincident", "equal"]
                .contains(&c["kind"].as_str().unwrap_or(""))
        })
        .count();
    assert_eq!(
        paper, 172,
        "the paper's four kinds are its base constraints"
    );
    let counts = &v["constraint_counts"];
    if counts.is_object() {
        let sum: u64 = ["coplanar", "coaxial", "coincident", "equal"]
            .iter()
            .map(|k| counts[k].as_u64().unwrap_or(0))
            .sum();
        assert_eq!(sum, 172, "constraint_counts add up: {counts}");
    }
    let words: Vec<&str> = constraints
        .iter()
        .filter_map(|c| c["text"].as_str())
        .collect();
    assert_eq!(
        words.len(),
        constraints.len(),
        "every relation is given in words"
    );
    assert!(
        words
            .iter()
            .any(|w| w.starts_with("seat.bottom is coplanar with")
                || w.ends_with("is coplanar with seat.bottom")),
        "a relation with seat.bottom in words"
    );
    let names: Vec<&str> = parts.iter().filter_map(|p| p["name"].as_str()).collect();
    for name in ["left_front_leg", "seat", "back", "right_arm"] {
        assert!(names.contains(&name), "part `{name}` in {names:?}");
    }
    let first = &slots[0];
    assert_eq!(first["location"]["file"], "examples/paper/chair.scad");
    assert!(first["location"]["line"].as_u64().is_some());
    assert!(first["location"]["column"].as_u64().is_some());
}

#[test]
fn bad_model_exits_1_with_a_diagnostic() {
    let out = reparamc(&["inspect", "tests/bad/nonfinite_literal.scad"]);
    assert_eq!(out.status.code(), Some(1));
    assert_eq!(stdout(&out), "", "nothing on stdout after an error");
    let err = stderr(&out);
    assert!(err.contains("error[E"), "{err}");
    assert!(
        err.contains("tests/bad/nonfinite_literal.scad:3:7"),
        "{err}"
    );
    assert!(err.contains('^'), "{err}");
    assert!(
        !err.contains("\u{1b}["),
        "no colours when stderr is not a terminal"
    );

    let out = reparamc(&["inspect", "tests/bad/unclosed_brace.scad", "--json"]);
    assert_eq!(out.status.code(), Some(1));
    assert_eq!(stdout(&out), "", "no JSON after an error");
    assert!(stderr(&out).contains("error[E0"));
}

#[test]
fn warnings_go_to_stderr_and_succeed() {
    let out = reparamc(&["inspect", "tests/bad/missing_semicolon_statement.scad"]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(stderr(&out).contains("warning["), "{}", stderr(&out));
    assert!(stdout(&out).starts_with("tests/bad/missing_semicolon_statement.scad: "));
}

#[test]
fn missing_file_exits_1_with_a_clear_message() {
    let out = reparamc(&["inspect", "examples/no_such_model.scad"]);
    assert_eq!(out.status.code(), Some(1));
    assert_eq!(stdout(&out), "");
    let err = stderr(&out);
    assert!(
        err.contains("examples/no_such_model.scad"),
        "names the file: {err}"
    );
    assert!(
        err.to_lowercase().contains("no such file")
            || err.to_lowercase().contains("not found")
            || err.to_lowercase().contains("cannot read"),
        "says what is wrong: {err}"
    );
    assert!(!err.contains("panicked"), "{err}");
}

#[test]
fn help_works() {
    let out = reparamc(&["--help"]);
    assert_eq!(out.status.code(), Some(0));
    let text = stdout(&out);
    assert!(text.contains("Usage"), "{text}");
    assert!(text.contains("inspect"), "{text}");

    let out = reparamc(&["inspect", "--help"]);
    assert_eq!(out.status.code(), Some(0));
    let text = stdout(&out);
    assert!(text.contains("--json"), "{text}");

    let out = reparamc(&["--version"]);
    assert_eq!(out.status.code(), Some(0));
    assert!(stdout(&out).starts_with("reparamc "));
}

#[test]
fn usage_errors_exit_2() {
    let out = reparamc(&["inspect"]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(stderr(&out).contains("Usage"));
    let out = reparamc(&["frobnicate", "x.scad"]);
    assert_eq!(out.status.code(), Some(2));
    let out = reparamc(&[]);
    assert_eq!(out.status.code(), Some(2));
}
