//! Front-end benchmark: parse, evaluate and find candidates on a generated model of 1,000
//! parts, and the peak memory of doing it once.
//!
//! The model is a showroom of 125 chairs on a 5 × 5 × 5 grid of shelves, 8 parts each
//! (four legs, a seat, a back, two arms), written the way people write models: variables
//! at the top, a `chair` module with parameters and defaults, `for` loops for the legs and
//! arms, `translate`, `color`, and one call per chair with its own sizes (a third of the
//! chairs have round legs, i.e. cylinders).
//!
//! `cargo bench --bench front` times the whole pipeline (`load_model_text` +
//! `find_candidates`) and each stage, then re-runs this binary with `REPARAMC_BENCH_PEAK`
//! set: that process runs the pipeline once and prints its `VmHWM` (peak resident memory)
//! from `/proc/self/status`. The generated model is also written to the temporary
//! directory, for `reparamc inspect`.

use criterion::{Criterion, criterion_group};
use reparamc::front::source::SourceMap;
use std::hint::black_box;
use std::path::Path;
use std::time::Instant;

const CHAIRS_PER_SIDE: usize = 5;
const PARTS_PER_CHAIR: usize = 8;
const PEAK_ENV: &str = "REPARAMC_BENCH_PEAK";
const MODEL_PATH: &str = "showroom.scad";

/// A small deterministic generator (64-bit LCG), so the model is the same on every run.
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> u64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        self.0 >> 33
    }

    /// One of `choices`.
    fn pick<T: Copy>(&mut self, choices: &[T]) -> T {
        choices[(self.next() % choices.len() as u64) as usize]
    }
}

/// The showroom model as OpenSCAD text: 125 chairs of 8 parts, 1,000 parts in all.
fn showroom() -> String {
    let mut rng = Lcg(0x5eed);
    let mut s = String::from(
        "// A showroom: 125 chairs on a 5 x 5 x 5 grid of shelves, eight parts each.\n\
         \n\
         spacing = 120;       // distance between chairs on a shelf\n\
         shelf_height = 150;  // distance between shelves\n\
         leg = 4;             // leg thickness\n\
         board = 3;           // thickness of seat, back and arms\n\
         \n\
         // one chair, its corner at the origin\n\
         module chair(width = 45, depth = 42, seat_height = 45, back_height = 40,\n\
         \x20            arm_height = 20, round_legs = false) {\n\
         \x20   // legs, one at each corner\n\
         \x20   for (x = [0, width - leg], y = [0, depth - leg])\n\
         \x20       translate([x, y, 0])\n\
         \x20           if (round_legs)\n\
         \x20               translate([leg / 2, leg / 2, 0])\n\
         \x20                   cylinder(h = seat_height - board, d = leg, $fn = 24);\n\
         \x20           else\n\
         \x20               cube([leg, leg, seat_height - board]);\n\
         \x20   // seat\n\
         \x20   color(\"burlywood\")\n\
         \x20       translate([0, 0, seat_height - board])\n\
         \x20           cube([width, depth, board]);\n\
         \x20   // back\n\
         \x20   translate([0, depth - board, seat_height])\n\
         \x20       cube([width, board, back_height]);\n\
         \x20   // arms\n\
         \x20   for (x = [0, width - board])\n\
         \x20       translate([x, 0, seat_height])\n\
         \x20           cube([board, depth - board, arm_height]);\n\
         }\n\
         \n",
    );
    for shelf in 0..CHAIRS_PER_SIDE {
        s.push_str(&format!("// shelf {}\n", shelf + 1));
        for row in 0..CHAIRS_PER_SIDE {
            for col in 0..CHAIRS_PER_SIDE {
                let width = rng.pick(&[40, 42, 45, 48, 50, 52, 55, 60]);
                let depth = rng.pick(&[38, 40, 42, 44, 46, 50]);
                let seat = rng.pick(&[42, 44, 45, 46, 48, 50]);
                let back = rng.pick(&[30, 35, 38, 40, 45, 50, 55]);
                let arm = rng.pick(&[15, 18, 20, 22, 25]);
                let round = if (shelf + row + col) % 3 == 0 {
                    ", round_legs = true"
                } else {
                    ""
                };
                s.push_str(&format!(
                    "translate([{col} * spacing, {row} * spacing, {shelf} * shelf_height]) \
                     chair({width}, {depth}, seat_height = {seat}, back_height = {back}, \
                     arm_height = {arm}{round});\n"
                ));
            }
        }
    }
    s
}

fn load(text: &str) -> reparamc::front::eval::Evaluated {
    let mut sources = SourceMap::new();
    match reparamc::load_model_text(&mut sources, Path::new(MODEL_PATH), text.as_bytes()) {
        Ok(e) => e,
        Err(d) => panic!("the generated model fails:\n{}", d.render_plain(&sources)),
    }
}

fn bench(c: &mut Criterion) {
    let text = showroom();
    let evaluated = load(&text);
    assert_eq!(
        evaluated.model.parts.len(),
        CHAIRS_PER_SIDE.pow(3) * PARTS_PER_CHAIR
    );

    let mut group = c.benchmark_group("front_1000_parts");
    group.sample_size(20);
    group.bench_function("parse_evaluate_candidates", |b| {
        b.iter(|| {
            let evaluated = load(black_box(&text));
            reparamc::analysis::find_candidates(&evaluated.model)
        })
    });
    group.bench_function("parse", |b| {
        b.iter(|| reparamc::front::parse::parse_program(0, black_box(&text)))
    });
    group.bench_function("parse_evaluate", |b| b.iter(|| load(black_box(&text))));
    group.bench_function("candidates", |b| {
        b.iter(|| reparamc::analysis::find_candidates(black_box(&evaluated.model)))
    });
    group.finish();
}

/// `VmHWM` (peak resident set) of this process, in kB.
fn peak_kb() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

/// CPU time (user + system, all threads) this process has used, in seconds; 10 ms steps.
fn cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    // Fields after the `(command)`: state is field 3, utime 14, stime 15.
    let rest = &stat[stat.rfind(')')? + 2..];
    let fields: Vec<&str> = rest.split_whitespace().collect();
    let ticks: u64 = fields.get(11)?.parse::<u64>().ok()? + fields.get(12)?.parse::<u64>().ok()?;
    Some(ticks as f64 / 100.0)
}

/// In the re-invoked process: the pipeline once (peak memory, cold stage times), then
/// repeated runs for wall and CPU time per run (CPU time is robust on a busy machine).
fn measure_once() {
    let text = showroom();
    let before = peak_kb().unwrap_or(0);
    let t0 = Instant::now();
    let mut sources = SourceMap::new();
    let program = reparamc::front::parse::parse_program(0, &text).map(|p| p.stmts.len());
    let t1 = Instant::now();
    let evaluated = reparamc::load_model_text(&mut sources, Path::new(MODEL_PATH), text.as_bytes())
        .unwrap_or_else(|d| panic!("{}", d.render_plain(&sources)));
    let t2 = Instant::now();
    let candidates = reparamc::analysis::find_candidates(&evaluated.model);
    let t3 = Instant::now();
    let peak = peak_kb().unwrap_or(0);
    println!(
        "model: {} bytes, {} statements, {} parts, {} parameters, {} candidates",
        text.len(),
        program.unwrap_or(0),
        evaluated.model.parts.len(),
        evaluated.model.slots.len(),
        candidates.list.len()
    );
    println!(
        "one cold run: parse {:.1} ms, parse+evaluate {:.1} ms, candidates {:.1} ms",
        (t1 - t0).as_secs_f64() * 1e3,
        (t2 - t1).as_secs_f64() * 1e3,
        (t3 - t2).as_secs_f64() * 1e3
    );
    println!(
        "peak memory (VmHWM): {:.1} MB ({:.1} MB before the pipeline)",
        peak as f64 / 1024.0,
        before as f64 / 1024.0
    );
    drop((candidates, evaluated, sources));

    const RUNS: u32 = 20;
    let (cpu0, wall0) = (cpu_seconds(), Instant::now());
    for _ in 0..RUNS {
        let evaluated = load(black_box(&text));
        black_box(reparamc::analysis::find_candidates(&evaluated.model));
    }
    let wall = wall0.elapsed().as_secs_f64() / f64::from(RUNS);
    if let (Some(a), Some(b)) = (cpu0, cpu_seconds()) {
        println!(
            "parse+evaluate+candidates over {RUNS} runs: {:.1} ms wall, {:.1} ms CPU per run",
            wall * 1e3,
            (b - a) / f64::from(RUNS) * 1e3
        );
    }
}

/// Runs this binary again with `PEAK_ENV` set, so the peak is the pipeline's alone.
fn report_peak() {
    let path = std::env::temp_dir().join("reparamc-bench-showroom.scad");
    if std::fs::write(&path, showroom()).is_ok() {
        println!("generated model written to {}", path.display());
    }
    let Ok(exe) = std::env::current_exe() else {
        eprintln!("cannot find the benchmark binary to measure peak memory");
        return;
    };
    match std::process::Command::new(exe).env(PEAK_ENV, "1").output() {
        Ok(out) if out.status.success() => print!("{}", String::from_utf8_lossy(&out.stdout)),
        Ok(out) => eprintln!(
            "peak-memory run failed: {}",
            String::from_utf8_lossy(&out.stderr)
        ),
        Err(e) => eprintln!("cannot re-run the benchmark binary: {e}"),
    }
}

criterion_group! {
    name = benches;
    // No plots: this machine has no font for criterion's plotters backend.
    config = Criterion::default().without_plots();
    targets = bench
}

fn main() {
    if std::env::var_os(PEAK_ENV).is_some() {
        measure_once();
        return;
    }
    benches();
    Criterion::default().configure_from_args().final_summary();
    // Only in a real benchmark run (`cargo bench` passes `--bench`), not in `cargo test`.
    if std::env::args().any(|a| a == "--bench") {
        report_peak();
    }
}
