//! Shortcuts past the per-pixel kernel: pixels whose answer is known without compositing.
//!
//! Most of a view's pixels are background, or lie well inside one part's silhouette in
//! front of every other part there. Their kernel answer is nothing, or that part's visible
//! surface alone: coverage 1, its shade, no gradient entry (a saturated coverage has no
//! edge). A [`Tiles`] map classifies each [`TILE`]×[`TILE`] square as empty (nothing
//! reaches it), covered by one item (its surface at every pixel; for one box face seen
//! whole, a single shade) or mixed; [`PixelCtx::covered_pixel`] evaluates a covered pixel
//! from its ray's intersection alone, and [`PixelCtx::opaque_front`] finds the same two
//! cases pixel by pixel where a tile is mixed.
//!
//! Invariant: every shortcut's output is bit-for-bit what the kernel visiting every item
//! returns (`render_view_exhaustive`; `tests/render_shortcuts.rs`). An item is absent
//! where its parts' hulls are far enough that the kernel gives it neither coverage nor an
//! intersection test; a surface is alone where every other item present lies wholly
//! behind it, so the kernel's compositing drops it. Over a tile both are proved from the
//! hull's signed distance, the minimum of linear functions with unit gradients: concave
//! (its minimum over a square is at a corner) and 1-Lipschitz (it changes by at most the
//! distance moved); and from the depth of a convex part's front surface, largest over a
//! square at a corner. A pixel whose ray misses the surface goes to the kernel.

use super::pixel::{PixelCtx, PixelOut};
use super::{HULL_MARGIN, NEAR_SLACK};
use crate::render::scene::{CUTOFF, Hit, is_box};
use glam::DVec3;
use rayon::prelude::*;

/// Least relative lead of a box's entry face over its other faces at a tile's corners for
/// the tile to be taken as showing that face alone.
const FACE_MARGIN: f64 = crate::tolerance::SHORTCUT_DEPTH_SLACK;

/// Side of a tile, pixels.
pub(super) const TILE: u32 = 8;

/// Slack (pixels) on every signed-distance bound.
const BOUND_SLACK: f64 = crate::tolerance::SHORTCUT_PIXEL_SLACK;

/// What a tile holds, as far as its pixels' outputs go.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Tile {
    /// No item reaches any of its pixels: background.
    Empty,
    /// The item whose surface every pixel shows alone, and the soft channels' value at
    /// every pixel when that surface is one face of a box seen whole (`(M, S) = (1, S)`).
    Covered(u32, Option<f32>),
    /// Anything else: each pixel goes through the kernel.
    Mixed,
}

/// Per tile of a view, what it holds.
pub(super) struct Tiles {
    columns: u32,
    tiles: Vec<Tile>,
}

impl Tiles {
    /// The tiles of `ctx`'s view that meet `region` (`[x0, y0, x1, y1)`, pixels); the rest,
    /// and all of them when the view takes no shortcuts, are mixed.
    pub(super) fn new(ctx: &PixelCtx, region: [u32; 4]) -> Tiles {
        let frame = &ctx.prep.frame;
        let columns = frame.width.div_ceil(TILE);
        let rows = frame.height.div_ceil(TILE);
        let [x0, y0, x1, y1] = region;
        let meets = |tx: u32, ty: u32| {
            tx * TILE < x1 && (tx + 1) * TILE > x0 && ty * TILE < y1 && (ty + 1) * TILE > y0
        };
        let tiles: Vec<Tile> = (0..rows * columns)
            .into_par_iter()
            .map(|i| {
                let (tx, ty) = (i % columns, i / columns);
                if ctx.shortcuts && meets(tx, ty) {
                    tile_kind(ctx, tx, ty)
                } else {
                    Tile::Mixed
                }
            })
            .collect();
        Tiles { columns, tiles }
    }

    /// What pixel `(x, y)`'s tile holds.
    pub(super) fn at(&self, x: u32, y: u32) -> Tile {
        self.tiles[((y / TILE) * self.columns + x / TILE) as usize]
    }
}

/// What tile `(tx, ty)` holds. It is covered by an item that is a single part whose
/// coverage is saturated at every pixel centre of the tile and whose surface there is
/// nearer than every other item that is present in the tile.
///
/// The part is convex, so its front depth over the tile is largest at a corner (`1/t` of
/// the front surface is concave in pixel coordinates under a perspective map, `t` itself
/// convex under an orthographic one): every other present item must lie wholly behind the
/// largest of the corners' depths.
fn tile_kind(ctx: &PixelCtx, tx: u32, ty: u32) -> Tile {
    let frame = &ctx.prep.frame;
    let x0 = tx * TILE;
    let y0 = ty * TILE;
    let x1 = (x0 + TILE).min(frame.width);
    let y1 = (y0 + TILE).min(frame.height);
    // Pixel centres of the tile: the square [lo, hi].
    let lo = [x0 as f64 + 0.5, y0 as f64 + 0.5];
    let hi = [x1 as f64 - 0.5, y1 as f64 - 0.5];
    let centre = [(lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0];
    let reach = ((hi[0] - lo[0]).hypot(hi[1] - lo[1])) / 2.0;
    let corners = [lo, [hi[0], lo[1]], hi, [lo[0], hi[1]]];
    let full = saturation(ctx.sigma);
    let absent = full.max(HULL_MARGIN) + BOUND_SLACK;
    let is_present = |idx: usize| {
        let Some(r) = ctx.prep.rects[idx] else {
            return false;
        };
        if r[2] <= x0 || r[0] >= x1 || r[3] <= y0 || r[1] >= y1 {
            return false;
        }
        // Absent at every pixel centre: absent at the tile's centre by `reach` more.
        !ctx.absent_at(idx, centre, absent + reach)
    };
    let mut present = ctx
        .prep
        .order
        .iter()
        .map(|&i| i as usize)
        .filter(|&i| is_present(i));
    let Some(first) = present.next() else {
        return Tile::Empty;
    };
    let Some((deepest, face)) = front_depth(ctx, first, &corners, full) else {
        return Tile::Mixed;
    };
    let behind = deepest + NEAR_SLACK * (1.0 + deepest.abs());
    match present.next() {
        Some(next) if ctx.prep.near[next] <= behind => Tile::Mixed,
        _ => {
            let shade = face.map(|n| (0.0 + ctx.shade_of(first, n)) as f32);
            Tile::Covered(first as u32, shade)
        }
    }
}

/// The largest depth of item `idx`'s surface at `corners`, if it is a single part whose
/// coverage is saturated at each of them and whose surface each corner's ray meets in
/// front of the eye; and the world normal of that surface if it is one face of a box at
/// every corner, entered clearly before the others ([`FACE_MARGIN`]). A face's image is
/// convex, so every pixel between the corners then shows that face.
fn front_depth(
    ctx: &PixelCtx,
    idx: usize,
    corners: &[[f64; 2]; 4],
    full: f64,
) -> Option<(f64, Option<DVec3>)> {
    let item = &ctx.scene.items[idx];
    if !item.is_single() {
        return None;
    }
    let part = &ctx.scene.parts[item.parts[0]];
    let hull = ctx.prep.hulls[item.parts[0]].as_ref()?;
    if !part.valid
        || corners
            .iter()
            .any(|&c| hull.signed_distance(c).0 < full + BOUND_SLACK)
    {
        return None;
    }
    let mut deepest = f64::NEG_INFINITY;
    let mut face = None;
    let mut one_face = true;
    for c in corners {
        let ray = ctx.prep.frame.ray(c[0], c[1]);
        let hit = part.intersect(ray.origin, ray.dir)?;
        if hit.t0 <= 0.0 {
            return None;
        }
        deepest = deepest.max(hit.t0);
        let clear = part
            .entry_face_margin(ray.origin, ray.dir)
            .is_some_and(|m| m > FACE_MARGIN);
        one_face &= clear && face.is_none_or(|n| n == hit.n0);
        face = Some(hit.n0);
    }
    Some((deepest, face.filter(|_| one_face)))
}

impl PixelCtx<'_> {
    /// Pixel `(px, py)` of a tile that item `idx` covers alone: its surface where the ray
    /// meets it in front of the eye, else the kernel's answer. `last` keeps the last item,
    /// normal and shade seen: neighbouring pixels on one face share them.
    pub(super) fn covered_pixel(
        &self,
        idx: u32,
        px: u32,
        py: u32,
        last: &mut Option<(u32, DVec3, f64)>,
    ) -> Option<PixelOut> {
        let frame = &self.prep.frame;
        let ray = frame.ray(px as f64 + 0.5, py as f64 + 0.5);
        let part = self.scene.items[idx as usize].parts[0];
        let hit = self
            .prep
            .intersect(self.scene, part, ray.origin, ray.dir)
            .filter(|h| h.t1 > 0.0 && h.t0 > 0.0)?;
        let shade = match *last {
            Some((item, n, s)) if item == idx && n == hit.n0 => s,
            _ => {
                let s = self.shade_of(idx as usize, hit.n0);
                *last = Some((idx, hit.n0, s));
                s
            }
        };
        Some(self.surface_alone(idx as usize, &hit, shade))
    }

    /// A pixel that shows item `idx`'s surface `hit` alone, of shade `shade`: as
    /// compositing one opaque layer over nothing gives it (`S = 0 + 1·shade`).
    fn surface_alone(&self, idx: usize, hit: &Hit, shade: f64) -> PixelOut {
        PixelOut {
            m: 1.0,
            s: 0.0 + shade,
            item: idx as i32,
            normal: self.prep.frame.to_eye(hit.n0),
            depth: hit.t0,
        }
    }
}

impl PixelCtx<'_> {
    /// The pixel when no item is present there (background), or when the first item
    /// present (in depth order) is a single part that covers it whole and whose surface it
    /// sees, and every other item present lies wholly behind that surface: the kernel's
    /// answer is then that surface alone (coverage 1, its shade, no gradient entry, as
    /// `composite` drops what an opaque layer hides). An item is absent where its parts'
    /// hulls are far enough that the kernel gives it neither coverage nor an intersection
    /// test.
    pub(super) fn opaque_front(
        &self,
        px: u32,
        py: u32,
        u: [f64; 2],
        o: DVec3,
        d: DVec3,
    ) -> Option<PixelOut> {
        let prep = self.prep;
        let full = saturation(self.sigma);
        let absent = full.max(HULL_MARGIN);
        let mut present = prep.order.iter().map(|&i| i as usize).filter(|&i| {
            prep.rects[i].is_some_and(|r| px >= r[0] && px < r[2] && py >= r[1] && py < r[3])
        });
        let Some(first) = present.find(|&i| !self.absent_at(i, u, absent)) else {
            // Nothing here: the kernel would composite no layer.
            return Some(PixelOut {
                m: 0.0,
                s: 0.0,
                item: -1,
                normal: DVec3::ZERO,
                depth: f64::INFINITY,
            });
        };
        let item = &self.scene.items[first];
        if !item.is_single() {
            return None;
        }
        let part = item.parts[0];
        let g = &self.scene.parts[part];
        let hull = prep.hulls[part].as_ref()?;
        if !g.valid || hull.signed_distance(u).0 < full {
            return None;
        }
        let hit = prep
            .intersect(self.scene, part, o, d)
            .filter(|h| h.t1 > 0.0 && h.t0 > 0.0)?;
        for next in present {
            if prep.near[next] > hit.t0 {
                break;
            }
            if !self.absent_at(next, u, absent) && !self.behind_at(next, u, o, d, hit.t0) {
                return None;
            }
        }
        Some(self.surface_alone(first, &hit, self.shade_of(first, hit.n0)))
    }

    /// Whether item `idx`, a single part, lies behind depth `t` along this pixel's ray as
    /// the kernel sees it: its visible surface there, or (where it shows none) the depth
    /// its layer would take, is deeper than `t`. False for other items.
    fn behind_at(&self, idx: usize, u: [f64; 2], o: DVec3, d: DVec3, t: f64) -> bool {
        let item = &self.scene.items[idx];
        if !item.is_single() {
            return false;
        }
        let p = item.parts[0];
        let g = &self.scene.parts[p];
        let tested = self.prep.hulls[p]
            .as_ref()
            .is_none_or(|h| h.signed_distance(u).0 > -HULL_MARGIN);
        let visible = if tested {
            self.prep
                .intersect(self.scene, p, o, d)
                .filter(|h| h.t1 > 0.0 && h.t0 > 0.0)
        } else {
            None
        };
        let depth = visible.map_or_else(|| self.prep.frame.depth(g.center), |h| h.t0);
        depth > t
    }

    /// Whether item `idx` is absent at pixel centre `u`: every drawn part's hull at least
    /// `absent` pixels away.
    fn absent_at(&self, idx: usize, u: [f64; 2], absent: f64) -> bool {
        self.scene.items[idx].parts.iter().all(|&p| {
            !self.scene.parts[p].valid
                || self.prep.hulls[p]
                    .as_ref()
                    .is_some_and(|h| h.signed_distance(u).0 <= -absent)
        })
    }
}

/// The signed distance (pixels, inside positive) at and beyond which a part's coverage is
/// exactly 1, and at and below whose negative it is exactly 0 (box filter: half a pixel's
/// diagonal; soft edges: their cut-off; hard edges: coverage comes from the ray alone).
fn saturation(sigma: Option<f64>) -> f64 {
    match sigma {
        Some(s) if is_box(s) => std::f64::consts::FRAC_1_SQRT_2,
        Some(s) => CUTOFF * s,
        None => 0.0,
    }
}
