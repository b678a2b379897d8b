//! The fitting quality table: every example model, fitted from its base to targets that
//! OpenSCAD rendered of each of its variants, scored by exact 3-D IoU.
//!
//! Used by `benches/fit_quality.rs` (the whole table; one case under `cargo test`).

#![allow(dead_code)]

use reparamc::command::fit::Settings;
use reparamc::fit::loss::Target;
use reparamc::fit::{FitOptions, Parametric, fit};
use reparamc::render::camera::{Camera, default_views};
use reparamc::render::openscad::{self, OpenScadRender};
use reparamc::render::{Backend, CpuBackend};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The settings of the quality table: the `fit` command's default ([`Settings::far`]):
/// Adam (the paper's SGD needs many more rounds on targets this far from the base), the
/// paper's loss, 10 rounds of 30 iterations, the first half warm (one round stretching the
/// model, then the structural subspace); each stage's last round settles, two sweeps of
/// face moves finish (thin boards the gradient leaves a little thick), and two of
/// refinement (edges a fraction of a pixel off). The pictures frame the variant, so the fit
/// sees them inside a border of background: a part of the base outside every picture must
/// still cost.
pub fn table_options() -> FitOptions {
    Settings::far().fit_options()
}

/// The case `model/variant`.
pub fn case(model: &str, variant: &str) -> Case {
    cases()
        .into_iter()
        .find(|c| c.model == model && c.variant == variant)
        .unwrap_or_else(|| panic!("no case {model}/{variant}"))
}

pub fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A base model and one of its variants.
#[derive(Debug, Clone)]
pub struct Case {
    pub model: String,
    pub variant: String,
    pub base: PathBuf,
    pub target: PathBuf,
}

fn scad_in(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .map(|r| r.filter_map(|e| e.ok().map(|e| e.path())).collect())
        .unwrap_or_default();
    v.retain(|p| p.extension().is_some_and(|x| x == "scad"));
    v.sort();
    v
}

/// Every (model, variant): variants from `examples/variations/<model>/` where they exist,
/// else from `tests/fixtures/variants/<model>/`.
pub fn cases() -> Vec<Case> {
    let root = repo();
    let mut out = Vec::new();
    let mut models: Vec<(String, PathBuf)> = Vec::new();
    for p in scad_in(&root.join("examples")) {
        models.push((p.file_stem().unwrap().to_string_lossy().into_owned(), p));
    }
    for p in scad_in(&root.join("examples/paper")) {
        models.push((
            format!("paper_{}", p.file_stem().unwrap().to_string_lossy()),
            p,
        ));
    }
    for (name, base) in models {
        let mut variants = scad_in(&root.join("examples/variations").join(&name));
        if variants.is_empty() {
            variants = scad_in(&root.join("tests/fixtures/variants").join(&name));
        }
        for v in variants {
            out.push(Case {
                model: name.clone(),
                variant: v.file_stem().unwrap().to_string_lossy().into_owned(),
                base: base.clone(),
                target: v,
            });
        }
    }
    out
}

pub fn load(path: &Path) -> reparamc::ir::Model {
    let mut sources = reparamc::front::source::SourceMap::new();
    reparamc::load_model(&mut sources, path)
        .unwrap_or_else(|d| panic!("{}: {}", path.display(), d.message))
        .model
}

/// The numbers of the variant at `target` as slot values of the base's program, read as
/// `--vary` reads a variation (a literal one file writes `-20` and the other `15` is the
/// slot at 20 and at -15), or `None` when the variant is not the base's program with
/// other numbers. Slots matched by name or index would compare `20` with `15` there.
pub fn truth_in_base(base: &Path, target: &Path) -> Option<Vec<f64>> {
    let mut sources = reparamc::front::source::SourceMap::new();
    let (parsed, evaluated) = reparamc::load_model_parsed(&mut sources, base).ok()?;
    reparamc::variation::load_variation(&mut sources, parsed.main, &evaluated.model, target)
        .ok()
        .map(|v| v.values)
}

/// The model at `path` written with slot values `x` and evaluated again (what `fit -o`
/// writes).
pub fn fitted_model(path: &Path, base: &reparamc::ir::Model, x: &[f64]) -> reparamc::ir::Model {
    let mut sources = reparamc::front::source::SourceMap::new();
    let (loaded, _) = reparamc::load_model_parsed(&mut sources, path).unwrap();
    let text = sources.text(loaded.main).to_string();
    let written = reparamc::back::rewrite::with_slot_values(&text, loaded.main, &base.slots, x);
    let mut s2 = reparamc::front::source::SourceMap::new();
    reparamc::load_model_text(&mut s2, path, written.as_bytes())
        .unwrap_or_else(|d| panic!("{}: fitted model: {}", path.display(), d.message))
        .model
}

/// Result of one case.
#[derive(Debug, Clone)]
pub struct Outcome {
    pub case: Case,
    pub iou_start: f64,
    pub iou: f64,
    pub loss_start: f64,
    pub loss_end: f64,
    pub seconds: f64,
    pub steps: usize,
}

fn union_bounds(a: ([f64; 3], [f64; 3]), b: Option<([f64; 3], [f64; 3])>) -> ([f64; 3], [f64; 3]) {
    match b {
        None => a,
        Some(b) => (
            std::array::from_fn(|i| a.0[i].min(b.0[i])),
            std::array::from_fn(|i| a.1[i].max(b.1[i])),
        ),
    }
}

/// The five cameras a case is seen from, framing the variant alone, as pictures of it
/// would (`FRAME_UNION`: the base and the variant together, as the table did until
/// 2026-12-01; a variant much smaller than the base is then seen small).
pub fn case_cameras(
    base: &reparamc::ir::Model,
    target: &reparamc::ir::Model,
    size: u32,
    views: usize,
) -> Vec<Camera> {
    // Framed on the target alone, a base that is much larger reaches out of the pictures
    // and parts out of every picture are lost unless the fit sees a border around them
    // (`table_options().border`).
    let (lo, hi) = if std::env::var("FRAME_UNION").is_ok() {
        union_bounds(base.bounds().unwrap(), target.bounds())
    } else {
        target.bounds().unwrap()
    };
    default_views(lo, hi, views, size, size).unwrap()
}

/// Renders the targets with OpenSCAD, fits, and scores the fit.
pub fn run_case(
    case: &Case,
    opts: &FitOptions,
    size: u32,
    views: usize,
    backend: &mut dyn Backend,
) -> Outcome {
    let target = load(&case.target);
    // `FROM_TRUTH`: start at the answer, to see whether the fit stays there.
    let base_path = if std::env::var("FROM_TRUTH").is_ok() {
        &case.target
    } else {
        &case.base
    };
    let base = load(base_path);
    if base.slots.len() != target.slots.len() {
        eprintln!(
            "{}: variant has other slots ({} vs {})",
            case.target.display(),
            target.slots.len(),
            base.slots.len()
        );
    }
    let cams = case_cameras(&base, &target, size, views);
    // `SUPERSAMPLE=k` (experiments): targets rendered at 2^k times the size and pooled, so
    // edges are antialiased as in photographs and generated pictures.
    let ss: u32 = std::env::var("SUPERSAMPLE")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(0);
    let pictures: Vec<_> = cams
        .iter()
        .map(|c| {
            let mut big = c.clone();
            big.width <<= ss;
            big.height <<= ss;
            openscad::render(&case.target, &big, &OpenScadRender::default())
                .unwrap_or_else(|e| panic!("{e}"))
        })
        .collect();
    let targets: Vec<Target> = Target::set_from_rgb(&pictures)
        .into_iter()
        .map(|mut t| {
            for _ in 0..ss {
                t = t.pooled();
            }
            t
        })
        .collect();
    let problem = Parametric::new(&base);
    let warm = std::env::var("WARM")
        .ok()
        .map_or(opts.rounds / 2, |w| w.parse().unwrap());
    let stages = match std::env::var("SCALE")
        .ok()
        .and_then(|v| v.parse::<usize>().ok())
    {
        Some(scale) => reparamc::fit::staged_with(
            &base,
            scale,
            warm.saturating_sub(scale),
            opts.rounds - warm.min(opts.rounds),
        ),
        None => reparamc::fit::staged(&base, opts.rounds, warm),
    };
    let t0 = Instant::now();
    let result = fit(
        &problem,
        &cams,
        &targets,
        &stages,
        backend,
        opts,
        &mut |_| {},
    )
    .unwrap_or_else(|e| panic!("{}: {e}", case.target.display()));
    let seconds = t0.elapsed().as_secs_f64();
    if std::env::var("TRUTH").is_ok() {
        // The loss at the true answer, for comparison with the fitted one.
        // And both with hard edges (the starting loss of a one-step fit from there).
        let backend = &mut *backend;
        let mut loss_at = |p: Parametric, sigma: f64| -> f64 {
            let t_opts = FitOptions {
                rounds: 1,
                iterations: 1,
                proportions: false,
                polish: 0,
                refine: 0,
                damped_rerun: None,
                sigma: (sigma, sigma),
                ..opts.clone()
            };
            let r = fit(
                &p,
                &cams,
                &targets,
                &[reparamc::fit::Stage::slots(1)],
                &mut *backend,
                &t_opts,
                &mut |_| {},
            )
            .unwrap();
            r.start_loss.iter().sum::<f64>()
        };
        let mut at_fit = Parametric::new(&base);
        at_fit.x0 = result.x.clone();
        eprintln!(
            "  loss at the truth {:.5}, at the fit {:.5}; hard edges: {:.5}, {:.5}",
            loss_at(Parametric::new(&target), opts.sigma.1),
            result.end_loss.iter().sum::<f64>(),
            loss_at(Parametric::new(&target), reparamc::fit::HARD_SIGMA),
            loss_at(at_fit, reparamc::fit::HARD_SIGMA),
        );
    }
    let truth = truth_in_base(base_path, &case.target);
    if let Ok(v) = std::env::var("SLOTS") {
        // `SLOTS=d`: the slots that ended more than d (default 0.3) from the truth (in the
        // base's terms; matched by name where the variant has other slots).
        let off: f64 = v.parse().unwrap_or(0.3);
        for (i, sl) in base.slots.iter().enumerate() {
            let by_name = || target.slots.iter().find(|t| t.name == sl.name);
            let Some(t) = truth
                .as_ref()
                .map(|t| t[i])
                .or_else(|| by_name().map(|t| t.value))
            else {
                continue;
            };
            if (result.x[i] - t).abs() > off {
                eprintln!(
                    "  {:24} base {:8.2} fit {:8.2} target {:8.2}",
                    sl.name, sl.value, result.x[i], t
                );
            }
        }
    }
    if std::env::var("TRACE").is_ok() {
        for st in result.curve.iter().step_by(10) {
            eprintln!(
                "  round {} it {} loss {:.5} sigma {:.2}",
                st.round, st.iteration, st.loss, st.sigma
            );
        }
    }
    let iou_of = |x: &[f64]| {
        let fitted = fitted_model(base_path, &base, x);
        reparamc::geom::iou((&fitted.parts, &fitted.csg), (&target.parts, &target.csg))
    };
    let iou = iou_of(&result.x);
    if let (true, Some(truth)) = (std::env::var("BLAME").is_ok(), &truth) {
        // Which slots cost the most IoU: each set to its true value alone.
        let mut gains: Vec<(f64, usize)> = (0..base.slots.len())
            .filter(|&i| (result.x[i] - truth[i]).abs() > 1e-9)
            .map(|i| {
                let mut x = result.x.clone();
                x[i] = truth[i];
                (iou_of(&x) - iou, i)
            })
            .collect();
        gains.sort_by(|a, b| b.0.total_cmp(&a.0));
        // And the IoU with the first k of them all set to the truth.
        let mut x = result.x.clone();
        for (g, i) in gains.iter().take(8) {
            x[*i] = truth[*i];
            eprintln!(
                "  blame {:24} fit {:8.2} target {:8.2} IoU +{g:.3} (with the above {:.3})",
                base.slots[*i].name,
                result.x[*i],
                truth[*i],
                iou_of(&x)
            );
        }
    }
    if std::env::var("MISMATCH").is_ok() {
        // Pixels whose hard coverage disagrees with the target's mask, per view.
        let tp = Parametric::new(&target);
        let count = |p: &Parametric, x: &[f64], label: &str| -> Vec<usize> {
            let scene = p.scene(x);
            cams.iter()
                .zip(&targets)
                .map(|(c, t)| {
                    let v = reparamc::render::soft::prepare_view(&scene, c, None);
                    let (_, hard, _) = reparamc::render::soft::render_view(
                        &scene,
                        &v,
                        None,
                        reparamc::render::scene::DEFAULT_SHADE,
                        false,
                    );
                    if let Ok(dir) = std::env::var("GALLERY") {
                        // Red: ours only; blue: the target's only (four times the size).
                        let mut img =
                            reparamc::render::image::Rgb::new(t.width, t.height, [1.0; 3]);
                        for (px, (a, b)) in img.data.iter_mut().zip(hard.mask().zip(&t.m)) {
                            *px = match (a, *b > 0.5) {
                                (true, true) => [0.8; 3],
                                (true, false) => [1.0, 0.0, 0.0],
                                (false, true) => [0.0, 0.0, 1.0],
                                _ => [1.0; 3],
                            };
                        }
                        let path = PathBuf::from(dir).join(format!(
                            "{}_{}_{}_{label}.png",
                            case.model, case.variant, c.name
                        ));
                        let big = img.resize(4 * t.width, 4 * t.height);
                        std::fs::write(path, big.encode_png()).unwrap();
                    }
                    hard.mask()
                        .zip(&t.m)
                        .filter(|(a, b)| *a != (**b > 0.5))
                        .count()
                })
                .collect()
        };
        eprintln!(
            "  mask mismatch at the fit {:?}, at the truth {:?}",
            count(&problem, &result.x, "fit"),
            count(&tp, &tp.x0, "truth")
        );
    }
    if let Ok(dir) = std::env::var("GALLERY") {
        let mut imgs = Vec::new();
        for (c, t) in cams.iter().zip(&targets) {
            for x in [&problem.x0, &result.x] {
                let scene = problem.scene(x);
                let v = reparamc::render::soft::prepare_view(&scene, c, None);
                let (s, _, _) = reparamc::render::soft::render_view(
                    &scene,
                    &v,
                    Some(0.4),
                    reparamc::render::scene::DEFAULT_SHADE,
                    false,
                );
                imgs.push(reparamc::render::image::picture(&s));
            }
            let tm = reparamc::render::soft::SoftImage {
                width: t.width,
                height: t.height,
                m: t.m.clone(),
                s: t.s.clone(),
            };
            imgs.insert(imgs.len() - 1, reparamc::render::image::picture(&tm));
        }
        let g = reparamc::render::image::grid(&imgs, 3);
        let path = PathBuf::from(dir).join(format!("{}_{}.png", case.model, case.variant));
        std::fs::write(path, g.encode_png()).unwrap();
    }
    Outcome {
        case: case.clone(),
        iou_start: iou_of(&problem.x0),
        iou,
        loss_start: result.start_loss.iter().sum(),
        loss_end: result.end_loss.iter().sum(),
        seconds,
        steps: result.curve.len(),
    }
}

pub fn cpu() -> CpuBackend {
    CpuBackend::new()
}
