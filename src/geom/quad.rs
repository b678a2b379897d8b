//! One-dimensional adaptive quadrature for piecewise-smooth integrands.
//!
//! [`integrate`] computes `∫ₐᵇ f` for an `f` that returns a value ([`V3`]) and a
//! *signature*: a hash of the structure that produced the value (which surfaces bound which
//! stretches). Where the signature is constant, `f` is analytic inside the piece, except for
//! square-root behaviour at the piece's ends (a ray grazing a curved surface there); so:
//!
//! - every piece is integrated with Gauss–Kronrod 10/21 after the substitution
//!   `y = a + (b − a)·sin²(πu/2)`, which makes `√(y − a)` and `√(b − y)` ends analytic;
//! - when two nodes of a piece disagree on the signature, the change between them is found
//!   by bisection (to ~1e-13 of the piece) and the piece is split there, so kinks — where
//!   two surfaces of a CSG cross — become piece ends instead of slowing convergence;
//! - otherwise a piece whose Kronrod–Gauss difference exceeds the tolerance is halved.
//!
//! Invariants: results are finite sums of finite samples; a budget of pieces and a smallest
//! splittable width bound the work for any input.

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
    /// Relative error allowed per piece.
    pub rtol: f64,
    /// Absolute error allowed per unit length of the integration variable.
    pub atol_density: f64,
    /// Pieces narrower than this are never split.
    pub min_width: f64,
    /// Most pieces one integral may create (splits at signature changes included).
    pub budget: u32,
}

/// Gauss–Kronrod 10/21 (QUADPACK's `qk21`): Kronrod abscissae on [0, 1] from the outside in,
/// Kronrod weights, and the weights of the Gauss nodes among them (odd indices).
const XK: [f64; 11] = [
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
const WK: [f64; 11] = [
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
const WG: [f64; 5] = [
    0.066_671_344_308_688_14,
    0.149_451_349_150_580_6,
    0.219_086_362_515_982_04,
    0.269_266_719_309_996_36,
    0.295_524_224_714_752_87,
];
const N: usize = 21;

/// Node `i` (0..21, increasing) as `(ξ, kronrod weight, gauss weight)`.
fn node(i: usize) -> (f64, f64, f64) {
    let j = if i < 11 { i } else { 20 - i };
    let wg = if j % 2 == 1 { WG[j / 2] } else { 0.0 };
    let x = if i < 11 { -XK[j] } else { XK[j] };
    (x, WK[j], wg)
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

fn nodes() -> &'static [Node; N] {
    static NODES: std::sync::OnceLock<[Node; N]> = std::sync::OnceLock::new();
    NODES.get_or_init(|| {
        std::array::from_fn(|i| {
            let (xi, wk, wg) = node(i);
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
        })
    })
}

/// `∫ₐᵇ f`; see the module documentation.
pub(crate) fn integrate(f: &mut impl FnMut(f64) -> (V3, u64), a: f64, b: f64, tol: &Tol) -> V3 {
    if !(b > a) {
        return [0.0; 3];
    }
    let mut run = Run {
        tol: *tol,
        budget: tol.budget,
        density: None,
        width: b - a,
    };
    run.piece(f, a, b)
}

/// One integral in progress.
struct Run {
    tol: Tol,
    budget: u32,
    /// Error allowed per unit length, set from the first estimate of the whole integral:
    /// the error budget is global, so pieces at a square-root end (self-similar under
    /// halving) stop once their share of the total error is small enough.
    density: Option<f64>,
    width: f64,
}

/// Gauss–Kronrod 10/21 on one piece: the Kronrod value, and QUADPACK's error estimate
/// (the Kronrod–Gauss difference scaled down for smooth integrands).
fn gk21(f: &mut impl FnMut(f64) -> (V3, u64), a: f64, b: f64) -> (V3, f64, [f64; N], [u64; N]) {
    let w = b - a;
    let mut ys = [0.0; N];
    let mut ss = [0u64; N];
    let mut vals = [[0.0; 3]; N];
    let (mut k, mut g) = ([0.0; 3], [0.0; 3]);
    for (i, n) in nodes().iter().enumerate() {
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
    let nodes = nodes();
    for c in 0..3 {
        // QUADPACK's `resasc`: the Kronrod rule applied to |f − mean f|.
        let mean = k[c];
        let asc: f64 = (0..N)
            .map(|i| nodes[i].wk * (vals[i][c] - mean).abs())
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
    fn piece(&mut self, f: &mut impl FnMut(f64) -> (V3, u64), a: f64, b: f64) -> V3 {
        let (k, err, ys, ss) = gk21(f, a, b);
        let density = *self.density.get_or_insert_with(|| {
            let size = k.iter().fold(0.0, |m: f64, v| m.max(v.abs()));
            (self.tol.rtol * size / self.width).max(self.tol.atol_density)
        });
        // Pieces this small are accepted as they are: below them, rounding noise (a grazing
        // chord, two breaks within an ulp) would make structure flicker, not converge.
        let splittable = b - a > self.tol.min_width.max(1e-9 * self.width);
        if splittable
            && self.budget >= 2
            && let Some(i) = (0..N - 1).find(|&i| ss[i] != ss[i + 1])
        {
            self.budget -= 2;
            let y = locate(f, (ys[i], ss[i]), (ys[i + 1], ss[i + 1]), b - a);
            if y > a && y < b {
                let left = self.piece(f, a, y);
                return add(left, self.piece(f, y, b));
            }
        }
        if err <= density * (b - a) || self.budget < 2 || !splittable {
            return k;
        }
        self.budget -= 2;
        let m = 0.5 * (a + b);
        let left = self.piece(f, a, m);
        add(left, self.piece(f, m, b))
    }
}

/// Where the signature changes between `lo` and `hi` (found by bisection).
fn locate(f: &mut impl FnMut(f64) -> (V3, u64), lo: (f64, u64), hi: (f64, u64), width: f64) -> f64 {
    let mut lo = lo;
    let mut hi = hi.0;
    // Nodes keep ~1e-5 of a piece away from its ends, so this is close enough for the
    // change never to fall between a node and the end of the piece it is split into.
    let eps = 1e-7 * width;
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
        }
    }

    #[test]
    fn rule_is_exact_on_polynomials() {
        for p in 0..32 {
            let (mut k, mut g) = (0.0, 0.0);
            for i in 0..N {
                let (x, wk, wg) = node(i);
                k += wk * x.powi(p);
                g += wg * x.powi(p);
            }
            let exact = if p % 2 == 0 {
                2.0 / (p as f64 + 1.0)
            } else {
                0.0
            };
            assert!((k - exact).abs() < 1e-14, "kronrod x^{p}: {k} vs {exact}");
            if p < 20 {
                assert!((g - exact).abs() < 1e-14, "gauss x^{p}: {g} vs {exact}");
            }
        }
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
