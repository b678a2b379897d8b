//! Exact ray passages through a part: the ray is taken to the part's local frame and cut
//! against the box, frustum or sphere there. Entry/exit normals are outward and in world
//! space, and a passage has `t0 <= t1` (ray parameters, the same in both frames).

use super::{Hit, Kind, PartGeom};
use crate::tolerance::{LENGTH_FLOOR, PARALLEL_SINE_SQUARED, RENDER_ROUNDOFF};
use glam::DVec3;

impl PartGeom {
    /// The ray's exact passage through the part (world ray; parameters are the ray's).
    pub fn intersect(&self, origin: DVec3, dir: DVec3) -> Option<Hit> {
        self.intersect_from(self.to_local(origin), dir)
    }

    /// [`PartGeom::intersect`] of the ray from the local point `o` (`to_local` of its world
    /// origin, which a perspective view's rays share) along world direction `dir`.
    #[inline]
    pub fn intersect_from(&self, o: DVec3, dir: DVec3) -> Option<Hit> {
        if !self.valid {
            return None;
        }
        let d = self.dir_to_local(dir);
        let local = match self.kind {
            Kind::Box => {
                let (t0, t1, (a0, s0), (a1, s1)) = intersect_box(o, d, self.lo, self.hi)?;
                return Some(Hit {
                    t0,
                    t1,
                    n0: self.axis_normals[a0] * s0,
                    n1: self.axis_normals[a1] * s1,
                });
            }
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

    /// For a box the ray enters (in front of its origin): how much sooner it crosses its
    /// entry face's plane than any other face plane it enters through, relative to the
    /// entry parameter. `None` for other kinds, a miss, or an entry behind the origin.
    pub fn entry_face_margin(&self, origin: DVec3, dir: DVec3) -> Option<f64> {
        if !self.valid || self.kind != Kind::Box {
            return None;
        }
        let o = self.to_local(origin);
        let d = self.dir_to_local(dir);
        let (t0, _, (a0, _), _) = intersect_box(o, d, self.lo, self.hi)?;
        if t0 <= 0.0 {
            return None;
        }
        let mut margin = f64::INFINITY;
        for a in (0..3).filter(|&a| a != a0 && d[a] != 0.0) {
            let ta = (self.lo[a] - o[a]) / d[a];
            let tb = (self.hi[a] - o[a]) / d[a];
            margin = margin.min(t0 - ta.min(tb));
        }
        Some(margin / t0)
    }

    /// For a ray that misses the part (or nearly does): the normal of the surface the ray
    /// passes closest to, continuing the visible face past the silhouette.
    pub fn near_normal(&self, origin: DVec3, dir: DVec3) -> DVec3 {
        let o = self.to_local(origin);
        let d = self.dir_to_local(dir);
        let n = match self.kind {
            Kind::Box => {
                let mut best = f64::NEG_INFINITY;
                let mut n = DVec3::Z;
                for a in 0..3 {
                    if d[a] == 0.0 {
                        continue;
                    }
                    let ta = (self.lo[a] - o[a]) / d[a];
                    let tb = (self.hi[a] - o[a]) / d[a];
                    let (near, sign) = if ta < tb { (ta, -1.0) } else { (tb, 1.0) };
                    if near > best {
                        best = near;
                        n = DVec3::ZERO;
                        n[a] = sign;
                    }
                }
                n
            }
            Kind::Frustum => {
                let (z0, z1) = (self.lo[2], self.hi[2]);
                let dd = d[0] * d[0] + d[1] * d[1];
                if dd <= PARALLEL_SINE_SQUARED * d.dot(d) {
                    DVec3::new(0.0, 0.0, if d[2] > 0.0 { -1.0 } else { 1.0 })
                } else {
                    let ts = -(o[0] * d[0] + o[1] * d[1]) / dd;
                    let p = o + d * ts;
                    if p[2] < z0 && d[2] > 0.0 {
                        DVec3::NEG_Z
                    } else if p[2] > z1 && d[2] < 0.0 {
                        DVec3::Z
                    } else {
                        let k = (self.r2 - self.r1) / (z1 - z0);
                        let r = (p[0] * p[0] + p[1] * p[1]).sqrt().max(LENGTH_FLOOR);
                        DVec3::new(p[0] / r, p[1] / r, -k)
                    }
                }
            }
            Kind::Sphere => {
                let dd = d.dot(d).max(LENGTH_FLOOR);
                let ts = -o.dot(d) / dd;
                o + d * ts
            }
        };
        self.normal_to_world(n)
    }
}

/// A local intersection.
struct LocalHit {
    t0: f64,
    t1: f64,
    n0: DVec3,
    n1: DVec3,
}

/// A ray's passage through the box `[lo, hi]`: entry and exit parameters and the faces
/// there, each an axis and the sign of its outward normal.
#[allow(clippy::type_complexity)]
#[inline]
fn intersect_box(
    o: DVec3,
    d: DVec3,
    lo: DVec3,
    hi: DVec3,
) -> Option<(f64, f64, (usize, f64), (usize, f64))> {
    let mut t0 = f64::NEG_INFINITY;
    let mut t1 = f64::INFINITY;
    let mut f0 = (2, 1.0);
    let mut f1 = (2, 1.0);
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
            f0 = (a, sign);
        }
        if far < t1 {
            t1 = far;
            f1 = (a, -sign);
        }
    }
    (t0 <= t1 && t0.is_finite() && t1.is_finite()).then_some((t0, t1, f0, f1))
}

fn intersect_sphere(o: DVec3, d: DVec3, r: f64) -> Option<LocalHit> {
    let a = d.dot(d);
    let b = o.dot(d);
    let c = o.dot(o) - r * r;
    let disc = b * b - a * c;
    if disc < 0.0 || a <= 0.0 {
        return None;
    }
    let q = disc.sqrt();
    let t0 = (-b - q) / a;
    let t1 = (-b + q) / a;
    let p0 = o + d * t0;
    let p1 = o + d * t1;
    Some(LocalHit {
        t0,
        t1,
        n0: p0,
        n1: p1,
    })
}

/// A frustum along local z from `z0` to `z1` with radii `r1`, `r2` there.
fn intersect_frustum(o: DVec3, d: DVec3, z0: f64, z1: f64, r1: f64, r2: f64) -> Option<LocalHit> {
    // The slab z0 ≤ z ≤ z1.
    let (mut s0, mut s1, sn0, sn1);
    if d[2] == 0.0 {
        if o[2] < z0 || o[2] > z1 {
            return None;
        }
        s0 = f64::NEG_INFINITY;
        s1 = f64::INFINITY;
        sn0 = DVec3::ZERO;
        sn1 = DVec3::ZERO;
    } else {
        let ta = (z0 - o[2]) / d[2];
        let tb = (z1 - o[2]) / d[2];
        if ta < tb {
            s0 = ta;
            s1 = tb;
            sn0 = DVec3::NEG_Z;
            sn1 = DVec3::Z;
        } else {
            s0 = tb;
            s1 = ta;
            sn0 = DVec3::Z;
            sn1 = DVec3::NEG_Z;
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
    let pieces = cone_pieces(a, b, c, scale_a)?;
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
    let side_normal = |t: f64| -> DVec3 {
        let p = o + d * t;
        DVec3::new(p[0], p[1], -k * (c0 + k * p[2]))
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

/// The pieces of the line where `a·t² + b·t + c ≤ 0` (unused ones NaN; `None`: nowhere);
/// `scale_a` is the size `a` is compared with to call it zero.
fn cone_pieces(a: f64, b: f64, c: f64, scale_a: f64) -> Option<[(f64, f64); 2]> {
    let mut pieces: [(f64, f64); 2] = [(f64::NAN, f64::NAN); 2];
    if a.abs() <= RENDER_ROUNDOFF * scale_a {
        if b.abs() <= LENGTH_FLOOR {
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
    Some(pieces)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::scene::NTHETA;

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
        let h = p
            .intersect(DVec3::new(0.0, -10.0, 0.5), DVec3::new(0.0, 1.0, 0.0))
            .unwrap();
        assert!((h.t0 - 9.0).abs() < 1e-12 && (h.t1 - 11.0).abs() < 1e-12);
        assert_eq!(h.n0, DVec3::new(0.0, -1.0, 0.0));
        assert_eq!(h.n1, DVec3::new(0.0, 1.0, 0.0));
        assert!(
            p.intersect(DVec3::new(0.0, -10.0, 1.5), DVec3::new(0.0, 1.0, 0.0))
                .is_none()
        );
    }

    #[test]
    fn frustum_hits_side_and_caps() {
        let mut th = unit();
        th[12..15].copy_from_slice(&[10.0, 4.0, 2.0]);
        let p = PartGeom::from_theta(Kind::Frustum, false, th);
        // Along x at z = 5: radius 3.
        let h = p
            .intersect(DVec3::new(-10.0, 0.0, 5.0), DVec3::new(1.0, 0.0, 0.0))
            .unwrap();
        assert!((h.t0 - 7.0).abs() < 1e-9 && (h.t1 - 13.0).abs() < 1e-9);
        assert!(h.n0[0] < 0.0 && h.n0[2] > 0.0);
        // Down the axis: top cap then bottom cap.
        let h = p
            .intersect(DVec3::new(0.0, 0.0, 20.0), DVec3::new(0.0, 0.0, -1.0))
            .unwrap();
        assert!((h.t0 - 10.0).abs() < 1e-9 && (h.t1 - 20.0).abs() < 1e-9);
        assert_eq!(h.n0, DVec3::new(0.0, 0.0, 1.0));
        assert!(
            p.intersect(DVec3::new(3.5, 0.0, 20.0), DVec3::new(0.0, 0.0, -1.0))
                .is_some()
        );
        assert!(
            p.intersect(DVec3::new(4.5, 0.0, 20.0), DVec3::new(0.0, 0.0, -1.0))
                .is_none()
        );
        // A cone to a point.
        th[14] = 0.0;
        let c = PartGeom::from_theta(Kind::Frustum, false, th);
        let h = c
            .intersect(DVec3::new(-10.0, 0.0, 5.0), DVec3::new(1.0, 0.0, 0.0))
            .unwrap();
        assert!((h.t1 - h.t0 - 4.0).abs() < 1e-9);
    }

    #[test]
    fn sphere_under_scale() {
        let mut th = unit();
        th[0] = 2.0;
        th[12] = 1.0;
        let p = PartGeom::from_theta(Kind::Sphere, true, th);
        let h = p
            .intersect(DVec3::new(-10.0, 0.0, 0.0), DVec3::new(1.0, 0.0, 0.0))
            .unwrap();
        assert!((h.t0 - 8.0).abs() < 1e-9 && (h.t1 - 12.0).abs() < 1e-9);
        assert!((h.n0[0] + 1.0).abs() < 1e-9);
    }
}
