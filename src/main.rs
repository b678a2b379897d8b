//! The `reparamc` command line: parses flags, calls the library, prints diagnostics.

use clap::{Parser, Subcommand};
use codespan_reporting::term::termcolor::{ColorChoice, StandardStream};
use reparamc::front::diag::Diagnostic;
use reparamc::front::source::SourceMap;
use std::io::{IsTerminal, Write};
use std::path::PathBuf;
use std::process::ExitCode;

/// Exit code for a model that could not be compiled (a diagnostic was printed).
const EXIT_MODEL_ERROR: u8 = 1;
/// Exit code for a failure to write output.
const EXIT_IO_ERROR: u8 = 3;

#[derive(Parser)]
#[command(
    name = "reparamc",
    version,
    about = "Re-parameterize OpenSCAD models: find the relations a design relies on and expose a few meaningful sliders."
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Show a model's parameters, parts and the geometric relations that hold on it.
    Inspect {
        /// The OpenSCAD model to read.
        model: PathBuf,
        /// Print JSON instead of tables.
        #[arg(long)]
        json: bool,
    },
}

fn stderr() -> StandardStream {
    let choice = if std::io::stderr().is_terminal() {
        ColorChoice::Auto
    } else {
        ColorChoice::Never
    };
    StandardStream::stderr(choice)
}

fn report(sources: &SourceMap, diags: &[Diagnostic]) {
    let mut err = stderr();
    for d in diags {
        d.emit(sources, &mut err);
    }
}

fn inspect(model: PathBuf, json: bool) -> ExitCode {
    let mut sources = SourceMap::new();
    let evaluated = match reparamc::load_model(&mut sources, &model) {
        Ok(e) => e,
        Err(d) => {
            report(&sources, &[*d]);
            return ExitCode::from(EXIT_MODEL_ERROR);
        }
    };
    report(&sources, &evaluated.warnings);
    let candidates = reparamc::analysis::find_candidates(&evaluated.model);
    let inspection = reparamc::back::inspect::inspect(&sources, &evaluated.model, &candidates);
    let text = if json {
        match serde_json::to_string_pretty(&inspection) {
            Ok(s) => s + "\n",
            Err(e) => {
                eprintln!("error: cannot write JSON: {e}");
                return ExitCode::from(EXIT_IO_ERROR);
            }
        }
    } else {
        inspection.to_text()
    };
    let mut out = std::io::stdout().lock();
    if let Err(e) = out.write_all(text.as_bytes()).and_then(|_| out.flush()) {
        if e.kind() == std::io::ErrorKind::BrokenPipe {
            return ExitCode::SUCCESS;
        }
        eprintln!("error: cannot write output: {e}");
        return ExitCode::from(EXIT_IO_ERROR);
    }
    ExitCode::SUCCESS
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        Command::Inspect { model, json } => inspect(model, json),
    }
}
