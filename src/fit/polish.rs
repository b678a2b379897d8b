//! Moves after the gradient rounds, kept when the loss drops: single faces of single parts
//! and the faces of several parts that share a plane in the model as written (a contact, a
//! flush), moved by fractions of the parts' extent, each pass after the whole-part moves of
//! [`super::part_moves`] ([`polish`]); and single slots and faces moved by a pixel or less
//! on hard edges ([`refine`]).
//!
//! Invariants: a face move changes only the chosen face among its part's faces, and a plane
//! move only the plane's faces among its parts' faces; of the changes of slots that do so,
//! the one that moves the other parts' faces least and the smallest are offered
//! ([`keeping_others`]), round-off removed. Every move kept lowers the fine loss
//! ([`Edges::Fine`]) in the lighting the judge then stands in (a jump's own lighting,
//! [`super::part_moves`]; with a plain loss, the result is never worse than the start).

use super::Parametric;
use super::part_moves::{Edges, Judge, sweep_parts};
use crate::analysis::linalg;
use crate::ir::Affine;
use crate::tolerance::RELATIVE_EPSILON;
use nalgebra::{DMatrix, DVector};

/// Moves of one face tried by [`polish`], as fractions of the part's extent along it
/// (negative: inwards; −0.95 all but removes the part along that axis).
const FACE_MOVES: [f64; 10] = [-0.95, -0.5, -0.25, -0.1, -0.03, 0.03, 0.1, 0.25, 0.5, 1.0];

/// Face moves: for each part and each of its faces, try moving that face alone (the
/// smallest change of slots that moves it and keeps the part's other faces) by 3% to 100%
/// of the part's extent outwards and 3% to 95% inwards; keep the best move when the loss
/// drops. Gradients only see edges that are visible; this reaches faces hidden behind other
/// parts (a shelf grown up into a table top), sizes the loss barely sees, and parts the
/// target does not have (a chair's arms squashed flat for a stool). Each pass first moves
/// every part whole along its thinnest axis ([`sweep_parts`]): a shelf onto the picture's
/// shelf many of its thicknesses away; and last every plane group together
/// ([`plane_groups`]): a board thinned with the boards it holds. `loss` judges a point with
/// the edges asked for; moves are kept by [`Edges::Fine`] (the whole-part moves also ask
/// for [`Edges::Coarse`]). `sweeps` passes, or until nothing improves.
pub fn polish(
    problem: &Parametric,
    mut x: Vec<f64>,
    sweeps: usize,
    judge: &mut dyn Judge,
    ok: &dyn Fn(&[f64]) -> bool,
) -> Vec<f64> {
    let mut best = judge.loss(&x, Edges::Fine);
    let shifts = |extent: f64, out: f64| -> Vec<f64> {
        FACE_MOVES.iter().map(|frac| out * frac * extent).collect()
    };
    let solves = part_solves(problem);
    let groups = plane_moves(problem);
    for _ in 0..sweeps {
        // Whole parts first: a face move would squash a part the picture shows elsewhere
        // (its wrong pixels gone), and a squashed part's moves are too short to get there.
        let parts = sweep_parts(problem, &solves, &mut x, &mut best, judge, ok);
        let mut loss = |x: &[f64]| judge.loss(x, Edges::Fine);
        let faces = sweep_faces(problem, &solves, &mut x, &mut best, &shifts, &mut loss, ok);
        let planes = sweep_planes(problem, &groups, &mut x, &mut best, &mut loss, ok);
        if !faces && !planes && !parts {
            break;
        }
    }
    x
}

/// Moves of a plane's faces together tried by [`polish`], as fractions of the thinnest of
/// their parts along the plane's normal, both ways.
const PLANE_MOVES: [f64; 5] = [0.03, 0.1, 0.25, 0.5, 0.95];

/// Faces of two or more parts that lie on one plane in the model as written (at
/// `Parametric::anchor`): a contact (a side's inner face on the bottom's end) or a flush
/// (two tops at one height). Each group is `(part, face)` pairs, all along one axis.
pub fn plane_groups(problem: &Parametric) -> Vec<Vec<(usize, usize)>> {
    let eps = RELATIVE_EPSILON * problem.scale;
    let mut groups = Vec::new();
    for axis in 0..3u8 {
        let mut at: Vec<(f64, usize, usize)> = Vec::new();
        for (p, faces) in problem.faces.iter().enumerate() {
            for (j, (a, _, form)) in faces.iter().enumerate() {
                if *a == axis && !form.is_constant() {
                    at.push((form.eval(&problem.anchor), p, j));
                }
            }
        }
        at.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut start = 0;
        for k in 1..=at.len() {
            if k < at.len() && at[k].0 - at[k - 1].0 <= eps {
                continue;
            }
            let group: Vec<(usize, usize)> = at[start..k].iter().map(|g| (g.1, g.2)).collect();
            let parts = group
                .iter()
                .map(|g| g.0)
                .collect::<std::collections::BTreeSet<_>>();
            if parts.len() >= 2 {
                groups.push(group);
            }
            start = k;
        }
    }
    groups
}

/// A plane group ([`plane_groups`]) prepared for moving: its parts, the rows of all their
/// faces over the slots with their changes of slots ([`keeping_others`]), and a 0/1 mask of
/// the plane's faces among those rows. It depends on the model, not on the point, so it is
/// worked out once per pass.
struct PlaneMove {
    axis: u8,
    parts: Vec<usize>,
    a: DMatrix<f64>,
    solves: Vec<DMatrix<f64>>,
    on_plane: DVector<f64>,
}

/// Every plane group of `problem`, prepared ([`PlaneMove`]).
fn plane_moves(problem: &Parametric) -> Vec<PlaneMove> {
    let d = problem.x0.len();
    plane_groups(problem)
        .into_iter()
        .map(|group| {
            let axis = problem.faces[group[0].0][group[0].1].0;
            let mut parts: Vec<usize> = group.iter().map(|g| g.0).collect();
            parts.sort_unstable();
            parts.dedup();
            let rows: Vec<(usize, usize, &Affine)> = parts
                .iter()
                .flat_map(|&p| {
                    problem.faces[p]
                        .iter()
                        .enumerate()
                        .map(move |(j, f)| (p, j, &f.2))
                })
                .collect();
            let forms: Vec<&Affine> = rows.iter().map(|r| r.2).collect();
            let a = linalg::matrix(&forms, d);
            let solves = keeping_others(problem, &a, &parts);
            // 1 on the rows of the plane's faces, 0 on their parts' other faces.
            let on_plane = DVector::from_iterator(
                rows.len(),
                rows.iter()
                    .map(|r| f64::from(u8::from(group.contains(&(r.0, r.1))))),
            );
            PlaneMove {
                axis,
                parts,
                a,
                solves,
                on_plane,
            }
        })
        .collect()
}

/// One pass over the plane groups: every face of a group is moved by the same shift (the
/// smallest change of slots that does so and keeps every other face of their parts), by
/// [`PLANE_MOVES`] of the thinnest of their parts along the plane's normal either way; the
/// best is kept when the loss drops below `best`. A single face move opens a gap where two
/// parts touched (a side thinned away from the bottom it held) and the loss refuses it;
/// moved together they stay in contact. Whether any move was kept.
fn sweep_planes(
    problem: &Parametric,
    planes: &[PlaneMove],
    x: &mut Vec<f64>,
    best: &mut f64,
    loss: &mut dyn FnMut(&[f64]) -> f64,
    ok: &dyn Fn(&[f64]) -> bool,
) -> bool {
    let mut improved = false;
    for plane in planes {
        let thinnest = plane
            .parts
            .iter()
            .map(|&p| extent_along(problem, p, plane.axis, x))
            .fold(f64::INFINITY, f64::min);
        if !(thinnest.is_finite() && thinnest > 0.0) {
            continue;
        }
        let moves: Vec<Vec<f64>> = PLANE_MOVES
            .iter()
            .flat_map(|f| [f * thinnest, -f * thinnest])
            .flat_map(|shift| plane.solves.iter().map(move |solve| (shift, solve)))
            .filter_map(|(shift, solve)| {
                let b = &plane.on_plane * shift;
                let (dx, cand) = step(x, solve, &b, shift);
                // Every face of the parts must move as asked (no slot moves a member
                // without another face of its part, or a shared slot ties them otherwise).
                let off = (&plane.a * &dx - &b).amax();
                (off <= RELATIVE_EPSILON * thinnest.max(problem.scale)).then_some(cand)
            })
            .collect();
        if let Some((l, cand)) = super::best_improvement(moves, *best, loss, ok) {
            *best = l;
            *x = cand;
            improved = true;
        }
    }
    improved
}

/// The change of slots `solve · b` of a move by `shift` ([`without_round_off`]) and the
/// point `x` moved by it.
pub(super) fn step(
    x: &[f64],
    solve: &DMatrix<f64>,
    b: &DVector<f64>,
    shift: f64,
) -> (DVector<f64>, Vec<f64>) {
    let dx = without_round_off(solve * b, shift);
    let cand = x.iter().zip(dx.iter()).map(|(a, d)| a + d).collect();
    (dx, cand)
}

/// `dx` with the entries round-off left in the pseudo-inverse's solution (under
/// [`RELATIVE_EPSILON`] of the move `shift`) set to zero: otherwise a move would also nudge
/// numbers it does not mean to move, and a loss those nudges lower by round-off alone
/// would take it (and walk hidden faces anywhere, one tie at a time).
fn without_round_off(mut dx: DVector<f64>, shift: f64) -> DVector<f64> {
    let tol = RELATIVE_EPSILON * shift.abs();
    dx.iter_mut()
        .filter(|v| v.abs() <= tol)
        .for_each(|v| *v = 0.0);
    dx
}

/// Part `p`'s extent along `axis` at `x` (its faces' spread).
pub(super) fn extent_along(problem: &Parametric, p: usize, axis: u8, x: &[f64]) -> f64 {
    let (low, high) = spans(problem, p, x)[usize::from(axis)];
    high - low
}

/// Part `p`'s span `(low, high)` along each axis at `x` (`(∞, −∞)` along an axis it has no
/// face on).
pub(super) fn spans(problem: &Parametric, p: usize, x: &[f64]) -> [(f64, f64); 3] {
    let mut out = [(f64::INFINITY, f64::NEG_INFINITY); 3];
    for f in &problem.faces[p] {
        let v = f.2.eval(x);
        let s = &mut out[usize::from(f.0)];
        *s = (s.0.min(v), s.1.max(v));
    }
    out
}

/// Per part, the changes of slots that move its faces as asked (none for a part with fewer
/// than two faces or none that a slot moves), each a `slots × faces` matrix
/// ([`keeping_others`]): a face move's changes of slots. They depend on the model, not on
/// the point, so they are worked out once per pass.
pub(super) fn part_solves(problem: &Parametric) -> Vec<Vec<DMatrix<f64>>> {
    let d = problem.x0.len();
    (0..problem.faces.len())
        .map(|p| {
            let faces = &problem.faces[p];
            if faces.len() < 2 {
                return Vec::new();
            }
            let rows: Vec<&Affine> = faces.iter().map(|f| &f.2).collect();
            let a = linalg::matrix(&rows, d);
            if a.iter().all(|v| *v == 0.0) {
                return Vec::new();
            }
            keeping_others(problem, &a, &[p])
        })
        .collect()
}

/// The changes of slots `M b` that move the faces whose rows are `own` (of the parts
/// `parts`) by `b`: first the one that, among those, moves every other part's faces least
/// (least squares over their rows; not at all where no slot ties them to the moved faces)
/// and is smallest among the rest; then, where it differs, the smallest change of slots.
/// The smallest alone shares a move between a part's own translation and a wrapper's that
/// carries the whole model (a `.csg` `multmatrix` around a group), and so moves every part
/// of the group by half of it; the first alone leaves the greedy sweep other paths than
/// before, one of which walked the desk off OpenSCAD's pictures of it (both are offered).
fn keeping_others(problem: &Parametric, own: &DMatrix<f64>, parts: &[usize]) -> Vec<DMatrix<f64>> {
    let d = problem.x0.len();
    let own_pinv = linalg::pinv(own);
    let rows: Vec<&Affine> = (0..problem.faces.len())
        .filter(|q| !parts.contains(q))
        .flat_map(|q| problem.faces[q].iter().map(|f| &f.2))
        .collect();
    if rows.is_empty() {
        return vec![own_pinv];
    }
    let others = linalg::matrix(&rows, d);
    // Changes of slots that leave the own faces where they are: the null space of `own`.
    let free = DMatrix::identity(d, d) - &own_pinv * own;
    let through = &others * &free;
    let keep = &own_pinv - linalg::pinv(&through) * (&others * &own_pinv);
    let apart = (&keep - &own_pinv).amax() > RELATIVE_EPSILON * own_pinv.amax();
    if apart {
        vec![keep, own_pinv]
    } else {
        vec![keep]
    }
}

/// One pass over every face of every part: the shifts `shifts(extent, outwards)` of that
/// face alone are tried and the best is kept when the loss drops below `best`. Whether any
/// move was kept. `solves` are the parts' [`part_solves`].
fn sweep_faces(
    problem: &Parametric,
    solves: &[Vec<DMatrix<f64>>],
    x: &mut Vec<f64>,
    best: &mut f64,
    shifts: &dyn Fn(f64, f64) -> Vec<f64>,
    loss: &mut dyn FnMut(&[f64]) -> f64,
    ok: &dyn Fn(&[f64]) -> bool,
) -> bool {
    let mut improved = false;
    for (p, solves) in solves.iter().enumerate() {
        for j in 0..problem.faces[p].len() {
            let moves = face_moves(problem, p, j, solves, x, shifts);
            if let Some((l, cand)) = super::best_improvement(moves, *best, loss, ok) {
                *best = l;
                *x = cand;
                improved = true;
            }
        }
    }
    improved
}

/// The points `x` with face `j` of part `p` alone moved by `shifts(extent, outwards)`
/// (through each of the part's changes of slots `solves`, [`part_solves`]), keeping those
/// that move that face as asked; none for a face no slot moves or a part of no extent
/// along its axis.
pub(super) fn face_moves(
    problem: &Parametric,
    p: usize,
    j: usize,
    solves: &[DMatrix<f64>],
    x: &[f64],
    shifts: &dyn Fn(f64, f64) -> Vec<f64>,
) -> Vec<Vec<f64>> {
    let faces = &problem.faces[p];
    let (axis, high, ref form) = faces[j];
    let extent = extent_along(problem, p, axis, x);
    if extent.is_nan() || extent <= 0.0 || form.is_constant() {
        return Vec::new();
    }
    // Outwards is up for a high face, down for a low one.
    let out = if high { 1.0 } else { -1.0 };
    shifts(extent, out)
        .into_iter()
        .flat_map(|shift| solves.iter().map(move |solve| (shift, solve)))
        .filter_map(|(shift, solve)| {
            let mut b = DVector::zeros(faces.len());
            b[j] = shift;
            let (_, cand) = step(x, solve, &b, shift);
            // The move must actually move that face.
            let moved =
                (form.eval(&cand) - form.eval(x) - shift).abs() <= RELATIVE_EPSILON * extent;
            moved.then_some(cand)
        })
        .collect()
}

/// Moves tried by [`refine`], in units of its `step` (about a pixel), each both ways.
const REFINE_MOVES: [f64; 4] = [1.0, 0.5, 0.25, 0.125];

/// Small moves judged on the hard-edged loss: each slot in turn, then each face alone (as
/// in [`polish`]), is moved by `step` (world units, about a pixel) and by halves of it down
/// to an eighth, both ways, and the best move is kept while the loss drops. Soft edges put
/// a fitted edge midway between the two pixel centres an aliased picture's edge lies
/// between, and leave thin parts a fraction of a pixel off; with hard edges only what
/// disagrees with the target at pixel centres costs, so this brings edges onto the
/// pictures' own pixels. `sweeps` passes, or until nothing improves.
pub fn refine(
    problem: &Parametric,
    mut x: Vec<f64>,
    step: f64,
    sweeps: usize,
    loss: &mut dyn FnMut(&[f64]) -> f64,
    ok: &dyn Fn(&[f64]) -> bool,
) -> Vec<f64> {
    let mut best = loss(&x);
    let steps: Vec<f64> = REFINE_MOVES
        .iter()
        .flat_map(|f| [f * step, -f * step])
        .collect();
    // Faces move by the same steps whatever their part's extent.
    let shifts = |_: f64, _: f64| steps.clone();
    let solves = part_solves(problem);
    for _ in 0..sweeps {
        let mut improved = false;
        for i in 0..x.len() {
            let moves = steps.iter().map(|dv| {
                let mut c = x.clone();
                c[i] += dv;
                c
            });
            if let Some((l, cand)) = super::best_improvement(moves, best, loss, ok) {
                best = l;
                x = cand;
                improved = true;
            }
        }
        improved |= sweep_faces(problem, &solves, &mut x, &mut best, &shifts, loss, ok);
        if !improved {
            break;
        }
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    fn chair() -> crate::ir::Model {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/chair.scad");
        let mut sources = crate::front::source::SourceMap::new();
        crate::front::load_model(&mut sources, &path).unwrap().model
    }

    #[test]
    fn hard_edges_are_brought_onto_the_targets_pixels() {
        // A "picture" of every face of the chair on a grid of 1-unit pixels: which pixel
        // centre each face lies past. The target moves three numbers by less than, about
        // and more than a pixel; the start is the chair itself.
        let m = chair();
        let p = Parametric::new(&m);
        let picture = |x: &[f64]| -> Vec<f64> {
            p.faces
                .iter()
                .flatten()
                .map(|f| (f.2.eval(x) + 0.5).floor())
                .collect()
        };
        let mut truth = p.x0.clone();
        for (name, by) in [
            ("seat.z", 0.4),
            ("back.height", -0.7),
            ("left_arm.width", 1.3),
        ] {
            let i = m.slots.iter().position(|s| s.name == name).unwrap();
            truth[i] += by;
        }
        let want = picture(&truth);
        let mut loss = |x: &[f64]| -> f64 {
            picture(x)
                .iter()
                .zip(&want)
                .map(|(a, b)| (a - b) * (a - b))
                .sum()
        };
        assert!(loss(&p.x0) > 0.0);
        let x = refine(&p, p.x0.clone(), 1.0, 3, &mut loss, &|_| true);
        assert_eq!(loss(&x), 0.0, "faces off the target's pixels");
        // Numbers the picture does not ask to move stay put.
        let moved = (0..x.len())
            .filter(|&i| (x[i] - p.x0[i]).abs() > 1e-9 && truth[i] == p.x0[i])
            .map(|i| m.slots[i].name.as_str())
            .collect::<Vec<_>>();
        assert!(moved.is_empty(), "moved {moved:?}");
    }

    #[test]
    fn a_board_is_thinned_together_with_the_board_it_holds() {
        // A side 10 thick holding a bottom at its inner face; the "picture" wants the side
        // 5 thick and sees any gap between the two.
        let m = crate::front::test_model(
            "cube([10, 50, 50]);\ntranslate([10, 0, 0]) cube([80, 50, 5]);\n",
        );
        let p = Parametric::new(&m);
        let face = |x: &[f64], part: usize, high: bool| -> f64 {
            let f = p.faces[part]
                .iter()
                .find(|f| f.0 == 0 && f.1 == high)
                .unwrap();
            f.2.eval(x)
        };
        let mut loss = |x: &[f64]| -> f64 {
            let (inner, end) = (face(x, 0, true), face(x, 1, false));
            (inner - 5.0).powi(2) + 100.0 * (end - inner).powi(2)
        };
        let along_x = plane_groups(&p)
            .into_iter()
            .filter(|g| p.faces[g[0].0][g[0].1].0 == 0)
            .count();
        assert_eq!(along_x, 1, "one contact along x");
        let x = polish(&p, p.x0.clone(), 2, &mut loss, &|_| true);
        assert!(
            (face(&x, 0, true) - 5.0).abs() < 1e-9,
            "side {}",
            face(&x, 0, true)
        );
        assert!(
            (face(&x, 1, false) - 5.0).abs() < 1e-9,
            "bottom {}",
            face(&x, 1, false)
        );
        // The bottom's far end and the side's outer face stay.
        assert!((face(&x, 1, true) - 90.0).abs() < 1e-9);
        assert!(face(&x, 0, false).abs() < 1e-9);
    }

    #[test]
    fn a_part_the_target_lacks_is_squashed_in_one_sweep() {
        // The chair's left arm; the loss is its volume (and any other part's move).
        let m = chair();
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
        // As a picture would, the loss also sees every other part's faces move.
        let others = |x: &[f64]| -> f64 {
            (0..p.faces.len())
                .filter(|&q| q != arm)
                .flat_map(|q| p.faces[q].iter())
                .map(|f| (f.2.eval(x) - f.2.eval(&p.x0)).powi(2))
                .sum()
        };
        let v0 = volume(&p.x0);
        let x = polish(
            &p,
            p.x0.clone(),
            1,
            &mut |x: &[f64]| volume(x) + 1e6 * others(x),
            &|x| extents(x).iter().all(|&e| e > 0.0),
        );
        let v = volume(&x);
        assert!(v < 0.01 * v0, "arm volume {v0} -> {v}");
        // Nothing but the arm's numbers moved.
        let moved: Vec<&str> = (0..x.len())
            .filter(|&i| (x[i] - p.x0[i]).abs() > 1e-9 * p.scale)
            .map(|i| m.slots[i].name.as_str())
            .collect();
        assert!(moved.iter().all(|n| n.contains("arm")), "moved {moved:?}");
    }

    #[test]
    fn a_part_moved_whole_leaves_the_parts_its_wrapper_carries() {
        // Two parts in one translated group, as `.csg` writes them: the board's own
        // translation moves it, not the group's (which would move the block by half).
        let m = crate::front::test_model(
            "translate([0, 0, 5]) { cube([10, 10, 10]); translate([20, 0, 0]) cube([10, 10, 3]); }\n",
        );
        let p = Parametric::new(&m);
        let solve = part_solves(&p)[1][0].clone();
        let b = DVector::from_iterator(
            p.faces[1].len(),
            p.faces[1].iter().map(|f| f64::from(u8::from(f.0 == 2))),
        );
        let x: Vec<f64> =
            p.x0.iter()
                .zip((solve * b).iter())
                .map(|(a, d)| a + d)
                .collect();
        for f in &p.faces[1] {
            let want = f64::from(u8::from(f.0 == 2));
            assert!((f.2.eval(&x) - f.2.eval(&p.x0) - want).abs() < 1e-9);
        }
        for f in &p.faces[0] {
            assert!(
                (f.2.eval(&x) - f.2.eval(&p.x0)).abs() < 1e-9,
                "the block moved"
            );
        }
    }
}
