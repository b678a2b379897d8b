//! The reference hard renderer: one exact ray per pixel through `geom`'s CSG ray intervals,
//! shaded by the visible surface's normal.
//!
//! It shares nothing with the soft renderer but the camera, so tests can hold the soft
//! kernel (and the wgpu backend) to it.

use super::camera::Camera;
use super::soft::HardImage;
use crate::geom::{Ray, Solid};
use crate::ir::{CsgNode, Part};
use glam::DVec3;
use rayon::prelude::*;

/// The exact visible surface per pixel (`item` is 0 where a surface is seen, −1 elsewhere).
pub fn render_hard(parts: &[Part], csg: &CsgNode, camera: &Camera) -> HardImage {
    let solid = Solid::new(parts, csg);
    let frame = camera.frame();
    let (w, h) = (camera.width, camera.height);
    let rows: Vec<Vec<(i32, [f32; 3], f32)>> = (0..h)
        .into_par_iter()
        .map(|y| {
            (0..w)
                .map(|x| {
                    let r = frame.ray(x as f64 + 0.5, y as f64 + 0.5);
                    let ray = Ray {
                        origin: r.origin.to_array(),
                        dir: r.dir.to_array(),
                    };
                    let hit = solid
                        .ray(&ray)
                        .into_iter()
                        .find(|iv| iv.t1 > 0.0 && iv.t0 > 0.0);
                    match hit {
                        Some(iv) => {
                            let n = frame.to_eye(DVec3::from(iv.n0)).as_vec3().to_array();
                            (0, n, iv.t0 as f32)
                        }
                        None => (-1, [0.0; 3], f32::INFINITY),
                    }
                })
                .collect()
        })
        .collect();
    let mut img = HardImage {
        width: w,
        height: h,
        item: Vec::with_capacity((w * h) as usize),
        normal: Vec::with_capacity((w * h) as usize),
        depth: Vec::with_capacity((w * h) as usize),
    };
    for row in rows {
        for (i, n, d) in row {
            img.item.push(i);
            img.normal.push(n);
            img.depth.push(d);
        }
    }
    img
}

/// Shaded picture of a hard image with the given shading coefficients.
pub fn picture(img: &HardImage, shade: [f64; super::scene::NSHADE]) -> super::image::Rgb {
    use super::image::{BACKGROUND, SURFACE};
    let data = img
        .item
        .iter()
        .zip(&img.normal)
        .map(|(&i, n)| {
            if i < 0 {
                return BACKGROUND;
            }
            let f = super::scene::shade_features(n.map(|v| v as f64));
            let s: f64 = (0..super::scene::NSHADE).map(|k| shade[k] * f[k]).sum();
            SURFACE.map(|c| c * s as f32)
        })
        .collect();
    super::image::Rgb {
        width: img.width,
        height: img.height,
        data,
    }
}
