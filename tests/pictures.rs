//! The pictures a user looks at: the distortion plot (PNG and SVG), the presets gallery and
//! the HTML report, checked for what they show, and the page opened in headless Chromium.

mod common;

use reparamc::analysis::cutoff::Cutoff;
use reparamc::back::gallery::{BLEND, DEFAULTS, LABEL_H, TILE_H, TILE_W, origin, size};
use reparamc::back::plot::{PlotFormat, X_LABEL, Y_LABEL, distortion_plot, escape};
use reparamc::back::report::{ChosenRelation, Report};
use reparamc::command::compile::{CompileOptions, CompileOutput, compile};
use reparamc::command::pictures::Progress;
use reparamc::front::source::SourceMap;
use reparamc::render::image::Rgb;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::{Arc, Mutex, OnceLock};

const VARIATIONS: [&str; 3] = ["bench", "stool", "armchair"];

/// The environment variable that sets how long the main job runs before its bar shows.
const QUIET_FOR_VAR: &str = "REPARAMC_PROGRESS_AFTER";

/// What discovery told the chair's job of its steps: (relations decided, relations).
static STEPS: Mutex<Vec<(usize, usize)>> = Mutex::new(Vec::new());

/// The bundled chair with three variations, with every picture asked for (made once), its
/// discovery's steps recorded in [`STEPS`].
fn chair() -> &'static CompileOutput {
    static OUT: OnceLock<CompileOutput> = OnceLock::new();
    OUT.get_or_init(|| {
        let dir = common::repo().join("examples/variations/chair");
        let record = |done, total| STEPS.lock().expect("steps").push((done, total));
        let options = CompileOptions {
            model: common::repo().join("examples/chair.scad"),
            variations: VARIATIONS
                .iter()
                .map(|v| dir.join(format!("{v}.scad")))
                .collect(),
            plot: Some(PlotFormat::Png),
            gallery: true,
            page: true,
            progress: Progress {
                stage: None,
                step: Some(Arc::new(record)),
            },
            ..CompileOptions::default()
        };
        compile(&options, &mut SourceMap::new()).expect("the chair compiles")
    })
}

/// A report with `curve` and a cutoff at `keep` (change points `paper`, `published`).
fn report_with(curve: &[f64], keep: usize, paper: usize, published: usize) -> Report {
    let chosen = (1..curve.len())
        .map(|i| ChosenRelation {
            relation: format!("part{i}.width equals part{}.width", i + 1),
            z: Some(i as f64),
            intent_probability: Some(0.5),
            residual: Some(0.1),
        })
        .collect();
    Report {
        model: "m.scad".into(),
        parameter_count: 10,
        base_constraint_count: curve.len() - 1,
        method: "test".into(),
        chosen,
        noise: None,
        kept_count: keep,
        cutoff: Some(Cutoff {
            keep,
            paper,
            published,
            reason: "the next relation is broken".into(),
        }),
        distortion_curve: curve.to_vec(),
        dimension: 1,
        free_variables: Vec::new(),
        variations: Vec::new(),
        toggles: Vec::new(),
    }
}

fn svg_of(report: &Report) -> String {
    String::from_utf8(distortion_plot(report, PlotFormat::Svg).expect("the plot draws"))
        .expect("SVG is text")
}

#[test]
fn plot_png_has_its_size_and_shows_the_curve_and_the_cutoff() {
    let png = chair().plot.as_ref().expect("a plot was asked for");
    let img = Rgb::decode_png(png).expect("a PNG");
    assert_eq!((img.width, img.height), (960, 540));
    let count = |f: &dyn Fn([f32; 3]) -> bool| img.data.iter().filter(|&&c| f(c)).count();
    // The cutoff is a red line across the plot's height, the curve a blue line.
    let red = count(&|c| c[0] > 0.7 && c[1] < 0.3 && c[2] < 0.3);
    let blue = count(&|c| c[2] > 0.6 && c[0] < 0.3 && c[1] < 0.5);
    assert!(red > 2 * 300, "red pixels: {red}");
    assert!(blue > 300, "blue pixels: {blue}");
}

#[test]
fn plot_svg_names_its_axes_and_gives_each_step_its_relation() {
    let report = &chair().compiled.report;
    let svg = svg_of(report);
    for label in [
        X_LABEL,
        Y_LABEL,
        "kept prefix",
        "distortion after each relation",
    ] {
        assert!(svg.contains(label), "the SVG lacks `{label}`");
    }
    let keep = report.keep_step();
    assert!(svg.contains(&format!("cutoff: keep {keep}")));
    assert!(
        svg.contains(&format!("Cutoff at {keep}:")),
        "the reason is written"
    );
    // The title's count is of the relations tested (the rest were implied), so it is
    // not mistaken for the summary's count of every relation that holds.
    let tested = report.distortion_curve.len() - 1;
    assert!(
        svg.contains(&format!("{keep} of the {tested} tested kept")),
        "the title says what it counts"
    );
    assert_eq!(svg.matches("<title>").count(), report.chosen.len());
    for (s, c) in report.chosen.iter().enumerate() {
        let tip = format!("<title>step {}: {}", s + 1, escape(&c.relation));
        assert!(svg.contains(&tip), "no tooltip `{tip}`");
    }
}

#[test]
fn plot_marks_the_change_points_only_where_they_differ_from_the_cutoff() {
    let curve = [0.0, 0.01, 0.02, 0.03, 0.3, 0.5, 0.6];
    let apart = svg_of(&report_with(&curve, 2, 4, 5));
    assert!(apart.contains("change point: keep 4"));
    assert!(apart.contains("the published mean-shift point: keep 5"));
    let same = svg_of(&report_with(&curve, 3, 3, 3));
    assert!(!same.contains("change point"));
    assert!(!same.contains("mean-shift point"));
}

#[test]
fn plot_is_logarithmic_only_when_the_curve_spans_decades() {
    let wide = svg_of(&report_with(&[0.0, 1e-5, 1e-4, 1e-2, 0.5], 2, 2, 2));
    assert!(wide.contains("log scale"));
    let narrow = svg_of(&report_with(&[0.0, 0.2, 0.3, 0.5], 2, 2, 2));
    assert!(!narrow.contains("log scale"));
}

/// The pixels of tile `k`'s picture, or of its label band.
fn crop(img: &Rgb, k: usize, label: bool) -> Vec<[f32; 3]> {
    let (ox, oy) = origin(k);
    let (y0, h) = if label {
        (oy + TILE_H, LABEL_H)
    } else {
        (oy, TILE_H)
    };
    (y0..y0 + h)
        .flat_map(|y| (ox..ox + TILE_W).map(move |x| (x, y)))
        .map(|(x, y)| img.get(x, y))
        .collect()
}

/// How many pixels of `a` and `b` differ visibly.
fn differing(a: &[[f32; 3]], b: &[[f32; 3]]) -> usize {
    a.iter()
        .zip(b)
        .filter(|(p, q)| (0..3).any(|k| (p[k] - q[k]).abs() > 0.1))
        .count()
}

#[test]
fn gallery_has_a_labelled_tile_per_preset_and_the_tiles_differ() {
    let g = chair().gallery.as_ref().expect("a gallery was asked for");
    let mut want = vec![DEFAULTS.to_string()];
    want.extend(VARIATIONS.iter().map(|v| v.to_string()));
    want.push(BLEND.to_string());
    assert_eq!(g.names, want);
    let img = Rgb::decode_png(&g.png).expect("a PNG");
    assert_eq!((img.width, img.height), size(want.len()));
    let tiles: Vec<_> = (0..want.len()).map(|k| crop(&img, k, false)).collect();
    let labels: Vec<_> = (0..want.len()).map(|k| crop(&img, k, true)).collect();
    let area = (TILE_W * TILE_H) as usize;
    for (k, (t, l)) in tiles.iter().zip(&labels).enumerate() {
        let drawn = t.iter().filter(|c| c.iter().any(|&v| v < 0.9)).count();
        assert!(drawn > area / 50, "tile {k} shows almost nothing");
        let ink = l.iter().filter(|c| c.iter().all(|&v| v < 0.5)).count();
        assert!(ink > 20, "tile {k} has no label");
    }
    for i in 0..tiles.len() {
        for j in i + 1..tiles.len() {
            let d = differing(&tiles[i], &tiles[j]);
            assert!(
                d > area / 100,
                "tiles {i} and {j} differ in {d} pixels only"
            );
            assert!(
                differing(&labels[i], &labels[j]) > 0,
                "labels {i} and {j} are the same"
            );
        }
    }
}

#[test]
fn report_page_shows_what_was_decided_and_links_nothing_outside() {
    let out = chair();
    let page = out.page.as_ref().expect("a page was asked for");
    let report = &out.compiled.report;
    for forbidden in ["<script", "<link", "href=", "url(", "@import"] {
        assert!(!page.contains(forbidden), "the page has `{forbidden}`");
    }
    assert_eq!(
        page.matches("src=\"").count(),
        page.matches("src=\"data:image/png;base64,").count()
    );
    for v in &report.free_variables {
        assert!(page.contains(&format!("<code>{}</code>", escape(&v.name))));
        assert!(page.contains(&escape(&v.description)));
    }
    for c in &report.chosen {
        assert!(page.contains(&escape(&c.relation)), "{}", c.relation);
    }
    assert!(page.contains("Relations left out"));
    for part in report.toggles.iter().flatten() {
        assert!(page.contains(&format!("<code>{}</code>", escape(part))));
    }
    assert!(page.contains("<svg"), "the plot is inline");
}

#[test]
fn discovery_tells_its_steps_up_to_every_relation_decided() {
    let n = chair().compiled.candidates.list.len();
    let steps = STEPS.lock().expect("steps").clone();
    assert!(steps.len() > 2, "{steps:?}");
    assert!(steps.iter().all(|&(_, total)| total == n), "{steps:?}");
    assert!(steps.windows(2).all(|w| w[0].0 <= w[1].0), "{steps:?}");
    assert!(
        steps[0].0 < n,
        "the first call is before any step: {steps:?}"
    );
    assert_eq!(steps.last(), Some(&(n, n)));
}

#[test]
fn the_cutoff_of_exact_variations_says_so_instead_of_a_zero_sigma() {
    // The chair's variations are typed files: exact, so the noise sits at its floor.
    let report = &chair().compiled.report;
    let noise = report.noise.expect("a noise model");
    assert!(noise.exact(), "{noise:?}");
    let reason = &report.cutoff.as_ref().expect("a cutoff").reason;
    assert!(reason.contains("(exact variations, no noise)"), "{reason}");
    assert!(
        !reason.contains("σ =") && !reason.contains("odds"),
        "{reason}"
    );
    let page = chair().page.as_ref().expect("a page");
    assert!(page.contains("The variations are exact (no noise)"));
    assert!(!page.contains("σ = 0.000"));
}

#[test]
fn report_page_opens_in_chromium_without_errors_and_every_image_shows() {
    let dir: PathBuf = common::tempfile(Path::new("page"), "d");
    std::fs::create_dir_all(&dir).expect("a scratch folder");
    let page = chair().page.as_ref().expect("a page was asked for");
    std::fs::write(dir.join("r.html"), page).expect("write the page");
    // A broken page first, so the check is seen to catch what it looks for.
    std::fs::write(
        dir.join("bad.html"),
        "<!DOCTYPE html><html><body><img src=\"missing.png\"><script>console.error('boom')</script></body></html>",
    )
    .expect("write the broken page");
    let bad = common::browser::open(&dir.join("bad.html"));
    assert!(
        !bad.console.is_empty(),
        "a console error goes unseen: {bad:?}"
    );
    assert_eq!(
        (bad.images, bad.broken.len(), bad.svgs),
        (1, 1, 0),
        "{bad:?}"
    );
    let shown = common::browser::open(&dir.join("r.html"));
    assert!(shown.clean(), "{shown:?}");
    let images = page.matches("<img ").count();
    assert!(images >= 2, "views and gallery: {images} images");
    assert_eq!((shown.images, shown.svgs), (images, 1), "{shown:?}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_command_writes_each_format_its_file_names_and_keeps_the_json_report() {
    let dir = common::tempfile(Path::new("cli"), "d");
    std::fs::create_dir_all(&dir).expect("a scratch folder");
    let run = Command::new(env!("CARGO_BIN_EXE_reparamc"))
        .arg(common::repo().join("examples/chair.scad"))
        .arg("-o")
        .arg(dir.join("out.scad"))
        .arg("--report")
        .arg(dir.join("r.json"))
        .arg("--plot")
        .arg(dir.join("curve.svg"))
        .arg("--gallery")
        .arg(dir.join("g.png"))
        .env(QUIET_FOR_VAR, "0")
        .output()
        .expect("the binary runs");
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let json = std::fs::read_to_string(dir.join("r.json")).expect("the report");
    let v: serde_json::Value = serde_json::from_str(&json).expect("the report is JSON");
    assert!(v.get("chosen").is_some());
    let svg = std::fs::read_to_string(dir.join("curve.svg")).expect("the plot");
    assert!(svg.starts_with("<svg") && svg.contains(X_LABEL));
    let g = Rgb::read_png(&dir.join("g.png")).expect("the gallery is a PNG");
    assert_eq!(
        (g.width, g.height),
        size(1),
        "no variations: the defaults alone"
    );
    // Standard error is not a terminal here: no progress bar is drawn on it.
    let err = String::from_utf8_lossy(&run.stderr);
    assert!(!err.contains('\r') && !err.contains('\u{1b}'), "{err:?}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_long_job_shows_its_progress_on_a_terminal() {
    // `script` (util-linux) runs the command on a pseudo-terminal and copies what it drew.
    let dir = common::tempfile(Path::new("tty"), "d");
    std::fs::create_dir_all(&dir).expect("a scratch folder");
    let vary = common::repo().join("examples/variations/chair");
    let mut line = format!(
        "{} {} -o {}",
        env!("CARGO_BIN_EXE_reparamc"),
        common::repo().join("examples/chair.scad").display(),
        dir.join("out.scad").display()
    );
    for v in VARIATIONS {
        line += &format!(" --vary {}", vary.join(format!("{v}.scad")).display());
    }
    line += &format!(" --report {}", dir.join("r.html").display());
    // The job here takes less than the second the bar waits for: it is told to show at once.
    let run = Command::new("script")
        .args(["-qefc", &line, "/dev/null"])
        .env(QUIET_FOR_VAR, "0")
        .output()
        .expect("`script` (util-linux) runs");
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let tty = String::from_utf8_lossy(&run.stdout);
    // The bar is over discovery's steps, of every candidate relation, with the stage beside.
    let n = chair().compiled.candidates.list.len();
    let steps = format!("/{n} relations decided");
    assert!(
        tty.contains(&steps),
        "no bar over discovery's steps ({steps}): {tty:?}"
    );
    // Which later states are drawn depends on the bar's refresh rate and the machine's
    // load (a state shorter than a refresh may never be drawn), so only the steps and the
    // first stage are required.
    assert!(
        tty.contains("reading the model"),
        "no stage before it: {tty:?}"
    );
    assert!(tty.contains("sliders drive"), "no summary line: {tty:?}");
    let _ = std::fs::remove_dir_all(&dir);
}
