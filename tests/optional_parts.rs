//! Optional parts are judged against the part's own size, not the model's: in a model of
//! hundreds of parts every small visible part changes the whole by less than a thousandth,
//! and none of them may become a switch.

use reparamc::analysis::optional::optional_parts;
use reparamc::analysis::similarity::VolumeSimilarity;
use reparamc::front::source::SourceMap;

/// `n` visible 10-unit cubes in a row, and one small cube at height `z` over the first
/// (on top of it at 10, hidden inside it at 2).
fn row(n: usize, z: f64) -> String {
    let mut s = String::new();
    for i in 0..n {
        s.push_str(&format!(
            "translate([{}, 0, 0]) cube([10, 10, 10]);\n",
            i * 20
        ));
    }
    s.push_str(&format!("translate([2, 2, {z}]) cube([3, 3, 3]);\n"));
    s
}

/// The model of `text`, loaded from a file in `dir`.
fn load(dir: &std::path::Path, name: &str, text: &str) -> reparamc::ir::Model {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    let mut sources = SourceMap::new();
    reparamc::load_model(&mut sources, &path).unwrap().model
}

#[test]
fn small_visible_parts_of_a_large_model_are_not_optional_hidden_ones_are() {
    let dir = std::env::temp_dir().join(format!("reparamc-optional-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let n = 1500;
    let model = load(&dir, "row.scad", &row(n, 10.0));
    let hiding = load(&dir, "hiding.scad", &row(n, 2.0)).slot_values();
    let sim = VolumeSimilarity::new(&model);
    let optional = optional_parts(&model, &[model.slot_values(), hiding], &sim, 0.0);
    assert_eq!(
        optional,
        vec![vec![], vec![n]],
        "only the cube the variation hides is optional there"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_part_the_input_hides_too_is_never_optional() {
    let dir = std::env::temp_dir().join(format!("reparamc-hidden-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let model = load(&dir, "row.scad", &row(3, 2.0));
    let sim = VolumeSimilarity::new(&model);
    let optional = optional_parts(&model, &[model.slot_values()], &sim, 0.0);
    assert_eq!(optional, vec![Vec::<usize>::new()]);
    std::fs::remove_dir_all(&dir).ok();
}
