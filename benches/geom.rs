//! Geometry benchmark: exact volumes and IoU by ray intervals.
//!
//! - `iou/chairs_8_boxes`: IoU of an 8-box chair (examples/chair.scad) and a variation of it
//!   (back moved, a leg longer) — the inner loop of constraint discovery.
//! - `iou_local/chairs_8_boxes`: the same IoU computed incrementally over the changed region.
//! - `volume/furniture_1000_parts`: a generated 10 × 10 grid of furniture, 100 pieces of 10
//!   parts each — a seat (box) on four round legs (z cylinders), two rails (x cylinders)
//!   through the legs, a back (box) and two back posts (z cylinders), alternating with
//!   tables whose legs are boxes — 1,000 parts, half of them curved.
//!
//! `cargo bench --bench geom` prints criterion's timings.

use criterion::{Criterion, criterion_group, criterion_main};
use reparamc::geom;
use reparamc::ir::{CsgNode, Num, Part, Primitive, Transform};
use std::hint::black_box;

type M = [[f64; 4]; 3];

fn translate(x: f64, y: f64, z: f64) -> M {
    [[1.0, 0.0, 0.0, x], [0.0, 1.0, 0.0, y], [0.0, 0.0, 1.0, z]]
}

/// `translate([x, y, z]) rotate([0, 90, 0])`: local z along world x.
fn along_x(x: f64, y: f64, z: f64) -> M {
    [[0.0, 0.0, 1.0, x], [0.0, 1.0, 0.0, y], [-1.0, 0.0, 0.0, z]]
}

fn part(primitive: Primitive, m: M) -> Part {
    Part {
        name: String::new(),
        primitive,
        world: Transform::from_values(m),
        span: Default::default(),
        misaligned: None,
        fragments: [0.0, 12.0, 2.0],
        highlighted: false,
        statements: Vec::new(),
    }
}

fn cube(x: f64, y: f64, z: f64, m: M) -> Part {
    let size = [x, y, z].map(Num::constant);
    part(
        Primitive::Cube {
            size,
            center: false,
        },
        m,
    )
}

fn cylinder(h: f64, r: f64, m: M) -> Part {
    let (h, r1, r2) = (Num::constant(h), Num::constant(r), Num::constant(r));
    part(
        Primitive::Cylinder {
            h,
            r1,
            r2,
            center: false,
        },
        m,
    )
}

/// examples/chair.scad: four legs, seat, back, two arms.
fn chair(back_y: f64, back_h: f64, leg_h: f64) -> Vec<Part> {
    let t = translate;
    vec![
        cube(15.0, 15.0, 70.0, t(-50.0, -50.0, -70.0)),
        cube(15.0, 15.0, leg_h, t(35.0, -50.0, -leg_h)),
        cube(15.0, 15.0, 70.0, t(-50.0, 35.0, -70.0)),
        cube(15.0, 15.0, 70.0, t(35.0, 35.0, -70.0)),
        cube(100.0, 100.0, 15.0, t(-50.0, -50.0, 0.0)),
        cube(100.0, 15.0, back_h, t(-50.0, back_y, 15.0)),
        cube(15.0, 85.0, 30.0, t(-50.0, -50.0, 15.0)),
        cube(15.0, 85.0, 30.0, t(35.0, -50.0, 15.0)),
    ]
}

/// One piece of furniture (10 parts) with its corner at `(x, y)`.
fn furniture(x: f64, y: f64, k: usize, out: &mut Vec<Part>) {
    let s = 1.0 + 0.05 * (k % 7) as f64;
    let (w, d, h) = (40.0 * s, 40.0, 45.0);
    let legs = [
        (3.0, 3.0),
        (w - 3.0, 3.0),
        (3.0, d - 3.0),
        (w - 3.0, d - 3.0),
    ];
    if k.is_multiple_of(2) {
        // A chair on round legs, with rails through them and a back on round posts.
        for (lx, ly) in legs {
            out.push(cylinder(h, 2.0, translate(x + lx, y + ly, 0.0)));
        }
        out.push(cube(w, d, 4.0, translate(x, y, h)));
        for ly in [3.0, d - 3.0] {
            out.push(cylinder(w - 6.0, 1.0, along_x(x + 3.0, y + ly, 15.0)));
        }
        out.push(cube(w, 3.0, 30.0, translate(x, y + d - 4.0, h + 14.0)));
        for lx in [3.0, w - 3.0] {
            out.push(cylinder(10.0, 1.5, translate(x + lx, y + d - 2.5, h + 4.0)));
        }
    } else {
        // A table on square legs, with an apron and a round centre column.
        for (lx, ly) in legs {
            out.push(cube(
                4.0,
                4.0,
                h,
                translate(x + lx - 2.0, y + ly - 2.0, 0.0),
            ));
        }
        out.push(cube(w, d, 3.0, translate(x, y, h)));
        out.push(cube(
            w - 6.0,
            2.0,
            8.0,
            translate(x + 3.0, y + 1.0, h - 8.0),
        ));
        out.push(cube(
            w - 6.0,
            2.0,
            8.0,
            translate(x + 3.0, y + d - 3.0, h - 8.0),
        ));
        out.push(cylinder(h, 3.0, translate(x + w / 2.0, y + d / 2.0, 0.0)));
        out.push(cylinder(20.0, 1.0, along_x(x + 4.0, y + d / 2.0, 10.0)));
        out.push(cylinder(h - 8.0, 1.5, translate(x + w / 2.0, y + 3.0, 0.0)));
    }
}

fn showroom() -> Vec<Part> {
    let mut parts = Vec::new();
    for i in 0..10 {
        for j in 0..10 {
            furniture(60.0 * i as f64, 50.0 * j as f64, i * 10 + j, &mut parts);
        }
    }
    assert_eq!(parts.len(), 1000);
    parts
}

fn union_of(n: usize) -> CsgNode {
    CsgNode::Union((0..n).map(CsgNode::Part).collect())
}

fn bench(c: &mut Criterion) {
    let a = chair(35.0, 70.0, 70.0);
    let b = chair(30.0, 60.0, 80.0);
    let u = union_of(8);
    c.bench_function("iou/chairs_8_boxes", |bch| {
        bch.iter(|| geom::iou(black_box((&a, &u)), black_box((&b, &u))))
    });
    let region = geom::changed_region(&a, &b).expect("same parts");
    let va = geom::volume(&a, &u);
    c.bench_function("iou_local/chairs_8_boxes", |bch| {
        bch.iter(|| geom::iou_local(black_box((&a, &u)), black_box((&b, &u)), &region, va))
    });
    let room = showroom();
    let all = union_of(room.len());
    let mut group = c.benchmark_group("volume");
    group.sample_size(10);
    group.bench_function("furniture_1000_parts", |bch| {
        bch.iter(|| geom::volume(black_box(&room), black_box(&all)))
    });
    group.finish();
}

criterion_group! {
    name = benches;
    // No plots: this machine has no font for criterion's plotters backend.
    config = Criterion::default().without_plots();
    targets = bench
}
criterion_main!(benches);
