//! Snapshots of the emitted OpenSCAD for every example (structural prior, no variations)
//! and for the chairs with their variations. A change to the output shows as a diff
//! (`cargo insta review`); every accepted snapshot was read.

mod common;

use common::*;
use reparamc::command::compile::{Options, reparameterize};
use reparamc::front::source::SourceMap;
use std::path::{Path, PathBuf};

fn emitted(model: &Path, variations: &[PathBuf]) -> String {
    let mut sources = SourceMap::new();
    // Relative paths keep the snapshots the same on every machine.
    let rel = model.strip_prefix(repo()).unwrap_or(model).to_path_buf();
    let (loaded, evaluated) = reparamc::load_model_parsed(&mut sources, &rel).expect("model loads");
    let vars: Vec<_> = variations
        .iter()
        .map(|v| {
            let rel = v.strip_prefix(repo()).unwrap_or(v);
            reparamc::variation::load_variation(&mut sources, loaded.main, &evaluated.model, rel)
                .expect("variation loads")
        })
        .collect();
    let stem = model.file_stem().unwrap().to_string_lossy();
    let options = Options {
        all_constraints: false,
        presets_name: Some(format!("{stem}_param.json")),
        measure: false,
    };
    reparameterize(&sources, &loaded, &evaluated.model, &vars, &options).scad
}

fn settings() -> insta::Settings {
    let mut s = insta::Settings::clone_current();
    s.set_snapshot_path("../snapshots");
    s.set_prepend_module_to_snapshot(false);
    s
}

#[test]
fn every_example_without_variations() {
    let mut models = scad_files("examples");
    models.extend(scad_files("examples/paper"));
    for m in models {
        let dir = m
            .parent()
            .unwrap()
            .file_name()
            .unwrap()
            .to_string_lossy()
            .into_owned();
        let stem = m.file_stem().unwrap().to_string_lossy().into_owned();
        let name = if dir == "paper" {
            format!("emit_paper_{stem}")
        } else {
            format!("emit_{stem}")
        };
        settings().bind(|| insta::assert_snapshot!(name, emitted(&m, &[])));
    }
}

#[test]
fn chairs_with_variations() {
    for (model, dir, name) in [
        (
            "examples/paper/chair.scad",
            "examples/variations/paper_chair",
            "emit_paper_chair_varied",
        ),
        (
            "examples/chair.scad",
            "examples/variations/chair",
            "emit_chair_varied",
        ),
    ] {
        let vars = scad_files(dir);
        settings().bind(|| insta::assert_snapshot!(name, emitted(&repo().join(model), &vars)));
    }
}
