//! Soft silhouettes on the CPU: the per-pixel kernel, compositing, and the gradient of a
//! function of the image with respect to every part parameter.
//!
//! For each view a [`ViewPrep`] holds the camera frame and each part's silhouette hull.
//! [`render_view`] evaluates every pixel: each item's coverage (a sigmoid of the signed
//! distance to its hull, or exactly 0/1 with `sigma = None`), its visible surface (exact ray
//! intersection, booleans by segment classification), and front-to-back compositing into
//! coverage `M` and premultiplied shade `S` ([`render_soft`] does the same without keeping
//! the hard surface, which a loss does not read). Pixels near a silhouette also record an
//! [`Entry`]: how `M` and `S` change with that part's signed distance and how the distance
//! changes with the two hull vertices of the deciding edge. [`theta_gradient`] turns
//! per-pixel derivatives (of a loss, say) and those entries into `∂/∂θ` for every part.
//!
//! This module owns the prepared view, the rendered images and the per-view driver;
//! `cache` keeps each view's last soft render, so a scene that changed in a few parts is
//! rendered again only where they are or were; `pixel` holds the per-pixel kernel,
//! `visible` the exact boolean visible surface along a ray, and `gradient` the recorded
//! entries and their chain rule to `θ`.

// Geometry here indexes several arrays by axis; index loops read best.
#![allow(clippy::needless_range_loop)]

mod cache;
mod gradient;
mod pixel;
mod visible;

pub use cache::SoftCache;
pub use gradient::{Entries, Entry, SurfaceEntry, accumulate_vertices, theta_gradient};

use super::camera::{Camera, Frame};
use super::scene::{CUTOFF, Hull, NSHADE, Scene, hull};
use pixel::{PixelCtx, Scratch};
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
    let (w, h) = (prep.frame.width, prep.frame.height);
    let npx = (w * h) as usize;
    let mut hard = HardImage {
        width: w,
        height: h,
        item: vec![-1; npx],
        normal: vec![[0.0; 3]; npx],
        depth: vec![f32::INFINITY; npx],
    };
    let (soft, entries) = render_into(scene, prep, sigma, shade, want_entries, Some(&mut hard));
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
    render_into(scene, prep, sigma, shade, want_entries, None)
}

/// One row of a hard image: item, normal, depth.
type HardRow<'a> = (&'a mut [i32], &'a mut [[f32; 3]], &'a mut [f32]);

/// Evaluates every pixel of the view into new soft channels, and into `hard` when given.
fn render_into(
    scene: &Scene,
    prep: &ViewPrep,
    sigma: Option<f64>,
    shade: [f64; NSHADE],
    want_entries: bool,
    hard: Option<&mut HardImage>,
) -> (SoftImage, Entries) {
    let (w, h) = (prep.frame.width, prep.frame.height);
    let (ctx, span) = pixel_rows(scene, prep, sigma, shade);
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
            let y = y as u32;
            let (x0, x1) = span[y as usize];
            for x in x0..x1 {
                let out = ctx.pixel(x, y, &mut scratch, want_entries.then_some(&mut entries));
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
    let mut entries = Entries::default();
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
    let (ctx, span) = pixel_rows(scene, prep, sigma, shade);
    let [x0, y0, x1, y1] = region;
    let n = prep.frame.width as usize;
    soft.m
        .par_chunks_mut(n)
        .zip(soft.s.par_chunks_mut(n))
        .enumerate()
        .filter(|(y, _)| (y0..y1).contains(&(*y as u32)))
        .for_each(|(y, (m, s))| {
            let mut scratch = Scratch::default();
            let y = y as u32;
            let (sx0, sx1) = span[y as usize];
            for x in x0..x1 {
                let (mv, sv) = if (sx0..sx1).contains(&x) {
                    let out = ctx.pixel(x, y, &mut scratch, None);
                    (out.m as f32, out.s as f32)
                } else {
                    (0.0, 0.0)
                };
                m[x as usize] = mv;
                s[x as usize] = sv;
            }
        });
}

/// The per-pixel context of a view and the span of each of its rows ([`row_spans`]).
fn pixel_rows<'a>(
    scene: &'a Scene,
    prep: &'a ViewPrep,
    sigma: Option<f64>,
    shade: [f64; NSHADE],
) -> (PixelCtx<'a>, Vec<(u32, u32)>) {
    let ctx = PixelCtx {
        scene,
        prep,
        sigma,
        shade,
    };
    (ctx, row_spans(prep, prep.frame.width, prep.frame.height))
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
