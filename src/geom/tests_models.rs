//! Unit tests on small models: chairs, a grid of furniture, mixed curved CSG under rigid
//! motions, inclusion–exclusion between two solids, incremental IoU, crossing planks.

use super::tests::*;
use super::*;
use crate::ir::Part;
use std::f64::consts::PI;

/// A small chair: four legs (z cylinders), a seat, a back, a stretcher along x.
fn chair() -> Vec<Part> {
    let mut v = Vec::new();
    for (x, y) in [(0.0, 0.0), (4.0, 0.0), (0.0, 4.0), (4.0, 4.0)] {
        v.push(cyl(4.0, 0.3, 0.3, false, translate([x, y, 0.0])));
    }
    v.push(cube([5.0, 5.0, 0.5], false, translate([-0.5, -0.5, 4.0])));
    v.push(cube([5.0, 0.5, 4.0], false, translate([-0.5, 4.0, 4.5])));
    v.push(cyl(
        4.0,
        0.2,
        0.2,
        false,
        mul(&translate([0.0, 0.0, 1.0]), &rotate([0.0, 90.0, 0.0])),
    ));
    v
}

#[test]
fn incremental_iou_matches_full_iou() {
    let a = chair();
    let mut b = a.clone();
    // Move the back and change a leg's radius.
    b[5] = cube([5.0, 0.5, 3.0], false, translate([-0.5, 3.8, 4.5]));
    b[1] = cyl(4.0, 0.4, 0.3, false, translate([4.0, 0.0, 0.0]));
    let u = union(a.len());
    let full = iou((&a, &u), (&b, &u));
    let region = changed_region(&a, &b).unwrap();
    assert!(region.contains(&Aabb::of_part(&b[5])) && region.contains(&Aabb::of_part(&a[1])));
    let va = volume(&a, &u);
    let local = iou_local((&a, &u), (&b, &u), &region, va);
    assert!((full - local).abs() < 1e-9, "{full} vs {local}");
    assert!(full < 0.9 && full > 0.6, "{full}");
    // Nothing changed: an empty region, IoU 1.
    let none = changed_region(&a, &a).unwrap();
    assert!(none.is_empty());
    assert_eq!(iou_local((&a, &u), (&a, &u), &none, va), 1.0);
    assert!((iou((&a, &u), (&a, &u)) - 1.0).abs() < 1e-12);
}

#[test]
fn chair_volume_is_sum_of_parts_minus_overlaps() {
    let parts = chair();
    let legs = 4.0 * PI * 0.09 * 4.0;
    let seat = 12.5;
    let back = 10.0;
    // The stretcher runs from x = 0 to 4 at y = 0, z = 1: inside the two front legs for
    // the half of their disks it crosses; what is outside them is its length minus the
    // chord-weighted overlap, computed here by subtracting its intersection with the legs.
    let stretcher = PI * 0.04 * 4.0;
    let total = vol(&parts);
    let s = vec![parts[6].clone(), parts[0].clone(), parts[1].clone()];
    let inside = volume(
        &s,
        &CsgNode::Intersection(vec![
            CsgNode::Part(0),
            CsgNode::Union(vec![CsgNode::Part(1), CsgNode::Part(2)]),
        ]),
    );
    assert_close(total, legs + seat + back + stretcher - inside, 1e-9);
    assert!(inside > 0.0 && inside < stretcher / 4.0);
}

#[test]
fn many_disjoint_parts_sum_exactly() {
    let mut parts = Vec::new();
    let mut expect = 0.0;
    for i in 0..30 {
        for j in 0..30 {
            let (x, y) = (3.0 * i as f64, 3.0 * j as f64);
            if (i + j) % 3 == 0 {
                parts.push(cyl(2.0, 1.0, 0.5, false, translate([x, y, 0.0])));
                expect += frustum_volume(2.0, 1.0, 0.5);
            } else {
                parts.push(cube([1.0, 2.0, 1.5], false, translate([x, y, 0.25])));
                expect += 3.0;
            }
        }
    }
    // A floor slab under everything, touching every part.
    parts.push(cube(
        [100.0, 100.0, 1.0],
        false,
        translate([-5.0, -5.0, -1.0]),
    ));
    expect += 10000.0;
    assert_close(vol(&parts), expect, 1e-10);
}

#[test]
fn volume_in_region_clips() {
    let s = vec![sphere(1.0, ID)];
    let u = union(1);
    let upper = Aabb::new([-5.0, -5.0, 0.0], [5.0, 5.0, 5.0]);
    assert_close(volume_in(&s, &u, &upper), 2.0 / 3.0 * PI, 1e-9);
    let quarter = Aabb::new([0.0, 0.0, -5.0], [5.0, 5.0, 5.0]);
    assert_close(volume_in(&s, &u, &quarter), PI / 3.0, 1e-9);
    let slab = Aabb::new([-5.0, -5.0, 0.5], [5.0, 5.0, 5.0]);
    assert_close(
        volume_in(&s, &u, &slab),
        PI * (2.0 / 3.0 - 0.5 + 0.125 / 3.0),
        1e-9,
    );
}

/// A small mixed model: boxes, cylinders along every axis, a cone, a sphere, some tilted.
fn mixed(at: &M) -> (Vec<Part>, CsgNode) {
    let t = |m: M| mul(at, &m);
    let parts = vec![
        cube([6.0, 4.0, 1.0], false, t(ID)),
        cyl(3.0, 0.8, 0.8, false, t(translate([1.0, 1.0, 1.0]))),
        cyl(
            6.0,
            0.5,
            0.5,
            false,
            t(mul(&translate([0.0, 3.0, 2.5]), &rotate([0.0, 90.0, 0.0]))),
        ),
        cyl(
            2.0,
            1.0,
            0.2,
            false,
            t(mul(&translate([4.5, 2.0, 1.0]), &rotate([25.0, 10.0, 0.0]))),
        ),
        sphere(1.2, t(translate([3.0, 2.0, 1.5]))),
        cube(
            [1.0, 1.0, 3.0],
            true,
            t(mul(&translate([5.0, 0.5, 0.5]), &rotate([0.0, 0.0, 37.0]))),
        ),
        cyl(
            8.0,
            0.3,
            0.3,
            true,
            t(mul(&translate([3.0, 2.0, 0.5]), &rotate([90.0, 0.0, 0.0]))),
        ),
    ];
    let csg = CsgNode::Difference(vec![
        CsgNode::Union((0..6).map(CsgNode::Part).collect()),
        CsgNode::Part(6),
    ]);
    (parts, csg)
}

#[test]
fn volume_is_invariant_under_rigid_motions() {
    let (parts, csg) = mixed(&ID);
    let v = volume(&parts, &csg);
    assert!(v > 35.0 && v < 50.0, "{v}");
    for m in [
        translate([100.0, -50.0, 7.0]),
        mul(&scale([-1.0, 1.0, 1.0]), &rotate([0.0, 0.0, 90.0])),
        rotate([90.0, 0.0, 0.0]),
        rotate([33.0, -12.0, 71.0]),
    ] {
        let (p, c) = mixed(&m);
        assert_close(volume(&p, &c), v, 1e-9);
    }
}

/// The mixed model without its sphere and tilted cone: extrusions along the axes only.
fn prismatic(at: &M) -> (Vec<Part>, CsgNode) {
    let (mut parts, _) = mixed(at);
    parts.remove(4);
    parts.remove(3);
    let csg = CsgNode::Difference(vec![
        CsgNode::Union((0..4).map(CsgNode::Part).collect()),
        CsgNode::Part(4),
    ]);
    (parts, csg)
}

#[test]
fn inclusion_exclusion() {
    let (a, ca) = prismatic(&ID);
    let (b, cb) = prismatic(&translate([0.7, -0.4, 0.3]));
    let o = overlap((&a, &ca), (&b, &cb), None);
    assert_close(o.a, volume(&a, &ca), 1e-9);
    // A ∩ B and A ∪ B as CSG trees over both part lists.
    let n = a.len();
    let both: Vec<Part> = a.iter().chain(&b).cloned().collect();
    fn shift(c: &CsgNode, n: usize) -> CsgNode {
        let all = |v: &[CsgNode]| v.iter().map(|c| shift(c, n)).collect();
        match c {
            CsgNode::Part(i) => CsgNode::Part(i + n),
            CsgNode::Union(v) => CsgNode::Union(all(v)),
            CsgNode::Difference(v) => CsgNode::Difference(all(v)),
            CsgNode::Intersection(v) => CsgNode::Intersection(all(v)),
        }
    }
    let inter = CsgNode::Intersection(vec![ca.clone(), shift(&cb, n)]);
    let uni = CsgNode::Union(vec![ca.clone(), shift(&cb, n)]);
    assert_close(o.inter, volume(&both, &inter), 1e-8);
    assert_close(o.union, volume(&both, &uni), 1e-8);
    assert!(o.iou() > 0.2 && o.iou() < 0.95, "{}", o.iou());
}

#[test]
fn incremental_iou_with_curved_parts() {
    let (a, csg) = prismatic(&ID);
    let mut b = a.clone();
    // A thicker rail, and the upright cylinder moved.
    b[2] = cyl(
        6.0,
        0.6,
        0.6,
        false,
        mul(&translate([0.0, 2.8, 2.4]), &rotate([0.0, 90.0, 0.0])),
    );
    b[1] = cyl(3.0, 0.8, 0.8, false, translate([1.3, 1.1, 1.0]));
    let region = changed_region(&a, &b).unwrap();
    let va = volume(&a, &csg);
    let local = iou_local((&a, &csg), (&b, &csg), &region, va);
    let full = iou((&a, &csg), (&b, &csg));
    assert!((local - full).abs() < 1e-9, "{local} vs {full}");
    assert!(full < 1.0 && full > 0.8, "{full}");
}

#[test]
fn solid_rays_agree_with_volume_slices() {
    // A vertical ray through the mixed model, and a horizontal one along y: the union's
    // intervals are sorted, disjoint, with unit normals.
    let (parts, csg) = mixed(&rotate([10.0, 20.0, 30.0]));
    let solid = Solid::new(&parts, &csg);
    let b = solid.bounds();
    assert!(!b.is_empty());
    let c: [f64; 3] = std::array::from_fn(|a| 0.5 * (b.min[a] + b.max[a]));
    for ray in [
        Ray {
            origin: [c[0], c[1], b.min[2] - 10.0],
            dir: [0.0, 0.0, 1.0],
        },
        Ray {
            origin: [c[0] - 1.0, b.min[1] - 10.0, c[2]],
            dir: [0.1, 1.0, 0.05],
        },
    ] {
        let ivs = solid.ray(&ray);
        assert!(!ivs.is_empty());
        for w in ivs.windows(2) {
            assert!(w[0].t1 < w[1].t0);
        }
        for iv in &ivs {
            assert!(iv.t0 < iv.t1);
            for n in [iv.n0, iv.n1] {
                let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
                assert!((len - 1.0).abs() < 1e-12);
            }
            // Entering, the outward normal faces against the ray; leaving, along it.
            let d = ray.dir;
            assert!(iv.n0[0] * d[0] + iv.n0[1] * d[1] + iv.n0[2] * d[2] <= 1e-12);
            assert!(iv.n1[0] * d[0] + iv.n1[1] * d[1] + iv.n1[2] * d[2] >= -1e-12);
        }
    }
}

#[test]
fn a_fan_of_crossing_boxes() {
    // Twelve planks crossing at one place, each turned 3° from the last and lifted a
    // little: the index cannot separate them, and every pair's edges cross. The same fan
    // turned a quarter (lines then cut it the other way) must hold the same volume.
    let fan = |turn: f64| -> Vec<Part> {
        (0..12)
            .map(|k| {
                let m = mul(
                    &translate([0.0, 0.0, 0.1 * k as f64]),
                    &rotate([0.0, 0.0, turn + 3.0 * k as f64]),
                );
                cube([10.0, 1.0, 1.0], true, m)
            })
            .collect()
    };
    let v = vol(&fan(0.0));
    assert!(v > 10.0 && v < 120.0, "{v}");
    assert_close(vol(&fan(90.0)), v, 1e-8);
}

#[test]
fn a_removal_never_changes_less_than_its_lower_bound() {
    // The chair (legs under the seat, a stretcher through two legs, rotated by
    // `rotate([0, 90, 0])`) and the mixed model (tilted parts, a subtracted rod), upright
    // and turned by 90° about x.
    let chair = (chair(), union(7));
    let turned = mixed(&rotate([90.0, 0.0, 0.0]));
    let mut bounded = 0;
    for (parts, csg) in [chair, mixed(&ID), turned] {
        let solid = Prepared::new(parts.clone(), csg);
        for p in 0..parts.len() {
            let bound = solid.removal_lower_bound(p);
            let exact = solid.changed_volume(&[(p, None)]);
            assert!(
                bound <= exact * (1.0 + 1e-9) + 1e-12,
                "part {p}: {bound} > {exact}"
            );
            if bound > 0.0 {
                bounded += 1;
            }
        }
    }
    // The seat, the back and the mixed model's base show themselves without integrating;
    // the subtracted rod and the tilted parts never do.
    assert!(bounded >= 4, "{bounded} parts bounded");
}
