//! Gradient entries a pixel records (its sensitivity to a part's silhouette distance or to a
//! subtracted part's surface) and the chain rule that turns per-pixel loss derivatives and
//! those entries into `∂loss/∂θ` per part.

use super::ViewPrep;
use crate::render::scene::{NTHETA, Scene, sample_jacobian, surface_jacobian};
use glam::DVec3;

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
    pub n: DVec3,
    pub q: DVec3,
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
