//! Optional parts are judged against the part's own size, not the model's: in a model of
//! hundreds of parts every small visible part changes the whole by less than a thousandth,
//! and none of them may become a switch. A variation leaves a part out by a zero; a part it
//! only moves inside another is still there.

use reparamc::analysis::optional::optional_parts;
use reparamc::analysis::similarity::VolumeSimilarity;
use reparamc::front::source::SourceMap;

/// `n` visible 10-unit cubes in a row, and one small cube of side `side` at height `z` over
/// the first (on top of it at 10, hidden inside it at 2).
fn row(n: usize, z: f64, side: f64) -> String {
    let mut s = String::new();
    for i in 0..n {
        s.push_str(&format!(
            "translate([{}, 0, 0]) cube([10, 10, 10]);\n",
            i * 20
        ));
    }
    s.push_str(&format!("translate([2, 2, {z}]) cube([{side}, 3, 3]);\n"));
    s
}

/// The model of `text`, loaded from a file in `dir`.
fn load(dir: &std::path::Path, name: &str, text: &str) -> reparamc::ir::Model {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    let mut sources = SourceMap::new();
    reparamc::load_model(&mut sources, &path).unwrap().model
}

/// The parts each variation (`variations`, program texts) does without, for the model of
/// `text`; `case` names the scratch folder.
fn optional_in(case: &str, text: &str, variations: &[String]) -> (usize, Vec<Vec<usize>>) {
    let dir = std::env::temp_dir().join(format!("reparamc-{case}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let model = load(&dir, "model.scad", text);
    let values: Vec<Vec<f64>> = variations
        .iter()
        .enumerate()
        .map(|(i, v)| load(&dir, &format!("v{i}.scad"), v).slot_values())
        .collect();
    let sim = VolumeSimilarity::new(&model);
    let optional = optional_parts(&model, &values, &sim);
    std::fs::remove_dir_all(&dir).ok();
    (model.parts.len(), optional)
}

#[test]
fn small_visible_parts_of_a_large_model_are_not_optional_zeroed_ones_are() {
    let n = 1500;
    let (parts, optional) = optional_in(
        "optional",
        &row(n, 10.0, 3.0),
        &[row(n, 10.0, 3.0), row(n, 10.0, 0.0)],
    );
    assert_eq!(parts, n + 1);
    assert_eq!(
        optional,
        vec![vec![], vec![n]],
        "only the cube the variation sizes to zero is optional there"
    );
}

#[test]
fn a_part_the_input_hides_too_is_never_optional() {
    let (_, optional) = optional_in(
        "hidden",
        &row(3, 2.0, 3.0),
        &[row(3, 2.0, 3.0), row(3, 2.0, 0.0)],
    );
    assert_eq!(optional, vec![Vec::<usize>::new(); 2]);
}

#[test]
fn a_part_a_variation_moves_inside_another_is_still_there() {
    let (_, optional) = optional_in(
        "covered",
        &row(3, 10.0, 3.0),
        &[row(3, 2.0, 3.0), row(3, 10.0, -0.5)],
    );
    assert_eq!(
        optional,
        vec![Vec::<usize>::new(); 2],
        "covered by a neighbour or sized past zero by noise, the small cube is still meant"
    );
}
