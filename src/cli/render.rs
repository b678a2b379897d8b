//! `reparamc render`: pictures of a model from named or explicit cameras.

use super::{EXIT_IO_ERROR, EXIT_MODEL_ERROR, load};
use reparamc::front::diag::Diagnostic;
use reparamc::front::source::SourceMap;
use reparamc::output::write_atomic;
use reparamc::render::camera::{
    Camera, CameraSpec, Projection, cameras_json, default_views, parse_cameras_json,
};
use reparamc::render::image::{grid, picture};
use reparamc::render::scene::{DEFAULT_SHADE, Scene};
use reparamc::render::soft::prepare_view;
use reparamc::render::{Backend, CpuBackend};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Softness of rendered edges (pixels): a little anti-aliasing.
pub const EDGE_SOFTNESS: f64 = 0.4;

#[derive(clap::Args)]
pub struct Args {
    /// The OpenSCAD model to render.
    model: PathBuf,
    /// Where to write: a `.png` file gets a grid of all views; any other path is a folder
    /// that gets one PNG per view and a `cameras.json` (a target folder for `fit`).
    #[arg(short, long)]
    output: PathBuf,
    /// Number of views around the model (when no --camera or --cameras is given).
    #[arg(long, default_value_t = 5)]
    views: usize,
    /// Image size in pixels (square), or WIDTHxHEIGHT.
    #[arg(long, default_value = "256")]
    size: String,
    /// A camera in OpenSCAD's `--camera` syntax: `tx,ty,tz,rx,ry,rz,dist` or
    /// `ex,ey,ez,cx,cy,cz`. Repeat for several views.
    #[arg(long, allow_hyphen_values = true)]
    camera: Vec<String>,
    /// Projection of --camera views.
    #[arg(long, value_enum, default_value_t = ProjectionArg::Perspective)]
    projection: ProjectionArg,
    /// Cameras from a `cameras.json` file.
    #[arg(long, conflicts_with = "camera")]
    cameras: Option<PathBuf>,
    #[command(flatten)]
    backend: BackendArgs,
}

#[derive(Clone, Copy, clap::ValueEnum)]
pub enum ProjectionArg {
    #[value(alias = "p")]
    Perspective,
    #[value(alias = "o", alias = "ortho")]
    Orthographic,
}

impl From<ProjectionArg> for Projection {
    fn from(p: ProjectionArg) -> Projection {
        match p {
            ProjectionArg::Perspective => Projection::Perspective,
            ProjectionArg::Orthographic => Projection::Orthographic,
        }
    }
}

/// Which renderer to use.
#[derive(clap::Args, Clone, Copy)]
pub struct BackendArgs {
    /// Use the wgpu backend, even on a software Vulkan device (by default it is used when a
    /// hardware GPU adapter is found).
    #[arg(long, conflicts_with = "cpu")]
    pub gpu: bool,
    /// Use the CPU backend.
    #[arg(long)]
    pub cpu: bool,
}

/// Picks a backend and says which on standard error. A missing GPU is never an error.
/// Without `--gpu`, a software Vulkan device (lavapipe) is not used: the CPU backend is
/// faster than a GPU emulated on the same CPU.
pub fn choose_backend(args: BackendArgs) -> Box<dyn Backend> {
    #[cfg(feature = "gpu")]
    if args.gpu || (!args.cpu && reparamc::render::gpu::hardware_likely()) {
        match reparamc::render::gpu::GpuBackend::with_software(args.gpu) {
            Ok(g) => {
                eprintln!("renderer: {}", g.name());
                return Box::new(g);
            }
            Err(e) => {
                if args.gpu {
                    eprintln!("note: no GPU backend ({e}); using the CPU");
                }
            }
        }
    }
    #[cfg(not(feature = "gpu"))]
    if args.gpu {
        eprintln!("note: this build has no GPU backend; using the CPU");
    }
    let c = CpuBackend;
    eprintln!("renderer: {}", c.name());
    Box::new(c)
}

/// Reports a problem with a non-model input (no source span) and returns the exit code.
pub fn input_error(code: &'static str, message: String) -> ExitCode {
    super::report(&SourceMap::new(), &[Diagnostic::error(code, message)]);
    ExitCode::from(EXIT_MODEL_ERROR)
}

pub fn parse_size(text: &str) -> Option<(u32, u32)> {
    let ok = |v: u32| (1..=16384).contains(&v).then_some(v);
    match text.split_once(['x', 'X']) {
        Some((w, h)) => Some((ok(w.trim().parse().ok()?)?, ok(h.trim().parse().ok()?)?)),
        None => {
            let s = ok(text.trim().parse().ok()?)?;
            Some((s, s))
        }
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

pub fn run(args: Args) -> ExitCode {
    let Some(size) = parse_size(&args.size) else {
        return input_error(
            "E0703",
            format!(
                "`--size {}` is not a size (give N or WIDTHxHEIGHT, at most 16384)",
                args.size
            ),
        );
    };
    let Some((_, evaluated)) = load(&args.model) else {
        return ExitCode::from(EXIT_MODEL_ERROR);
    };
    let model = &evaluated.model;
    let scene = Scene::from_parts(&model.parts, &model.csg);
    let Some((lo, hi)) = scene.bounds() else {
        return input_error(
            "E0704",
            format!("{}: the model has no parts to render", args.model.display()),
        );
    };
    let cameras: Vec<Camera> = if let Some(path) = &args.cameras {
        match read_cameras(path, size) {
            Ok(c) => c,
            Err(e) => return input_error("E0701", e),
        }
    } else if !args.camera.is_empty() {
        let mut v = Vec::new();
        for (i, text) in args.camera.iter().enumerate() {
            match Camera::parse_openscad(
                &format!("view{}", i + 1),
                text,
                args.projection.into(),
                size.0,
                size.1,
            ) {
                Ok(c) => v.push(c),
                Err(e) => return input_error("E0703", format!("`--camera {text}`: {e}")),
            }
        }
        v
    } else {
        if args.views == 0 {
            return input_error("E0703", "`--views 0`: nothing to render".into());
        }
        match default_views(lo, hi, args.views, size.0, size.1) {
            Ok(v) => v,
            Err(e) => return input_error("E0703", format!("the default views: {e}")),
        }
    };
    let mut backend = choose_backend(args.backend);
    let views: Vec<_> = cameras
        .iter()
        .map(|c| prepare_view(&scene, c, Some(EDGE_SOFTNESS)))
        .collect();
    let shades = vec![DEFAULT_SHADE; views.len()];
    let rendered = backend.render(&scene, &views, Some(EDGE_SOFTNESS), &shades);
    let pictures: Vec<_> = rendered.iter().map(|(s, _)| picture(s)).collect();
    if pictures
        .iter()
        .zip(&rendered)
        .all(|(_, (s, _))| s.m.iter().all(|&m| m < 0.5))
    {
        eprintln!("warning: no part of the model is in view of any camera");
    }
    let is_png = args
        .output
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("png"));
    if is_png {
        let cols = (pictures.len() as f64).sqrt().ceil() as usize;
        let img = grid(&pictures, cols.max(1));
        if let Err(e) = write_atomic(&args.output, &img.encode_png()) {
            eprintln!("error: cannot write `{}`: {e}", args.output.display());
            return ExitCode::from(EXIT_IO_ERROR);
        }
        eprintln!("wrote {} ({} views)", args.output.display(), pictures.len());
        return ExitCode::SUCCESS;
    }
    // A folder: one picture per view and the cameras, all written or none.
    if let Err(e) = std::fs::create_dir_all(&args.output) {
        eprintln!("error: cannot create `{}`: {e}", args.output.display());
        return ExitCode::from(EXIT_IO_ERROR);
    }
    let mut specs = Vec::new();
    let mut written: Vec<PathBuf> = Vec::new();
    for (cam, img) in cameras.iter().zip(&pictures) {
        let name = format!("{}.png", cam.name);
        let path = args.output.join(&name);
        if let Err(e) = write_atomic(&path, &img.encode_png()) {
            for w in &written {
                let _ = std::fs::remove_file(w);
            }
            eprintln!("error: cannot write `{}`: {e}", path.display());
            return ExitCode::from(EXIT_IO_ERROR);
        }
        written.push(path);
        specs.push(CameraSpec::of(cam, Some(name)));
    }
    let json = args.output.join("cameras.json");
    if let Err(e) = write_atomic(&json, cameras_json(&specs).as_bytes()) {
        for w in &written {
            let _ = std::fs::remove_file(w);
        }
        eprintln!("error: cannot write `{}`: {e}", json.display());
        return ExitCode::from(EXIT_IO_ERROR);
    }
    eprintln!(
        "wrote {} views and cameras.json to {}",
        pictures.len(),
        args.output.display()
    );
    ExitCode::SUCCESS
}
