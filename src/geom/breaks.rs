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
//!   that cell.
//!
//! Break points are candidates: extra ones cost a little time, never accuracy.

use super::shape::{Kind, Shape, roots};

/// The cap rims of a frustum: `(z, radius)`.
fn caps(kind: &Kind) -> [(f64, f64); 2] {
    match *kind {
        Kind::Frustum { z0, z1, r, .. } => [(z0, r[0]), (z1, r[1])],
        _ => [(0.0, 0.0); 2],
    }
}

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
        let v = 1 - u;
        out.extend([self.lo[v], self.hi[v]]);
        match self.kind {
            Kind::Box { .. } if self.aligned => {}
            Kind::Box { .. } => {
                for &(i, j) in &EDGES {
                    let (a, b) = (self.corners[i], self.corners[j]);
                    if (a[u] - c) * (b[u] - c) < 0.0 {
                        out.push(a[v] + (c - a[u]) / (b[u] - a[u]) * (b[v] - a[v]));
                    }
                }
            }
            Kind::Frustum { .. } => {
                for (z, r) in caps(&self.kind) {
                    self.rim_crossings(u, c, z, r, out);
                }
                self.silhouette(u, c, out);
            }
            Kind::Sphere { .. } => self.silhouette(u, c, out),
        }
    }

    /// Where the rim of the cap at `z` crosses the line `{coordinate u = c}`, as values of
    /// the other coordinate.
    fn rim_crossings(&self, u: usize, c: f64, z: f64, r: f64, out: &mut Vec<f64>) {
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
        for th in [phi - delta, phi + delta] {
            out.push(self.rim_point(z, r, th)[1 - u]);
        }
    }

    /// Where vertical lines on the line `{coordinate u = c}` are tangent to the shape's
    /// quadric (the silhouette of the sphere, or of the infinite cone or cylinder that
    /// carries a frustum's side).
    fn silhouette(&self, u: usize, c: f64, out: &mut Vec<f64>) {
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
            out.extend([mid + r0, mid + r1].into_iter().filter(|y| y.is_finite()));
        }
    }
}
