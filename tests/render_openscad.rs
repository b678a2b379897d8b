//! Our cameras reproduce OpenSCAD's: every example rendered by `openscad` and by us from
//! the same cameras (gimbal with roll, eye/center, orthographic) gives the same foreground.

use glam::DVec3;
use reparamc::fit::loss::Target;
use reparamc::render::camera::{Camera, Projection};
use reparamc::render::openscad::{self, OpenScadRender};
use reparamc::render::scene::{DEFAULT_SHADE, Scene};
use reparamc::render::soft::{prepare_view, render_view};
use reparamc::render::{cpu, scene};
use std::path::{Path, PathBuf};

fn examples() -> Vec<PathBuf> {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let mut v = Vec::new();
    for dir in ["examples", "examples/paper"] {
        for e in std::fs::read_dir(root.join(dir)).unwrap() {
            let p = e.unwrap().path();
            if p.extension().is_some_and(|x| x == "scad") {
                v.push(p);
            }
        }
    }
    v.sort();
    v
}

fn load(path: &Path) -> reparamc::ir::Model {
    let mut sources = reparamc::front::source::SourceMap::new();
    reparamc::load_model(&mut sources, path)
        .unwrap_or_else(|d| panic!("{}: {}", path.display(), d.message))
        .model
}

fn iou(a: &[bool], b: &[bool]) -> f64 {
    let i = a.iter().zip(b).filter(|(x, y)| **x && **y).count();
    let u = a.iter().zip(b).filter(|(x, y)| **x || **y).count();
    if u == 0 { 1.0 } else { i as f64 / u as f64 }
}

/// Three cameras around the model's bounds.
fn cameras(lo: [f64; 3], hi: [f64; 3]) -> Vec<Camera> {
    let (lo, hi) = (DVec3::from(lo), DVec3::from(hi));
    let c = (lo + hi) * 0.5;
    let r = (hi - lo).length() / 2.0;
    let dist = r / (11.25f64).to_radians().sin() * 1.15;
    let g = Camera::from_openscad(
        "gimbal_roll",
        &[c[0], c[1], c[2], 60.0, 12.0, 30.0, dist],
        Projection::Perspective,
        160,
        120,
    )
    .unwrap();
    let eye = c + DVec3::new(0.6 * dist, -0.7 * dist, 0.4 * dist);
    let e = Camera::from_openscad(
        "eye",
        &[eye[0], eye[1], eye[2], c[0], c[1], c[2]],
        Projection::Perspective,
        128,
        128,
    )
    .unwrap();
    let o = Camera::from_openscad(
        "ortho",
        &[c[0], c[1], c[2], 70.0, 0.0, 200.0, dist],
        Projection::Orthographic,
        140,
        120,
    )
    .unwrap();
    vec![g, e, o]
}

#[test]
fn masks_match_openscad() {
    if !openscad::available() {
        eprintln!("skipped: openscad or xvfb-run missing (run scripts/setup)");
        return;
    }
    let mut worst = (1.0f64, String::new());
    for path in examples() {
        let model = load(&path);
        let (lo, hi) = model.bounds().unwrap();
        let scene = Scene::from_parts(&model.parts, &model.csg);
        for cam in cameras(lo, hi) {
            let theirs = openscad::render(&path, &cam, &OpenScadRender::default()).unwrap();
            let t = Target::from_rgb(&theirs);
            let their_mask: Vec<bool> = t.m.iter().map(|&m| m > 0.5).collect();
            let exact = cpu::render_hard(&model.parts, &model.csg, &cam);
            let exact_mask: Vec<bool> = exact.mask().collect();
            let prep = prepare_view(&scene, &cam, None);
            let (_, hard, _) = render_view(&scene, &prep, None, DEFAULT_SHADE, false);
            let kernel_mask: Vec<bool> = hard.mask().collect();
            let a = iou(&their_mask, &exact_mask);
            let b = iou(&exact_mask, &kernel_mask);
            let name = format!(
                "{} {}",
                path.file_name().unwrap().to_string_lossy(),
                cam.name
            );
            eprintln!("{name:40} openscad vs exact {a:.4}   exact vs kernel {b:.4}");
            if a < worst.0 {
                worst = (a, name.clone());
            }
            assert!(a >= 0.98, "{name}: mask IoU with OpenSCAD {a:.4} < 0.98");
            assert!(b >= 0.995, "{name}: kernel vs exact {b:.4}");
        }
    }
    let _ = scene::NTHETA;
    eprintln!("worst: {:.4} ({})", worst.0, worst.1);
}
