//! Fitting quality on pictures nobody tuned it for: families from the generator
//! (`reparamc::families`), each fitted from its input model to a far variant (a held-out
//! draw of its intent parameters, optional parts dropped as drawn) seen from five cameras,
//! with the `fit` command's default settings. The five cameras are drawn at random around
//! the variant (per seed), so no fixed set of views can be tuned to. Targets are drawn by
//! our renderer (`reparamc render`) and, when `openscad` is installed, by OpenSCAD itself
//! (its CGAL render, whose booleans are what the program means);
//! each fit is scored by exact 3-D IoU of the fitted model against the variant.
//!
//! Prints, per target source, the share of fits with IoU ≥ 0.9 and ≥ 0.95, the median, and
//! the mean time per fit. `FIT_FAMILIES_SEEDS=a..b` (default `0..20`), `FIT_FAMILIES_SIZE`
//! (default 256), `FIT_FAMILIES_SOURCES=ours,openscad`, `FIT_FAMILIES_SCHEDULE=paper` (the
//! paper's schedule instead of the default; `far` is the default's recipe by name),
//! `FIT_FAMILIES_REACH` (the schedule's [`Settings::reach`] instead),
//! `FIT_FAMILIES_SIZE_PRIOR` (its [`Settings::size_prior`] instead),
//! `FIT_FAMILIES_TIE_PRIOR` (its [`Settings::tie_prior`] instead),
//! `FIT_FAMILIES_SOFT_EDGES=sigmoid|blurred` (its [`Settings::soft_edges`] instead),
//! `FIT_FAMILIES_PREVIEW=1` (OpenSCAD's targets drawn by its preview instead of CGAL),
//! `FIT_FAMILIES_ONE_COLOUR=1` (one grey per surface instead of a brightness per part),
//! `FIT_FAMILIES_FIXED_VIEWS=1` (the five default views of `reparamc render` instead of
//! random ones), `FIT_FAMILIES_KEEP=dir` (keep each fit's model, variant, views and result
//! in `dir/<seed>-<source>/` instead of deleting them). Under `cargo test` (`--bench`
//! absent) it fits one family at 48 pixels as a smoke test.

use reparamc::command::fit::{Options as FitOpts, Settings, prepare};
use reparamc::command::render::BackendChoice;
use reparamc::families::rng::Rng;
use reparamc::families::{Family, style::Style};
use reparamc::fit::SoftEdges;
use reparamc::front::source::SourceMap;
use reparamc::render::camera::{
    Camera, CameraSpec, Projection, cameras_json, default_views, framing,
};
use reparamc::render::openscad::{self, OpenScadRender};
use reparamc::render::scene::{BOX_FILTER, DEFAULT_SHADE, Scene};
use reparamc::render::soft::{prepare_view, render_view};
use std::path::{Path, PathBuf};
use std::time::Instant;

const CPU: BackendChoice = BackendChoice {
    gpu: false,
    cpu: true,
};

fn env_or<T: std::str::FromStr>(name: &str, default: T) -> T {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

fn load(path: &Path) -> reparamc::ir::Model {
    reparamc::load_model(&mut SourceMap::new(), path)
        .unwrap_or_else(|d| panic!("{}: {}", path.display(), d.message))
        .model
}

/// The input model and its first held-out variation, written to `dir`.
fn write_family(family: &Family, dir: &Path) -> (PathBuf, PathBuf) {
    let style: Style = family.style;
    let program = family.program(style);
    let base = dir.join("model.scad");
    let variant = dir.join("variant.scad");
    std::fs::write(&base, family.input_text(style)).unwrap();
    let far = &family.held_out[0];
    let values = program.values(&far.theta, &far.dropped);
    std::fs::write(&variant, program.render(&values)).unwrap();
    (base, variant)
}

/// Five cameras from random directions around a box (azimuth uniform over the circle,
/// OpenSCAD's tilt `rx` uniform over the 20° to 80° the default views span: from nearly
/// above to nearly level), framed as the default views frame it; the same for the same
/// family seed.
fn random_views(lo: [f64; 3], hi: [f64; 3], size: u32, seed: u64) -> Vec<Camera> {
    let (center, dist) = framing(lo, hi, size, size).unwrap();
    let mut rng = Rng::new(seed ^ 0x0ca3_e7a5);
    (0..5)
        .map(|v| {
            let (tilt, azimuth) = (rng.range(20.0, 80.0), rng.range(0.0, 360.0));
            let params = [center.x, center.y, center.z, tilt, 0.0, azimuth, dist];
            let name = format!("view{}", v + 1);
            Camera::from_openscad(&name, &params, Projection::Perspective, size, size).unwrap()
        })
        .collect()
}

/// Five views framing the variant (random ones unless `FIT_FAMILIES_FIXED_VIEWS` is set),
/// drawn by `source` into `views/` with a `cameras.json`.
fn targets(variant: &Path, views: &Path, size: u32, source: &str, seed: u64) -> bool {
    let m = load(variant);
    let scene = Scene::from_parts(&m.parts, &m.csg);
    let Some((lo, hi)) = scene.bounds() else {
        return false;
    };
    let cams = if std::env::var_os("FIT_FAMILIES_FIXED_VIEWS").is_some() {
        default_views(lo, hi, 5, size, size).unwrap()
    } else {
        random_views(lo, hi, size, seed)
    };
    std::fs::create_dir_all(views).unwrap();
    let mut specs = Vec::new();
    for c in &cams {
        let name = format!("{}.png", c.name);
        specs.push(CameraSpec::of(c, Some(name.clone())));
        let img = if source == "openscad" {
            // CGAL's render: OpenSCAD's booleans, as its `.csg` means them. The preview
            // draws a cut flush with a face (the generator's hollows) as a z-fighting film.
            let how = OpenScadRender {
                full_render: std::env::var_os("FIT_FAMILIES_PREVIEW").is_none(),
                ..OpenScadRender::default()
            };
            match openscad::render(variant, c, &how) {
                Ok(img) => img,
                Err(e) => {
                    eprintln!("openscad: {e}");
                    return false;
                }
            }
        } else {
            let v = prepare_view(&scene, c, Some(BOX_FILTER));
            let soft = render_view(&scene, &v, Some(BOX_FILTER), DEFAULT_SHADE, false).0;
            reparamc::render::image::picture(&soft)
        };
        std::fs::write(views.join(name), img.encode_png()).unwrap();
    }
    std::fs::write(views.join("cameras.json"), cameras_json(&specs)).unwrap();
    true
}

/// The schedule `FIT_FAMILIES_SCHEDULE` names (the default's when unset).
fn base_settings() -> Settings {
    match std::env::var("FIT_FAMILIES_SCHEDULE").as_deref() {
        Ok("far") => Settings::far(),
        Ok("paper") => Settings::paper(),
        _ => Settings::default(),
    }
}

/// `FIT_FAMILIES_SOFT_EDGES=sigmoid|blurred` instead of the schedule's `default`.
fn soft_edges(default: SoftEdges) -> SoftEdges {
    match std::env::var("FIT_FAMILIES_SOFT_EDGES").as_deref() {
        Ok("sigmoid") => SoftEdges::Sigmoid,
        Ok("blurred") => SoftEdges::Blurred,
        _ => default,
    }
}

/// Fits the family's model to the variant's pictures with the default settings: IoU and
/// seconds.
fn fit_one(seed: u64, size: u32, source: &str) -> Option<(f64, f64)> {
    let family = Family::generate(seed, 0)?;
    let keep = std::env::var_os("FIT_FAMILIES_KEEP").map(PathBuf::from);
    let dir = match &keep {
        Some(root) => root.join(format!("{seed}-{source}")),
        None => std::env::temp_dir().join(format!(
            "reparamc-fit-families-{}-{seed}-{source}",
            std::process::id()
        )),
    };
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let (base, variant) = write_family(&family, &dir);
    let views = dir.join("views");
    if !targets(&variant, &views, size, source, seed) {
        return None;
    }
    let base_settings = base_settings();
    let opts = FitOpts {
        model: base.clone(),
        target: views,
        subspace: false,
        max_size: None,
        gallery: false,
        backend: CPU,
        settings: Settings {
            reach: env_or("FIT_FAMILIES_REACH", base_settings.reach),
            size_prior: env_or("FIT_FAMILIES_SIZE_PRIOR", base_settings.size_prior),
            tie_prior: env_or("FIT_FAMILIES_TIE_PRIOR", base_settings.tie_prior),
            soft_edges: soft_edges(base_settings.soft_edges),
            per_item_albedo: std::env::var_os("FIT_FAMILIES_ONE_COLOUR").is_none(),
            ..base_settings
        },
    };
    let mut sources = SourceMap::new();
    let job = prepare(&opts, &mut sources).ok()?;
    let t0 = Instant::now();
    let fitted = job.run(&mut |_| {}).ok()?;
    let seconds = t0.elapsed().as_secs_f64();
    let fitted_path = dir.join("fitted.scad");
    std::fs::write(&fitted_path, &fitted.scad).unwrap();
    let (a, b) = (load(&fitted_path), load(&variant));
    let iou = reparamc::geom::iou((&a.parts, &a.csg), (&b.parts, &b.csg));
    if keep.is_none() {
        let _ = std::fs::remove_dir_all(&dir);
    }
    Some((iou, seconds))
}

fn main() {
    let bench = std::env::args().any(|a| a == "--bench");
    let (seeds, size) = if bench {
        let range: String = env_or("FIT_FAMILIES_SEEDS", "0..20".to_string());
        let (a, b) = range.split_once("..").unwrap_or(("0", "20"));
        let (a, b): (u64, u64) = (a.parse().unwrap_or(0), b.parse().unwrap_or(20));
        (a..b, env_or("FIT_FAMILIES_SIZE", 256u32))
    } else {
        (0..1, 48)
    };
    let sources: String = env_or("FIT_FAMILIES_SOURCES", "ours,openscad".to_string());
    for source in sources.split(',') {
        if source == "openscad" && !openscad::available() {
            println!("openscad: not installed, skipped");
            continue;
        }
        let mut ious = Vec::new();
        let mut seconds = 0.0;
        for seed in seeds.clone() {
            let Some((iou, s)) = fit_one(seed, size, source) else {
                println!("{source} seed {seed}: no fit");
                continue;
            };
            println!("{source} seed {seed}: IoU {iou:.3} in {s:.1} s");
            ious.push(iou);
            seconds += s;
        }
        if ious.is_empty() {
            continue;
        }
        let n = ious.len() as f64;
        ious.sort_by(f64::total_cmp);
        let share = |t: f64| ious.iter().filter(|&&v| v >= t).count() as f64 / n;
        println!(
            "{source}: {} fits at {size}×{size}: IoU ≥ 0.9 {:.0}%, ≥ 0.95 {:.0}%, median {:.3}, {:.1} s per fit",
            ious.len(),
            100.0 * share(0.9),
            100.0 * share(0.95),
            ious[ious.len() / 2],
            seconds / n
        );
    }
}
