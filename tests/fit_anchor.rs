//! The fit's regulariser pulls towards the model's own numbers (`Parametric::anchor`), also
//! when the fit starts elsewhere, as every round of `explore` after the first does: the
//! paper's λ‖x − x₀‖² keeps the rounds tied to the original program.

use reparamc::fit::loss::Target;
use reparamc::fit::{FitOptions, Parametric, Stage, fit};
use reparamc::render::CpuBackend;
use reparamc::render::camera::default_views;
use reparamc::render::scene::DEFAULT_SHADE;
use reparamc::render::soft::{prepare_view, render_view};

#[test]
fn a_fit_started_elsewhere_is_pulled_towards_the_model() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/chair.scad");
    let mut sources = reparamc::front::source::SourceMap::new();
    let m = reparamc::load_model(&mut sources, &path).unwrap().model;
    // The fit starts with the chair's back 20 units taller, and the pictures show that
    // start exactly: only the regulariser has a reason to move.
    let mut p = Parametric::new(&m);
    let back = m
        .slots
        .iter()
        .position(|s| s.name == "back.height")
        .unwrap();
    let model = p.x0[back];
    p.x0[back] = model + 20.0;
    let (lo, hi) = m.bounds().unwrap();
    let cams = default_views(lo, hi, 3, 48, 48).unwrap();
    let targets: Vec<Target> = cams
        .iter()
        .map(|c| {
            let scene = p.scene(&p.x0);
            let v = prepare_view(&scene, c, Some(0.4));
            Target::from_soft(&render_view(&scene, &v, Some(0.4), DEFAULT_SHADE, false).0)
        })
        .collect();
    let fitted = |lambda: f64| {
        let opts = FitOptions {
            lambda,
            iterations: 40,
            rounds: 1,
            ..FitOptions::default()
        };
        let r = fit(
            &p,
            &cams,
            &targets,
            &[Stage::slots(1)],
            &mut CpuBackend::new(),
            &opts,
            &mut |_| {},
        )
        .unwrap();
        r.x[back]
    };
    let free = fitted(0.0);
    let pulled = fitted(100.0);
    let start = model + 20.0;
    eprintln!(
        "back: model {model}, start {start}; fitted {free:.3} without, {pulled:.3} with λ = 100"
    );
    assert!(
        (free - start).abs() < 0.5,
        "no regulariser, no reason to move"
    );
    assert!(
        pulled < start - 5.0,
        "the regulariser pulls towards the model's {model}"
    );
    assert!(pulled >= model - 1e-9, "and not past it");
}
