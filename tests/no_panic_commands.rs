//! Nothing panics in the commands a user runs, whatever the files: property tests over
//! the main job with mutated variant files (and its presets, report, plot and diff),
//! `render` with extreme models and cameras, and `fit` with mutated targets (a mangled
//! `cameras.json`, truncated, odd or differently sized images, missing files, an empty
//! folder).
//!
//! Each case runs under `catch_unwind`; any panic fails it and proptest shrinks the input.
//! The seed is fixed; `NO_PANIC_COMMAND_CASES` (default 24 per property) runs a longer
//! search, and failures are persisted to `tests/no_panic_commands.proptest-regressions`.

mod common;
#[path = "common/mutate.rs"]
mod mutate;

use mutate::{Mutation, NUMBERS, apply, mutation};
use proptest::prelude::*;
use proptest::test_runner::{FileFailurePersistence, RngSeed, TestCaseError};
use reparamc::command::compile::{CompileOptions, compile};
use reparamc::command::fit::{self, Settings};
use reparamc::command::render::{self, BackendChoice, Cameras, Layout, Pictures, Projection};
use reparamc::front::source::SourceMap;
use std::path::PathBuf;
use std::sync::OnceLock;
use std::sync::atomic::{AtomicUsize, Ordering};

fn config(seed: u64) -> ProptestConfig {
    let cases = std::env::var("NO_PANIC_COMMAND_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(24);
    ProptestConfig {
        cases,
        rng_seed: RngSeed::Fixed(seed),
        failure_persistence: Some(Box::new(FileFailurePersistence::Direct(
            "tests/no_panic_commands.proptest-regressions",
        ))),
        max_shrink_iters: 256,
        ..ProptestConfig::default()
    }
}

/// Runs `f`; a panic is the case's failure, named with `what`.
fn no_panic(what: &str, f: impl FnOnce() + std::panic::UnwindSafe) -> Result<(), TestCaseError> {
    std::panic::catch_unwind(f).map_err(|p| {
        let text = p
            .downcast_ref::<&str>()
            .map(|s| (*s).to_string())
            .or_else(|| p.downcast_ref::<String>().cloned())
            .unwrap_or_default();
        TestCaseError::fail(format!("panic `{text}` in {what}"))
    })
}

/// A fresh scratch folder for one case.
fn scratch(name: &str) -> PathBuf {
    static N: AtomicUsize = AtomicUsize::new(0);
    let dir = std::env::temp_dir().join(format!(
        "reparamc-nopanic-{}-{name}-{}",
        std::process::id(),
        N.fetch_add(1, Ordering::Relaxed)
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch folder");
    dir
}

const MODEL: &str = "examples/chair.scad";

fn variants() -> Vec<PathBuf> {
    common::scad_files("examples/variations/chair")
}

/// The main job on the chair with its variations, one of them mutated; everything the
/// command makes is made (presets, report, plot, diff), or the diagnostic rendered.
fn main_job(which: usize, edits: &[Mutation]) {
    let dir = scratch("main");
    let mut vars = variants();
    let i = which % vars.len();
    let mut text = std::fs::read(&vars[i]).expect("variant readable");
    for m in edits {
        apply(&mut text, m);
    }
    let mutated = dir.join("variant.scad");
    std::fs::write(&mutated, &text).expect("write variant");
    vars[i] = mutated;
    vars.truncate(3);
    let options = CompileOptions {
        model: common::repo().join(MODEL),
        variations: vars,
        plot: Some(reparamc::back::plot::PlotFormat::Svg),
        diff_to: Some("out.scad".into()),
        ..CompileOptions::default()
    };
    let mut sources = SourceMap::new();
    match compile(&options, &mut sources) {
        Ok(out) => {
            let _ = out.compiled.report.to_json();
            let _ = out.compiled.report.summary_line("out.scad");
            for w in &out.warnings {
                let _ = w.render_plain(&sources);
            }
        }
        Err(d) => {
            let _ = d.render_plain(&sources);
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// Numbers a model or a camera may be given.
const EXTREME: &[&str] = &[
    "0", "-0", "1", "-1", "3.5", "1e-300", "5e-324", "1e15", "1e300", "1e308", "-1e308", "1e999",
    "0/0", "-1e999", "1e-9",
];

fn extreme() -> impl Strategy<Value = &'static str> {
    prop::sample::select(EXTREME)
}

/// A camera in OpenSCAD's syntax: six or seven numbers, or something that is not one.
fn camera() -> impl Strategy<Value = String> {
    let number = prop_oneof![
        4 => extreme().prop_map(str::to_owned),
        1 => prop::sample::select(&["nan", "inf", "-inf", "", "x", "1,2"][..]).prop_map(str::to_owned),
    ];
    prop::collection::vec(number, 0..9).prop_map(|v| v.join(","))
}

fn cameras() -> impl Strategy<Value = Cameras> {
    prop_oneof![
        (prop::collection::vec(camera(), 1..4), any::<bool>()).prop_map(|(specs, ortho)| {
            Cameras::OpenScad {
                specs,
                projection: if ortho {
                    Projection::Orthographic
                } else {
                    Projection::Perspective
                },
            }
        }),
        (0usize..7).prop_map(Cameras::Around),
    ]
}

/// A small model whose every number is extreme.
fn extreme_model() -> impl Strategy<Value = String> {
    prop::collection::vec(extreme(), 8).prop_map(|n| {
        format!(
            "translate([{}, {}, {}]) cube([{}, {}, {}]);\nscale({}) sphere({});\n",
            n[0], n[1], n[2], n[3], n[4], n[5], n[6], n[7]
        )
    })
}

fn render_case(model: &str, cameras: Cameras, size: (u32, u32), grid: bool) {
    let dir = scratch("render");
    let path = dir.join("m.scad");
    std::fs::write(&path, model).expect("write model");
    let opts = render::Options {
        model: path,
        call: None,
        size,
        cameras,
        backend: BackendChoice {
            gpu: false,
            cpu: true,
        },
        layout: if grid { Layout::Grid } else { Layout::Views },
    };
    let mut sources = SourceMap::new();
    let _ = render::render(&opts, &mut sources);
    let _ = std::fs::remove_dir_all(&dir);
}

/// A target folder's pictures (name, PNG), its `cameras.json`, and a picture of another size.
type Targets = (Vec<(String, Vec<u8>)>, String, Vec<u8>);

/// A target folder of two 16×16 views of a small model, and one view at another size.
fn base_targets() -> &'static Targets {
    static BASE: OnceLock<Targets> = OnceLock::new();
    BASE.get_or_init(|| {
        let views = |size, n| {
            let opts = render::Options {
                model: common::repo().join("examples/paper/bottle.scad"),
                call: None,
                size,
                cameras: Cameras::Around(n),
                backend: BackendChoice {
                    gpu: false,
                    cpu: true,
                },
                layout: Layout::Views,
            };
            match render::render(&opts, &mut SourceMap::new()) {
                Ok(r) => match r.pictures {
                    Pictures::Views {
                        files,
                        cameras_json,
                    } => (files, cameras_json),
                    Pictures::Grid { .. } => panic!("asked for views"),
                },
                Err(_) => panic!("the bottle renders"),
            }
        };
        let (files, json) = views((16, 16), 2);
        let (other, _) = views((24, 12), 1);
        (files, json, other[0].1.clone())
    })
}

/// What happens to one file of a target folder.
#[derive(Debug, Clone)]
enum FileEdit {
    Keep,
    Drop,
    Truncate(f64),
    OtherSize,
    Garbage(Vec<u8>),
    Edit(Vec<Mutation>),
}

fn file_edit() -> impl Strategy<Value = FileEdit> {
    prop_oneof![
        4 => Just(FileEdit::Keep),
        1 => Just(FileEdit::Drop),
        1 => (0.0..1.0f64).prop_map(FileEdit::Truncate),
        1 => Just(FileEdit::OtherSize),
        1 => prop::collection::vec(any::<u8>(), 0..64).prop_map(FileEdit::Garbage),
        2 => prop::collection::vec(mutation(), 1..4).prop_map(FileEdit::Edit),
    ]
}

fn edited(bytes: &[u8], edit: &FileEdit, other: &[u8]) -> Option<Vec<u8>> {
    Some(match edit {
        FileEdit::Keep => bytes.to_vec(),
        FileEdit::Drop => return None,
        FileEdit::Truncate(f) => bytes[..(bytes.len() as f64 * f) as usize].to_vec(),
        FileEdit::OtherSize => other.to_vec(),
        FileEdit::Garbage(g) => g.clone(),
        FileEdit::Edit(ms) => {
            let mut b = bytes.to_vec();
            for m in ms {
                apply(&mut b, m);
            }
            b
        }
    })
}

fn fit_case(json_edit: &FileEdit, image_edits: &[FileEdit], empty: bool, subspace: bool) {
    let (files, json, other) = base_targets();
    let dir = scratch("fit");
    if !empty {
        if let Some(b) = edited(json.as_bytes(), json_edit, json.as_bytes()) {
            std::fs::write(dir.join("cameras.json"), b).expect("write cameras");
        }
        for ((name, png), edit) in files.iter().zip(image_edits.iter().cycle()) {
            if let Some(b) = edited(png, edit, other) {
                std::fs::write(dir.join(name), b).expect("write view");
            }
        }
    }
    let opts = fit::Options {
        model: common::repo().join("examples/paper/bottle.scad"),
        target: dir.clone(),
        subspace,
        max_size: None,
        gallery: true,
        backend: BackendChoice {
            gpu: false,
            cpu: true,
        },
        settings: Settings {
            iterations: 2,
            rounds: 1,
            polish: 0,
            refine: 0,
            proportions: false,
            ..Settings::default()
        },
    };
    let mut sources = SourceMap::new();
    if let Ok(job) = fit::prepare(&opts, &mut sources)
        && let Ok(fitted) = job.run(&mut |_| {})
    {
        let _ = serde_json::to_string(&fitted.report);
    }
    let _ = std::fs::remove_dir_all(&dir);
}

proptest! {
    #![proptest_config(config(0x3a1b))]
    #[test]
    fn main_job_with_mutated_variants(which in 0usize..6, edits in prop::collection::vec(mutation(), 1..4)) {
        no_panic("the main job", || main_job(which, &edits))?;
    }
}

proptest! {
    #![proptest_config(config(0x3a1c))]
    #[test]
    fn render_extreme_models_and_cameras(
        model in extreme_model(),
        cams in cameras(),
        w in 1u32..24,
        h in 1u32..24,
        grid in any::<bool>(),
    ) {
        no_panic("render", || render_case(&model, cams, (w, h), grid))?;
    }
}

proptest! {
    #![proptest_config(config(0x3a1d))]
    #[test]
    fn fit_with_mutated_targets(
        json in file_edit(),
        images in prop::collection::vec(file_edit(), 1..3),
        empty in prop::bool::weighted(0.05),
        subspace in any::<bool>(),
    ) {
        no_panic("fit", || fit_case(&json, &images, empty, subspace))?;
    }
}

/// The numbers the variant mutations use include every extreme the model properties use.
#[test]
fn extremes_are_tried() {
    for n in ["1e308", "0/0", "-1e308"] {
        assert!(NUMBERS.contains(&n) && EXTREME.contains(&n), "{n}");
    }
}
