//! `reparamc inspect`: parameters, parts and relations of a model.
//!
//! Flags in → [`InspectOptions`] → the library's `inspect` → tables or JSON on standard
//! output, diagnostics on standard error.

use super::{EXIT_IO_ERROR, or_report, print_stdout, report};
use reparamc::command::inspect::{InspectOptions, inspect};
use reparamc::front::source::SourceMap;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(clap::Args)]
pub struct Args {
    /// The OpenSCAD model to read.
    model: PathBuf,
    /// Print JSON instead of tables.
    #[arg(long)]
    json: bool,
    /// Draw this module call at the end of the model (for a file that only defines
    /// modules): `--call 'chair()'`, `--call 'chair(seat_h = 45)'`.
    #[arg(long, value_name = "CALL")]
    call: Option<String>,
}

pub fn run(args: Args) -> ExitCode {
    let mut sources = SourceMap::new();
    let options = InspectOptions {
        model: args.model,
        call: args.call,
    };
    let result = inspect(&options, &mut sources);
    let found = match or_report(&sources, result) {
        Ok(found) => found,
        Err(code) => return code,
    };
    report(&sources, &found.warnings);
    if !args.json {
        return print_stdout(&found.inspection.to_text());
    }
    match found.inspection.to_json() {
        Ok(s) => print_stdout(&s),
        Err(e) => {
            eprintln!("error: cannot write JSON: {e}");
            ExitCode::from(EXIT_IO_ERROR)
        }
    }
}
