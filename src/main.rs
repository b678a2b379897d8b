//! The `reparamc` command line: parses flags, calls the library, prints diagnostics.

// The library's lint policy (see `src/lib.rs`): no unwrap, expect or panic outside tests.
#![cfg_attr(
    not(test),
    deny(
        clippy::unwrap_used,
        clippy::expect_used,
        clippy::panic,
        clippy::todo,
        clippy::dbg_macro
    )
)]

mod cli;

fn main() -> std::process::ExitCode {
    cli::run()
}
