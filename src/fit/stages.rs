//! Where a fit moves, stage by stage: a basis of directions in slot space (or every slot)
//! and a number of rounds. The default schedule goes from coarse to fine: the model's
//! proportions first (every length scaled along its axis), then the structural subspace
//! (parts move with what they touch), then every slot.
//!
//! Invariant: every basis has one row per slot of the model it was built from.

use super::optimize;
use crate::ir::{Affine, Model};
use crate::render::scene::{Kind, PartGeom, theta_forms};
use nalgebra::DMatrix;

/// One stage of a fit: where it moves and for how many rounds. Each stage starts where the
/// previous one ended.
#[derive(Debug, Clone, PartialEq)]
pub struct Stage {
    /// A basis `N` (d × d′) of the directions to move in; `None`: every slot.
    pub basis: Option<DMatrix<f64>>,
    pub rounds: usize,
}

impl Stage {
    pub fn slots(rounds: usize) -> Stage {
        Stage {
            basis: None,
            rounds,
        }
    }
}

/// Rounds of the proportions stage at the start of a warm schedule.
pub const SCALE_ROUNDS: usize = 1;

/// The default schedule: the first `warm` rounds move the model's proportions
/// ([`scale_basis`], one round when `warm` is at least 2) and then inside the structural
/// subspace (the relations that hold a design together); the rest in slot space.
pub fn staged(model: &Model, rounds: usize, warm: usize) -> Vec<Stage> {
    let warm = warm.min(rounds);
    let scale = if warm >= 2 { SCALE_ROUNDS } else { 0 };
    staged_with(model, scale, warm - scale, rounds - warm)
}

/// `scale` rounds of proportions, `structure` rounds in the structural subspace, `rest`
/// rounds in slot space (stages with no rounds are left out).
pub fn staged_with(model: &Model, scale: usize, structure: usize, rest: usize) -> Vec<Stage> {
    let mut stages = Vec::new();
    if scale > 0 {
        stages.push(Stage {
            basis: Some(scale_basis(model)),
            rounds: scale,
        });
    }
    if structure > 0 {
        stages.push(Stage {
            basis: Some(structure_basis(model)),
            rounds: structure,
        });
    }
    if rest > 0 {
        stages.push(Stage::slots(rest));
    }
    stages
}

/// Null-space basis of constraint rows over `d` slots.
pub fn basis_of(rows: &[&Affine], d: usize) -> DMatrix<f64> {
    let c = crate::analysis::linalg::matrix(rows, d);
    optimize::null_space(&c)
}

/// The subspace of every relation that holds on the model (its base constraints).
pub fn constraint_basis(model: &Model) -> DMatrix<f64> {
    let c = crate::analysis::find_candidates(model);
    let rows: Vec<&Affine> = c.list.iter().flat_map(|k| k.rows.iter()).collect();
    basis_of(&rows, model.slots.len())
}

/// The subspace of the structural prior (`analysis::prior`): contacts, coaxiality,
/// repeated parts' sizes, placements, a bar's profile.
pub fn structure_basis(model: &Model) -> DMatrix<f64> {
    let rows = crate::analysis::prior::structural_rows(model);
    basis_of(&rows.iter().collect::<Vec<_>>(), model.slots.len())
}

/// How much each slot acts along each world axis: from every part parameter the slot
/// enters (a translation or linear entry of the part's placement acts along its row's axis;
/// a primitive's size along its local axis acts along the world axes that axis maps to),
/// weighted by the slot's coefficient there. Rows sum to 1, or are zero for slots that no
/// length depends on (angles, counts).
pub fn axis_weights(parts: &[crate::ir::Part], slots: usize) -> Vec<[f64; 3]> {
    let mut w = vec![[0.0f64; 3]; slots];
    for part in parts {
        let g = PartGeom::from_part(part);
        let forms = theta_forms(part);
        // World axes a local axis maps to, by the size of the placement's column.
        let local_to_world = |c: usize| -> [f64; 3] {
            let col: [f64; 3] = std::array::from_fn(|r| g.theta[4 * r + c].abs());
            let sum: f64 = col.iter().sum();
            if sum > 0.0 {
                col.map(|v| v / sum)
            } else {
                [0.0; 3]
            }
        };
        for (k, form) in forms.iter().enumerate() {
            let Some(form) = form else { continue };
            let axes: [f64; 3] = match (k, g.kind) {
                // Placement: row `k / 4` of the world transform.
                (0..12, _) => std::array::from_fn(|r| if r == k / 4 { 1.0 } else { 0.0 }),
                (_, Kind::Box) => local_to_world(k - 12),
                // A frustum's height, then its two radii (across its axis).
                (12, Kind::Frustum) => local_to_world(2),
                (_, Kind::Frustum) => {
                    let (x, y) = (local_to_world(0), local_to_world(1));
                    std::array::from_fn(|r| 0.5 * (x[r] + y[r]))
                }
                (_, Kind::Sphere) => [1.0 / 3.0; 3],
            };
            for &(s, a) in &form.terms {
                for r in 0..3 {
                    w[s as usize][r] += a.abs() * axes[r];
                }
            }
        }
    }
    for row in &mut w {
        let sum: f64 = row.iter().sum();
        if sum > 0.0 {
            row.iter_mut().for_each(|v| *v /= sum);
        }
    }
    w
}

/// Directions that scale the model along each world axis about the origin: column `a`
/// moves every slot by its value times its weight along axis `a` ([`axis_weights`]), so a
/// step along it stretches lengths and positions along that axis together (a stool's rungs
/// come down with its seat). d × 3.
pub fn scale_basis(model: &Model) -> DMatrix<f64> {
    let w = axis_weights(&model.parts, model.slots.len());
    let x0 = model.slot_values();
    DMatrix::from_fn(x0.len(), 3, |s, a| x0[s] * w[s][a])
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::front::test_model as model;

    #[test]
    fn lengths_scale_along_their_axes() {
        // A box 10 × 20 × 30 raised by 5, and a cylinder of radius 2 and height 8 lying
        // along x.
        let m = model(
            "translate([0, 0, 5]) cube([10, 20, 30]);\n\
             rotate([0, 90, 0]) cylinder(h = 8, r = 2);\n",
        );
        let w = axis_weights(&m.parts, m.slots.len());
        let by_value = |v: f64| {
            let i = m.slots.iter().position(|s| s.value == v).unwrap();
            w[i]
        };
        assert_eq!(by_value(10.0), [1.0, 0.0, 0.0]);
        assert_eq!(by_value(20.0), [0.0, 1.0, 0.0]);
        assert_eq!(by_value(30.0), [0.0, 0.0, 1.0]);
        assert_eq!(by_value(5.0), [0.0, 0.0, 1.0]);
        let h = by_value(8.0);
        assert!((h[0] - 1.0).abs() < 1e-9, "height along x: {h:?}");
        let r = by_value(2.0);
        assert!(
            r[0] < 1e-9 && (r[1] - 0.5).abs() < 1e-9,
            "radius across x: {r:?}"
        );
        // Stretching along z moves the box's height and its lift alike.
        let n = scale_basis(&m);
        let i30 = m.slots.iter().position(|s| s.value == 30.0).unwrap();
        let i5 = m.slots.iter().position(|s| s.value == 5.0).unwrap();
        assert_eq!((n[(i30, 2)], n[(i5, 2)]), (30.0, 5.0));
        assert_eq!(n[(i30, 0)], 0.0);
    }
}
