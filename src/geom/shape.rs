//! Prepared parts: one primitive in its own frame, with the inverse of its world matrix.
//!
//! A [`Shape`] is a [`Part`] made ready for ray casting: the primitive in local coordinates
//! (a box `lo..hi`, a frustum `z0..z1` with radius `w(z) = alpha + k·z`, a sphere), the world
//! matrix `[L | t]`, `L⁻¹` and `−L⁻¹t`, and tight world bounds. A world ray `o + s·d` maps to
//! the local ray `L⁻¹(o − t) + s·L⁻¹d` with the *same* parameter `s`, so hits computed
//! locally are world hits; normals go back through `L⁻ᵀ` (outward stays outward under any
//! invertible affine map, mirrors included).
//!
//! Invariants: a shape always has positive volume — zero or negative sizes, NaN or infinite
//! entries and singular matrices make [`Shape::new`] return `None` (the part is empty).
//! A [`Hit`] always has `t0 < t1` and finite ends. `aligned` is true exactly for boxes whose
//! `L` is a scaled signed permutation: their footprint is their bounding rectangle and the
//! stretch a vertical ray spends inside them is the same everywhere over it. `prism[a]` is
//! true when the shape is an extrusion along world axis `a` with caps perpendicular to it
//! (a box with an edge along `a`, a cylinder whose axis is `a`): then the length of a
//! vertical line inside it does not change when the line moves along `a` (for `a = z`: it is
//! constant over the footprint).

use crate::ir::{Part, Primitive};
use crate::tolerance::{GEOM_BOUNDS_PAD, GEOM_NEGLIGIBLE_ENTRY, GEOM_ROUNDOFF};

/// Face codes: a box's `2·axis` (low side) and `2·axis + 1` (high side); a frustum's caps
/// and side; a sphere's single surface.
pub(crate) const BOTTOM: u8 = 0;
pub(crate) const TOP: u8 = 1;
pub(crate) const SIDE: u8 = 2;

#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Kind {
    Box {
        lo: [f64; 3],
        hi: [f64; 3],
    },
    /// `z0 < z1`, cap radii `r = [w(z0), w(z1)]`, both `>= 0`, not both zero.
    Frustum {
        z0: f64,
        z1: f64,
        r: [f64; 2],
        k: f64,
        alpha: f64,
    },
    Sphere {
        r: f64,
    },
}

/// Entry and exit of a line through a shape, with the faces hit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Hit {
    pub t0: f64,
    pub t1: f64,
    pub f0: u8,
    pub f1: u8,
}

#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Shape {
    pub kind: Kind,
    /// World matrix `[L | t]`.
    pub m: [[f64; 4]; 3],
    /// `L⁻¹`.
    pub inv: [[f64; 3]; 3],
    /// `−L⁻¹t`: the local image of the world origin.
    pub inv_o: [f64; 3],
    /// Tight world bounds.
    pub lo: [f64; 3],
    pub hi: [f64; 3],
    pub aligned: bool,
    pub prism: [bool; 3],
    /// For a prism along z: the local axis along world z, and the stretch every vertical
    /// line through its footprint spends inside it.
    z_prism: Option<(usize, Hit)>,
    /// World corners of a box (unused for other kinds).
    pub corners: [[f64; 3]; 8],
}

fn finite(v: f64) -> Option<f64> {
    v.is_finite().then_some(v)
}

fn local_kind(p: &Primitive) -> Option<Kind> {
    match p {
        Primitive::Cube { size, center } => {
            let s = [
                finite(size[0].value)?,
                finite(size[1].value)?,
                finite(size[2].value)?,
            ];
            if s.iter().any(|&v| v <= 0.0) {
                return None;
            }
            let (lo, hi) = if *center {
                (s.map(|v| -v / 2.0), s.map(|v| v / 2.0))
            } else {
                ([0.0; 3], s)
            };
            Some(Kind::Box { lo, hi })
        }
        Primitive::Cylinder { h, r1, r2, center } => {
            let (h, r1, r2) = (finite(h.value)?, finite(r1.value)?, finite(r2.value)?);
            if h <= 0.0 || r1 < 0.0 || r2 < 0.0 || (r1 == 0.0 && r2 == 0.0) {
                return None;
            }
            let z0 = if *center { -h / 2.0 } else { 0.0 };
            let k = (r2 - r1) / h;
            Some(Kind::Frustum {
                z0,
                z1: z0 + h,
                r: [r1, r2],
                k,
                alpha: r1 - k * z0,
            })
        }
        Primitive::Sphere { r } => {
            let r = finite(r.value)?;
            (r > 0.0).then_some(Kind::Sphere { r })
        }
    }
}

/// `L⁻¹` of the 3×3 part of `m`, or `None` when (relatively) singular.
fn inverse(m: &[[f64; 4]; 3]) -> Option<[[f64; 3]; 3]> {
    let a = |i: usize, j: usize| m[i][j];
    let cof = |i: usize, j: usize| {
        let (r0, r1) = ((i + 1) % 3, (i + 2) % 3);
        let (c0, c1) = ((j + 1) % 3, (j + 2) % 3);
        a(r0, c0) * a(r1, c1) - a(r0, c1) * a(r1, c0)
    };
    let det = (0..3).map(|j| a(0, j) * cof(0, j)).sum::<f64>();
    let norms: f64 = (0..3)
        .map(|i| (0..3).map(|j| a(i, j) * a(i, j)).sum::<f64>().sqrt())
        .product();
    if !(det.abs() > GEOM_ROUNDOFF * norms) || !det.is_finite() {
        return None;
    }
    // (L⁻¹)[i][j] = cofactor(j, i) / det
    Some(std::array::from_fn(|i| {
        std::array::from_fn(|j| cof(j, i) / det)
    }))
}

/// True when each row and each column of `L` has exactly one non-negligible entry.
pub(crate) fn is_signed_permutation(m: &[[f64; 4]; 3]) -> bool {
    let big = |i: usize, j: usize| {
        let norm = (0..3).map(|k| m[i][k].abs()).fold(0.0, f64::max);
        m[i][j].abs() > GEOM_NEGLIGIBLE_ENTRY * norm
    };
    (0..3).all(|i| (0..3).filter(|&j| big(i, j)).count() == 1)
        && (0..3).all(|j| (0..3).filter(|&i| big(i, j)).count() == 1)
}

pub(crate) fn mat_vec(m: &[[f64; 3]; 3], v: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|i| m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2])
}

impl Shape {
    /// The prepared part, or `None` when it holds no volume (or has non-finite numbers).
    pub fn new(part: &Part) -> Option<Shape> {
        let v = part.world.values();
        let m = [v[0], v[1], v[2]];
        if m.iter().flatten().any(|x| !x.is_finite()) {
            return None;
        }
        let kind = local_kind(&part.primitive)?;
        let inv = inverse(&m)?;
        let t = [m[0][3], m[1][3], m[2][3]];
        let inv_o = mat_vec(&inv, t).map(|v| -v);
        let mut s = Shape {
            kind,
            m,
            inv,
            inv_o,
            lo: [0.0; 3],
            hi: [0.0; 3],
            aligned: false,
            prism: [false; 3],
            z_prism: None,
            corners: [[0.0; 3]; 8],
        };
        s.set_bounds();
        s.aligned = matches!(kind, Kind::Box { .. }) && is_signed_permutation(&m);
        s.prism = std::array::from_fn(|a| s.is_prism_along(a));
        s.z_prism = s.prism[2].then(|| s.vertical_stretch()).flatten();
        let ok = (0..3).all(|a| s.lo[a].is_finite() && s.hi[a].is_finite() && s.lo[a] < s.hi[a]);
        ok.then_some(s)
    }

    /// True when world axis `a` is a local axis `u` of the primitive (a box's any, a
    /// cylinder's z) and the other local axes are perpendicular to it: `L⁻¹` has a single
    /// non-negligible entry in column `a`, at row `u`, and none elsewhere in row `u`.
    fn is_prism_along(&self, a: usize) -> bool {
        let inv = &self.inv;
        let norm = inv.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
        let big = |i: usize, j: usize| inv[i][j].abs() > GEOM_NEGLIGIBLE_ENTRY * norm;
        let Some(u) = (0..3).find(|&i| big(i, a)) else {
            return false;
        };
        let cross = (0..3).all(|i| i == u || !big(i, a)) && (0..3).all(|j| j == a || !big(u, j));
        match self.kind {
            Kind::Box { .. } => cross,
            Kind::Frustum { k, .. } => cross && u == 2 && k == 0.0,
            Kind::Sphere { .. } => false,
        }
    }

    /// The local axis along world z of a prism along z, and its stretch on vertical lines.
    fn vertical_stretch(&self) -> Option<(usize, Hit)> {
        let u = match self.kind {
            Kind::Box { .. } => {
                (0..3).max_by(|&i, &j| self.inv[i][2].abs().total_cmp(&self.inv[j][2].abs()))?
            }
            _ => 2,
        };
        let (low, high) = match self.kind {
            Kind::Box { .. } => (2 * u as u8, 2 * u as u8 + 1),
            _ => (BOTTOM, TOP),
        };
        let (f0, f1) = if self.inv[u][2] > 0.0 {
            (low, high)
        } else {
            (high, low)
        };
        Some((
            u,
            Hit {
                t0: self.lo[2],
                t1: self.hi[2],
                f0,
                f1,
            },
        ))
    }

    /// The world image of a local point.
    pub fn world(&self, p: [f64; 3]) -> [f64; 3] {
        let m = &self.m;
        std::array::from_fn(|i| m[i][0] * p[0] + m[i][1] * p[1] + m[i][2] * p[2] + m[i][3])
    }

    fn set_bounds(&mut self) {
        let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
        let mut grow = |c: [f64; 3], e: [f64; 3]| {
            for a in 0..3 {
                lo[a] = lo[a].min(c[a] - e[a]);
                hi[a] = hi[a].max(c[a] + e[a]);
            }
        };
        match self.kind {
            Kind::Box { lo: l, hi: h } => {
                for c in 0..8 {
                    let p = std::array::from_fn(|a| if c >> a & 1 == 0 { l[a] } else { h[a] });
                    self.corners[c] = self.world(p);
                    grow(self.corners[c], [0.0; 3]);
                }
            }
            Kind::Frustum { z0, z1, r, .. } => {
                for (z, r) in [(z0, r[0]), (z1, r[1])] {
                    let e = std::array::from_fn(|i| r * self.m[i][0].hypot(self.m[i][1]));
                    grow(self.world([0.0, 0.0, z]), e);
                }
            }
            Kind::Sphere { r } => {
                let e = std::array::from_fn(|i| {
                    r * (0..3).map(|j| self.m[i][j].powi(2)).sum::<f64>().sqrt()
                });
                grow(self.world([0.0; 3]), e);
            }
        }
        self.lo = lo;
        self.hi = hi;
    }

    /// The local ray of the world line `(x, y, s)`, `s ∈ ℝ` (parallel to z).
    #[inline]
    pub fn vertical_local(&self, x: f64, y: f64) -> ([f64; 3], [f64; 3]) {
        let (m, c) = (&self.inv, &self.inv_o);
        let o = std::array::from_fn(|i| c[i] + m[i][0] * x + m[i][1] * y);
        let d = std::array::from_fn(|i| m[i][2]);
        (o, d)
    }

    /// Where the vertical line through `(x, y)` is inside the shape (`t` is world z).
    #[inline]
    pub fn hit_vertical(&self, x: f64, y: f64) -> Option<Hit> {
        if !(x >= self.lo[0] && x <= self.hi[0] && y >= self.lo[1] && y <= self.hi[1]) {
            return None;
        }
        if let Some((u, hit)) = self.z_prism {
            return self.in_cross_section(u, x, y).then_some(hit);
        }
        let (o, d) = self.vertical_local(x, y);
        self.hit_local(o, d)
    }

    /// Whether the vertical line through `(x, y)` meets a prism along z (local axis `u`).
    fn in_cross_section(&self, u: usize, x: f64, y: f64) -> bool {
        let local = |j: usize| self.inv_o[j] + self.inv[j][0] * x + self.inv[j][1] * y;
        match self.kind {
            Kind::Box { lo, hi } => (0..3)
                .filter(|&j| j != u)
                .all(|j| (lo[j]..=hi[j]).contains(&local(j))),
            Kind::Frustum { r, .. } => local(0).powi(2) + local(1).powi(2) <= r[0] * r[0],
            Kind::Sphere { .. } => false,
        }
    }

    /// Where the world line `o + t·d` is inside the shape.
    pub fn hit_ray(&self, o: [f64; 3], d: [f64; 3]) -> Option<Hit> {
        if o.iter().chain(&d).any(|v| !v.is_finite()) || d == [0.0; 3] || self.misses_bounds(o, d) {
            return None;
        }
        let lo = mat_vec(&self.inv, o);
        let lo = std::array::from_fn(|i| lo[i] + self.inv_o[i]);
        self.hit_local(lo, mat_vec(&self.inv, d))
    }

    /// True when the line cannot meet the (slightly grown) world bounds: most lines of a
    /// large model are turned away here, before any transform.
    fn misses_bounds(&self, o: [f64; 3], d: [f64; 3]) -> bool {
        let (mut t0, mut t1) = (f64::NEG_INFINITY, f64::INFINITY);
        for a in 0..3 {
            let pad = GEOM_BOUNDS_PAD * (self.hi[a] - self.lo[a]);
            let (lo, hi) = (self.lo[a] - pad, self.hi[a] + pad);
            if d[a] == 0.0 {
                if o[a] < lo || o[a] > hi {
                    return true;
                }
                continue;
            }
            let (ta, tb) = ((lo - o[a]) / d[a], (hi - o[a]) / d[a]);
            t0 = t0.max(ta.min(tb));
            t1 = t1.min(ta.max(tb));
        }
        t0 > t1
    }

    fn hit_local(&self, o: [f64; 3], d: [f64; 3]) -> Option<Hit> {
        // Quadrics are solved from the point of the line nearest the primitive's centre, so
        // that a far origin does not cancel digits away (a grazing line's chord is
        // ill-conditioned enough as it is).
        let centre = match self.kind {
            Kind::Box { .. } => return self.hit_local_at(o, d),
            Kind::Frustum { z0, z1, .. } => [0.0, 0.0, 0.5 * (z0 + z1)],
            Kind::Sphere { .. } => [0.0; 3],
        };
        let dd = dot(d, d);
        let p = std::array::from_fn(|i| o[i] - centre[i]);
        let s = -dot(p, d) / dd;
        if !s.is_finite() {
            return None;
        }
        let o2 = std::array::from_fn(|i| o[i] + s * d[i]);
        let mut h = self.hit_local_at(o2, d)?;
        h.t0 += s;
        h.t1 += s;
        (h.t0 < h.t1).then_some(h)
    }

    fn hit_local_at(&self, o: [f64; 3], d: [f64; 3]) -> Option<Hit> {
        let h = match self.kind {
            Kind::Box { lo, hi } => hit_box(lo, hi, o, d),
            Kind::Frustum {
                z0, z1, k, alpha, ..
            } => hit_frustum(z0, z1, k, alpha, o, d),
            Kind::Sphere { r } => {
                let a2 = dot(d, d);
                let a1 = 2.0 * dot(o, d);
                let a0 = dot(o, o) - r * r;
                match quad_le0(a2, a1, a0) {
                    QSet::Between(t0, t1) => Some(Hit {
                        t0,
                        t1,
                        f0: SIDE,
                        f1: SIDE,
                    }),
                    _ => None,
                }
            }
        }?;
        (h.t0 < h.t1 && h.t0.is_finite() && h.t1.is_finite()).then_some(h)
    }

    /// The outward unit world normal of face `face` at the world point `p`.
    pub fn normal(&self, face: u8, p: [f64; 3]) -> [f64; 3] {
        let q = mat_vec(&self.inv, p);
        let q: [f64; 3] = std::array::from_fn(|i| q[i] + self.inv_o[i]);
        let g = match self.kind {
            Kind::Box { .. } => {
                let mut g = [0.0; 3];
                g[(face / 2) as usize % 3] = if face.is_multiple_of(2) { -1.0 } else { 1.0 };
                g
            }
            Kind::Frustum { k, alpha, .. } => match face {
                BOTTOM => [0.0, 0.0, -1.0],
                TOP => [0.0, 0.0, 1.0],
                _ => [q[0], q[1], -k * (alpha + k * q[2])],
            },
            Kind::Sphere { .. } => q,
        };
        // L⁻ᵀ g
        let inv = &self.inv;
        let n: [f64; 3] = std::array::from_fn(|i| (0..3).map(|j| inv[j][i] * g[j]).sum());
        let len = dot(n, n).sqrt();
        if len > 0.0 && len.is_finite() {
            n.map(|v| v / len)
        } else {
            // The apex of a cone: any direction along the axis will do.
            let axis = [self.m[0][2], self.m[1][2], self.m[2][2]];
            let l = dot(axis, axis).sqrt();
            axis.map(|v| v / l)
        }
    }
}

pub(crate) fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn hit_box(lo: [f64; 3], hi: [f64; 3], o: [f64; 3], d: [f64; 3]) -> Option<Hit> {
    let (mut t0, mut t1) = (f64::NEG_INFINITY, f64::INFINITY);
    let (mut f0, mut f1) = (0u8, 0u8);
    for a in 0..3 {
        if d[a] == 0.0 {
            if !(o[a] >= lo[a] && o[a] <= hi[a]) {
                return None;
            }
            continue;
        }
        let (mut ta, mut tb) = ((lo[a] - o[a]) / d[a], (hi[a] - o[a]) / d[a]);
        let (mut fa, mut fb) = (2 * a as u8, 2 * a as u8 + 1);
        if ta > tb {
            std::mem::swap(&mut ta, &mut tb);
            std::mem::swap(&mut fa, &mut fb);
        }
        if ta > t0 {
            (t0, f0) = (ta, fa);
        }
        if tb < t1 {
            (t1, f1) = (tb, fb);
        }
    }
    (t0 < t1).then_some(Hit { t0, t1, f0, f1 })
}

fn hit_frustum(z0: f64, z1: f64, k: f64, alpha: f64, o: [f64; 3], d: [f64; 3]) -> Option<Hit> {
    // The slab z0 ≤ z ≤ z1.
    let slab = if d[2] == 0.0 {
        if !(o[2] >= z0 && o[2] <= z1) {
            return None;
        }
        Hit {
            t0: f64::NEG_INFINITY,
            t1: f64::INFINITY,
            f0: SIDE,
            f1: SIDE,
        }
    } else {
        let (ta, tb) = ((z0 - o[2]) / d[2], (z1 - o[2]) / d[2]);
        if ta < tb {
            Hit {
                t0: ta,
                t1: tb,
                f0: BOTTOM,
                f1: TOP,
            }
        } else {
            Hit {
                t0: tb,
                t1: ta,
                f0: TOP,
                f1: BOTTOM,
            }
        }
    };
    // Inside the (double) cone x² + y² ≤ w(z)²; within the slab w ≥ 0, so this is the frustum.
    let w0 = alpha + k * o[2];
    let wd = k * d[2];
    let a2 = d[0] * d[0] + d[1] * d[1] - wd * wd;
    let a1 = 2.0 * (o[0] * d[0] + o[1] * d[1] - w0 * wd);
    let a0 = o[0] * o[0] + o[1] * o[1] - w0 * w0;
    let clip = |lo: f64, hi: f64| -> Option<Hit> {
        let mut h = slab;
        if lo > h.t0 {
            (h.t0, h.f0) = (lo, SIDE);
        }
        if hi < h.t1 {
            (h.t1, h.f1) = (hi, SIDE);
        }
        (h.t0 < h.t1).then_some(h)
    };
    match quad_le0(a2, a1, a0) {
        QSet::None => None,
        QSet::All => clip(f64::NEG_INFINITY, f64::INFINITY),
        QSet::Between(r0, r1) => clip(r0, r1),
        QSet::Outside(r0, r1) => {
            // Both pieces cannot be non-empty in exact arithmetic (the slab holds one nappe);
            // if rounding says so, their hull is the convex answer.
            match (clip(f64::NEG_INFINITY, r0), clip(r1, f64::INFINITY)) {
                (Some(a), Some(b)) => Some(Hit {
                    t0: a.t0,
                    t1: b.t1,
                    f0: a.f0,
                    f1: b.f1,
                }),
                (a, b) => a.or(b),
            }
        }
    }
}

/// The set `{s : a2·s² + a1·s + a0 ≤ 0}`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum QSet {
    None,
    All,
    Between(f64, f64),
    /// `s ≤ first` or `s ≥ second`.
    Outside(f64, f64),
}

/// The real roots of `a·s² + b·s + c` in increasing order (`None` when there are none or
/// the polynomial vanishes identically), computed without cancellation.
pub(crate) fn roots(a: f64, b: f64, c: f64) -> Option<(f64, f64)> {
    if a == 0.0 {
        if b == 0.0 {
            return None;
        }
        let r = -c / b;
        return Some((r, r));
    }
    let disc = b * b - 4.0 * a * c;
    if !(disc >= 0.0) {
        return None;
    }
    let q = -0.5 * (b + disc.sqrt().copysign(b));
    if q == 0.0 {
        return Some((0.0, 0.0));
    }
    let (r0, r1) = (q / a, c / q);
    Some(if r0 < r1 { (r0, r1) } else { (r1, r0) })
}

pub(crate) fn quad_le0(a2: f64, a1: f64, a0: f64) -> QSet {
    if a2 == 0.0 {
        if a1 == 0.0 {
            return if a0 <= 0.0 { QSet::All } else { QSet::None };
        }
        let r = -a0 / a1;
        return if a1 > 0.0 {
            QSet::Between(f64::NEG_INFINITY, r)
        } else {
            QSet::Between(r, f64::INFINITY)
        };
    }
    match roots(a2, a1, a0) {
        Some((r0, r1)) if a2 > 0.0 => QSet::Between(r0, r1),
        Some((r0, r1)) if r0 < r1 => QSet::Outside(r0, r1),
        Some(_) => QSet::All,
        None if a2 > 0.0 => QSet::None,
        None => QSet::All,
    }
}
