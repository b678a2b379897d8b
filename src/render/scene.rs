//! A model's parts prepared for rendering: exact ray intersection, silhouette hulls and the
//! per-pixel soft-silhouette kernel shared (in spirit, line by line) with `shaders/soft.wgsl`.
//!
//! Every part is a convex primitive (box, frustum, ellipsoid) under an affine world map. Its
//! 15 parameters `θ` are the 12 entries of the world matrix `[L | t]` (row-major) and three
//! primitive numbers (cube: the size; cylinder: `h, r1, r2`; sphere: `r, 0, 0`). Each is an
//! affine form in the slots, which is how gradients reach slots.
//!
//! Per view, each part's silhouette is the convex hull of its projected sample points (box
//! corners; points around a frustum's end circles; the tangency circle of a sphere), and a
//! pixel's *coverage* of the part is `sigmoid(s/σ)` with `s` the signed distance (pixels,
//! positive inside) from the pixel center to that hull. Derivatives of `s` with respect to
//! the hull's vertices, and of the vertices with respect to `θ`, give the gradient. Moving
//! sample points as material points gives the silhouette's first-order motion exactly (the
//! silhouette is an envelope), so the derivatives hold for curved parts too.
//!
//! A pixel's image is front-to-back compositing of *items* (the operands of the top-level
//! union): a part, or a boolean subtree whose visible surface is found exactly by
//! classifying the ray's segments. Two channels come out: coverage `M` and premultiplied
//! shade `S`, where a surface's shade is a linear function of its eye-space normal.

// Geometry here indexes several arrays by axis; index loops read best.
#![allow(clippy::needless_range_loop)]

use super::camera::{Frame, Vec3, cross, dot, norm, normalize};
use crate::ir::{Affine, CsgNode, Part, Primitive};

/// Number of parameters of a part.
pub const NTHETA: usize = 15;
/// Coverage is exactly 0 or 1 beyond this many σ from a silhouette.
pub const CUTOFF: f64 = 9.0;
/// Number of shading features.
pub const NSHADE: usize = 5;
/// Tolerance (pixels) of polygonal silhouettes of curved parts.
const CHORD_TOLERANCE: f64 = 0.05;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    Box,
    Frustum,
    Sphere,
}

/// One part's numeric geometry.
#[derive(Debug, Clone, PartialEq)]
pub struct PartGeom {
    pub kind: Kind,
    pub centered: bool,
    pub theta: [f64; NTHETA],
    /// World map `P = L·p + t`.
    pub l: [[f64; 3]; 3],
    pub t: Vec3,
    /// `L⁻¹` and `−L⁻¹·t`.
    pub inv: [[f64; 3]; 3],
    pub inv_t: Vec3,
    /// Local box (for a frustum: `lo.z = z0`, `hi.z = z1`).
    pub lo: Vec3,
    pub hi: Vec3,
    /// Frustum radii at `z0` and `z1`; a sphere's radius is `r1`.
    pub r1: f64,
    pub r2: f64,
    /// World position of the local box's center.
    pub center: Vec3,
    /// False for a degenerate part (singular map, negative size): it is never drawn.
    pub valid: bool,
    /// Points per circle of a curved part's silhouette; 0 chooses from the view. A fit
    /// fixes it so the polygon does not change shape as sizes change.
    pub ring: u32,
}

/// A ray's passage through a convex part: entry and exit parameters with outward normals.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hit {
    pub t0: f64,
    pub t1: f64,
    pub n0: Vec3,
    pub n1: Vec3,
}

fn mat_vec(m: &[[f64; 3]; 3], v: Vec3) -> Vec3 {
    [dot(m[0], v), dot(m[1], v), dot(m[2], v)]
}

fn det3(m: &[[f64; 3]; 3]) -> f64 {
    dot(m[0], cross(m[1], m[2]))
}

fn inverse3(m: &[[f64; 3]; 3]) -> Option<[[f64; 3]; 3]> {
    let d = det3(m);
    let scale = m.iter().flatten().fold(0.0f64, |a, v| a.max(v.abs()));
    if d.abs() <= 1e-12 * scale.powi(3) || !d.is_finite() {
        return None;
    }
    let c0 = cross(m[1], m[2]);
    let c1 = cross(m[2], m[0]);
    let c2 = cross(m[0], m[1]);
    // inverse = adjugate / det; adjugate columns are the cross products.
    Some([
        [c0[0] / d, c1[0] / d, c2[0] / d],
        [c0[1] / d, c1[1] / d, c2[1] / d],
        [c0[2] / d, c1[2] / d, c2[2] / d],
    ])
}

impl PartGeom {
    /// The numeric geometry of a part (its numbers' current values).
    pub fn from_part(p: &Part) -> PartGeom {
        let mut theta = [0.0; NTHETA];
        for i in 0..3 {
            for j in 0..4 {
                theta[4 * i + j] = p.world.m[i][j].value;
            }
        }
        let (kind, centered) = match &p.primitive {
            Primitive::Cube { size, center } => {
                for a in 0..3 {
                    theta[12 + a] = size[a].value;
                }
                (Kind::Box, *center)
            }
            Primitive::Cylinder { h, r1, r2, center } => {
                theta[12] = h.value;
                theta[13] = r1.value;
                theta[14] = r2.value;
                (Kind::Frustum, *center)
            }
            Primitive::Sphere { r } => {
                theta[12] = r.value;
                (Kind::Sphere, true)
            }
        };
        PartGeom::from_theta(kind, centered, theta)
    }

    /// Geometry from parameters.
    pub fn from_theta(kind: Kind, centered: bool, theta: [f64; NTHETA]) -> PartGeom {
        let l = [
            [theta[0], theta[1], theta[2]],
            [theta[4], theta[5], theta[6]],
            [theta[8], theta[9], theta[10]],
        ];
        let t = [theta[3], theta[7], theta[11]];
        let (lo, hi, r1, r2, sizes_ok) = match kind {
            Kind::Box => {
                let s = [theta[12], theta[13], theta[14]];
                let ok = s.iter().all(|&v| v > 0.0);
                if centered {
                    (s.map(|v| -v / 2.0), s.map(|v| v / 2.0), 0.0, 0.0, ok)
                } else {
                    ([0.0; 3], s, 0.0, 0.0, ok)
                }
            }
            Kind::Frustum => {
                let (h, r1, r2) = (theta[12], theta[13], theta[14]);
                let (z0, z1) = if centered {
                    (-h / 2.0, h / 2.0)
                } else {
                    (0.0, h)
                };
                let r = r1.max(r2);
                let ok = h > 0.0 && r1 >= 0.0 && r2 >= 0.0 && r > 0.0;
                ([-r, -r, z0], [r, r, z1], r1, r2, ok)
            }
            Kind::Sphere => {
                let r = theta[12];
                ([-r; 3], [r; 3], r, r, r > 0.0)
            }
        };
        let inv = inverse3(&l);
        let valid = sizes_ok && inv.is_some() && theta.iter().all(|v| v.is_finite());
        let inv = inv.unwrap_or([[0.0; 3]; 3]);
        let it = mat_vec(&inv, t);
        let mid = [
            (lo[0] + hi[0]) / 2.0,
            (lo[1] + hi[1]) / 2.0,
            (lo[2] + hi[2]) / 2.0,
        ];
        let center = super::camera::add(mat_vec(&l, mid), t);
        PartGeom {
            kind,
            centered,
            theta,
            l,
            t,
            inv,
            inv_t: [-it[0], -it[1], -it[2]],
            lo,
            hi,
            r1,
            r2,
            center,
            valid,
            ring: 0,
        }
    }

    /// Local coordinates of a world point.
    pub fn to_local(&self, p: Vec3) -> Vec3 {
        super::camera::add(mat_vec(&self.inv, p), self.inv_t)
    }

    /// Local direction of a world direction (same ray parameter in both frames).
    pub fn dir_to_local(&self, d: Vec3) -> Vec3 {
        mat_vec(&self.inv, d)
    }

    /// World unit normal of a local normal (`L⁻ᵀ·n`).
    pub fn normal_to_world(&self, n: Vec3) -> Vec3 {
        let m = &self.inv;
        normalize([
            m[0][0] * n[0] + m[1][0] * n[1] + m[2][0] * n[2],
            m[0][1] * n[0] + m[1][1] * n[1] + m[2][1] * n[2],
            m[0][2] * n[0] + m[1][2] * n[1] + m[2][2] * n[2],
        ])
    }

    /// World point of a local point.
    pub fn to_world(&self, p: Vec3) -> Vec3 {
        super::camera::add(mat_vec(&self.l, p), self.t)
    }

    /// The ray's exact passage through the part (world ray; parameters are the ray's).
    pub fn intersect(&self, origin: Vec3, dir: Vec3) -> Option<Hit> {
        if !self.valid {
            return None;
        }
        let o = self.to_local(origin);
        let d = self.dir_to_local(dir);
        let local = match self.kind {
            Kind::Box => intersect_box(o, d, self.lo, self.hi),
            Kind::Frustum => intersect_frustum(o, d, self.lo[2], self.hi[2], self.r1, self.r2),
            Kind::Sphere => intersect_sphere(o, d, self.r1),
        }?;
        Some(Hit {
            t0: local.t0,
            t1: local.t1,
            n0: self.normal_to_world(local.n0),
            n1: self.normal_to_world(local.n1),
        })
    }

    /// For a ray that misses the part (or nearly does): the normal of the surface the ray
    /// passes closest to, continuing the visible face past the silhouette.
    pub fn near_normal(&self, origin: Vec3, dir: Vec3) -> Vec3 {
        let o = self.to_local(origin);
        let d = self.dir_to_local(dir);
        let n = match self.kind {
            Kind::Box => {
                let mut best = f64::NEG_INFINITY;
                let mut n = [0.0, 0.0, 1.0];
                for a in 0..3 {
                    if d[a] == 0.0 {
                        continue;
                    }
                    let ta = (self.lo[a] - o[a]) / d[a];
                    let tb = (self.hi[a] - o[a]) / d[a];
                    let (near, sign) = if ta < tb { (ta, -1.0) } else { (tb, 1.0) };
                    if near > best {
                        best = near;
                        n = [0.0; 3];
                        n[a] = sign;
                    }
                }
                n
            }
            Kind::Frustum => {
                let (z0, z1) = (self.lo[2], self.hi[2]);
                let dd = d[0] * d[0] + d[1] * d[1];
                if dd <= 1e-18 * dot(d, d) {
                    [0.0, 0.0, if d[2] > 0.0 { -1.0 } else { 1.0 }]
                } else {
                    let ts = -(o[0] * d[0] + o[1] * d[1]) / dd;
                    let p = [o[0] + ts * d[0], o[1] + ts * d[1], o[2] + ts * d[2]];
                    if p[2] < z0 && d[2] > 0.0 {
                        [0.0, 0.0, -1.0]
                    } else if p[2] > z1 && d[2] < 0.0 {
                        [0.0, 0.0, 1.0]
                    } else {
                        let k = (self.r2 - self.r1) / (z1 - z0);
                        let r = (p[0] * p[0] + p[1] * p[1]).sqrt().max(1e-300);
                        [p[0] / r, p[1] / r, -k]
                    }
                }
            }
            Kind::Sphere => {
                let dd = dot(d, d).max(1e-300);
                let ts = -dot(o, d) / dd;
                [o[0] + ts * d[0], o[1] + ts * d[1], o[2] + ts * d[2]]
            }
        };
        self.normal_to_world(n)
    }
}

/// A local intersection.
struct LocalHit {
    t0: f64,
    t1: f64,
    n0: Vec3,
    n1: Vec3,
}

fn intersect_box(o: Vec3, d: Vec3, lo: Vec3, hi: Vec3) -> Option<LocalHit> {
    let mut t0 = f64::NEG_INFINITY;
    let mut t1 = f64::INFINITY;
    let mut n0 = [0.0; 3];
    let mut n1 = [0.0; 3];
    for a in 0..3 {
        if d[a] == 0.0 {
            if o[a] < lo[a] || o[a] > hi[a] {
                return None;
            }
            continue;
        }
        let ta = (lo[a] - o[a]) / d[a];
        let tb = (hi[a] - o[a]) / d[a];
        let (near, far, sign) = if ta < tb {
            (ta, tb, -1.0)
        } else {
            (tb, ta, 1.0)
        };
        if near > t0 {
            t0 = near;
            n0 = [0.0; 3];
            n0[a] = sign;
        }
        if far < t1 {
            t1 = far;
            n1 = [0.0; 3];
            n1[a] = -sign;
        }
    }
    (t0 <= t1 && t0.is_finite() && t1.is_finite()).then_some(LocalHit { t0, t1, n0, n1 })
}

fn intersect_sphere(o: Vec3, d: Vec3, r: f64) -> Option<LocalHit> {
    let a = dot(d, d);
    let b = dot(o, d);
    let c = dot(o, o) - r * r;
    let disc = b * b - a * c;
    if disc < 0.0 || a <= 0.0 {
        return None;
    }
    let q = disc.sqrt();
    let t0 = (-b - q) / a;
    let t1 = (-b + q) / a;
    let p0 = [o[0] + t0 * d[0], o[1] + t0 * d[1], o[2] + t0 * d[2]];
    let p1 = [o[0] + t1 * d[0], o[1] + t1 * d[1], o[2] + t1 * d[2]];
    Some(LocalHit {
        t0,
        t1,
        n0: p0,
        n1: p1,
    })
}

/// A frustum along local z from `z0` to `z1` with radii `r1`, `r2` there.
fn intersect_frustum(o: Vec3, d: Vec3, z0: f64, z1: f64, r1: f64, r2: f64) -> Option<LocalHit> {
    // The slab z0 ≤ z ≤ z1.
    let (mut s0, mut s1, sn0, sn1);
    if d[2] == 0.0 {
        if o[2] < z0 || o[2] > z1 {
            return None;
        }
        s0 = f64::NEG_INFINITY;
        s1 = f64::INFINITY;
        sn0 = [0.0; 3];
        sn1 = [0.0; 3];
    } else {
        let ta = (z0 - o[2]) / d[2];
        let tb = (z1 - o[2]) / d[2];
        if ta < tb {
            s0 = ta;
            s1 = tb;
            sn0 = [0.0, 0.0, -1.0];
            sn1 = [0.0, 0.0, 1.0];
        } else {
            s0 = tb;
            s1 = ta;
            sn0 = [0.0, 0.0, 1.0];
            sn1 = [0.0, 0.0, -1.0];
        }
    }
    // The cone x² + y² ≤ ρ(z)², ρ(z) = c0 + k·z.
    let k = (r2 - r1) / (z1 - z0);
    let c0 = r1 - k * z0;
    let rho_o = c0 + k * o[2];
    let a = d[0] * d[0] + d[1] * d[1] - k * k * d[2] * d[2];
    let b = 2.0 * (o[0] * d[0] + o[1] * d[1] - rho_o * k * d[2]);
    let c = o[0] * o[0] + o[1] * o[1] - rho_o * rho_o;
    let scale_a = d[0] * d[0] + d[1] * d[1] + k * k * d[2] * d[2];
    // Pieces of the line where the quadratic is ≤ 0.
    let mut pieces: [(f64, f64); 2] = [(f64::NAN, f64::NAN); 2];
    if a.abs() <= 1e-12 * scale_a {
        if b.abs() <= 1e-300 {
            if c > 0.0 {
                return None;
            }
            pieces[0] = (f64::NEG_INFINITY, f64::INFINITY);
        } else if b > 0.0 {
            pieces[0] = (f64::NEG_INFINITY, -c / b);
        } else {
            pieces[0] = (-c / b, f64::INFINITY);
        }
    } else {
        let disc = b * b - 4.0 * a * c;
        if disc < 0.0 {
            if a > 0.0 {
                return None;
            }
            pieces[0] = (f64::NEG_INFINITY, f64::INFINITY);
        } else {
            let q = disc.sqrt();
            // Numerically stable roots.
            let qq = -0.5 * (b + b.signum() * q);
            let (mut ra, mut rb) = if qq != 0.0 {
                (qq / a, c / qq)
            } else {
                (0.0, 0.0)
            };
            if ra > rb {
                std::mem::swap(&mut ra, &mut rb);
            }
            if a > 0.0 {
                pieces[0] = (ra, rb);
            } else {
                pieces[0] = (f64::NEG_INFINITY, ra);
                pieces[1] = (rb, f64::INFINITY);
            }
        }
    }
    // Keep the piece that overlaps the slab (the frustum is convex: at most one does).
    let mut best: Option<(f64, f64)> = None;
    for &(p0, p1) in &pieces {
        if p0.is_nan() {
            continue;
        }
        let lo = p0.max(s0);
        let hi = p1.min(s1);
        if lo <= hi && best.is_none_or(|(b0, b1)| hi - lo > b1 - b0) {
            best = Some((lo, hi));
        }
    }
    let (t0, t1) = best?;
    if !t0.is_finite() || !t1.is_finite() {
        return None;
    }
    let side_normal = |t: f64| -> Vec3 {
        let p = [o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2]];
        [p[0], p[1], -k * (c0 + k * p[2])]
    };
    let n0 = if t0 == s0 { sn0 } else { side_normal(t0) };
    let n1 = if t1 == s1 { sn1 } else { side_normal(t1) };
    s0 = t0;
    s1 = t1;
    Some(LocalHit {
        t0: s0,
        t1: s1,
        n0,
        n1,
    })
}

/// The point of a part's surface nearest (in the sense of its nearest face) to a world
/// point: the signed distance (world units, positive outside), the surface point in local
/// coordinates as a material point, its world unit normal, and `N·(L·∂q/∂prim)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfacePoint {
    pub sd: f64,
    pub q: Vec3,
    pub n: Vec3,
    pub ldq: [f64; 3],
}

impl PartGeom {
    /// Signed distance from a world point to the part's nearest face plane (the largest of
    /// the face distances, so exact near faces), with that face's material point.
    pub fn surface_distance(&self, p: Vec3) -> Option<SurfacePoint> {
        if !self.valid {
            return None;
        }
        let q = self.to_local(p);
        let inv = &self.inv;
        let rowlen = |a: usize| norm(inv[a]).max(1e-300);
        // World normal of a local normal and the factor from local to world distance.
        let world = |nl: Vec3| -> (Vec3, f64) {
            let w = [
                inv[0][0] * nl[0] + inv[1][0] * nl[1] + inv[2][0] * nl[2],
                inv[0][1] * nl[0] + inv[1][1] * nl[1] + inv[2][1] * nl[2],
                inv[0][2] * nl[0] + inv[1][2] * nl[1] + inv[2][2] * nl[2],
            ];
            let l = norm(w).max(1e-300);
            ([w[0] / l, w[1] / l, w[2] / l], l)
        };
        let finish = |sd: f64, qs: Vec3, n: Vec3, dq: [Vec3; 3]| -> SurfacePoint {
            let ldq = std::array::from_fn(|k| dot(n, mat_vec(&self.l, dq[k])));
            SurfacePoint { sd, q: qs, n, ldq }
        };
        let zero = [0.0; 3];
        match self.kind {
            Kind::Box => {
                let mut best = (f64::NEG_INFINITY, 0usize, false);
                for a in 0..3 {
                    let l = rowlen(a);
                    let dlo = (self.lo[a] - q[a]) / l;
                    let dhi = (q[a] - self.hi[a]) / l;
                    if dlo > best.0 {
                        best = (dlo, a, false);
                    }
                    if dhi > best.0 {
                        best = (dhi, a, true);
                    }
                }
                let (sd, a, high) = best;
                let mut qs = q;
                qs[a] = if high { self.hi[a] } else { self.lo[a] };
                let mut nl = [0.0; 3];
                nl[a] = if high { 1.0 } else { -1.0 };
                let (n, _) = world(nl);
                let mut dq = [zero; 3];
                dq[a][a] = match (self.centered, high) {
                    (true, true) => 0.5,
                    (true, false) => -0.5,
                    (false, true) => 1.0,
                    (false, false) => 0.0,
                };
                Some(finish(sd, qs, n, dq))
            }
            Kind::Frustum => {
                let (z0, z1) = (self.lo[2], self.hi[2]);
                let (dz0, dz1) = if self.centered {
                    (-0.5, 0.5)
                } else {
                    (0.0, 1.0)
                };
                let h = z1 - z0;
                let k = (self.r2 - self.r1) / h;
                let rho = (q[0] * q[0] + q[1] * q[1]).sqrt();
                let (c, s) = if rho > 1e-300 {
                    (q[0] / rho, q[1] / rho)
                } else {
                    (1.0, 0.0)
                };
                let rs = self.r1 + k * (q[2] - z0);
                let kk = (1.0 + k * k).sqrt();
                let (ns, ws) = world([c / kk, s / kk, -k / kk]);
                let side = (rho - rs) / kk / ws;
                let l2 = rowlen(2);
                let bottom = (z0 - q[2]) / l2;
                let top = (q[2] - z1) / l2;
                if side >= bottom && side >= top {
                    let v = (q[2] - z0) / h;
                    let qs = [rs * c, rs * s, q[2]];
                    let dq = [
                        [0.0, 0.0, dz0 + v * (dz1 - dz0)],
                        [(1.0 - v) * c, (1.0 - v) * s, 0.0],
                        [v * c, v * s, 0.0],
                    ];
                    Some(finish(side, qs, ns, dq))
                } else if bottom >= top {
                    let (n, _) = world([0.0, 0.0, -1.0]);
                    Some(finish(
                        bottom,
                        [q[0], q[1], z0],
                        n,
                        [[0.0, 0.0, dz0], zero, zero],
                    ))
                } else {
                    let (n, _) = world([0.0, 0.0, 1.0]);
                    Some(finish(
                        top,
                        [q[0], q[1], z1],
                        n,
                        [[0.0, 0.0, dz1], zero, zero],
                    ))
                }
            }
            Kind::Sphere => {
                let r = self.r1;
                let rho = norm(q).max(1e-300);
                let nl = [q[0] / rho, q[1] / rho, q[2] / rho];
                let (n, w) = world(nl);
                let sd = (rho - r) / w;
                Some(finish(
                    sd,
                    [nl[0] * r, nl[1] * r, nl[2] * r],
                    n,
                    [nl, zero, zero],
                ))
            }
        }
    }
}

/// `∂sd/∂θ` of a surface point: minus the normal motion of its material point.
pub fn surface_jacobian(sp_n: Vec3, q: Vec3, ldq: [f64; 3]) -> [f64; NTHETA] {
    let mut j = [0.0; NTHETA];
    for i in 0..3 {
        for k in 0..3 {
            j[4 * i + k] = -sp_n[i] * q[k];
        }
        j[4 * i + 3] = -sp_n[i];
    }
    for k in 0..3 {
        j[12 + k] = -ldq[k];
    }
    j
}

/// One step of an item's boolean program (postfix).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Op {
    Part(u32),
    Union(u32),
    /// The first of `n` operands minus the others.
    Difference(u32),
    Intersection(u32),
}

/// An operand of the top-level union.
#[derive(Debug, Clone, PartialEq)]
pub struct Item {
    pub program: Vec<Op>,
    /// The parts the program mentions, in order.
    pub parts: Vec<usize>,
    /// For `difference() { A; B; ... }` whose subtracted operands are parts or unions of
    /// parts: the length of `A`'s program (a prefix) and the subtracted parts. Their edges
    /// on `A`'s surface are then soft too (the rim of a mug's hollow).
    pub split: Option<(usize, Vec<usize>)>,
}

impl Item {
    pub fn is_single(&self) -> bool {
        self.program.len() == 1
    }

    /// The program of the first operand of a split difference.
    pub fn positive(&self) -> &[Op] {
        match &self.split {
            Some((k, _)) => &self.program[..*k],
            None => &self.program,
        }
    }
}

/// The split of a difference program (see [`Item::split`]).
fn split_difference(program: &[Op]) -> Option<(usize, Vec<usize>)> {
    let Some(&Op::Difference(n)) = program.last() else {
        return None;
    };
    // Start of each operand on the stack.
    let mut starts: Vec<usize> = Vec::new();
    for (i, op) in program[..program.len() - 1].iter().enumerate() {
        match *op {
            Op::Part(_) => starts.push(i),
            Op::Union(k) | Op::Difference(k) | Op::Intersection(k) => {
                let at = starts.len().checked_sub(k as usize)?;
                let s = starts[at];
                starts.truncate(at);
                starts.push(s);
            }
        }
    }
    if starts.len() != n as usize || n < 2 {
        return None;
    }
    let positive = starts[1];
    let mut negatives = Vec::new();
    for op in &program[positive..program.len() - 1] {
        match *op {
            Op::Part(i) => negatives.push(i as usize),
            Op::Union(_) => {}
            _ => return None,
        }
    }
    Some((positive, negatives))
}

/// Splits a CSG tree into the operands of its top-level union (nested unions flattened).
pub fn items_of(csg: &CsgNode) -> Vec<Item> {
    fn flatten<'a>(n: &'a CsgNode, out: &mut Vec<&'a CsgNode>) {
        match n {
            CsgNode::Union(c) => c.iter().for_each(|c| flatten(c, out)),
            other => out.push(other),
        }
    }
    fn compile(n: &CsgNode, prog: &mut Vec<Op>) -> bool {
        let (children, op): (&Vec<CsgNode>, fn(u32) -> Op) = match n {
            CsgNode::Part(i) => {
                prog.push(Op::Part(*i as u32));
                return true;
            }
            CsgNode::Union(c) => (c, Op::Union),
            CsgNode::Difference(c) => (c, Op::Difference),
            CsgNode::Intersection(c) => (c, Op::Intersection),
        };
        let mut n = 0;
        for c in children {
            if compile(c, prog) {
                n += 1;
            }
        }
        if n == 0 {
            return false;
        }
        if n > 1 {
            prog.push(op(n));
        }
        true
    }
    let mut tops = Vec::new();
    flatten(csg, &mut tops);
    tops.into_iter()
        .filter_map(|n| {
            let mut program = Vec::new();
            if !compile(n, &mut program) {
                return None;
            }
            let mut parts: Vec<usize> = Vec::new();
            for op in &program {
                if let Op::Part(i) = op
                    && !parts.contains(&(*i as usize))
                {
                    parts.push(*i as usize);
                }
            }
            let split = split_difference(&program);
            Some(Item {
                program,
                parts,
                split,
            })
        })
        .collect()
}

/// Evaluates a boolean program: is the point inside, given each part's membership?
pub fn eval_inside(program: &[Op], inside: &dyn Fn(usize) -> bool) -> bool {
    let mut stack: Vec<bool> = Vec::with_capacity(8);
    for op in program {
        match *op {
            Op::Part(i) => stack.push(inside(i as usize)),
            Op::Union(n) => {
                let at = stack.len() - n as usize;
                let v = stack[at..].iter().any(|&b| b);
                stack.truncate(at);
                stack.push(v);
            }
            Op::Difference(n) => {
                let at = stack.len() - n as usize;
                let v = stack[at] && !stack[at + 1..].iter().any(|&b| b);
                stack.truncate(at);
                stack.push(v);
            }
            Op::Intersection(n) => {
                let at = stack.len() - n as usize;
                let v = stack[at..].iter().all(|&b| b);
                stack.truncate(at);
                stack.push(v);
            }
        }
    }
    stack.pop().unwrap_or(false)
}

/// Soft coverage of a program from its parts' coverages, with the derivative with respect
/// to part `seed`'s coverage: union `1 − Π(1 − a)`, intersection `Π a`, difference: its
/// first operand (holes are decided exactly, not softly).
pub fn eval_soft(program: &[Op], alpha: &dyn Fn(usize) -> f64, seed: Option<usize>) -> (f64, f64) {
    let mut stack: Vec<(f64, f64)> = Vec::with_capacity(8);
    for op in program {
        match *op {
            Op::Part(i) => {
                let d = if seed == Some(i as usize) { 1.0 } else { 0.0 };
                stack.push((alpha(i as usize), d));
            }
            Op::Union(n) => {
                let at = stack.len() - n as usize;
                // 1 − Π(1 − a): value and forward derivative.
                let (mut p, mut dp) = (1.0, 0.0);
                for &(a, da) in &stack[at..] {
                    dp = dp * (1.0 - a) - p * da;
                    p *= 1.0 - a;
                }
                stack.truncate(at);
                stack.push((1.0 - p, -dp));
            }
            Op::Difference(n) => {
                let at = stack.len() - n as usize;
                let first = stack[at];
                stack.truncate(at);
                stack.push(first);
            }
            Op::Intersection(n) => {
                let at = stack.len() - n as usize;
                let (mut p, mut dp) = (1.0, 0.0);
                for &(a, da) in &stack[at..] {
                    dp = dp * a + p * da;
                    p *= a;
                }
                stack.truncate(at);
                stack.push((p, dp));
            }
        }
    }
    stack.pop().unwrap_or((0.0, 0.0))
}

/// A silhouette sample point of a part: its local position and its derivative with respect
/// to the three primitive parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    pub local: Vec3,
    pub dprim: [Vec3; 3],
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
            edges: [(e1 as u32, 0.0), (0, 0.0)],
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

/// A pixel's soft coverage of one hull.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Coverage {
    pub alpha: f64,
    /// Signed distance to the nearest edge (pixels, positive inside).
    pub s: f64,
    /// `(edge, ∂α/∂s_edge)` for the first `n` entries.
    pub edges: [(u32, f64); 2],
    pub n: usize,
}

#[inline]
pub fn logistic(x: f64) -> f64 {
    1.0 / (1.0 + (-x).exp())
}

/// The local sample points whose projections bound the part's silhouette in this view.
pub fn samples(p: &PartGeom, frame: &Frame) -> Vec<Sample> {
    let zero = [0.0; 3];
    match p.kind {
        Kind::Box => (0..8)
            .map(|c| {
                let mut local = [0.0; 3];
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
                    local: [p.r1 * c, p.r1 * s, z0],
                    dprim: [[0.0, 0.0, dz0], [c, s, 0.0], zero],
                });
                out.push(Sample {
                    local: [p.r2 * c, p.r2 * s, z1],
                    dprim: [[0.0, 0.0, dz1], zero, [c, s, 0.0]],
                });
            }
            out
        }
        Kind::Sphere => {
            let r = p.r1;
            let n = ring_count(p, frame, r);
            // The tangency circle seen from the eye (or along the view, orthographic).
            let (axis, center, radius) = if frame.ortho {
                (normalize(p.dir_to_local(frame.forward)), [0.0; 3], r)
            } else {
                let e = p.to_local(frame.eye);
                let dist = norm(e);
                if dist <= r * (1.0 + 1e-9) {
                    return Vec::new();
                }
                let f = r * r / (dist * dist);
                let center = [e[0] * f, e[1] * f, e[2] * f];
                (normalize(e), center, r * (1.0 - f).sqrt())
            };
            let helper = if axis[0].abs() < 0.9 {
                [1.0, 0.0, 0.0]
            } else {
                [0.0, 1.0, 0.0]
            };
            let u = normalize(cross(axis, helper));
            let v = cross(axis, u);
            (0..n)
                .map(|k| {
                    let phi = std::f64::consts::TAU * (k as f64 + 0.5) / n as f64;
                    let (s, c) = phi.sin_cos();
                    let local = [
                        center[0] + radius * (c * u[0] + s * v[0]),
                        center[1] + radius * (c * u[1] + s * v[1]),
                        center[2] + radius * (c * u[2] + s * v[2]),
                    ];
                    Sample {
                        local,
                        dprim: [[local[0] / r, local[1] / r, local[2] / r], zero, zero],
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
    let stretch = (0..3)
        .map(|j| norm([p.l[0][j], p.l[1][j], p.l[2][j]]))
        .fold(0.0f64, f64::max);
    let world_r = r * stretch;
    let px_per_unit = if frame.ortho {
        frame.focal
    } else {
        let z = frame.depth(p.center) - world_r;
        if z <= 1e-9 {
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
    let eps = 1e-12 * span * span;
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
            let dp = mat_vec(&p.l, s.dprim[q]);
            j[r][12 + q] = dot(*row, dp);
        }
    }
    Some(j)
}

/// The shading features of an eye-space normal: `1, n_x, n_y, n_z, |n·l|` with OpenSCAD's
/// light direction `l = (−1, −1, 1)/√3`.
#[inline]
pub fn shade_features(n: Vec3) -> [f64; NSHADE] {
    let k = 1.0 / 3f64.sqrt();
    [1.0, n[0], n[1], n[2], (k * (-n[0] - n[1] + n[2])).abs()]
}

/// Default shading coefficients: faces of every orientation get different greys.
pub const DEFAULT_SHADE: [f64; NSHADE] = [0.45, -0.12, 0.3, 0.1, 0.15];

/// The slot forms of a part's 15 parameters (`None` for a constant or a non-affine one).
pub fn theta_forms(p: &Part) -> [Option<Affine>; NTHETA] {
    let mut out: [Option<Affine>; NTHETA] = Default::default();
    let keep = |n: &crate::ir::Num| n.affine().filter(|a| !a.is_constant()).cloned();
    for i in 0..3 {
        for j in 0..4 {
            out[4 * i + j] = keep(&p.world.m[i][j]);
        }
    }
    match &p.primitive {
        Primitive::Cube { size, .. } => {
            for a in 0..3 {
                out[12 + a] = keep(&size[a]);
            }
        }
        Primitive::Cylinder { h, r1, r2, .. } => {
            out[12] = keep(h);
            out[13] = keep(r1);
            out[14] = keep(r2);
        }
        Primitive::Sphere { r } => out[12] = keep(r),
    }
    out
}

/// The parameters of a part at slot values `x` (non-affine numbers keep their value).
pub fn theta_at(p: &Part, forms: &[Option<Affine>; NTHETA], x: &[f64]) -> [f64; NTHETA] {
    let mut theta = PartGeom::from_part(p).theta;
    for (k, f) in forms.iter().enumerate() {
        if let Some(f) = f {
            theta[k] = f.eval(x);
        }
    }
    theta
}

/// A model's parts, ready for rendering.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    pub parts: Vec<PartGeom>,
    pub items: Vec<Item>,
}

impl Scene {
    pub fn new(parts: Vec<PartGeom>, csg: &CsgNode) -> Scene {
        let items = items_of(csg)
            .into_iter()
            .filter(|it| it.parts.iter().all(|&p| p < parts.len()))
            .collect();
        Scene { parts, items }
    }

    pub fn from_parts(parts: &[Part], csg: &CsgNode) -> Scene {
        Scene::new(parts.iter().map(PartGeom::from_part).collect(), csg)
    }

    /// World bounding box of the drawn parts (`None` if nothing is drawn).
    pub fn bounds(&self) -> Option<(Vec3, Vec3)> {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        let mut any = false;
        for it in &self.items {
            for &i in &it.parts {
                let p = &self.parts[i];
                if !p.valid {
                    continue;
                }
                any = true;
                for c in 0..8 {
                    let q =
                        std::array::from_fn(|a| if c >> a & 1 == 0 { p.lo[a] } else { p.hi[a] });
                    let w = p.to_world(q);
                    for a in 0..3 {
                        lo[a] = lo[a].min(w[a]);
                        hi[a] = hi[a].max(w[a]);
                    }
                }
            }
        }
        any.then_some((lo, hi))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit() -> [f64; NTHETA] {
        let mut t = [0.0; NTHETA];
        t[0] = 1.0;
        t[5] = 1.0;
        t[10] = 1.0;
        t
    }

    #[test]
    fn box_hit_and_normals() {
        let mut th = unit();
        th[12..15].copy_from_slice(&[2.0, 2.0, 2.0]);
        let p = PartGeom::from_theta(Kind::Box, true, th);
        let h = p.intersect([0.0, -10.0, 0.5], [0.0, 1.0, 0.0]).unwrap();
        assert!((h.t0 - 9.0).abs() < 1e-12 && (h.t1 - 11.0).abs() < 1e-12);
        assert_eq!(h.n0, [0.0, -1.0, 0.0]);
        assert_eq!(h.n1, [0.0, 1.0, 0.0]);
        assert!(p.intersect([0.0, -10.0, 1.5], [0.0, 1.0, 0.0]).is_none());
    }

    #[test]
    fn frustum_hits_side_and_caps() {
        let mut th = unit();
        th[12..15].copy_from_slice(&[10.0, 4.0, 2.0]);
        let p = PartGeom::from_theta(Kind::Frustum, false, th);
        // Along x at z = 5: radius 3.
        let h = p.intersect([-10.0, 0.0, 5.0], [1.0, 0.0, 0.0]).unwrap();
        assert!((h.t0 - 7.0).abs() < 1e-9 && (h.t1 - 13.0).abs() < 1e-9);
        assert!(h.n0[0] < 0.0 && h.n0[2] > 0.0);
        // Down the axis: top cap then bottom cap.
        let h = p.intersect([0.0, 0.0, 20.0], [0.0, 0.0, -1.0]).unwrap();
        assert!((h.t0 - 10.0).abs() < 1e-9 && (h.t1 - 20.0).abs() < 1e-9);
        assert_eq!(h.n0, [0.0, 0.0, 1.0]);
        assert!(p.intersect([3.5, 0.0, 20.0], [0.0, 0.0, -1.0]).is_some());
        assert!(p.intersect([4.5, 0.0, 20.0], [0.0, 0.0, -1.0]).is_none());
        // A cone to a point.
        th[14] = 0.0;
        let c = PartGeom::from_theta(Kind::Frustum, false, th);
        let h = c.intersect([-10.0, 0.0, 5.0], [1.0, 0.0, 0.0]).unwrap();
        assert!((h.t1 - h.t0 - 4.0).abs() < 1e-9);
    }

    #[test]
    fn sphere_under_scale() {
        let mut th = unit();
        th[0] = 2.0;
        th[12] = 1.0;
        let p = PartGeom::from_theta(Kind::Sphere, true, th);
        let h = p.intersect([-10.0, 0.0, 0.0], [1.0, 0.0, 0.0]).unwrap();
        assert!((h.t0 - 8.0).abs() < 1e-9 && (h.t1 - 12.0).abs() < 1e-9);
        assert!((h.n0[0] + 1.0).abs() < 1e-9);
    }

    #[test]
    fn soft_union_derivative() {
        let prog = [Op::Part(0), Op::Part(1), Op::Union(2)];
        let a = |i: usize| [0.3, 0.6][i];
        let (v, d) = eval_soft(&prog, &a, Some(0));
        assert!((v - (1.0 - 0.7 * 0.4)).abs() < 1e-12);
        assert!((d - 0.4).abs() < 1e-12);
    }

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
