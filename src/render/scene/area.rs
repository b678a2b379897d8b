//! The box filter: a pixel's exact area coverage of a silhouette hull, and its derivatives.
//!
//! With edge softness [`BOX_FILTER`] a pixel's coverage of a part is the share of the pixel
//! square inside the part's hull (the square clipped by each edge's half-plane, its area by
//! the shoelace formula) — what an antialiased picture shows, and the mean of what an
//! aliased one shows. Moving edge `i` outwards by `δ` (a translation along its normal)
//! grows that area by `L·δ`, with `L` the length of the edge inside the square; a tilt
//! moves the edge by an amount linear along it, so the derivative is `L` times the signed
//! distance's derivative at the middle of that piece. So each edge crossing the pixel is one
//! gradient entry, `(edge, L)` evaluated at the piece's middle.
//!
//! Boxes' and frustums' hulls are their exact silhouettes (a frustum's within a twentieth of
//! a pixel); a sphere's is its polygon.

use super::hull::{COVERAGE_EDGES, Coverage, Hull};
use crate::tolerance::RENDER_ROUNDOFF;

/// The edge softness that asks for the box filter instead of a sigmoid: exact area
/// coverage of each pixel square.
pub const BOX_FILTER: f64 = 0.0;

/// The sigmoid softness (pixels) that stands in for the box filter where a soft edge has
/// no hull to clip (the cut edges of a difference): a sigmoid with the box's slope at the
/// edge, `1/(4σ)` = 1 per pixel.
pub const BOX_EQUIVALENT_SIGMA: f64 = 0.25;

/// Half the diagonal of a pixel: beyond it from every edge, a pixel is all in or all out.
const HALF_DIAGONAL: f64 = std::f64::consts::FRAC_1_SQRT_2;

/// Whether `sigma` asks for the box filter.
pub fn is_box(sigma: f64) -> bool {
    sigma <= BOX_FILTER
}

/// The sigmoid softness of `sigma` where a sigmoid is needed ([`BOX_EQUIVALENT_SIGMA`] for
/// the box filter).
pub fn sigmoid_sigma(sigma: f64) -> f64 {
    if is_box(sigma) {
        BOX_EQUIVALENT_SIGMA
    } else {
        sigma
    }
}

impl Hull {
    /// The share of the unit pixel square centred at `u` inside the polygon, and for each
    /// edge crossing the square (at most [`COVERAGE_EDGES`]) `∂α/∂s` with the point where
    /// `∂s` is to be taken.
    pub fn area_coverage(&self, u: [f64; 2]) -> Coverage {
        let (s, e) = self.signed_distance(u);
        let mut c = Coverage {
            alpha: 0.0,
            s,
            edges: [(e as u32, 0.0); COVERAGE_EDGES],
            at: [u; COVERAGE_EDGES],
            n: 0,
        };
        if s <= -HALF_DIAGONAL {
            return c;
        }
        if s >= HALF_DIAGONAL {
            c.alpha = 1.0;
            return c;
        }
        let mut poly = square(u);
        let m = self.verts.len();
        for (i, &(n, off)) in self.edges.iter().enumerate() {
            let d = n[0] * u[0] + n[1] * u[1] - off;
            if d <= -HALF_DIAGONAL {
                continue;
            }
            poly = clip(&poly, n, off);
            if poly.is_empty() {
                return c;
            }
            let a = self.verts[i];
            let b = self.verts[(i + 1) % m];
            if let Some((len, mid)) = inside_square(a, b, u)
                && c.n < COVERAGE_EDGES
            {
                c.edges[c.n] = (i as u32, len);
                c.at[c.n] = mid;
                c.n += 1;
            }
        }
        c.alpha = area(&poly).clamp(0.0, 1.0);
        c
    }
}

/// Most convex pieces the uncovered part of a pixel is kept in while layers are laid over
/// it (far more than seams of a few parts need); past this, the pixel composites its
/// layers as independent.
pub const UNCOVERED_PIECES: usize = 64;

impl Hull {
    /// The part of the unit pixel square centred at `u` inside the polygon
    /// (counter-clockwise; empty when they do not meet).
    pub fn pixel_polygon(&self, u: [f64; 2]) -> Vec<[f64; 2]> {
        let mut poly = square(u);
        for &(n, off) in &self.edges {
            if n[0] * u[0] + n[1] * u[1] - off <= -HALF_DIAGONAL {
                continue;
            }
            poly = clip(&poly, n, off);
            if poly.is_empty() {
                break;
            }
        }
        poly
    }
}

/// The unit square centred at `u`, counter-clockwise.
fn square(u: [f64; 2]) -> Vec<[f64; 2]> {
    vec![
        [u[0] - 0.5, u[1] - 0.5],
        [u[0] + 0.5, u[1] - 0.5],
        [u[0] + 0.5, u[1] + 0.5],
        [u[0] - 0.5, u[1] + 0.5],
    ]
}

/// The area each of `layers` (front to back; convex, counter-clockwise, inside the unit
/// square centred at `u`) adds to those in front of it: the square's uncovered part is kept
/// as disjoint convex pieces, and each layer takes what it covers of every piece and leaves
/// the rest (the piece outside each of its edges in turn). `None` past
/// [`UNCOVERED_PIECES`].
pub fn visible_areas(u: [f64; 2], layers: &[Vec<[f64; 2]>]) -> Option<Vec<f64>> {
    let mut uncovered = vec![square(u)];
    let mut out = Vec::with_capacity(layers.len());
    for layer in layers {
        let mut taken = 0.0;
        let mut left = Vec::with_capacity(uncovered.len());
        for piece in &uncovered {
            taken += area(&intersect(piece, layer));
            let mut rest = piece.clone();
            for k in 0..layer.len() {
                let Some((n, off)) = edge_plane(layer[k], layer[(k + 1) % layer.len()]) else {
                    continue;
                };
                let outside = clip(&rest, [-n[0], -n[1]], -off);
                if area(&outside) > 0.0 {
                    left.push(outside);
                }
                rest = clip(&rest, n, off);
                if rest.is_empty() {
                    break;
                }
            }
        }
        if left.len() > UNCOVERED_PIECES {
            return None;
        }
        uncovered = left;
        out.push(taken);
    }
    Some(out)
}

/// The outward normal and offset of the edge `p → q` of a counter-clockwise polygon
/// (`None` for an edge of no length).
fn edge_plane(p: [f64; 2], q: [f64; 2]) -> Option<([f64; 2], f64)> {
    let e = [q[0] - p[0], q[1] - p[1]];
    let len = (e[0] * e[0] + e[1] * e[1]).sqrt();
    if len <= RENDER_ROUNDOFF {
        return None;
    }
    let n = [e[1] / len, -e[0] / len];
    Some((n, n[0] * p[0] + n[1] * p[1]))
}

/// The intersection of two convex polygons (counter-clockwise).
fn intersect(a: &[[f64; 2]], b: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let mut out = a.to_vec();
    for k in 0..b.len() {
        let Some((n, off)) = edge_plane(b[k], b[(k + 1) % b.len()]) else {
            continue;
        };
        out = clip(&out, n, off);
        if out.is_empty() {
            break;
        }
    }
    out
}

/// The polygon `poly` cut to the half-plane `n·p ≤ off` (Sutherland–Hodgman).
fn clip(poly: &[[f64; 2]], n: [f64; 2], off: f64) -> Vec<[f64; 2]> {
    let side = |p: [f64; 2]| n[0] * p[0] + n[1] * p[1] - off;
    let mut out = Vec::with_capacity(poly.len() + 1);
    for k in 0..poly.len() {
        let (p, q) = (poly[k], poly[(k + 1) % poly.len()]);
        let (dp, dq) = (side(p), side(q));
        if dp <= 0.0 {
            out.push(p);
        }
        if (dp < 0.0 && dq > 0.0) || (dp > 0.0 && dq < 0.0) {
            let t = dp / (dp - dq);
            out.push([p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])]);
        }
    }
    out
}

/// Area of a simple polygon (shoelace), counter-clockwise positive.
fn area(poly: &[[f64; 2]]) -> f64 {
    let mut a = 0.0;
    for k in 0..poly.len() {
        let (p, q) = (poly[k], poly[(k + 1) % poly.len()]);
        a += p[0] * q[1] - q[0] * p[1];
    }
    0.5 * a
}

/// The piece of segment `a → b` inside the unit square centred at `u` (Liang–Barsky): its
/// length and middle, when it has length.
fn inside_square(a: [f64; 2], b: [f64; 2], u: [f64; 2]) -> Option<(f64, [f64; 2])> {
    let d = [b[0] - a[0], b[1] - a[1]];
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for k in 0..2 {
        let (lo, hi) = (u[k] - 0.5 - a[k], u[k] + 0.5 - a[k]);
        if d[k].abs() <= RENDER_ROUNDOFF {
            if lo > 0.0 || hi < 0.0 {
                return None;
            }
            continue;
        }
        let (ta, tb) = (lo / d[k], hi / d[k]);
        let (ta, tb) = if ta < tb { (ta, tb) } else { (tb, ta) };
        t0 = t0.max(ta);
        t1 = t1.min(tb);
    }
    if t1 <= t0 {
        return None;
    }
    let len = (t1 - t0) * (d[0] * d[0] + d[1] * d[1]).sqrt();
    let tm = 0.5 * (t0 + t1);
    Some((len, [a[0] + tm * d[0], a[1] + tm * d[1]]))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn polygon(verts: Vec<[f64; 2]>) -> Hull {
        let m = verts.len();
        let mut edges = Vec::new();
        for i in 0..m {
            let (a, b) = (verts[i], verts[(i + 1) % m]);
            let e = [b[0] - a[0], b[1] - a[1]];
            let len = (e[0] * e[0] + e[1] * e[1]).sqrt();
            let n = [e[1] / len, -e[0] / len];
            edges.push((n, n[0] * a[0] + n[1] * a[1]));
        }
        Hull {
            src: (0..m as u32).collect(),
            edges,
            samples: Vec::new(),
            lo: [0.0; 2],
            hi: [0.0; 2],
            verts,
        }
    }

    /// A quadrilateral tilted across a few pixels, in the hulls' order (positive area).
    fn sliver() -> Vec<[f64; 2]> {
        vec![[3.2, 0.8], [3.6, 3.1], [0.7, 3.9], [0.3, 1.2]]
    }

    #[test]
    fn pixels_share_the_polygons_area() {
        let h = polygon(sliver());
        let total: f64 = (0..6)
            .flat_map(|y| (0..6).map(move |x| [x as f64 + 0.5, y as f64 + 0.5]))
            .map(|u| h.area_coverage(u).alpha)
            .sum();
        assert!((total - area(&h.verts)).abs() < 1e-12, "{total}");
    }

    #[test]
    fn two_halves_of_a_pixel_cover_it_whole() {
        // Two parts meeting at a seam through the pixel, and one overlapping both.
        let top = polygon(vec![[0.0, 0.0], [4.0, 0.0], [4.0, 1.3], [0.0, 1.3]]);
        let leg = polygon(vec![[0.0, 1.3], [4.0, 1.3], [4.0, 4.0], [0.0, 4.0]]);
        let u = [1.5, 1.5];
        let (a, b) = (top.pixel_polygon(u), leg.pixel_polygon(u));
        assert!((area(&a) - 0.3).abs() < 1e-12 && (area(&b) - 0.7).abs() < 1e-12);
        let seam = visible_areas(u, &[a.clone(), b.clone()]).unwrap();
        assert!((seam[0] - 0.3).abs() < 1e-12 && (seam[1] - 0.7).abs() < 1e-12);
        // A band across the middle in front: the others add only what it leaves.
        let mid = polygon(vec![[0.0, 1.2], [4.0, 1.2], [4.0, 1.6], [0.0, 1.6]]);
        let c = mid.pixel_polygon(u);
        let v = visible_areas(u, &[c, a, b]).unwrap();
        let want = [0.4, 0.2, 0.4];
        for (got, want) in v.iter().zip(want) {
            assert!((got - want).abs() < 1e-12, "{v:?}");
        }
    }

    #[test]
    fn the_derivative_is_the_edge_length_inside_the_pixel() {
        // Each vertex moved: the change of the coverage against the entries' prediction.
        let verts = sliver();
        let base = polygon(verts.clone());
        let eps = 1e-6;
        for u in [[1.5, 1.5], [0.5, 2.5], [3.5, 3.5], [2.5, 0.5]] {
            let c = base.area_coverage(u);
            for v in 0..verts.len() {
                for k in 0..2 {
                    let mut moved = verts.clone();
                    moved[v][k] += eps;
                    let fd = (polygon(moved).area_coverage(u).alpha - c.alpha) / eps;
                    let mut pred = 0.0;
                    for j in 0..c.n {
                        let (edge, ds) = c.edges[j];
                        let (ga, gb) = base.edge_gradient(edge as usize, c.at[j]);
                        if edge as usize == v {
                            pred += ds * ga[k];
                        }
                        if (edge as usize + 1) % verts.len() == v {
                            pred += ds * gb[k];
                        }
                    }
                    assert!((fd - pred).abs() < 1e-5, "{u:?} v{v} {k}: {fd} vs {pred}");
                }
            }
        }
    }
}
