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

use super::camera::{Camera, Frame, Vec3};
use super::scene::{
    CUTOFF, Coverage, Hull, NSHADE, NTHETA, PartGeom, Scene, eval_inside, eval_soft, hull,
    sample_jacobian, shade_features,
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

/// A pixel's sensitivity to one part's signed distance.
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

/// What one layer (an item at a pixel) contributes.
#[derive(Clone, Copy)]
struct Layer {
    depth: f64,
    alpha: f64,
    shade: f64,
    item: u32,
    /// `h`: zero inside a hole of a boolean item.
    keep: f64,
    /// The item's part states in the scratch.
    states: (u32, u32),
}

/// Per-thread buffers reused from pixel to pixel.
#[derive(Default)]
struct Scratch {
    layers: Vec<Layer>,
    states: Vec<(u32, PartAt)>,
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
        let v: f64 = self
            .shade
            .iter()
            .zip(f.iter())
            .take(NSHADE)
            .map(|(s, x)| s * x)
            .sum();
        (v, n)
    }

    fn pixel(
        &self,
        px: u32,
        py: u32,
        scratch: &mut Scratch,
        entries: Option<&mut Vec<Entry>>,
    ) -> PixelOut {
        let frame = &self.prep.frame;
        let u = [px as f64 + 0.5, py as f64 + 0.5];
        let ray = frame.ray(u[0], u[1]);
        let (o, d) = (ray.origin, ray.dir);
        let Scratch {
            layers,
            states,
            mb,
            sb,
        } = scratch;
        layers.clear();
        states.clear();
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
                None => {
                    let first = item.parts[0];
                    let g = &self.scene.parts[first];
                    let n = match get(first).and_then(|s| s.hit) {
                        Some(h) => h.n0,
                        None => g.near_normal(o, d),
                    };
                    (frame.depth(g.center), n)
                }
            };
            let (shade, _) = self.shade_of(n_world);
            layers.push(Layer {
                depth,
                alpha,
                shade,
                item: idx as u32,
                keep,
                states: (first_state as u32, states.len() as u32),
            });
        }
        // Front-to-back compositing.
        layers.sort_by(|a, b| a.depth.total_cmp(&b.depth));
        let n = layers.len();
        let mut m = 0.0;
        let mut s = 0.0;
        let mut t = 1.0;
        for l in layers.iter() {
            s += t * l.alpha * l.shade;
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
                sb[k] = l.alpha * l.shade + (1.0 - l.alpha) * sb[k + 1];
            }
            let mut tk = 1.0;
            let pixel = py * frame.width + px;
            for k in 0..n {
                let l = layers[k];
                let dm_da = tk * (1.0 - mb[k + 1]);
                let ds_da = tk * (l.shade - sb[k + 1]);
                tk *= 1.0 - l.alpha;
                if dm_da == 0.0 && ds_da == 0.0 {
                    continue;
                }
                let item = &self.scene.items[l.item as usize];
                let mine = &states[l.states.0 as usize..l.states.1 as usize];
                for &(p, st) in mine {
                    if !st.hull {
                        continue;
                    }
                    if st.cov.n == 0 {
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
                        eval_soft(&item.program, &get, Some(p as usize)).1 * l.keep
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
                        entries.push(Entry {
                            pixel,
                            part: p,
                            edge,
                            dm: dm_da * f,
                            ds: ds_da * f,
                            ga,
                            gb,
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

/// The first point along the ray where a boolean item's solid begins, with its outward
/// normal (an exit from a subtracted part shows that part's surface turned inward).
fn visible_surface(program: &[super::scene::Op], st: &[(u32, PartAt)]) -> Option<(f64, Vec3)> {
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
            return Some((t, n));
        }
        was = now;
    }
    None
}

/// Renders one view: soft channels (hard edges when `sigma` is `None`), the hard surface,
/// and (when asked) the gradient entries.
pub fn render_view(
    scene: &Scene,
    prep: &ViewPrep,
    sigma: Option<f64>,
    shade: [f64; NSHADE],
    want_entries: bool,
) -> (SoftImage, HardImage, Vec<Entry>) {
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
    #[allow(clippy::type_complexity)]
    let rows: Vec<(
        Vec<f32>,
        Vec<f32>,
        Vec<i32>,
        Vec<[f32; 3]>,
        Vec<f32>,
        Vec<Entry>,
    )> = (0..h)
        .into_par_iter()
        .map(|y| {
            let n = w as usize;
            let mut m = vec![0.0f32; n];
            let mut s = vec![0.0f32; n];
            let mut item = vec![-1i32; n];
            let mut normal = vec![[0.0f32; 3]; n];
            let mut depth = vec![f32::INFINITY; n];
            let mut entries = Vec::new();
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
    let mut entries = Vec::new();
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
    entries: &[Entry],
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
    for e in entries {
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
    accumulate_vertices(scene, prep, &dv)
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
