//! Pictures read as coverage, measured on pictures the project did not draw: generated
//! families rendered by OpenSCAD. Its own pictures have hard edges, and read as exactly the
//! pixels the object shows; the same view drawn at four times the size and pooled is
//! antialiased as photographs and generated pictures are, and reads close to the true share
//! of each pixel the object covers (the pooled hard mask). Every fit's target goes through
//! this reading, so an error here is an error in every fit (a thin board read thicker, a
//! pale face read as half background).

mod common;

use reparamc::families::Family;
use reparamc::fit::loss::Target;
use reparamc::front::source::SourceMap;
use reparamc::render::camera::{Camera, default_views};
use reparamc::render::image::Rgb;
use reparamc::render::openscad::{self, OpenScadRender};
use reparamc::render::scene::Scene;
use std::path::{Path, PathBuf};

/// Seeds of the families looked at (each a few parts to a few dozen).
const SEEDS: std::ops::Range<u64> = 0..4;

/// Pixels per side of the pictures read.
const SIZE: u32 = 96;

/// Supersampling of the antialiased pictures, per side.
const SS: u32 = 4;

/// A family's first held-out variant, written to a scratch folder, and two of its views.
fn variant(seed: u64) -> Option<(PathBuf, Vec<Camera>)> {
    let family = Family::generate(seed, 0)?;
    let program = family.program(family.style);
    let far = &family.held_out[0];
    let dir = std::env::temp_dir().join(format!(
        "reparamc-coverage-reading-{}-{seed}",
        std::process::id()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("variant.scad");
    std::fs::write(
        &path,
        program.render(&program.values(&far.theta, &far.dropped)),
    )
    .unwrap();
    let model = reparamc::load_model(&mut SourceMap::new(), &path)
        .unwrap_or_else(|d| panic!("{}", d.message))
        .model;
    let (lo, hi) = Scene::from_parts(&model.parts, &model.csg).bounds()?;
    Some((path, default_views(lo, hi, 2, SIZE, SIZE).unwrap()))
}

/// The picture's pixels whose colour differs from the background beyond any shading
/// noise: what OpenSCAD drew the object on.
fn drawn(img: &Rgb, background: [f32; 3]) -> Vec<f32> {
    img.data
        .iter()
        .map(|c| {
            let d = (0..3)
                .map(|k| (c[k] - background[k]).abs())
                .fold(0.0, f32::max);
            if d >= 0.02 { 1.0 } else { 0.0 }
        })
        .collect()
}

/// `mask` (of a picture `SS` times the size) pooled to the true coverage of each pixel.
fn pooled(mask: &[f32], width: u32) -> Vec<f32> {
    let (big, small) = (width as usize, (width / SS) as usize);
    let mut out = vec![0.0f32; small * small];
    for (k, v) in mask.iter().enumerate() {
        out[(k / big / SS as usize) * small + (k % big) / SS as usize] += v / (SS * SS) as f32;
    }
    out
}

fn render(path: &Path, cam: &Camera, scale: u32) -> Rgb {
    let mut c = cam.clone();
    c.width *= scale;
    c.height *= scale;
    openscad::render(path, &c, &OpenScadRender::default()).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn openscad_pictures_read_as_their_pixels_and_pooled_ones_near_their_coverage() {
    if !openscad::available() {
        eprintln!("skipped: openscad missing (run scripts/setup)");
        return;
    }
    let (mut wrong_hard, mut drawn_px) = (0usize, 0usize);
    let (mut err_aa, mut err_naive, mut partial) = (0.0f64, 0.0f64, 0usize);
    for seed in SEEDS {
        let Some((path, cams)) = variant(seed) else {
            continue;
        };
        for cam in &cams {
            let hard = render(&path, cam, 1);
            let t = Target::from_rgb(&hard);
            let want = drawn(&hard, t.background);
            drawn_px += want.iter().filter(|&&v| v > 0.0).count();
            wrong_hard += t.m.iter().zip(&want).filter(|(a, b)| a != b).count();

            let big = render(&path, cam, SS);
            let truth = pooled(&drawn(&big, t.background), big.width);
            let small = big.resize(SIZE, SIZE);
            let read = Target::from_rgb(&small);
            // The naive reading: every pixel that differs from the background is object.
            let naive = drawn(&small, read.background);
            for i in 0..truth.len() {
                if truth[i] > 0.0 && truth[i] < 1.0 {
                    partial += 1;
                }
                err_aa += (read.m[i] - truth[i]).abs() as f64;
                err_naive += (naive[i] - truth[i]).abs() as f64;
            }
        }
        let _ = std::fs::remove_dir_all(path.parent().unwrap());
    }
    assert!(drawn_px > 0 && partial > 0, "no family drawn");
    eprintln!(
        "hard: {wrong_hard} of {drawn_px} pixels misread; antialiased: error {:.3} per \
         partly covered pixel (thresholding: {:.3})",
        err_aa / partial as f64,
        err_naive / partial as f64
    );
    // OpenSCAD's pictures have no mixed pixels: every pixel it drew on is object, whole.
    assert_eq!(wrong_hard, 0, "of {drawn_px} pixels drawn");
    // Antialiased: well under the error of reading every coloured pixel as object, which
    // makes every part half a pixel fatter on each side.
    assert!(
        err_aa <= 0.25 * err_naive,
        "unmixing {err_aa:.1} against thresholding {err_naive:.1} ({partial} partial pixels)"
    );
}
