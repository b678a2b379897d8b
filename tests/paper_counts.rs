//! The paper's Table 1: parameter and base-constraint counts of its five models, and the
//! dimension left when every base constraint is imposed (`paper-models.md`).

mod common;

use reparamc::analysis::{RelationKind, find_candidates, linalg};
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
    // The paper's four kinds only: tangency is reparamc's, not in its base constraints.
    let rows: Vec<_> = c
        .list
        .iter()
        .filter(|c| RelationKind::PAPER.contains(&c.kind))
        .flat_map(|c| c.rows.iter())
        .collect();
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

/// A row of `n` stools (four legs and a seat each) written out literal by literal: every
/// leg of every stool is 5 wide and 40 tall, a run of far more than `LARGE_RUN` equal
/// features.
fn stools(n: usize, scale: f64) -> String {
    let mut s = String::new();
    for i in 0..n {
        let x = i as f64 * 100.0;
        let h = 40.0 * scale;
        for (dx, dy) in [(0.0, 0.0), (25.0, 0.0), (0.0, 25.0), (25.0, 25.0)] {
            s.push_str(&format!(
                "translate([{}, {dy}, 0]) cube([5, 5, {h}]);\n",
                x + dx
            ));
        }
        s.push_str(&format!("translate([{x}, 0, {h}]) cube([30, 30, 4]);\n"));
    }
    s
}

#[test]
fn large_runs_list_few_pairs_but_count_all_and_span_the_same_space() {
    let dir = std::env::temp_dir().join(format!("reparamc-runs-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("stools.scad");
    std::fs::write(&path, stools(12, 1.0)).unwrap();
    let mut sources = SourceMap::new();
    let model = reparamc::load_model(&mut sources, &path).unwrap().model;
    // Two variations: every stool grows alike, so legs stay equal across stools.
    let mut variations = Vec::new();
    for scale in [0.8, 1.3] {
        let p = dir.join(format!("v{scale}.scad"));
        std::fs::write(&p, stools(12, scale)).unwrap();
        let v = reparamc::load_model(&mut sources, &p).unwrap().model;
        variations.push(v.slot_values());
    }
    let all = find_candidates(&model);
    let some = reparamc::analysis::find_candidates_for(&model, &variations);
    assert!(
        some.list.len() * 2 < all.list.len(),
        "{} of {} pairs listed",
        some.list.len(),
        all.list.len()
    );
    assert_eq!(some.total(), all.total(), "the paper's count is every pair");
    let span = |c: &reparamc::analysis::Candidates| {
        // The paper's four kinds only: tangency is reparamc's, not in its base constraints.
        let rows: Vec<_> = c
            .list
            .iter()
            .filter(|c| RelationKind::PAPER.contains(&c.kind))
            .flat_map(|c| c.rows.iter())
            .collect();
        linalg::nullity(&rows, model.slots.len())
    };
    assert_eq!(span(&some), span(&all));
    // What the variations keep (candidates they all satisfy) spans the same space too.
    let kept = |c: &reparamc::analysis::Candidates| {
        let rows: Vec<_> = c
            .list
            .iter()
            .filter(|k| {
                k.rows
                    .iter()
                    .all(|r| variations.iter().all(|v| r.eval(v).abs() < 1e-9))
            })
            .flat_map(|c| c.rows.iter())
            .collect();
        linalg::nullity(&rows, model.slots.len())
    };
    assert_eq!(kept(&some), kept(&all));
    std::fs::remove_dir_all(&dir).ok();
}
