//! A model prepared for fitting ([`Parametric`]): each part's kind and the affine forms
//! of its parameters in the slots, so that the fit can rebuild the scene at any slot values
//! and carry the renderer's gradient per part parameter back to the slots.
//!
//! Invariants: `forms`, `kinds`, `base` and `faces` have one entry per part of the model;
//! every form reads slots below `x0.len()`; `anchor` has `x0`'s length; `scale` is positive.

use crate::ir::{Affine, Model};
use crate::render::camera::Camera;
use crate::render::scene::{Kind, NTHETA, PartGeom, Scene, theta_at, theta_forms};
use crate::tolerance::{FIT_DIVISOR_FLOOR, FIT_SIZE_FLOOR};

/// A model prepared for fitting: each part's kind and the slot forms of its parameters.
#[derive(Debug, Clone)]
pub struct Parametric {
    pub kinds: Vec<(Kind, bool)>,
    pub forms: Vec<[Option<Affine>; NTHETA]>,
    pub base: Vec<crate::ir::Part>,
    pub csg: crate::ir::CsgNode,
    /// Where the fit starts.
    pub x0: Vec<f64>,
    /// What the regulariser pulls towards: the model's own numbers, also when a fit starts
    /// elsewhere (each round of `explore` starts where the last one ended).
    pub anchor: Vec<f64>,
    /// The model's size (longest side of its bounding box).
    pub scale: f64,
    /// Fixed points per circle of each curved part's silhouette (see [`Parametric::fix_rings`]).
    pub rings: Vec<u32>,
    /// Each part's face planes (axis, high side, affine form), for face moves.
    pub faces: Vec<Vec<(u8, bool, Affine)>>,
    /// The relations the model's structure singles out
    /// ([`crate::analysis::prior::structural_rows`]: contacts, repeats, coaxiality), one
    /// row each, zero at the model: what the tie prior ([`super::prior`]) keeps unless the
    /// pictures say otherwise.
    pub ties: Vec<Affine>,
}

impl Parametric {
    pub fn new(model: &Model) -> Parametric {
        let kinds = model
            .parts
            .iter()
            .map(|p| {
                let g = PartGeom::from_part(p);
                (g.kind, g.centered)
            })
            .collect();
        let forms = model.parts.iter().map(theta_forms).collect();
        Parametric {
            kinds,
            forms,
            base: model.parts.clone(),
            csg: model.csg.clone(),
            x0: model.slot_values(),
            anchor: model.slot_values(),
            scale: model.size().max(FIT_SIZE_FLOOR),
            rings: Vec::new(),
            faces: {
                let mut faces = vec![Vec::new(); model.parts.len()];
                for f in crate::analysis::candidates::affine_features(model) {
                    if let crate::ir::FeatureKind::Plane { axis, high } = f.kind
                        && let Some(form) = f.forms.first()
                    {
                        faces[f.part].push((axis, high, form.clone()));
                    }
                }
                faces
            },
            ties: crate::analysis::prior::structural_rows(model),
        }
    }

    /// Fixes each curved part's silhouette polygon to the finest count any camera needs at
    /// the start, so the loss stays smooth as radii change.
    pub fn fix_rings(&mut self, cameras: &[Camera]) {
        let geoms = self.geoms(&self.x0);
        self.rings = geoms
            .iter()
            .map(|g| {
                cameras
                    .iter()
                    .map(|c| {
                        let r = g.r1.max(g.r2);
                        crate::render::scene::ring_count(g, &c.frame(), r) as u32
                    })
                    .max()
                    .unwrap_or(0)
            })
            .collect();
    }

    /// How far the face that moves most moves from slot values `a` to `b` (world units).
    pub fn farthest_face_move(&self, a: &[f64], b: &[f64]) -> f64 {
        self.faces
            .iter()
            .flatten()
            .map(|(_, _, f)| (f.eval(b) - f.eval(a)).abs())
            .fold(0.0, f64::max)
    }

    /// The parts' geometry at slot values `x`.
    pub fn geoms(&self, x: &[f64]) -> Vec<PartGeom> {
        self.base
            .iter()
            .zip(&self.forms)
            .zip(&self.kinds)
            .enumerate()
            .map(|(i, ((p, f), &(kind, centered)))| {
                let mut g = PartGeom::from_theta(kind, centered, theta_at(p, f, x));
                g.ring = self.rings.get(i).copied().unwrap_or(0);
                g
            })
            .collect()
    }

    pub fn scene(&self, x: &[f64]) -> Scene {
        Scene::new(self.geoms(x), &self.csg)
    }

    /// `∂loss/∂x` from `∂loss/∂θ`.
    pub fn chain(&self, dtheta: &[[f64; NTHETA]]) -> Vec<f64> {
        let mut g = vec![0.0; self.x0.len()];
        for (forms, d) in self.forms.iter().zip(dtheta) {
            for (f, &dv) in forms.iter().zip(d) {
                if dv == 0.0 {
                    continue;
                }
                if let Some(f) = f {
                    for &(s, a) in &f.terms {
                        g[s as usize] += a * dv;
                    }
                }
            }
        }
        g
    }

    /// Lower bounds that keep every part a solid: each size (and each scale factor of an
    /// axis-aligned transform) stays at least `min_extent` in world units, radii stay
    /// non-negative. Only bounds that hold at `x₀` are returned.
    pub fn guards(&self, min_extent: f64) -> Vec<(Affine, f64)> {
        self.size_forms(min_extent)
            .into_iter()
            .map(|(f, min)| (f, min.unwrap_or(0.0)))
            .filter(|(f, min)| f.eval(&self.x0) >= *min)
            .collect()
    }

    /// The forms of the parts' sizes a size prior weighs: each extent of a box, a frustum's
    /// height and the sum of its radii, a sphere's radius, each scale factor of an
    /// axis-aligned transform (signed so that it is positive), each one that some slot
    /// moves and that is positive at the anchor.
    pub fn sizes(&self) -> Vec<Affine> {
        self.size_forms(0.0)
            .into_iter()
            .filter(|(_, min)| min.is_some())
            .map(|(f, _)| f)
            .filter(|f| !f.is_constant() && f.eval(&self.anchor) > 0.0)
            .collect()
    }

    /// Each size form with the least it may be for a world extent of `min_extent` (`None`
    /// for a single radius of a frustum, which a cone has at 0).
    fn size_forms(&self, min_extent: f64) -> Vec<(Affine, Option<f64>)> {
        let mut out: Vec<(Affine, Option<f64>)> = Vec::new();
        for (i, (forms, &(kind, _))) in self.forms.iter().zip(&self.kinds).enumerate() {
            let g = PartGeom::from_part(&self.base[i]);
            let col = |j: usize| -> f64 {
                (0..3)
                    .map(|r| g.theta[4 * r + j].powi(2))
                    .sum::<f64>()
                    .sqrt()
                    .max(FIT_DIVISOR_FLOOR)
            };
            let local = [g.hi[0] - g.lo[0], g.hi[1] - g.lo[1], g.hi[2] - g.lo[2]];
            let mut push = |f: &Option<Affine>, sign: f64, min: Option<f64>| {
                if let Some(f) = f {
                    out.push((f.scale(sign), min));
                }
            };
            match kind {
                Kind::Box => {
                    for a in 0..3 {
                        push(&forms[12 + a], 1.0, Some(min_extent / col(a)));
                    }
                }
                Kind::Frustum => {
                    push(&forms[12], 1.0, Some(min_extent / col(2)));
                    push(&forms[13], 1.0, None);
                    push(&forms[14], 1.0, None);
                    if let (Some(a), Some(b)) = (&forms[13], &forms[14]) {
                        push(&Some(a.add(b)), 1.0, Some(min_extent / col(0).max(col(1))));
                    }
                }
                Kind::Sphere => push(&forms[12], 1.0, Some(min_extent / col(0))),
            }
            // Scale factors of an axis-aligned map keep their sign and some size.
            let aligned =
                (0..3).all(|r| (0..3).filter(|&c| g.theta[4 * r + c] != 0.0).count() == 1);
            if aligned {
                for r in 0..3 {
                    for c in 0..3 {
                        let v = g.theta[4 * r + c];
                        if v != 0.0 && local[c] > 0.0 {
                            push(&forms[4 * r + c], v.signum(), Some(min_extent / local[c]));
                        }
                    }
                }
            }
        }
        out
    }

    /// Slots that reach some part's geometry.
    pub fn live_slots(&self) -> Vec<bool> {
        let mut live = vec![false; self.x0.len()];
        for forms in &self.forms {
            for f in forms.iter().flatten() {
                for s in f.slots() {
                    live[s as usize] = true;
                }
            }
        }
        live
    }
}
