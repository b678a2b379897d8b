//! `reparamc inspect`: parameters, parts and relations of a model.

use super::{EXIT_IO_ERROR, EXIT_MODEL_ERROR, load, print_stdout};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(clap::Args)]
pub struct Args {
    /// The OpenSCAD model to read.
    model: PathBuf,
    /// Print JSON instead of tables.
    #[arg(long)]
    json: bool,
}

pub fn run(args: Args) -> ExitCode {
    let Some((sources, evaluated)) = load(&args.model) else {
        return ExitCode::from(EXIT_MODEL_ERROR);
    };
    let candidates = reparamc::analysis::find_candidates(&evaluated.model);
    let inspection = reparamc::back::inspect::inspect(&sources, &evaluated.model, &candidates);
    if !args.json {
        return print_stdout(&inspection.to_text());
    }
    match serde_json::to_string_pretty(&inspection) {
        Ok(s) => print_stdout(&(s + "\n")),
        Err(e) => {
            eprintln!("error: cannot write JSON: {e}");
            ExitCode::from(EXIT_IO_ERROR)
        }
    }
}
