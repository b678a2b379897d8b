//! A part's silhouette in one view: sample points whose projections bound it, their convex
//! hull (counter-clockwise in pixels), a pixel's soft coverage of that hull, and the
//! jacobians from hull vertices back to the part's parameters.

use super::{CUTOFF, Kind, NTHETA, PartGeom};
use crate::render::camera::{Frame, unit};
use crate::tolerance::{NEAR_DEPTH, PARALLEL_SINE, RENDER_ROUNDOFF};
use glam::DVec3;

/// Tolerance (pixels) of polygonal silhouettes of curved parts.
const CHORD_TOLERANCE: f64 = 0.05;

/// A silhouette sample point of a part: its local position and its derivative with respect
/// to the three primitive parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    pub local: DVec3,
    pub dprim: [DVec3; 3],
}

/// A part's silhouette in one view: a convex polygon (counter-clockwise in pixel
/// coordinates), with each vertex's sample point.
#[derive(Debug, Clone, PartialEq)]
pub struct Hull {
    pub verts: Vec<[f64; 2]>,
    pub src: Vec<u32>,
    /// Outward unit normal and offset of each edge `i → i+1`: `d = n·u − c`.
    pub edges: Vec<([f64; 2], f64)>,
    pub samples: Vec<Sample>,
    /// Pixel bounding box of the polygon.
    pub lo: [f64; 2],
    pub hi: [f64; 2],
}

impl Hull {
    /// Signed distance (pixels, positive inside) from `u` to the polygon, and the edge that
    /// decides it.
    #[inline]
    pub fn signed_distance(&self, u: [f64; 2]) -> (f64, usize) {
        let mut best = f64::NEG_INFINITY;
        let mut at = 0;
        for (i, &(n, c)) in self.edges.iter().enumerate() {
            let d = n[0] * u[0] + n[1] * u[1] - c;
            if d > best {
                best = d;
                at = i;
            }
        }
        (-best, at)
    }

    /// Soft coverage of pixel `u` with edge softness `sigma`, and `∂α/∂s` for the (at most
    /// two) edges it depends on.
    ///
    /// Near one edge the coverage is `sigmoid(s/σ)`. Where the polygon is thin (an edge
    /// roughly opposite the nearest one is also near), the far side is subtracted too:
    /// `α = max(0, 1 − σ(d₁/σ) − σ(d₂/σ))` with `d = −s` the outward distances. That keeps a
    /// thin part's total coverage equal to its area at any softness, so blurring never
    /// pushes thin parts to vanish.
    #[inline]
    pub fn coverage(&self, u: [f64; 2], sigma: f64) -> Coverage {
        let (s1, e1) = self.signed_distance(u);
        let mut c = Coverage {
            alpha: 0.0,
            s: s1,
            edges: [(e1 as u32, 0.0); COVERAGE_EDGES],
            at: [u; COVERAGE_EDGES],
            n: 0,
        };
        let band = CUTOFF * sigma;
        if s1 <= -band {
            return c;
        }
        if s1 >= band {
            c.alpha = 1.0;
            return c;
        }
        let n1 = self.edges[e1].0;
        // The nearest roughly opposite edge.
        let mut d2 = f64::NEG_INFINITY;
        let mut e2 = usize::MAX;
        for (i, &(n, off)) in self.edges.iter().enumerate() {
            if n[0] * n1[0] + n[1] * n1[1] < -0.7 {
                let d = n[0] * u[0] + n[1] * u[1] - off;
                if d > d2 {
                    d2 = d;
                    e2 = i;
                }
            }
        }
        let f1 = logistic(-s1 / sigma);
        let (f2, use2) = if e2 != usize::MAX && d2 > -band {
            (logistic(d2 / sigma), true)
        } else {
            (0.0, false)
        };
        let a = 1.0 - f1 - f2;
        if a <= 0.0 {
            return c;
        }
        c.alpha = a;
        // ∂α/∂s = σ'(d/σ)/σ with s = −d.
        c.edges[0].1 = f1 * (1.0 - f1) / sigma;
        c.n = 1;
        if use2 {
            c.edges[1] = (e2 as u32, f2 * (1.0 - f2) / sigma);
            c.n = 2;
        }
        c
    }

    /// `∂s/∂a` and `∂s/∂b` for edge `i` (`a` its start vertex, `b` its end).
    pub fn edge_gradient(&self, i: usize, u: [f64; 2]) -> ([f64; 2], [f64; 2]) {
        let a = self.verts[i];
        let b = self.verts[(i + 1) % self.verts.len()];
        let e = [b[0] - a[0], b[1] - a[1]];
        let len2 = e[0] * e[0] + e[1] * e[1];
        let len = len2.sqrt();
        let w = [u[0] - a[0], u[1] - a[1]];
        let d = (w[0] * e[1] - w[1] * e[0]) / len;
        let n = [e[1] / len, -e[0] / len];
        let dd_db = [-w[1] / len - d * e[0] / len2, w[0] / len - d * e[1] / len2];
        let dd_da = [-n[0] - dd_db[0], -n[1] - dd_db[1]];
        // s = −d
        ([-dd_da[0], -dd_da[1]], [-dd_db[0], -dd_db[1]])
    }
}

/// Most edges a pixel's coverage depends on (a box filter's pixel may see a corner and a
/// far side; more than this are left out of the gradient).
pub const COVERAGE_EDGES: usize = 4;

/// A pixel's soft coverage of one hull.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Coverage {
    pub alpha: f64,
    /// Signed distance to the nearest edge (pixels, positive inside).
    pub s: f64,
    /// `(edge, ∂α/∂s_edge)` for the first `n` entries.
    pub edges: [(u32, f64); COVERAGE_EDGES],
    /// Where each edge's `∂s` is taken: the pixel's centre for a sigmoid, the middle of the
    /// edge's piece inside the pixel for the box filter.
    pub at: [[f64; 2]; COVERAGE_EDGES],
    pub n: usize,
}

#[inline]
pub fn logistic(x: f64) -> f64 {
    1.0 / (1.0 + (-x).exp())
}

/// The local sample points whose projections bound the part's silhouette in this view.
pub fn samples(p: &PartGeom, frame: &Frame) -> Vec<Sample> {
    let zero = DVec3::ZERO;
    match p.kind {
        Kind::Box => (0..8)
            .map(|c| {
                let mut local = DVec3::ZERO;
                let mut dprim = [zero; 3];
                for a in 0..3 {
                    let high = c >> a & 1 == 1;
                    local[a] = if high { p.hi[a] } else { p.lo[a] };
                    dprim[a][a] = match (p.centered, high) {
                        (true, true) => 0.5,
                        (true, false) => -0.5,
                        (false, true) => 1.0,
                        (false, false) => 0.0,
                    };
                }
                Sample { local, dprim }
            })
            .collect(),
        Kind::Frustum => {
            let (z0, z1) = (p.lo[2], p.hi[2]);
            let n = ring_count(p, frame, p.r1.max(p.r2));
            let (dz0, dz1) = if p.centered { (-0.5, 0.5) } else { (0.0, 1.0) };
            let mut out = Vec::with_capacity(2 * n);
            for k in 0..n {
                let phi = std::f64::consts::TAU * (k as f64 + 0.5) / n as f64;
                let (s, c) = phi.sin_cos();
                out.push(Sample {
                    local: DVec3::new(p.r1 * c, p.r1 * s, z0),
                    dprim: [DVec3::new(0.0, 0.0, dz0), DVec3::new(c, s, 0.0), zero],
                });
                out.push(Sample {
                    local: DVec3::new(p.r2 * c, p.r2 * s, z1),
                    dprim: [DVec3::new(0.0, 0.0, dz1), zero, DVec3::new(c, s, 0.0)],
                });
            }
            out
        }
        Kind::Sphere => {
            let r = p.r1;
            let n = ring_count(p, frame, r);
            // The tangency circle seen from the eye (or along the view, orthographic).
            let (axis, center, radius) = if frame.ortho {
                (unit(p.dir_to_local(frame.forward)), DVec3::ZERO, r)
            } else {
                let e = p.to_local(frame.eye);
                let dist = e.length();
                if dist <= r * (1.0 + PARALLEL_SINE) {
                    return Vec::new();
                }
                let f = r * r / (dist * dist);
                (unit(e), e * f, r * (1.0 - f).sqrt())
            };
            let helper = if axis[0].abs() < 0.9 {
                DVec3::X
            } else {
                DVec3::Y
            };
            let u = unit(axis.cross(helper));
            let v = axis.cross(u);
            (0..n)
                .map(|k| {
                    let phi = std::f64::consts::TAU * (k as f64 + 0.5) / n as f64;
                    let (s, c) = phi.sin_cos();
                    let local = center + (u * c + v * s) * radius;
                    Sample {
                        local,
                        dprim: [local / r, zero, zero],
                    }
                })
                .collect()
        }
    }
}

/// Points per circle so the polygon is within [`CHORD_TOLERANCE`] pixels of the circle
/// (or the part's fixed count).
pub fn ring_count(p: &PartGeom, frame: &Frame, r: f64) -> usize {
    if p.ring > 0 {
        return p.ring as usize;
    }
    let stretch = (0..3).map(|j| p.l.col(j).length()).fold(0.0f64, f64::max);
    let world_r = r * stretch;
    let px_per_unit = if frame.ortho {
        frame.focal
    } else {
        let z = frame.depth(p.center) - world_r;
        if z <= NEAR_DEPTH {
            return 128;
        }
        frame.focal / z
    };
    let r_px = world_r * px_per_unit;
    let n = (std::f64::consts::PI * (r_px / (2.0 * CHORD_TOLERANCE)).sqrt()).ceil();
    (n as usize).clamp(8, 128)
}

/// The hull of a part in a view, or `None` when some sample is behind the eye (the part is
/// then drawn with hard edges only).
pub fn hull(p: &PartGeom, frame: &Frame) -> Option<Hull> {
    if !p.valid {
        return None;
    }
    let samples = samples(p, frame);
    if samples.is_empty() {
        return None;
    }
    let mut pts: Vec<([f64; 2], u32)> = Vec::with_capacity(samples.len());
    for (i, s) in samples.iter().enumerate() {
        let (u, _) = frame.project(p.to_world(s.local))?;
        pts.push((u, i as u32));
    }
    let hull_pts = convex_hull(&mut pts);
    if hull_pts.len() < 3 {
        return None;
    }
    let verts: Vec<[f64; 2]> = hull_pts.iter().map(|h| h.0).collect();
    let src: Vec<u32> = hull_pts.iter().map(|h| h.1).collect();
    let m = verts.len();
    let mut edges = Vec::with_capacity(m);
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for i in 0..m {
        let a = verts[i];
        let b = verts[(i + 1) % m];
        let e = [b[0] - a[0], b[1] - a[1]];
        let len = (e[0] * e[0] + e[1] * e[1]).sqrt();
        let n = [e[1] / len, -e[0] / len];
        edges.push((n, n[0] * a[0] + n[1] * a[1]));
        for k in 0..2 {
            lo[k] = lo[k].min(a[k]);
            hi[k] = hi[k].max(a[k]);
        }
    }
    Some(Hull {
        verts,
        src,
        edges,
        samples,
        lo,
        hi,
    })
}

/// Andrew's monotone chain; counter-clockwise, no collinear points, no duplicates.
fn convex_hull(pts: &mut [([f64; 2], u32)]) -> Vec<([f64; 2], u32)> {
    pts.sort_by(|a, b| a.0[0].total_cmp(&b.0[0]).then(a.0[1].total_cmp(&b.0[1])));
    let turn = |o: [f64; 2], a: [f64; 2], b: [f64; 2]| {
        (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    };
    let span = pts
        .iter()
        .fold(0.0f64, |m, p| m.max(p.0[0].abs()).max(p.0[1].abs()))
        .max(1.0);
    let eps = RENDER_ROUNDOFF * span * span;
    let mut h: Vec<([f64; 2], u32)> = Vec::with_capacity(pts.len() + 1);
    for &p in pts.iter() {
        while h.len() >= 2 && turn(h[h.len() - 2].0, h[h.len() - 1].0, p.0) <= eps {
            h.pop();
        }
        h.push(p);
    }
    let lower = h.len() + 1;
    for &p in pts.iter().rev().skip(1) {
        while h.len() >= lower && turn(h[h.len() - 2].0, h[h.len() - 1].0, p.0) <= eps {
            h.pop();
        }
        h.push(p);
    }
    h.pop();
    h
}

/// `∂(pixel)/∂θ` of a sample point (2 rows of 15).
pub fn sample_jacobian(p: &PartGeom, s: &Sample, frame: &Frame) -> Option<[[f64; NTHETA]; 2]> {
    let world = p.to_world(s.local);
    let (_, du) = frame.project(world)?;
    let mut j = [[0.0; NTHETA]; 2];
    for (r, row) in du.iter().enumerate() {
        for i in 0..3 {
            for k in 0..3 {
                j[r][4 * i + k] = row[i] * s.local[k];
            }
            j[r][4 * i + 3] = row[i];
        }
        for q in 0..3 {
            let dp = p.l * s.dprim[q];
            j[r][12 + q] = row.dot(dp);
        }
    }
    Some(j)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hull_edge_gradient_matches_differences() {
        let mut h = Hull {
            verts: vec![[0.0, 0.0], [4.0, 0.5], [3.0, 3.0], [0.5, 2.0]],
            src: vec![0, 1, 2, 3],
            edges: vec![],
            samples: vec![],
            lo: [0.0; 2],
            hi: [4.0, 3.0],
        };
        let rebuild = |h: &mut Hull| {
            h.edges.clear();
            for i in 0..h.verts.len() {
                let a = h.verts[i];
                let b = h.verts[(i + 1) % h.verts.len()];
                let e = [b[0] - a[0], b[1] - a[1]];
                let len = (e[0] * e[0] + e[1] * e[1]).sqrt();
                let n = [e[1] / len, -e[0] / len];
                h.edges.push((n, n[0] * a[0] + n[1] * a[1]));
            }
        };
        rebuild(&mut h);
        let u = [2.5, -0.7];
        let (s, e) = h.signed_distance(u);
        assert!(s < 0.0);
        let (ga, gb) = h.edge_gradient(e, u);
        let eps = 1e-6;
        for (vi, g) in [(e, ga), ((e + 1) % 4, gb)] {
            for k in 0..2 {
                let mut h2 = h.clone();
                h2.verts[vi][k] += eps;
                rebuild(&mut h2);
                let s2 = -(h2.edges[e].0[0] * u[0] + h2.edges[e].0[1] * u[1] - h2.edges[e].1);
                assert!(((s2 - s) / eps - g[k]).abs() < 1e-5);
            }
        }
    }
}
