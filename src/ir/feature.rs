//! Features: the face planes, axis lines, key points and extents of a part.
//!
//! Each feature is a list of numbers (one for a plane or an extent, two for an axis line —
//! its coordinates on the other two axes in x, y, z order — three for a point) computed from
//! the part's primitive and world matrix. For an axis-aligned part the numbers are affine in
//! slots once the evaluator has frozen what it must; a part off the axes has no features.
//!
//! Which features a part has is the paper's definition: a box has six face planes, three
//! axis lines, eight corners and three extents; a cylinder or cone two end planes, one axis
//! line, two end-cap centres and three extents (its bounding box); a sphere its centre and
//! three extents. Beyond the paper, a round part also has the planes its curved side
//! touches (four for a cylinder or cone, six for a sphere): the paper's four relation kinds
//! cannot say that a board rests on an axle. Every part also has its three mid-planes
//! (`Centre`), where its placement is: mirror symmetry and equal spacing speak of them.

use super::num::{FreezeSide, Num};
use super::part::{Part, Primitive};
use serde::Serialize;

pub const AXIS_NAMES: [&str; 3] = ["x", "y", "z"];
/// Face names by axis, low side then high side.
pub const FACE_NAMES: [[&str; 2]; 3] = [["left", "right"], ["front", "back"], ["bottom", "top"]];
pub const EXTENT_NAMES: [&str; 3] = ["width", "depth", "height"];

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum FeatureKind {
    /// A face plane normal to `axis`, on its low or high side.
    Plane { axis: u8, high: bool },
    /// An axis line along `axis`.
    AxisLine { axis: u8 },
    /// A key point; `sides` says low (false) or high (true) on each axis for box corners,
    /// and the end along the cylinder axis for cap centres.
    Point { sides: [bool; 3], cap: bool },
    /// The extent along `axis`.
    Extent { axis: u8 },
    /// A plane a round part's curved side touches, normal to `axis` (across the part's own
    /// axis), on its low or high side: where a board resting on an axle or a wheel on the
    /// floor meets it. Not one of the paper's features.
    Side { axis: u8, high: bool },
    /// The mid-plane of the part's world interval normal to `axis`: where its placement is,
    /// which mirror symmetry and equal spacing speak of. Not one of the paper's features,
    /// and never paired with another feature by the paper's four kinds.
    Centre { axis: u8 },
}

/// One feature of one part, with its numbers.
#[derive(Debug, Clone)]
pub struct Feature {
    pub part: usize,
    pub kind: FeatureKind,
    /// The role within the part, e.g. `top`, `height`, `z_axis`, `left_front_bottom`.
    pub role: String,
    pub nums: Vec<Num>,
}

/// The local axis each world axis maps to, and the sign of that entry.
fn alignment(part: &Part) -> Option<[(usize, f64); 3]> {
    let perm = part.world.axis_permutation()?;
    Some(std::array::from_fn(|i| {
        let j = perm[i];
        (j, part.world.m[i][j].value.signum())
    }))
}

/// `t + w·p` with the inner factor `p` frozen if both depend on slots.
fn place(t: &Num, w: &Num, p: &Num) -> Num {
    t.add(&w.mul(p, FreezeSide::Right))
}

/// Local interval along each local axis, and the local radius used for side extremes.
struct LocalShape {
    lo: [Num; 3],
    hi: [Num; 3],
}

fn local_shape(prim: &Primitive) -> LocalShape {
    let half = |n: &Num| n.mul(&Num::constant(0.5), FreezeSide::Right);
    match prim {
        Primitive::Cube { size, center } => {
            if *center {
                LocalShape {
                    lo: size.each_ref().map(|s| half(s).neg()),
                    hi: size.each_ref().map(half),
                }
            } else {
                LocalShape {
                    lo: std::array::from_fn(|_| Num::constant(0.0)),
                    hi: size.clone(),
                }
            }
        }
        Primitive::Cylinder { h, r1, r2, center } => {
            let r = if r2.value > r1.value { r2 } else { r1 };
            let (z0, z1) = if *center {
                (half(h).neg(), half(h))
            } else {
                (Num::constant(0.0), h.clone())
            };
            LocalShape {
                lo: [r.neg(), r.neg(), z0],
                hi: [r.clone(), r.clone(), z1],
            }
        }
        Primitive::Sphere { r } => LocalShape {
            lo: std::array::from_fn(|_| r.neg()),
            hi: std::array::from_fn(|_| r.clone()),
        },
    }
}

/// World interval `(low, high)` of the part along each world axis, as numbers.
pub fn world_intervals(part: &Part) -> Option<[(Num, Num); 3]> {
    let align = alignment(part)?;
    let shape = local_shape(&part.primitive);
    Some(std::array::from_fn(|i| {
        let (j, sign) = align[i];
        let t = &part.world.m[i][3];
        let w = &part.world.m[i][j];
        let a = place(t, w, &shape.lo[j]);
        let b = place(t, w, &shape.hi[j]);
        if sign > 0.0 { (a, b) } else { (b, a) }
    }))
}

/// The smaller cap of a cylinder or cone whose two radii are different numbers: its world
/// interval along each axis across the part's own, `(axis, low, high)`, which the part's
/// box (drawn by the larger radius) does not show. Empty for other parts, and where both
/// radii are the very same number (`r = …`), since the box shows both caps then.
pub fn smaller_cap(part: &Part) -> Vec<(usize, Num, Num)> {
    let Primitive::Cylinder { r1, r2, .. } = &part.primitive else {
        return Vec::new();
    };
    let (Some(align), Some(axis)) = (alignment(part), cylinder_axis(part)) else {
        return Vec::new();
    };
    if r1.form == r2.form {
        return Vec::new();
    }
    // The box takes r1 unless r2 is larger (`local_shape`); this is the other one.
    let r = if r2.value > r1.value { r1 } else { r2 };
    (0..3)
        .filter(|&i| i != axis)
        .map(|i| {
            let (j, sign) = align[i];
            let (t, w) = (&part.world.m[i][3], &part.world.m[i][j]);
            let (a, b) = (place(t, w, &r.neg()), place(t, w, r));
            if sign > 0.0 { (i, a, b) } else { (i, b, a) }
        })
        .collect()
}

/// The world axis a cylinder's local z maps to.
fn cylinder_axis(part: &Part) -> Option<usize> {
    let align = alignment(part)?;
    (0..3).find(|&i| align[i].0 == 2)
}

/// The world axis along a cylinder's own axis (its `length`); `None` for other parts.
pub fn axial_axis(part: &Part) -> Option<usize> {
    cylinder_axis(part).filter(|_| matches!(part.primitive, Primitive::Cylinder { .. }))
}

/// Every feature of `part` (index `index`), or `None` if the part is off the axes.
pub fn part_features(part: &Part, index: usize) -> Option<Vec<Feature>> {
    let iv = world_intervals(part)?;
    let mut found = match &part.primitive {
        Primitive::Cube { .. } => box_features(&iv),
        Primitive::Cylinder { .. } => {
            let axis = cylinder_axis(part)?;
            let mut found = cylinder_features(&iv, axis);
            found.extend(side_planes(&iv, Some(axis)));
            found
        }
        Primitive::Sphere { .. } => {
            let sides = [false; 3];
            let nums = (0..3).map(|a| center(&iv, a)).collect();
            let mut found = vec![(
                FeatureKind::Point { sides, cap: true },
                "center".into(),
                nums,
            )];
            found.extend(side_planes(&iv, None));
            found
        }
    };
    found.extend(extent_features(&iv, axial_axis(part)));
    found.extend(centre_features(&iv));
    // The smaller cap's width, so a relation can say a cylinder's two radii are one (only
    // where it is affine already: freezing a cap's radius to make it so would take a
    // number from the variations that change it).
    if let Some((axis, lo, hi)) = smaller_cap(part).into_iter().next()
        && hi.sub(&lo).affine().is_some()
    {
        let top =
            matches!(&part.primitive, Primitive::Cylinder { r1, r2, .. } if r2.value <= r1.value);
        let role = if top { "top_width" } else { "bottom_width" };
        found.push((
            FeatureKind::Extent { axis: axis as u8 },
            role.to_string(),
            vec![hi.sub(&lo)],
        ));
    }
    let features = found.into_iter().map(|(kind, role, nums)| Feature {
        part: index,
        kind,
        role,
        nums,
    });
    Some(features.collect())
}

/// A feature before it knows its part: kind, role and numbers.
type Described = (FeatureKind, String, Vec<Num>);

/// The middle of world interval `a`.
fn center(iv: &[(Num, Num); 3], a: usize) -> Num {
    iv[a]
        .0
        .add(&iv[a].1)
        .mul(&Num::constant(0.5), FreezeSide::Right)
}

/// The two end planes along `axis`, low first.
fn end_planes(iv: &[(Num, Num); 3], axis: usize) -> Vec<Described> {
    [(false, &iv[axis].0), (true, &iv[axis].1)]
        .into_iter()
        .map(|(high, n)| {
            let kind = FeatureKind::Plane {
                axis: axis as u8,
                high,
            };
            (
                kind,
                FACE_NAMES[axis][high as usize].to_string(),
                vec![n.clone()],
            )
        })
        .collect()
}

/// A box's six faces, its three centre lines and its eight corners, in that order.
fn box_features(iv: &[(Num, Num); 3]) -> Vec<Described> {
    let mut out: Vec<Described> = (0..3).flat_map(|a| end_planes(iv, a)).collect();
    for (a, axis_name) in AXIS_NAMES.iter().enumerate() {
        let others: Vec<Num> = (0..3).filter(|&b| b != a).map(|b| center(iv, b)).collect();
        let role = format!("{axis_name}_axis");
        out.push((FeatureKind::AxisLine { axis: a as u8 }, role, others));
    }
    for c in 0..8u8 {
        let sides = [c & 1 != 0, c & 2 != 0, c & 4 != 0];
        let nums = (0..3)
            .map(|a| {
                if sides[a] {
                    iv[a].1.clone()
                } else {
                    iv[a].0.clone()
                }
            })
            .collect();
        let role = (0..3)
            .map(|a| FACE_NAMES[a][sides[a] as usize])
            .collect::<Vec<_>>()
            .join("_");
        out.push((FeatureKind::Point { sides, cap: false }, role, nums));
    }
    out
}

/// A cylinder's (or cone's) two end planes, its axis and the centres of its two caps.
fn cylinder_features(iv: &[(Num, Num); 3], axis: usize) -> Vec<Described> {
    let mut out = end_planes(iv, axis);
    let others: Vec<Num> = (0..3)
        .filter(|&b| b != axis)
        .map(|b| center(iv, b))
        .collect();
    out.push((
        FeatureKind::AxisLine { axis: axis as u8 },
        "axis".into(),
        others,
    ));
    for (high, end) in [(false, &iv[axis].0), (true, &iv[axis].1)] {
        let nums = (0..3)
            .map(|a| {
                if a == axis {
                    end.clone()
                } else {
                    center(iv, a)
                }
            })
            .collect();
        let mut sides = [false; 3];
        sides[axis] = high;
        let role = format!("{}_center", FACE_NAMES[axis][high as usize]);
        out.push((FeatureKind::Point { sides, cap: true }, role, nums));
    }
    out
}

/// A round part's side extremes: the planes its curved side touches on each axis across
/// `axis` (every axis for a sphere, `axis` `None`), named like a box's faces.
fn side_planes(iv: &[(Num, Num); 3], axis: Option<usize>) -> Vec<Described> {
    (0..3)
        .filter(|&a| Some(a) != axis)
        .flat_map(|a| {
            [(false, &iv[a].0), (true, &iv[a].1)].map(|(high, n)| {
                let kind = FeatureKind::Side {
                    axis: a as u8,
                    high,
                };
                (
                    kind,
                    FACE_NAMES[a][high as usize].to_string(),
                    vec![n.clone()],
                )
            })
        })
        .collect()
}

/// The mid-planes of the part's world intervals, one per axis (`x_centre`, …).
fn centre_features(iv: &[(Num, Num); 3]) -> Vec<Described> {
    (0..3)
        .map(|a| {
            let kind = FeatureKind::Centre { axis: a as u8 };
            (
                kind,
                format!("{}_centre", AXIS_NAMES[a]),
                vec![center(iv, a)],
            )
        })
        .collect()
}

/// The three extents (`length` along a round part's axis).
fn extent_features(iv: &[(Num, Num); 3], axial: Option<usize>) -> Vec<Described> {
    (0..3)
        .map(|a| {
            let role = if Some(a) == axial {
                "length"
            } else {
                EXTENT_NAMES[a]
            };
            let nums = vec![iv[a].1.sub(&iv[a].0)];
            (
                FeatureKind::Extent { axis: a as u8 },
                role.to_string(),
                nums,
            )
        })
        .collect()
}
