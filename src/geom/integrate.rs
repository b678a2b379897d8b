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
//! - **Order.** In a cell, lines run along x or along y, whichever fewer of its shapes vary
//!   along (a rail along x is constant on lines along x); below, "x" is the outer axis.
//! - **Strips.** The x breaks of the cell's shapes (bounds, corners, rim extremes, where a
//!   footprint crosses the cell's side) cut it into strips. A strip whose shapes are all
//!   extrusions along x (axis-aligned boxes among them) looks the same on every line: one
//!   line at its middle, and along it one ray per y cell, is *exact*. Other strips are cut
//!   further where break curves of shapes that overlap in z cross (`crossings`), and
//!   integrate `g(x) = ∫ f dy` adaptively (`quad`) from those pieces, locating remaining
//!   kinks where the set of kinds of stretch met by the line changes; pieces narrower than a
//!   tenth of their strip take the cheaper 7/15 rule (fewer lines).
//! - **Level curves.** Where a curved surface meets a flat cap of another shape of the leaf
//!   (or a clip plane), the length inside their boolean has a kink: each such curve is a
//!   break of the lines, and its tangents along the lines are breaks of the strips.
//! - **Lines.** Along a line the y breaks cut it into segments; a segment seen only by
//!   extrusions along y or z (aligned boxes, upright cylinders) takes one ray, others are
//!   integrated adaptively (segments under 2% of the line with the 7/15 rule). Rays return
//!   a signature (the merged order of every interval end) so kinks are found and split
//!   exactly; ends of A and B tie only within rounding noise, so surfaces that touch
//!   without crossing cost no split. Breaks closer than `eps` are one.
//!
//! Invariants: the result is a sum of finite terms; the z clip and the xy domain bound the
//! integral to the requested region; shapes with an empty footprint never enter a cell.

use super::crossings::{self, Curves, Hasher};
use super::csg::{Iv, Program, Surf, clipped_common_len, clipped_len};
use super::quad::{self, Tol, V3};
use super::shape::Shape;
use crate::tolerance::{
    GEOM_COINCIDENT, GEOM_ROUNDOFF, GEOM_TIE_OF_COINCIDENT, QUAD_AREA_ATOL, QUAD_AREA_RTOL,
    QUAD_LINE_ATOL, QUAD_LINE_RTOL, QUAD_MIN_WIDTH,
};

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
    /// Interval ends closer than this are one point (see `csg`).
    eps: f64,
    line_tol: Tol,
    area_tol: Tol,
    mask: Vec<bool>,
    ivs: Vec<Iv>,
    ybreaks: Vec<f64>,
    /// Kinds of stretch met by the current line's rays.
    kinds: Vec<u64>,
    /// The leaf's `(outer, inner)` axes: lines run along `inner`.
    axes: (usize, usize),
    /// Scratch: the shapes seen by a segment, and the programs pruned to them.
    live: Vec<u32>,
    segment_programs: [Program; 2],
    /// The leaf's level curves: `(shape, height)` where a curved shape meets a horizontal
    /// face of another shape, or a clip plane, of the leaf.
    levels: Vec<(u32, f64)>,
    crossing_scratch: crossings::Scratch,
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
        eps: GEOM_COINCIDENT * size,
        line_tol: Tol {
            rtol: QUAD_LINE_RTOL,
            atol_density: QUAD_LINE_ATOL * size,
            min_width: QUAD_MIN_WIDTH * size,
            budget: 200,
            short: 0.0,
        },
        area_tol: Tol {
            rtol: QUAD_AREA_RTOL,
            atol_density: QUAD_AREA_ATOL * size * size,
            min_width: QUAD_MIN_WIDTH * size,
            budget: 200,
            // Narrow pieces of strips (between rim extremes of similar parts) are smooth
            // enough for the 7/15 rule; lines keep 10/21, which needs fewer splits there.
            short: 0.1,
        },
        mask: vec![false; job.shapes.len()],
        ivs: Vec::new(),
        ybreaks: Vec::new(),
        kinds: Vec::new(),
        axes: (0, 1),
        live: Vec::new(),
        segment_programs: Default::default(),
        levels: Vec::new(),
        crossing_scratch: Default::default(),
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

    /// `∫∫ f` over a leaf cell, strip by strip, in the better order of the two axes.
    fn leaf(&mut self, r: Rect, ids: &[u32], progs: [&Program; 2]) -> V3 {
        // Lines run along the axis that the fewest shapes vary along (a rail along x makes
        // lines along x constant where a line along y would have to be integrated).
        let varying = |inner: usize| {
            ids.iter()
                .filter(|&&i| !(self.shape(i).prism[inner] || self.shape(i).prism[2]))
                .count()
        };
        let (o, inner) = if varying(0) < varying(1) {
            (1, 0)
        } else {
            (0, 1)
        };
        self.axes = (o, inner);
        self.set_levels(ids);
        let mut cuts = vec![r.lo[o], r.hi[o]];
        for &i in ids {
            let s = self.shape(i);
            s.axis_breaks(o, &mut cuts);
            // Where a footprint's boundary crosses a side of the cell along the lines, the
            // integral over the cell has a kink.
            for side in [r.lo[inner], r.hi[inner]] {
                if !s.aligned && s.lo[inner] < side && side < s.hi[inner] {
                    s.line_breaks(inner, side, &mut cuts);
                }
            }
        }
        for &(i, h) in &self.levels {
            let s = self.shape(i);
            s.level_axis_breaks(o, h, &mut cuts);
            for side in [r.lo[inner], r.hi[inner]] {
                if s.lo[inner] < side && side < s.hi[inner] {
                    s.level_breaks(inner, side, h, &mut |v, _| cuts.push(v));
                }
            }
        }
        cuts.retain(|&c| c >= r.lo[o] && c <= r.hi[o]);
        cuts.sort_unstable_by(f64::total_cmp);
        // Breaks closer than rounding noise (a cos 90° of 6e-17) would only make slivers.
        let eps = GEOM_ROUNDOFF * self.size;
        cuts.dedup_by(|b, a| *b - *a <= eps);
        if let Some(last) = cuts.last_mut() {
            *last = r.hi[o];
        }
        let mut total = [0.0; 3];
        let mut strip = Vec::with_capacity(ids.len());
        for w in cuts.windows(2) {
            let (ca, cb) = (w[0], w[1]);
            strip.clear();
            strip.extend(ids.iter().copied().filter(|&i| {
                let s = self.shape(i);
                s.lo[o] < cb && s.hi[o] > ca
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
            // Extrusions across the strip (aligned boxes among them) look the same on every
            // line of it.
            let part = if strip.iter().all(|&i| self.shape(i).prism[o]) {
                let mid = 0.5 * (ca + cb);
                quad::scale(self.line(mid, &r, &strip, progs, false).0, cb - ca)
            } else {
                // Known kinks inside the strip: where curves of shapes that meet cross.
                let mut pieces = vec![ca];
                let curves = Curves {
                    shapes: self.shapes,
                    ids: &strip,
                    levels: &self.levels,
                    axes: self.axes,
                    eps: self.eps,
                };
                crossings::crossings(&curves, ca, cb, &mut self.crossing_scratch, &mut pieces);
                pieces.push(cb);
                let tol = self.area_tol;
                let mut g = |c: f64| self.line(c, &r, &strip, progs, true);
                quad::integrate_pieces(&mut g, &pieces, &tol)
            };
            total = quad::add(total, part);
        }
        total
    }

    /// Collects the level curves of the leaf's shapes `ids`: for every curved shape that
    /// can meet a horizontal plane along a curve of its own, the heights strictly inside it
    /// of the flat caps of other shapes whose footprints' bounds meet its own, and of the
    /// clip planes.
    fn set_levels(&mut self, ids: &[u32]) {
        let mut levels = std::mem::take(&mut self.levels);
        levels.clear();
        let mut hs = Vec::new();
        for &i in ids {
            let s = self.shape(i);
            if !s.has_levels() {
                continue;
            }
            hs.clear();
            hs.extend([self.z.0, self.z.1]);
            for &j in ids {
                let t = self.shape(j);
                if j != i
                    && t.has_flat_caps()
                    && (0..2).all(|a| t.lo[a] < s.hi[a] && s.lo[a] < t.hi[a])
                {
                    hs.extend([t.lo[2], t.hi[2]]);
                }
            }
            let eps = self.eps;
            hs.retain(|&h| h > s.lo[2] + eps && h < s.hi[2] - eps);
            hs.sort_unstable_by(f64::total_cmp);
            hs.dedup_by(|b, a| *b - *a <= eps);
            levels.extend(hs.iter().map(|&h| (i, h)));
        }
        self.levels = levels;
    }

    /// `∫ f` along the line at outer coordinate `c` across the cell, with a signature of
    /// the line's structure when `structure` is set (else 0).
    fn line(
        &mut self,
        c: f64,
        r: &Rect,
        ids: &[u32],
        progs: [&Program; 2],
        structure: bool,
    ) -> (V3, u64) {
        let (o, inner) = self.axes;
        let mut ys = std::mem::take(&mut self.ybreaks);
        ys.clear();
        ys.extend([r.lo[inner], r.hi[inner]]);
        let ys_hi = r.hi[inner];
        for &i in ids {
            let s = self.shape(i);
            if c >= s.lo[o] && c <= s.hi[o] {
                s.line_breaks(o, c, &mut ys);
            }
        }
        for &(i, h) in &self.levels {
            let s = self.shape(i);
            if c >= s.lo[o] && c <= s.hi[o] {
                s.level_breaks(o, c, h, &mut |y, _| ys.push(y));
            }
        }
        ys.retain(|&y| y >= r.lo[inner] && y <= r.hi[inner]);
        ys.sort_unstable_by(f64::total_cmp);
        // Breaks closer than rounding noise (the rim of two coaxial parts computed from
        // matrices an ulp apart) would only make slivers whose rays see a structure by
        // chance, which would make the line's kinds flicker from line to line.
        let eps = self.eps;
        ys.dedup_by(|b, a| *b - *a <= eps);
        if let Some(last) = ys.last_mut() {
            *last = ys_hi;
        }
        self.kinds.clear();
        let mut total = [0.0; 3];
        for k in 0..ys.len().saturating_sub(1) {
            let (ya, yb) = (ys[k], ys[k + 1]);
            // Extrusions along the line or along z (aligned boxes among them) are constant
            // along a segment.
            let mut live = std::mem::take(&mut self.live);
            live.clear();
            live.extend(ids.iter().copied().filter(|&i| {
                let s = self.shape(i);
                c >= s.lo[o] && c <= s.hi[o] && s.lo[inner] < yb && s.hi[inner] > ya
            }));
            let varying = live.iter().any(|&i| {
                let s = self.shape(i);
                !(s.prism[inner] || s.prism[2])
            });
            let part = if live.is_empty() {
                [0.0; 3]
            } else if varying {
                // Many rays: let them test only the segment's shapes.
                let mut seg = std::mem::take(&mut self.segment_programs);
                live.iter().for_each(|&i| self.mask[i as usize] = true);
                for (p, out) in progs.iter().zip(seg.iter_mut()) {
                    p.prune_into(&|s| self.mask[s as usize], out);
                }
                live.iter().for_each(|&i| self.mask[i as usize] = false);
                let mut tol = self.line_tol;
                // Segments under 2% of the line (between rims of similar parts) converge
                // with the 7/15 rule; longer ones need fewer splits with 10/21.
                if yb - ya < 0.02 * (r.hi[inner] - r.lo[inner]) {
                    tol.short = f64::INFINITY;
                }
                let mut f = |y: f64| self.sample(c, y, [&seg[0], &seg[1]], true, structure);
                let v = quad::integrate(&mut f, ya, yb, &tol);
                self.segment_programs = seg;
                v
            } else {
                let mid = 0.5 * (ya + yb);
                quad::scale(self.sample(c, mid, progs, false, structure).0, yb - ya)
            };
            self.live = live;
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

    /// `f` at outer coordinate `c`, inner coordinate `t`, for both solids; with `sig`, the
    /// signature of the ray's structure (else 0); with `kinds`, the kinds of its stretches
    /// are collected for the line.
    fn sample(
        &mut self,
        c: f64,
        t: f64,
        progs: [&Program; 2],
        sig: bool,
        kinds: bool,
    ) -> (V3, u64) {
        let (x, y) = if self.axes.0 == 0 { (c, t) } else { (t, c) };
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
        progs[0].eval(&mut hit, buf, self.eps);
        let na = buf.len();
        progs[1].eval(&mut hit, buf, self.eps);
        let (a, b) = buf.split_at(na);
        let (z0, z1) = self.z;
        let v = [
            clipped_len(a, z0, z1),
            clipped_len(b, z0, z1),
            clipped_common_len(a, b, z0, z1),
        ];
        if kinds {
            push_kinds(a, b, self.z, self.eps, &mut self.kinds);
        }
        let s = if sig {
            signature(a, b, self.z, self.eps)
        } else {
            0
        };
        (v, s)
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
fn push_kinds(a: &[Iv], b: &[Iv], z: (f64, f64), eps: f64, out: &mut Vec<u64>) {
    const CLIP: u64 = u64::MAX >> 8;
    let mut push = |list: u64, iv: &Iv| {
        if iv.t1.min(z.1) - iv.t0.max(z.0) > eps {
            let e0 = if iv.t0 < z.0 + eps { CLIP } else { iv.s0.key() };
            let e1 = if iv.t1 > z.1 - eps { CLIP } else { iv.s1.key() };
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
        // The later start and the earlier end; of two within eps, A's.
        let (t0, s0) = if x.t0 >= y.t0 - eps {
            (x.t0, x.s0)
        } else {
            (y.t0, y.s0)
        };
        let (t1, s1) = if x.t1 <= y.t1 + eps {
            (x.t1, x.s1)
        } else {
            (y.t1, y.s1)
        };
        push(2, &Iv { t0, t1, s0, s1 });
        if x.t1 < y.t1 {
            i += 1;
        } else {
            j += 1;
        }
    }
}

/// How far an end of B may lie before an end `t` of A and still tie with it: rounding
/// noise (a hundredth of `eps`, or ~50 ulps of `t` far from the origin).
fn tie(t: f64, eps: f64) -> f64 {
    GEOM_TIE_OF_COINCIDENT * eps + GEOM_ROUNDOFF * t.abs()
}

/// The end points of both lists and the clip planes, merged in order along the line, each
/// named by its list, surface and side: equal signatures mean the same formula for `f`.
/// Ends of A and B within rounding noise ([`tie`]) count as one point, ordered A first, so
/// coincident faces of A and B do not make the order flicker; ends within `eps` of a clip
/// plane come before it (each list is already more than `eps` apart inside). Ends of A and
/// B closer than `eps` but not tied keep their true order: where two surfaces touch without
/// crossing (coaxial copies sharing one scale), ordering them by a fixed rule inside `eps`
/// would change the signature in a thin band around the contact where `f` is smooth, and
/// every line through it would be split twice there. A crossing still changes the order.
fn signature(a: &[Iv], b: &[Iv], z: (f64, f64), eps: f64) -> u64 {
    let end = |v: &[Iv], k: usize| -> (f64, u64) {
        let iv = &v[k / 2];
        let (t, s) = if k.is_multiple_of(2) {
            (iv.t0, iv.s0)
        } else {
            (iv.t1, iv.s1)
        };
        (t, s.key() << 1 | (k as u64 & 1))
    };
    let clips = [(z.0, 1u64 << 62), (z.1, 1u64 << 62 | 1)];
    let nclip = if z.0.is_finite() || z.1.is_finite() {
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
        if i < na && ta <= tb + tie(ta, eps) && ta <= tc + eps {
            h.add(end(a, i).1);
            i += 1;
        } else if j < nb && tb <= tc + eps {
            h.add(end(b, j).1 | 1 << 63);
            j += 1;
        } else {
            h.add(clips[c].1);
            c += 1;
        }
    }
    h.finish()
}
