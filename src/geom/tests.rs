//! Unit tests of the geometry module: single primitives and small booleans against
//! closed-form volumes and ray hits, degenerate input, and the helpers that build parts.

use super::*;
use crate::ir::{Num, Primitive, Transform};
use std::f64::consts::PI;

pub(super) type M = [[f64; 4]; 3];

pub(super) const ID: M = [
    [1.0, 0.0, 0.0, 0.0],
    [0.0, 1.0, 0.0, 0.0],
    [0.0, 0.0, 1.0, 0.0],
];

pub(super) fn mul(a: &M, b: &M) -> M {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let t = if j == 3 { a[i][3] } else { 0.0 };
            t + (0..3).map(|k| a[i][k] * b[k][j]).sum::<f64>()
        })
    })
}

pub(super) fn translate(v: [f64; 3]) -> M {
    let mut m = ID;
    (0..3).for_each(|i| m[i][3] = v[i]);
    m
}

pub(super) fn scale(v: [f64; 3]) -> M {
    let mut m = ID;
    (0..3).for_each(|i| m[i][i] = v[i]);
    m
}

/// OpenSCAD's `rotate([ax, ay, az])`: Rz · Ry · Rx, degrees.
pub(super) fn rotate(deg: [f64; 3]) -> M {
    let [x, y, z] = deg.map(f64::to_radians);
    let rx = [
        [1.0, 0.0, 0.0, 0.0],
        [0.0, x.cos(), -x.sin(), 0.0],
        [0.0, x.sin(), x.cos(), 0.0],
    ];
    let ry = [
        [y.cos(), 0.0, y.sin(), 0.0],
        [0.0, 1.0, 0.0, 0.0],
        [-y.sin(), 0.0, y.cos(), 0.0],
    ];
    let rz = [
        [z.cos(), -z.sin(), 0.0, 0.0],
        [z.sin(), z.cos(), 0.0, 0.0],
        [0.0, 0.0, 1.0, 0.0],
    ];
    mul(&rz, &mul(&ry, &rx))
}

pub(super) fn part(primitive: Primitive, m: M) -> Part {
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

pub(super) fn cube(s: [f64; 3], center: bool, m: M) -> Part {
    part(
        Primitive::Cube {
            size: s.map(Num::constant),
            center,
        },
        m,
    )
}

pub(super) fn cyl(h: f64, r1: f64, r2: f64, center: bool, m: M) -> Part {
    let k = Num::constant;
    part(
        Primitive::Cylinder {
            h: k(h),
            r1: k(r1),
            r2: k(r2),
            center,
        },
        m,
    )
}

pub(super) fn sphere(r: f64, m: M) -> Part {
    part(
        Primitive::Sphere {
            r: Num::constant(r),
        },
        m,
    )
}

pub(super) fn union(n: usize) -> CsgNode {
    CsgNode::Union((0..n).map(CsgNode::Part).collect())
}

pub(super) fn vol(parts: &[Part]) -> f64 {
    volume(parts, &union(parts.len()))
}

pub(super) fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * b.abs().max(1e-300)
}

#[track_caller]
pub(super) fn assert_close(a: f64, b: f64, rel: f64) {
    assert!(
        close(a, b, rel),
        "{a} vs {b} (rel {:e})",
        (a - b).abs() / b.abs()
    );
}

pub(super) fn frustum_volume(h: f64, r1: f64, r2: f64) -> f64 {
    PI * h * (r1 * r1 + r1 * r2 + r2 * r2) / 3.0
}

/// Rotations that put a local axis along world x, y, z and three oblique directions.
pub(super) fn orientations() -> Vec<M> {
    vec![
        ID,
        rotate([0.0, 90.0, 0.0]),
        rotate([90.0, 0.0, 0.0]),
        rotate([30.0, 0.0, 0.0]),
        rotate([17.0, 41.0, 73.0]),
        rotate([-65.0, 12.5, 200.0]),
    ]
}

#[test]
fn box_slab_test_and_normals() {
    let p = cube([2.0, 3.0, 4.0], false, translate([1.0, 1.0, 1.0]));
    let r = Ray {
        origin: [2.0, 2.0, -5.0],
        dir: [0.0, 0.0, 2.0],
    };
    let iv = ray_part(&p, &r).unwrap();
    assert_eq!((iv.t0, iv.t1), (3.0, 5.0));
    assert_eq!(iv.n0, [0.0, 0.0, -1.0]);
    assert_eq!(iv.n1, [0.0, 0.0, 1.0]);
    let miss = Ray {
        origin: [0.0, 0.0, 0.0],
        dir: [0.0, 0.0, 1.0],
    };
    assert!(ray_part(&p, &miss).is_none());
    // Oblique, entering through the left face.
    let r = Ray {
        origin: [0.0, 2.0, 2.0],
        dir: [1.0, 0.0, 0.5],
    };
    let iv = ray_part(&p, &r).unwrap();
    assert_eq!((iv.t0, iv.t1), (1.0, 3.0));
    assert_eq!(iv.n0, [-1.0, 0.0, 0.0]);
    assert_eq!(iv.n1, [1.0, 0.0, 0.0]);
    assert_eq!(vol(&[p]), 24.0);
}

#[test]
fn frustum_and_cone_rays() {
    // Cone r1 = 2, r2 = 0, h = 4 along z: at height z the radius is 2 − z/2.
    let p = cyl(4.0, 2.0, 0.0, false, ID);
    let r = Ray {
        origin: [-10.0, 0.0, 2.0],
        dir: [1.0, 0.0, 0.0],
    };
    let iv = ray_part(&p, &r).unwrap();
    assert!((iv.t0 - 9.0).abs() < 1e-12 && (iv.t1 - 11.0).abs() < 1e-12);
    let s = 1.0 / 5f64.sqrt();
    assert!((iv.n0[0] + 2.0 * s).abs() < 1e-12 && (iv.n0[2] - s).abs() < 1e-12);
    // Down the axis: bottom cap to apex.
    let r = Ray {
        origin: [0.0, 0.0, 10.0],
        dir: [0.0, 0.0, -1.0],
    };
    let iv = ray_part(&p, &r).unwrap();
    assert!((iv.t0 - 6.0).abs() < 1e-12 && (iv.t1 - 10.0).abs() < 1e-12);
    assert_eq!(iv.n1, [0.0, 0.0, -1.0]);
    // A centred frustum with r1 < r2, hit through the top cap and the side.
    let p = cyl(2.0, 1.0, 3.0, true, ID);
    let r = Ray {
        origin: [2.5, 0.0, 5.0],
        dir: [0.0, 0.0, -1.0],
    };
    let iv = ray_part(&p, &r).unwrap();
    // radius 1 + (z + 1) reaches 2.5 at z = 0.5
    assert!(
        (iv.t0 - 4.0).abs() < 1e-12 && (iv.t1 - 4.5).abs() < 1e-12,
        "{iv:?}"
    );
    assert_eq!(iv.n0, [0.0, 0.0, 1.0]);
}

#[test]
fn sphere_ray_and_volume() {
    let p = sphere(2.0, translate([1.0, 0.0, 0.0]));
    let r = Ray {
        origin: [1.0, 0.0, -10.0],
        dir: [0.0, 0.0, 1.0],
    };
    let iv = ray_part(&p, &r).unwrap();
    assert!((iv.t0 - 8.0).abs() < 1e-12 && (iv.t1 - 12.0).abs() < 1e-12);
    assert!((iv.n0[2] + 1.0).abs() < 1e-12);
    assert_close(vol(&[p]), 4.0 / 3.0 * PI * 8.0, 1e-10);
}

#[test]
fn analytic_volumes_in_every_orientation() {
    for (n, rot) in orientations().iter().enumerate() {
        let at = mul(&translate([3.0, -2.0, 5.0]), rot);
        let cases = [
            (cube([2.0, 3.0, 5.0], true, at), 30.0),
            (cyl(5.0, 2.0, 2.0, false, at), frustum_volume(5.0, 2.0, 2.0)),
            (cyl(3.0, 2.0, 0.5, true, at), frustum_volume(3.0, 2.0, 0.5)),
            (cyl(4.0, 0.0, 1.5, false, at), frustum_volume(4.0, 0.0, 1.5)),
            (cyl(4.0, 1.5, 0.0, false, at), frustum_volume(4.0, 1.5, 0.0)),
            (sphere(1.7, at), 4.0 / 3.0 * PI * 1.7f64.powi(3)),
        ];
        for (k, (p, exact)) in cases.into_iter().enumerate() {
            let v = vol(&[p]);
            assert!(
                close(v, exact, 1e-9),
                "orientation {n} case {k}: {v} vs {exact}"
            );
        }
    }
}

#[test]
fn box_under_rotate_30_is_exact() {
    let p = cube([4.0, 2.0, 3.0], false, rotate([0.0, 0.0, 30.0]));
    assert_close(vol(std::slice::from_ref(&p)), 24.0, 1e-13);
    let q = cube([4.0, 2.0, 3.0], false, rotate([30.0, 0.0, 0.0]));
    assert_close(vol(&[q]), 24.0, 1e-13);
    // A rotated ray through the rotated box: the hit is as long as the box is wide.
    let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
    let r = Ray {
        origin: [-10.0 * c + 2.0 * c - s, -10.0 * s + 2.0 * s + c, 1.0],
        dir: [c, s, 0.0],
    };
    let iv = ray_part(&p, &r).unwrap();
    assert!((iv.t1 - iv.t0 - 4.0).abs() < 1e-12, "{iv:?}");
    assert!((iv.n0[0] + c).abs() < 1e-12 && (iv.n0[1] + s).abs() < 1e-12);
}

#[test]
fn non_uniformly_scaled_cylinder_is_elliptic() {
    // scale([2, 0.5, 3]) cylinder(h=2, r=1): an elliptic cylinder, semi-axes 2 and 0.5, length 6.
    for rot in orientations() {
        let m = mul(&rot, &scale([2.0, 0.5, 3.0]));
        assert_close(
            vol(&[cyl(2.0, 1.0, 1.0, false, m)]),
            PI * 2.0 * 0.5 * 6.0,
            1e-9,
        );
        assert_close(vol(&[sphere(1.0, m)]), 4.0 / 3.0 * PI * 3.0, 1e-9);
    }
    // Outward normals stay outward under a mirror.
    let m = mul(&scale([-1.0, 1.0, 1.0]), &scale([2.0, 1.0, 1.0]));
    let r = Ray {
        origin: [-10.0, 0.0, 0.5],
        dir: [1.0, 0.0, 0.0],
    };
    let iv = ray_part(&cyl(1.0, 1.0, 1.0, false, m), &r).unwrap();
    assert!((iv.t0 - 8.0).abs() < 1e-12 && (iv.t1 - 12.0).abs() < 1e-12);
    assert!((iv.n0[0] + 1.0).abs() < 1e-12 && (iv.n1[0] - 1.0).abs() < 1e-12);
}

#[test]
fn unions_are_not_double_counted() {
    let a = cube([2.0, 2.0, 2.0], false, ID);
    let b = cube([2.0, 2.0, 2.0], false, translate([1.0, 1.0, 1.0]));
    assert_eq!(vol(&[a.clone(), b.clone()]), 15.0);
    assert_eq!(vol(&[a.clone(), a.clone()]), 8.0);
    let s = sphere(1.0, ID);
    assert_close(vol(&[s.clone(), s.clone(), s]), 4.0 / 3.0 * PI, 1e-10);
    // Two z cylinders half overlapping: lens area by formula.
    let c1 = cyl(1.0, 1.0, 1.0, false, ID);
    let c2 = cyl(1.0, 1.0, 1.0, false, translate([1.0, 0.0, 0.0]));
    let lens = 2.0 * (0.5f64).acos() - 0.5 * 3f64.sqrt();
    assert_close(vol(&[c1, c2]), 2.0 * PI - lens, 1e-9);
}

#[test]
fn difference_and_intersection() {
    let outer = cube([10.0, 10.0, 10.0], false, ID);
    let hole = cube([2.0, 2.0, 20.0], false, translate([4.0, 4.0, -5.0]));
    let parts = vec![outer.clone(), hole];
    let d = CsgNode::Difference(vec![CsgNode::Part(0), CsgNode::Part(1)]);
    assert_eq!(volume(&parts, &d), 1000.0 - 40.0);
    let i = CsgNode::Intersection(vec![CsgNode::Part(0), CsgNode::Part(1)]);
    assert_eq!(volume(&parts, &i), 40.0);
    // A cylindrical hole along x, and a sphere intersected with a box (a hemisphere).
    let drill = cyl(
        20.0,
        2.0,
        2.0,
        false,
        mul(&translate([-5.0, 5.0, 5.0]), &rotate([0.0, 90.0, 0.0])),
    );
    let parts = vec![outer, drill];
    assert_close(volume(&parts, &d), 1000.0 - PI * 4.0 * 10.0, 1e-9);
    let parts = vec![
        sphere(3.0, ID),
        cube([10.0, 10.0, 5.0], false, translate([-5.0, -5.0, 0.0])),
    ];
    assert_close(volume(&parts, &i), 2.0 / 3.0 * PI * 27.0, 1e-9);
    // Subtracting a box that only touches a face removes nothing.
    let parts = vec![
        cube([1.0; 3], false, ID),
        cube([1.0; 3], false, translate([1.0, 0.0, 0.0])),
    ];
    assert_eq!(volume(&parts, &d), 1.0);
    let rays = ray_solid(
        &[
            cube([4.0; 3], false, ID),
            sphere(1.0, translate([2.0, 2.0, 2.0])),
        ],
        &d,
        &Ray {
            origin: [2.0, 2.0, -1.0],
            dir: [0.0, 0.0, 1.0],
        },
    );
    assert_eq!(rays.len(), 2);
    assert!((rays[0].t1 - 2.0).abs() < 1e-12 && (rays[1].t0 - 4.0).abs() < 1e-12);
    // The hole's surface faces into the hole: down at its bottom, up at its top.
    assert!((rays[0].n1[2] - 1.0).abs() < 1e-12 && (rays[1].n0[2] + 1.0).abs() < 1e-12);
}

#[test]
fn degenerate_parts_are_empty() {
    let parts = vec![
        cube([0.0, 1.0, 1.0], false, ID),
        cube([f64::NAN, 1.0, 1.0], false, ID),
        cyl(1.0, 0.0, 0.0, false, ID),
        cyl(-1.0, 1.0, 1.0, false, ID),
        sphere(0.0, ID),
        sphere(1.0, scale([1.0, 0.0, 1.0])),
        sphere(1.0, translate([f64::INFINITY, 0.0, 0.0])),
    ];
    assert_eq!(vol(&parts), 0.0);
    let csg = CsgNode::Union(vec![CsgNode::Part(99)]);
    assert_eq!(volume(&parts, &csg), 0.0);
    assert_eq!(volume(&[], &CsgNode::Union(vec![])), 0.0);
    let r = Ray {
        origin: [f64::NAN, 0.0, 0.0],
        dir: [0.0, 0.0, 1.0],
    };
    assert!(ray_part(&cube([1.0; 3], false, ID), &r).is_none());
}

#[test]
fn overlap_and_iou_of_shifted_boxes() {
    let a = vec![cube([2.0, 2.0, 2.0], false, ID)];
    let b = vec![cube([2.0, 2.0, 2.0], false, translate([1.0, 0.0, 0.0]))];
    let u = union(1);
    let o = overlap((&a, &u), (&b, &u), None);
    assert_eq!((o.a, o.b, o.inter, o.union), (8.0, 8.0, 4.0, 12.0));
    assert_eq!(iou((&a, &u), (&b, &u)), 1.0 / 3.0);
    let r = Aabb::new([0.0; 3], [1.5, 2.0, 1.0]);
    let o = overlap((&a, &u), (&b, &u), Some(r));
    assert_eq!((o.a, o.b, o.inter), (3.0, 1.0, 1.0));
}

#[test]
fn edited_iou_equals_the_whole_models_iou() {
    // A plate with a hole, a post through the hole's rim, and a far-away box: edits of one
    // part (moved, resized, removed) measured locally agree with the whole integral.
    let parts = vec![
        cube([10.0, 10.0, 2.0], false, ID),
        cube([2.0, 2.0, 6.0], false, translate([4.0, 4.0, -2.0])),
        cyl(5.0, 1.0, 1.0, false, translate([3.0, 3.0, 0.0])),
        cube([3.0, 3.0, 3.0], false, translate([40.0, 0.0, 0.0])),
    ];
    let tree = CsgNode::Union(vec![
        CsgNode::Difference(vec![CsgNode::Part(0), CsgNode::Part(1)]),
        CsgNode::Part(2),
        CsgNode::Part(3),
    ]);
    let prepared = super::Prepared::new(parts.clone(), tree.clone());
    let edits: Vec<Vec<super::Edit>> = vec![
        vec![(
            1,
            Some(cube([3.0, 2.0, 6.0], false, translate([4.0, 4.0, -2.0]))),
        )],
        vec![(
            2,
            Some(cyl(5.0, 1.5, 1.0, false, translate([3.5, 3.0, 0.0]))),
        )],
        vec![(3, None)],
        vec![
            (2, None),
            (
                3,
                Some(cube([3.0, 4.0, 3.0], false, translate([40.0, 0.0, 0.0]))),
            ),
        ],
        vec![(0, Some(parts[0].clone()))],
    ];
    for edit in edits {
        let mut after = parts.clone();
        let mut removed = Vec::new();
        for (i, p) in &edit {
            match p {
                Some(p) => after[*i] = p.clone(),
                None => removed.push(*i),
            }
        }
        let pruned = tree.without(&removed).unwrap();
        let whole = iou((&parts, &tree), (&after, &pruned));
        assert_close(prepared.iou_edited(&edit), whole, 1e-9);
        // Applying the edit updates the volume by the same local integral.
        let mut applied = prepared.clone();
        applied.apply(&edit);
        assert_close(applied.volume(), volume(&after, &pruned), 1e-9);
    }
}
