//! Soft silhouettes on the CPU: the per-pixel kernel, compositing, and the gradient of an
//! image loss with respect to every part parameter.
//!
//! For each view a [`ViewPrep`] holds the camera frame and each part's silhouette hull.
//! [`render_view`] evaluates every pixel: each item's coverage (a sigmoid of the signed
//! distance to its hull, or exactly 0/1 with `sigma = None`), its visible surface (exact ray
//! intersection, booleans by segment classification), and front-to-back compositing into
//! coverage `M` and premultiplied shade `S`. Pixels near a silhouette also record an
//! [`Entry`]: how `M` and `S` change with that part's signed distance and how the distance
//! changes with the two hull vertices of the deciding edge. [`theta_gradient`] turns
//! per-pixel loss derivatives and those entries into `∂loss/∂θ` for every part.

// Geometry here indexes several arrays by axis; index loops read best.
#![allow(clippy::needless_range_loop)]

use super::camera::{Camera, Frame, Vec3, dot, scale};
use super::scene::{
    CUTOFF, Coverage, Hull, NSHADE, NTHETA, PartGeom, Scene, SurfacePoint, eval_inside, eval_soft,
    hull, logistic, sample_jacobian, shade_features, surface_jacobian,
};
use rayon::prelude::*;

/// Pixels of hard-edge tolerance around a polygonal hull (the exact silhouette of a curved
/// part lies within a small fraction of a pixel outside its polygon).
const HULL_MARGIN: f64 = 1.5;

/// A view ready to render: camera frame, hulls per part, pixel rectangles per item.
#[derive(Debug, Clone)]
pub struct ViewPrep {
    pub frame: Frame,
    pub hulls: Vec<Option<Hull>>,
    /// Per item: the pixel rectangle `[x0, y0, x1, y1)` outside which it is absent.
    pub rects: Vec<Option<[u32; 4]>>,
}

/// Prepares a view for soft edges of width `sigma` pixels (`None`: hard edges).
pub fn prepare_view(scene: &Scene, camera: &Camera, sigma: Option<f64>) -> ViewPrep {
    let frame = camera.frame();
    let hulls: Vec<Option<Hull>> = scene.parts.iter().map(|p| hull(p, &frame)).collect();
    let margin = HULL_MARGIN.max(sigma.map_or(0.0, |s| CUTOFF * s)) + 1.0;
    let (w, h) = (frame.width as f64, frame.height as f64);
    let rects = scene
        .items
        .iter()
        .map(|it| {
            let mut lo = [f64::INFINITY; 2];
            let mut hi = [f64::NEG_INFINITY; 2];
            let mut any = false;
            for &p in &it.parts {
                if !scene.parts[p].valid {
                    continue;
                }
                any = true;
                match &hulls[p] {
                    Some(hl) => {
                        for k in 0..2 {
                            lo[k] = lo[k].min(hl.lo[k]);
                            hi[k] = hi[k].max(hl.hi[k]);
                        }
                    }
                    None => {
                        lo = [0.0, 0.0];
                        hi = [w, h];
                    }
                }
            }
            if !any {
                return None;
            }
            let x0 = (lo[0] - margin).floor().clamp(0.0, w) as u32;
            let y0 = (lo[1] - margin).floor().clamp(0.0, h) as u32;
            let x1 = (hi[0] + margin).ceil().clamp(0.0, w) as u32;
            let y1 = (hi[1] + margin).ceil().clamp(0.0, h) as u32;
            (x0 < x1 && y0 < y1).then_some([x0, y0, x1, y1])
        })
        .collect();
    ViewPrep {
        frame,
        hulls,
        rects,
    }
}

/// A pixel's sensitivity to one part's signed distance to its silhouette.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Entry {
    pub pixel: u32,
    pub part: u32,
    /// The hull edge (its start vertex index) that decides the distance.
    pub edge: u32,
    /// `∂M/∂s` and `∂S/∂s`.
    pub dm: f64,
    pub ds: f64,
    /// `∂s/∂(start vertex)` and `∂s/∂(end vertex)`.
    pub ga: [f64; 2],
    pub gb: [f64; 2],
}

/// A pixel's sensitivity to a subtracted part's surface where it cuts the visible surface
/// (the rim of a hollow): `∂M/∂sd`, `∂S/∂sd` with `sd` the signed distance (world units) of
/// the visible point to that part's nearest face, whose material point and normal are given.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceEntry {
    pub pixel: u32,
    pub part: u32,
    pub dm: f64,
    pub ds: f64,
    pub n: [f64; 3],
    pub q: [f64; 3],
    pub ldq: [f64; 3],
}

/// A view's gradient entries.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Entries {
    pub edges: Vec<Entry>,
    pub surfaces: Vec<SurfaceEntry>,
}

impl Entries {
    pub fn extend(&mut self, other: Entries) {
        self.edges.extend(other.edges);
        self.surfaces.extend(other.surfaces);
    }
}

/// Soft channels of a view: coverage and premultiplied shade.
#[derive(Debug, Clone, PartialEq)]
pub struct SoftImage {
    pub width: u32,
    pub height: u32,
    pub m: Vec<f32>,
    pub s: Vec<f32>,
}

/// The exact (hard) visible surface per pixel.
#[derive(Debug, Clone, PartialEq)]
pub struct HardImage {
    pub width: u32,
    pub height: u32,
    /// Item index of the visible surface, or −1.
    pub item: Vec<i32>,
    /// Eye-space unit normal of the visible surface (x right, y up, z to the viewer).
    pub normal: Vec<[f32; 3]>,
    pub depth: Vec<f32>,
}

impl HardImage {
    pub fn mask(&self) -> impl Iterator<Item = bool> + '_ {
        self.item.iter().map(|&i| i >= 0)
    }
}

/// What one layer (an item at a pixel) contributes: coverage `α` and premultiplied shade
/// `P` (`α·shade` for a plain surface).
///
/// A split difference is one layer too: its first operand's front surface where it is
/// kept (fraction `κ`) mixed with what the cut shows behind it (the cavity; nothing for a
/// hole through): `α = a·(κ + (1 − κ)·c)`, `P = a·(κ·sh_f + (1 − κ)·c·sh_c)`.
#[derive(Clone, Copy)]
struct Layer {
    depth: f64,
    alpha: f64,
    premult: f64,
    item: u32,
    /// `h`: zero inside a hole of a boolean item (not split).
    keep: f64,
    /// The item's part states in the scratch.
    states: (u32, u32),
    /// Whether this is a split difference (the fields below are used).
    split: bool,
    /// `a`, `κ`, `c` (1 if the cut shows a surface) and the two shades.
    alpha_a: f64,
    kappa: f64,
    cavity: f64,
    sh_front: f64,
    sh_cavity: f64,
    /// The subtracted parts near the front point, in the scratch.
    negs: (u32, u32),
}

/// A subtracted part near a split difference's front point.
#[derive(Clone, Copy)]
struct Neg {
    part: u32,
    kappa: f64,
    /// `∂κ/∂sd`.
    dk: f64,
    sp: SurfacePoint,
    /// The part whose surface holds the front point, `∂sd/∂(its surface jacobian)`, and
    /// that surface point.
    front: Option<(u32, f64, SurfacePoint)>,
}

/// Per-thread buffers reused from pixel to pixel.
#[derive(Default)]
struct Scratch {
    layers: Vec<Layer>,
    states: Vec<(u32, PartAt)>,
    negs: Vec<Neg>,
    mb: Vec<f64>,
    sb: Vec<f64>,
}

/// Per-part state at a pixel.
#[derive(Clone, Copy)]
struct PartAt {
    alpha: f64,
    hull: bool,
    cov: Coverage,
    hit: Option<super::scene::Hit>,
}

struct PixelCtx<'a> {
    scene: &'a Scene,
    prep: &'a ViewPrep,
    sigma: Option<f64>,
    shade: [f64; NSHADE],
}

/// Output of one pixel.
struct PixelOut {
    m: f64,
    s: f64,
    item: i32,
    normal: Vec3,
    depth: f64,
}

impl PixelCtx<'_> {
    fn part_at(&self, p: usize, u: [f64; 2], o: Vec3, d: Vec3) -> PartAt {
        let g: &PartGeom = &self.scene.parts[p];
        let mut st = PartAt {
            alpha: 0.0,
            hull: false,
            cov: Coverage {
                alpha: 0.0,
                s: f64::NEG_INFINITY,
                edges: [(0, 0.0); 2],
                n: 0,
            },
            hit: None,
        };
        if !g.valid {
            return st;
        }
        let mut test = true;
        if let Some(h) = &self.prep.hulls[p] {
            st.hull = true;
            st.cov = match self.sigma {
                Some(sigma) => h.coverage(u, sigma),
                None => {
                    let (s, e) = h.signed_distance(u);
                    Coverage {
                        alpha: 0.0,
                        s,
                        edges: [(e as u32, 0.0), (0, 0.0)],
                        n: 0,
                    }
                }
            };
            test = st.cov.s > -HULL_MARGIN;
        }
        if test {
            st.hit = g.intersect(o, d).filter(|h| h.t1 > 0.0);
        }
        st.alpha = match (self.sigma, st.hull) {
            (Some(_), true) => st.cov.alpha,
            _ => {
                if st.hit.is_some() {
                    1.0
                } else {
                    0.0
                }
            }
        };
        st
    }

    fn shade_of(&self, n_world: Vec3) -> (f64, Vec3) {
        let n = self.prep.frame.to_eye(n_world);
        let f = shade_features(n);
        let mut v = 0.0;
        for k in 0..NSHADE {
            v += self.shade[k] * f[k];
        }
        (v, n)
    }

    fn pixel(
        &self,
        px: u32,
        py: u32,
        scratch: &mut Scratch,
        entries: Option<&mut Entries>,
    ) -> PixelOut {
        let frame = &self.prep.frame;
        let u = [px as f64 + 0.5, py as f64 + 0.5];
        let ray = frame.ray(u[0], u[1]);
        let (o, d) = (ray.origin, ray.dir);
        let Scratch {
            layers,
            states,
            negs,
            mb,
            sb,
        } = scratch;
        layers.clear();
        states.clear();
        negs.clear();
        let mut best_hard: Option<(f64, i32, Vec3)> = None;
        for (idx, item) in self.scene.items.iter().enumerate() {
            let Some(r) = self.prep.rects[idx] else {
                continue;
            };
            if px < r[0] || px >= r[2] || py < r[1] || py >= r[3] {
                continue;
            }
            let first_state = states.len();
            for &p in &item.parts {
                let st = self.part_at(p, u, o, d);
                states.push((p as u32, st));
            }
            let st = &states[first_state..];
            let get = |p: usize| st.iter().find(|(q, _)| *q as usize == p).map(|x| x.1);
            let range = (first_state as u32, states.len() as u32);
            // The exact visible surface of the item.
            let visible: Option<(f64, Vec3)> = if item.is_single() {
                st[0].1.hit.filter(|h| h.t0 > 0.0).map(|h| (h.t0, h.n0))
            } else {
                visible_surface(&item.program, st)
            };
            if let Some((t, n)) = visible
                && best_hard.is_none_or(|b| t < b.0)
            {
                best_hard = Some((t, idx as i32, n));
            }
            let plain = Layer {
                depth: 0.0,
                alpha: 0.0,
                premult: 0.0,
                item: idx as u32,
                keep: 1.0,
                states: range,
                split: false,
                alpha_a: 1.0,
                kappa: 1.0,
                cavity: 0.0,
                sh_front: 0.0,
                sh_cavity: 0.0,
                negs: (0, 0),
            };
            // The continuation of the first part's face past the silhouette.
            let fallback = || {
                let first = item.parts[0];
                let g = &self.scene.parts[first];
                let n = match get(first).and_then(|s| s.hit) {
                    Some(h) => h.n0,
                    None => g.near_normal(o, d),
                };
                (frame.depth(g.center), n)
            };
            if let Some((_, negatives)) = &item.split {
                // A difference with soft cut edges: the first operand's front surface, kept
                // where it is outside every subtracted part, and the cavity behind.
                let pos = item.positive();
                let front: Option<(f64, Vec3, usize)> = if pos.len() == 1 {
                    st[0].1.hit.filter(|h| h.t0 > 0.0).map(|h| (h.t0, h.n0, 0))
                } else {
                    visible_surface_at(pos, st)
                };
                let alpha_a = match self.sigma {
                    None => {
                        if front.is_some() {
                            1.0
                        } else {
                            0.0
                        }
                    }
                    Some(_) => eval_soft(pos, &|p| get(p).map_or(0.0, |s| s.alpha), None).0,
                };
                if alpha_a <= 0.0 {
                    states.truncate(first_state);
                    continue;
                }
                let Some((ta, na, ka)) = front else {
                    let (depth, n) = fallback();
                    let sh = self.shade_of(n).0;
                    layers.push(Layer {
                        depth,
                        alpha: alpha_a,
                        premult: alpha_a * sh,
                        ..plain
                    });
                    continue;
                };
                let pa = [o[0] + ta * d[0], o[1] + ta * d[1], o[2] + ta * d[2]];
                // The front point as a material point of its part: the front moves with it.
                let part_a = st[ka].0;
                let sp_a = self.scene.parts[part_a as usize].surface_distance(pa);
                let na_d = dot(na, d);
                let first_neg = negs.len();
                let mut kappa = 1.0;
                let mut deepest: Option<(f64, usize)> = None;
                for &b in negatives {
                    let Some(sb_) = get(b) else { continue };
                    let gb = &self.scene.parts[b];
                    let kb = match self.sigma {
                        None => {
                            let inside = sb_.hit.is_some_and(|h| h.t0 <= ta && ta <= h.t1);
                            if inside { 0.0 } else { 1.0 }
                        }
                        Some(sigma) => {
                            let Some(sp) = gb.surface_distance(pa) else {
                                continue;
                            };
                            let g = pixel_scale(frame, d, ta, na, sp.n);
                            let s = sp.sd / g;
                            if s >= CUTOFF * sigma {
                                1.0
                            } else if s <= -CUTOFF * sigma {
                                0.0
                            } else {
                                let k = logistic(s / sigma);
                                // ∂sd/∂(front offset): the front point slides along the ray.
                                let along = if na_d.abs() > 1e-12 {
                                    -dot(sp.n, d) / na_d
                                } else {
                                    0.0
                                };
                                negs.push(Neg {
                                    part: b as u32,
                                    kappa: k,
                                    dk: k * (1.0 - k) / (sigma * g),
                                    sp,
                                    front: sp_a.map(|a| (part_a, along, a)),
                                });
                                k
                            }
                        }
                    };
                    kappa *= kb;
                    if deepest.is_none_or(|(k, _)| kb < k) {
                        deepest = Some((kb, b));
                    }
                }
                let neg_range = (first_neg as u32, negs.len() as u32);
                let sh_front = self.shade_of(na).0;
                // What the cut shows: the solid after leaving the deepest subtracted part
                // (nothing for a hole through); outside every subtracted part, the front.
                let (cavity, sh_cavity) = if kappa < 1.0 {
                    let exit = deepest
                        .and_then(|(_, b)| get(b))
                        .and_then(|s| s.hit)
                        .filter(|h| h.t1 > ta);
                    match exit {
                        Some(h) => match first_solid_from(&item.program, st, h.t1) {
                            Some((_, nc)) => (1.0, self.shade_of(nc).0),
                            None => (0.0, 0.0),
                        },
                        None => (1.0, sh_front),
                    }
                } else {
                    (1.0, sh_front)
                };
                let alpha = alpha_a * (kappa + (1.0 - kappa) * cavity);
                if alpha > 0.0 {
                    layers.push(Layer {
                        depth: ta,
                        alpha,
                        premult: alpha_a * (kappa * sh_front + (1.0 - kappa) * cavity * sh_cavity),
                        split: true,
                        alpha_a,
                        kappa,
                        cavity,
                        sh_front,
                        sh_cavity,
                        negs: neg_range,
                        ..plain
                    });
                } else {
                    states.truncate(first_state);
                    negs.truncate(first_neg);
                }
                continue;
            }
            let (alpha, keep) = match self.sigma {
                None => (if visible.is_some() { 1.0 } else { 0.0 }, 1.0),
                Some(_) => {
                    if item.is_single() {
                        (st[0].1.alpha, 1.0)
                    } else {
                        let a =
                            eval_soft(&item.program, &|p| get(p).map_or(0.0, |s| s.alpha), None).0;
                        let support = eval_inside(&item.program, &|p| {
                            get(p).is_some_and(|s| s.hit.is_some())
                        });
                        let keep = if support && visible.is_none() {
                            0.0
                        } else {
                            1.0
                        };
                        (a * keep, keep)
                    }
                }
            };
            if alpha <= 0.0 {
                states.truncate(first_state);
                continue;
            }
            let (depth, n_world) = match visible {
                Some((t, n)) => (t, n),
                None => fallback(),
            };
            layers.push(Layer {
                depth,
                alpha,
                premult: alpha * self.shade_of(n_world).0,
                keep,
                ..plain
            });
        }
        // Front-to-back compositing.
        layers.sort_by(|a, b| a.depth.total_cmp(&b.depth));
        let n = layers.len();
        let mut m = 0.0;
        let mut s = 0.0;
        let mut t = 1.0;
        for l in layers.iter() {
            s += t * l.premult;
            m += t * l.alpha;
            t *= 1.0 - l.alpha;
        }
        if let (Some(entries), Some(_)) = (entries, self.sigma) {
            // Composites of what lies behind each layer.
            mb.clear();
            mb.resize(n + 1, 0.0);
            sb.clear();
            sb.resize(n + 1, 0.0);
            for k in (0..n).rev() {
                let l = &layers[k];
                mb[k] = l.alpha + (1.0 - l.alpha) * mb[k + 1];
                sb[k] = l.premult + (1.0 - l.alpha) * sb[k + 1];
            }
            let mut tk = 1.0;
            let pixel = py * frame.width + px;
            for k in 0..n {
                let l = layers[k];
                // ∂M/∂α, ∂S/∂α and ∂S/∂P of this layer.
                let dm_da = tk * (1.0 - mb[k + 1]);
                let ds_da = -tk * sb[k + 1];
                let ds_dp = tk;
                tk *= 1.0 - l.alpha;
                if dm_da == 0.0 && ds_da == 0.0 && ds_dp == 0.0 {
                    continue;
                }
                let item = &self.scene.items[l.item as usize];
                let mine = &states[l.states.0 as usize..l.states.1 as usize];
                // How this layer's α and P depend on the (first operand's) coverage.
                let (a_factor, p_factor) = if l.split {
                    (
                        l.kappa + (1.0 - l.kappa) * l.cavity,
                        l.kappa * l.sh_front + (1.0 - l.kappa) * l.cavity * l.sh_cavity,
                    )
                } else {
                    (1.0, l.premult / l.alpha)
                };
                let dm_dc = dm_da * a_factor;
                let ds_dc = ds_da * a_factor + ds_dp * p_factor;
                let program = item.positive();
                for &(p, st) in mine {
                    if !st.hull || st.cov.n == 0 {
                        continue;
                    }
                    let da_item = if item.is_single() {
                        1.0
                    } else {
                        let get = |q: usize| {
                            mine.iter()
                                .find(|(r, _)| *r as usize == q)
                                .map_or(0.0, |x| x.1.alpha)
                        };
                        eval_soft(program, &get, Some(p as usize)).1 * l.keep
                    };
                    if da_item == 0.0 {
                        continue;
                    }
                    let Some(h) = &self.prep.hulls[p as usize] else {
                        continue;
                    };
                    for &(edge, dalpha_ds) in &st.cov.edges[..st.cov.n] {
                        let f = da_item * dalpha_ds;
                        let (ga, gb) = h.edge_gradient(edge as usize, u);
                        entries.edges.push(Entry {
                            pixel,
                            part: p,
                            edge,
                            dm: dm_dc * f,
                            ds: ds_dc * f,
                            ga,
                            gb,
                        });
                    }
                }
                // Subtracted parts, through κ.
                if !l.split {
                    continue;
                }
                let dm_dk = dm_da * l.alpha_a * (1.0 - l.cavity);
                let ds_dk = ds_da * l.alpha_a * (1.0 - l.cavity)
                    + ds_dp * l.alpha_a * (l.sh_front - l.cavity * l.sh_cavity);
                if dm_dk == 0.0 && ds_dk == 0.0 {
                    continue;
                }
                for ng in &negs[l.negs.0 as usize..l.negs.1 as usize] {
                    let others = if ng.kappa > 0.0 {
                        l.kappa / ng.kappa
                    } else {
                        0.0
                    };
                    let f = others * ng.dk;
                    if f == 0.0 {
                        continue;
                    }
                    entries.surfaces.push(SurfaceEntry {
                        pixel,
                        part: ng.part,
                        dm: dm_dk * f,
                        ds: ds_dk * f,
                        n: ng.sp.n,
                        q: ng.sp.q,
                        ldq: ng.sp.ldq,
                    });
                    if let Some((pa, along, spa)) = ng.front
                        && along != 0.0
                    {
                        entries.surfaces.push(SurfaceEntry {
                            pixel,
                            part: pa,
                            dm: dm_dk * f * along,
                            ds: ds_dk * f * along,
                            n: spa.n,
                            q: spa.q,
                            ldq: spa.ldq,
                        });
                    }
                }
            }
        }
        let (item, normal, depth) = match best_hard {
            Some((t, i, n)) => (i, frame.to_eye(n), t),
            None => (-1, [0.0; 3], f64::INFINITY),
        };
        PixelOut {
            m,
            s,
            item,
            normal,
            depth,
        }
    }
}

/// Pixel-space length of the gradient of a distance along normal `nb`, for a point that
/// moves on the plane (normal `na`) hit at parameter `t` of the ray `d`: how many world
/// units of that distance one pixel is.
fn pixel_scale(frame: &Frame, d: Vec3, t: f64, na: Vec3, nb: Vec3) -> f64 {
    let dd = dot(na, d);
    let f = frame.focal;
    let axes = [scale(frame.right, 1.0 / f), scale(frame.up, -1.0 / f)];
    let mut g2 = 0.0;
    for dv in axes {
        let dp = if dd.abs() < 1e-12 {
            // Grazing: the point slides along the ray; count the plain footprint.
            if frame.ortho { dv } else { scale(dv, t) }
        } else if frame.ortho {
            let dt = -dot(na, dv) / dd;
            [dv[0] + dt * d[0], dv[1] + dt * d[1], dv[2] + dt * d[2]]
        } else {
            let dt = -t * dot(na, dv) / dd;
            [
                t * dv[0] + dt * d[0],
                t * dv[1] + dt * d[1],
                t * dv[2] + dt * d[2],
            ]
        };
        let c = dot(nb, dp);
        g2 += c * c;
    }
    g2.sqrt().max(1e-12)
}

/// The first point at or after `t_start` where the item's solid begins (the point just
/// after `t_start` counts: it shows the surface being left there, turned inward).
fn first_solid_from(
    program: &[super::scene::Op],
    st: &[(u32, PartAt)],
    t_start: f64,
) -> Option<(f64, Vec3)> {
    let index_of = |p: usize| st.iter().position(|(q, _)| *q as usize == p);
    let mut inside: Vec<bool> = st
        .iter()
        .map(|(_, s)| s.hit.is_some_and(|h| h.t0 <= t_start && t_start < h.t1))
        .collect();
    let member =
        |inside: &[bool]| eval_inside(program, &|p| index_of(p).is_some_and(|k| inside[k]));
    if member(&inside) {
        // Solid right after leaving a part at t_start: that part's exit surface, inward.
        let k = st
            .iter()
            .position(|(_, s)| s.hit.is_some_and(|h| h.t1 == t_start))?;
        let h = st[k].1.hit?;
        return Some((t_start, [-h.n1[0], -h.n1[1], -h.n1[2]]));
    }
    let mut events: Vec<(f64, usize, bool)> = Vec::new();
    for (k, (_, s)) in st.iter().enumerate() {
        if let Some(h) = s.hit {
            if h.t0 > t_start {
                events.push((h.t0, k, true));
            }
            if h.t1 > t_start {
                events.push((h.t1, k, false));
            }
        }
    }
    events.sort_by(|a, b| a.0.total_cmp(&b.0));
    for &(t, k, entry) in &events {
        inside[k] = entry;
        if member(&inside) {
            let h = st[k].1.hit?;
            let n = if entry {
                h.n0
            } else {
                [-h.n1[0], -h.n1[1], -h.n1[2]]
            };
            return Some((t, n));
        }
    }
    None
}

/// The first point along the ray where a boolean item's solid begins, with its outward
/// normal (an exit from a subtracted part shows that part's surface turned inward).
fn visible_surface(program: &[super::scene::Op], st: &[(u32, PartAt)]) -> Option<(f64, Vec3)> {
    visible_surface_at(program, st).map(|(t, n, _)| (t, n))
}

/// [`visible_surface`] with the state index of the part whose surface it is.
fn visible_surface_at(
    program: &[super::scene::Op],
    st: &[(u32, PartAt)],
) -> Option<(f64, Vec3, usize)> {
    let mut events: Vec<(f64, usize, bool)> = Vec::with_capacity(2 * st.len());
    let mut inside: Vec<bool> = vec![false; st.len()];
    for (k, (_, s)) in st.iter().enumerate() {
        if let Some(h) = s.hit {
            if h.t0 > 0.0 {
                events.push((h.t0, k, true));
            } else {
                inside[k] = true;
            }
            events.push((h.t1, k, false));
        }
    }
    if events.is_empty() {
        return None;
    }
    events.sort_by(|a, b| a.0.total_cmp(&b.0));
    let index_of = |p: usize| st.iter().position(|(q, _)| *q as usize == p);
    let member =
        |inside: &[bool]| eval_inside(program, &|p| index_of(p).is_some_and(|k| inside[k]));
    let mut was = member(&inside);
    for &(t, k, entry) in &events {
        inside[k] = entry;
        let now = member(&inside);
        if now && !was && t > 0.0 {
            let h = st[k].1.hit.expect("events come from hits");
            let n = if entry {
                h.n0
            } else {
                [-h.n1[0], -h.n1[1], -h.n1[2]]
            };
            return Some((t, n, k));
        }
        was = now;
    }
    None
}

/// One row of a view: coverage, shade, item, normal, depth, entries.
type Row = (
    Vec<f32>,
    Vec<f32>,
    Vec<i32>,
    Vec<[f32; 3]>,
    Vec<f32>,
    Entries,
);

/// Renders one view: soft channels (hard edges when `sigma` is `None`), the hard surface,
/// and (when asked) the gradient entries.
pub fn render_view(
    scene: &Scene,
    prep: &ViewPrep,
    sigma: Option<f64>,
    shade: [f64; NSHADE],
    want_entries: bool,
) -> (SoftImage, HardImage, Entries) {
    let (w, h) = (prep.frame.width, prep.frame.height);
    let ctx = PixelCtx {
        scene,
        prep,
        sigma,
        shade,
    };
    // The span of each row that some item touches; the rest is background.
    let mut span = vec![(w, 0u32); h as usize];
    for r in prep.rects.iter().flatten() {
        for y in r[1]..r[3] {
            let sp = &mut span[y as usize];
            sp.0 = sp.0.min(r[0]);
            sp.1 = sp.1.max(r[2]);
        }
    }
    let rows: Vec<Row> = (0..h)
        .into_par_iter()
        .map(|y| {
            let n = w as usize;
            let mut m = vec![0.0f32; n];
            let mut s = vec![0.0f32; n];
            let mut item = vec![-1i32; n];
            let mut normal = vec![[0.0f32; 3]; n];
            let mut depth = vec![f32::INFINITY; n];
            let mut entries = Entries::default();
            let mut scratch = Scratch::default();
            let (x0, x1) = span[y as usize];
            {
                for x in x0..x1 {
                    let out = ctx.pixel(x, y, &mut scratch, want_entries.then_some(&mut entries));
                    let i = x as usize;
                    m[i] = out.m as f32;
                    s[i] = out.s as f32;
                    item[i] = out.item;
                    normal[i] = out.normal.map(|v| v as f32);
                    depth[i] = out.depth as f32;
                }
            }
            (m, s, item, normal, depth, entries)
        })
        .collect();
    let npx = (w * h) as usize;
    let mut soft = SoftImage {
        width: w,
        height: h,
        m: Vec::with_capacity(npx),
        s: Vec::with_capacity(npx),
    };
    let mut hard = HardImage {
        width: w,
        height: h,
        item: Vec::with_capacity(npx),
        normal: Vec::with_capacity(npx),
        depth: Vec::with_capacity(npx),
    };
    let mut entries = Entries::default();
    for (m, s, item, normal, depth, e) in rows {
        soft.m.extend(m);
        soft.s.extend(s);
        hard.item.extend(item);
        hard.normal.extend(normal);
        hard.depth.extend(depth);
        entries.extend(e);
    }
    (soft, hard, entries)
}

/// `∂loss/∂θ` per part from per-pixel derivatives `gm = ∂loss/∂M`, `gs = ∂loss/∂S`.
pub fn theta_gradient(
    scene: &Scene,
    prep: &ViewPrep,
    entries: &Entries,
    gm: &[f32],
    gs: &[f32],
) -> Vec<[f64; NTHETA]> {
    // ∂loss/∂(hull vertex) per part.
    let mut dv: Vec<Vec<[f64; 2]>> = prep
        .hulls
        .iter()
        .map(|h| {
            h.as_ref()
                .map_or(Vec::new(), |h| vec![[0.0; 2]; h.verts.len()])
        })
        .collect();
    for e in &entries.edges {
        let i = e.pixel as usize;
        let c = gm[i] as f64 * e.dm + gs[i] as f64 * e.ds;
        if c == 0.0 {
            continue;
        }
        let v = &mut dv[e.part as usize];
        let a = e.edge as usize;
        let b = (a + 1) % v.len();
        v[a][0] += c * e.ga[0];
        v[a][1] += c * e.ga[1];
        v[b][0] += c * e.gb[0];
        v[b][1] += c * e.gb[1];
    }
    let mut out = accumulate_vertices(scene, prep, &dv);
    for e in &entries.surfaces {
        let i = e.pixel as usize;
        let c = gm[i] as f64 * e.dm + gs[i] as f64 * e.ds;
        if c == 0.0 {
            continue;
        }
        let j = surface_jacobian(e.n, e.q, e.ldq);
        for (acc, jq) in out[e.part as usize].iter_mut().zip(j) {
            *acc += c * jq;
        }
    }
    out
}

/// Chains `∂loss/∂(hull vertex)` to `∂loss/∂θ`.
pub fn accumulate_vertices(
    scene: &Scene,
    prep: &ViewPrep,
    dv: &[Vec<[f64; 2]>],
) -> Vec<[f64; NTHETA]> {
    let mut out = vec![[0.0; NTHETA]; scene.parts.len()];
    for (p, h) in prep.hulls.iter().enumerate() {
        let Some(h) = h else { continue };
        for (k, g) in dv[p].iter().enumerate() {
            if g[0] == 0.0 && g[1] == 0.0 {
                continue;
            }
            let s = &h.samples[h.src[k] as usize];
            if let Some(j) = sample_jacobian(&scene.parts[p], s, &prep.frame) {
                for q in 0..NTHETA {
                    out[p][q] += g[0] * j[0][q] + g[1] * j[1][q];
                }
            }
        }
    }
    out
}
