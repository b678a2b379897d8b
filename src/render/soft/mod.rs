//! Soft silhouettes on the CPU: the per-pixel kernel, compositing, and the gradient of a
//! function of the image with respect to every part parameter.
//!
//! For each view a [`ViewPrep`] holds the camera frame, each part's silhouette hull, and
//! each item's near depth (the items visited nearest first). [`render_view`] evaluates
//! every pixel: each item's coverage (a sigmoid of the signed distance to its hull, or
//! exactly 0/1 with `sigma = None`), its visible surface (exact ray intersection, booleans
//! by segment classification), and front-to-back compositing into coverage `M` and
//! premultiplied shade `S`, where nothing behind an opaque layer counts ([`render_soft`]
//! does the same without keeping the hard surface, which a loss does not read). Pixels
//! near a silhouette also record an [`Entry`]: how `M` and `S` change with that part's
//! signed distance and how the distance changes with the two hull vertices of the deciding
//! edge. [`theta_gradient`] turns per-pixel derivatives (of a loss, say) and those entries
//! into `∂/∂θ` for every part.
//!
//! Shortcuts skip work whose answer is known, and change no bit of the result (tested
//! against [`render_view_exhaustive`], which takes none): tiles nothing reaches are
//! background, tiles one box face covers alone are that face's shade (`tiles`), a pixel
//! whose nearest item covers it whole in front of every other is that surface alone, and a
//! pixel stops visiting items once the rest lie behind an opaque surface.
//!
//! This module owns the prepared view, the rendered images and the per-view driver;
//! `cache` keeps each view's last soft render, so a scene that changed in a few parts is
//! rendered again only where they are or were; `pixel` holds the per-pixel kernel,
//! `tiles` what each square of pixels holds, `visible` the exact boolean visible surface
//! along a ray, and `gradient` the recorded entries and their chain rule to `θ`.

// Geometry here indexes several arrays by axis; index loops read best.
#![allow(clippy::needless_range_loop)]

mod cache;
mod gradient;
mod pixel;
mod shortcuts;
mod visible;

pub use cache::SoftCache;
pub use gradient::{Entries, Entry, SurfaceEntry, accumulate_vertices, theta_gradient};

use super::camera::{Camera, Frame};
use super::scene::{CUTOFF, Hull, NSHADE, Scene, hull};
use pixel::{PixelCtx, PixelOut, Scratch};
use rayon::prelude::*;
use shortcuts::{Tile, Tiles};

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
    /// Per item: a depth no point of its parts is nearer than (the least depth of their
    /// boxes' corners, lowered by [`crate::tolerance::SHORTCUT_DEPTH_SLACK`]); infinite
    /// for an item with nothing drawn.
    pub near: Vec<f64>,
    /// The items in order of `near` (ties by index): the order a pixel visits them in.
    pub order: Vec<u32>,
    /// Per part, the eye in its local frame when every ray starts there (a perspective
    /// view); empty for an orthographic view.
    pub local_eyes: Vec<glam::DVec3>,
}

impl ViewPrep {
    /// Part `p`'s passage of the ray from `o` along `d` (a ray of this view).
    #[inline]
    pub fn intersect(
        &self,
        scene: &Scene,
        p: usize,
        o: glam::DVec3,
        d: glam::DVec3,
    ) -> Option<super::scene::Hit> {
        let g = &scene.parts[p];
        match self.local_eyes.get(p) {
            Some(&eye) => g.intersect_from(eye, d),
            None => g.intersect(o, d),
        }
    }
}

/// Relative slack of an item's near depth.
const NEAR_SLACK: f64 = crate::tolerance::SHORTCUT_DEPTH_SLACK;

/// Item `it`'s near depth in `frame` (see [`ViewPrep::near`]).
fn near_depth(scene: &Scene, it: &super::scene::Item, frame: &Frame) -> f64 {
    let mut near = f64::INFINITY;
    for &p in &it.parts {
        let g = &scene.parts[p];
        if !g.valid {
            continue;
        }
        for c in 0..8 {
            let q: [f64; 3] =
                std::array::from_fn(|a| if c >> a & 1 == 0 { g.lo[a] } else { g.hi[a] });
            near = near.min(frame.depth(g.to_world(glam::DVec3::from(q))));
        }
    }
    near - NEAR_SLACK * (1.0 + near.abs())
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
    let near: Vec<f64> = scene
        .items
        .iter()
        .map(|it| near_depth(scene, it, &frame))
        .collect();
    let mut order: Vec<u32> = (0..scene.items.len() as u32).collect();
    order.sort_by(|&a, &b| {
        near[a as usize]
            .total_cmp(&near[b as usize])
            .then(a.cmp(&b))
    });
    let local_eyes = if frame.ortho {
        Vec::new()
    } else {
        scene.parts.iter().map(|g| g.to_local(frame.eye)).collect()
    };
    ViewPrep {
        frame,
        hulls,
        rects,
        near,
        order,
        local_eyes,
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

/// Renders one view: soft channels (hard edges when `sigma` is `None`), the hard surface,
/// and (when asked) the gradient entries.
pub fn render_view(
    scene: &Scene,
    prep: &ViewPrep,
    sigma: Option<f64>,
    shade: [f64; NSHADE],
    want_entries: bool,
) -> (SoftImage, HardImage, Entries) {
    render_with_surface(
        &PixelCtx::new(scene, prep, sigma, shade, true),
        want_entries,
    )
}

/// [`render_view`] with every pixel through the whole kernel, visiting every item: no
/// shortcut (covered or empty tiles, a pixel's opaque front, items behind it). The
/// reference the shortcuts are held to, bit for bit.
pub fn render_view_exhaustive(
    scene: &Scene,
    prep: &ViewPrep,
    sigma: Option<f64>,
    shade: [f64; NSHADE],
    want_entries: bool,
) -> (SoftImage, HardImage, Entries) {
    render_with_surface(
        &PixelCtx::new(scene, prep, sigma, shade, false),
        want_entries,
    )
}

/// Soft channels, the hard surface and (when asked) the entries of `ctx`'s view.
fn render_with_surface(ctx: &PixelCtx, want_entries: bool) -> (SoftImage, HardImage, Entries) {
    let (w, h) = (ctx.prep.frame.width, ctx.prep.frame.height);
    let npx = (w * h) as usize;
    let mut hard = HardImage {
        width: w,
        height: h,
        item: vec![-1; npx],
        normal: vec![[0.0; 3]; npx],
        depth: vec![f32::INFINITY; npx],
    };
    let (soft, entries) = render_into(ctx, want_entries, Some(&mut hard));
    (soft, hard, entries)
}

/// [`render_view`] without the hard surface, for a loss and its gradient: the same soft
/// channels and entries, without filling (or allocating) the surface's buffers.
pub fn render_soft(
    scene: &Scene,
    prep: &ViewPrep,
    sigma: Option<f64>,
    shade: [f64; NSHADE],
    want_entries: bool,
) -> (SoftImage, Entries) {
    render_into(
        &PixelCtx::new(scene, prep, sigma, shade, true),
        want_entries,
        None,
    )
}

/// One row of a hard image: item, normal, depth.
type HardRow<'a> = (&'a mut [i32], &'a mut [[f32; 3]], &'a mut [f32]);

/// Evaluates every pixel of the view into new soft channels, and into `hard` when given.
fn render_into(
    ctx: &PixelCtx,
    want_entries: bool,
    hard: Option<&mut HardImage>,
) -> (SoftImage, Entries) {
    let prep = ctx.prep;
    let (w, h) = (prep.frame.width, prep.frame.height);
    let (span, tiles) = pixel_rows(ctx, [0, 0, w, h]);
    let npx = (w * h) as usize;
    let mut soft = SoftImage {
        width: w,
        height: h,
        m: vec![0.0; npx],
        s: vec![0.0; npx],
    };
    let n = w as usize;
    let hard_rows: Vec<Option<HardRow>> = match hard {
        Some(hd) => hd
            .item
            .chunks_mut(n)
            .zip(hd.normal.chunks_mut(n))
            .zip(hd.depth.chunks_mut(n))
            .map(|((i, nm), d)| Some((i, nm, d)))
            .collect(),
        None => (0..h).map(|_| None).collect(),
    };
    // Each row writes its own slices of the images; entries are gathered in row order.
    let rows: Vec<Entries> = soft
        .m
        .par_chunks_mut(n)
        .zip(soft.s.par_chunks_mut(n))
        .zip(hard_rows.into_par_iter())
        .enumerate()
        .map(|(y, ((m, s), mut hard_row))| {
            let mut entries = Entries::default();
            let mut scratch = Scratch::default();
            let mut last = None;
            let y = y as u32;
            let (x0, x1) = span[y as usize];
            for x in x0..x1 {
                if hard_row.is_none()
                    && let Tile::Covered(_, Some(shade)) = tiles.at(x, y)
                {
                    (m[x as usize], s[x as usize]) = (1.0, shade);
                    continue;
                }
                let wanted = want_entries.then_some(&mut entries);
                let Some(out) = tiled_pixel(ctx, &tiles, x, y, &mut scratch, &mut last, wanted)
                else {
                    continue;
                };
                let i = x as usize;
                m[i] = out.m as f32;
                s[i] = out.s as f32;
                if let Some((item, normal, depth)) = &mut hard_row {
                    item[i] = out.item;
                    normal[i] = out.normal.as_vec3().to_array();
                    depth[i] = out.depth as f32;
                }
            }
            entries
        })
        .collect();
    let mut entries = Entries {
        edges: Vec::with_capacity(rows.iter().map(|e| e.edges.len()).sum()),
        surfaces: Vec::with_capacity(rows.iter().map(|e| e.surfaces.len()).sum()),
    };
    for e in rows {
        entries.extend(e);
    }
    (soft, entries)
}

/// Evaluates the pixels of `region` (`[x0, y0, x1, y1)`) into `soft`, as [`render_soft`]
/// evaluates them: a pixel outside its row's item span is background.
fn render_region(
    scene: &Scene,
    prep: &ViewPrep,
    sigma: Option<f64>,
    shade: [f64; NSHADE],
    region: [u32; 4],
    soft: &mut SoftImage,
) {
    let ctx = PixelCtx::new(scene, prep, sigma, shade, true);
    let (span, tiles) = pixel_rows(&ctx, region);
    let [x0, y0, x1, y1] = region;
    let n = prep.frame.width as usize;
    soft.m
        .par_chunks_mut(n)
        .zip(soft.s.par_chunks_mut(n))
        .enumerate()
        .filter(|(y, _)| (y0..y1).contains(&(*y as u32)))
        .for_each(|(y, (m, s))| {
            let mut scratch = Scratch::default();
            let mut last = None;
            let y = y as u32;
            let (sx0, sx1) = span[y as usize];
            for x in x0..x1 {
                let (mv, sv) = if let Tile::Covered(_, Some(shade)) = tiles.at(x, y) {
                    (1.0, shade)
                } else if (sx0..sx1).contains(&x) {
                    tiled_pixel(&ctx, &tiles, x, y, &mut scratch, &mut last, None)
                        .map_or((0.0, 0.0), |out| (out.m as f32, out.s as f32))
                } else {
                    (0.0, 0.0)
                };
                m[x as usize] = mv;
                s[x as usize] = sv;
            }
        });
}

/// Pixel `(x, y)` as its tile allows: nothing for background (`None`), a covered tile's
/// surface, or the kernel's answer.
fn tiled_pixel(
    ctx: &PixelCtx,
    tiles: &Tiles,
    x: u32,
    y: u32,
    scratch: &mut Scratch,
    last: &mut Option<(u32, glam::DVec3, f64)>,
    entries: Option<&mut Entries>,
) -> Option<PixelOut> {
    let covered = match tiles.at(x, y) {
        Tile::Empty => return None,
        Tile::Covered(idx, _) => ctx.covered_pixel(idx, x, y, last),
        Tile::Mixed => None,
    };
    Some(covered.unwrap_or_else(|| ctx.pixel(x, y, scratch, entries)))
}

/// The span of each row of `ctx`'s view ([`row_spans`]) and its tiles that meet `region`.
fn pixel_rows(ctx: &PixelCtx, region: [u32; 4]) -> (Vec<(u32, u32)>, Tiles) {
    let prep = ctx.prep;
    let span = row_spans(prep, prep.frame.width, prep.frame.height);
    (span, Tiles::new(ctx, region))
}

/// The span `[x0, x1)` of each row that some item touches; the rest is background.
fn row_spans(prep: &ViewPrep, w: u32, h: u32) -> Vec<(u32, u32)> {
    let mut span = vec![(w, 0u32); h as usize];
    for r in prep.rects.iter().flatten() {
        for y in r[1]..r[3] {
            let sp = &mut span[y as usize];
            sp.0 = sp.0.min(r[0]);
            sp.1 = sp.1.max(r[2]);
        }
    }
    span
}
