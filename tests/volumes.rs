//! OpenSCAD is the oracle for volumes: each small model is rendered by the real `openscad`
//! to an ASCII STL, whose volume (divergence theorem) is compared with ours, computed from
//! our own evaluation of the same file by ray intervals.
//!
//! Box-only models must agree to 1e-9 (OpenSCAD prints 6 significant digits, so their
//! coordinates are chosen to print exactly); rotated boxes, whose corners are irrational, to
//! the STL's printing precision (~5e-7 of a coordinate, a few 1e-6 of a volume).
//! Curved models are polygonised by OpenSCAD: a regular n-gon of circumradius r has area
//! `n r² sin(2π/n) / 2`, so a prism or frustum holds `c = n sin(2π/n) / 2π` of the exact
//! volume; each case says how its exact volume maps to OpenSCAD's, and we compare with that.

mod common;

use common::{openscad_export, tempfile};
use reparamc::front::source::SourceMap;
use reparamc::geom;
use reparamc::ir::Model;
use std::f64::consts::PI;
use std::path::{Path, PathBuf};

/// What OpenSCAD's polygonised solid holds, given our exact volume.
#[derive(Clone, Copy)]
enum Expect {
    /// Polyhedral: the same volume.
    Exact,
    /// Prisms and frustums with `$fn = n`: `c(n) · V`.
    Polygons(f64),
    /// A box of volume `b` minus prisms with `$fn = n`: `b − c(n)(b − V)`.
    BoxMinusPolygons(f64, f64),
    /// A sphere of radius r with `$fn = n`: OpenSCAD's stack of rings, computed exactly.
    Sphere(f64, f64),
}

struct Case {
    name: &'static str,
    scad: &'static str,
    expect: Expect,
    /// Relative tolerance of the comparison.
    tol: f64,
}

fn cases() -> Vec<Case> {
    use Expect::*;
    vec![
        Case {
            name: "box",
            scad: "cube([10, 20, 30]);",
            expect: Exact,
            tol: 1e-9,
        },
        Case {
            name: "scaled_centred_box",
            scad: "translate([1, 2, 3]) scale([2, 0.5, 1.5]) cube(4, center = true);",
            expect: Exact,
            tol: 1e-9,
        },
        Case {
            name: "union_of_overlapping_boxes",
            scad: "union() { cube([10, 10, 10]); translate([5, 5, 5]) cube([10, 10, 10]);
                   translate([-3, 2, 1]) cube([4, 4, 4]); translate([2, 2, 2]) cube(3); }",
            expect: Exact,
            tol: 1e-9,
        },
        Case {
            name: "difference_with_holes",
            scad: "difference() { cube([20, 20, 10]); translate([5, 5, -1]) cube([4, 4, 12]);
                   translate([12, 3, 2]) cube([5, 14, 3]); translate([-1, 15, 7]) cube([30, 2, 5]); }",
            expect: Exact,
            tol: 1e-9,
        },
        Case {
            name: "intersection_of_boxes",
            scad: "intersection() { cube([10, 10, 10]); translate([5, -2, 3]) cube([10, 8, 20]);
                   translate([-1, 1, -1]) cube([8, 20, 9]); }",
            expect: Exact,
            tol: 1e-9,
        },
        Case {
            name: "mirrored_boxes",
            scad: "mirror([1, 0, 0]) cube([3, 4, 5]); translate([1, 0, 0]) mirror([0, 1, 1]) cube([2, 2, 6]);",
            expect: Exact,
            tol: 1e-9,
        },
        Case {
            name: "rotated_box",
            scad: "rotate([0, 0, 30]) cube([10, 4, 3]);",
            expect: Exact,
            tol: 2e-5,
        },
        Case {
            name: "obliquely_rotated_boxes",
            scad: "rotate([20, 35, 10]) translate([1, 2, 3]) cube([3, 5, 7]);
                   translate([20, 0, 0]) rotate([-50, 10, 75]) cube([6, 2, 4], center = true);",
            expect: Exact,
            tol: 2e-5,
        },
        Case {
            name: "cylinder_z",
            scad: "cylinder(h = 10, r = 3, $fn = 256);",
            expect: Polygons(256.0),
            tol: 2e-6,
        },
        Case {
            name: "cylinder_x",
            scad: "translate([20, 0, 0]) rotate([0, 90, 0]) cylinder(h = 8, r = 2, $fn = 256);",
            expect: Polygons(256.0),
            tol: 2e-6,
        },
        Case {
            name: "cylinder_y",
            scad: "translate([0, 20, 5]) rotate([-90, 0, 0]) cylinder(h = 6, r = 2.5, center = true, $fn = 256);",
            expect: Polygons(256.0),
            tol: 2e-6,
        },
        Case {
            name: "cone",
            scad: "cylinder(h = 10, r1 = 4, r2 = 1, $fn = 256);",
            expect: Polygons(256.0),
            tol: 2e-6,
        },
        Case {
            name: "cone_to_a_point_tilted",
            scad: "rotate([30, 20, 10]) cylinder(h = 5, r1 = 3, r2 = 0, $fn = 256);",
            expect: Polygons(256.0),
            tol: 2e-6,
        },
        Case {
            name: "elliptic_cylinder",
            scad: "rotate([0, 45, 0]) scale([2, 0.5, 1]) cylinder(h = 4, r = 3, $fn = 256);",
            expect: Polygons(256.0),
            tol: 2e-6,
        },
        Case {
            name: "sphere",
            scad: "translate([1, 2, 3]) sphere(r = 5, $fn = 256);",
            expect: Sphere(5.0, 256.0),
            tol: 2e-6,
        },
        Case {
            name: "box_with_cylindrical_hole",
            scad: "difference() { cube([20, 20, 10]);
                   translate([10, 10, -1]) cylinder(h = 12, r = 4, $fn = 64); }",
            expect: BoxMinusPolygons(4000.0, 64.0),
            tol: 2e-6,
        },
    ]
}

/// The fraction of a circle's area a regular n-gon inscribed in it covers.
fn polygon_factor(n: f64) -> f64 {
    n * (2.0 * PI / n).sin() / (2.0 * PI)
}

/// OpenSCAD 2021's sphere: `(n + 1) / 2` rings at polar angles `180° (i + ½) / rings`, each a
/// regular n-gon of the same phase; consecutive rings bound frustums of a pyramid.
fn openscad_sphere_volume(r: f64, n: f64) -> f64 {
    let rings = (n as usize).div_ceil(2);
    let ring = |i: usize| {
        let phi = PI * (i as f64 + 0.5) / rings as f64;
        (r * phi.cos(), r * phi.sin())
    };
    let area = |rho: f64| n * rho * rho * (2.0 * PI / n).sin() / 2.0;
    (0..rings - 1)
        .map(|i| {
            let ((z0, r0), (z1, r1)) = (ring(i), ring(i + 1));
            let (a0, a1) = (area(r0), area(r1));
            (z0 - z1) / 3.0 * (a0 + a1 + (a0 * a1).sqrt())
        })
        .sum()
}

fn expected(e: Expect, ours: f64) -> f64 {
    match e {
        Expect::Exact => ours,
        Expect::Polygons(n) => polygon_factor(n) * ours,
        Expect::BoxMinusPolygons(b, n) => b - polygon_factor(n) * (b - ours),
        Expect::Sphere(r, n) => {
            let exact = 4.0 / 3.0 * PI * r.powi(3);
            assert!(
                (ours - exact).abs() <= 1e-9 * exact,
                "sphere: ours {ours} vs 4/3 π r³ {exact}"
            );
            openscad_sphere_volume(r, n)
        }
    }
}

fn write_model(name: &str, scad: &str) -> PathBuf {
    let path = tempfile(Path::new(&format!("{name}.scad")), "scad");
    std::fs::write(&path, scad).expect("cannot write a temporary model");
    path
}

/// Renders `model` with the real `openscad` and returns the STL's enclosed volume.
fn openscad_volume(model: &Path) -> f64 {
    let (run, text) = openscad_export(model, "stl");
    assert!(
        run.status.success(),
        "openscad failed on {}: {}",
        model.display(),
        String::from_utf8_lossy(&run.stderr)
    );
    stl_volume(&text.expect("openscad wrote no STL"))
}

/// The signed volume enclosed by an ASCII STL: `Σ v0 · (v1 × v2) / 6` over its triangles.
fn stl_volume(text: &str) -> f64 {
    let vertices: Vec<[f64; 3]> = text
        .lines()
        .filter_map(|l| l.trim().strip_prefix("vertex "))
        .map(|rest| {
            let v: Vec<f64> = rest
                .split_whitespace()
                .map(|t| t.parse().expect("bad STL number"))
                .collect();
            [v[0], v[1], v[2]]
        })
        .collect();
    assert_eq!(vertices.len() % 3, 0, "STL vertices do not form triangles");
    vertices
        .chunks(3)
        .map(|t| {
            let (a, b, c) = (t[0], t[1], t[2]);
            let cross = [
                b[1] * c[2] - b[2] * c[1],
                b[2] * c[0] - b[0] * c[2],
                b[0] * c[1] - b[1] * c[0],
            ];
            (a[0] * cross[0] + a[1] * cross[1] + a[2] * cross[2]) / 6.0
        })
        .sum()
}

fn evaluate(path: &Path) -> Model {
    let mut sources = SourceMap::new();
    match reparamc::load_model(&mut sources, path) {
        Ok(e) => e.model,
        Err(d) => panic!("{}", d.render_plain(&sources)),
    }
}

fn our_volume(m: &Model) -> f64 {
    geom::volume(&m.parts, &m.csg)
}

/// Runs `f` over `items` on two threads (the CI machine has two cores).
fn parallel<T: Sync, R: Send>(items: &[T], f: impl Fn(&T) -> R + Sync) -> Vec<R> {
    let half = items.len().div_ceil(2);
    std::thread::scope(|s| {
        let (a, b) = items.split_at(half);
        let f = &f;
        let h = s.spawn(move || a.iter().map(f).collect::<Vec<R>>());
        let mut rb: Vec<R> = b.iter().map(f).collect();
        let mut ra = h.join().expect("worker panicked");
        ra.append(&mut rb);
        ra
    })
}

#[test]
fn volumes_match_openscad() {
    let cases = cases();
    let failures: Vec<String> = parallel(&cases, |case| {
        let path = write_model(case.name, case.scad);
        let ours = our_volume(&evaluate(&path));
        let theirs = openscad_volume(&path);
        let _ = std::fs::remove_file(&path);
        let want = expected(case.expect, ours);
        let rel = (want - theirs).abs() / theirs.abs();
        (rel > case.tol || rel.is_nan()).then(|| {
            format!(
                "{}: ours {ours} (as OpenSCAD polygonises it: {want}) vs OpenSCAD {theirs}, \
                 relative difference {rel:e} > {:e}",
                case.name, case.tol
            )
        })
    })
    .into_iter()
    .flatten()
    .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Volumes of `A ∩ B` and `A ∪ B` from OpenSCAD's own booleans.
fn openscad_boolean_volumes(a: &str, b: &str) -> (f64, f64) {
    let inter = write_model(
        "inter",
        &format!("intersection() {{ union() {{ {a} }} union() {{ {b} }} }}"),
    );
    let union = write_model("union", &format!("union() {{ {a} {b} }}"));
    let v = (openscad_volume(&inter), openscad_volume(&union));
    let _ = std::fs::remove_file(inter);
    let _ = std::fs::remove_file(union);
    v
}

fn check_overlap(a: &str, b: &str, tol: f64) {
    let (pa, pb) = (write_model("a", a), write_model("b", b));
    let (ma, mb) = (evaluate(&pa), evaluate(&pb));
    let _ = std::fs::remove_file(pa);
    let _ = std::fs::remove_file(pb);
    let o = geom::overlap((&ma.parts, &ma.csg), (&mb.parts, &mb.csg), None);
    let (inter, union) = openscad_boolean_volumes(a, b);
    let close = |x: f64, y: f64| (x - y).abs() <= tol * y.abs();
    assert!(
        close(o.inter, inter),
        "A ∩ B: ours {} vs OpenSCAD {inter}",
        o.inter
    );
    assert!(
        close(o.union, union),
        "A ∪ B: ours {} vs OpenSCAD {union}",
        o.union
    );
    assert!(
        close(o.iou(), inter / union),
        "IoU {} vs {}",
        o.iou(),
        inter / union
    );
    let iou = geom::iou((&ma.parts, &ma.csg), (&mb.parts, &mb.csg));
    assert_eq!(iou, o.iou());
}

#[test]
fn iou_of_shifted_boxes_matches_openscad_booleans() {
    check_overlap(
        "cube([10, 10, 10]); translate([12, 0, 0]) cube([2, 3, 4]);",
        "translate([3, 4, -2]) cube([10, 10, 10]); translate([12.5, 1, 1]) cube([2, 3, 4]);",
        1e-9,
    );
}

#[test]
fn iou_of_shifted_cylinders_matches_openscad_booleans() {
    // Lenses of polygons are not a fixed fraction of lenses of circles: compare within the
    // polygonisation error of $fn = 128, (2π/128)² / 6 ≈ 4e-4.
    check_overlap(
        "cylinder(h = 10, r = 5, $fn = 128);",
        "translate([3, 2, 4]) cylinder(h = 10, r = 5, $fn = 128);",
        1e-3,
    );
}

#[test]
fn incremental_iou_equals_full_iou_on_an_example() {
    let path = common::repo().join("examples/chair.scad");
    let a = evaluate(&path);
    let text = std::fs::read_to_string(&path).expect("examples/chair.scad");
    // Move the back and lengthen a leg.
    let changed = text
        .replace(
            "translate([-50, 35, 15]) cube([100, 15, 70]);",
            "translate([-50, 30, 15]) cube([100, 15, 60]);",
        )
        .replace(
            "translate([35, -50, -70]) cube([15, 15, 70]);",
            "translate([35, -50, -80]) cube([15, 15, 80]);",
        );
    assert_ne!(
        changed, text,
        "examples/chair.scad changed; update this test"
    );
    let pb = write_model("chair_variant", &changed);
    let b = evaluate(&pb);
    let _ = std::fs::remove_file(pb);
    let (sa, sb) = ((&a.parts[..], &a.csg), (&b.parts[..], &b.csg));
    let full = geom::iou(sa, sb);
    let region = geom::changed_region(&a.parts, &b.parts).expect("same part count");
    let local = geom::iou_local(sa, sb, &region, geom::volume(&a.parts, &a.csg));
    assert!((full - local).abs() < 1e-12, "{full} vs {local}");
    assert!(full < 1.0 && full > 0.5, "{full}");
}
