//! Pictures that show the whole object (`FitOptions::border`): the fit sees each picture
//! inside a frame of background, so a part that has moved out of the picture still costs
//! loss (and is drawn back in) instead of hiding where no picture sees it.

use reparamc::fit::loss::Target;
use reparamc::fit::{FitOptions, Parametric, Stage, fit};
use reparamc::render::CpuBackend;
use reparamc::render::camera::{Camera, default_views};
use reparamc::render::scene::{BOX_FILTER, DEFAULT_SHADE};
use reparamc::render::soft::{prepare_view, render_view};
use std::path::PathBuf;

fn model(rel: &str) -> reparamc::ir::Model {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(rel);
    let mut sources = reparamc::front::source::SourceMap::new();
    reparamc::load_model(&mut sources, &path).unwrap().model
}

/// The image loss of `x` against `targets` before any step.
fn loss_at(p: &Parametric, x: &[f64], cams: &[Camera], targets: &[Target], border: f64) -> f64 {
    let mut start = p.clone();
    start.x0 = x.to_vec();
    let opts = FitOptions {
        rounds: 1,
        iterations: 1,
        proportions: false,
        damped_rerun: None,
        border,
        ..FitOptions::default()
    };
    let r = fit(
        &start,
        cams,
        targets,
        &[Stage::slots(1)],
        &mut CpuBackend::new(),
        &opts,
        &mut |_| {},
    )
    .unwrap();
    r.start_loss.iter().sum()
}

#[test]
fn a_part_just_outside_the_picture_still_costs() {
    // The paper chair without its back (sunk inside the seat), seen from the front.
    let m = model("examples/paper/chair.scad");
    let p = Parametric::new(&m);
    let slot = |name: &str| m.slots.iter().position(|s| s.name == name).unwrap();
    let mut truth = p.x0.clone();
    truth[slot("back.z")] = 7.5;
    truth[slot("back.height")] = 1.0;
    let (lo, hi) = m.bounds().unwrap();
    let cams: Vec<Camera> = default_views(lo, hi, 2, 64, 64).unwrap().split_off(1);
    let scene = p.scene(&truth);
    let targets: Vec<Target> = cams
        .iter()
        .map(|c| {
            // Drawn as `reparamc render` draws pictures: area coverage.
            let v = prepare_view(&scene, c, Some(BOX_FILTER));
            Target::from_soft(&render_view(&scene, &v, Some(BOX_FILTER), DEFAULT_SHADE, false).0)
        })
        .collect();
    // The back as a 6-unit cube (two pixels) eight pixels right of the picture's edge.
    let cam = &cams[0];
    let f = cam.frame();
    let ray = f.ray(cam.width as f64 + 8.0, cam.height as f64 / 2.0);
    let along = (cam.center - cam.eye).length() / ray.dir.dot(f.forward);
    let mut outside = truth.clone();
    for (k, axis) in ["x", "y", "z"].iter().enumerate() {
        outside[slot(&format!("back.{axis}"))] = ray.origin[k] + along * ray.dir[k];
    }
    for size in ["width", "depth", "height"] {
        outside[slot(&format!("back.{size}"))] = 6.0;
    }
    let (plain, hidden) = (
        loss_at(&p, &truth, &cams, &targets, 0.0),
        loss_at(&p, &outside, &cams, &targets, 0.0),
    );
    eprintln!("without a border: {plain:.6} at the truth, {hidden:.6} with the back outside");
    assert!(
        (hidden - plain).abs() <= 0.01 * plain,
        "the back is in the picture"
    );
    let (plain, seen) = (
        loss_at(&p, &truth, &cams, &targets, 0.25),
        loss_at(&p, &outside, &cams, &targets, 0.25),
    );
    eprintln!("with a border: {plain:.6} at the truth, {seen:.6} with the back outside");
    assert!(
        seen > 1.5 * plain,
        "the back outside the picture costs nothing"
    );
}
