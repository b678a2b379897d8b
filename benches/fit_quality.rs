//! The fitting quality table: every example model fitted from its base to OpenSCAD renders
//! (five cameras) of each of its variants, scored by exact 3-D IoU between the fitted and
//! the true variant. `cargo bench --bench fit_quality` prints the whole table (and writes it
//! as Markdown to `target/fit_quality.md`); under `cargo test` one case runs, as a smoke test.
//!
//! Environment: `FIT_QUALITY_SIZE` (pixels, default 256), `FIT_QUALITY_CASES` (comma-separated
//! substrings of `model/variant` to run), `FIT_QUALITY_GPU=1` to fit with the wgpu backend.
//! For experiments, the table's settings can be overridden: `FIT_SHADING`, `FIT_LAMBDA`,
//! `FIT_SIZE_PRIOR`, `FIT_POLISH`, `FIT_REFINE`, `FIT_BORDER`, `FIT_SETTLE`, `FIT_REACH`,
//! `FIT_ROUNDS`, `FIT_LEVELS`, `FIT_SIGMA_END`, `FIT_DAMPED` (Adam's floor in the rerun, 0:
//! none), and `FIT_ALBEDO`, `FIT_PROPORTIONS`, `FIT_RELATIVE`, `FIT_COVERAGE`,
//! `FIT_BLURRED` (0 or 1; 0: the soft rounds on sigmoid edges); `WARM` and `SCALE` set the
//! rounds of the structural and stretch stages; `FRAME_UNION` frames the cameras on the
//! base and the variant together instead of on the variant alone (with `FIT_BORDER=0`: the
//! table before 2026-12-01, with `FIT_REFINE=0` as well). `SLOTS` (or `SLOTS=d`: the slots more
//! than d from the truth), `TRUTH` (the loss there, soft and hard), `TRACE`, `BLAME` (the
//! slots whose true value alone gains most IoU, and the IoU with the first k of them set),
//! `MISMATCH` (pixels whose hard coverage disagrees with the target's mask; with `GALLERY`
//! also drawn) and `GALLERY=dir` print or draw more about each fit; `FROM_TRUTH` starts
//! each fit at the true variant; `SUPERSAMPLE=k` renders the targets at 2^k times the size
//! and pools them (antialiased targets).

#[path = "../tests/fit_support/quality.rs"]
mod quality;

use reparamc::fit::{FitOptions, SoftEdges};
use std::fmt::Write;

/// The table's settings with overrides from the environment, for experiments.
fn options_from_env() -> FitOptions {
    let mut o = quality::table_options();
    let get = |k: &str| std::env::var(k).ok().and_then(|v| v.parse::<f64>().ok());
    if let Some(v) = get("FIT_SHADING") {
        o.loss.shading = v;
    }
    if let Some(v) = get("FIT_LAMBDA") {
        o.lambda = v;
    }
    if let Some(v) = get("FIT_SIZE_PRIOR") {
        o.size_prior = v;
    }
    if let Some(v) = get("FIT_TIE_PRIOR") {
        o.tie_prior = v;
    }
    if let Some(v) = get("FIT_SETTLE") {
        o.settle = v;
    }
    if let Some(v) = get("FIT_REACH") {
        o.reach = v;
    }
    if let Some(v) = get("FIT_POLISH") {
        o.polish = v as usize;
    }
    if let Some(v) = get("FIT_REFINE") {
        o.refine = v as usize;
    }
    if let Some(v) = get("FIT_BORDER") {
        o.border = v;
    }
    if let Some(v) = get("FIT_ROUNDS") {
        o.rounds = v as usize;
    }
    if let Some(v) = get("FIT_LEVELS") {
        o.levels = v as u32;
    }
    if let Some(v) = get("FIT_SIGMA_END") {
        o.sigma.1 = v;
    }
    if let Some(v) = get("FIT_ALBEDO") {
        o.per_item_albedo = v != 0.0;
    }
    if let Some(v) = get("FIT_PROPORTIONS") {
        o.proportions = v != 0.0;
    }
    if let Some(v) = get("FIT_DAMPED") {
        o.damped_rerun = (v > 0.0).then_some(v);
    }
    if let Some(v) = get("FIT_RELATIVE") {
        o.relative_steps = v != 0.0;
    }
    if let Some(v) = get("FIT_COVERAGE") {
        o.coverage = v != 0.0;
    }
    if let Some(v) = get("FIT_BLURRED") {
        o.soft_edges = if v != 0.0 {
            SoftEdges::Blurred
        } else {
            SoftEdges::Sigmoid
        };
    }
    o
}

fn main() {
    let full = std::env::args().any(|a| a == "--bench");
    if !reparamc::render::openscad::available() {
        eprintln!("fit_quality: skipped (openscad or xvfb-run missing; run scripts/setup)");
        return;
    }
    let size: u32 = std::env::var("FIT_QUALITY_SIZE")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(256);
    let filter = std::env::var("FIT_QUALITY_CASES").unwrap_or_default();
    let mut cases = quality::cases();
    if !filter.is_empty() {
        cases.retain(|c| {
            let n = format!("{}/{}", c.model, c.variant);
            filter.split(',').any(|f| n.contains(f))
        });
    } else if !full {
        cases.retain(|c| c.model == "paper_table" && c.variant == "coffee_table");
    }
    let mut backend: Box<dyn reparamc::render::Backend> = Box::new(quality::cpu());
    #[cfg(feature = "gpu")]
    if std::env::var("FIT_QUALITY_GPU").is_ok() {
        backend = Box::new(reparamc::render::gpu::GpuBackend::new().expect("a wgpu adapter"));
    }
    let opts = options_from_env();
    let mut rows = Vec::new();
    let mut md = String::new();
    let _ = writeln!(
        md,
        "| model | variant | IoU before | IoU fitted | seconds |"
    );
    let _ = writeln!(md, "|---|---|---:|---:|---:|");
    for case in &cases {
        let o = quality::run_case(case, &opts, size, 5, backend.as_mut());
        eprintln!(
            "{:16} {:16} IoU {:.3} -> {:.3}   loss {:.5}   {:.1} s",
            o.case.model, o.case.variant, o.iou_start, o.iou, o.loss_end, o.seconds
        );
        let _ = writeln!(
            md,
            "| {} | {} | {:.3} | {:.3} | {:.1} |",
            o.case.model, o.case.variant, o.iou_start, o.iou, o.seconds
        );
        rows.push(o);
    }
    if rows.is_empty() {
        return;
    }
    let worst = rows.iter().map(|o| o.iou).fold(1.0, f64::min);
    let mean = rows.iter().map(|o| o.iou).sum::<f64>() / rows.len() as f64;
    let below: Vec<String> = rows
        .iter()
        .filter(|o| o.iou < 0.9)
        .map(|o| format!("{}/{} ({:.3})", o.case.model, o.case.variant, o.iou))
        .collect();
    let _ = writeln!(
        md,
        "\n{} fits at {size}×{size}: mean IoU {mean:.3}, worst {worst:.3}; below 0.9: {}",
        rows.len(),
        if below.is_empty() {
            "none".into()
        } else {
            below.join(", ")
        }
    );
    eprintln!("{}", md.lines().last().unwrap_or_default());
    if full {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("target/fit_quality.md");
        let _ = std::fs::write(&path, &md);
        eprintln!("fit_quality: table written to {}", path.display());
    }
}
