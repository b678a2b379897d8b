//! Parts a stage lost, offered back. A part whose extent along one of its own axes a stage
//! took under a pixel, though the stage started it at least [`LOST_FROM_PIXELS`] pixels
//! across, is lost ([`lost_parts`]); [`restored`] puts its placement and sizes back where
//! the stage found them. The fitter then runs the rest of the schedule, finishing passes
//! included, both from the stage's end and from that point with its lost parts back, and
//! returns the branch whose best point its judge prefers (`Fitter::run_from`, once per
//! fit). The branches are compared finished, not at the stage's end: the finishing passes
//! reorder them (a generated bookcase whose variant drops a shelf: at the stage's end the
//! run whose bottom board had grown over the first shelf led, 0.00281 against 0.00288; finished,
//! the branch with the shelves back ends at 0.00100 against 0.00145).
//!
//! Why: a gradient step sees only what is visible. A part shrunk under a pixel gets no
//! gradient back, and face moves in proportion to its extent ([`super::polish()`]) cannot
//! regrow it. Adam's steps are alike in world units for every number, so a part's small
//! size reaches its guard before a large misplacement of it is taken back (a bookcase's
//! shelves, a camera's lens). Judging the part put back after one more round was tried
//! and is not enough: a neighbour has grown over its pixels by then, and undoing that takes
//! the stages after.
//!
//! Invariant: the restoration is the least change of slots that puts every parameter of
//! the part (its placement and sizes) where it stood (other parts sharing those slots move
//! with it); `None` when they cannot be put back so.

use super::Parametric;
use super::options::LOST_FROM_PIXELS;
use crate::analysis::linalg;
use crate::ir::Affine;
use crate::render::scene::PartGeom;
use crate::tolerance::RELATIVE_EPSILON;

/// Part `p`'s extent along each of its own axes at `x`, in world units (0 for a part that
/// is not drawn there).
fn extents(geom: &PartGeom) -> [f64; 3] {
    if !geom.valid {
        return [0.0; 3];
    }
    std::array::from_fn(|a| geom.l.col(a).length() * (geom.hi[a] - geom.lo[a]).abs())
}

/// The parts lost between `start` and `end`: at least [`LOST_FROM_PIXELS`] pixels across
/// on each of their axes at `start`, under one pixel on some axis at `end` (`pixel`: the
/// finest view's pixel in world units).
pub fn lost_parts(problem: &Parametric, start: &[f64], end: &[f64], pixel: f64) -> Vec<usize> {
    let (before, after) = (problem.geoms(start), problem.geoms(end));
    (0..before.len())
        .filter(|&p| {
            let shown = extents(&before[p])
                .iter()
                .all(|&e| e >= LOST_FROM_PIXELS * pixel);
            let gone = extents(&after[p]).iter().any(|&e| e < pixel);
            shown && gone
        })
        .collect()
}

/// `x` with part `p`'s parameters (its placement and sizes) put back to their values at
/// `start`, by the least change of slots; `None` when that change does not put them back.
pub fn restored(problem: &Parametric, x: &[f64], start: &[f64], p: usize) -> Option<Vec<f64>> {
    let rows: Vec<&Affine> = problem.forms[p].iter().flatten().collect();
    let a = linalg::matrix(&rows, x.len());
    let b = nalgebra::DVector::from_iterator(
        rows.len(),
        rows.iter().map(|f| f.eval(start) - f.eval(x)),
    );
    let dx = linalg::pinv(&a) * &b;
    let cand: Vec<f64> = x.iter().zip(dx.iter()).map(|(v, d)| v + d).collect();
    let scale = problem.scale;
    rows.iter()
        .all(|f| (f.eval(&cand) - f.eval(start)).abs() <= RELATIVE_EPSILON * scale)
        .then_some(cand)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 10-unit cube with a 4-unit board beside it.
    fn cube_and_board() -> Parametric {
        let text = b"cube([10, 10, 10]);\ntranslate([10, 0, 0]) cube([4, 10, 10]);\n";
        let mut sources = crate::front::source::SourceMap::new();
        let path = std::path::Path::new("two.scad");
        let model = crate::front::load_model_text(&mut sources, path, text)
            .unwrap()
            .model;
        Parametric::new(&model)
    }

    /// `x` with the slot holding the board's width set to `width`.
    fn board_width(problem: &Parametric, width: f64) -> Vec<f64> {
        let mut x = problem.x0.clone();
        let i = x.iter().position(|&v| v == 4.0).unwrap();
        x[i] = width;
        x
    }

    #[test]
    fn a_part_shrunk_under_a_pixel_is_lost_and_put_back_where_it_stood() {
        let problem = cube_and_board();
        let start = problem.x0.clone();
        let end = board_width(&problem, 0.1);
        assert_eq!(lost_parts(&problem, &start, &end, 0.5), vec![1]);
        let back = restored(&problem, &end, &start, 1).unwrap();
        for f in problem.forms[1].iter().flatten() {
            assert!((f.eval(&back) - f.eval(&start)).abs() < 1e-9);
        }
        // The cube beside it keeps its numbers.
        for f in problem.forms[0].iter().flatten() {
            assert!((f.eval(&back) - f.eval(&end)).abs() < 1e-9);
        }
    }

    #[test]
    fn a_part_still_a_pixel_across_or_never_two_is_not_lost() {
        let problem = cube_and_board();
        let start = problem.x0.clone();
        // Shrunk, but still more than a pixel across.
        assert!(lost_parts(&problem, &start, &board_width(&problem, 0.6), 0.5).is_empty());
        // At pixels of 3 units the 4-unit board never was two pixels across.
        assert!(lost_parts(&problem, &start, &board_width(&problem, 0.1), 3.0).is_empty());
    }
}
