//! Files a command reads and writes: an output that cannot be written, or that is an
//! input (through `./` or a symlink), is refused with a message naming it before any work,
//! and nothing is written; a variation that is the model itself is a diagnostic; Ctrl-C
//! during the main job or a fit leaves no output, no temporary file and the input as it
//! was.

mod common;

use common::snapshot;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_reparamc"))
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// A fresh folder holding a copy of `model` as `model.scad`.
fn folder_with(name: &str, model: &str) -> PathBuf {
    let dir = common::tempfile(Path::new(name), "dir");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::copy(common::repo().join(model), dir.join("model.scad")).unwrap();
    dir
}

/// Every file in `dir`, sorted.
fn listing(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

#[test]
fn outputs_that_cannot_be_written_or_are_inputs_are_named() {
    let dir = folder_with("outputs", "examples/chair.scad");
    std::fs::create_dir(dir.join("folder")).unwrap();
    std::os::unix::fs::symlink(dir.join("model.scad"), dir.join("link.scad")).unwrap();
    let variant = common::repo().join("examples/variations/chair/bench.scad");
    let before = std::fs::read(dir.join("model.scad")).unwrap();
    let cases: &[(&[&str], &str)] = &[
        (
            &["model.scad", "-o", "folder"],
            "the output `folder` is a folder",
        ),
        (
            &["model.scad", "-o", "./model.scad"],
            "the output `./model.scad` is the input `model.scad`",
        ),
        (
            &["model.scad", "-o", "link.scad"],
            "the output `link.scad` is the input `model.scad`",
        ),
        (
            &["model.scad", "-o", "missing/out.scad"],
            "the folder `missing` does not exist",
        ),
        (
            &["model.scad", "-o", "model.scad/out.scad"],
            "cannot write `model.scad/out.scad`",
        ),
        (
            &["model.scad", "-o", "out.scad", "--report", "folder"],
            "the output `folder` is a folder",
        ),
        (
            &["fit", "model.scad", "--target", "folder", "-o", "link.scad"],
            "the output `link.scad` is the input `model.scad`",
        ),
        (
            &["render", "model.scad", "-o", "./link.scad.png/x.png"],
            "cannot write",
        ),
    ];
    for (args, want) in cases {
        let out = bin().args(*args).current_dir(&dir).output().unwrap();
        let text = stderr(&out);
        assert_eq!(out.status.code(), Some(3), "{args:?}: {text}");
        assert!(text.contains(want), "{args:?}: no `{want}` in {text}");
    }
    // A report over a variation.
    let shown = variant.to_string_lossy().into_owned();
    let out = bin()
        .args([
            "model.scad",
            "-o",
            "out.scad",
            "--vary",
            &shown,
            "--report",
            &shown,
        ])
        .current_dir(&dir)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(3), "{}", stderr(&out));
    assert!(stderr(&out).contains("is the input"), "{}", stderr(&out));
    assert_eq!(std::fs::read(dir.join("model.scad")).unwrap(), before);
    assert_eq!(listing(&dir), ["folder", "link.scad", "model.scad"]);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_variation_that_is_the_model_is_a_diagnostic() {
    let out = bin()
        .args([
            "examples/chair.scad",
            "-o",
            "-",
            "--vary",
            "./examples/chair.scad",
        ])
        .current_dir(common::repo())
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let text = stderr(&out);
    snapshot(
        "variation_is_the_model",
        Path::new("examples/chair.scad"),
        &text,
    );
    assert!(text.starts_with("error[E0603]"), "{text}");
}

/// Starts `args` in `dir`, interrupts it with SIGINT once it has run for `after`, and
/// returns its exit status; fails if it ended before the interrupt.
fn interrupt(dir: &Path, args: &[&str], after: Duration) -> std::process::ExitStatus {
    let mut child = bin()
        .args(args)
        .current_dir(dir)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while start.elapsed() < after {
        assert!(
            child.try_wait().unwrap().is_none(),
            "{args:?} ended before the interrupt"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
    let sent = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(sent.success());
    child.wait().unwrap()
}

#[test]
fn ctrl_c_leaves_no_output_and_the_input_untouched() {
    // The main job on a grid of 196 boxes takes several seconds.
    let dir = folder_with("interrupt", "examples/chair.scad");
    let grid: String = (0..196)
        .map(|k| {
            let (i, j) = (k / 14, k % 14);
            format!(
                "translate([{}, {}, 0]) cube([{}, {}, {}]);\n",
                i * 5,
                j * 5,
                3 + i % 3,
                3 + j % 2,
                4 + (i * j) % 5
            )
        })
        .collect();
    std::fs::write(dir.join("grid.scad"), &grid).unwrap();
    let status = interrupt(
        &dir,
        &["grid.scad", "-o", "out.scad"],
        Duration::from_millis(800),
    );
    assert_eq!(status.code(), Some(130));
    assert_eq!(
        std::fs::read_to_string(dir.join("grid.scad")).unwrap(),
        grid
    );
    // A fit of the chair to its own pictures, with many rounds.
    let out = bin()
        .args([
            "render",
            "model.scad",
            "-o",
            "views",
            "--views",
            "3",
            "--size",
            "48",
            "--cpu",
        ])
        .current_dir(&dir)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", stderr(&out));
    let model = std::fs::read(dir.join("model.scad")).unwrap();
    let status = interrupt(
        &dir,
        &[
            "fit",
            "model.scad",
            "--target",
            "views",
            "-o",
            "fitted.scad",
            "--rounds",
            "50",
            "--cpu",
            "--report",
            "r.json",
        ],
        Duration::from_millis(1500),
    );
    assert_eq!(status.code(), Some(130));
    assert_eq!(std::fs::read(dir.join("model.scad")).unwrap(), model);
    assert_eq!(listing(&dir), ["grid.scad", "model.scad", "views"]);
    let _ = std::fs::remove_dir_all(&dir);
}
