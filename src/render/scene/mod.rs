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
//! positive inside) from the pixel center to that hull, or with the box filter
//! ([`BOX_FILTER`]) the exact share of the pixel square inside it (`area`). Derivatives of `s` with respect to
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
//! `items` the boolean programs, `hull` the per-view silhouettes and their jacobians, `area` the box filter.

// Geometry here indexes several arrays by axis; index loops read best.
#![allow(clippy::needless_range_loop)]

mod area;
mod hull;
mod intersect;
mod items;

pub use area::{BOX_EQUIVALENT_SIGMA, BOX_FILTER, is_box, sigmoid_sigma, visible_areas};
pub use hull::{
    COVERAGE_EDGES, Coverage, Hull, Sample, hull, logistic, ring_count, sample_jacobian, samples,
};
pub use items::{Item, Op, eval_inside, eval_soft, items_of};

use super::camera::unit;
use crate::ir::{Affine, CsgNode, Part, Primitive};
use crate::tolerance::{LENGTH_FLOOR, RENDER_ROUNDOFF};
use glam::{DMat3, DVec3};

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
    pub l: DMat3,
    pub t: DVec3,
    /// `L⁻¹` and `−L⁻¹·t`.
    pub inv: DMat3,
    pub inv_t: DVec3,
    /// Local box (for a frustum: `lo.z = z0`, `hi.z = z1`).
    pub lo: DVec3,
    pub hi: DVec3,
    /// Frustum radii at `z0` and `z1`; a sphere's radius is `r1`.
    pub r1: f64,
    pub r2: f64,
    /// World position of the local box's center.
    pub center: DVec3,
    /// World unit normals of the local `+x`, `+y`, `+z` faces (`L⁻ᵀ·eₐ`, normalised): a
    /// box's faces, worked out once rather than per ray.
    pub axis_normals: [DVec3; 3],
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
    pub n0: DVec3,
    pub n1: DVec3,
}

/// `m⁻¹` as the adjugate (columns: cross products of rows) over the determinant, or
/// `None` for a singular map. Written out rather than `DMat3::inverse` so the numbers stay
/// the ones the renderer has always computed (a division by the determinant, not a
/// multiplication by its reciprocal).
fn inverse3(m: &DMat3) -> Option<DMat3> {
    let (r0, r1, r2) = (m.row(0), m.row(1), m.row(2));
    let d = r0.dot(r1.cross(r2));
    let scale = m.to_cols_array().iter().fold(0.0f64, |a, v| a.max(v.abs()));
    if d.abs() <= RENDER_ROUNDOFF * scale.powi(3) || !d.is_finite() {
        return None;
    }
    let c0 = r1.cross(r2);
    let c1 = r2.cross(r0);
    let c2 = r0.cross(r1);
    Some(DMat3::from_cols(c0 / d, c1 / d, c2 / d))
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
        let l = DMat3::from_rows(
            DVec3::new(theta[0], theta[1], theta[2]),
            DVec3::new(theta[4], theta[5], theta[6]),
            DVec3::new(theta[8], theta[9], theta[10]),
        );
        let t = DVec3::new(theta[3], theta[7], theta[11]);
        let (lo, hi, r1, r2, sizes_ok) = match kind {
            Kind::Box => {
                let s = [theta[12], theta[13], theta[14]];
                let ok = s.iter().all(|&v| v > 0.0);
                if centered {
                    let lo = DVec3::from(s.map(|v| -v / 2.0));
                    (lo, DVec3::from(s.map(|v| v / 2.0)), 0.0, 0.0, ok)
                } else {
                    (DVec3::ZERO, DVec3::from(s), 0.0, 0.0, ok)
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
                (DVec3::new(-r, -r, z0), DVec3::new(r, r, z1), r1, r2, ok)
            }
            Kind::Sphere => {
                let r = theta[12];
                (DVec3::splat(-r), DVec3::splat(r), r, r, r > 0.0)
            }
        };
        let inv = inverse3(&l);
        let valid = sizes_ok && inv.is_some() && theta.iter().all(|v| v.is_finite());
        let inv = inv.unwrap_or(DMat3::ZERO);
        let it = inv * t;
        let mid = (lo + hi) / 2.0;
        let center = l * mid + t;
        let axis_normals = [DVec3::X, DVec3::Y, DVec3::Z].map(|e| unit(inv.mul_transpose_vec3(e)));
        PartGeom {
            kind,
            centered,
            theta,
            l,
            t,
            inv,
            inv_t: -it,
            lo,
            hi,
            r1,
            r2,
            center,
            axis_normals,
            valid,
            ring: 0,
        }
    }

    /// Local coordinates of a world point.
    #[inline]
    pub fn to_local(&self, p: DVec3) -> DVec3 {
        self.inv * p + self.inv_t
    }

    /// Local direction of a world direction (same ray parameter in both frames).
    #[inline]
    pub fn dir_to_local(&self, d: DVec3) -> DVec3 {
        self.inv * d
    }

    /// World unit normal of a local normal (`L⁻ᵀ·n`).
    #[inline]
    pub fn normal_to_world(&self, n: DVec3) -> DVec3 {
        unit(self.inv.mul_transpose_vec3(n))
    }

    /// World point of a local point.
    pub fn to_world(&self, p: DVec3) -> DVec3 {
        self.l * p + self.t
    }
}

/// The point of a part's surface nearest (in the sense of its nearest face) to a world
/// point: the signed distance (world units, positive outside), the surface point in local
/// coordinates as a material point, its world unit normal, and `N·(L·∂q/∂prim)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfacePoint {
    pub sd: f64,
    pub q: DVec3,
    pub n: DVec3,
    pub ldq: [f64; 3],
}

impl PartGeom {
    /// Signed distance from a world point to the part's nearest face plane (the largest of
    /// the face distances, so exact near faces), with that face's material point.
    pub fn surface_distance(&self, p: DVec3) -> Option<SurfacePoint> {
        if !self.valid {
            return None;
        }
        let q = self.to_local(p);
        let zero = DVec3::ZERO;
        match self.kind {
            Kind::Box => {
                let mut best = (f64::NEG_INFINITY, 0usize, false);
                for a in 0..3 {
                    let l = self.row_length(a);
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
                let mut nl = DVec3::ZERO;
                nl[a] = if high { 1.0 } else { -1.0 };
                let (n, _) = self.world_normal(nl);
                let mut dq = [zero; 3];
                dq[a][a] = match (self.centered, high) {
                    (true, true) => 0.5,
                    (true, false) => -0.5,
                    (false, true) => 1.0,
                    (false, false) => 0.0,
                };
                Some(self.surface_point(sd, qs, n, dq))
            }
            Kind::Frustum => Some(self.frustum_surface(q)),
            Kind::Sphere => {
                let r = self.r1;
                let rho = q.length().max(LENGTH_FLOOR);
                let nl = q / rho;
                let (n, w) = self.world_normal(nl);
                let sd = (rho - r) / w;
                Some(self.surface_point(sd, nl * r, n, [nl, zero, zero]))
            }
        }
    }

    /// [`PartGeom::surface_distance`] of a frustum, at local point `q`: its side or a cap.
    fn frustum_surface(&self, q: DVec3) -> SurfacePoint {
        let zero = DVec3::ZERO;
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
        let (ns, ws) = self.world_normal(DVec3::new(c / kk, s / kk, -k / kk));
        let side = (rho - rs) / kk / ws;
        let l2 = self.row_length(2);
        let bottom = (z0 - q[2]) / l2;
        let top = (q[2] - z1) / l2;
        if side >= bottom && side >= top {
            let v = (q[2] - z0) / h;
            let qs = DVec3::new(rs * c, rs * s, q[2]);
            let dq = [
                DVec3::new(0.0, 0.0, dz0 + v * (dz1 - dz0)),
                DVec3::new((1.0 - v) * c, (1.0 - v) * s, 0.0),
                DVec3::new(v * c, v * s, 0.0),
            ];
            self.surface_point(side, qs, ns, dq)
        } else if bottom >= top {
            let (n, _) = self.world_normal(DVec3::NEG_Z);
            let dq = [DVec3::new(0.0, 0.0, dz0), zero, zero];
            self.surface_point(bottom, DVec3::new(q[0], q[1], z0), n, dq)
        } else {
            let (n, _) = self.world_normal(DVec3::Z);
            let dq = [DVec3::new(0.0, 0.0, dz1), zero, zero];
            self.surface_point(top, DVec3::new(q[0], q[1], z1), n, dq)
        }
    }

    /// Length of row `a` of `L⁻¹`: local distance along axis `a` per world distance.
    fn row_length(&self, a: usize) -> f64 {
        self.inv.row(a).length().max(LENGTH_FLOOR)
    }

    /// World unit normal of a local normal and the factor from local to world distance.
    fn world_normal(&self, nl: DVec3) -> (DVec3, f64) {
        let w = self.inv.mul_transpose_vec3(nl);
        let l = w.length().max(LENGTH_FLOOR);
        (w / l, l)
    }

    /// A surface point with `N·(L·∂q/∂prim)` from the material point's derivatives `dq`.
    fn surface_point(&self, sd: f64, qs: DVec3, n: DVec3, dq: [DVec3; 3]) -> SurfacePoint {
        let ldq = std::array::from_fn(|k| n.dot(self.l * dq[k]));
        SurfacePoint { sd, q: qs, n, ldq }
    }
}

/// `∂sd/∂θ` of a surface point: minus the normal motion of its material point.
pub fn surface_jacobian(sp_n: DVec3, q: DVec3, ldq: [f64; 3]) -> [f64; NTHETA] {
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
pub fn shade_features(n: [f64; 3]) -> [f64; NSHADE] {
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
    pub fn bounds(&self) -> Option<([f64; 3], [f64; 3])> {
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
                    let q: [f64; 3] =
                        std::array::from_fn(|a| if c >> a & 1 == 0 { p.lo[a] } else { p.hi[a] });
                    let w = p.to_world(DVec3::from(q));
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
