//! The command line: flags in, library calls, diagnostics and files out.
//!
//! One module per subcommand; this one holds the flag definitions, the shared output
//! helpers and the exit codes. Nothing here computes results: it calls the library.

mod compile;
mod explore;
mod fit;
mod inspect;
mod render;

use clap::{Parser, Subcommand};
use codespan_reporting::term::termcolor::{ColorChoice, StandardStream};
use reparamc::front::diag::Diagnostic;
use reparamc::front::source::SourceMap;
use std::io::{IsTerminal, Write};
use std::process::ExitCode;

/// Exit code for a model that could not be compiled (a diagnostic was printed).
pub const EXIT_MODEL_ERROR: u8 = 1;
/// Exit code for a failure to write output.
pub const EXIT_IO_ERROR: u8 = 3;
/// Exit code for a server (language model, img2img) that failed or answered wrongly.
pub const EXIT_SERVER_ERROR: u8 = 4;

/// What an interrupt leaves, when a command writes as it goes (`explore`); by default
/// nothing, as every other command writes its files at the end.
pub static INTERRUPTED: std::sync::OnceLock<&'static str> = std::sync::OnceLock::new();

#[derive(Parser)]
#[command(
    name = "reparamc",
    version,
    about = "Re-parameterize OpenSCAD models: find the relations a design relies on and expose a few meaningful sliders."
)]
#[command(args_conflicts_with_subcommands = true)]
pub struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    /// The main job (when no subcommand is given).
    #[command(flatten)]
    main: compile::Args,
}

#[derive(Subcommand)]
enum Command {
    /// Show a model's parameters, parts and the geometric relations that hold on it.
    Inspect(inspect::Args),
    /// Render a model from named or explicit cameras (OpenSCAD's `--camera` conventions).
    Render(render::Args),
    /// Fit a model's numbers to pictures of what it should become.
    Fit(fit::Args),
    /// The zero-shot loop: a language model proposes kinds of the object, img2img servers
    /// guide a fit towards each, and the main job runs on the variations found.
    Explore(explore::Args),
}

/// Runs the command line and returns the process exit code.
pub fn run() -> ExitCode {
    let cli = Cli::parse();
    // Ctrl-C: whatever is half-written goes, and nothing else was touched (every output is
    // written whole at the end, inputs never).
    let _ = ctrlc::set_handler(|| {
        reparamc::output::remove_unfinished();
        let note = INTERRUPTED.get().copied().unwrap_or("no output written");
        eprintln!("interrupted: {note}");
        std::process::exit(130);
    });
    match cli.command {
        Some(Command::Inspect(args)) => inspect::run(args),
        Some(Command::Render(args)) => render::run(args),
        Some(Command::Fit(args)) => fit::run(args),
        Some(Command::Explore(args)) => explore::run(args),
        None => compile::run(cli.main),
    }
}

fn stderr() -> StandardStream {
    let choice = if std::io::stderr().is_terminal() {
        ColorChoice::Auto
    } else {
        ColorChoice::Never
    };
    StandardStream::stderr(choice)
}

/// Prints diagnostics rustc-style on standard error.
pub fn report(sources: &SourceMap, diags: &[Diagnostic]) {
    let mut err = stderr();
    for d in diags {
        d.emit(sources, &mut err);
    }
}

/// Checks, before a job runs, that every output can be written and names no input; on
/// failure the message is printed and the exit code returned.
pub fn check_outputs(
    outputs: &[&std::path::Path],
    inputs: &[std::path::PathBuf],
) -> Result<(), ExitCode> {
    for out in outputs {
        if let Err(text) = reparamc::output::check_output(out, inputs) {
            eprintln!("error: {text}");
            return Err(ExitCode::from(EXIT_IO_ERROR));
        }
    }
    Ok(())
}

/// Every file `sources` read (the model, its includes, its variations).
pub fn inputs_of(sources: &SourceMap) -> Vec<std::path::PathBuf> {
    (0..sources.len())
        .map(|f| sources.path(f).to_path_buf())
        .collect()
}

/// Writes `text` to standard output; a closed pipe (`| head`) is not an error.
pub fn print_stdout(text: &str) -> ExitCode {
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|_| out.flush()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: cannot write output: {e}");
            ExitCode::from(EXIT_IO_ERROR)
        }
    }
}

/// An entry point's result; on its error, the diagnostic printed and the model-error exit
/// code to return.
pub fn or_report<T>(
    sources: &SourceMap,
    result: Result<T, Box<Diagnostic>>,
) -> Result<T, ExitCode> {
    result.map_err(|d| {
        report(sources, &[*d]);
        ExitCode::from(EXIT_MODEL_ERROR)
    })
}
