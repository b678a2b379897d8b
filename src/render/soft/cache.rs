//! Each view's last soft render ([`SoftCache`]), so that a scene that differs from it in a
//! few parts (a fit's single-number and single-face moves) is rendered again only inside
//! the pixel rectangles of the items those parts belong to, before and after the change.
//!
//! Invariant: the result equals a whole render to the bit. A pixel outside every changed
//! item's rectangle (before and after) is evaluated from the same items with the same
//! geometry, so it keeps its value; a cached image is reused only for the same camera
//! frame, softness, shading, items and albedo, and every other case renders the whole view.

use super::{SoftImage, ViewPrep, render_region, render_soft};
use crate::render::camera::Frame;
use crate::render::scene::{NSHADE, Scene};
use rayon::prelude::*;

/// A changed region covering more than this share of the image is rendered whole (the
/// copy of the cached image would only add to the same work).
const WHOLE_SHARE: f64 = 0.6;

/// The scene of the last render and the last soft render of each view (by position in the
/// list of views), all rendered from that scene.
#[derive(Debug, Default, Clone)]
pub struct SoftCache {
    scene: Option<Scene>,
    views: Vec<Option<Last>>,
}

/// What of a view to render again.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Redraw {
    /// Nothing changed: the last image serves.
    Nothing,
    /// Only the pixels of this rectangle `[x0, y0, x1, y1)`.
    Region([u32; 4]),
    /// The whole view: the last image cannot serve (another camera, softness, shading,
    /// item list or albedo), or the change is too wide to gain from.
    Whole,
}

/// One view's last render and what, besides the scene, it was rendered from.
#[derive(Debug, Clone)]
struct Last {
    frame: Frame,
    sigma: Option<f64>,
    shade: [f64; NSHADE],
    rects: Vec<Option<[u32; 4]>>,
    image: SoftImage,
}

impl SoftCache {
    /// The soft image of each view (no gradient entries), equal to [`render_soft`]'s, each
    /// rendered only where the scene changed since that view's last render here. The
    /// images are the cache's own, redrawn in place (no copy of a whole image per call).
    pub fn render(
        &mut self,
        scene: &Scene,
        views: &[ViewPrep],
        sigma: Option<f64>,
        shades: &[[f64; NSHADE]],
    ) -> Vec<&SoftImage> {
        // Views beyond this call's are dropped: the scene kept is this call's.
        self.views.resize(views.len(), None);
        let moved = self
            .scene
            .as_ref()
            .and_then(|last| moved_parts(last, scene));
        self.views
            .par_iter_mut()
            .zip(views.par_iter().zip(shades.par_iter()))
            .for_each(|(last, (prep, &shade))| {
                let redraw = match (&moved, last.as_ref()) {
                    (Some(moved), Some(l)) => l.changed(moved, scene, prep, sigma, shade),
                    _ => Redraw::Whole,
                };
                match (redraw, last.as_mut()) {
                    (Redraw::Nothing, Some(l)) => l.rects.clone_from(&prep.rects),
                    (Redraw::Region(region), Some(l)) => {
                        render_region(scene, prep, sigma, shade, region, &mut l.image);
                        l.rects.clone_from(&prep.rects);
                    }
                    _ => {
                        *last = Some(Last {
                            frame: prep.frame,
                            sigma,
                            shade,
                            rects: prep.rects.clone(),
                            image: render_soft(scene, prep, sigma, shade, false).0,
                        });
                    }
                }
            });
        self.scene = Some(scene.clone());
        // Every view was just rendered: none is left `None`.
        self.views
            .iter()
            .filter_map(|l| l.as_ref().map(|l| &l.image))
            .collect()
    }
}

/// Which parts of `scene` differ from `last`; `None` when the two scenes are not the same
/// assembly (other items, albedo or number of parts), so nothing rendered from `last`
/// serves.
fn moved_parts(last: &Scene, scene: &Scene) -> Option<Vec<bool>> {
    let same = last.parts.len() == scene.parts.len()
        && last.items == scene.items
        && last.albedo == scene.albedo;
    same.then(|| {
        last.parts
            .iter()
            .zip(&scene.parts)
            .map(|(a, b)| a != b)
            .collect()
    })
}

impl Last {
    /// What of the view must be rendered again for `scene`, whose parts `moved` says which
    /// changed since this view's render.
    fn changed(
        &self,
        moved: &[bool],
        scene: &Scene,
        prep: &ViewPrep,
        sigma: Option<f64>,
        shade: [f64; NSHADE],
    ) -> Redraw {
        if self.frame != prep.frame || self.sigma != sigma || self.shade != shade {
            return Redraw::Whole;
        }
        let mut region: Option<[u32; 4]> = None;
        for (i, item) in scene.items.iter().enumerate() {
            if !item.parts.iter().any(|&p| moved[p]) {
                continue;
            }
            for r in [self.rects[i], prep.rects[i]].into_iter().flatten() {
                let u = region.get_or_insert(r);
                *u = [
                    u[0].min(r[0]),
                    u[1].min(r[1]),
                    u[2].max(r[2]),
                    u[3].max(r[3]),
                ];
            }
        }
        let whole = (prep.frame.width * prep.frame.height) as f64;
        match region {
            None => Redraw::Nothing,
            Some(r) if ((r[2] - r[0]) * (r[3] - r[1])) as f64 > WHOLE_SHARE * whole => {
                Redraw::Whole
            }
            Some(r) => Redraw::Region(r),
        }
    }
}
