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
use crate::render::scene::{Item, NSHADE, PartGeom, Scene};
use rayon::prelude::*;

/// A changed region covering more than this share of the image is rendered whole (the
/// copy of the cached image would only add to the same work).
const WHOLE_SHARE: f64 = 0.6;

/// The last soft render of each view (by position in the list of views).
#[derive(Debug, Default, Clone)]
pub struct SoftCache {
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

/// One view's last render and everything it was rendered from.
#[derive(Debug, Clone)]
struct Last {
    frame: Frame,
    sigma: Option<f64>,
    shade: [f64; NSHADE],
    parts: Vec<PartGeom>,
    items: Vec<Item>,
    albedo: Vec<f64>,
    rects: Vec<Option<[u32; 4]>>,
    image: SoftImage,
}

impl SoftCache {
    /// The soft image of each view (no gradient entries), equal to [`render_soft`]'s, each
    /// rendered only where the scene changed since that view's last render here.
    pub fn render(
        &mut self,
        scene: &Scene,
        views: &[ViewPrep],
        sigma: Option<f64>,
        shades: &[[f64; NSHADE]],
    ) -> Vec<SoftImage> {
        if self.views.len() < views.len() {
            self.views.resize(views.len(), None);
        }
        self.views
            .par_iter_mut()
            .zip(views.par_iter().zip(shades.par_iter()))
            .map(|(last, (prep, &shade))| {
                let redraw = last
                    .as_ref()
                    .map_or(Redraw::Whole, |l| l.changed(scene, prep, sigma, shade));
                let image = match (redraw, last.as_ref()) {
                    (Redraw::Nothing, Some(l)) => l.image.clone(),
                    (Redraw::Region(region), Some(l)) => {
                        let mut image = l.image.clone();
                        render_region(scene, prep, sigma, shade, region, &mut image);
                        image
                    }
                    _ => render_soft(scene, prep, sigma, shade, false).0,
                };
                *last = Some(Last {
                    frame: prep.frame,
                    sigma,
                    shade,
                    parts: scene.parts.clone(),
                    items: scene.items.clone(),
                    albedo: scene.albedo.clone(),
                    rects: prep.rects.clone(),
                    image: image.clone(),
                });
                image
            })
            .collect()
    }
}

impl Last {
    /// What of the view must be rendered again for `scene`.
    fn changed(
        &self,
        scene: &Scene,
        prep: &ViewPrep,
        sigma: Option<f64>,
        shade: [f64; NSHADE],
    ) -> Redraw {
        let same = self.frame == prep.frame
            && self.sigma == sigma
            && self.shade == shade
            && self.parts.len() == scene.parts.len()
            && self.items == scene.items
            && self.albedo == scene.albedo;
        if !same {
            return Redraw::Whole;
        }
        let moved: Vec<bool> = self
            .parts
            .iter()
            .zip(&scene.parts)
            .map(|(a, b)| a != b)
            .collect();
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
