//! What a fit believes before it sees the pictures: the paper's pull
//! `λ‖(x − anchor)/size‖²` towards the model's own numbers, a size prior
//! `w·Σ ln²(s(x)/s(anchor))` over the parts' sizes `s` ([`Parametric::sizes`]), and a tie
//! prior `t·Σ ln(1 + (r(x)/p)²)` over the residuals `r` of the model's structural relations
//! ([`Parametric::ties`], `p` the finest pixel).
//!
//! The size prior is scale-free: a size is as likely to halve as to double, whatever its
//! magnitude. Where the pictures tell, it is negligible against the image loss (see
//! [`super::options::SIZE_PRIOR`]); where they barely do (a back panel behind the boards in
//! front of it, seen by one steep camera), a thin part keeps its proportion instead of
//! growing into the hollow before it, which its pictures hardly tell from the truth. A
//! part shrunk under [`DROP_RATIO`] of its size counts as dropped and is not pulled back.
//!
//! The tie prior is the structural prior ([`crate::analysis::prior`]) made soft: a contact,
//! a repeat or a coaxiality of the model is kept unless the pictures pull it apart. Its
//! pull is strongest at one pixel apart and fades beyond (a mixture of "the relation holds"
//! and "it is broken, by any amount"), so a shelf the pictures show only by its front edge
//! keeps the depth of the boards it is flush with, while a relation the pictures break by
//! many pixels costs a constant and does not hold the fit back.
//!
//! Invariants: every term is 0 at the anchor, with gradient 0; every size weighed is
//! positive at the anchor and read at no less than `floor`; sizes that always change by
//! the same ratio (the same form in several parts, or one a multiple of another) are
//! weighed once, and so are identical ties.

use super::options::FitOptions;
use super::parametric::Parametric;
use crate::ir::Affine;
use crate::tolerance::RELATIVE_ROUNDOFF;

/// A size under this fraction of the model's counts as a part the kind drops, as kinds of
/// an object may lack one (the generator's families do, and discovery's optional parts):
/// it costs what this fraction costs and is not pulled back, so the prior never holds up a
/// part the pictures lack. Above it a size costs the square of its log ratio.
pub const DROP_RATIO: f64 = 0.25;

/// The prior of a fit, set up for one problem.
#[derive(Debug, Clone)]
pub struct Prior {
    anchor: Vec<f64>,
    scale: f64,
    lambda: f64,
    /// The parts' sizes with their values at the anchor.
    sizes: Vec<(Affine, f64)>,
    size_weight: f64,
    /// The least a size is read as (a size guard keeps sizes above it anyway).
    floor: f64,
    /// The structural ties, each scaled to move as a face does (its largest coefficient
    /// 1), with its value at the anchor.
    ties: Vec<(Affine, f64)>,
    tie_weight: f64,
    /// A tie's residual is read in units of this length (the finest pixel).
    tie_unit: f64,
}

impl Prior {
    /// The prior of `problem` with `opts`' weights (`lambda`, `size_prior`, `tie_prior`);
    /// sizes are read as at least `opts.min_extent` of the model, ties' residuals in
    /// units of `pixel` world units.
    pub fn new(problem: &Parametric, opts: &FitOptions, pixel: f64) -> Prior {
        let mut sizes: Vec<(Affine, f64)> = Vec::new();
        for f in problem.sizes() {
            let at = f.eval(&problem.anchor);
            if !sizes.iter().any(|(g, g_at)| same_ratio(&f, at, g, *g_at)) {
                sizes.push((f, at));
            }
        }
        let mut ties: Vec<(Affine, f64)> = Vec::new();
        for t in &problem.ties {
            let big = t.terms.iter().map(|(_, c)| c.abs()).fold(0.0, f64::max);
            if big == 0.0 {
                continue;
            }
            let t = t.scale(1.0 / big);
            if !ties.iter().any(|(u, _)| same_row(&t, u)) {
                let at = t.eval(&problem.anchor);
                ties.push((t, at));
            }
        }
        Prior {
            anchor: problem.anchor.clone(),
            scale: problem.scale,
            lambda: opts.lambda,
            sizes,
            size_weight: opts.size_prior,
            floor: (opts.min_extent * problem.scale).max(f64::MIN_POSITIVE),
            ties,
            tie_weight: opts.tie_prior,
            tie_unit: pixel.max(f64::MIN_POSITIVE),
        }
    }

    /// The prior's value at `x` and its gradient over the slots.
    pub fn at(&self, x: &[f64]) -> (f64, Vec<f64>) {
        let mut v = 0.0;
        let mut g = vec![0.0; x.len()];
        for (i, (xi, ai)) in x.iter().zip(&self.anchor).enumerate() {
            let r = (xi - ai) / self.scale;
            v += self.lambda * r * r;
            g[i] = 2.0 * self.lambda * r / self.scale;
        }
        if self.size_weight > 0.0 {
            v += self.sizes_at(x, &mut g);
        }
        if self.tie_weight > 0.0 {
            v += self.ties_at(x, &mut g);
        }
        (v, g)
    }

    /// The size prior at `x`, its gradient added to `g`.
    fn sizes_at(&self, x: &[f64], g: &mut [f64]) -> f64 {
        let dropped = DROP_RATIO.ln();
        let mut v = 0.0;
        for (f, at) in &self.sizes {
            let s = f.eval(x).max(self.floor);
            let l = (s / at).ln();
            if l <= dropped {
                v += self.size_weight * dropped * dropped;
                continue;
            }
            v += self.size_weight * l * l;
            add_form(g, f, 2.0 * self.size_weight * l / s);
        }
        v
    }

    /// The tie prior at `x`: `w·ln(1 + u²)` per tie pulled `u` units apart, its gradient
    /// added to `g`. It resists most at one unit and ever less beyond: a tie the pictures
    /// break by many pixels costs about the same however far it is broken.
    fn ties_at(&self, x: &[f64], g: &mut [f64]) -> f64 {
        let mut v = 0.0;
        for (t, at) in &self.ties {
            let u = (t.eval(x) - at) / self.tie_unit;
            v += self.tie_weight * (1.0 + u * u).ln();
            add_form(
                g,
                t,
                2.0 * self.tie_weight * u / ((1.0 + u * u) * self.tie_unit),
            );
        }
        v
    }
}

/// Adds `k` times form `f`'s gradient to `g`.
fn add_form(g: &mut [f64], f: &Affine, k: f64) {
    for &(slot, c) in &f.terms {
        g[slot as usize] += k * c;
    }
}

/// Whether rows `a` and `b` are the same relation (equal, or one the negation of the other).
fn same_row(a: &Affine, b: &Affine) -> bool {
    let close = |x: f64, y: f64| (x - y).abs() <= RELATIVE_ROUNDOFF * x.abs().max(y.abs()).max(1.0);
    termwise(a, b, close) || termwise(a, b, |x, y| close(x, -y))
}

/// Whether sizes `f` and `g` (`f_at` and `g_at` at the anchor) change by the same ratio
/// wherever the slots go: `f/f_at = g/g_at` term by term. One design decision (the legs'
/// thickness, a board size every board shares) is then weighed once, however many parts
/// carry it.
fn same_ratio(f: &Affine, f_at: f64, g: &Affine, g_at: f64) -> bool {
    let close = |a: f64, b: f64| (a - b).abs() <= RELATIVE_ROUNDOFF * a.abs().max(b.abs());
    termwise(f, g, |a, b| close(a / f_at, b / g_at))
}

/// Whether forms `f` and `g` have the same slots and `close` holds between their constants
/// and between each pair of coefficients.
fn termwise(f: &Affine, g: &Affine, close: impl Fn(f64, f64) -> bool) -> bool {
    f.terms.len() == g.terms.len()
        && close(f.constant, g.constant)
        && f.terms
            .iter()
            .zip(&g.terms)
            .all(|(&(s, a), &(t, b))| s == t && close(a, b))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The prior of `p` with these weights, sizes read as at least 0.01, ties in units of 1.
    fn weighed(p: &Parametric, lambda: f64, sizes: f64, ties: f64) -> Prior {
        let opts = FitOptions {
            lambda,
            size_prior: sizes,
            tie_prior: ties,
            min_extent: 0.01 / p.scale,
            ..FitOptions::default()
        };
        Prior::new(p, &opts, 1.0)
    }

    /// The first slot whose value at the anchor is `v`.
    fn slot_of(p: &Parametric, v: f64) -> usize {
        p.anchor
            .iter()
            .position(|&a| a == v)
            .unwrap_or_else(|| panic!("a slot of {v}"))
    }

    /// The anchor with the slots in `changes` set to their values.
    fn anchor_with(p: &Parametric, changes: &[(usize, f64)]) -> Vec<f64> {
        let mut x = p.anchor.clone();
        for &(slot, v) in changes {
            x[slot] = v;
        }
        x
    }

    fn board() -> Parametric {
        let src = "cube([40, 20, 2]);\ntranslate([0, 0, 2]) cube([40, 2, 30]);\n";
        Parametric::new(&crate::front::test_model(src))
    }

    #[test]
    fn zero_at_the_anchor_with_no_slope() {
        let p = board();
        let prior = weighed(&p, 0.001, 1e-5, 1e-5);
        let (v, g) = prior.at(&p.anchor);
        assert_eq!(v, 0.0);
        assert!(g.iter().all(|&d| d == 0.0));
    }

    #[test]
    fn halving_a_size_costs_what_doubling_it_does() {
        let p = board();
        let prior = weighed(&p, 0.0, 1e-5, 0.0);
        let thin = slot_of(&p, 2.0);
        let cost = |k: f64| prior.at(&anchor_with(&p, &[(thin, 2.0 * k)])).0;
        assert!(cost(2.0) > 0.0);
        assert!((cost(2.0) - cost(0.5)).abs() < 1e-12 * cost(2.0).max(1e-300) + 1e-15);
        // The same absolute growth of a thick size costs far less.
        let thick = slot_of(&p, 40.0);
        assert!(prior.at(&anchor_with(&p, &[(thick, 42.0)])).0 < cost(2.0) / 100.0);
    }

    #[test]
    fn a_part_squashed_past_the_drop_ratio_is_not_pulled_back() {
        let p = board();
        let prior = weighed(&p, 0.0, 1e-5, 0.0);
        let thin = slot_of(&p, 2.0);
        let at = |k: f64| prior.at(&anchor_with(&p, &[(thin, 2.0 * k)]));
        let (quarter, _) = at(DROP_RATIO);
        let (gone, slope) = at(0.05);
        assert!((gone - quarter).abs() <= 1e-12 * quarter);
        assert_eq!(slope[thin], 0.0);
        // Just above the ratio it still pulls the size back up (a negative slope).
        assert!(at(DROP_RATIO * 1.1).1[thin] < 0.0);
    }

    #[test]
    fn a_size_many_parts_share_is_weighed_once() {
        let legs = |n: usize| {
            let mut src = String::from("w = 4;\n");
            for i in 0..n {
                src += &format!("translate([{}, 0, 0]) cube([w, w, 30]);\n", 10 * i);
            }
            Parametric::new(&crate::front::test_model(&src))
        };
        let cost = |p: &Parametric| {
            let prior = weighed(p, 0.0, 1e-5, 0.0);
            prior.at(&anchor_with(p, &[(slot_of(p, 4.0), 8.0)])).0
        };
        let one = cost(&legs(1));
        assert!(one > 0.0);
        assert!((cost(&legs(4)) - one).abs() <= 1e-12 * one);
    }

    #[test]
    fn a_tie_resists_most_near_one_unit_and_little_once_broken() {
        // The upright stands on the board: its height off the floor is the board's
        // thickness (both 3, two slots).
        let p = Parametric::new(&crate::front::test_model(
            "cube([40, 20, 3]);\ntranslate([0, 0, 3]) cube([40, 5, 30]);\n",
        ));
        let prior = weighed(&p, 0.0, 0.0, 1e-5);
        let threes: Vec<usize> = (0..p.anchor.len())
            .filter(|&i| p.anchor[i] == 3.0)
            .collect();
        assert_eq!(threes.len(), 2);
        let at = |thick: f64, lift: f64| {
            prior.at(&anchor_with(
                &p,
                &[(threes[0], 3.0 + thick), (threes[1], 3.0 + lift)],
            ))
        };
        // Moving both keeps the contact: nothing to pay.
        assert_eq!(at(1.0, 1.0).0, 0.0);
        // Parting them costs, and the pull back is strongest near one unit.
        let (near, near_slope) = at(1.0, 0.0);
        let (far, far_slope) = at(20.0, 0.0);
        assert!(near > 0.0 && far > near);
        assert!(near_slope[threes[0]].abs() > 5.0 * far_slope[threes[0]].abs());
        assert!(far_slope[threes[0]].abs() > 0.0);
    }

    #[test]
    fn gradient_matches_differences() {
        let p = board();
        let prior = weighed(&p, 0.001, 1e-5, 1e-5);
        let x: Vec<f64> = p.anchor.iter().map(|v| v * 1.3 + 0.7).collect();
        let (_, g) = prior.at(&x);
        for i in 0..x.len() {
            let h = 1e-5;
            let (mut a, mut b) = (x.clone(), x.clone());
            a[i] += h;
            b[i] -= h;
            let fd = (prior.at(&a).0 - prior.at(&b).0) / (2.0 * h);
            assert!(
                (fd - g[i]).abs() <= 1e-6 * g[i].abs().max(1e-9),
                "slot {i}: {fd} vs {}",
                g[i]
            );
        }
    }
}
