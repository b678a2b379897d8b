//! The `render` command's entry point: pictures of a model from named or explicit cameras.
//!
//! [`render`] loads the model, makes its cameras (a `cameras.json`, OpenSCAD `--camera`
//! specs, or views around the model), picks a renderer and draws every view; it returns
//! the pictures as PNG bytes (one grid, or one per view with the `cameras.json` that makes
//! the folder a target for `fit`) and what the user should read, in order. It also holds
//! what `fit` shares with it: the choice of renderer ([`Backend`]), the edge softness of
//! pictures for people.
//!
//! Invariant: nothing here prints or writes a file; every line the user is to read is a
//! [`Message`], in the order it arose.

use super::{Failure, Message, as_messages};
use crate::front::source::SourceMap;
use crate::render::camera::{
    Camera, CameraError, CameraSpec, cameras_json, default_views, parse_cameras_json,
};
use crate::render::image::{Rgb, grid, picture};
use crate::render::scene::{DEFAULT_SHADE, Scene};
use crate::render::soft::{SoftImage, prepare_view};
use crate::render::{Backend, CpuBackend};
use std::path::{Path, PathBuf};

pub use crate::render::camera::Projection;

/// Softness of rendered edges: the box filter, exact area coverage of every pixel (the
/// antialiasing a picture for people wants, and what `fit` reads back as coverage).
pub const EDGE_SOFTNESS: f64 = crate::render::scene::BOX_FILTER;

/// Which renderer to use. Neither: the GPU when a hardware adapter is likely, else the
/// CPU.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct BackendChoice {
    /// The wgpu backend, even on a software Vulkan device.
    pub gpu: bool,
    /// The CPU backend.
    pub cpu: bool,
}

/// Where the cameras come from.
#[derive(Debug, Clone, PartialEq)]
pub enum Cameras {
    /// A `cameras.json` file; views without a size get the options' size.
    File(PathBuf),
    /// Cameras in OpenSCAD's `--camera` syntax (`tx,ty,tz,rx,ry,rz,dist` or
    /// `ex,ey,ez,cx,cy,cz`), named `view1`, `view2`, …
    OpenScad {
        specs: Vec<String>,
        projection: Projection,
    },
    /// This many views around the model.
    Around(usize),
}

/// What to draw.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Layout {
    /// One picture with every view in a grid.
    Grid,
    /// One picture per view, and their cameras as a `cameras.json`.
    Views,
}

/// The `render` command's options.
#[derive(Debug, Clone, PartialEq)]
pub struct Options {
    pub model: PathBuf,
    /// A module call to draw at the end of the model (`--call`).
    pub call: Option<String>,
    /// Image size in pixels (width, height).
    pub size: (u32, u32),
    pub cameras: Cameras,
    pub backend: BackendChoice,
    pub layout: Layout,
}

/// The pictures drawn.
#[derive(Debug, Clone, PartialEq)]
pub enum Pictures {
    /// The grid of all views (PNG) and how many views it holds.
    Grid { png: Vec<u8>, views: usize },
    /// Each view as (file name, PNG), and the `cameras.json` text naming those files.
    Views {
        files: Vec<(String, Vec<u8>)>,
        cameras_json: String,
    },
}

/// What `render` produced.
#[derive(Debug, Clone, PartialEq)]
pub struct Rendered {
    /// The model's warnings, the renderer chosen, and whether anything was in view.
    pub messages: Vec<Message>,
    pub pictures: Pictures,
}

/// Renders the model of `opts` from its cameras. Every file read goes into `sources`.
pub fn render(opts: &Options, sources: &mut SourceMap) -> Result<Rendered, Failure> {
    let call = opts.call.as_deref();
    let evaluated =
        crate::front::load_model_calling(sources, &opts.model, call).map_err(Failure::from)?;
    let mut messages = as_messages(evaluated.warnings);
    let model = &evaluated.model;
    let scene = Scene::from_parts(&model.parts, &model.csg);
    let Some((lo, hi)) = scene.bounds() else {
        let text = format!("{}: the model has no parts to render", opts.model.display());
        return Err(Failure::input(messages, "E0704", text));
    };
    let around = |n: usize| default_views(lo, hi, n, opts.size.0, opts.size.1);
    let cameras = match make_cameras(&opts.cameras, opts.size, &around) {
        Ok(c) => c,
        Err((code, text)) => return Err(Failure::input(messages, code, text)),
    };
    let mut backend = choose_backend(opts.backend, &mut messages);
    let rendered = draw(backend.as_mut(), &scene, &cameras);
    if rendered.iter().all(|s| s.m.iter().all(|&m| m < 0.5)) {
        messages.push(Message::Line(
            "warning: no part of the model is in view of any camera".into(),
        ));
    }
    let pictures: Vec<Rgb> = rendered.iter().map(picture).collect();
    let pictures = match opts.layout {
        Layout::Grid => {
            let cols = (pictures.len() as f64).sqrt().ceil() as usize;
            Pictures::Grid {
                png: grid(&pictures, cols.max(1)).encode_png(),
                views: pictures.len(),
            }
        }
        Layout::Views => {
            let mut specs = Vec::new();
            let mut files = Vec::new();
            for (cam, img) in cameras.iter().zip(&pictures) {
                let name = format!("{}.png", cam.name);
                files.push((name.clone(), img.encode_png()));
                specs.push(CameraSpec::of(cam, Some(name)));
            }
            Pictures::Views {
                files,
                cameras_json: cameras_json(&specs),
            }
        }
    };
    Ok(Rendered { messages, pictures })
}

/// The cameras `source` names, at `size` where it does not say; `around(n)` is `n` views
/// around the model. On failure, the diagnostic's code and text.
fn make_cameras(
    source: &Cameras,
    size: (u32, u32),
    around: &dyn Fn(usize) -> Result<Vec<Camera>, CameraError>,
) -> Result<Vec<Camera>, (&'static str, String)> {
    match source {
        Cameras::File(path) => read_cameras(path, size).map_err(|e| ("E0701", e)),
        Cameras::OpenScad { specs, projection } => specs
            .iter()
            .enumerate()
            .map(|(i, text)| {
                let name = format!("view{}", i + 1);
                Camera::parse_openscad(&name, text, *projection, size.0, size.1)
                    .map_err(|e| ("E0703", format!("`--camera {text}`: {e}")))
            })
            .collect(),
        Cameras::Around(0) => Err(("E0703", "`--views 0`: nothing to render".into())),
        Cameras::Around(n) => around(*n).map_err(|e| ("E0703", format!("the default views: {e}"))),
    }
}

fn read_cameras(path: &Path, size: (u32, u32)) -> Result<Vec<Camera>, String> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("{}: cannot read it: {e}", path.display()))?;
    let specs = parse_cameras_json(&text).map_err(|e| format!("{}: {e}", path.display()))?;
    specs
        .iter()
        .map(|s| s.camera(Some(size)))
        .collect::<Result<_, _>>()
        .map_err(|e| format!("{}: {e}", path.display()))
}

/// Picks a renderer and says which (a missing GPU is never an error). Without `gpu`, a
/// software Vulkan device (lavapipe) is not used: the CPU backend is faster than a GPU
/// emulated on the same CPU.
pub(crate) fn choose_backend(
    choice: BackendChoice,
    messages: &mut Vec<Message>,
) -> Box<dyn Backend> {
    #[cfg(feature = "gpu")]
    if choice.gpu || (!choice.cpu && crate::render::gpu::hardware_likely()) {
        match crate::render::gpu::GpuBackend::with_software(choice.gpu) {
            Ok(g) => {
                messages.push(Message::Line(format!("renderer: {}", g.name())));
                return Box::new(g);
            }
            Err(e) => {
                if choice.gpu {
                    messages.push(Message::Line(format!(
                        "note: no GPU backend ({e}); using the CPU"
                    )));
                }
            }
        }
    }
    #[cfg(not(feature = "gpu"))]
    if choice.gpu {
        messages.push(Message::Line(
            "note: this build has no GPU backend; using the CPU".into(),
        ));
    }
    let c = CpuBackend::new();
    messages.push(Message::Line(format!("renderer: {}", c.name())));
    Box::new(c)
}

/// Pictures of `scene` from `cameras` as a person sees them: soft edges of
/// [`EDGE_SOFTNESS`], the default shading.
pub(crate) fn draw(backend: &mut dyn Backend, scene: &Scene, cameras: &[Camera]) -> Vec<SoftImage> {
    let views: Vec<_> = cameras
        .iter()
        .map(|c| prepare_view(scene, c, Some(EDGE_SOFTNESS)))
        .collect();
    let shades = vec![DEFAULT_SHADE; views.len()];
    backend
        .render(scene, &views, Some(EDGE_SOFTNESS), &shades)
        .into_iter()
        .map(|(s, _)| s)
        .collect()
}
