//! The main job against the oracle: the emitted file must load in OpenSCAD, reproduce the
//! input at default values, keep every chosen relation and positive sizes for any slider
//! setting in range, reproduce each variation through its preset, and show its sliders with
//! their groups, descriptions and ranges.

mod common;

use common::*;
use reparamc::analysis::candidates::Candidates;
use reparamc::command::compile::{Compiled, Options, reparameterize};
use reparamc::front::source::SourceMap;
use reparamc::ir::feature::part_features;
use reparamc::ir::{CsgNode, Model, Part};
use std::path::{Path, PathBuf};
use std::process::Command;

struct Run {
    model: Model,
    compiled: Compiled,
    out: PathBuf,
}

fn variations_of(name: &str) -> Vec<PathBuf> {
    let dir = format!("examples/variations/{name}");
    if repo().join(&dir).is_dir() {
        scad_files(&dir)
    } else {
        Vec::new()
    }
}

/// Compiles `model` with `variations` and writes the outputs to a temporary folder.
fn run(model: &Path, variations: &[PathBuf]) -> Run {
    let mut sources = SourceMap::new();
    let (loaded, evaluated) = match reparamc::load_model_parsed(&mut sources, model) {
        Ok(x) => x,
        Err(d) => panic!("{}", d.render_plain(&sources)),
    };
    let mut vars = Vec::new();
    for v in variations {
        match reparamc::variation::load_variation(&mut sources, loaded.main, &evaluated.model, v) {
            Ok(x) => vars.push(x),
            Err(d) => panic!("{}", d.render_plain(&sources)),
        }
    }
    let stem = model.file_stem().unwrap().to_string_lossy().into_owned();
    let options = Options {
        all_constraints: false,
        presets_name: Some(format!("{stem}_param.json")),
        measure: true,
    };
    let compiled = reparameterize(&sources, &loaded, &evaluated.model, &vars, &options);
    let dir = tempfile(model, "out");
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join(format!("{stem}_param.scad"));
    std::fs::write(&out, &compiled.scad).unwrap();
    if let Some(p) = &compiled.presets {
        std::fs::write(out.with_extension("json"), p).unwrap();
    }
    Run {
        model: evaluated.model,
        compiled,
        out,
    }
}

/// `openscad -o x.csg` with extra arguments, returning the parts.
fn export(model: &Path, extra: &[String]) -> Vec<CsgPart> {
    let csg = tempfile(model, "csg");
    let out = Command::new("openscad")
        .args(extra)
        .arg("-o")
        .arg(&csg)
        .arg(model)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "openscad failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(&csg).unwrap();
    let _ = std::fs::remove_file(&csg);
    csg_parts(&text)
}

fn paper_and_natural_runs() -> Vec<(PathBuf, Vec<PathBuf>)> {
    let mut v = Vec::new();
    for m in ["chair", "table", "car", "camera", "bottle"] {
        v.push((
            repo().join(format!("examples/paper/{m}.scad")),
            variations_of(&format!("paper_{m}")),
        ));
    }
    v.push((repo().join("examples/chair.scad"), variations_of("chair")));
    v
}

#[test]
fn defaults_reproduce_the_input_for_every_example() {
    let mut jobs: Vec<(PathBuf, Vec<PathBuf>)> = scad_files("examples")
        .into_iter()
        .map(|p| (p, Vec::new()))
        .collect();
    jobs.extend(
        scad_files("examples/paper")
            .into_iter()
            .map(|p| (p, Vec::new())),
    );
    jobs.extend(paper_and_natural_runs());
    let mut failures = Vec::new();
    for (model, vars) in &jobs {
        let r = run(model, vars);
        let errs = compare_parts(&export(&r.out, &[]), &export(model, &[]));
        if !errs.is_empty() {
            failures.push(format!(
                "{} ({} variations): {}",
                model.display(),
                vars.len(),
                errs.join("; ")
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Every kept relation's residual on OpenSCAD's parts, and every size.
fn check_setting(
    cands: &Candidates,
    compiled: &Compiled,
    parts: &[CsgPart],
    tol: f64,
) -> Vec<String> {
    let mut errs = Vec::new();
    let feats: Vec<_> = parts
        .iter()
        .enumerate()
        .map(|(i, p)| part_features(&part_from_csg(p), i).unwrap_or_default())
        .collect();
    let value = |f: usize| -> Option<Vec<f64>> {
        let af = &cands.features[f];
        let found = feats.get(af.part)?.iter().find(|x| x.kind == af.kind)?;
        Some(found.nums.iter().map(|n| n.value).collect())
    };
    for c in &compiled.kept {
        if c.feature_indices().any(|f| value(f).is_none()) {
            errs.push(format!("no feature for {}", cands.describe(c)));
            continue;
        }
        let residuals = c.residuals(|f| value(f).unwrap_or_default());
        if residuals.iter().any(|r| r.abs() > tol) {
            errs.push(format!(
                "{} fails: residuals {residuals:?}",
                cands.describe(c)
            ));
        }
    }
    for (i, p) in parts.iter().enumerate() {
        let sizes: &[f64] = match p.kind {
            "cube" => &p.args[..3],
            "cylinder" => &p.args[..1],
            _ => &p.args[..],
        };
        if sizes.iter().any(|&s| s <= 0.0) {
            errs.push(format!(
                "part {i} has a size that is not positive: {:?}",
                p.args
            ));
        }
    }
    errs
}

fn random_settings(model: &Path, vars: &[PathBuf], count: usize, seed: u64) {
    let r = run(model, vars);
    let tol = 1e-4 * r.model.size();
    let mut rng = Rng(seed);
    let mut failures = Vec::new();
    for k in 0..count {
        let mut defs = Vec::new();
        for f in &r.compiled.report.free_variables {
            let v = f.range.min + rng.next() * (f.range.max - f.range.min);
            defs.push(format!("{}={v}", f.name));
        }
        // Every other setting also blends toward the variations.
        if k % 2 == 1 {
            for v in &r.compiled.report.variations {
                let name = reparamc::analysis::names::sanitize(&v.name);
                defs.push(format!("{name}={}", rng.next()));
            }
        }
        let args: Vec<String> = defs
            .iter()
            .flat_map(|d| ["-D".to_string(), d.clone()])
            .collect();
        let parts = export(&r.out, &args);
        let errs = check_setting(&r.compiled.candidates, &r.compiled, &parts, tol);
        if !errs.is_empty() {
            failures.push(format!("{}: {}", defs.join(" "), errs.join("; ")));
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {count} settings break the model:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

#[test]
fn random_settings_keep_relations_paper_chair() {
    random_settings(
        &repo().join("examples/paper/chair.scad"),
        &variations_of("paper_chair"),
        200,
        0x9e3779b97f4a7c15,
    );
}

#[test]
fn random_settings_keep_relations_other_models() {
    for (m, seed) in [("table", 3), ("car", 5), ("camera", 7), ("bottle", 11)] {
        let model = repo().join(format!("examples/paper/{m}.scad"));
        random_settings(&model, &variations_of(&format!("paper_{m}")), 25, seed);
    }
    random_settings(&repo().join("examples/stool.scad"), &[], 25, 13);
}

fn union_of(n: usize) -> CsgNode {
    CsgNode::Union((0..n).map(CsgNode::Part).collect())
}

#[test]
fn presets_reproduce_their_variations() {
    let mut failures = Vec::new();
    for (model, vars) in paper_and_natural_runs() {
        let r = run(&model, &vars);
        for (j, v) in r.compiled.report.variations.iter().enumerate() {
            let name = reparamc::analysis::names::sanitize(&v.name);
            let json = r.out.with_extension("json");
            let args = vec![
                "-p".to_string(),
                json.display().to_string(),
                "-P".to_string(),
                name,
            ];
            let theirs: Vec<Part> = export(&r.out, &args).iter().map(part_from_csg).collect();
            let skip: Vec<usize> = v
                .optional_parts
                .iter()
                .filter_map(|n| r.model.parts.iter().position(|p| &p.name == n))
                .collect();
            let ours: Vec<Part> = r
                .model
                .parts_at(&r.compiled.projected[j])
                .unwrap()
                .into_iter()
                .enumerate()
                .filter(|(i, _)| !skip.contains(i))
                .map(|(_, p)| p)
                .collect();
            let (a, b) = (anchored(&theirs), anchored(&ours));
            let iou = reparamc::geom::iou((&a, &union_of(a.len())), (&b, &union_of(b.len())));
            if a.len() != b.len() || iou < 0.99 {
                failures.push(format!(
                    "{} preset {}: {} vs {} parts, IoU {iou}",
                    model.display(),
                    v.name,
                    a.len(),
                    b.len()
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn ast_shows_every_slider_with_group_description_and_range() {
    let r = run(
        &repo().join("examples/paper/chair.scad"),
        &variations_of("paper_chair"),
    );
    let ast = tempfile(&r.out, "ast");
    let out = Command::new("openscad")
        .arg("-o")
        .arg(&ast)
        .arg(&r.out)
        .output()
        .unwrap();
    assert!(out.status.success());
    let text = std::fs::read_to_string(&ast).unwrap();
    let _ = std::fs::remove_file(&ast);
    for f in &r.compiled.report.free_variables {
        let fmt = |v: f64| reparamc::back::emit::number(v);
        let block = format!(
            "//Group(\"Shape\")\n//Description(\"{}\")\n//Parameter([{} : {} : {}])\n{} = {};",
            f.description,
            fmt(f.range.min),
            fmt(f.range.step),
            fmt(f.range.max),
            f.name,
            fmt(f.value)
        );
        assert!(
            text.contains(&block),
            "missing in .ast:\n{block}\n---\n{text}"
        );
    }
    for v in &r.compiled.report.variations {
        let name = reparamc::analysis::names::sanitize(&v.name);
        assert!(
            text.contains("//Group(\"Variations\")\n//Description("),
            "no Variations group"
        );
        assert!(
            text.contains(&format!("//Parameter([0 : 0.05 : 1])\n{name} = 0;")),
            "no blend slider for {name}"
        );
    }
    assert!(text.contains("//Group(\"Parts\")"), "no part switches");
}

#[test]
fn diff_prints_what_changed_from_input_to_output() {
    // In a folder of its own, so the diff's headers are the plain file names.
    let dir = tempfile(Path::new("stool.scad"), "dir");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::copy(repo().join("examples/stool.scad"), dir.join("stool.scad")).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_reparamc"))
        .args(["stool.scad", "-o", "stool_param.scad", "--diff"])
        .current_dir(&dir)
        .env("NO_COLOR", "1")
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{stderr}");
    let diff = String::from_utf8(out.stdout).unwrap();
    let written = std::fs::read_to_string(dir.join("stool_param.scad")).unwrap();
    let input = std::fs::read_to_string(dir.join("stool.scad")).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    assert!(
        diff.starts_with("--- stool.scad\n+++ stool_param.scad\n@@ "),
        "{diff}"
    );
    // Every removed line is the input's and every added line the output's.
    for line in diff.lines().skip(2) {
        if let Some(l) = line.strip_prefix('-') {
            assert!(input.lines().any(|i| i == l), "not in the input: {l}");
        } else if let Some(l) = line.strip_prefix('+') {
            assert!(written.lines().any(|o| o == l), "not in the output: {l}");
        }
    }
    assert!(stderr.contains("stool_param.scad: "), "{stderr}");
    let mut settings = insta::Settings::clone_current();
    settings.set_snapshot_path("../snapshots");
    settings.set_prepend_module_to_snapshot(false);
    settings.bind(|| insta::assert_snapshot!("diff_stool", diff));
}

#[test]
fn diff_and_standard_output_do_not_mix() {
    let out = Command::new(env!("CARGO_BIN_EXE_reparamc"))
        .args(["examples/stool.scad", "-o", "-", "--diff"])
        .current_dir(repo())
        .env("NO_COLOR", "1")
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(out.stdout.is_empty());
}
