//! Pictures rendered by OpenSCAD itself (the `openscad` binary under `xvfb-run`), from our
//! cameras: targets for fitting, and the oracle for camera conventions.

use super::camera::Camera;
use super::image::Rgb;
use std::path::Path;
use std::process::Command;

/// Options for an OpenSCAD render.
#[derive(Debug, Clone, PartialEq)]
pub struct OpenScadRender {
    /// `$fn` for curved parts (OpenSCAD draws them as polygons).
    pub fn_segments: u32,
    /// Use CGAL (`--render`) instead of the fast preview.
    pub full_render: bool,
    /// Colour scheme name (`Cornfield`, `Tomorrow`, ...).
    pub colorscheme: String,
}

impl Default for OpenScadRender {
    fn default() -> Self {
        OpenScadRender {
            fn_segments: 96,
            full_render: false,
            colorscheme: "Cornfield".into(),
        }
    }
}

/// Whether `openscad` and `xvfb-run` are on the path.
pub fn available() -> bool {
    let ok = |cmd: &str| {
        Command::new("sh")
            .arg("-c")
            .arg(format!("command -v {cmd}"))
            .output()
            .is_ok_and(|o| o.status.success())
    };
    ok("openscad") && ok("xvfb-run")
}

/// Renders `model` as OpenSCAD sees it from `camera`.
pub fn render(model: &Path, camera: &Camera, opts: &OpenScadRender) -> Result<Rgb, String> {
    use std::sync::atomic::{AtomicUsize, Ordering};
    static N: AtomicUsize = AtomicUsize::new(0);
    let out = std::env::temp_dir().join(format!(
        "reparamc-openscad-{}-{}.png",
        std::process::id(),
        N.fetch_add(1, Ordering::Relaxed)
    ));
    let mut cmd = Command::new("xvfb-run");
    cmd.arg("-a").arg("openscad");
    if opts.full_render {
        cmd.arg("--render");
    }
    cmd.arg("-D")
        .arg(format!("$fn={}", opts.fn_segments))
        .arg(format!("--colorscheme={}", opts.colorscheme))
        .args(camera.openscad_args())
        .arg("-o")
        .arg(&out)
        .arg(model);
    let output = cmd
        .output()
        .map_err(|e| format!("cannot run xvfb-run openscad: {e}"))?;
    let result = if output.status.success() {
        Rgb::read_png(&out).map_err(|e| format!("openscad wrote no usable PNG: {e}"))
    } else {
        Err(format!(
            "openscad failed on {}: {}",
            model.display(),
            String::from_utf8_lossy(&output.stderr)
        ))
    };
    let _ = std::fs::remove_file(&out);
    result
}
