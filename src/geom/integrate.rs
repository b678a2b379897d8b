//! The volume integral over the xy plane, for one solid or two at once.
//!
//! `V = ∫∫ f(x, y) dx dy`, where `f` is the length of the vertical line through `(x, y)`
//! inside the solid (clipped to a z range). For two solids A and B the integrand is the
//! vector `(|A|, |B|, |A ∩ B|)` along the line, so one pass gives both volumes and the
//! intersection (the union is `|A| + |B| − |A ∩ B|`).
//!
//! Structure:
//! - **Spatial index.** The domain is split recursively (a k-d tree over the xy bounds of the
//!   shapes, cutting at existing bounds so no new break lines appear) until a cell sees at
//!   most [`LEAF`] shapes; each cell carries the CSG programs pruned to what it sees. A ray
//!   then tests only the shapes of its cell, so cost grows with the model, not its square.
//! - **Strips.** In a cell, the x breaks of its shapes (bounds, corners, rim extremes) cut it
//!   into strips. A strip whose shapes are all axis-aligned boxes has an integrand that is
//!   piecewise constant on rectangles: one line at the strip's middle, and along it one ray
//!   per y cell, is *exact*. Other strips integrate `g(x) = ∫ f dy` adaptively (`quad`).
//! - **Lines.** Along a line the y breaks cut it into segments; a segment seen only by
//!   aligned boxes takes one ray, others are integrated adaptively. Rays return a signature
//!   (the merged order of every interval end) so kinks are found and split exactly.
//!
//! Invariants: the result is a sum of finite terms; the z clip and the xy domain bound the
//! integral to the requested region; shapes with an empty footprint never enter a cell.

use super::csg::{Iv, Program, Surf, clipped_common_len, clipped_len};
use super::quad::{self, Tol, V3};
use super::shape::Shape;

/// Most shapes in a cell of the spatial index.
const LEAF: usize = 12;
const MAX_DEPTH: u32 = 40;

#[derive(Debug, Clone, Copy)]
struct Rect {
    lo: [f64; 2],
    hi: [f64; 2],
}

/// What to integrate: shapes, up to two programs over them, and the region.
pub(crate) struct Job<'a> {
    pub shapes: &'a [Shape],
    pub programs: [&'a Program; 2],
    /// The region `(min, max)`; infinite sides mean unbounded.
    pub region: ([f64; 3], [f64; 3]),
}

struct Integrator<'a> {
    shapes: &'a [Shape],
    /// The longest side of the domain: the scale of tolerances.
    size: f64,
    z: (f64, f64),
    line_tol: Tol,
    area_tol: Tol,
    mask: Vec<bool>,
    ivs: Vec<Iv>,
    ybreaks: Vec<f64>,
    /// Kinds of stretch met by the current line's rays.
    kinds: Vec<u64>,
}

/// `(|A|, |B|, |A ∩ B|)` inside the job's region.
pub(crate) fn integrate(job: &Job) -> V3 {
    let (rmin, rmax) = job.region;
    let inside = |s: &Shape| (0..3).all(|a| s.lo[a] < rmax[a] && s.hi[a] > rmin[a]);
    let mut ids: Vec<u32> = job.programs.iter().flat_map(|p| p.shapes()).collect();
    ids.sort_unstable();
    ids.dedup();
    ids.retain(|&i| inside(&job.shapes[i as usize]));
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for &i in &ids {
        let s = &job.shapes[i as usize];
        for a in 0..3 {
            lo[a] = lo[a].min(s.lo[a].max(rmin[a]));
            hi[a] = hi[a].max(s.hi[a].min(rmax[a]));
        }
    }
    if ids.is_empty() || (0..3).any(|a| !(lo[a] < hi[a])) {
        return [0.0; 3];
    }
    let size = (0..3).map(|a| hi[a] - lo[a]).fold(0.0, f64::max);
    let mut it = Integrator {
        shapes: job.shapes,
        size,
        z: (rmin[2], rmax[2]),
        line_tol: Tol {
            rtol: 1e-10,
            atol_density: 1e-11 * size,
            min_width: 1e-9 * size,
            budget: 200,
        },
        area_tol: Tol {
            rtol: 1e-9,
            atol_density: 1e-10 * size * size,
            min_width: 1e-9 * size,
            budget: 200,
        },
        mask: vec![false; job.shapes.len()],
        ivs: Vec::new(),
        ybreaks: Vec::new(),
        kinds: Vec::new(),
    };
    let progs = it.restrict(job.programs, &ids);
    let rect = Rect {
        lo: [lo[0], lo[1]],
        hi: [hi[0], hi[1]],
    };
    it.cell(rect, ids, [&progs[0], &progs[1]], 0)
}

impl Integrator<'_> {
    fn shape(&self, i: u32) -> &Shape {
        &self.shapes[i as usize]
    }

    /// The programs pruned to the shapes in `ids`.
    fn restrict(&mut self, progs: [&Program; 2], ids: &[u32]) -> [Program; 2] {
        ids.iter().for_each(|&i| self.mask[i as usize] = true);
        let mask = &self.mask;
        let out = progs.map(|p| p.prune(&|s| mask[s as usize]));
        ids.iter().for_each(|&i| self.mask[i as usize] = false);
        out
    }

    /// A cell of the spatial index: split it, or integrate it as a leaf.
    fn cell(&mut self, r: Rect, ids: Vec<u32>, progs: [&Program; 2], depth: u32) -> V3 {
        if progs.iter().all(|p| p.is_empty()) {
            return [0.0; 3];
        }
        if ids.len() > LEAF
            && depth < MAX_DEPTH
            && let Some((axis, at)) = self.split(&r, &ids)
        {
            let mut total = [0.0; 3];
            for side in 0..2 {
                let sub: Vec<u32> = ids
                    .iter()
                    .copied()
                    .filter(|&i| {
                        let s = self.shape(i);
                        if side == 0 {
                            s.lo[axis] < at
                        } else {
                            s.hi[axis] > at
                        }
                    })
                    .collect();
                let mut rect = r;
                if side == 0 {
                    rect.hi[axis] = at;
                } else {
                    rect.lo[axis] = at;
                }
                let p = self.restrict(progs, &sub);
                total = quad::add(total, self.cell(rect, sub, [&p[0], &p[1]], depth + 1));
            }
            return total;
        }
        self.leaf(r, &ids, progs)
    }

    /// A cut at the median shape bound along the axis that best separates the shapes, if
    /// it leaves each side with at most three quarters of them.
    fn split(&self, r: &Rect, ids: &[u32]) -> Option<(usize, f64)> {
        let mut best: Option<(usize, usize, f64)> = None;
        for axis in 0..2 {
            let mut cuts: Vec<f64> = ids
                .iter()
                .flat_map(|&i| [self.shape(i).lo[axis], self.shape(i).hi[axis]])
                .filter(|&v| v > r.lo[axis] && v < r.hi[axis])
                .collect();
            if cuts.is_empty() {
                continue;
            }
            let mid = cuts.len() / 2;
            let at = *cuts.select_nth_unstable_by(mid, f64::total_cmp).1;
            let left = ids.iter().filter(|&&i| self.shape(i).lo[axis] < at).count();
            let right = ids.iter().filter(|&&i| self.shape(i).hi[axis] > at).count();
            let cost = left.max(right);
            if best.is_none_or(|b| cost < b.1) {
                best = Some((axis, cost, at));
            }
        }
        let (axis, cost, at) = best?;
        (4 * cost <= 3 * ids.len()).then_some((axis, at))
    }

    /// `∫∫ f` over a leaf cell, strip by strip.
    fn leaf(&mut self, r: Rect, ids: &[u32], progs: [&Program; 2]) -> V3 {
        let mut xs = vec![r.lo[0], r.hi[0]];
        for &i in ids {
            let s = self.shape(i);
            s.x_breaks(&mut xs);
            // Where a footprint's boundary crosses the cell's lower or upper side, the
            // integral over the cell has a kink.
            for side in r.lo[1..].iter().chain(&r.hi[1..]) {
                if !s.aligned && s.lo[1] < *side && *side < s.hi[1] {
                    s.line_breaks(1, *side, &mut xs);
                }
            }
        }
        xs.retain(|&x| x >= r.lo[0] && x <= r.hi[0]);
        xs.sort_unstable_by(f64::total_cmp);
        // Breaks closer than rounding noise (a cos 90° of 6e-17) would only make slivers.
        let eps = 1e-14 * self.size;
        xs.dedup_by(|b, a| *b - *a <= eps);
        if let Some(last) = xs.last_mut() {
            *last = r.hi[0];
        }
        let mut total = [0.0; 3];
        let mut strip = Vec::with_capacity(ids.len());
        for w in xs.windows(2) {
            let (xa, xb) = (w[0], w[1]);
            strip.clear();
            strip.extend(ids.iter().copied().filter(|&i| {
                let s = self.shape(i);
                s.lo[0] < xb && s.hi[0] > xa
            }));
            if strip.is_empty() {
                continue;
            }
            // Rays test only the strip's shapes.
            let pruned = (strip.len() < ids.len()).then(|| self.restrict(progs, &strip));
            let progs = match &pruned {
                Some([a, b]) => [a, b],
                None => progs,
            };
            // Extrusions along x (aligned boxes among them) look the same on every line.
            let part = if strip.iter().all(|&i| self.shape(i).prism[0]) {
                quad::scale(
                    self.line(0.5 * (xa + xb), &r, &strip, progs, false).0,
                    xb - xa,
                )
            } else {
                let tol = self.area_tol;
                let mut g = |x: f64| self.line(x, &r, &strip, progs, true);
                quad::integrate(&mut g, xa, xb, &tol)
            };
            total = quad::add(total, part);
        }
        total
    }

    /// `∫ f(x, y) dy` across the cell, with a signature of the line's structure when
    /// `structure` is set (else 0).
    fn line(
        &mut self,
        x: f64,
        r: &Rect,
        ids: &[u32],
        progs: [&Program; 2],
        structure: bool,
    ) -> (V3, u64) {
        let mut ys = std::mem::take(&mut self.ybreaks);
        ys.clear();
        ys.extend([r.lo[1], r.hi[1]]);
        for &i in ids {
            let s = self.shape(i);
            if x >= s.lo[0] && x <= s.hi[0] {
                s.line_breaks(0, x, &mut ys);
            }
        }
        ys.retain(|&y| y >= r.lo[1] && y <= r.hi[1]);
        ys.sort_unstable_by(f64::total_cmp);
        ys.dedup();
        self.kinds.clear();
        let mut total = [0.0; 3];
        for k in 0..ys.len().saturating_sub(1) {
            let (ya, yb) = (ys[k], ys[k + 1]);
            // Extrusions along y or z (aligned boxes among them) are constant along a segment.
            let (mut live, mut varying) = (false, false);
            for &i in ids {
                let s = self.shape(i);
                if x >= s.lo[0] && x <= s.hi[0] && s.lo[1] < yb && s.hi[1] > ya {
                    live = true;
                    if !(s.prism[1] || s.prism[2]) {
                        varying = true;
                        break;
                    }
                }
            }
            if !live {
                continue;
            }
            let part = if varying {
                let tol = self.line_tol;
                let mut f = |y: f64| self.sample(x, y, progs, true, structure);
                quad::integrate(&mut f, ya, yb, &tol)
            } else {
                let mid = 0.5 * (ya + yb);
                quad::scale(self.sample(x, mid, progs, false, structure).0, yb - ya)
            };
            total = quad::add(total, part);
        }
        self.ybreaks = ys;
        if !structure {
            return (total, 0);
        }
        // The line's structure: which kinds of stretch it met (see `push_kinds`), as a set.
        let mut kinds = std::mem::take(&mut self.kinds);
        kinds.sort_unstable();
        kinds.dedup();
        let mut h = Hasher::new();
        kinds.iter().for_each(|&k| h.add(k));
        kinds.clear();
        self.kinds = kinds;
        (total, h.finish())
    }

    /// `f(x, y)` for both solids; with `sig`, the signature of the ray's structure (else 0);
    /// with `kinds`, the kinds of its stretches are collected for the line.
    fn sample(
        &mut self,
        x: f64,
        y: f64,
        progs: [&Program; 2],
        sig: bool,
        kinds: bool,
    ) -> (V3, u64) {
        let shapes = self.shapes;
        let buf = &mut self.ivs;
        buf.clear();
        let mut hit = |i: u32| {
            shapes[i as usize].hit_vertical(x, y).map(|h| Iv {
                t0: h.t0,
                t1: h.t1,
                s0: Surf {
                    shape: i,
                    face: h.f0,
                    flip: false,
                },
                s1: Surf {
                    shape: i,
                    face: h.f1,
                    flip: false,
                },
            })
        };
        progs[0].eval(&mut hit, buf);
        let na = buf.len();
        progs[1].eval(&mut hit, buf);
        let (a, b) = buf.split_at(na);
        let (z0, z1) = self.z;
        let v = [
            clipped_len(a, z0, z1),
            clipped_len(b, z0, z1),
            clipped_common_len(a, b, z0, z1),
        ];
        if kinds {
            push_kinds(a, b, z0, z1, &mut self.kinds);
        }
        (v, if sig { signature(a, b, z0, z1) } else { 0 })
    }
}

/// A small non-cryptographic hash of a token sequence.
struct Hasher(u64);

impl Hasher {
    fn new() -> Self {
        Hasher(0x243f_6a88_85a3_08d3)
    }
    fn add(&mut self, token: u64) {
        self.0 = (self.0 ^ token).wrapping_mul(0x9e37_79b9_7f4a_7c15);
        self.0 ^= self.0 >> 31;
    }
    fn finish(&self) -> u64 {
        self.0
    }
}

/// Pushes the kind of every stretch along a ray: each interval of A, of B and of A ∩ B,
/// clipped to `[z0, z1]`, named by the surfaces (or clip planes) at its ends.
///
/// A line's set of kinds changes with x where the integral along it stops being smooth in
/// x: where two shapes that overlap in z start or stop meeting on it (a rail entering a leg),
/// where a difference starts to cut. Breaks of unrelated shapes crossing each other (a leg's
/// rim passing the edge of a back high above it) change the order of stretches along the
/// line but not this set, so they cost nothing.
fn push_kinds(a: &[Iv], b: &[Iv], z0: f64, z1: f64, out: &mut Vec<u64>) {
    let surf = |s: Surf| u64::from(s.shape) << 8 | u64::from(s.face) << 1 | u64::from(s.flip);
    let mut push = |list: u64, iv: &Iv| {
        if iv.t1.min(z1) > iv.t0.max(z0) {
            let e0 = if iv.t0 < z0 {
                u64::MAX >> 8
            } else {
                surf(iv.s0)
            };
            let e1 = if iv.t1 > z1 {
                u64::MAX >> 8
            } else {
                surf(iv.s1)
            };
            let mut h = Hasher::new();
            [list, e0, e1].into_iter().for_each(|t| h.add(t));
            out.push(h.finish());
        }
    };
    a.iter().for_each(|iv| push(0, iv));
    b.iter().for_each(|iv| push(1, iv));
    let (mut i, mut j) = (0, 0);
    while i < a.len() && j < b.len() {
        let (x, y) = (&a[i], &b[j]);
        let (t0, s0) = if x.t0 >= y.t0 {
            (x.t0, x.s0)
        } else {
            (y.t0, y.s0)
        };
        let (t1, s1) = if x.t1 <= y.t1 {
            (x.t1, x.s1)
        } else {
            (y.t1, y.s1)
        };
        if t0 < t1 {
            push(2, &Iv { t0, t1, s0, s1 });
        }
        if x.t1 < y.t1 {
            i += 1;
        } else {
            j += 1;
        }
    }
}

/// The end points of both lists and the clip planes, merged in order along the line, each
/// named by its list, surface and side: equal signatures mean the same formula for `f`.
fn signature(a: &[Iv], b: &[Iv], z0: f64, z1: f64) -> u64 {
    let end = |v: &[Iv], k: usize| -> (f64, u64) {
        let iv = &v[k / 2];
        let (t, s) = if k.is_multiple_of(2) {
            (iv.t0, iv.s0)
        } else {
            (iv.t1, iv.s1)
        };
        let tok = u64::from(s.shape) << 16 | u64::from(s.face) << 4 | (k as u64 & 1) << 1;
        (t, tok | u64::from(s.flip))
    };
    let clips = [(z0, 1u64 << 62), (z1, 1u64 << 62 | 1)];
    let nclip = if z0.is_finite() || z1.is_finite() {
        2
    } else {
        0
    };
    let (na, nb) = (2 * a.len(), 2 * b.len());
    let (mut i, mut j, mut c) = (0, 0, 0);
    let mut h = Hasher::new();
    while i < na || j < nb || c < nclip {
        let ta = if i < na { end(a, i).0 } else { f64::INFINITY };
        let tb = if j < nb { end(b, j).0 } else { f64::INFINITY };
        let tc = if c < nclip { clips[c].0 } else { f64::INFINITY };
        if i < na && ta <= tb && ta <= tc {
            h.add(end(a, i).1);
            i += 1;
        } else if j < nb && tb <= tc {
            h.add(end(b, j).1 | 1 << 63);
            j += 1;
        } else {
            h.add(clips[c].1);
            c += 1;
        }
    }
    h.finish()
}
