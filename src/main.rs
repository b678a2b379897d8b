//! The `reparamc` command line: parses flags, calls the library, prints diagnostics.

mod cli;

fn main() -> std::process::ExitCode {
    cli::run()
}
