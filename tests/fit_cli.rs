//! `reparamc render` and `reparamc fit` from the outside: a round trip, and every kind of
//! bad input reported with the file and what is wrong, a non-zero exit, and no output.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_reparamc"))
}

fn repo(rel: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(rel)
}

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("reparamc-fit-cli-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Renders a small target folder of `model`.
fn targets(model: &str, dir: &Path) {
    let o = bin()
        .args(["render", "--cpu", "--size", "40", "--views", "3", "-o"])
        .arg(dir)
        .arg(repo(model))
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
}

fn fit(target: &Path, out: &Path, extra: &[&str]) -> Output {
    bin()
        .args(["fit", "--cpu", "--rounds", "2", "--iterations", "3"])
        .args(extra)
        .arg("--target")
        .arg(target)
        .arg("-o")
        .arg(out)
        .arg(repo("examples/chair.scad"))
        .output()
        .unwrap()
}

/// The main command on the chair with the variation `vary`, writing `out`.
fn chair_varied_by(vary: &Path, out: &Path) -> Output {
    bin()
        .arg(repo("examples/chair.scad"))
        .arg("--vary")
        .arg(vary)
        .arg("-o")
        .arg(out)
        .output()
        .unwrap()
}

/// A failed fit: non-zero exit, the message mentions every `needles`, no output written.
fn fails(target: &Path, needles: &[&str]) {
    fails_with(target, &[], needles);
}

/// [`fails`] with `extra` arguments.
fn fails_with(target: &Path, extra: &[&str], needles: &[&str]) {
    let out = target.parent().unwrap().join(format!(
        "{}-fitted.scad",
        target.file_name().unwrap().to_string_lossy()
    ));
    let o = fit(target, &out, extra);
    let err = stderr(&o);
    assert!(
        !o.status.success(),
        "expected a failure, got success: {err}"
    );
    for n in needles {
        assert!(err.contains(n), "`{n}` not in: {err}");
    }
    assert!(!out.exists(), "a partial output was written");
    assert!(!err.contains("panicked"), "{err}");
}

#[test]
fn render_then_fit_round_trip() {
    let d = scratch("roundtrip");
    let t = d.join("lounge");
    targets("examples/variations/chair/lounge.scad", &t);
    assert!(t.join("cameras.json").exists());
    let out = d.join("fitted.scad");
    let report = d.join("report.json");
    let gallery = d.join("gallery.png");
    let o = fit(
        &t,
        &out,
        &[
            "--report",
            report.to_str().unwrap(),
            "--gallery",
            gallery.to_str().unwrap(),
            "--border",
            "0.25",
            "--refine",
            "1",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("renderer: CPU"));
    // The fitted file is the same program with other numbers.
    let mut sources = reparamc::front::source::SourceMap::new();
    let fitted = reparamc::load_model(&mut sources, &out).unwrap().model;
    let mut sources = reparamc::front::source::SourceMap::new();
    let base = reparamc::load_model(&mut sources, &repo("examples/chair.scad"))
        .unwrap()
        .model;
    assert_eq!(fitted.slots.len(), base.slots.len());
    assert_eq!(fitted.parts.len(), base.parts.len());
    let rep: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    assert_eq!(rep["curve"].as_array().unwrap().len(), 6);
    let png = reparamc::render::image::Rgb::read_png(&gallery).unwrap();
    assert_eq!(png.width, 3 * 40 + 4);
    // Beside it, its uncertainty: every number the pictures show, with its deviation,
    // and the summary says how many they do not.
    let side: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(d.join("fitted.json")).unwrap()).unwrap();
    assert_eq!(side["format"], "reparamc-fit-uncertainty/1");
    let numbers = side["numbers"].as_array().unwrap();
    assert!(!numbers.is_empty() && numbers.len() <= base.slots.len());
    assert_eq!(side["information"].as_array().unwrap().len(), numbers.len());
    assert!(stderr(&o).contains("numbers the pictures do not determine"));
    // The main command reads it back with the variation.
    let o = chair_varied_by(&out, &d.join("param.scad"));
    assert!(o.status.success(), "{}", stderr(&o));
    // A stale sidecar (the variant edited after the fit: here, the sidecar's record of a
    // number) is an error that names it.
    let mut stale = side.clone();
    let v = stale["numbers"][0]["value"].as_f64().unwrap();
    stale["numbers"][0]["value"] = serde_json::json!(v + 1.0);
    std::fs::write(d.join("fitted.json"), stale.to_string()).unwrap();
    let o = chair_varied_by(&out, &d.join("param2.scad"));
    assert!(!o.status.success());
    assert!(stderr(&o).contains("E0604"), "{}", stderr(&o));
    assert!(stderr(&o).contains("fitted.json"), "{}", stderr(&o));
    assert!(!d.join("param2.scad").exists());
}

#[test]
fn the_report_cannot_take_the_sidecars_place() {
    let d = scratch("sidecar-clash");
    let t = d.join("lounge");
    targets("examples/variations/chair/lounge.scad", &t);
    let out = d.join("fitted.scad");
    let o = fit(
        &t,
        &out,
        &["--report", d.join("fitted.json").to_str().unwrap()],
    );
    assert!(!o.status.success());
    assert!(stderr(&o).contains("uncertainty"), "{}", stderr(&o));
    assert!(!out.exists());
}

#[test]
fn bad_target_folders() {
    let d = scratch("bad");
    // No such folder.
    fails(
        &d.join("nowhere"),
        &["nowhere", "cannot open the target folder"],
    );
    // No images.
    let empty = d.join("empty");
    std::fs::create_dir_all(&empty).unwrap();
    fails(&empty, &["empty", "no images"]);
    // Images but no cameras.json.
    let good = d.join("good");
    targets("examples/chair.scad", &good);
    let nojson = d.join("nojson");
    std::fs::create_dir_all(&nojson).unwrap();
    std::fs::copy(good.join("front.png"), nojson.join("front.png")).unwrap();
    fails(&nojson, &["cameras.json", "missing"]);
    // Malformed cameras.json.
    let bad = d.join("badjson");
    std::fs::create_dir_all(&bad).unwrap();
    std::fs::copy(good.join("front.png"), bad.join("front.png")).unwrap();
    std::fs::write(
        bad.join("cameras.json"),
        "[{\"name\": \"front\", \"eye\": [0, 1]",
    )
    .unwrap();
    fails(&bad, &["cameras.json", "not a list of cameras"]);
    // A camera with no eye.
    std::fs::write(
        bad.join("cameras.json"),
        r#"[{"name": "front", "center": [0, 0, 0]}]"#,
    )
    .unwrap();
    fails(&bad, &["cameras.json", "no `eye`"]);
    // A camera whose picture is missing.
    let missing = d.join("missing");
    copy_dir(&good, &missing);
    std::fs::remove_file(missing.join("right.png")).unwrap();
    fails(&missing, &["right.png", "cannot read it"]);
    // A truncated PNG.
    let trunc = d.join("truncated");
    copy_dir(&good, &trunc);
    let bytes = std::fs::read(trunc.join("front.png")).unwrap();
    std::fs::write(trunc.join("front.png"), &bytes[..bytes.len() / 2]).unwrap();
    fails(&trunc, &["front.png", "truncated"]);
    // Not a PNG at all.
    let text = d.join("text");
    copy_dir(&good, &text);
    std::fs::write(text.join("front.png"), "hello").unwrap();
    fails(&text, &["front.png", "not a PNG, JPEG or WebP"]);
    // A picture of another size than cameras.json says.
    let sizes = d.join("sizes");
    copy_dir(&good, &sizes);
    let small = reparamc::render::image::Rgb::new(20, 20, [1.0; 3]);
    std::fs::write(sizes.join("right.png"), small.encode_png()).unwrap();
    fails(&sizes, &["right.png", "20×20", "cameras.json"]);
    // Settings out of range name the flag.
    fails_with(
        &good,
        &["--settle", "2"],
        &["--settle", "not a number from 0 to 1"],
    );
    fails_with(
        &good,
        &["--border", "1.5"],
        &["--border", "not a number from 0 to 1"],
    );
    fails_with(
        &good,
        &["--sigma", "2,-1"],
        &["--sigma", "two positive numbers"],
    );
    fails_with(
        &good,
        &["--size-prior=-1e-5"],
        &["--size-prior", "must not be negative"],
    );
    fails_with(
        &good,
        &["--tie-prior=-1e-5"],
        &["--tie-prior", "must not be negative"],
    );
}

#[test]
fn nothing_in_view() {
    let d = scratch("view");
    let t = d.join("away");
    std::fs::create_dir_all(&t).unwrap();
    // A camera far off to the side, looking away from the chair.
    std::fs::write(
        t.join("cameras.json"),
        r#"[{"name": "away", "eye": [5000, 0, 0], "center": [9000, 0, 0], "width": 32, "height": 32}]"#,
    )
    .unwrap();
    std::fs::write(
        t.join("away.png"),
        reparamc::render::image::Rgb::new(32, 32, [1.0; 3]).encode_png(),
    )
    .unwrap();
    fails(&t, &["E0702", "no part of the model is in view"]);
}

#[test]
fn bad_render_arguments() {
    let d = scratch("render");
    let out = d.join("x.png");
    for (args, needle) in [
        (vec!["--camera", "1,2,3"], "6 numbers"),
        (vec!["--camera", "0,0,0,a,0,0,100"], "`a` is not a number"),
        (vec!["--size", "0"], "is not a size"),
        (
            vec!["--camera", "0,0,0,0,0,0"],
            "eye and center are the same point",
        ),
    ] {
        let o = bin()
            .arg("render")
            .args(&args)
            .arg("-o")
            .arg(&out)
            .arg(repo("examples/chair.scad"))
            .output()
            .unwrap();
        let err = stderr(&o);
        assert!(!o.status.success(), "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: `{needle}` not in {err}");
        assert!(!out.exists());
    }
    // The model file is reported like any model error.
    let o = bin()
        .args(["render", "-o"])
        .arg(&out)
        .arg(repo("tests/bad/unclosed_brace.scad"))
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1));
    assert!(!out.exists());
}

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let e = e.unwrap();
        std::fs::copy(e.path(), to.join(e.file_name())).unwrap();
    }
}
