//! The presets gallery (`--gallery`): the model at its defaults, at each preset and at an
//! even blend of all presets, side by side in one labelled picture.
//!
//! [`tiles`] reads the states from what the output file says (the sliders' defaults, each
//! blend's values, the switches a preset turns off), so each tile is what the Customizer
//! shows for that choice. [`gallery`] renders every tile from one camera (OpenSCAD's
//! default view, framed on all tiles at once, so sizes compare) with the project's exact
//! CPU renderer at twice the size, downsampled, and letters each tile's name under it.
//! Invariant: tiles keep their order (defaults, presets in the file's order, blend).

use super::emit::EmitPlan;
use super::font::{FAMILY, ready};
use super::plot::encode_png;
use crate::analysis::reparam::Solution;
use crate::ir::Model;
use crate::render::camera::{Camera, default_views};
use crate::render::cpu::{picture, render_hard};
use crate::render::image::{BACKGROUND, Rgb};
use crate::render::scene::DEFAULT_SHADE;
use plotters::prelude::*;

/// One tile's picture size (pixels), without its label.
pub const TILE_W: u32 = 320;
pub const TILE_H: u32 = 260;
/// The height of the label band under each tile.
pub const LABEL_H: u32 = 34;
/// The gap between tiles.
pub const GAP: u32 = 8;
/// Tiles per row.
pub const COLUMNS: usize = 5;
/// The tile name of the model at its defaults, and of the even blend of all presets.
pub const DEFAULTS: &str = "defaults";
pub const BLEND: &str = "even blend";

/// One state of the model: its name, slot values and the parts switched off.
#[derive(Debug, Clone)]
pub struct Tile {
    pub name: String,
    pub values: Vec<f64>,
    pub skip: Vec<usize>,
}

/// The picture and the tiles' names, in order.
#[derive(Debug, Clone)]
pub struct Gallery {
    pub png: Vec<u8>,
    pub names: Vec<String>,
}

/// The defaults, each preset, and (with two presets or more) their even blend.
pub fn tiles(solution: &Solution, plan: &EmitPlan) -> Vec<Tile> {
    let defaults: Vec<f64> = plan.sliders.iter().map(|s| s.value).collect();
    let mut out = vec![Tile {
        name: DEFAULTS.to_string(),
        values: solution.slot_values(&defaults),
        skip: Vec::new(),
    }];
    for (j, b) in plan.blends.iter().enumerate() {
        let skip = plan
            .switches
            .iter()
            .filter(|s| s.toggle.off_in.contains(&j))
            .flat_map(|s| s.toggle.parts.iter().copied())
            .collect();
        out.push(Tile {
            name: b.name.clone(),
            values: solution.slot_values(&b.values),
            skip,
        });
    }
    if plan.blends.len() >= 2 {
        let share = 1.0 / plan.blends.len() as f64;
        let mean: Vec<f64> = (0..defaults.len())
            .map(|i| plan.blends.iter().map(|b| b.values[i] * share).sum())
            .collect();
        out.push(Tile {
            name: BLEND.to_string(),
            values: solution.slot_values(&mean),
            skip: Vec::new(),
        });
    }
    out
}

/// One camera that frames every tile: OpenSCAD's default view of their joint bounds, or
/// `views` views around them. An error when nothing is drawn or the box cannot be framed.
pub fn cameras(model: &Model, tiles: &[Tile], views: usize) -> Result<Vec<Camera>, String> {
    let mut bounds: Option<([f64; 3], [f64; 3])> = None;
    for t in tiles {
        for (i, p) in parts_of(model, t)?.iter().enumerate() {
            if t.skip.contains(&i) {
                continue;
            }
            let (l, h) = p.world_bounds();
            bounds = Some(match bounds {
                None => (l, h),
                Some((lo, hi)) => (
                    std::array::from_fn(|a| lo[a].min(l[a])),
                    std::array::from_fn(|a| hi[a].max(h[a])),
                ),
            });
        }
    }
    let (lo, hi) = bounds.ok_or("the model has no parts to draw")?;
    default_views(lo, hi, views, 2 * TILE_W, 2 * TILE_H).map_err(|e| e.to_string())
}

/// The parts of the model in state `tile`; an error when a number is not affine in the
/// slots (drawing it would need the program run again).
fn parts_of(model: &Model, tile: &Tile) -> Result<Vec<crate::ir::Part>, String> {
    model.parts_at(&tile.values).ok_or_else(|| {
        format!(
            "`{}` needs the program run again at its values (a number is not affine in the model's numbers)",
            tile.name
        )
    })
}

/// The model in state `tile` seen by `camera`, antialiased to half the camera's size.
pub fn render_tile(model: &Model, tile: &Tile, camera: &Camera) -> Result<Rgb, String> {
    let parts = parts_of(model, tile)?;
    let (w, h) = (camera.width.div_ceil(2), camera.height.div_ceil(2));
    Ok(match model.csg.without(&tile.skip) {
        Some(csg) if !parts.is_empty() => {
            picture(&render_hard(&parts, &csg, camera), DEFAULT_SHADE).resize(w, h)
        }
        _ => Rgb::new(w, h, BACKGROUND),
    })
}

/// The gallery of `tiles` as a labelled PNG.
pub fn gallery(model: &Model, tiles: &[Tile]) -> Result<Gallery, String> {
    ready()?;
    let camera = cameras(model, tiles, 1)?
        .into_iter()
        .next()
        .ok_or("no camera frames the model")?;
    let images = tiles
        .iter()
        .map(|t| render_tile(model, t, &camera))
        .collect::<Result<Vec<Rgb>, String>>()?;
    let (width, height) = size(tiles.len());
    let mut buf = vec![255u8; (width * height * 3) as usize];
    for (k, img) in images.iter().enumerate() {
        let (ox, oy) = origin(k);
        for y in 0..img.height.min(TILE_H) {
            for x in 0..img.width.min(TILE_W) {
                let at = (((oy + y) * width + ox + x) * 3) as usize;
                let c = img
                    .get(x, y)
                    .map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8);
                buf[at..at + 3].copy_from_slice(&c);
            }
        }
    }
    letter(&mut buf, (width, height), tiles)?;
    Ok(Gallery {
        png: encode_png(&buf, width, height)?,
        names: tiles.iter().map(|t| t.name.clone()).collect(),
    })
}

/// The picture's size for `count` tiles.
pub fn size(count: usize) -> (u32, u32) {
    let cols = count.clamp(1, COLUMNS) as u32;
    let rows = count.div_ceil(COLUMNS).max(1) as u32;
    (
        cols * TILE_W + (cols + 1) * GAP,
        rows * (TILE_H + LABEL_H) + (rows + 1) * GAP,
    )
}

/// The top-left pixel of tile `k`'s picture; its label band is right under it.
pub fn origin(k: usize) -> (u32, u32) {
    let (col, row) = ((k % COLUMNS) as u32, (k / COLUMNS) as u32);
    (
        GAP + col * (TILE_W + GAP),
        GAP + row * (TILE_H + LABEL_H + GAP),
    )
}

/// Frames each tile and writes its name in its label band.
fn letter(buf: &mut [u8], (w, h): (u32, u32), tiles: &[Tile]) -> Result<(), String> {
    let root = BitMapBackend::with_buffer(buf, (w, h)).into_drawing_area();
    let style = TextStyle::from((FAMILY, 20))
        .color(&RGBColor(40, 40, 40))
        .pos(plotters::style::text_anchor::Pos::new(
            plotters::style::text_anchor::HPos::Center,
            plotters::style::text_anchor::VPos::Center,
        ));
    for (k, t) in tiles.iter().enumerate() {
        let (x, y) = origin(k);
        let (x, y) = (x as i32, y as i32);
        let (tw, th) = (TILE_W as i32, (TILE_H + LABEL_H) as i32);
        root.draw(&Rectangle::new(
            [(x, y), (x + tw, y + th)],
            RGBColor(200, 200, 200),
        ))
        .map_err(|e| e.to_string())?;
        let label = (x + tw / 2, y + TILE_H as i32 + LABEL_H as i32 / 2);
        root.draw_text(&t.name, &style, label)
            .map_err(|e| e.to_string())?;
    }
    root.present().map_err(|e| e.to_string())
}
