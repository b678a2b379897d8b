//! Target folders: pictures (PNG, JPEG or WebP, of any size, each its own) plus the
//! `cameras.json` that says where each was taken from.
//!
//! Every problem is reported with the file it is in and what is wrong with it, before any
//! fitting starts.

use crate::render::camera::{Camera, CameraSpec, parse_cameras_json};
use crate::render::image::Rgb;
use std::path::{Path, PathBuf};

/// A problem with a target folder, naming the file.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{}: {what}", file.display())]
pub struct TargetError {
    pub file: PathBuf,
    pub what: String,
}

fn err(file: &Path, what: impl Into<String>) -> TargetError {
    TargetError {
        file: file.to_path_buf(),
        what: what.into(),
    }
}

/// The file name endings of pictures a target folder may hold.
const PICTURE_EXTENSIONS: [&str; 4] = ["png", "jpg", "jpeg", "webp"];

/// The pictures of a target folder with their cameras.
#[derive(Debug, Clone, PartialEq)]
pub struct TargetSet {
    pub cameras: Vec<Camera>,
    pub images: Vec<Rgb>,
    pub files: Vec<PathBuf>,
}

/// Reads `dir/cameras.json` and every picture it names.
pub fn load_target_dir(dir: &Path) -> Result<TargetSet, TargetError> {
    let meta = std::fs::metadata(dir)
        .map_err(|e| err(dir, format!("cannot open the target folder: {e}")))?;
    if !meta.is_dir() {
        return Err(err(
            dir,
            "the target is not a folder (it must hold PNGs and a cameras.json)",
        ));
    }
    let pngs: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(|e| err(dir, format!("cannot list the target folder: {e}")))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            p.extension()
                .is_some_and(|x| PICTURE_EXTENSIONS.iter().any(|e| x.eq_ignore_ascii_case(e)))
        })
        .collect();
    let json = dir.join("cameras.json");
    if pngs.is_empty() {
        return Err(err(
            dir,
            "the target folder has no images (*.png, *.jpg, *.webp)",
        ));
    }
    let text = match std::fs::read_to_string(&json) {
        Ok(t) => t,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            return Err(err(
                &json,
                "missing: the target folder needs a cameras.json saying where each picture was taken from",
            ));
        }
        Err(e) => return Err(err(&json, format!("cannot read it: {e}"))),
    };
    let specs = parse_cameras_json(&text).map_err(|e| err(&json, e.to_string()))?;
    load_with_specs(dir, &json, &specs)
}

/// Loads the pictures named by `specs` (relative to `dir`); each view's camera takes its
/// picture's size unless `cameras.json` gives one, which must then agree.
pub fn load_with_specs(
    dir: &Path,
    json: &Path,
    specs: &[CameraSpec],
) -> Result<TargetSet, TargetError> {
    let mut cameras = Vec::new();
    let mut images = Vec::new();
    let mut files = Vec::new();
    for spec in specs {
        let file = dir.join(spec.image_name());
        let img = Rgb::read_picture(&file).map_err(|what| err(&file, what))?;
        let cam = spec
            .camera(Some((img.width, img.height)))
            .map_err(|e| err(json, e.to_string()))?;
        if (cam.width, cam.height) != (img.width, img.height) {
            return Err(err(
                &file,
                format!(
                    "the image is {}×{} but camera `{}` in cameras.json says {}×{}",
                    img.width, img.height, cam.name, cam.width, cam.height
                ),
            ));
        }
        cameras.push(cam);
        images.push(img);
        files.push(file);
    }
    Ok(TargetSet {
        cameras,
        images,
        files,
    })
}

impl TargetSet {
    /// The same views at a smaller size (the longer side at most `max_side` pixels).
    pub fn downsized(&self, max_side: u32) -> TargetSet {
        let mut out = self.clone();
        for (c, img) in out.cameras.iter_mut().zip(out.images.iter_mut()) {
            let long = c.width.max(c.height);
            if long <= max_side {
                continue;
            }
            let k = max_side as f64 / long as f64;
            let w = ((c.width as f64 * k).round() as u32).max(1);
            let h = ((c.height as f64 * k).round() as u32).max(1);
            *img = img.resize(w, h);
            *c = c.with_size(w, h);
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn views_may_be_jpeg_or_webp_and_of_different_sizes() {
        let dir = std::env::temp_dir().join(format!("reparamc-targets-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let mut png = Rgb::new(40, 30, [1.0; 3]);
        png.data[15 * 40 + 20] = [0.2, 0.3, 0.4];
        std::fs::write(dir.join("a.png"), png.encode_png()).unwrap();
        let grey = image::RgbImage::from_pixel(24, 24, image::Rgb([200, 100, 50]));
        grey.save(dir.join("b.jpg")).unwrap();
        grey.save(dir.join("c.webp")).unwrap();
        let json = r#"[
            {"name": "a", "eye": [0, -50, 0], "center": [0, 0, 0], "image": "a.png"},
            {"name": "b", "eye": [50, 0, 0], "center": [0, 0, 0], "image": "b.jpg"},
            {"name": "c", "eye": [0, 0, 50], "center": [0, 0, 0], "up": [0, 1, 0], "image": "c.webp"}
        ]"#;
        std::fs::write(dir.join("cameras.json"), json).unwrap();
        let set = load_target_dir(&dir).unwrap();
        let _ = std::fs::remove_dir_all(&dir);
        let sizes: Vec<(u32, u32)> = set.cameras.iter().map(|c| (c.width, c.height)).collect();
        assert_eq!(sizes, vec![(40, 30), (24, 24), (24, 24)]);
        // JPEG's rounding, WebP's lossless colour.
        let c = set.images[1].get(12, 12);
        assert!((c[0] - 200.0 / 255.0).abs() < 0.02, "{c:?}");
        assert_eq!(
            set.images[2].get(3, 3),
            [200.0 / 255.0, 100.0 / 255.0, 50.0 / 255.0]
        );
    }
}
