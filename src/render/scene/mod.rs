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
//!
//! This module owns the part geometry (`PartGeom`, its world/local maps and nearest-face
//! distance), the parameter forms and the `Scene`; `intersect` owns exact ray passages,
//! `items` the boolean programs, `hull` the per-view silhouettes and their jacobians.

// Geometry here indexes several arrays by axis; index loops read best.
#![allow(clippy::needless_range_loop)]

mod hull;
mod intersect;
mod items;

pub use hull::{Coverage, Hull, Sample, hull, logistic, ring_count, sample_jacobian, samples};
pub use items::{Item, Op, eval_inside, eval_soft, items_of};

use super::camera::{Vec3, cross, dot, norm, normalize};
use crate::ir::{Affine, CsgNode, Part, Primitive};
use crate::tolerance::{LENGTH_FLOOR, RENDER_ROUNDOFF};

/// Number of parameters of a part.
pub const NTHETA: usize = 15;
/// Coverage is exactly 0 or 1 beyond this many σ from a silhouette.
pub const CUTOFF: f64 = 9.0;
/// Number of shading features.
pub const NSHADE: usize = 5;

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

pub(super) fn mat_vec(m: &[[f64; 3]; 3], v: Vec3) -> Vec3 {
    [dot(m[0], v), dot(m[1], v), dot(m[2], v)]
}

fn det3(m: &[[f64; 3]; 3]) -> f64 {
    dot(m[0], cross(m[1], m[2]))
}

fn inverse3(m: &[[f64; 3]; 3]) -> Option<[[f64; 3]; 3]> {
    let d = det3(m);
    let scale = m.iter().flatten().fold(0.0f64, |a, v| a.max(v.abs()));
    if d.abs() <= RENDER_ROUNDOFF * scale.powi(3) || !d.is_finite() {
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
        let rowlen = |a: usize| norm(inv[a]).max(LENGTH_FLOOR);
        // World normal of a local normal and the factor from local to world distance.
        let world = |nl: Vec3| -> (Vec3, f64) {
            let w = [
                inv[0][0] * nl[0] + inv[1][0] * nl[1] + inv[2][0] * nl[2],
                inv[0][1] * nl[0] + inv[1][1] * nl[1] + inv[2][1] * nl[2],
                inv[0][2] * nl[0] + inv[1][2] * nl[1] + inv[2][2] * nl[2],
            ];
            let l = norm(w).max(LENGTH_FLOOR);
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
                let (c, s) = if rho > LENGTH_FLOOR {
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
                let rho = norm(q).max(LENGTH_FLOOR);
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
    /// Per item: the brightness of its material, multiplying its shade (1 for every item
    /// unless set; see [`Scene::with_albedo`]).
    pub albedo: Vec<f64>,
}

impl Scene {
    pub fn new(parts: Vec<PartGeom>, csg: &CsgNode) -> Scene {
        let items: Vec<Item> = items_of(csg)
            .into_iter()
            .filter(|it| it.parts.iter().all(|&p| p < parts.len()))
            .collect();
        let albedo = vec![1.0; items.len()];
        Scene {
            parts,
            items,
            albedo,
        }
    }

    /// The scene with each item's albedo (items beyond `albedo` keep 1).
    pub fn with_albedo(mut self, albedo: &[f64]) -> Scene {
        for (a, &b) in self.albedo.iter_mut().zip(albedo) {
            *a = b;
        }
        self
    }

    /// Item `i`'s albedo.
    pub fn albedo_of(&self, i: usize) -> f64 {
        self.albedo.get(i).copied().unwrap_or(1.0)
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
