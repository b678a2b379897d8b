//! `--call`: re-parameterizing the geometry of one module call, and the help a file that
//! only defines modules gets.
//!
//! A library file (`module chair(seat_h = 45) {…}` and nothing else) draws nothing.
//! `--call 'chair(seat_h = 50)'` names what to draw: the call text is parsed alone first (it
//! must be one module instantiation; its syntax errors point into it, shown as the file
//! `--call`), then appended to the model's text as its last statement. The model, its
//! variant files (the same call is appended to each) and the emitted output therefore all
//! read as the file with that call at its end, and the call's own numbers are parameters
//! like any other.

use super::ast::{InstanceKind, Param, Program, StmtKind};
use super::diag::{DResult, Diagnostic};
use super::load::Loaded;
use super::parse::parse_program;
use super::source::SourceMap;
use super::walk::{Visitor, visit_stmts};
use crate::span::Span;
use std::collections::HashSet;

/// The name diagnostics give the `--call` text.
const CALL_FILE: &str = "--call";

/// The statement a call text becomes: trimmed, with one `;`.
fn statement(call: &str) -> String {
    let trimmed = call.trim();
    let trimmed = trimmed.strip_suffix(';').unwrap_or(trimmed).trim_end();
    format!("{trimmed};")
}

/// What is appended to a model's text (and each variant's) for `call`.
pub fn appended(call: &str) -> String {
    format!("\n{}\n", statement(call))
}

/// Checks that `call` is one module instantiation; its diagnostic points into the call
/// text, which is then added to `sources` as the file `--call`.
pub fn check_call(sources: &mut SourceMap, call: &str) -> DResult<()> {
    let text = statement(call);
    let file = sources.len();
    let fail = |sources: &mut SourceMap, d: Box<Diagnostic>| {
        sources.add(CALL_FILE, text.clone());
        Err(d)
    };
    let program = match parse_program(file, &text) {
        Ok(p) => p,
        Err(d) => return fail(sources, d),
    };
    let one_call = matches!(
        program.stmts.as_slice(),
        [s] if matches!(&s.kind, StmtKind::Instance(i) if matches!(i.kind, InstanceKind::Call { .. }))
    );
    if one_call {
        return Ok(());
    }
    let d = Diagnostic::error("E0403", "`--call` must be one module call")
        .at(Span::new(file, 0, text.len()), "this is not a single call")
        .with_note("for example `--call 'chair()'` or `--call 'chair(seat_h = 45)'`");
    fail(sources, Box::new(d))
}

/// For a file that defines modules: the modules with their parameters and how to pick one.
pub fn module_only_help(sources: &SourceMap, loaded: &Loaded) -> Option<String> {
    let program: &Program = loaded.programs.get(&loaded.main)?;
    let modules: Vec<String> = program
        .stmts
        .iter()
        .filter_map(|s| match &s.kind {
            StmtKind::ModuleDef { name, params, .. } => {
                Some(format!("{}({})", name.name, parameters(sources, params)))
            }
            _ => None,
        })
        .collect();
    // The module to suggest: the first one no module calls (a helper like `leg` is
    // called by `chair`), else the first.
    let called = called_modules(program);
    let defined: Vec<&str> = program
        .stmts
        .iter()
        .filter_map(|s| match &s.kind {
            StmtKind::ModuleDef { name, .. } => Some(name.name.as_str()),
            _ => None,
        })
        .collect();
    let first = defined
        .iter()
        .find(|n| !called.contains(**n))
        .or(defined.first())?;
    Some(format!(
        "this file defines modules but calls none of them:\n{}\nhelp: pick the one to re-parameterize with `--call '{first}()'`; any call works, like `--call '{first}(…)'` with arguments",
        modules
            .iter()
            .map(|m| format!("    module {m}"))
            .collect::<Vec<_>>()
            .join("\n")
    ))
}

/// The names of every module instantiated anywhere in `program`.
fn called_modules(program: &Program) -> HashSet<String> {
    struct Calls(HashSet<String>);
    impl<'a> Visitor<'a> for Calls {
        fn enter(&mut self, s: &'a super::ast::Stmt) {
            if let StmtKind::Instance(i) = &s.kind
                && let InstanceKind::Call { name, .. } = &i.kind
            {
                self.0.insert(name.name.clone());
            }
        }
    }
    let mut calls = Calls(HashSet::new());
    visit_stmts(&program.stmts, &mut calls);
    calls.0
}

/// A module's parameters as written: `w, h = 10`.
fn parameters(sources: &SourceMap, params: &[Param]) -> String {
    params
        .iter()
        .map(|p| match &p.default {
            Some(d) => format!("{} = {}", p.name.name, sources.snippet(d.span)),
            None => p.name.name.clone(),
        })
        .collect::<Vec<_>>()
        .join(", ")
}
