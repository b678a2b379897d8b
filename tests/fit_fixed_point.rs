//! The truth is a fixed point of the fit: a model fitted, with the command's default
//! settings, to its own renders (drawn by `reparamc render`, antialiased, read back from
//! PNG) comes back with every face within `FIXED_POINT_PIXELS` of where it was. On
//! examples and on generated families.

use reparamc::command::fit::Settings;
use reparamc::fit::Parametric;
use reparamc::fit::targets::load_target_dir;
use reparamc::front::source::SourceMap;
use reparamc::tolerance::FIXED_POINT_PIXELS;
use std::path::{Path, PathBuf};

#[path = "fit_support/views.rs"]
mod views;

/// Image side of the targets.
const SIZE: u32 = 64;

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
    let fitted = views::fit_cpu(model, &views, Settings::default());
    let loaded = reparamc::load_model(&mut SourceMap::new(), model).unwrap();
    let p = Parametric::new(&loaded.model);
    let x: Vec<f64> = fitted.report.slots.iter().map(|s| s.after).collect();
    let pixel = load_target_dir(&views)
        .unwrap()
        .cameras
        .iter()
        .map(|c| c.pixel_size())
        .fold(f64::INFINITY, f64::min);
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
    let _ = std::fs::remove_dir_all(&dir);
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
