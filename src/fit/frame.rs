//! The pictures as a fit sees them: the border of background a fit may put around each
//! ([`super::FitOptions::border`]): pictures that show the whole object say that nothing
//! lies outside them, and the border is where the fit can see a part that has left them;
//! and the halved cameras and pooled targets of coarse levels
//! ([`super::FitOptions::levels`]).
//!
//! Invariant: a bordered camera sees everything at the same pixel size, shifted by the
//! border on both axes; the bordered target holds the picture unchanged in its middle and
//! background (no coverage) around it. Each level halves the one before it exactly.

use super::loss::Target;
use super::options::MIN_LEVEL_SIDE;
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

/// The coarsest level, at most `levels`, at which every camera's image halves evenly to at
/// least [`MIN_LEVEL_SIDE`] pixels a side.
pub(super) fn coarsest_level(cameras: &[Camera], levels: u32) -> u32 {
    let mut max_level = 0u32;
    while max_level < levels
        && cameras.iter().all(|c| {
            let k = 1u32 << (max_level + 1);
            c.width % k == 0
                && c.height % k == 0
                && c.width / k >= MIN_LEVEL_SIDE
                && c.height / k >= MIN_LEVEL_SIDE
        })
    {
        max_level += 1;
    }
    max_level
}

/// Levels 1 to `max_level` of small images: each halves the previous level's cameras and
/// pools its targets.
pub(super) fn halved_levels(
    cameras: &[Camera],
    targets: &[Target],
    max_level: u32,
) -> Vec<(Vec<Camera>, Vec<Target>)> {
    let mut levels: Vec<(Vec<Camera>, Vec<Target>)> = Vec::new();
    for _ in 0..max_level {
        let (cams, tgts) = match levels.last() {
            Some((c, t)) => (&c[..], &t[..]),
            None => (cameras, targets),
        };
        let next = (
            cams.iter()
                .map(|c| c.with_size(c.width / 2, c.height / 2))
                .collect(),
            tgts.iter().map(Target::pooled).collect(),
        );
        levels.push(next);
    }
    levels
}
