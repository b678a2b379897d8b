//! Fitting recovers variants from OpenSCAD renders (a fast subset of the quality table in
//! `benches/fit_quality.rs`).

#[path = "fit_support/quality.rs"]
mod quality;

use reparamc::fit::FitOptions;

#[test]
#[ignore]
fn explore() {
    let filter = std::env::var("CASES").unwrap_or_default();
    let mut opts = FitOptions::default();
    if let Ok(r) = std::env::var("ROUNDS") {
        opts.rounds = r.parse().unwrap();
    }
    if let Ok(r) = std::env::var("LR") {
        opts.lr = r.parse().unwrap();
    }
    if let Ok(r) = std::env::var("LEVELS") {
        opts.levels = r.parse().unwrap();
    }
    if let Ok(r) = std::env::var("SIG0") {
        opts.sigma.0 = r.parse().unwrap();
    }
    if let Ok(r) = std::env::var("SHADING") {
        opts.loss.shading = r.parse().unwrap();
    }
    if let Ok(r) = std::env::var("POLISH") {
        opts.polish = r.parse().unwrap();
    }
    if std::env::var("REL").is_ok() {
        opts.relative_steps = true;
    }
    if std::env::var("ADAM").is_ok() {
        opts.optimizer = reparamc::fit::optimize::Optimizer::adam();
    }
    for case in quality::cases() {
        let name = format!("{}/{}", case.model, case.variant);
        if !filter.is_empty() && !filter.split(',').any(|f| name.contains(f)) {
            continue;
        }
        let size = std::env::var("SIZE").map_or(128, |s| s.parse().unwrap());
        let o = quality::run_case(&case, &opts, size, 5, &mut quality::cpu());
        eprintln!(
            "{name:32} IoU {:.3} -> {:.3}  loss {:.4} -> {:.4}  {:.1}s {} steps ({:.0}/s)",
            o.iou_start,
            o.iou,
            o.loss_start,
            o.loss_end,
            o.seconds,
            o.steps,
            o.steps as f64 / o.seconds
        );
    }
}
