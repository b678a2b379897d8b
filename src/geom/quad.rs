//! One-dimensional adaptive quadrature for piecewise-smooth integrands.
//!
//! [`integrate`] computes `∫ₐᵇ f` for an `f` that returns a value ([`V3`]) and a
//! *signature*: a hash of the structure that produced the value (which surfaces bound which
//! stretches). Where the signature is constant, `f` is analytic inside the piece, except for
//! square-root behaviour at the piece's ends (a ray grazing a curved surface there); so:
//!
//! - every piece is integrated with Gauss–Kronrod 10/21 (7/15 for pieces narrower than
//!   [`Tol::short`] of the whole) after the substitution `y = a + (b − a)·sin²(πu/2)`,
//!   which makes `√(y − a)` and `√(b − y)` ends analytic;
//! - when two nodes of a piece disagree on the signature, the change between them is found
//!   by bisection (to ~1e-9 of the piece) and the piece is split there, so kinks — where
//!   two surfaces of a CSG cross — become piece ends instead of slowing convergence;
//! - then, as QUADPACK's `qag` does, the piece with the largest error estimate is halved
//!   until the estimates sum to less than the allowance (relative to the first estimate of
//!   the whole integral, or absolute per unit length, whichever is larger).
//!
//! Invariants: results are finite sums of finite samples; budgets of splits and a smallest
//! splittable width bound the work for any input.

use crate::tolerance::{GEOM_BISECTION, GEOM_SLIVER, QUAD_MIN_WIDTH};

pub(crate) type V3 = [f64; 3];

pub(crate) fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

pub(crate) fn scale(a: V3, k: f64) -> V3 {
    a.map(|v| v * k)
}

/// Error control for one integral over `[a, b]`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Tol {
    /// Error allowed relative to the integral.
    pub rtol: f64,
    /// Absolute error allowed per unit length of the integration variable.
    pub atol_density: f64,
    /// Pieces narrower than this are never split.
    pub min_width: f64,
    /// Most error-driven splits in one integral.
    pub budget: u32,
    /// Pieces narrower than this fraction of the whole take Gauss–Kronrod 7/15 (else 10/21;
    /// infinite: every piece).
    pub short: f64,
}

/// Gauss–Kronrod 10/21 (QUADPACK's `qk21`): the Kronrod abscissae in [0, 1] (the rule is
/// symmetric on [-1, 1]) from the outside in,
/// Kronrod weights, and the weights of the Gauss nodes among them (odd indices).
const XK21: [f64; 11] = [
    0.995_657_163_025_808_1,
    0.973_906_528_517_171_7,
    0.930_157_491_355_708_2,
    0.865_063_366_688_984_5,
    0.780_817_726_586_416_9,
    0.679_409_568_299_024_4,
    0.562_757_134_668_604_7,
    0.433_395_394_129_247_2,
    0.294_392_862_701_460_2,
    0.148_874_338_981_631_2,
    0.0,
];
const WK21: [f64; 11] = [
    0.011_694_638_867_371_874,
    0.032_558_162_307_964_73,
    0.054_755_896_574_352,
    0.075_039_674_810_919_95,
    0.093_125_454_583_697_6,
    0.109_387_158_802_297_64,
    0.123_491_976_262_065_85,
    0.134_709_217_311_473_33,
    0.142_775_938_577_060_08,
    0.147_739_104_901_338_5,
    0.149_445_554_002_916_9,
];
const WG21: [f64; 5] = [
    0.066_671_344_308_688_14,
    0.149_451_349_150_580_6,
    0.219_086_362_515_982_04,
    0.269_266_719_309_996_36,
    0.295_524_224_714_752_87,
];

/// Gauss–Kronrod 7/15 (QUADPACK's `qk15`), laid out as the 10/21 rule; the Gauss rule has
/// a node at the centre.
const XK15: [f64; 8] = [
    0.991_455_371_120_812_6,
    0.949_107_912_342_758_5,
    0.864_864_423_359_769_1,
    0.741_531_185_599_394_4,
    0.586_087_235_467_691_1,
    0.405_845_151_377_397_2,
    0.207_784_955_007_898_5,
    0.0,
];
const WK15: [f64; 8] = [
    0.022_935_322_010_529_225,
    0.063_092_092_629_978_55,
    0.104_790_010_322_250_18,
    0.140_653_259_715_525_92,
    0.169_004_726_639_267_9,
    0.190_350_578_064_785_4,
    0.204_432_940_075_298_9,
    0.209_482_141_084_727_83,
];
const WG15: [f64; 4] = [
    0.129_484_966_168_869_7,
    0.279_705_391_489_276_7,
    0.381_830_050_505_118_9,
    0.417_959_183_673_469_4,
];

/// Most nodes of a rule.
const N: usize = 21;

/// Node `i` (increasing on [-1, 1]) of a rule `(abscissae, kronrod weights, gauss weights)`
/// as `(ξ, kronrod weight, gauss weight)`.
fn node((xk, wk, wg): (&[f64], &[f64], &[f64]), i: usize) -> (f64, f64, f64) {
    let half = xk.len() - 1;
    let j = if i <= half { i } else { 2 * half - i };
    let g = if j % 2 == 1 { wg[j / 2] } else { 0.0 };
    let x = if i <= half { -xk[j] } else { xk[j] };
    (x, wk[j], g)
}

/// The nodes of the 10/21 rule, or of the 7/15 rule when `low_order`, after the
/// end-smoothing substitution (computed once).
fn nodes(low_order: bool) -> &'static [Node] {
    static NODES: std::sync::OnceLock<[Vec<Node>; 2]> = std::sync::OnceLock::new();
    let rules = NODES.get_or_init(|| {
        [(&XK21[..], &WK21[..], &WG21[..]), (&XK15, &WK15, &WG15)].map(|r| {
            (0..2 * r.0.len() - 1)
                .map(|i| Node::new(node(r, i)))
                .collect()
        })
    });
    &rules[usize::from(low_order)]
}

/// One node of the rule on `[0, 1]` after the end-smoothing substitution: the offset from
/// the nearer end as a fraction of the width (`sin²(πu/2)` or `cos²(πu/2)`, exact near that
/// end), which end, the Jacobian per unit width, and the Kronrod and Gauss weights.
#[derive(Debug, Clone, Copy)]
struct Node {
    offset: f64,
    from_start: bool,
    jac: f64,
    wk: f64,
    wg: f64,
}

impl Node {
    fn new((xi, wk, wg): (f64, f64, f64)) -> Node {
        let u = 0.5 * (1.0 + xi);
        let h = std::f64::consts::FRAC_PI_2 * u;
        let from_start = u <= 0.5;
        Node {
            offset: if from_start {
                h.sin().powi(2)
            } else {
                h.cos().powi(2)
            },
            from_start,
            jac: std::f64::consts::FRAC_PI_2 * (2.0 * h).sin(),
            wk: 0.5 * wk,
            wg: 0.5 * wg,
        }
    }
}

/// `∫ₐᵇ f`; see the module documentation.
pub(crate) fn integrate(f: &mut impl FnMut(f64) -> (V3, u64), a: f64, b: f64, tol: &Tol) -> V3 {
    integrate_pieces(f, &[a, b], tol)
}

/// `∫ f` from the first to the last of `cuts` (increasing), starting from the pieces
/// between consecutive cuts (known breaks of `f`); the allowance is relative to the whole.
pub(crate) fn integrate_pieces(
    f: &mut impl FnMut(f64) -> (V3, u64),
    cuts: &[f64],
    tol: &Tol,
) -> V3 {
    let (Some(&a), Some(&b)) = (cuts.first(), cuts.last()) else {
        return [0.0; 3];
    };
    if !(b > a) {
        return [0.0; 3];
    }
    let mut run = Run {
        tol: *tol,
        splits: tol.budget,
        structure_splits: STRUCTURE_SPLITS,
        allowed: 0.0,
        width: b - a,
        pieces: Vec::new(),
        done: [0.0; 3],
        err: 0.0,
    };
    let first: Vec<_> = cuts
        .windows(2)
        .filter(|w| w[1] > w[0])
        .map(|w| {
            (
                w[0],
                w[1],
                gk(f, w[0], w[1], nodes(w[1] - w[0] < tol.short * (b - a))),
            )
        })
        .collect();
    let total = first.iter().fold([0.0; 3], |acc, p| add(acc, p.2.0));
    let size = total.iter().fold(0.0, |m: f64, v| m.max(v.abs()));
    run.allowed = (tol.rtol * size).max(tol.atol_density * run.width);
    for (a, b, g) in first {
        run.file(f, a, b, g);
    }
    run.refine(f);
    run.pieces.iter().fold(run.done, |acc, p| add(acc, p.k))
}

/// Most splits at structure changes in one integral: past them, structure that flickers
/// (rounding near a tangency) is left to the error estimate.
const STRUCTURE_SPLITS: u32 = 24;

/// A piece awaiting refinement.
#[derive(Debug, Clone, Copy)]
struct Piece {
    a: f64,
    b: f64,
    k: V3,
    err: f64,
}

/// One integral in progress: QUADPACK's global strategy (split the piece with the largest
/// error until their sum is within the allowance), after splitting at structure changes.
struct Run {
    tol: Tol,
    /// Error-driven splits left.
    splits: u32,
    /// Structure-driven splits left.
    structure_splits: u32,
    /// Absolute error allowed for the whole integral, set from its first estimate.
    allowed: f64,
    width: f64,
    pieces: Vec<Piece>,
    /// Sum of pieces that can no longer be split.
    done: V3,
    /// Sum of the error estimates of `pieces`.
    err: f64,
}

/// The result of [`gk`] (nodes past the rule's count are unused).
type Gk = (V3, f64, [f64; N], [u64; N]);

/// One Gauss–Kronrod pass over `[a, b]`: the Kronrod value, QUADPACK's error estimate (the
/// Kronrod–Gauss difference scaled down for smooth integrands), and the nodes' points and
/// signatures.
fn gk(f: &mut impl FnMut(f64) -> (V3, u64), a: f64, b: f64, nodes: &[Node]) -> Gk {
    let w = b - a;
    let mut ys = [0.0; N];
    let mut ss = [0u64; N];
    let mut vals = [[0.0; 3]; N];
    let (mut k, mut g) = ([0.0; 3], [0.0; 3]);
    for (i, n) in nodes.iter().enumerate() {
        let y = if n.from_start {
            a + w * n.offset
        } else {
            b - w * n.offset
        };
        let (v, s) = f(y);
        (ys[i], ss[i]) = (y, s);
        for c in 0..3 {
            vals[i][c] = v[c] * w * n.jac;
            k[c] += n.wk * vals[i][c];
            g[c] += n.wg * vals[i][c];
        }
    }
    let mut err = 0.0f64;
    for c in 0..3 {
        // QUADPACK's `resasc`: the Kronrod rule applied to |f − mean f|.
        let asc: f64 = nodes
            .iter()
            .zip(&vals)
            .map(|(n, v)| n.wk * (v[c] - k[c]).abs())
            .sum();
        let diff = (k[c] - g[c]).abs();
        let e = if asc > 0.0 && diff > 0.0 {
            asc * (200.0 * diff / asc).powf(1.5).min(1.0)
        } else {
            diff
        };
        err = err.max(e);
    }
    (k, err, ys, ss)
}

impl Run {
    /// The nodes of the rule for a piece of width `w`.
    fn nodes(&self, w: f64) -> &'static [Node] {
        nodes(w < self.tol.short * self.width)
    }

    /// Evaluates `[a, b]`, splitting it where the structure changes, and files the pieces.
    fn add(&mut self, f: &mut impl FnMut(f64) -> (V3, u64), a: f64, b: f64) {
        let g = gk(f, a, b, self.nodes(b - a));
        self.file(f, a, b, g);
    }

    /// Files `[a, b]` with its Gauss–Kronrod pass `g`, splitting it where the structure
    /// changes.
    fn file(&mut self, f: &mut impl FnMut(f64) -> (V3, u64), a: f64, b: f64, g: Gk) {
        let (k, err, ys, ss) = g;
        // Structure changes narrower than this are left to the error estimate: below it,
        // rounding (two breaks within an ulp, a grazing chord) makes structure flicker.
        let wide = b - a > self.tol.min_width.max(GEOM_SLIVER * self.width);
        if wide
            && self.structure_splits > 0
            && let Some(i) = (0..self.nodes(b - a).len() - 1).find(|&i| ss[i] != ss[i + 1])
        {
            self.structure_splits -= 1;
            let y = locate(f, (ys[i], ss[i]), (ys[i + 1], ss[i + 1]), b - a);
            if y > a && y < b {
                self.add(f, a, y);
                self.add(f, y, b);
                return;
            }
        }
        self.pieces.push(Piece { a, b, k, err });
        self.err += err;
    }

    /// Halves the piece with the largest error until the errors fit the allowance.
    fn refine(&mut self, f: &mut impl FnMut(f64) -> (V3, u64)) {
        let min_width = self.tol.min_width.max(QUAD_MIN_WIDTH * self.width);
        while self.err > self.allowed && self.splits > 0 {
            let Some(worst) = (0..self.pieces.len())
                .max_by(|&i, &j| self.pieces[i].err.total_cmp(&self.pieces[j].err))
            else {
                break;
            };
            let p = self.pieces.swap_remove(worst);
            self.err -= p.err;
            if p.b - p.a <= min_width {
                self.done = add(self.done, p.k);
                continue;
            }
            self.splits -= 1;
            let m = 0.5 * (p.a + p.b);
            self.add(f, p.a, m);
            self.add(f, m, p.b);
        }
    }
}

/// Where the signature changes between `lo` and `hi` (found by bisection).
fn locate(f: &mut impl FnMut(f64) -> (V3, u64), lo: (f64, u64), hi: (f64, u64), width: f64) -> f64 {
    let mut lo = lo;
    let mut hi = hi.0;
    // Close enough that the change sits between a piece's end and its first node (~1e-5 of
    // the piece in), where a kink costs ~(1e-9)² of the piece and no further splitting.
    let eps = GEOM_BISECTION * width;
    for _ in 0..64 {
        let m = 0.5 * (lo.0 + hi);
        if !(hi - lo.0 > eps) || m <= lo.0 || m >= hi {
            break;
        }
        // A third structure in between counts as a change too: any change will do.
        if f(m).1 == lo.1 {
            lo.0 = m;
        } else {
            hi = m;
        }
    }
    0.5 * (lo.0 + hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tol() -> Tol {
        Tol {
            rtol: 1e-12,
            atol_density: 1e-15,
            min_width: 0.0,
            budget: 4000,
            short: 0.0,
        }
    }

    /// Asserts that a rule's Kronrod nodes integrate `x^p` on [-1, 1] exactly up to degree
    /// `kronrod` and its Gauss nodes up to degree `gauss`.
    fn assert_exact(rule: (&[f64], &[f64], &[f64]), nodes: usize, kronrod: i32, gauss: i32) {
        for p in 0..=kronrod {
            let (mut k, mut g) = (0.0, 0.0);
            for i in 0..nodes {
                let (x, wk, wg) = node(rule, i);
                k += wk * x.powi(p);
                g += wg * x.powi(p);
            }
            let exact = if p % 2 == 0 {
                2.0 / (p as f64 + 1.0)
            } else {
                0.0
            };
            assert!((k - exact).abs() < 1e-14, "kronrod x^{p}: {k} vs {exact}");
            if p <= gauss {
                assert!((g - exact).abs() < 1e-14, "gauss x^{p}: {g} vs {exact}");
            }
        }
    }

    #[test]
    fn rule_is_exact_on_polynomials() {
        assert_exact((&XK21, &WK21, &WG21), N, 31, 19);
    }

    #[test]
    fn low_order_rule_is_exact_on_polynomials() {
        assert_exact((&XK15, &WK15, &WG15), 15, 22, 13);
    }

    #[test]
    fn short_pieces_are_exact() {
        let mut f = |y: f64| ([(1.0 - y * y).max(0.0).sqrt(), y * y, 1.0], 0);
        let cuts = [-1.0, -0.99, -0.9, 0.95, 1.0];
        let t = Tol {
            short: 0.1,
            ..tol()
        };
        let r = integrate_pieces(&mut f, &cuts, &t);
        assert!((r[0] - std::f64::consts::FRAC_PI_2).abs() < 1e-13, "{r:?}");
        assert!((r[1] - 2.0 / 3.0).abs() < 1e-14);
        assert!((r[2] - 2.0).abs() < 1e-14);
    }

    #[test]
    fn smooth_and_sqrt_ends_are_exact() {
        let mut f = |y: f64| ([(1.0 - y * y).max(0.0).sqrt(), y * y, 1.0], 0);
        let r = integrate(&mut f, -1.0, 1.0, &tol());
        assert!((r[0] - std::f64::consts::FRAC_PI_2).abs() < 1e-13, "{r:?}");
        assert!((r[1] - 2.0 / 3.0).abs() < 1e-14);
        assert!((r[2] - 2.0).abs() < 1e-14);
    }

    #[test]
    fn kinks_are_located_by_signature() {
        let k = 0.3141592;
        let mut f = |y: f64| ([(y - k).abs(), 0.0, 0.0], u64::from(y > k));
        let r = integrate(&mut f, 0.0, 1.0, &tol());
        let exact = (k * k + (1.0 - k) * (1.0 - k)) / 2.0;
        assert!((r[0] - exact).abs() < 1e-13, "{} vs {exact}", r[0]);
    }

    #[test]
    fn unsigned_kinks_still_converge() {
        let k = 0.3141592;
        let mut f = |y: f64| ([(y - k).abs(), 0.0, 0.0], 0);
        let r = integrate(&mut f, 0.0, 1.0, &tol());
        let exact = (k * k + (1.0 - k) * (1.0 - k)) / 2.0;
        assert!((r[0] - exact).abs() < 1e-9, "{} vs {exact}", r[0]);
    }
}
