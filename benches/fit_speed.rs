//! Fitting speed: the chair fitted to five 128×128 views, iterations per second on the CPU
//! backend (and on the wgpu backend when an adapter exists), and peak memory. Under `cargo
//! bench` it also times one whole fit as a user runs it: `reparamc fit` with its default
//! settings, the chair to five 256×256 views of the bar stool (`reparamc render`'s views),
//! on the CPU backend.

use criterion::{Criterion, criterion_group, criterion_main};
use reparamc::fit::loss::Target;
use reparamc::fit::{FitOptions, Parametric, Stage, fit};
use reparamc::render::camera::{Camera, default_views};
use reparamc::render::scene::DEFAULT_SHADE;
use reparamc::render::soft::{prepare_view, render_view};
use reparamc::render::{Backend, CpuBackend};
use std::path::PathBuf;
use std::time::{Duration, Instant};

const ITERATIONS: usize = 30;

struct Setup {
    problem: Parametric,
    cameras: Vec<Camera>,
    targets: Vec<Target>,
}

fn setup() -> Setup {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let mut sources = reparamc::front::source::SourceMap::new();
    let model = reparamc::load_model(&mut sources, &root.join("examples/chair.scad"))
        .expect("the chair loads")
        .model;
    let problem = Parametric::new(&model);
    let (lo, hi) = model.bounds().unwrap();
    let cameras = default_views(lo, hi, 5, 128, 128).expect("cameras frame the chair");
    // Targets: the chair with a wider seat and longer legs, rendered by us.
    let mut xt = problem.x0.clone();
    for (i, s) in model.slots.iter().enumerate() {
        if s.name.ends_with(".height") && s.name.contains("leg") {
            xt[i] *= 1.2;
        }
        if s.name == "seat.width" {
            xt[i] *= 1.3;
        }
    }
    let scene = problem.scene(&xt);
    let targets = cameras
        .iter()
        .map(|c| {
            let v = prepare_view(&scene, c, Some(0.4));
            let (img, _, _) = render_view(&scene, &v, Some(0.4), DEFAULT_SHADE, false);
            Target::from_soft(&img)
        })
        .collect();
    Setup {
        problem,
        cameras,
        targets,
    }
}

fn run(s: &Setup, backend: &mut dyn Backend) -> Duration {
    // The optimiser's rate: the opening proportions search (a fixed cost of about fifty
    // loss evaluations, not iterations) is left out.
    let opts = FitOptions {
        rounds: 1,
        iterations: ITERATIONS,
        proportions: false,
        ..FitOptions::default()
    };
    let t = Instant::now();
    fit(
        &s.problem,
        &s.cameras,
        &s.targets,
        &[Stage::slots(1)],
        backend,
        &opts,
        &mut |_| {},
    )
    .expect("the fit runs");
    t.elapsed()
}

fn peak_mb() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM:"))
                .and_then(|l| l.split_whitespace().nth(1)?.parse::<f64>().ok())
        })
        .map_or(f64::NAN, |kb| kb / 1024.0)
}

fn report(name: &str, s: &Setup, backend: &mut dyn Backend) {
    // A warm-up, then the best of three timed fits.
    run(s, backend);
    let best = (0..3).map(|_| run(s, backend)).min().unwrap();
    let rate = ITERATIONS as f64 / best.as_secs_f64();
    eprintln!(
        "fit_speed: {name}: {rate:.0} iterations/s (chair, 5 views of 128×128); peak memory {:.0} MB",
        peak_mb()
    );
}

/// One whole fit as the `fit` command runs it (default settings, CPU): the chair to five
/// 256×256 views of the bar stool drawn as `reparamc render` draws them. Seconds.
fn whole_fit_seconds() -> f64 {
    use reparamc::command::fit::{Options as FitOpts, Settings, prepare};
    use reparamc::command::render::{self, BackendChoice, Cameras, Layout, Pictures};
    use reparamc::front::source::SourceMap;
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let cpu = BackendChoice {
        gpu: false,
        cpu: true,
    };
    let dir = std::env::temp_dir().join(format!("reparamc-fit-speed-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let drawn = render::render(
        &render::Options {
            model: root.join("examples/variations/chair/bar_stool.scad"),
            call: None,
            size: (256, 256),
            cameras: Cameras::Around(5),
            backend: cpu,
            layout: Layout::Views,
        },
        &mut SourceMap::new(),
    )
    .unwrap_or_else(|_| panic!("the bar stool renders"));
    let Pictures::Views {
        files,
        cameras_json,
    } = drawn.pictures
    else {
        unreachable!("views were asked for")
    };
    for (name, png) in files {
        std::fs::write(dir.join(name), png).unwrap();
    }
    std::fs::write(dir.join("cameras.json"), cameras_json).unwrap();
    let opts = FitOpts {
        model: root.join("examples/chair.scad"),
        target: dir.clone(),
        subspace: false,
        max_size: None,
        gallery: false,
        backend: cpu,
        settings: Settings::default(),
    };
    let job = prepare(&opts, &mut SourceMap::new()).unwrap_or_else(|_| panic!("the fit starts"));
    let t = Instant::now();
    job.run(&mut |_| {})
        .unwrap_or_else(|_| panic!("the fit runs"));
    let seconds = t.elapsed().as_secs_f64();
    let _ = std::fs::remove_dir_all(&dir);
    seconds
}

fn bench(c: &mut Criterion) {
    if std::env::args().any(|a| a == "--bench") {
        eprintln!(
            "fit_speed: whole fit, chair to five 256×256 views of the bar stool, default settings, CPU: {:.1} s",
            whole_fit_seconds()
        );
    }
    let s = setup();
    breakdown(&s);
    let mut cpu = CpuBackend::new();
    report("CPU", &s, &mut cpu);
    let mut g = c.benchmark_group("fit_chair_5x128");
    g.sample_size(10);
    g.bench_function("cpu_30_iterations", |b| b.iter(|| run(&s, &mut cpu)));
    #[cfg(feature = "gpu")]
    match reparamc::render::gpu::GpuBackend::new() {
        Ok(mut gpu) => {
            report(&gpu.name(), &s, &mut gpu);
            g.bench_function("wgpu_30_iterations", |b| b.iter(|| run(&s, &mut gpu)));
        }
        Err(e) => eprintln!("fit_speed: no wgpu backend ({e})"),
    }
    g.finish();
}

criterion_group! {
    name = benches;
    // No plots: this machine has no font for criterion's plotters backend.
    config = Criterion::default().without_plots();
    targets = bench
}
criterion_main!(benches);

/// Where an iteration's time goes (printed once).
#[allow(dead_code)]
fn breakdown(s: &Setup) {
    use reparamc::fit::loss::view_loss;
    use reparamc::render::soft::theta_gradient;
    let scene = s.problem.scene(&s.problem.x0);
    let n = 50;
    let (mut tp, mut tr, mut tl, mut tg) = (0.0, 0.0, 0.0, 0.0);
    for _ in 0..n {
        for (c, t) in s.cameras.iter().zip(&s.targets) {
            let a = Instant::now();
            let v = prepare_view(&scene, c, Some(0.5));
            let b = Instant::now();
            let (img, _, e) = render_view(&scene, &v, Some(0.5), DEFAULT_SHADE, true);
            let cc = Instant::now();
            let l = view_loss(&img, t, &reparamc::fit::loss::LossSpec::default(), true);
            let d = Instant::now();
            let _ = theta_gradient(&scene, &v, &e, &l.dm, &l.ds);
            let f = Instant::now();
            tp += (b - a).as_secs_f64();
            tr += (cc - b).as_secs_f64();
            tl += (d - cc).as_secs_f64();
            tg += (f - d).as_secs_f64();
        }
    }
    let k = 1000.0 / n as f64;
    eprintln!(
        "per iteration (5 views): prepare {:.2} ms, render {:.2} ms, loss {:.2} ms, gradient {:.2} ms",
        tp * k,
        tr * k,
        tl * k,
        tg * k
    );
}
