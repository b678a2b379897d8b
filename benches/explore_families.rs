//! The zero-shot loop on objects nobody tuned it for: each family from the generator
//! (`reparamc::families`) is explored by `reparamc explore` with three prompts, each
//! answered by the stand-in img2img server of `tests/explore.rs` with perturbed renders
//! of one of the family's draws (view-inconsistent jitter of every number, a part missing
//! in some samples, recoloured, antialiased, JPEG). Each prompt's variation is scored by
//! exact 3-D IoU against its hidden draw, and, when `openscad` is installed, each preset
//! of the output as OpenSCAD evaluates it, standing where the input stands (centred on
//! its floor), as the draw is.
//!
//! Prints per family and in all: the share of variations with IoU ≥ 0.9, the share of
//! presets with IoU ≥ 0.95 (issue 19's two bars), the medians, and the seconds per
//! prompt. `EXPLORE_FAMILIES_SEEDS=a..b` (default `0..10`), `EXPLORE_FAMILIES_ROUNDS`
//! (default 30), `EXPLORE_FAMILIES_SIZE` (default 64; the command's defaults are 400 rounds
//! at 256), `EXPLORE_FAMILIES_KEEP=dir` (keep every run in `dir/<seed>/`). Under
//! `cargo test` (`--bench` absent) it explores one family for two rounds as a smoke test.

#[path = "../tests/common/mod.rs"]
mod common;
#[path = "../tests/explore_support/server.rs"]
mod server;

use common::anchored;
use reparamc::families::Family;
use reparamc::geom::iou;
use reparamc::ir::Model;
use server::{Mode, model_of, start_for};
use std::path::Path;
use std::process::Command;
use std::time::Instant;

fn env_or<T: std::str::FromStr>(name: &str, default: T) -> T {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

/// The prompts, one per hidden draw (the stand-in serves a prompt's own draw).
const PROMPTS: [&str; 3] = ["kind a", "kind b", "kind c"];

fn iou_of(a: &Model, b: &Model) -> f64 {
    iou((&a.parts, &a.csg), (&b.parts, &b.csg))
}

/// The output's preset `name` as OpenSCAD evaluates it, if it does.
fn preset(dir: &Path, name: &str) -> Option<Model> {
    let (out, csg) = common::openscad_preset(&dir.join("out.scad"), name);
    let csg = csg.filter(|_| out.status.success())?;
    Some(model_of("preset.csg", &csg))
}

/// What one family's exploration gave.
struct Outcome {
    variations: Vec<f64>,
    presets: Vec<f64>,
    seconds: f64,
}

/// Explores family `seed` with one prompt per draw; `None` when it has no draws or the
/// command fails (printed).
fn explore_one(seed: u64, rounds: usize, size: u32, openscad: bool) -> Option<Outcome> {
    let family = Family::generate(seed, PROMPTS.len())?;
    let keep = std::env::var_os("EXPLORE_FAMILIES_KEEP").map(std::path::PathBuf::from);
    let dir = match &keep {
        Some(root) => root.join(seed.to_string()),
        None => std::env::temp_dir().join(format!(
            "reparamc-explore-families-{}-{seed}",
            std::process::id()
        )),
    };
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let program = family.program(family.style);
    std::fs::write(dir.join("model.scad"), family.input_text(family.style)).unwrap();
    let targets: Vec<(String, Model)> = PROMPTS
        .iter()
        .zip(&family.training)
        .map(|(p, d)| {
            let text = program.render(&program.values(&d.theta, &d.dropped));
            (p.to_string(), model_of("draw.scad", &text))
        })
        .collect();
    let srv = start_for(targets.clone(), Mode::Good);
    let t0 = Instant::now();
    let out = Command::new(env!("CARGO_BIN_EXE_reparamc"))
        .arg("explore")
        .arg(dir.join("model.scad"))
        .args(["--object", "thing", "-o"])
        .arg(dir.join("out.scad"))
        .arg("--run")
        .arg(dir.join("run"))
        .args(["--rounds", &rounds.to_string(), "--size", &size.to_string()])
        .args([
            "--diffusion-size",
            &size.to_string(),
            "--diffusion",
            &srv.url,
        ])
        .args(PROMPTS.iter().flat_map(|p| ["--prompt", p]))
        .env_remove("OPENAI_API_KEY")
        .output()
        .unwrap();
    let seconds = t0.elapsed().as_secs_f64() / targets.len() as f64;
    if !out.status.success() {
        println!(
            "seed {seed}: explore failed: {}",
            String::from_utf8_lossy(&out.stderr).trim()
        );
        return None;
    }
    let mut outcome = Outcome {
        variations: Vec::new(),
        presets: Vec::new(),
        seconds,
    };
    for (prompt, target) in &targets {
        let name = prompt.replace(' ', "_");
        let text = std::fs::read_to_string(dir.join(format!("run/{name}.scad"))).ok()?;
        outcome
            .variations
            .push(iou_of(&model_of("v.scad", &text), target));
        if let Some(p) = openscad.then(|| preset(&dir, &name)).flatten() {
            let (a, b) = (anchored(&p.parts), anchored(&target.parts));
            outcome.presets.push(iou((&a, &p.csg), (&b, &target.csg)));
        }
    }
    if keep.is_none() {
        let _ = std::fs::remove_dir_all(&dir);
    }
    Some(outcome)
}

fn median(v: &[f64]) -> f64 {
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    s.get(s.len() / 2).copied().unwrap_or(f64::NAN)
}

fn share(v: &[f64], bar: f64) -> String {
    let n = v.iter().filter(|&&x| x >= bar).count();
    format!(
        "{n} of {} ({:.1}%)",
        v.len(),
        100.0 * n as f64 / v.len().max(1) as f64
    )
}

fn list(v: &[f64]) -> String {
    v.iter()
        .map(|x| format!("{x:.3}"))
        .collect::<Vec<_>>()
        .join(" ")
}

fn main() {
    let bench = std::env::args().any(|a| a == "--bench");
    let (seeds, rounds, size) = if bench {
        let range: String = env_or("EXPLORE_FAMILIES_SEEDS", "0..10".to_string());
        let (a, b) = range.split_once("..").unwrap_or(("0", "10"));
        let (a, b): (u64, u64) = (a.parse().unwrap_or(0), b.parse().unwrap_or(10));
        (
            a..b,
            env_or("EXPLORE_FAMILIES_ROUNDS", 30usize),
            env_or("EXPLORE_FAMILIES_SIZE", 64u32),
        )
    } else {
        (0..1, 2, 48)
    };
    let openscad = reparamc::render::openscad::available();
    let (mut variations, mut presets, mut seconds, mut runs) = (Vec::new(), Vec::new(), 0.0, 0);
    for seed in seeds {
        let Some(o) = explore_one(seed, rounds, size, openscad) else {
            continue;
        };
        println!(
            "seed {seed}: variations {}  presets {}  {:.1} s per prompt",
            list(&o.variations),
            list(&o.presets),
            o.seconds
        );
        variations.extend(o.variations);
        presets.extend(o.presets);
        seconds += o.seconds;
        runs += 1;
    }
    println!(
        "explore_families, {rounds} rounds at {size} px: variations IoU >= 0.9 {}, median {:.3}",
        share(&variations, 0.9),
        median(&variations)
    );
    if openscad {
        println!(
            "  presets IoU >= 0.95 {}, >= 0.9 {}, median {:.3}",
            share(&presets, 0.95),
            share(&presets, 0.9),
            median(&presets)
        );
    } else {
        println!("  presets: openscad not installed, not scored");
    }
    println!(
        "  {:.1} s per prompt (the stand-in server's renders included)",
        seconds / runs.max(1) as f64
    );
}
