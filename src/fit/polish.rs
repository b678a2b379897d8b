//! Face moves after the gradient rounds: single faces of single parts moved by fractions
//! of the part's extent, kept when the loss drops (see [`polish`]).
//!
//! Invariant: a move changes only the chosen face among its part's faces (the smallest
//! change of slots that does so), and the result is never worse than the start.

use super::Parametric;
use crate::analysis::linalg;
use crate::ir::Affine;

/// Moves of one face tried by [`polish`], as fractions of the part's extent along it
/// (negative: inwards; −0.95 all but removes the part along that axis).
const FACE_MOVES: [f64; 10] = [-0.95, -0.5, -0.25, -0.1, -0.03, 0.03, 0.1, 0.25, 0.5, 1.0];

/// Face moves: for each part and each of its faces, try moving that face alone (the
/// smallest change of slots that moves it and keeps the part's other faces) by 3% to 100%
/// of the part's extent outwards and 3% to 95% inwards; keep the best move when the loss
/// drops. Gradients only see edges that are visible; this reaches faces hidden behind other
/// parts (a shelf grown up into a table top), sizes the loss barely sees, and parts the
/// target does not have (a chair's arms squashed flat for a stool). `sweeps` passes, or
/// until nothing improves.
pub fn polish(
    problem: &Parametric,
    mut x: Vec<f64>,
    sweeps: usize,
    loss: &mut dyn FnMut(&[f64]) -> f64,
    ok: &dyn Fn(&[f64]) -> bool,
) -> Vec<f64> {
    let d = x.len();
    let mut best = loss(&x);
    for _ in 0..sweeps {
        let mut improved = false;
        for faces in &problem.faces {
            if faces.len() < 2 {
                continue;
            }
            let rows: Vec<&Affine> = faces.iter().map(|f| &f.2).collect();
            let a = linalg::matrix(&rows, d);
            if a.iter().all(|v| *v == 0.0) {
                continue;
            }
            let pinv = linalg::pinv(&a);
            for (j, &(axis, high, ref form)) in faces.iter().enumerate() {
                let along: Vec<f64> = faces
                    .iter()
                    .filter(|f| f.0 == axis)
                    .map(|f| f.2.eval(&x))
                    .collect();
                let extent = along.iter().fold(f64::NEG_INFINITY, |m, v| m.max(*v))
                    - along.iter().fold(f64::INFINITY, |m, v| m.min(*v));
                if extent.is_nan() || extent <= 0.0 || form.is_constant() {
                    continue;
                }
                // Outwards is up for a high face, down for a low one.
                let out = if high { 1.0 } else { -1.0 };
                let moves = FACE_MOVES.iter().filter_map(|frac| {
                    let shift = out * frac * extent;
                    let mut b = nalgebra::DVector::zeros(faces.len());
                    b[j] = shift;
                    let dx = &pinv * b;
                    let cand: Vec<f64> = x.iter().zip(dx.iter()).map(|(a, b)| a + b).collect();
                    // The move must actually move that face.
                    let moved = (form.eval(&cand) - form.eval(&x) - shift).abs() <= 1e-6 * extent;
                    moved.then_some(cand)
                });
                if let Some((l, cand)) = super::best_improvement(moves, best, loss, ok) {
                    best = l;
                    x = cand;
                    improved = true;
                }
            }
        }
        if !improved {
            break;
        }
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_part_the_target_lacks_is_squashed_in_one_sweep() {
        // The chair's left arm; the loss is its volume.
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/chair.scad");
        let mut sources = crate::front::source::SourceMap::new();
        let m = crate::load_model(&mut sources, &path).unwrap().model;
        let p = Parametric::new(&m);
        let arm = m.parts.iter().position(|q| q.name == "left_arm").unwrap();
        let extents = |x: &[f64]| -> [f64; 3] {
            std::array::from_fn(|a| {
                let v: Vec<f64> = p.faces[arm]
                    .iter()
                    .filter(|f| usize::from(f.0) == a)
                    .map(|f| f.2.eval(x))
                    .collect();
                v.iter().fold(f64::MIN, |m, &x| m.max(x))
                    - v.iter().fold(f64::MAX, |m, &x| m.min(x))
            })
        };
        let volume = |x: &[f64]| -> f64 { extents(x).iter().product() };
        let v0 = volume(&p.x0);
        let x = polish(&p, p.x0.clone(), 1, &mut |x| volume(x), &|x| {
            extents(x).iter().all(|&e| e > 0.0)
        });
        let v = volume(&x);
        assert!(v < 0.01 * v0, "arm volume {v0} -> {v}");
        // Nothing but the arm's numbers moved.
        let moved: Vec<&str> = (0..x.len())
            .filter(|&i| (x[i] - p.x0[i]).abs() > 1e-9 * p.scale)
            .map(|i| m.slots[i].name.as_str())
            .collect();
        assert!(moved.iter().all(|n| n.contains("arm")), "moved {moved:?}");
    }
}
