//! The border of background a fit may put around each picture
//! ([`super::FitOptions::border`]): pictures that show the whole object say that nothing
//! lies outside them, and the border is where the fit can see a part that has left them.
//!
//! Invariant: a bordered camera sees everything at the same pixel size, shifted by the
//! border on both axes; the bordered target holds the picture unchanged in its middle and
//! background (no coverage) around it.

use super::loss::Target;
use crate::render::camera::Camera;

/// Border width in pixels for a camera: `fraction` of its height, in multiples of 8 so that
/// pooled levels keep the picture's pixel grid.
fn border_px(camera: &Camera, fraction: f64) -> u32 {
    8 * (fraction * camera.height as f64 / 8.0).round() as u32
}

/// The cameras and targets seen through a border `fraction` of each picture's height
/// wide (each target records its border, so the loss can take its means over the picture).
pub fn bordered(
    cameras: &[Camera],
    targets: &[Target],
    fraction: f64,
) -> (Vec<Camera>, Vec<Target>) {
    let px: Vec<u32> = cameras.iter().map(|c| border_px(c, fraction)).collect();
    (
        cameras
            .iter()
            .zip(&px)
            .map(|(c, &b)| c.with_border(b))
            .collect(),
        targets
            .iter()
            .zip(&px)
            .map(|(t, &b)| t.with_border(b))
            .collect(),
    )
}
