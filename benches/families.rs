//! Prints the rates of the main job and of the paper's plain method on random model
//! families (`reparamc::families`): reach, coherence, sliders against the intent
//! dimension, toggles, presets, time — at 1% noise with 3 training variations, and rows for
//! 0.5% and 2% noise and for 2 and 5 training variations.
//!
//! `FAMILIES_SEEDS=a..b` (or a count, `FAMILIES_SEEDS=50`) picks the families (200 by
//! default); `FAMILIES_ROWS=main` runs only the main condition; `FAMILIES_PAPER=0` leaves
//! out the paper's method (its greedy by exact IoU takes minutes on some families, where
//! ours takes a fraction of a second); `FAMILIES_TRACE=1` prints
//! every family's scores; `FAMILIES_DUMP=seed` prints one family's model in every style;
//! `FAMILIES_WRITE=dir` writes each family as files for the command (`dir/seed<N>/`:
//! `model.scad`, the noisy training variations `train<k>.scad`, the held-out `held<k>.scad`;
//! with `FAMILIES_SETUP`, of that condition);
//! `FAMILIES_SETUP=noise,training` runs one condition of your own instead of the rows.

use rayon::prelude::*;
use reparamc::back::rewrite::with_slot_values;
use reparamc::families::rates::{header, rates, row};
use reparamc::families::run::{Case, FamilyResult, Setup, evaluate_family};

fn seeds() -> Vec<u64> {
    let spec = std::env::var("FAMILIES_SEEDS").unwrap_or_else(|_| "200".into());
    if spec.contains(',') {
        return spec
            .split(',')
            .map(|s| s.trim().parse().expect("FAMILIES_SEEDS=a,b,c"))
            .collect();
    }
    match spec.split_once("..") {
        Some((a, b)) => {
            let a: u64 = a.trim().parse().expect("FAMILIES_SEEDS=a..b");
            let b: u64 = b.trim().parse().expect("FAMILIES_SEEDS=a..b");
            (a..b).collect()
        }
        None => (0..spec.trim().parse::<u64>().expect("FAMILIES_SEEDS=count")).collect(),
    }
}

fn trace(setup: Setup, r: &FamilyResult) {
    for (method, s) in [("ours", &r.ours), ("paper", &r.paper)] {
        eprintln!(
            "seed {} {} parts {} noise {} train {} {method}: d {} dim {} iou {:.4} broken {}{} false toggles {:?} missed {:?} preset {:?} {:.3}s sigma {:.3} of {:.3}",
            r.seed,
            r.style.name(),
            r.parts,
            setup.noise,
            setup.training,
            s.d,
            s.dimension,
            s.worst_iou,
            s.broken_settings,
            s.first_break
                .as_ref()
                .map_or(String::new(), |b| format!(" ({b})")),
            s.false_toggles,
            s.missed_optional,
            s.bad_preset,
            s.seconds,
            s.sigma.unwrap_or(0.0),
            r.sigma
        );
    }
}

/// Writes seed `seed`'s model as `dir/seed<N>/model.scad`, its noisy training variations
/// as `train<k>.scad` and its held-out ones as `held<k>.scad`, under `setup`.
fn write_family(seed: u64, dir: &std::path::Path, setup: Setup) {
    let case = match Case::load(seed, setup, None) {
        Ok(c) => c,
        Err(e) => return eprintln!("skipped: {e}"),
    };
    let out = dir.join(format!("seed{seed}"));
    std::fs::create_dir_all(&out).expect("a folder to write to");
    let text = case.sources.text(case.loaded.main);
    let file = |name: String, values: &[f64]| {
        let t = with_slot_values(text, case.loaded.main, &case.model.slots, values);
        std::fs::write(out.join(name), t).expect("writable");
    };
    file("model.scad".into(), &case.model.slot_values());
    for (k, v) in case.training.iter().enumerate() {
        file(format!("train{k}.scad"), &v.values);
    }
    for (k, v) in case.held_out.iter().enumerate() {
        file(format!("held{k}.scad"), &v.values);
    }
    eprintln!("seed {seed}: wrote {}", out.display());
}

fn main() {
    if !std::env::args().any(|a| a == "--bench") {
        eprintln!("families: run `cargo bench --bench families` for the table");
        return;
    }
    // `FAMILIES_DUMP=seed` prints that family's input text in every style and stops.
    if let Ok(seed) = std::env::var("FAMILIES_DUMP") {
        let seed: u64 = seed.parse().expect("FAMILIES_DUMP=seed");
        let f = reparamc::families::Family::generate(seed, 3).expect("a family");
        eprintln!(
            "seed {seed}: d {} ({:?}), style {}",
            f.dimension(),
            f.names(),
            f.style.name()
        );
        for style in reparamc::families::style::Style::ALL {
            println!("// ---- {}\n{}", style.name(), f.input_text(style));
        }
        return;
    }
    let seeds = seeds();
    let main_only = std::env::var("FAMILIES_ROWS").is_ok_and(|r| r == "main");
    let with_paper = std::env::var("FAMILIES_PAPER").map_or(true, |v| v != "0");
    let mut setups = vec![Setup {
        noise: 0.01,
        training: 3,
    }];
    // `FAMILIES_SETUP=noise,training` runs that one condition instead (for instance `0,5`:
    // exact variations, which show what the relation kinds can express at all).
    let custom = std::env::var("FAMILIES_SETUP").ok().map(|v| {
        let (n, t) = v.split_once(',').expect("FAMILIES_SETUP=noise,training");
        Setup {
            noise: n
                .trim()
                .parse()
                .expect("noise as a fraction of the model's size"),
            training: t.trim().parse().expect("training variations"),
        }
    });
    // `FAMILIES_WRITE=dir` writes each family (of the custom condition, else 1% noise and
    // 3 training) as files the command reads, and stops.
    if let Ok(dir) = std::env::var("FAMILIES_WRITE") {
        for &seed in &seeds {
            write_family(
                seed,
                std::path::Path::new(&dir),
                custom.unwrap_or(setups[0]),
            );
        }
        return;
    }
    if let Some(c) = custom {
        setups = vec![c];
    } else if !main_only {
        setups.extend([
            Setup {
                noise: 0.005,
                training: 3,
            },
            Setup {
                noise: 0.02,
                training: 3,
            },
            Setup {
                noise: 0.01,
                training: 2,
            },
            Setup {
                noise: 0.01,
                training: 5,
            },
        ]);
    }
    let tracing = std::env::var_os("FAMILIES_TRACE").is_some();
    print!("{}", header());
    for setup in setups {
        let results: Vec<Result<FamilyResult, String>> = seeds
            .par_iter()
            .map(|&s| {
                let r = evaluate_family(s, setup, with_paper);
                if tracing {
                    eprintln!("seed {s} done");
                }
                r
            })
            .collect();
        let mut ok = Vec::new();
        for r in results {
            match r {
                Ok(r) => {
                    if tracing {
                        trace(setup, &r);
                    }
                    ok.push(r);
                }
                Err(e) => eprintln!("skipped: {e}"),
            }
        }
        let condition = format!(
            "{}% noise, {} training",
            setup.noise * 100.0,
            setup.training
        );
        print!("{}", row(&condition, "reparamc", &rates(&ok, |r| &r.ours)));
        if with_paper {
            print!("{}", row(&condition, "paper", &rates(&ok, |r| &r.paper)));
        }
    }
}
