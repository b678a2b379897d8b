//! A part's private region: a lower bound, without integrating, on the volume that removing
//! the part from a solid changes.
//!
//! The *inner box* of a shape is an axis-aligned world box inside it: the box itself, the
//! square prism inscribed in a frustum (around its whole length at its smaller radius, or
//! around its wider half at that half's smaller radius, whichever holds more), the cube
//! inscribed in a sphere; only shapes whose matrix is a scaled signed permutation (up to
//! negligible entries) have one. Where the inner box lies outside every other shape's bounds, the solid at a point is the
//! CSG tree evaluated with this part alone present; if that contains the point, removing
//! the part empties it. So the volume of the inner box outside the other bounds is changed
//! by the removal, whatever the rest of the model: a lower bound on
//! [`super::Prepared::changed_volume`] of the removal (0 when there is no such region).
//!
//! Invariants: the bound never exceeds the exact changed volume (up to rounding); it is 0
//! for a part that draws nothing, a part the tree subtracts or intersects away when alone,
//! and a part seen by more than [`MAX_NEIGHBOURS`] other bounds (the grid would be large).

use super::aabb::Aabb;
use super::csg::Program;
use super::shape::{Kind, Shape, is_signed_permutation};
use crate::ir::CsgNode;
use crate::tolerance::GEOM_NEGLIGIBLE_ENTRY;

/// Most other bounds meeting the inner box for which the bound is computed.
pub const MAX_NEIGHBOURS: usize = 24;

/// Whether the tree contains a point where `part` alone is present (every other part
/// absent): the tree pruned to that part, as [`Program::from_csg`] prunes absent parts,
/// is not empty.
pub(crate) fn alone_inside(node: &CsgNode, part: usize) -> bool {
    !Program::from_csg(node, &|i| (i == part).then_some(0)).is_empty()
}

/// An axis-aligned world box inside the shape (see the module docs). Entries of the matrix
/// the shape counts as zero ([`GEOM_NEGLIGIBLE_ENTRY`], as `rotate([90, 0, 0])` leaves
/// them) may tilt the shape by that much: the box gives up that margin on every side.
pub(crate) fn inner_box(s: &Shape) -> Option<Aabb> {
    if !is_signed_permutation(&s.m) {
        return None;
    }
    let (lo, hi) = match s.kind {
        Kind::Box { lo, hi } => (lo, hi),
        Kind::Frustum { z0, z1, r, .. } => frustum_prism(z0, z1, r),
        Kind::Sphere { r } => {
            let h = r / 3f64.sqrt();
            ([-h; 3], [h; 3])
        }
    };
    let reach = (0..3)
        .map(|k| lo[k].abs().max(hi[k].abs()))
        .fold(0.0, f64::max);
    let (a, b) = (s.world(lo), s.world(hi));
    let margin = |k: usize| {
        let row = (0..3).map(|j| s.m[k][j].abs()).fold(0.0, f64::max);
        3.0 * GEOM_NEGLIGIBLE_ENTRY * row * reach
    };
    let bx = Aabb::new(
        std::array::from_fn(|k| a[k].min(b[k]) + margin(k)),
        std::array::from_fn(|k| a[k].max(b[k]) - margin(k)),
    );
    (!bx.is_empty()).then_some(bx)
}

/// The larger of two square prisms inside a frustum `z0..z1` with cap radii `r`: along the
/// whole length at the smaller radius, or along the wider half at the radius of its middle.
fn frustum_prism(z0: f64, z1: f64, r: [f64; 2]) -> ([f64; 3], [f64; 3]) {
    let mid = 0.5 * (z0 + z1);
    let r_mid = 0.5 * (r[0] + r[1]);
    let whole = (r[0].min(r[1]), z0, z1);
    let half = if r[0] >= r[1] {
        (r_mid, z0, mid)
    } else {
        (r_mid, mid, z1)
    };
    let vol = |(w, a, b): (f64, f64, f64)| w * w * (b - a);
    let (w, a, b) = if vol(half) > vol(whole) { half } else { whole };
    let h = w / std::f64::consts::SQRT_2;
    ([-h, -h, a], [h, h, b])
}

/// Volume of `inner` outside every box of `others`, on the grid their sides cut.
pub(crate) fn volume_outside(inner: &Aabb, others: &[Aabb]) -> f64 {
    let cuts: [Vec<f64>; 3] = std::array::from_fn(|a| {
        let mut c = vec![inner.min[a], inner.max[a]];
        for o in others {
            for v in [o.min[a], o.max[a]] {
                if v > inner.min[a] && v < inner.max[a] {
                    c.push(v);
                }
            }
        }
        c.sort_by(f64::total_cmp);
        c.dedup();
        c
    });
    let mut total = 0.0;
    for x in cuts[0].windows(2) {
        for y in cuts[1].windows(2) {
            for z in cuts[2].windows(2) {
                let c = [
                    0.5 * (x[0] + x[1]),
                    0.5 * (y[0] + y[1]),
                    0.5 * (z[0] + z[1]),
                ];
                let covered = others
                    .iter()
                    .any(|o| (0..3).all(|a| o.min[a] < c[a] && c[a] < o.max[a]));
                if !covered {
                    total += (x[1] - x[0]) * (y[1] - y[0]) * (z[1] - z[0]);
                }
            }
        }
    }
    total
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_volume_outside_counts_each_uncovered_cell_once() {
        let inner = Aabb::new([0.0; 3], [4.0, 2.0, 1.0]);
        // One box over the left half, one over the first quarter (inside the first).
        let others = [
            Aabb::new([-1.0; 3], [2.0, 3.0, 3.0]),
            Aabb::new([-1.0; 3], [1.0, 3.0, 3.0]),
        ];
        assert!((volume_outside(&inner, &others) - 4.0).abs() < 1e-12);
        assert!((volume_outside(&inner, &[]) - 8.0).abs() < 1e-12);
    }

    #[test]
    fn a_part_alone_is_inside_unless_the_tree_takes_it_away() {
        let tree = CsgNode::Union(vec![
            CsgNode::Difference(vec![CsgNode::Part(0), CsgNode::Part(1)]),
            CsgNode::Intersection(vec![CsgNode::Part(2), CsgNode::Part(3)]),
        ]);
        assert!(alone_inside(&tree, 0));
        assert!(!alone_inside(&tree, 1), "subtracted");
        assert!(!alone_inside(&tree, 2), "intersected with an absent part");
        assert!(!alone_inside(&tree, 4), "not in the tree");
    }

    #[test]
    fn a_frustum_keeps_the_larger_inscribed_prism() {
        // A cone to a point: the whole length has radius 0, the wide half 1 at its middle.
        let (lo, hi) = frustum_prism(0.0, 2.0, [2.0, 0.0]);
        let h = 1.0 / std::f64::consts::SQRT_2;
        assert!((hi[0] - h).abs() < 1e-12 && (lo[0] + h).abs() < 1e-12);
        assert_eq!((lo[2], hi[2]), (0.0, 1.0));
        // A cylinder: the whole length.
        let (lo, hi) = frustum_prism(0.0, 2.0, [1.0, 1.0]);
        assert_eq!((lo[2], hi[2]), (0.0, 2.0));
    }
}
