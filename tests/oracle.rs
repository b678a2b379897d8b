//! OpenSCAD is the oracle: our evaluated parts must equal the primitives of its `.csg`
//! export, and our affine forms must predict how its geometry moves when a slot changes.

mod common;

use common::*;
use reparamc::front::source::SourceMap;
use reparamc::ir::Model;
use reparamc::ir::feature::part_features;
use std::path::{Path, PathBuf};

fn all_models() -> Vec<PathBuf> {
    let mut v = scad_files("examples");
    v.extend(scad_files("examples/paper"));
    v.extend(scad_files("tests/models"));
    v
}

fn evaluate(path: &Path) -> Model {
    let mut sources = SourceMap::new();
    match reparamc::load_model(&mut sources, path) {
        Ok(e) => e.model,
        Err(d) => panic!("{}", d.render_plain(&sources)),
    }
}

/// Runs `f` over `items` on two threads (the CI machine has two cores).
fn parallel<T: Sync, R: Send>(items: &[T], f: impl Fn(&T) -> R + Sync) -> Vec<R> {
    let half = items.len().div_ceil(2);
    std::thread::scope(|s| {
        let (a, b) = items.split_at(half);
        let f = &f;
        let h = s.spawn(move || a.iter().map(f).collect::<Vec<R>>());
        let mut rb: Vec<R> = b.iter().map(f).collect();
        let mut ra = h.join().expect("worker panicked");
        ra.append(&mut rb);
        ra
    })
}

#[test]
fn there_are_enough_test_models() {
    assert!(scad_files("tests/models").len() >= 40);
}

#[test]
fn parts_equal_openscad_csg_export() {
    let models = all_models();
    let failures: Vec<String> = parallel(&models, |path| {
        let ours: Vec<CsgPart> = evaluate(path).parts.iter().map(our_part).collect();
        let theirs = csg_parts(&openscad_csg(path));
        let errs = compare_parts(&ours, &theirs);
        (!errs.is_empty()).then(|| format!("{}:\n  {}", path.display(), errs.join("\n  ")))
    })
    .into_iter()
    .flatten()
    .collect();
    assert!(
        failures.is_empty(),
        "{} of {} models disagree with OpenSCAD:\n{}",
        failures.len(),
        models.len(),
        failures.join("\n")
    );
}

/// The source with one literal replaced.
fn perturbed_source(text: &str, span: std::ops::Range<usize>, value: f64) -> String {
    format!("{}{}{}", &text[..span.start], value, &text[span.end..])
}

/// Slots to perturb in a model: a deterministic spread of at most `n`.
fn sample(count: usize, n: usize) -> Vec<usize> {
    if count <= n {
        return (0..count).collect();
    }
    (0..n)
        .map(|k| (k * count) / n + (k * 7919) % (count / n).max(1))
        .collect()
}

#[test]
fn affine_forms_predict_openscad_under_perturbation() {
    let models = all_models();
    let failures: Vec<String> = parallel(&models, |path| {
        let model = evaluate(path);
        let text = std::fs::read_to_string(path).expect("readable model");
        let base_values = model.slot_values();
        let features: Vec<_> = model
            .parts
            .iter()
            .enumerate()
            .filter(|(_, p)| p.misaligned.is_none())
            .filter_map(|(i, p)| part_features(p, i))
            .flatten()
            .collect();
        let mut errs = Vec::new();
        for s in sample(model.slots.len(), 3) {
            let slot = &model.slots[s];
            if slot.span.file != 0 {
                continue; // literals of included files are perturbed through their own tests
            }
            let delta = if slot.value.abs() >= 2.0 { 1.0 } else { 0.25 };
            let new_text = perturbed_source(&text, slot.span.range(), slot.value + delta);
            let tmp = tempfile(path, "scad");
            std::fs::write(&tmp, new_text).expect("write temp model");
            // Includes are resolved next to the model, so write beside it when it has any.
            let csg = if text.contains("include") || text.contains("use <") {
                let beside = path.with_file_name(format!(
                    ".perturbed-{}",
                    tmp.file_name().unwrap().to_string_lossy()
                ));
                std::fs::rename(&tmp, &beside).expect("move temp model");
                let c = openscad_csg(&beside);
                let _ = std::fs::remove_file(&beside);
                c
            } else {
                let c = openscad_csg(&tmp);
                let _ = std::fs::remove_file(&tmp);
                c
            };
            let theirs = csg_parts(&csg);
            let mut values = base_values.clone();
            values[s] += delta;
            for f in &features {
                let Some(part) = theirs.get(f.part) else {
                    errs.push(format!("slot {}: part {} vanished", slot.name, f.part));
                    break;
                };
                let Some(actual) = part_features(&part_from_csg(part), f.part) else {
                    continue;
                };
                let Some(af) = actual.iter().find(|a| a.kind == f.kind && a.role == f.role) else {
                    continue;
                };
                for (n, a) in f.nums.iter().zip(&af.nums) {
                    let Some(form) = n.affine() else { continue };
                    let predicted = form.eval(&values);
                    if !agrees(predicted, a.value)
                        && (predicted - a.value).abs() > 1e-5 * a.value.abs().max(1.0)
                    {
                        errs.push(format!(
                            "moving {} by {delta}: {}.{} predicted {predicted}, OpenSCAD {}",
                            slot.name, model.parts[f.part].name, f.role, a.value
                        ));
                    }
                }
            }
        }
        (!errs.is_empty()).then(|| format!("{}:\n  {}", path.display(), errs.join("\n  ")))
    })
    .into_iter()
    .flatten()
    .collect();
    assert!(
        failures.is_empty(),
        "affine forms mispredict OpenSCAD:\n{}",
        failures.join("\n")
    );
}
