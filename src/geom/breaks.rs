//! Where the stretch of a vertical line inside a shape stops being smooth.
//!
//! Volumes integrate `f(x, y)`, the length of the vertical line through `(x, y)` inside the
//! solid, first along one horizontal axis (a *line*) and then along the other. For one
//! shape, `f` is analytic except where the vertical line grazes the surface (the silhouette:
//! a square-root edge), crosses an edge (a box edge, a frustum's cap rim: a kink or a jump)
//! or passes the apex of a cone. Everything here works for either order (`x` then `y` or
//! the reverse): axes are parameters.
//!
//! - [`Shape::axis_breaks`]: the values of the outer coordinate where the set of break
//!   points of a line changes: tight bounds, box corners, the extremes of cap rims, the ends
//!   of a cone's contour generators (where the silhouette leaves a rim), apexes.
//! - [`Shape::line_breaks`]: for one line, the values of the inner coordinate where `f` is
//!   not smooth along it: bounds, edge crossings of a rotated box, rim crossings and
//!   silhouette points (roots of the discriminant of the ray–quadric equation, a quadratic
//!   along the line). The same curves cut with a line of the other family give where the
//!   shape's footprint crosses the side of an integration cell, which are outer breaks of
//!   that cell. [`Shape::labelled_breaks`] names each break's curve (for `crossings`).
//!   Bounds are breaks of boxes only: a curved shape's footprint is bounded by its rims and
//!   silhouette.
//! - [`Shape::level_breaks`], [`Shape::level_axis_breaks`]: the same for the curve where a
//!   cone's or sphere's surface meets a horizontal plane `z = h` (another shape's flat cap,
//!   a clip plane): there the length inside a boolean of the two has a kink.
//!
//! Break points are candidates: extra ones cost a little time, never accuracy.

use super::shape::{Kind, Shape, roots};
use crate::tolerance::GEOM_BOUNDS_PAD;

/// The cap rims of a frustum: `(z, radius)`.
fn caps(kind: &Kind) -> [(f64, f64); 2] {
    match *kind {
        Kind::Frustum { z0, z1, r, .. } => [(z0, r[0]), (z1, r[1])],
        _ => [(0.0, 0.0); 2],
    }
}

/// Labels of [`Shape::labelled_breaks`]: a box's bounds (2), a rotated box's edges (12), a
/// frustum's rims (2 caps × 2 crossings), a silhouette's two points. Labels from
/// [`LEVEL`] up are free for curves other than the shape's own (see
/// [`Shape::level_breaks`]).
pub(crate) const BOUND: u8 = 0;
pub(crate) const EDGE: u8 = 2;
pub(crate) const RIM: u8 = 16;
pub(crate) const SILHOUETTE: u8 = 20;
pub(crate) const LEVEL: u8 = 32;

/// The 12 edges of a box as pairs of corner indices.
const EDGES: [(usize, usize); 12] = [
    (0, 1),
    (2, 3),
    (4, 5),
    (6, 7),
    (0, 2),
    (1, 3),
    (4, 6),
    (5, 7),
    (0, 4),
    (1, 5),
    (2, 6),
    (3, 7),
];

impl Shape {
    /// The world point of the rim of the cap at `z` (radius `r`) at angle `th`.
    fn rim_point(&self, z: f64, r: f64, th: f64) -> [f64; 3] {
        self.world([r * th.cos(), r * th.sin(), z])
    }

    /// Pushes the values of world coordinate `a` (0: x, 1: y) where the structure of the
    /// shape's lines across that axis changes.
    pub fn axis_breaks(&self, a: usize, out: &mut Vec<f64>) {
        out.extend([self.lo[a], self.hi[a]]);
        match self.kind {
            Kind::Box { .. } if !self.aligned => out.extend(self.corners.iter().map(|c| c[a])),
            Kind::Frustum { k, .. } => {
                let d = [self.inv[0][2], self.inv[1][2], self.inv[2][2]];
                for (z, r) in caps(&self.kind) {
                    let c = self.world([0.0, 0.0, z]);
                    if r == 0.0 {
                        out.push(c[a]);
                        continue;
                    }
                    let reach = r * self.m[a][0].hypot(self.m[a][1]);
                    out.extend([c[a] - reach, c[a] + reach]);
                    // Contour generators end where the side's normal is horizontal on the rim:
                    // d_x cos θ + d_y sin θ = k d_z.
                    let rr = d[0].hypot(d[1]);
                    let cos = k * d[2] / rr;
                    if rr > 0.0 && cos.abs() <= 1.0 {
                        let (phi, delta) = (d[1].atan2(d[0]), cos.acos());
                        for th in [phi - delta, phi + delta] {
                            out.push(self.rim_point(z, r, th)[a]);
                        }
                    }
                }
            }
            _ => {}
        }
    }

    /// Pushes every candidate break, as values of world coordinate `1 − u`, of the
    /// vertical lines on the line `{coordinate u = c}` of the plane (`u = 0`: the line at
    /// x = c, breaks are y values; `u = 1`: the line at y = c, breaks are x values).
    pub fn line_breaks(&self, u: usize, c: f64, out: &mut Vec<f64>) {
        self.labelled_breaks(u, c, &mut |y, _| out.push(y));
    }

    /// [`Shape::line_breaks`], each with a label naming the curve it lies on and which of
    /// the curve's crossings with the line it is ([`BOUND`], [`EDGE`], [`RIM`],
    /// [`SILHOUETTE`] plus an index): as the line moves, a labelled break moves smoothly
    /// until it meets another one of the same shape or leaves the shape, which happens only
    /// at the shape's [`Shape::axis_breaks`].
    pub fn labelled_breaks(&self, u: usize, c: f64, push: &mut impl FnMut(f64, u8)) {
        let v = 1 - u;
        match self.kind {
            Kind::Box { .. } => {
                push(self.lo[v], BOUND);
                push(self.hi[v], BOUND + 1);
            }
            // The footprint of a curved shape is bounded by its rims and silhouette.
            Kind::Frustum { .. } | Kind::Sphere { .. } => {}
        }
        match self.kind {
            Kind::Box { .. } if self.aligned => {}
            Kind::Box { .. } => {
                for (e, &(i, j)) in EDGES.iter().enumerate() {
                    let (a, b) = (self.corners[i], self.corners[j]);
                    if (a[u] - c) * (b[u] - c) < 0.0 {
                        let y = a[v] + (c - a[u]) / (b[u] - a[u]) * (b[v] - a[v]);
                        push(y, EDGE + e as u8);
                    }
                }
            }
            Kind::Frustum { .. } => {
                for (cap, (z, r)) in caps(&self.kind).into_iter().enumerate() {
                    self.rim_crossings(u, c, z, r, &mut |y, i| push(y, RIM + 2 * cap as u8 + i));
                }
                self.silhouette(u, c, push);
            }
            Kind::Sphere { .. } => self.silhouette(u, c, push),
        }
    }

    /// Where the rim of the cap at `z` crosses the line `{coordinate u = c}`, as values of
    /// the other coordinate, labelled 0 and 1.
    fn rim_crossings(&self, u: usize, c: f64, z: f64, r: f64, push: &mut impl FnMut(f64, u8)) {
        let centre = self.world([0.0, 0.0, z]);
        let (a, b) = (r * self.m[u][0], r * self.m[u][1]);
        let reach = a.hypot(b);
        if !(reach > 0.0) || (c - centre[u]).abs() > reach {
            return;
        }
        let (phi, delta) = (
            b.atan2(a),
            ((c - centre[u]) / reach).clamp(-1.0, 1.0).acos(),
        );
        for (i, th) in [phi - delta, phi + delta].into_iter().enumerate() {
            push(self.rim_point(z, r, th)[1 - u], i as u8);
        }
    }

    /// Where vertical lines on the line `{coordinate u = c}` are tangent to the shape's
    /// quadric (the silhouette of the sphere, or of the infinite cone or cylinder that
    /// carries a frustum's side).
    fn silhouette(&self, u: usize, c: f64, push: &mut impl FnMut(f64, u8)) {
        let v = 1 - u;
        let mid = 0.5 * (self.lo[v] + self.hi[v]);
        let mut at = [0.0; 2];
        (at[u], at[v]) = (c, mid);
        let (p, d) = self.vertical_local(at[0], at[1]);
        let e = [self.inv[0][v], self.inv[1][v], self.inv[2][v]];
        // Along the line (origin p + η e, direction d) the quadric is a2 s² + 2 b s + c with
        // b = b0 + b1 η and c = c0 + c1 η + c2 η²; it touches where b² − a2 c = 0.
        let (a2, b0, b1, c0, c1, c2) = match self.kind {
            Kind::Frustum { k, alpha, .. } => {
                let (w0, w1, wd) = (alpha + k * p[2], k * e[2], k * d[2]);
                (
                    d[0] * d[0] + d[1] * d[1] - wd * wd,
                    p[0] * d[0] + p[1] * d[1] - w0 * wd,
                    e[0] * d[0] + e[1] * d[1] - w1 * wd,
                    p[0] * p[0] + p[1] * p[1] - w0 * w0,
                    2.0 * (p[0] * e[0] + p[1] * e[1] - w0 * w1),
                    e[0] * e[0] + e[1] * e[1] - w1 * w1,
                )
            }
            Kind::Sphere { r } => {
                let dot = super::shape::dot;
                (
                    dot(d, d),
                    dot(p, d),
                    dot(e, d),
                    dot(p, p) - r * r,
                    2.0 * dot(p, e),
                    dot(e, e),
                )
            }
            Kind::Box { .. } => return,
        };
        let qa = b1 * b1 - a2 * c2;
        let qb = 2.0 * b0 * b1 - a2 * c1;
        let qc = b0 * b0 - a2 * c0;
        if let Some((r0, r1)) = roots(qa, qb, qc) {
            for (i, y) in [mid + r0, mid + r1].into_iter().enumerate() {
                if y.is_finite() {
                    push(y, SILHOUETTE + i as u8);
                }
            }
        }
    }

    /// Whether the shape's curved surface can cross a horizontal plane along a curve that is
    /// not one of its rims: a cone, a tilted cylinder, a sphere (an upright cylinder's side
    /// is vertical, so it meets every plane along its footprint's boundary).
    pub fn has_levels(&self) -> bool {
        !matches!(self.kind, Kind::Box { .. }) && !self.prism[2]
    }

    /// Whether the shape's caps or faces include horizontal planes (an upright frustum, a
    /// box standing on a face): their heights are `lo[2]` and `hi[2]`.
    pub fn has_flat_caps(&self) -> bool {
        let row = |i: usize| self.inv[i];
        let flat = |r: [f64; 3]| r[0] == 0.0 && r[1] == 0.0 && r[2] != 0.0;
        match self.kind {
            Kind::Box { .. } => (0..3).any(|i| flat(row(i))),
            Kind::Frustum { .. } => flat(row(2)),
            Kind::Sphere { .. } => false,
        }
    }

    /// The curve where the shape's quadric meets the plane `z = h`, on the lines
    /// `{coordinate u = c}`: `(mid, m, qa, qb, qc)` such that on the line at `c = mid[u] + s`
    /// the curve's points are `mid[v] + η` with `qa η² + 2 (qb₀ + qb₁ s) η + qc₀ + 2 qc₁ s +
    /// qc₂ s² = 0`, and `m` maps `(s, η)` to local points.
    fn level(&self, u: usize, h: f64) -> Option<Level> {
        let v = 1 - u;
        let (diag, lin, c0) = match self.kind {
            Kind::Frustum { k, alpha, .. } => {
                ([1.0, 1.0, -k * k], [0.0, 0.0, -alpha * k], -alpha * alpha)
            }
            Kind::Sphere { r } => ([1.0; 3], [0.0; 3], -r * r),
            Kind::Box { .. } => return None,
        };
        let mut mid = [0.0; 2];
        mid[u] = 0.5 * (self.lo[u] + self.hi[u]);
        mid[v] = 0.5 * (self.lo[v] + self.hi[v]);
        let p0: [f64; 3] = std::array::from_fn(|i| {
            self.inv_o[i] + self.inv[i][0] * mid[0] + self.inv[i][1] * mid[1] + self.inv[i][2] * h
        });
        let eu = [self.inv[0][u], self.inv[1][u], self.inv[2][u]];
        let ev = [self.inv[0][v], self.inv[1][v], self.inv[2][v]];
        let bil = |a: [f64; 3], b: [f64; 3]| (0..3).map(|i| diag[i] * a[i] * b[i]).sum::<f64>();
        let lin_of = |a: [f64; 3]| (0..3).map(|i| lin[i] * a[i]).sum::<f64>();
        Some(Level {
            mid,
            p0,
            eu,
            ev,
            qa: bil(ev, ev),
            qb: [bil(p0, ev) + lin_of(ev), bil(eu, ev)],
            qc: [
                bil(p0, p0) + 2.0 * lin_of(p0) + c0,
                bil(p0, eu) + lin_of(eu),
                bil(eu, eu),
            ],
        })
    }

    /// Pushes where the curve of the shape's surface at height `h` crosses the line
    /// `{coordinate u = c}` (values of the other coordinate, labelled 0 and 1): where the
    /// stretch inside the shape meets a horizontal face of another shape, or a clip plane,
    /// at its end, so where the length inside their boolean has a kink.
    pub fn level_breaks(&self, u: usize, c: f64, h: f64, push: &mut impl FnMut(f64, u8)) {
        let Some(l) = self.level(u, h) else {
            return;
        };
        let s = c - l.mid[u];
        let qb = l.qb[0] + l.qb[1] * s;
        let qc = l.qc[0] + 2.0 * l.qc[1] * s + l.qc[2] * s * s;
        let Some((r0, r1)) = roots(l.qa, 2.0 * qb, qc) else {
            return;
        };
        // Only the part of a frustum's quadric between its caps is its surface.
        let slab = match self.kind {
            Kind::Frustum { z0, z1, .. } => {
                let pad = GEOM_BOUNDS_PAD * (z1 - z0);
                (z0 - pad, z1 + pad)
            }
            _ => (f64::NEG_INFINITY, f64::INFINITY),
        };
        for (i, eta) in [r0, r1].into_iter().enumerate() {
            let z = l.p0[2] + s * l.eu[2] + eta * l.ev[2];
            if eta.is_finite() && z >= slab.0 && z <= slab.1 {
                push(l.mid[1 - u] + eta, i as u8);
            }
        }
    }

    /// Pushes the values of world coordinate `a` where lines `{coordinate a = c}` are
    /// tangent to the curve of [`Shape::level_breaks`] at height `h`.
    pub fn level_axis_breaks(&self, a: usize, h: f64, out: &mut Vec<f64>) {
        let Some(l) = self.level(a, h) else {
            return;
        };
        // The discriminant (qb₀ + qb₁ s)² − qa (qc₀ + 2 qc₁ s + qc₂ s²) vanishes.
        let da = l.qb[1] * l.qb[1] - l.qa * l.qc[2];
        let db = 2.0 * (l.qb[0] * l.qb[1] - l.qa * l.qc[1]);
        let dc = l.qb[0] * l.qb[0] - l.qa * l.qc[0];
        if let Some((r0, r1)) = roots(da, db, dc) {
            out.extend(
                [r0, r1]
                    .into_iter()
                    .filter(|s| s.is_finite())
                    .map(|s| l.mid[a] + s),
            );
        }
    }
}

/// A curve of [`Shape::level_breaks`] in the frame of one family of lines.
struct Level {
    mid: [f64; 2],
    p0: [f64; 3],
    eu: [f64; 3],
    ev: [f64; 3],
    qa: f64,
    qb: [f64; 2],
    qc: [f64; 3],
}
