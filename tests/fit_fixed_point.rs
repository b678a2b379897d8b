//! The truth is a fixed point of the fit: a model fitted, with the command's default
//! settings, to its own renders (drawn by `reparamc render`, antialiased, read back from
//! PNG) comes back with every face within `FIXED_POINT_PIXELS` of where it was. On
//! examples and on generated families; and on OpenSCAD's own pictures, drawn with hard
//! edges (each pixel sampled at one point), which the fit compares with hard edges. And with steps bounded in pixels (`--reach`) it
//! attracts: started a few pixels off, in a random direction of every number at once, the
//! fit comes back to it (unbounded, Adam's steps can leave it a pixel short).

use reparamc::command::fit::Settings;
use reparamc::fit::Parametric;
use reparamc::fit::targets::load_target_dir;
use reparamc::front::source::SourceMap;
use reparamc::render::openscad::{self, OpenScadRender};
use reparamc::tolerance::FIXED_POINT_PIXELS;
use std::path::{Path, PathBuf};

#[path = "fit_support/views.rs"]
mod views;

/// Image side of the targets.
const SIZE: u32 = 64;

/// Image side of OpenSCAD's targets: enough for the desk's thin boards to show.
const OPENSCAD_SIZE: u32 = 128;

fn scratch(name: &str) -> PathBuf {
    views::scratch("fixed", name)
}

/// Fits `model` to its own renders with the default settings; the largest move of a face,
/// in pixels of the finest view.
fn face_drift(model: &Path, name: &str) -> f64 {
    let dir = scratch(name);
    let views = dir.join("views");
    std::fs::create_dir_all(&views).unwrap();
    views::render_views(model, &views, SIZE);
    let drift = face_distance(model, model, &views, Settings::default(), name);
    let _ = std::fs::remove_dir_all(&dir);
    drift
}

/// The finest view's pixel in the target folder `views`, world units.
fn finest_pixel(views: &Path) -> f64 {
    load_target_dir(views)
        .unwrap()
        .cameras
        .iter()
        .map(|c| c.pixel_size())
        .fold(f64::INFINITY, f64::min)
}

/// Fits `start` (the program of `model` with other numbers) to `model`'s renders in
/// `views` with `settings`; how far the fitted faces are from `model`'s, at most, in
/// pixels of the finest view.
fn face_distance(start: &Path, model: &Path, views: &Path, settings: Settings, name: &str) -> f64 {
    let fitted = views::fit_cpu(start, views, settings);
    let loaded = reparamc::load_model(&mut SourceMap::new(), model).unwrap();
    let p = Parametric::new(&loaded.model);
    let x: Vec<f64> = fitted.report.slots.iter().map(|s| s.after).collect();
    let pixel = finest_pixel(views);
    let mut worst = 0.0f64;
    for (part, faces) in loaded.model.parts.iter().zip(&p.faces) {
        for (axis, high, form) in faces {
            let moved = (form.eval(&x) - form.eval(&p.x0)).abs() / pixel;
            if moved > worst {
                eprintln!("{name}: {} face {axis}{high}: {moved:.3} px", part.name);
            }
            worst = worst.max(moved);
        }
    }
    eprintln!(
        "{name}: worst face moved {worst:.3} px, loss {} -> {}",
        fitted.start_loss(),
        fitted.end_loss()
    );
    worst
}

fn example(name: &str) {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(format!("examples/{name}.scad"));
    let worst = face_drift(&path, name);
    assert!(
        worst <= FIXED_POINT_PIXELS,
        "{name}: a face moved {worst:.3} px"
    );
}

/// Replaces every picture in `views` by OpenSCAD's render of `model` from its camera.
fn openscad_pictures(model: &Path, views: &Path) {
    let set = load_target_dir(views).unwrap();
    for (camera, file) in set.cameras.iter().zip(&set.files) {
        let img = openscad::render(model, camera, &OpenScadRender::default())
            .unwrap_or_else(|e| panic!("{e}"));
        std::fs::write(file, img.encode_png()).unwrap();
    }
}

#[test]
fn the_desk_is_a_fixed_point_of_openscad_s_pictures() {
    // Boards 2 to 3 units thick, 2 to 4 pixels here: a loss on area coverage against
    // point-sampled pictures thinned them by a third of a pixel and more.
    let name = "desk";
    let model = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(format!("examples/{name}.scad"));
    let dir = scratch("desk-openscad");
    let views = dir.join("views");
    views::render_views(&model, &views, OPENSCAD_SIZE);
    openscad_pictures(&model, &views);
    let worst = face_distance(&model, &model, &views, Settings::default(), name);
    let _ = std::fs::remove_dir_all(&dir);
    assert!(
        worst <= FIXED_POINT_PIXELS,
        "{name} from OpenSCAD's pictures: a face moved {worst:.3} px"
    );
}

#[test]
fn the_chair_is_a_fixed_point() {
    example("chair");
}

#[test]
fn the_table_is_a_fixed_point() {
    example("table");
}

#[test]
fn the_lamp_is_a_fixed_point() {
    example("lamp");
}

#[test]
fn generated_families_are_fixed_points() {
    for seed in [1u64, 2, 3] {
        let family = reparamc::families::Family::generate(seed, 0).unwrap();
        let dir = scratch(&format!("family{seed}-model"));
        let path = dir.join(format!("family{seed}.scad"));
        std::fs::write(&path, family.input_text(family.style)).unwrap();
        let worst = face_drift(&path, &format!("family{seed}"));
        assert!(
            worst <= FIXED_POINT_PIXELS,
            "family {seed}: a face moved {worst:.3} px"
        );
    }
}

/// How far off the truth the attraction test starts: its farthest face, in pixels.
const START_OFF_PIXELS: f64 = 2.0;

/// How far from the truth a fit started [`START_OFF_PIXELS`] off may end, pixels.
const RETURN_PIXELS: f64 = 0.5;

/// The reach the attraction test fits with (`--reach`), in edge softnesses.
const REACH: f64 = 0.5;

/// `model` with every number nudged by the same share, up or down at random (as a person
/// retyping it would), scaled so that the face that moves most moves `pixels` of `views`'
/// finest pixel; written beside the views.
fn nudged(model: &Path, views: &Path, pixels: f64, seed: u64) -> PathBuf {
    let mut sources = SourceMap::new();
    let (loaded, evaluated) = reparamc::load_model_parsed(&mut sources, model).unwrap();
    let truth = evaluated.model;
    let p = Parametric::new(&truth);
    let mut rng = reparamc::families::rng::Rng::new(seed);
    let dir: Vec<f64> =
        p.x0.iter()
            .map(|v| if rng.range(0.0, 1.0) < 0.5 { -v } else { *v })
            .collect();
    let at = |t: f64| -> Vec<f64> { p.x0.iter().zip(&dir).map(|(a, d)| a + t * d).collect() };
    let far = p.farthest_face_move(&p.x0, &at(1.0));
    let x = at(pixels * finest_pixel(views) / far);
    let text = sources.text(loaded.main).to_string();
    let written = reparamc::back::rewrite::with_slot_values(&text, loaded.main, &truth.slots, &x);
    let path = views.with_file_name("nudged.scad");
    std::fs::write(&path, written).unwrap();
    path
}

#[test]
fn with_bounded_steps_a_fit_started_pixels_off_comes_back() {
    for seed in [1u64, 2, 3, 10] {
        let family = reparamc::families::Family::generate(seed, 0).unwrap();
        let dir = scratch(&format!("family{seed}-nudged"));
        let model = dir.join(format!("family{seed}.scad"));
        std::fs::write(&model, family.input_text(family.style)).unwrap();
        let views = dir.join("views");
        views::render_views(&model, &views, SIZE);
        let start = nudged(&model, &views, START_OFF_PIXELS, seed);
        let settings = Settings {
            reach: REACH,
            ..Settings::default()
        };
        let name = format!("family{seed} nudged");
        let worst = face_distance(&start, &model, &views, settings, &name);
        let _ = std::fs::remove_dir_all(&dir);
        assert!(
            worst <= RETURN_PIXELS,
            "family {seed}: started {START_OFF_PIXELS} px off, a face ended {worst:.3} px off"
        );
    }
}
