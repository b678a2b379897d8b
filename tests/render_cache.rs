//! The renderer's shortcuts give what a whole render gives, to the bit: `render_soft` (the
//! soft channels and gradient entries without the hard surface), `SoftCache` (each
//! view's last render, drawn again only where parts changed) and the CPU backend's
//! `Backend::soft`, which answers from that cache.

use reparamc::render::camera::default_views;
use reparamc::render::scene::{BOX_FILTER, DEFAULT_SHADE, PartGeom, Scene};
use reparamc::render::soft::{SoftCache, ViewPrep, prepare_view, render_soft, render_view};

/// The model of `text`, loaded as the command loads a file.
fn model(name: &str, text: &str) -> reparamc::ir::Model {
    let mut sources = reparamc::front::source::SourceMap::new();
    reparamc::load_model_text(&mut sources, std::path::Path::new(name), text.as_bytes())
        .unwrap_or_else(|d| panic!("{name}: {}", d.message))
        .model
}

/// `scene` with part `part`'s parameter `k` moved by `by`.
fn move_part(scene: &mut Scene, part: usize, k: usize, by: f64) {
    let g = &scene.parts[part];
    let mut theta = g.theta;
    theta[k] += by;
    scene.parts[part] = PartGeom::from_theta(g.kind, g.centered, theta);
}

#[test]
fn the_soft_render_is_the_full_render_without_the_surface() {
    // A box with a bore through it (a split difference) on a cylinder: plain and boolean
    // items, hulls and curved edges.
    let m = model(
        "bored.scad",
        "difference() { cube([20, 10, 6]); translate([10, 5, -1]) cylinder(h = 8, r = 3); }\n\
         translate([5, 5, 6]) cylinder(h = 12, r1 = 4, r2 = 2);\n",
    );
    let scene = Scene::from_parts(&m.parts, &m.csg);
    let (lo, hi) = scene.bounds().unwrap();
    for camera in default_views(lo, hi, 3, 48, 40).unwrap() {
        for sigma in [Some(0.5), None] {
            let prep = prepare_view(&scene, &camera, sigma);
            let (soft, _, entries) = render_view(&scene, &prep, sigma, DEFAULT_SHADE, true);
            let only = render_soft(&scene, &prep, sigma, DEFAULT_SHADE, true);
            assert!(only.0.m.iter().filter(|&&v| v > 0.5).count() > 100);
            assert_eq!((soft, entries), only, "{} at {sigma:?}", camera.name);
        }
    }
}

#[test]
fn a_scene_rendered_again_where_it_changed_equals_a_whole_render() {
    // A table of plain boxes, a bored block (a difference) and a cone; each step moves one
    // part, or several, or none.
    let m = model(
        "table.scad",
        "cube([40, 20, 2]);\n\
         translate([1, 1, -15]) cube([2, 2, 15]);\n\
         translate([37, 17, -15]) cube([2, 2, 15]);\n\
         difference() { translate([50, 0, -15]) cube([12, 12, 12]); translate([56, 6, -16]) cylinder(h = 14, r = 3); }\n\
         translate([20, 10, 2]) cylinder(h = 8, r1 = 3, r2 = 1);\n",
    );
    let base = Scene::from_parts(&m.parts, &m.csg);
    let (lo, hi) = base.bounds().unwrap();
    let cameras = default_views(lo, hi, 3, 64, 48).unwrap();
    let shades = vec![DEFAULT_SHADE; cameras.len()];
    let mut cache = SoftCache::default();
    let mut scene = base.clone();
    let moves: [&[(usize, usize, f64)]; 5] = [
        &[],
        &[(1, 14, 1.5)],
        &[(1, 14, -0.7), (4, 12, 2.0)],
        &[],
        &[(3, 3, 4.0)],
    ];
    for sigma in [Some(BOX_FILTER), Some(0.5), None] {
        for step in moves {
            for &(part, k, by) in step {
                move_part(&mut scene, part, k, by);
            }
            let views: Vec<ViewPrep> = cameras
                .iter()
                .map(|c| prepare_view(&scene, c, sigma))
                .collect();
            let cached = cache.render(&scene, &views, sigma, &shades);
            for (v, image) in views.iter().zip(&cached) {
                let whole = render_soft(&scene, v, sigma, DEFAULT_SHADE, false).0;
                assert_eq!(&whole, *image, "{step:?} at {sigma:?}");
                assert!(whole.m.iter().filter(|&&x| x > 0.5).count() > 50);
            }
        }
    }
}

#[test]
fn the_cpu_backends_soft_pictures_are_its_whole_renders() {
    // `Backend::soft` (the uncertainty's renders) answers from the backend's cache, shared
    // with its losses: after single moves, with a loss between them, each picture equals
    // the soft half of a whole render.
    use reparamc::fit::loss::{ImageLoss, LossSpec, Target};
    use reparamc::render::{Backend, CpuBackend};
    let m = model(
        "table.scad",
        "cube([40, 20, 2]);\n\
         translate([1, 1, -15]) cube([2, 2, 15]);\n\
         translate([37, 17, -15]) cube([2, 2, 15]);\n",
    );
    let mut scene = Scene::from_parts(&m.parts, &m.csg);
    let (lo, hi) = scene.bounds().unwrap();
    let cameras = default_views(lo, hi, 2, 64, 48).unwrap();
    let shades = vec![DEFAULT_SHADE; cameras.len()];
    let mut backend = CpuBackend::new();
    let spec = LossSpec::default();
    for sigma in [0.5, BOX_FILTER] {
        for (part, by) in [(0, 0.0), (1, 1.5), (1, -0.7), (2, 2.0)] {
            move_part(&mut scene, part, 14, by);
            let views: Vec<ViewPrep> = cameras
                .iter()
                .map(|c| prepare_view(&scene, c, Some(sigma)))
                .collect();
            let soft = backend.soft(&scene, &views, Some(sigma), &shades);
            let whole = backend.render(&scene, &views, Some(sigma), &shades);
            for (s, (w, _)) in soft.iter().zip(&whole) {
                assert_eq!(s, w, "part {part} by {by} at {sigma}");
                assert!(s.m.iter().filter(|&&v| v > 0.5).count() > 20);
            }
            // A loss in between leaves the cache at this scene and softness.
            let targets: Vec<Target> = whole.iter().map(|(s, _)| Target::from_soft(s)).collect();
            let f = ImageLoss {
                targets: &targets,
                spec: &spec,
            };
            let v = backend.evaluate(&scene, &views, sigma, &shades, &f, false);
            assert!(v.per_view.iter().all(|&l| l == 0.0), "{:?}", v.per_view);
        }
    }
}
