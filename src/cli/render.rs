//! `reparamc render`: pictures of a model from named or explicit cameras.
//!
//! Flags in, [`reparamc::command::render`] called, pictures written (a grid, or a folder
//! of views with its `cameras.json`, all written or none), diagnostics out.

use super::{EXIT_IO_ERROR, EXIT_MODEL_ERROR};
use reparamc::command::render::{
    BackendChoice, Cameras, Layout, Options, Pictures, Projection, render,
};
use reparamc::command::{Failure, Message};
use reparamc::front::diag::Diagnostic;
use reparamc::front::source::SourceMap;
use reparamc::output::write_atomic;
use std::path::PathBuf;
use std::process::ExitCode;

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
    /// Draw this module call at the end of the model (for a file that only defines
    /// modules): `--call 'chair()'`, `--call 'chair(seat_h = 45)'`.
    #[arg(long, value_name = "CALL")]
    call: Option<String>,
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

impl From<BackendArgs> for BackendChoice {
    fn from(b: BackendArgs) -> BackendChoice {
        BackendChoice {
            gpu: b.gpu,
            cpu: b.cpu,
        }
    }
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

/// Prints a command's messages in order: diagnostics against `sources`, lines as they are.
pub fn say(sources: &SourceMap, messages: &[Message]) {
    for m in messages {
        match m {
            Message::Diagnostic(d) => super::report(sources, std::slice::from_ref(d)),
            Message::Line(line) => eprintln!("{line}"),
        }
    }
}

/// Prints what stopped a command and returns its exit code.
pub fn failed(sources: &SourceMap, failure: &Failure) -> ExitCode {
    say(sources, &failure.messages);
    ExitCode::from(EXIT_MODEL_ERROR)
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
    let cameras = if let Some(path) = &args.cameras {
        Cameras::File(path.clone())
    } else if !args.camera.is_empty() {
        Cameras::OpenScad {
            specs: args.camera.clone(),
            projection: args.projection.into(),
        }
    } else {
        Cameras::Around(args.views)
    };
    let is_png = args
        .output
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("png"));
    let opts = Options {
        model: args.model.clone(),
        call: args.call.clone(),
        size,
        cameras,
        backend: args.backend.into(),
        layout: if is_png { Layout::Grid } else { Layout::Views },
    };
    if is_png
        && let Err(code) = super::check_outputs(&[&args.output], std::slice::from_ref(&args.model))
    {
        return code;
    }
    let mut sources = SourceMap::new();
    let rendered = match render(&opts, &mut sources) {
        Ok(r) => r,
        Err(f) => return failed(&sources, &f),
    };
    say(&sources, &rendered.messages);
    if is_png && let Err(code) = super::check_outputs(&[&args.output], &super::inputs_of(&sources))
    {
        return code;
    }
    match &rendered.pictures {
        Pictures::Grid { png, views } => {
            if let Err(e) = write_atomic(&args.output, png) {
                eprintln!("error: cannot write `{}`: {e}", args.output.display());
                return ExitCode::from(EXIT_IO_ERROR);
            }
            eprintln!("wrote {} ({views} views)", args.output.display());
            ExitCode::SUCCESS
        }
        Pictures::Views {
            files,
            cameras_json,
        } => write_folder(&args.output, files, cameras_json),
    }
}

/// One picture per view and the cameras into `dir`, all written or none.
fn write_folder(
    dir: &std::path::Path,
    files: &[(String, Vec<u8>)],
    cameras_json: &str,
) -> ExitCode {
    if let Err(e) = std::fs::create_dir_all(dir) {
        eprintln!("error: cannot create `{}`: {e}", dir.display());
        return ExitCode::from(EXIT_IO_ERROR);
    }
    let mut written: Vec<PathBuf> = Vec::new();
    let all = files
        .iter()
        .map(|(name, png)| (dir.join(name), png.as_slice()))
        .chain(std::iter::once((
            dir.join("cameras.json"),
            cameras_json.as_bytes(),
        )));
    for (path, bytes) in all {
        if let Err(e) = write_atomic(&path, bytes) {
            for w in &written {
                let _ = std::fs::remove_file(w);
            }
            eprintln!("error: cannot write `{}`: {e}", path.display());
            return ExitCode::from(EXIT_IO_ERROR);
        }
        written.push(path);
    }
    eprintln!(
        "wrote {} views and cameras.json to {}",
        files.len(),
        dir.display()
    );
    ExitCode::SUCCESS
}
