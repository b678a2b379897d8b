//! The main job's quality benchmark, asserted: every clean variation stays reachable and
//! the dimension is at most one above the clean truth, for all five paper models under 1%
//! noise. (`cargo bench --bench quality` prints the same table.)

mod table1;

#[test]
fn discovery_under_noise_keeps_variations_reachable_with_tight_dimension() {
    let rows: Vec<table1::Row> = table1::MODELS
        .iter()
        .map(|m| table1::evaluate(m, 0x5eed))
        .collect();
    let table = table1::table(&rows);
    println!("{table}");
    for r in &rows {
        assert!(
            r.reachability >= 0.98,
            "{}: a clean variation is not reachable\n{table}",
            r.model
        );
        assert!(
            r.dimension <= r.clean_dimension + 1,
            "{}: dimension too high\n{table}",
            r.model
        );
    }
}
