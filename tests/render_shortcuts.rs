//! The renderer's pixel shortcuts change nothing: covered tiles (one box face seen whole),
//! empty tiles, a pixel's opaque front and the items wholly behind it give, to the bit,
//! what the whole kernel gives visiting every item at every pixel
//! (`render_view_exhaustive`): soft channels, hard surface and gradient entries.
//!
//! Scenes: generated families (boxes, cylinders, cones, differences, parts overlapping on
//! purpose) and the chair, each item of its own brightness; cameras around each
//! (perspective and orthographic); the box filter, soft edges narrow and wide, and hard
//! edges.

use reparamc::families::Family;
use reparamc::families::style::Style;
use reparamc::render::camera::{Camera, Projection, default_views};
use reparamc::render::scene::{BOX_FILTER, DEFAULT_SHADE, Scene};
use reparamc::render::soft::{prepare_view, render_soft, render_view, render_view_exhaustive};

fn scene_of(name: &str, text: &str) -> Scene {
    let mut sources = reparamc::front::source::SourceMap::new();
    let model =
        reparamc::load_model_text(&mut sources, std::path::Path::new(name), text.as_bytes())
            .unwrap_or_else(|d| panic!("{name}: {}", d.message))
            .model;
    // Items of different brightness, as a fit's per-item albedo makes them.
    let scene = Scene::from_parts(&model.parts, &model.csg);
    let albedo: Vec<f64> = (0..scene.items.len())
        .map(|i| 0.55 + 0.15 * (i % 4) as f64)
        .collect();
    scene.with_albedo(&albedo)
}

/// Five views around the scene at `size`², the last two orthographic.
fn cameras(scene: &Scene, size: u32) -> Vec<Camera> {
    let (lo, hi) = scene.bounds().expect("the scene draws something");
    let mut cams = default_views(lo, hi, 5, size, size).expect("views frame the scene");
    for c in cams.iter_mut().skip(3) {
        c.projection = Projection::Orthographic;
    }
    cams
}

/// Checks every view and edge softness of `scene`; returns how many pixels the views
/// cover in all (so a test can tell it looked at something).
fn check(name: &str, scene: &Scene, size: u32) -> usize {
    let mut covered = 0;
    for camera in cameras(scene, size) {
        for sigma in [Some(BOX_FILTER), Some(0.5), Some(2.0), None] {
            let prep = prepare_view(scene, &camera, sigma);
            let fast = render_view(scene, &prep, sigma, DEFAULT_SHADE, true);
            let slow = render_view_exhaustive(scene, &prep, sigma, DEFAULT_SHADE, true);
            let at = format!("{name}, {} view, edges {sigma:?}", camera.name);
            same_pixels("coverage", &fast.0.m, &slow.0.m, size, &at);
            same_pixels("shade", &fast.0.s, &slow.0.s, size, &at);
            assert!(fast.1 == slow.1, "hard surface differs: {at}");
            assert!(fast.2 == slow.2, "gradient entries differ: {at}");
            let soft = render_soft(scene, &prep, sigma, DEFAULT_SHADE, true);
            assert!(
                soft == (fast.0.clone(), fast.2),
                "soft render differs: {at}"
            );
            covered += fast.0.m.iter().filter(|&&m| m > 0.5).count();
        }
    }
    covered
}

/// Fails naming how many pixels of a channel differ and the first of them.
fn same_pixels(channel: &str, fast: &[f32], slow: &[f32], size: u32, at: &str) {
    let differ: Vec<usize> = (0..fast.len())
        .filter(|&i| fast[i].to_bits() != slow[i].to_bits())
        .collect();
    if let Some(&i) = differ.first() {
        let (x, y) = (i as u32 % size, i as u32 / size);
        panic!(
            "{channel}: {} pixels differ ({at}); first at ({x}, {y}): {} with shortcuts, {} without",
            differ.len(),
            fast[i],
            slow[i]
        );
    }
}

#[test]
fn generated_families_render_the_same_with_and_without_shortcuts() {
    let mut looked = 0;
    for seed in 0..12u64 {
        let Some(family) = Family::generate(seed, 3) else {
            continue;
        };
        let style = Style::ALL[seed as usize % Style::ALL.len()];
        let scene = scene_of(&format!("family{seed}.scad"), &family.input_text(style));
        assert!(
            check(&format!("family {seed}"), &scene, 64) > 1000,
            "family {seed}"
        );
        looked += 1;
    }
    assert!(looked >= 10, "only {looked} families generated");
}

#[test]
fn the_chair_renders_the_same_with_and_without_shortcuts() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(root.join("examples/chair.scad")).unwrap();
    let scene = scene_of("chair.scad", &text);
    assert!(check("chair", &scene, 96) > 10_000);
}
