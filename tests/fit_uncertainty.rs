//! A fit says how well its pictures determine every number, and discovery listens: a
//! variation fitted from pictures where a part is hidden does not pull that part's
//! relations.
//!
//! The model is a table whose top hides a bolt; the pictures show a thicker top. No camera
//! sees the bolt, so the fit can say nothing of where it belongs, and whatever it leaves
//! there (the bolt stretched with the table by the proportions search, or left where it
//! was) is no evidence. The fit runs slot by slot, so nothing but the pictures moves a
//! number. Read with its uncertainty sidecar, the fitted variation keeps the
//! bolt in the top's middle; the sidecar is what decides that.

use reparamc::command::compile::{CompileOptions, compile};
use reparamc::command::fit::Settings;
use reparamc::front::source::SourceMap;
use reparamc::ir::Model;
use reparamc::ir::feature::world_intervals;
use reparamc::tolerance::NOISE_MAX_SHARE;
use reparamc::variation::uncertainty::sidecar_path;
use std::path::Path;

#[path = "fit_support/views.rs"]
mod views;

const TABLE: &str = "\
// top
translate([0, 0, 40]) cube([60, 40, 4]);
// legs
cube([4, 4, 40]);
translate([56, 0, 0]) cube([4, 4, 40]);
translate([0, 36, 0]) cube([4, 4, 40]);
translate([56, 36, 0]) cube([4, 4, 40]);
// bolt, hidden inside the top
translate([20, 15, 41.5]) cube([20, 10, 1]);
";

/// The same table with a top three times as thick (the bolt as it was: no picture shows
/// it). No stretch of the whole table makes it, so the fit moves the top's faces on their
/// own and the bolt, which nothing moves, is left off the top's middle.
fn thicker() -> String {
    TABLE.replace("cube([60, 40, 4])", "cube([60, 40, 12])")
}

/// The bolt's and the top's middles along z at slot values `x`.
fn middles(model: &Model, x: &[f64]) -> (f64, f64) {
    let part = |name: &str| {
        model
            .parts
            .iter()
            .position(|p| p.name == name)
            .unwrap_or_else(|| panic!("no part {name}"))
    };
    let mid = |p: usize| {
        let z = &world_intervals(&model.parts[p]).expect("a box")[2];
        let at = |n: &reparamc::ir::Num| n.affine().expect("affine").eval(x);
        (at(&z.0) + at(&z.1)) / 2.0
    };
    (mid(part("bolt")), mid(part("top")))
}

/// Slot by slot from the start: the structural stage would carry the bolt along with the
/// top by the model's own relations, and leave no junk to test against. The paper's
/// schedule: the default's face moves may grow the bolt out to the thicker top's own faces
/// (a part that fills another explains the same pictures), and a bolt there is seen.
fn fit(model: &Path, target: &Path) -> reparamc::command::fit::Fitted {
    let settings = Settings {
        warm: Some(0),
        ..Settings::paper()
    };
    views::fit_cpu(model, target, settings)
}

/// The model's slot values for the variation, projected onto the kept relations.
fn projected(model: &Path, variant: &Path) -> Vec<f64> {
    let options = CompileOptions {
        model: model.to_path_buf(),
        variations: vec![variant.to_path_buf()],
        ..CompileOptions::default()
    };
    let out = compile(&options, &mut SourceMap::new()).expect("compiles");
    out.compiled.projected[0].clone()
}

#[test]
fn a_hidden_part_does_not_pull_its_relations() {
    let dir = views::scratch("uncertainty", "table");
    let model = dir.join("table.scad");
    std::fs::write(&model, TABLE).unwrap();
    let variant = dir.join("thick.scad");
    std::fs::write(&variant, thicker()).unwrap();
    let target = dir.join("views");
    views::render_views(&variant, &target, 64);

    let fitted = fit(&model, &target);
    let loaded = reparamc::load_model(&mut SourceMap::new(), &model).unwrap();
    let m = &loaded.model;
    // The top, seen large in every view, is pinned to a sliver of a pixel; the bolt is
    // not determined at all (or looser than the noise model's ceiling).
    let ceiling = NOISE_MAX_SHARE * m.size();
    for s in &fitted.report.slots {
        if s.name.starts_with("top") {
            let sd = s.std.unwrap_or_else(|| panic!("{}: undetermined", s.name));
            assert!(sd < 0.001 * m.size(), "{}: std {sd}", s.name);
        }
        if s.name.starts_with("bolt") {
            assert!(
                s.std.is_none_or(|sd| sd > ceiling),
                "{}: {:?}",
                s.name,
                s.std
            );
        }
    }

    let vary = dir.join("fitted.scad");
    std::fs::write(&vary, &fitted.scad).unwrap();
    std::fs::write(sidecar_path(&vary), fitted.uncertainty.to_json()).unwrap();
    let x: Vec<f64> = fitted.report.slots.iter().map(|s| s.after).collect();
    let (bolt, top) = middles(m, &x);
    eprintln!(
        "the fit left the bolt's middle {:.3} from the top's",
        bolt - top
    );

    let (bolt, top) = middles(m, &projected(&model, &vary));
    let eps = reparamc::tolerance::Tolerance::for_size(m.size()).epsilon;
    assert!(
        (bolt - top).abs() <= eps,
        "with the sidecar the bolt's middle is {:.4} from the top's",
        bolt - top
    );
    // The same file without its sidecar: the relation is pulled, and the bolt goes where
    // the fit left it.
    std::fs::remove_file(sidecar_path(&vary)).unwrap();
    let (bolt, top) = middles(m, &projected(&model, &vary));
    assert!(
        (bolt - top).abs() > 0.1,
        "without the sidecar the bolt's middle is {:.4} from the top's",
        bolt - top
    );
    let _ = std::fs::remove_dir_all(&dir);
}
