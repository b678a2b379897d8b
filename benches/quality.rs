//! Prints the main job's quality table (our Table 1): parameters, base constraints, chosen
//! constraints, dimension against the clean truth, reachability and cutoff step, for the
//! paper's five models with five noisy variations each.

#[path = "../tests/table1/mod.rs"]
mod table1;

fn main() {
    let rows: Vec<table1::Row> = table1::MODELS
        .iter()
        .map(|m| table1::evaluate(m, 0x5eed))
        .collect();
    print!("{}", table1::table(&rows));
}
