//! What a fit believes before it sees the pictures: the paper's pull
//! `λ‖(x − anchor)/size‖²` towards the model's own numbers, and a size prior `w·Σ ln²(s(x)/s(anchor))` over the
//! parts' sizes `s` ([`Parametric::sizes`]).
//!
//! The size prior is scale-free: a size is as likely to halve as to double, whatever its
//! magnitude. Where the pictures tell, it is negligible against the image loss (see
//! [`super::options::SIZE_PRIOR`]); where they barely do (a back panel behind the boards in
//! front of it, seen by one steep camera), a thin part keeps its proportion instead of
//! growing into the hollow before it, which its pictures hardly tell from the truth. A
//! part shrunk under [`DROP_RATIO`] of its size counts as dropped and is not pulled back.
//!
//! Invariants: both terms are 0 at the anchor, with gradient 0; every size weighed is
//! positive at the anchor and read at no less than `floor`; sizes that always change by
//! the same ratio (the same form in several parts, or one a multiple of another) are
//! weighed once.

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
}

impl Prior {
    /// The prior of `problem` with the pull's weight `lambda` and the size prior's
    /// `size_weight`; sizes are read as at least `floor` world units.
    pub fn new(problem: &Parametric, lambda: f64, size_weight: f64, floor: f64) -> Prior {
        let mut sizes: Vec<(Affine, f64)> = Vec::new();
        for f in problem.sizes() {
            let at = f.eval(&problem.anchor);
            if !sizes.iter().any(|(g, g_at)| same_ratio(&f, at, g, *g_at)) {
                sizes.push((f, at));
            }
        }
        Prior {
            anchor: problem.anchor.clone(),
            scale: problem.scale,
            lambda,
            sizes,
            size_weight,
            floor: floor.max(f64::MIN_POSITIVE),
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
            let dropped = DROP_RATIO.ln();
            for (f, at) in &self.sizes {
                let s = f.eval(x).max(self.floor);
                let l = (s / at).ln();
                if l <= dropped {
                    v += self.size_weight * dropped * dropped;
                    continue;
                }
                v += self.size_weight * l * l;
                let k = 2.0 * self.size_weight * l / s;
                for slot in f.slots() {
                    g[slot as usize] += k * f.coeff(slot);
                }
            }
        }
        (v, g)
    }
}

/// Whether sizes `f` and `g` (`f_at` and `g_at` at the anchor) change by the same ratio
/// wherever the slots go: `f/f_at = g/g_at` term by term. One design decision (the legs'
/// thickness, a board size every board shares) is then weighed once, however many parts
/// carry it.
fn same_ratio(f: &Affine, f_at: f64, g: &Affine, g_at: f64) -> bool {
    let close = |a: f64, b: f64| (a - b).abs() <= RELATIVE_ROUNDOFF * a.abs().max(b.abs());
    f.terms.len() == g.terms.len()
        && close(f.constant / f_at, g.constant / g_at)
        && f.terms
            .iter()
            .zip(&g.terms)
            .all(|(&(s, a), &(t, b))| s == t && close(a / f_at, b / g_at))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn board() -> Parametric {
        let src = "cube([40, 20, 2]);\ntranslate([0, 0, 2]) cube([40, 2, 30]);\n";
        Parametric::new(&crate::front::test_model(src))
    }

    #[test]
    fn zero_at_the_anchor_with_no_slope() {
        let p = board();
        let prior = Prior::new(&p, 0.001, 1e-5, 0.01);
        let (v, g) = prior.at(&p.anchor);
        assert_eq!(v, 0.0);
        assert!(g.iter().all(|&d| d == 0.0));
    }

    #[test]
    fn halving_a_size_costs_what_doubling_it_does() {
        let p = board();
        let prior = Prior::new(&p, 0.0, 1e-5, 0.01);
        let thin = p
            .anchor
            .iter()
            .position(|&v| v == 2.0)
            .expect("a slot of 2");
        let cost = |k: f64| {
            let mut x = p.anchor.clone();
            x[thin] *= k;
            prior.at(&x).0
        };
        assert!(cost(2.0) > 0.0);
        assert!((cost(2.0) - cost(0.5)).abs() < 1e-12 * cost(2.0).max(1e-300) + 1e-15);
        // The same absolute growth of a thick size costs far less.
        let thick = p
            .anchor
            .iter()
            .position(|&v| v == 40.0)
            .expect("a slot of 40");
        let mut x = p.anchor.clone();
        x[thick] += 2.0;
        assert!(prior.at(&x).0 < cost(2.0) / 100.0);
    }

    #[test]
    fn a_part_squashed_past_the_drop_ratio_is_not_pulled_back() {
        let p = board();
        let prior = Prior::new(&p, 0.0, 1e-5, 0.01);
        let thin = p
            .anchor
            .iter()
            .position(|&v| v == 2.0)
            .expect("a slot of 2");
        let at = |k: f64| {
            let mut x = p.anchor.clone();
            x[thin] = 2.0 * k;
            prior.at(&x)
        };
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
            let prior = Prior::new(p, 0.0, 1e-5, 0.01);
            let w = p
                .anchor
                .iter()
                .position(|&v| v == 4.0)
                .expect("a slot of 4");
            let mut x = p.anchor.clone();
            x[w] = 8.0;
            prior.at(&x).0
        };
        let one = cost(&legs(1));
        assert!(one > 0.0);
        assert!((cost(&legs(4)) - one).abs() <= 1e-12 * one);
    }

    #[test]
    fn gradient_matches_differences() {
        let p = board();
        let prior = Prior::new(&p, 0.001, 1e-5, 0.01);
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
