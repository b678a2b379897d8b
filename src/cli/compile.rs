//! The main command: `reparamc model.scad -o model_param.scad --vary a.scad …`.
//!
//! Loads the model and its variant files, runs the library's main job, and writes the
//! outputs atomically (a temporary file renamed into place), never over the input.

use super::{EXIT_IO_ERROR, EXIT_MODEL_ERROR, report};
use reparamc::compile::{Options, reparameterize};
use reparamc::front::source::SourceMap;
use reparamc::output::{same_file, write_atomic};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

#[derive(clap::Args, Debug, Default)]
pub struct Args {
    /// The OpenSCAD model to re-parameterize.
    pub model: Option<PathBuf>,
    /// Where to write the re-parameterized model (`-` for standard output); the parameter
    /// sets go beside it as `<name>.json`. Default: `<model>_param.scad` beside the model.
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// A variation of the model: the same program with other numbers (repeatable).
    #[arg(long = "vary", value_name = "FILE")]
    pub vary: Vec<PathBuf>,
    /// Write a machine-readable report (JSON) here.
    #[arg(long, value_name = "FILE")]
    pub report: Option<PathBuf>,
    /// Draw the distortion curve with the cutoff marked (PNG).
    #[arg(long, value_name = "FILE")]
    pub plot: Option<PathBuf>,
    /// Without variations, keep every relation that holds (the paper's symbolic baseline)
    /// instead of the structural prior.
    #[arg(long)]
    pub all_constraints: bool,
}

fn io_error(what: &Path, e: std::io::Error) -> ExitCode {
    eprintln!("error: cannot write `{}`: {e}", what.display());
    ExitCode::from(EXIT_IO_ERROR)
}

pub fn run(args: Args) -> ExitCode {
    let Some(model_path) = args.model.clone() else {
        eprintln!(
            "error: no model given\n\nUsage: reparamc <MODEL> -o <OUTPUT> [--vary <FILE>]...\n       reparamc inspect <MODEL>\n\nFor more information, try '--help'."
        );
        return ExitCode::from(2);
    };
    let output = args.output.clone().unwrap_or_else(|| {
        let stem = model_path
            .file_stem()
            .map_or("model".into(), |s| s.to_string_lossy().into_owned());
        model_path.with_file_name(format!("{stem}_param.scad"))
    });
    let to_stdout = output.as_os_str() == "-";
    if !to_stdout && same_file(&output, &model_path) {
        eprintln!(
            "error: the output `{}` is the input model; choose another file with -o",
            output.display()
        );
        return ExitCode::from(2);
    }
    let mut sources = SourceMap::new();
    let result =
        reparamc::with_large_stack(|| -> Result<_, Box<reparamc::front::diag::Diagnostic>> {
            let loaded = reparamc::front::load::load_file(&mut sources, &model_path)?;
            let evaluated = reparamc::front::eval::evaluate(&sources, &loaded)?;
            let mut variations = Vec::new();
            for v in &args.vary {
                variations.push(reparamc::variation::load_variation(
                    &mut sources,
                    loaded.main,
                    &evaluated.model,
                    v,
                )?);
            }
            let options = Options {
                all_constraints: args.all_constraints,
                presets_name: (!to_stdout)
                    .then(|| {
                        output
                            .with_extension("json")
                            .file_name()
                            .map(|n| n.to_string_lossy().into_owned())
                    })
                    .flatten(),
            };
            let compiled =
                reparameterize(&sources, &loaded, &evaluated.model, &variations, &options);
            Ok((evaluated.warnings, compiled))
        });
    let (warnings, compiled) = match result {
        Ok(r) => r,
        Err(d) => {
            report(&sources, &[*d]);
            return ExitCode::from(EXIT_MODEL_ERROR);
        }
    };
    report(&sources, &warnings);
    if to_stdout {
        if super::print_stdout(&compiled.scad) != ExitCode::SUCCESS {
            return ExitCode::from(EXIT_IO_ERROR);
        }
    } else {
        if let Err(e) = write_atomic(&output, compiled.scad.as_bytes()) {
            return io_error(&output, e);
        }
        if let Some(p) = &compiled.presets {
            let json = output.with_extension("json");
            if let Err(e) = write_atomic(&json, p.as_bytes()) {
                return io_error(&json, e);
            }
        }
    }
    if let Some(r) = &args.report {
        let text = serde_json::to_string_pretty(&compiled.report).unwrap_or_default() + "\n";
        if let Err(e) = write_atomic(r, text.as_bytes()) {
            return io_error(r, e);
        }
    }
    if let Some(p) = &args.plot {
        let keep = compiled
            .report
            .cutoff
            .as_ref()
            .map_or(compiled.report.kept_count, |c| c.keep);
        let png = reparamc::back::plot::distortion_png(&compiled.report.distortion_curve, keep);
        if let Err(e) = write_atomic(p, &png) {
            return io_error(p, e);
        }
    }
    let r = &compiled.report;
    eprintln!(
        "{}: {} sliders drive {} numbers, keeping {} of {} relations ({}){}",
        if to_stdout {
            "stdout".to_string()
        } else {
            output.display().to_string()
        },
        r.dimension,
        r.parameter_count,
        r.kept_count,
        r.base_constraint_count,
        r.method,
        if r.toggles.is_empty() {
            String::new()
        } else {
            format!(", {} part switches", r.toggles.len())
        }
    );
    ExitCode::SUCCESS
}
