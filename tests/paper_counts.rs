//! The paper's Table 1: parameter and base-constraint counts of its five models, and the
//! dimension left when every base constraint is imposed (`paper-models.md`).

mod common;

use reparamc::analysis::{find_candidates, linalg};
use reparamc::front::source::SourceMap;

fn counts(name: &str) -> (usize, usize, usize) {
    let path = common::repo()
        .join("examples/paper")
        .join(format!("{name}.scad"));
    let mut sources = SourceMap::new();
    let model = match reparamc::load_model(&mut sources, &path) {
        Ok(e) => e.model,
        Err(d) => panic!("{}", d.render_plain(&sources)),
    };
    let c = find_candidates(&model);
    let rows: Vec<_> = c.list.iter().flat_map(|c| c.rows.iter()).collect();
    (
        model.slots.len(),
        c.total(),
        linalg::nullity(&rows, model.slots.len()),
    )
}

#[test]
fn chair() {
    assert_eq!(counts("chair"), (48, 172, 7));
}

#[test]
fn table() {
    assert_eq!(counts("table"), (36, 90, 8));
}

#[test]
fn car() {
    assert_eq!(counts("car"), (42, 94, 11));
}

#[test]
fn camera() {
    assert_eq!(counts("camera"), (24, 21, 13));
}

#[test]
fn bottle() {
    // Six, plus the cone's top radius, which no relation touches.
    assert_eq!(counts("bottle"), (19, 20, 7));
}
