//! The zero-shot loop's own time per round (the servers' time aside): five views of the
//! chair at 256×256 rendered, best-of-3 samples per view compared with the renders, and
//! 30 fit steps towards the kept ones (issue 19: at most 0.3 s on this machine's CPU).

use criterion::{Criterion, criterion_group, criterion_main};
use reparamc::explore::diffusion::Pool;
use reparamc::explore::rounds::{Explorer, Settings};
use reparamc::render::image::Rgb;
use std::path::PathBuf;
use std::time::Duration;

fn round(c: &mut Criterion) {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let path = root.join("examples/chair.scad");
    let text = std::fs::read_to_string(&path).expect("the chair reads");
    let mut sources = reparamc::front::source::SourceMap::new();
    let (parsed, evaluated) =
        reparamc::load_model_parsed(&mut sources, &path).expect("the chair loads");
    let model = evaluated.model;
    let settings = Settings {
        size: 256,
        ..Settings::default()
    };
    let pool = Pool {
        servers: Vec::new(),
        timeout: Duration::from_secs(1),
        retries: 0,
        backoff: Duration::ZERO,
        parallel: 5,
    };
    let explorer = Explorer::new(&model, &text, parsed.main, &settings, &pool).expect("frames");
    // The samples: renders of the chair 30% wider, at the servers' 512×512.
    let x0 = explorer.x0().to_vec();
    let wide: Vec<f64> = x0.iter().map(|v| v * 1.3).collect();
    let cameras = explorer.cameras("bench", 0).expect("cameras");
    let big: Vec<_> = cameras.iter().map(|c| c.with_size(512, 512)).collect();
    let samples: Vec<Rgb> = explorer.render(&wide, &big);
    let mut g = c.benchmark_group("explore");
    g.sample_size(10).measurement_time(Duration::from_secs(20));
    g.bench_function("round_5x256_30_steps_own_time", |b| {
        b.iter(|| {
            let renders = explorer.render(&x0, &cameras);
            let answers: Vec<Vec<Rgb>> = samples.iter().map(|s| vec![s.clone(); 3]).collect();
            explorer
                .take(&x0, 0, &cameras, renders, answers)
                .expect("the round runs")
        })
    });
    g.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default().without_plots();
    targets = round
}
criterion_main!(benches);
