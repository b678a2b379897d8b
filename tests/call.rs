//! `--call`: a file that only defines modules, re-parameterized through one call of them.
//!
//! The main command's output keeps the file's text, module included, with the call added;
//! OpenSCAD loads it, and at default values it draws what the file with the call draws.
//! A variant file gets the same call. `inspect` and `render` take `--call` too, and a
//! `--call` that is not one module call is a located error.

mod common;

use common::*;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const LIBRARY: &str = "tests/fixtures/call/chair.scad";
const VARIANT: &str = "tests/fixtures/call/tall.scad";

fn reparamc(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_reparamc"))
        .args(args)
        .current_dir(repo())
        .output()
        .expect("the binary runs")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// The library's text with `call` appended, as its own file.
fn with_call(call: &str) -> PathBuf {
    let text = std::fs::read_to_string(repo().join(LIBRARY)).unwrap();
    let path = repo().join(format!(
        "tests/fixtures/call/.with_call_{}.scad",
        std::process::id()
    ));
    std::fs::write(&path, format!("{text}\n{call};\n")).unwrap();
    path
}

fn parts(model: &Path) -> Vec<CsgPart> {
    csg_parts(&openscad_csg(model))
}

#[test]
fn a_module_only_file_lists_its_modules_and_how_to_pick_one() {
    let out = reparamc(&[LIBRARY, "-o", "-"]);
    assert_eq!(out.status.code(), Some(1));
    let text = stderr(&out);
    for want in [
        "error[E0500]",
        "module chair(seat_w = 40, seat_d = 38, seat_h = 45, leg_s = 4)",
        "module stool(h = 60)",
        "--call 'chair()'",
    ] {
        assert!(text.contains(want), "no `{want}` in:\n{text}");
    }
}

#[test]
fn the_output_keeps_the_module_adds_the_call_and_draws_the_call_at_defaults() {
    for (call, vary) in [("chair()", None), ("chair(seat_h = 50)", Some(VARIANT))] {
        let out_path = tempfile(Path::new("call_out"), "scad");
        let shown = out_path.to_string_lossy().into_owned();
        let mut args = vec![LIBRARY, "-o", &shown, "--call", call];
        if let Some(v) = vary {
            args.extend(["--vary", v]);
        }
        let out = reparamc(&args);
        assert!(out.status.success(), "{call}: {}", stderr(&out));
        let written = std::fs::read_to_string(&out_path).unwrap();
        assert!(written.contains("module chair("), "{written}");
        assert!(written.contains("module stool("), "{written}");
        let name = call.split('(').next().unwrap();
        assert!(written.contains(&format!("{name}(")), "{written}");
        let reference = with_call(call);
        let errs = compare_parts(&parts(&out_path), &parts(&reference));
        let _ = std::fs::remove_file(&reference);
        let _ = std::fs::remove_file(&out_path);
        let _ = std::fs::remove_file(out_path.with_extension("json"));
        assert!(errs.is_empty(), "{call}: {}", errs.join("\n"));
    }
}

#[test]
fn the_call_numbers_are_parameters_and_a_variant_with_the_call_moves_them() {
    let out = reparamc(&["inspect", LIBRARY, "--call", "chair(seat_h = 50)"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = String::from_utf8_lossy(&out.stdout);
    // The call's own number is a parameter of the model, placed on the line after the
    // file's end, where the call is added.
    let lines = std::fs::read_to_string(repo().join(LIBRARY))
        .unwrap()
        .lines()
        .count();
    let at = format!("{LIBRARY}:{}:", lines + 2);
    assert!(
        text.lines()
            .any(|l| l.contains(&at) && l.split_whitespace().any(|w| w == "50")),
        "no parameter 50 at {at} in:\n{text}"
    );
    let rendered = tempfile(Path::new("call_render"), "png");
    let shown = rendered.to_string_lossy().into_owned();
    let out = reparamc(&[
        "render",
        LIBRARY,
        "--call",
        "stool(h = 30)",
        "-o",
        &shown,
        "--views",
        "2",
        "--size",
        "32",
        "--cpu",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(std::fs::metadata(&rendered).unwrap().len() > 0);
    let _ = std::fs::remove_file(&rendered);
}

#[test]
fn a_call_that_is_not_one_module_call_is_a_located_error() {
    for (call, want) in [
        ("chair(", "error[E0001]"),
        ("x = 3", "error[E0403]"),
        ("chair(); stool()", "error[E0403]"),
    ] {
        let out = reparamc(&[LIBRARY, "-o", "-", "--call", call]);
        assert_eq!(out.status.code(), Some(1), "{call}");
        let text = stderr(&out);
        assert!(text.contains(want), "{call}: {text}");
        assert!(text.contains("--call:1:"), "{call}: {text}");
    }
}
