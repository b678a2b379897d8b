//! Moves of whole parts in the finishing passes ([`sweep_parts`]): a part misplaced by more
//! than its own thickness covers none of the picture's pixels of it, so no gradient and no
//! face move reaches them. Each part is moved along its thinnest axis by multiples of its
//! thickness and onto its siblings; a move is kept when the fine loss drops, or, a jump
//! onto a sibling, when soft edges prefer it in the lighting fitted where it lands and,
//! settled there by small moves of that part, the fine loss drops in the lighting fitted
//! where it settled ([`Judge`]).
//!
//! Invariants: a part move changes only the part's faces along one axis, each by the same
//! shift (through the changes of slots [`super::polish`] works out, round-off removed); a
//! settling move changes only that part's faces along that axis. Every move kept lowers
//! the loss under [`Edges::Fine`].

use super::Parametric;
use super::polish::{extent_along, face_moves, spans, step};
use crate::tolerance::RELATIVE_EPSILON;
use nalgebra::{DMatrix, DVector};

/// How soft the edges are that a finishing move is judged with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Edges {
    /// The finishing passes' own (the last round's softness): what every move is kept by.
    Fine,
    /// The first round's softness: a part a few pixels from its place in the picture
    /// already overlaps it there, so nearer is better before it is on it.
    Coarse,
}

/// What the finishing passes ask of the loss they are judged by.
pub trait Judge {
    /// The loss at `x` with `edges`, under the lighting the judge stands in.
    fn loss(&mut self, x: &[f64], edges: Edges) -> f64;
    /// Stand in the lighting fitted at `x` (each view's shading, each part's albedo) or,
    /// with `None`, in the lighting last kept ([`Judge::keep_light`]; at first, the one
    /// the passes started in).
    fn light_at(&mut self, x: Option<&[f64]>);
    /// Keep the lighting the judge stands in: a move was kept in it.
    fn keep_light(&mut self);
}

/// A loss with no lighting of its own: every edge the same, nothing to refit.
impl<F: FnMut(&[f64]) -> f64> Judge for F {
    fn loss(&mut self, x: &[f64], _: Edges) -> f64 {
        self(x)
    }
    fn light_at(&mut self, _: Option<&[f64]>) {}
    fn keep_light(&mut self) {}
}

/// Moves of a whole part tried by [`sweep_parts`], as multiples of its extent along the axis
/// it is moved along, each both ways.
const PART_MOVES: [f64; 8] = [0.5, 1.0, 1.5, 2.0, 3.0, 4.0, 6.0, 8.0];

/// One pass over the parts: each is moved whole along its thinnest axis (every face of it
/// along that axis by the same shift, through each of its changes of slots `solves`) by
/// [`PART_MOVES`] of its extent there and onto each of its siblings ([`sibling_shifts`]),
/// and the best move is kept when the fine loss drops below `best`. Else the moves onto a
/// sibling are tried as jumps ([`jump`]), judged in the lighting fitted where they land.
/// A part misplaced by more than its own thickness covers none of the picture's pixels of
/// it: a shelf a few of its thicknesses above the picture's shelf, or stacked onto another
/// where the picture has one shelf fewer. Whether any move was kept (`best` is then the
/// fine loss in the lighting the judge stands in).
pub(super) fn sweep_parts(
    problem: &Parametric,
    solves: &[Vec<DMatrix<f64>>],
    x: &mut Vec<f64>,
    best: &mut f64,
    judge: &mut dyn Judge,
    ok: &dyn Fn(&[f64]) -> bool,
) -> bool {
    let mut improved = false;
    for (p, solves) in solves.iter().enumerate() {
        let Some((axis, extent)) = thinnest_axis(problem, p, x) else {
            continue;
        };
        let multiples: Vec<f64> = PART_MOVES
            .iter()
            .flat_map(|f| [f * extent, -f * extent])
            .collect();
        let siblings = sibling_shifts(problem, p, axis, x);
        let onto = shifted(problem, p, axis, solves, x, &siblings);
        let judged: Vec<(f64, Vec<f64>, bool)> = shifted(problem, p, axis, solves, x, &multiples)
            .into_iter()
            .map(|c| (c, false))
            .chain(onto.into_iter().map(|c| (c, true)))
            .filter(|(c, _)| ok(c))
            .map(|(c, sibling)| (judge.loss(&c, Edges::Fine), c, sibling))
            .collect();
        let kept = lowest_below(&judged, *best).or_else(|| {
            let tries = jump_tries(judged, &|c| is_jump(problem, (p, axis), x, c));
            jump(problem, (p, axis), solves, x, tries, judge, ok)
        });
        if let Some((l, cand)) = kept {
            *best = l;
            *x = cand;
            improved = true;
        }
    }
    improved
}

/// Of the moves `judged` (each with its loss), the first with the lowest loss, when that is
/// below `best`.
fn lowest_below(judged: &[(f64, Vec<f64>, bool)], best: f64) -> Option<(f64, Vec<f64>)> {
    judged
        .iter()
        .filter(|j| j.0 < best)
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|c| (c.0, c.1.clone()))
}

/// Of a part's moves that no fine loss kept (each with its loss in the lighting the judge
/// stands in and whether it is onto a sibling), those tried as jumps: of the moves `far`
/// says are jumps, every move onto a sibling and the [`JUMP_SCREEN`] multiples of its thickness that lighting judged best
/// (it misjudges a part moved where the picture has it, not which of the places it
/// could go shows a part at all).
fn jump_tries(judged: Vec<(f64, Vec<f64>, bool)>, far: &dyn Fn(&[f64]) -> bool) -> Vec<Vec<f64>> {
    let mut judged: Vec<_> = judged.into_iter().filter(|j| far(&j.1)).collect();
    judged.sort_by(|a, b| b.2.cmp(&a.2).then(a.0.total_cmp(&b.0)));
    let siblings = judged.iter().filter(|j| j.2).count();
    judged
        .into_iter()
        .take(siblings + JUMP_SCREEN)
        .map(|j| j.1)
        .collect()
}

/// How many moves by multiples of a part's thickness [`jump_tries`] passes on.
const JUMP_SCREEN: usize = 3;

/// The points `x` with part `p` moved whole along `axis` by each of `shifts` (every face of
/// it along `axis` by the same shift, its other faces kept), through each of its changes of
/// slots `solves`; those that move every face of the part as asked.
fn shifted(
    problem: &Parametric,
    p: usize,
    axis: u8,
    solves: &[DMatrix<f64>],
    x: &[f64],
    shifts: &[f64],
) -> Vec<Vec<f64>> {
    let faces = &problem.faces[p];
    let extent = extent_along(problem, p, axis, x);
    let along: Vec<f64> = faces
        .iter()
        .map(|f| f64::from(u8::from(f.0 == axis)))
        .collect();
    shifts
        .iter()
        .flat_map(|&shift| solves.iter().map(move |solve| (shift, solve)))
        .filter_map(|(shift, solve)| {
            let b = DVector::from_iterator(faces.len(), along.iter().map(|a| a * shift));
            let (_, cand) = step(x, solve, &b, shift);
            let moved = faces.iter().zip(b.iter()).all(|(f, want)| {
                (f.2.eval(&cand) - f.2.eval(x) - want).abs() <= RELATIVE_EPSILON * extent
            });
            moved.then_some(cand)
        })
        .collect()
}

/// Of `moves` of part `p` along its axis ([`jump_tries`]), the one [`Edges::Coarse`]
/// judges best, each in the lighting fitted where it lands, when that is better than `x`
/// in its own: settled there ([`settle`]), and kept when the fine loss, in the lighting
/// fitted where it settled, is below `x`'s in its own. The judge then stands in the
/// settled point's lighting; else in the one it stood in. The fine loss and the point.
///
/// The lighting is refitted because a misplaced part's albedo was fitted to what it
/// covers (a shelf over the back panel takes the panel's shade), and in that lighting the
/// part where the picture has it looks wrong.
fn jump(
    problem: &Parametric,
    (p, axis): (usize, u8),
    solves: &[DMatrix<f64>],
    x: &[f64],
    moves: Vec<Vec<f64>>,
    judge: &mut dyn Judge,
    ok: &dyn Fn(&[f64]) -> bool,
) -> Option<(f64, Vec<f64>)> {
    if moves.is_empty() {
        return None;
    }
    let here = lit(judge, x, Edges::Coarse);
    let mut coarse = |c: &[f64]| lit(judge, c, Edges::Coarse);
    let landed = super::best_improvement(moves, here, &mut coarse, ok);
    let kept = landed.and_then(|(_, landed)| {
        let base = lit(judge, x, Edges::Fine);
        judge.light_at(Some(&landed));
        let mut fine = |c: &[f64]| judge.loss(c, Edges::Fine);
        let (_, settled) = settle(problem, (p, axis), solves, landed, &mut fine, ok);
        let l = lit(judge, &settled, Edges::Fine);
        (l < base).then_some((l, settled))
    });
    match kept {
        Some(_) => judge.keep_light(),
        None => judge.light_at(None),
    }
    kept
}

/// Whether `cand` moves part `p` along `axis` by at least its extent from where it stands at
/// `x`: a jump ([`jump`]); shorter moves are the fine loss's to judge.
fn is_jump(problem: &Parametric, (p, axis): (usize, u8), x: &[f64], cand: &[f64]) -> bool {
    let extent = extent_along(problem, p, axis, x);
    let low = |x: &[f64]| spans(problem, p, x)[usize::from(axis)].0;
    (low(cand) - low(x)).abs() >= extent * (1.0 - RELATIVE_EPSILON)
}

/// The loss at `x` with `edges` in the lighting fitted at `x`.
fn lit(judge: &mut dyn Judge, x: &[f64], edges: Edges) -> f64 {
    judge.light_at(Some(x));
    judge.loss(x, edges)
}

/// Moves of a whole part tried by [`settle`], as fractions of its extent, each both ways.
const SETTLE_MOVES: [f64; 4] = [0.125, 0.25, 0.5, 1.0];

/// Moves of one face tried by [`settle`], as fractions of the part's extent (negative:
/// inwards).
const SETTLE_FACE_MOVES: [f64; 7] = [-0.5, -0.25, -0.1, 0.1, 0.25, 0.5, 1.0];

/// At most this many rounds of [`settle`]'s moves.
const SETTLE_ROUNDS: usize = 8;

/// Part `p`, just moved near where the picture has it, brought onto it by the fine loss:
/// the part moved whole along `axis` by [`SETTLE_MOVES`] of its extent and each of its
/// faces along `axis` by [`SETTLE_FACE_MOVES`] (its thickness may differ from the
/// picture's), the best kept while the loss drops, at most [`SETTLE_ROUNDS`] times. The
/// loss and the point.
fn settle(
    problem: &Parametric,
    (p, axis): (usize, u8),
    solves: &[DMatrix<f64>],
    mut x: Vec<f64>,
    loss: &mut dyn FnMut(&[f64]) -> f64,
    ok: &dyn Fn(&[f64]) -> bool,
) -> (f64, Vec<f64>) {
    let mut best = loss(&x);
    let faces = |extent: f64, out: f64| -> Vec<f64> {
        SETTLE_FACE_MOVES.iter().map(|f| out * f * extent).collect()
    };
    for _ in 0..SETTLE_ROUNDS {
        let extent = extent_along(problem, p, axis, &x);
        if !(extent.is_finite() && extent > 0.0) {
            break;
        }
        let shifts: Vec<f64> = SETTLE_MOVES
            .iter()
            .flat_map(|f| [f * extent, -f * extent])
            .collect();
        let mut moves = shifted(problem, p, axis, solves, &x, &shifts);
        for (j, face) in problem.faces[p].iter().enumerate() {
            if face.0 == axis {
                moves.extend(face_moves(problem, p, j, solves, &x, &faces));
            }
        }
        match super::best_improvement(moves, best, loss, ok) {
            Some((l, cand)) => (best, x) = (l, cand),
            None => break,
        }
    }
    (best, x)
}

/// Shifts along `axis` that put part `p` where a sibling of it is: another part about as
/// thick along `axis` (within a factor of two) whose span overlaps `p`'s across the other
/// two axes (one shelf above another), its low face onto the sibling's. A part the picture
/// lacks (one shelf fewer) then hides inside a sibling, which the gradient cannot do: on
/// the way every position costs more than where the part stands.
fn sibling_shifts(problem: &Parametric, p: usize, axis: u8, x: &[f64]) -> Vec<f64> {
    let own = spans(problem, p, x);
    let thick = own[usize::from(axis)].1 - own[usize::from(axis)].0;
    (0..problem.faces.len())
        .filter(|&q| q != p)
        .filter_map(|q| {
            let other = spans(problem, q, x);
            let t = other[usize::from(axis)].1 - other[usize::from(axis)].0;
            let alike = t > 0.5 * thick && t < 2.0 * thick;
            let across = (0..3)
                .filter(|&a| a != usize::from(axis))
                .all(|a| own[a].1.min(other[a].1) > own[a].0.max(other[a].0));
            (alike && across).then(|| other[usize::from(axis)].0 - own[usize::from(axis)].0)
        })
        .filter(|shift| shift.abs() > 0.0)
        .collect()
}

/// Part `p`'s thinnest axis at `x` among those a slot moves a face of, with its extent
/// there (`None` when no such axis has a positive extent).
fn thinnest_axis(problem: &Parametric, p: usize, x: &[f64]) -> Option<(u8, f64)> {
    (0..3u8)
        .filter(|&a| {
            problem.faces[p]
                .iter()
                .any(|f| f.0 == a && !f.2.is_constant())
        })
        .map(|a| (a, extent_along(problem, p, a, x)))
        .filter(|(_, e)| e.is_finite() && *e > 0.0)
        .min_by(|a, b| a.1.total_cmp(&b.1))
}

#[cfg(test)]
mod tests {
    use super::super::polish::polish;
    use super::*;

    /// How far the faces of `parts` across z moved from the model's numbers (squared), the
    /// shelf tests' stand-in for every other edge a picture shows.
    fn moved_across_z(p: &Parametric, parts: &[usize], x: &[f64]) -> f64 {
        parts
            .iter()
            .flat_map(|&q| p.faces[q].iter().filter(|f| f.0 != 2))
            .map(|f| (f.2.eval(x) - f.2.eval(&p.x0)).powi(2))
            .sum()
    }

    #[test]
    fn a_shelf_three_thicknesses_off_is_moved_onto_the_pictures() {
        // A 3-thick shelf at z 30; the "picture" has it at z 40 and sees, along z, the
        // length of what the two cover apart (no overlap: no gradient), and every other
        // face's move.
        let m = crate::front::test_model("translate([0, 0, 30]) cube([80, 50, 3]);\n");
        let p = Parametric::new(&m);
        let along_z = |x: &[f64]| spans(&p, 0, x)[2];
        let mut loss = |x: &[f64]| -> f64 {
            let (lo, hi) = along_z(x);
            let overlap = (hi.min(43.0) - lo.max(40.0)).max(0.0);
            (hi - lo) + 3.0 - 2.0 * overlap + 1e3 * moved_across_z(&p, &[0], x)
        };
        let x = polish(&p, p.x0.clone(), 3, &mut loss, &|x| {
            let (lo, hi) = along_z(x);
            hi > lo
        });
        let (lo, hi) = along_z(&x);
        assert!(
            (lo - 40.0).abs() < 0.3 && (hi - 43.0).abs() < 0.3,
            "shelf at {lo}..{hi}"
        );
    }

    #[test]
    fn a_shelf_the_picture_lacks_hides_in_its_sibling() {
        // Two shelves; the "picture" has only the upper one and sees, along z, what the
        // shelves cover apart from it. Squashing the lower one leaves a sliver; moving it
        // any few thicknesses costs as much as where it stands.
        let m = crate::front::test_model(
            "translate([0, 0, 30]) cube([80, 50, 3]);\ntranslate([0, 0, 90]) cube([80, 50, 3]);\n",
        );
        let p = Parametric::new(&m);
        let span = |x: &[f64], q: usize| spans(&p, q, x)[2];
        let mut loss = |x: &[f64]| -> f64 {
            let (a, b) = (span(x, 0), span(x, 1));
            // Covered length of the union, less twice its overlap with [90, 93], plus 3.
            let union = (a.1 - a.0) + (b.1 - b.0) - (a.1.min(b.1) - a.0.max(b.0)).max(0.0);
            let hit = |s: (f64, f64)| (s.1.min(93.0) - s.0.max(90.0)).max(0.0);
            let both = (a.1.min(b.1).min(93.0) - a.0.max(b.0).max(90.0)).max(0.0);
            let seen = hit(a) + hit(b) - both;
            union + 3.0 - 2.0 * seen + 1e3 * moved_across_z(&p, &[0, 1], x)
        };
        let x = polish(&p, p.x0.clone(), 2, &mut loss, &|x| {
            (0..2).all(|q| span(x, q).1 > span(x, q).0)
        });
        assert!(loss(&x) < 1e-9, "lower shelf at {:?}", span(&x, 0));
    }

    /// A loss with a lighting of its own, the shelf test's picture: a shelf at z 90 on a
    /// background. Part 0's albedo `a` is what its lighting fits: the picture's mean
    /// brightness over what part 0 covers (1 on the shelf, 0 off it). Along z the loss
    /// counts what the parts cover apart from the picture's shelf and, over part 0, how far
    /// `a` is from the picture's brightness.
    struct Lit<'a> {
        p: &'a Parametric,
        a: f64,
        kept: f64,
    }

    impl Lit<'_> {
        fn span(&self, x: &[f64], q: usize) -> (f64, f64) {
            spans(self.p, q, x)[2]
        }
        fn on_shelf(s: (f64, f64)) -> f64 {
            (s.1.min(93.0) - s.0.max(90.0)).max(0.0)
        }
    }

    impl Judge for Lit<'_> {
        fn loss(&mut self, x: &[f64], _: Edges) -> f64 {
            let (a, b) = (self.span(x, 0), self.span(x, 1));
            let union = (a.1 - a.0) + (b.1 - b.0) - (a.1.min(b.1) - a.0.max(b.0)).max(0.0);
            let both = (a.1.min(b.1).min(93.0) - a.0.max(b.0).max(90.0)).max(0.0);
            let seen = Self::on_shelf(a) + Self::on_shelf(b) - both;
            let on = Self::on_shelf(a);
            let shade = on * (1.0 - self.a).powi(2) + (a.1 - a.0 - on) * self.a.powi(2);
            union + 3.0 - 2.0 * seen + shade + 1e3 * moved_across_z(self.p, &[0, 1], x)
        }
        fn light_at(&mut self, x: Option<&[f64]>) {
            self.a = match x {
                Some(x) => {
                    let s = self.span(x, 0);
                    Self::on_shelf(s) / (s.1 - s.0)
                }
                None => self.kept,
            };
        }
        fn keep_light(&mut self) {
            self.kept = self.a;
        }
    }

    #[test]
    fn a_jump_is_judged_in_the_lighting_fitted_where_it_lands() {
        // The lower shelf, which the picture lacks, was lit where it stands: its albedo is
        // the background's, so onto its sibling it looks dark on a bright shelf and no
        // move is better in that lighting. Lit where it lands, it hides in its sibling.
        let m = crate::front::test_model(
            "translate([0, 0, 30]) cube([80, 50, 3]);\ntranslate([0, 0, 90]) cube([80, 50, 3]);\n",
        );
        let p = Parametric::new(&m);
        let mut judge = Lit {
            p: &p,
            a: 0.0,
            kept: 0.0,
        };
        let ok = |x: &[f64]| (0..2).all(|q| spans(&p, q, x)[2].1 > spans(&p, q, x)[2].0);
        let start = judge.loss(&p.x0, Edges::Fine);
        let x = polish(&p, p.x0.clone(), 2, &mut judge, &ok);
        let (lower, upper) = (spans(&p, 0, &x)[2], spans(&p, 1, &x)[2]);
        assert!(
            lower.0 >= upper.0 - 1e-9 && lower.1 <= upper.1 + 1e-9,
            "lower shelf at {lower:?}, upper at {upper:?}"
        );
        assert!(judge.loss(&x, Edges::Fine) < start);
    }
}
