//! The per-pixel kernel: each item's coverage and visible surface at one pixel,
//! front-to-back compositing into `M` and `S`, and (with soft edges) the gradient entries
//! of that pixel. Per-thread scratch buffers are cleared at the start of every pixel.
//!
//! [`PixelCtx::pixel`] drives one pixel: each item's layer (`item_layer`: a plain item, or a
//! split difference with its soft cut edges), front-to-back compositing, then the gradient
//! entries (`record_entries`). An item's part states stay in the scratch exactly while the
//! item has a layer.

use super::gradient::{Entries, Entry, SurfaceEntry};
use super::visible::{first_solid_from, visible_surface, visible_surface_at};
use super::{HULL_MARGIN, ViewPrep};
use crate::render::camera::Frame;
use crate::render::scene::{
    COVERAGE_EDGES, CUTOFF, Coverage, Hit, Item, NSHADE, PartGeom, Scene, SurfacePoint,
    eval_inside, eval_soft, is_box, logistic, shade_features, sigmoid_sigma, visible_areas,
};
use crate::tolerance::{PIXEL_SCALE_FLOOR, RENDER_ROUNDOFF};
use glam::DVec3;

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
pub(super) struct Scratch {
    layers: Vec<Layer>,
    states: Vec<(u32, PartAt)>,
    negs: Vec<Neg>,
    mb: Vec<f64>,
    sb: Vec<f64>,
}

/// Per-part state at a pixel.
#[derive(Clone, Copy)]
pub(super) struct PartAt {
    alpha: f64,
    hull: bool,
    cov: Coverage,
    pub(super) hit: Option<Hit>,
}

pub(super) struct PixelCtx<'a> {
    pub(super) scene: &'a Scene,
    pub(super) prep: &'a ViewPrep,
    pub(super) sigma: Option<f64>,
    pub(super) shade: [f64; NSHADE],
    /// Whether a pixel may skip work whose result is known (`opaque_front`, items wholly
    /// behind an opaque surface, covered and empty tiles); without, every pixel visits
    /// every item, the reference the shortcuts are tested against.
    pub(super) shortcuts: bool,
}

/// Output of one pixel.
pub(super) struct PixelOut {
    pub(super) m: f64,
    pub(super) s: f64,
    pub(super) item: i32,
    pub(super) normal: DVec3,
    pub(super) depth: f64,
}

impl<'a> PixelCtx<'a> {
    pub(super) fn new(
        scene: &'a Scene,
        prep: &'a ViewPrep,
        sigma: Option<f64>,
        shade: [f64; NSHADE],
        shortcuts: bool,
    ) -> PixelCtx<'a> {
        PixelCtx {
            scene,
            prep,
            sigma,
            shade,
            shortcuts,
        }
    }
}

impl PixelCtx<'_> {
    fn part_at(&self, p: usize, u: [f64; 2], o: DVec3, d: DVec3) -> PartAt {
        let g: &PartGeom = &self.scene.parts[p];
        let mut st = PartAt {
            alpha: 0.0,
            hull: false,
            cov: Coverage {
                alpha: 0.0,
                s: f64::NEG_INFINITY,
                edges: [(0, 0.0); COVERAGE_EDGES],
                at: [u; COVERAGE_EDGES],
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
                Some(sigma) if is_box(sigma) => h.area_coverage(u),
                Some(sigma) => h.coverage(u, sigma),
                None => {
                    let (s, e) = h.signed_distance(u);
                    Coverage {
                        alpha: 0.0,
                        s,
                        edges: [(e as u32, 0.0); COVERAGE_EDGES],
                        at: [u; COVERAGE_EDGES],
                        n: 0,
                    }
                }
            };
            test = st.cov.s > -HULL_MARGIN;
        }
        if test {
            st.hit = self
                .prep
                .intersect(self.scene, p, o, d)
                .filter(|h| h.t1 > 0.0);
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

    /// Shade of item `item`'s surface with world normal `n_world`: the view's shading
    /// times the item's albedo.
    pub(super) fn shade_of(&self, item: usize, n_world: DVec3) -> f64 {
        let n = self.prep.frame.to_eye(n_world);
        let f = shade_features(n.to_array());
        let mut v = 0.0;
        for k in 0..NSHADE {
            v += self.shade[k] * f[k];
        }
        v * self.scene.albedo_of(item)
    }

    pub(super) fn pixel(
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
        if self.shortcuts
            && let Some(out) = self.opaque_front(px, py, u, o, d)
        {
            return out;
        }
        scratch.layers.clear();
        scratch.states.clear();
        scratch.negs.clear();
        let mut best_hard: Option<(f64, i32, DVec3)> = None;
        // Items nearest first: once an opaque surface is found, an item that lies wholly
        // behind it can add nothing (`composite` drops what an opaque layer hides).
        let mut opaque = f64::INFINITY;
        for &idx in &self.prep.order {
            let idx = idx as usize;
            if self.shortcuts && self.prep.near[idx] > opaque {
                break;
            }
            let Some(r) = self.prep.rects[idx] else {
                continue;
            };
            if px < r[0] || px >= r[2] || py < r[1] || py >= r[3] {
                continue;
            }
            let item = &self.scene.items[idx];
            if let Some(t) = self.item_layer(idx, item, u, o, d, scratch, &mut best_hard) {
                opaque = opaque.min(t);
            }
        }
        let (mut m, mut s) = composite(&mut scratch.layers);
        if self.sigma.is_some_and(is_box)
            && let Some(exact) = self.union_composite(u, scratch)
        {
            (m, s) = exact;
        }
        if let (Some(entries), Some(_)) = (entries, self.sigma) {
            self.record_entries(scratch, py * frame.width + px, entries);
        }
        let (item, normal, depth) = match best_hard {
            Some((t, i, n)) => (i, frame.to_eye(n), t),
            None => (-1, DVec3::ZERO, f64::INFINITY),
        };
        PixelOut {
            m,
            s,
            item,
            normal,
            depth,
        }
    }

    /// With the box filter, `(M, S)` of layers (sorted by depth) as what they are, areas:
    /// `M` the area of their union, and each layer's shade weighted by the area it adds to
    /// what lies in front of it ([`visible_areas`]). Compositing coverages as independent
    /// makes a seam between two touching parts (half a pixel each) a quarter background.
    /// `None` (composite as independent) unless two or more layers cover the pixel partly
    /// and every layer is a plain part with a hull. The gradient entries stay those of
    /// independent compositing.
    fn union_composite(&self, u: [f64; 2], scratch: &Scratch) -> Option<(f64, f64)> {
        let layers = &scratch.layers;
        if layers.iter().filter(|l| l.alpha < 1.0).count() < 2 {
            return None;
        }
        let mut polys: Vec<Vec<[f64; 2]>> = Vec::with_capacity(layers.len());
        for l in layers {
            let item = &self.scene.items[l.item as usize];
            if l.split || !item.is_single() {
                return None;
            }
            polys.push(self.prep.hulls[item.parts[0]].as_ref()?.pixel_polygon(u));
        }
        let shares = visible_areas(u, &polys)?;
        let m: f64 = shares.iter().sum();
        let s = layers
            .iter()
            .zip(&shares)
            .map(|(l, a)| a * l.premult / l.alpha)
            .sum();
        Some((m.min(1.0), s))
    }

    /// Item `idx` at this pixel: its parts' states (kept in the scratch while the item has a
    /// layer), its exact visible surface (against `best_hard`) and its layer. Returns the
    /// depth of that surface when the layer is opaque there and lies at it: nothing behind
    /// it shows, softly or hard.
    #[allow(clippy::too_many_arguments)]
    fn item_layer(
        &self,
        idx: usize,
        item: &Item,
        u: [f64; 2],
        o: DVec3,
        d: DVec3,
        scratch: &mut Scratch,
        best_hard: &mut Option<(f64, i32, DVec3)>,
    ) -> Option<f64> {
        let Scratch {
            layers,
            states,
            negs,
            ..
        } = scratch;
        let first_state = states.len();
        for &p in &item.parts {
            let st = self.part_at(p, u, o, d);
            states.push((p as u32, st));
        }
        let st = &states[first_state..];
        let range = (first_state as u32, states.len() as u32);
        // The exact visible surface of the item.
        let visible: Option<(f64, DVec3)> = if item.is_single() {
            st[0].1.hit.filter(|h| h.t0 > 0.0).map(|h| (h.t0, h.n0))
        } else {
            visible_surface(&item.program, st)
        };
        if let Some((t, n)) = visible
            && best_hard.is_none_or(|b| (t, idx as i32) < (b.0, b.1))
        {
            *best_hard = Some((t, idx as i32, n));
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
        let layer = match &item.split {
            // A difference with soft cut edges: the first operand's front surface, kept where
            // it is outside every subtracted part, and the cavity behind.
            Some((_, negatives)) => self.split_layer(idx, item, negatives, st, plain, o, d, negs),
            None => self.plain_layer(idx, item, st, visible, plain, o, d),
        };
        match layer {
            Some(l) => {
                layers.push(l);
                let at_surface = !l.split && visible.is_some_and(|(t, _)| t == l.depth);
                (l.alpha >= 1.0 && at_surface).then_some(l.depth)
            }
            None => {
                states.truncate(first_state);
                None
            }
        }
    }

    /// The layer of an item that is not a split difference (`None` where it is absent).
    #[allow(clippy::too_many_arguments)]
    fn plain_layer(
        &self,
        idx: usize,
        item: &Item,
        st: &[(u32, PartAt)],
        visible: Option<(f64, DVec3)>,
        plain: Layer,
        o: DVec3,
        d: DVec3,
    ) -> Option<Layer> {
        let (alpha, keep) = match self.sigma {
            None => (if visible.is_some() { 1.0 } else { 0.0 }, 1.0),
            Some(_) => {
                if item.is_single() {
                    (st[0].1.alpha, 1.0)
                } else {
                    let a = eval_soft(&item.program, &|p| alpha_of(st, p), None).0;
                    let support = eval_inside(&item.program, &|p| {
                        state_of(st, p).is_some_and(|s| s.hit.is_some())
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
            return None;
        }
        let (depth, n_world) = match visible {
            Some((t, n)) => (t, n),
            None => self.fallback(item, st, o, d),
        };
        Some(Layer {
            depth,
            alpha,
            premult: alpha * self.shade_of(idx, n_world),
            keep,
            ..plain
        })
    }

    /// The continuation of an item's first part's face past the silhouette: its depth and
    /// world normal.
    fn fallback(&self, item: &Item, st: &[(u32, PartAt)], o: DVec3, d: DVec3) -> (f64, DVec3) {
        let first = item.parts[0];
        let g = &self.scene.parts[first];
        let n = match state_of(st, first).and_then(|s| s.hit) {
            Some(h) => h.n0,
            None => g.near_normal(o, d),
        };
        (self.prep.frame.depth(g.center), n)
    }

    /// The layer of a split difference (`None` where it is absent); its subtracted parts
    /// near the front point go to `negs`.
    #[allow(clippy::too_many_arguments)]
    fn split_layer(
        &self,
        idx: usize,
        item: &Item,
        negatives: &[usize],
        st: &[(u32, PartAt)],
        plain: Layer,
        o: DVec3,
        d: DVec3,
        negs: &mut Vec<Neg>,
    ) -> Option<Layer> {
        let pos = item.positive();
        let front: Option<(f64, DVec3, usize)> = if pos.len() == 1 {
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
            Some(_) => eval_soft(pos, &|p| alpha_of(st, p), None).0,
        };
        if alpha_a <= 0.0 {
            return None;
        }
        let Some((ta, na, ka)) = front else {
            let (depth, n) = self.fallback(item, st, o, d);
            let sh = self.shade_of(idx, n);
            return Some(Layer {
                depth,
                alpha: alpha_a,
                premult: alpha_a * sh,
                ..plain
            });
        };
        let first_neg = negs.len();
        let (kappa, deepest) = self.cut(negatives, st, (ta, na, ka), o, d, negs);
        let neg_range = (first_neg as u32, negs.len() as u32);
        let sh_front = self.shade_of(idx, na);
        // What the cut shows: the solid after leaving the deepest subtracted part (nothing
        // for a hole through); outside every subtracted part, the front.
        let (cavity, sh_cavity) = if kappa < 1.0 {
            let exit = deepest
                .and_then(|(_, b)| state_of(st, b))
                .and_then(|s| s.hit)
                .filter(|h| h.t1 > ta);
            match exit {
                Some(h) => match first_solid_from(&item.program, st, h.t1) {
                    Some((_, nc)) => (1.0, self.shade_of(idx, nc)),
                    None => (0.0, 0.0),
                },
                None => (1.0, sh_front),
            }
        } else {
            (1.0, sh_front)
        };
        let alpha = alpha_a * (kappa + (1.0 - kappa) * cavity);
        if alpha > 0.0 {
            Some(Layer {
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
            })
        } else {
            negs.truncate(first_neg);
            None
        }
    }

    /// How much of a split difference's front point (at ray parameter `ta`, normal `na`, on
    /// state `ka`'s part) its subtracted parts keep: the product `κ` of their soft
    /// outsides, and the deepest cut `(κ_b, b)`. Parts in the soft band go to `negs`.
    fn cut(
        &self,
        negatives: &[usize],
        st: &[(u32, PartAt)],
        (ta, na, ka): (f64, DVec3, usize),
        o: DVec3,
        d: DVec3,
        negs: &mut Vec<Neg>,
    ) -> (f64, Option<(f64, usize)>) {
        let frame = &self.prep.frame;
        let pa = o + d * ta;
        // The front point as a material point of its part: the front moves with it.
        let part_a = st[ka].0;
        let sp_a = self.scene.parts[part_a as usize].surface_distance(pa);
        let na_d = na.dot(d);
        let mut kappa = 1.0;
        let mut deepest: Option<(f64, usize)> = None;
        for &b in negatives {
            let Some(sb_) = state_of(st, b) else { continue };
            let gb = &self.scene.parts[b];
            let kb = match self.sigma {
                None => {
                    let inside = sb_.hit.is_some_and(|h| h.t0 <= ta && ta <= h.t1);
                    if inside { 0.0 } else { 1.0 }
                }
                Some(sigma) => {
                    let sigma = sigmoid_sigma(sigma);
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
                        let along = if na_d.abs() > RENDER_ROUNDOFF {
                            -sp.n.dot(d) / na_d
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
        (kappa, deepest)
    }

    /// The pixel's gradient entries: how `M` and `S` change with every soft edge and cut
    /// of the composited layers.
    fn record_entries(&self, scratch: &mut Scratch, pixel: u32, entries: &mut Entries) {
        let Scratch {
            layers,
            states,
            negs,
            mb,
            sb,
        } = scratch;
        let n = layers.len();
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
            self.edge_entries(&l, mine, (dm_dc, ds_dc), pixel, entries);
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
            let mine = &negs[l.negs.0 as usize..l.negs.1 as usize];
            cut_entries(&l, mine, (dm_dk, ds_dk), pixel, entries);
        }
    }

    /// Entries of a layer's soft edges, with `(∂M, ∂S)` per unit of its coverage `dc`.
    fn edge_entries(
        &self,
        l: &Layer,
        mine: &[(u32, PartAt)],
        (dm_dc, ds_dc): (f64, f64),
        pixel: u32,
        entries: &mut Entries,
    ) {
        let item = &self.scene.items[l.item as usize];
        let program = item.positive();
        for &(p, st) in mine {
            if !st.hull || st.cov.n == 0 {
                continue;
            }
            let da_item = if item.is_single() {
                1.0
            } else {
                let get = |q: usize| alpha_of(mine, q);
                eval_soft(program, &get, Some(p as usize)).1 * l.keep
            };
            if da_item == 0.0 {
                continue;
            }
            let Some(h) = &self.prep.hulls[p as usize] else {
                continue;
            };
            for (&(edge, dalpha_ds), &at) in st.cov.edges[..st.cov.n].iter().zip(&st.cov.at) {
                let f = da_item * dalpha_ds;
                let (ga, gb) = h.edge_gradient(edge as usize, at);
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
    }
}

/// Entries of a split layer's subtracted parts `negs`, with `(∂M, ∂S)` per unit of its `κ`.
fn cut_entries(
    l: &Layer,
    negs: &[Neg],
    (dm_dk, ds_dk): (f64, f64),
    pixel: u32,
    entries: &mut Entries,
) {
    for ng in negs {
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

/// Front-to-back compositing of the layers (sorted here by depth, ties by item): `(M, S)`.
/// Layers behind the first opaque one are dropped: they add nothing, and neither the exact
/// union of partial layers nor the gradient entries should look at them.
fn composite(layers: &mut Vec<Layer>) -> (f64, f64) {
    layers.sort_by(|a, b| a.depth.total_cmp(&b.depth).then(a.item.cmp(&b.item)));
    if let Some(k) = layers.iter().position(|l| l.alpha >= 1.0) {
        layers.truncate(k + 1);
    }
    let mut m = 0.0;
    let mut s = 0.0;
    let mut t = 1.0;
    for l in layers.iter() {
        s += t * l.premult;
        m += t * l.alpha;
        t *= 1.0 - l.alpha;
    }
    (m, s)
}

/// Part `p`'s state among an item's states.
fn state_of(st: &[(u32, PartAt)], p: usize) -> Option<PartAt> {
    st.iter().find(|(q, _)| *q as usize == p).map(|x| x.1)
}

/// Part `p`'s coverage among an item's states (0 if it has none).
fn alpha_of(st: &[(u32, PartAt)], p: usize) -> f64 {
    state_of(st, p).map_or(0.0, |s| s.alpha)
}

/// Pixel-space length of the gradient of a distance along normal `nb`, for a point that
/// moves on the plane (normal `na`) hit at parameter `t` of the ray `d`: how many world
/// units of that distance one pixel is.
fn pixel_scale(frame: &Frame, d: DVec3, t: f64, na: DVec3, nb: DVec3) -> f64 {
    let dd = na.dot(d);
    let f = frame.focal;
    let axes = [frame.right * (1.0 / f), frame.up * (-1.0 / f)];
    let mut g2 = 0.0;
    for dv in axes {
        let dp = if dd.abs() < RENDER_ROUNDOFF {
            // Grazing: the point slides along the ray; count the plain footprint.
            if frame.ortho { dv } else { dv * t }
        } else if frame.ortho {
            let dt = -na.dot(dv) / dd;
            dv + d * dt
        } else {
            let dt = -t * na.dot(dv) / dd;
            dv * t + d * dt
        };
        let c = nb.dot(dp);
        g2 += c * c;
    }
    g2.sqrt().max(PIXEL_SCALE_FLOOR)
}
