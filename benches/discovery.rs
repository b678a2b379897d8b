//! Discovery's speed on generated model families (issue 20: any model of at most 60 parts
//! with at most 8 noisy variations, cones included, in at most 1 s on this machine).
//!
//! Families come from `reparamc::families` with 8 training variations at 1% noise, loaded
//! as the command loads them; the time is the main job on the loaded model and its
//! variations (`reparameterize`: candidates, optional parts, the noise-model test, the
//! solve, projections, ranges, names and the emitted text; no file is written). For each
//! size class (3–15, 16–30, 31–45, 46–60 parts) criterion times the first family of the
//! class that has a cone, and the largest such family found. `DISCOVERY_SWEEP=n` also runs
//! the `n` largest cone families found, once each, and prints the slowest (`DISCOVERY_SCAN`
//! seeds are scanned, 400 by default). Under `cargo test` one small family runs once.

use criterion::{Criterion, criterion_group, criterion_main};
use reparamc::command::compile::{Options, reparameterize};
use reparamc::families::Family;
use reparamc::families::part::Shape;
use reparamc::families::run::{Case, Setup};
use reparamc::front::with_large_stack;
use std::time::Instant;

/// The condition: 8 noisy training variations, noise 1% of the model's size.
const SETUP: Setup = Setup {
    noise: 0.01,
    training: 8,
};

/// Part-count classes, one family timed per class.
const CLASSES: [(usize, usize); 4] = [(3, 15), (16, 30), (31, 45), (46, 60)];

fn env_count(name: &str, default: usize) -> usize {
    std::env::var(name)
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(default)
}

/// Does the family have a cone (a cylinder whose radii differ at the input)?
fn has_cone(f: &Family) -> bool {
    let theta = f.params.base();
    f.parts.iter().any(|p| match &p.shape {
        Shape::Cylinder { r1, r2, .. } => r1.eval(&theta) != r2.eval(&theta),
        Shape::Box { .. } => false,
    })
}

/// `(seed, parts)` of the families with a cone among the first `scan` seeds.
fn cone_families(scan: u64) -> Vec<(u64, usize)> {
    (0..scan)
        .filter_map(|seed| Family::generate(seed, SETUP.training).map(|f| (seed, f)))
        .filter(|(_, f)| has_cone(f))
        .map(|(seed, f)| (seed, f.parts.len()))
        .collect()
}

/// The main job on a loaded case: the number of sliders it made.
fn discover(case: &Case) -> usize {
    with_large_stack(|| {
        reparameterize(
            &case.sources,
            &case.loaded,
            &case.model,
            &case.training,
            &Options::default(),
        )
    })
    .solution
    .free
    .len()
}

/// The families to time: the first of each class, then the largest (seed, parts).
fn picks(found: &[(u64, usize)]) -> Vec<(u64, usize)> {
    let mut picks: Vec<(u64, usize)> = CLASSES
        .iter()
        .filter_map(|&(lo, hi)| found.iter().find(|f| (lo..=hi).contains(&f.1)).copied())
        .collect();
    if let Some(&largest) = found.iter().max_by_key(|f| (f.1, std::cmp::Reverse(f.0)))
        && !picks.contains(&largest)
    {
        picks.push(largest);
    }
    picks
}

/// Runs the `n` largest families once each and prints the slowest.
fn sweep(found: &[(u64, usize)], n: usize) {
    let mut by_size = found.to_vec();
    by_size.sort_by_key(|f| (std::cmp::Reverse(f.1), f.0));
    let mut slowest = (0.0f64, 0u64, 0usize);
    for &(seed, parts) in by_size.iter().take(n) {
        let Ok(case) = Case::load(seed, SETUP, None) else {
            continue;
        };
        let start = Instant::now();
        discover(&case);
        let s = start.elapsed().as_secs_f64();
        println!("sweep: seed {seed}, {parts} parts: {s:.3} s");
        if s > slowest.0 {
            slowest = (s, seed, parts);
        }
    }
    let (s, seed, parts) = slowest;
    println!("sweep of {n} families: slowest {s:.3} s (seed {seed}, {parts} parts)");
}

fn bench(c: &mut Criterion) {
    let measuring = std::env::args().any(|a| a == "--bench");
    let found = cone_families(env_count("DISCOVERY_SCAN", 400) as u64);
    let mut picks = picks(&found);
    if !measuring {
        picks.truncate(1);
    }
    let mut g = c.benchmark_group("discovery, 8 variations at 1% noise");
    g.sample_size(10);
    for (seed, parts) in picks {
        let case = Case::load(seed, SETUP, None).expect("the family loads");
        g.bench_function(format!("{parts} parts (seed {seed})"), |b| {
            b.iter(|| discover(&case))
        });
    }
    g.finish();
    let n = env_count("DISCOVERY_SWEEP", 0);
    if measuring && n > 0 {
        sweep(&found, n);
    }
}

criterion_group! {
    name = benches;
    // No plots: this machine has no font for criterion's plotters backend.
    config = Criterion::default().without_plots();
    targets = bench
}
criterion_main!(benches);
