//! Optional parts are judged against the part's own size, not the model's: in a model of
//! hundreds of parts every small visible part changes the whole by less than a thousandth,
//! and none of them may become a switch.

use reparamc::analysis::optional::optional_parts;
use reparamc::analysis::similarity::VolumeSimilarity;
use reparamc::front::source::SourceMap;

/// `n` visible 10-unit cubes in a row, and one small cube hidden inside the first.
fn row(n: usize) -> String {
    let mut s = String::new();
    for i in 0..n {
        s.push_str(&format!(
            "translate([{}, 0, 0]) cube([10, 10, 10]);\n",
            i * 20
        ));
    }
    s.push_str("translate([2, 2, 2]) cube([3, 3, 3]);\n");
    s
}

#[test]
fn small_visible_parts_of_a_large_model_are_not_optional_hidden_ones_are() {
    let dir = std::env::temp_dir().join(format!("reparamc-optional-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("row.scad");
    let n = 1500;
    std::fs::write(&path, row(n)).unwrap();
    let mut sources = SourceMap::new();
    let model = reparamc::load_model(&mut sources, &path).unwrap().model;
    let sim = VolumeSimilarity::new(&model);
    let optional = optional_parts(model.parts.len(), &[model.slot_values()], &sim);
    assert_eq!(optional, vec![vec![n]], "only the hidden cube is optional");
    std::fs::remove_dir_all(&dir).ok();
}
