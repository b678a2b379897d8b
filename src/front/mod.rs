//! The front end: OpenSCAD text in, evaluated geometry out.
//!
//! `source` owns files and spans, `diag` the diagnostics, `parse` turns text into the
//! `ast` with the pest grammar in `grammar/openscad.pest`, `load` reads a model and its
//! includes, `naming` finds the names comments and variables give, and `eval` runs the
//! program into an IR [`Model`](crate::ir::Model) whose features are affine forms.
//! `parse::tokens` is the one token stream beside the grammar (variant files are matched
//! on it), and the loaders below ([`load_model`] and its kin) are what every command uses
//! to read a model, on a thread with a stack deep enough for the call-depth limit.

pub mod ast;
pub mod call;
pub mod diag;
pub mod eval;
pub mod load;
pub mod naming;
pub mod parse;
pub mod source;
pub mod walk;

use diag::DResult;
use eval::Evaluated;
use source::SourceMap;
use std::path::Path;

/// Stack for evaluation: deeply nested models and recursion up to the call-depth limit
/// need more than a default thread stack.
const EVAL_STACK_BYTES: usize = 1 << 30;

/// Runs `f` on a thread with a large stack and returns its result. Where the system will
/// not give a thread that much, smaller stacks are tried, and at last the current thread.
pub fn with_large_stack<T: Send>(f: impl FnOnce() -> T + Send) -> T {
    let mut f = Some(f);
    for size in [
        EVAL_STACK_BYTES,
        EVAL_STACK_BYTES / 8,
        EVAL_STACK_BYTES / 64,
    ] {
        let outcome = std::thread::scope(|s| {
            let g = &mut f;
            let spawned = std::thread::Builder::new()
                .name("reparamc-eval".into())
                .stack_size(size)
                .spawn_scoped(s, move || g.take().map(|f| f()));
            spawned.ok().map(|h| match h.join() {
                Ok(v) => v,
                Err(panic) => std::panic::resume_unwind(panic),
            })
        });
        if let Some(Some(v)) = outcome {
            return v;
        }
    }
    match f.take() {
        Some(f) => f(),
        None => unreachable!("the closure runs at most once"),
    }
}

/// Reads, parses and evaluates the model at `path` (and what it includes).
pub fn load_model(sources: &mut SourceMap, path: &Path) -> DResult<Evaluated> {
    with_large_stack(|| {
        let loaded = load::load_file(sources, path)?;
        eval::evaluate(sources, &loaded)
    })
}

/// Like [`load_model`], drawing `call` (a module call, see [`call`]) at the file's end.
pub fn load_model_calling(
    sources: &mut SourceMap,
    path: &Path,
    call: Option<&str>,
) -> DResult<Evaluated> {
    with_large_stack(|| {
        let loaded = load::load_file_calling(sources, path, call)?;
        eval::evaluate(sources, &loaded)
    })
}

/// Like [`load_model`], also returning what was parsed (for matching variant files).
pub fn load_model_parsed(
    sources: &mut SourceMap,
    path: &Path,
) -> DResult<(load::Loaded, Evaluated)> {
    with_large_stack(|| {
        let loaded = load::load_file(sources, path)?;
        let evaluated = eval::evaluate(sources, &loaded)?;
        Ok((loaded, evaluated))
    })
}

/// Parses and evaluates model text as if it were the file `path`.
pub fn load_model_text(sources: &mut SourceMap, path: &Path, text: &[u8]) -> DResult<Evaluated> {
    with_large_stack(|| {
        let loaded = load::load_bytes(sources, path, text.to_vec())?;
        eval::evaluate(sources, &loaded)
    })
}

/// The model of `text` for unit tests; a diagnostic fails the test with its message.
#[cfg(test)]
pub(crate) fn test_model(text: &str) -> crate::ir::Model {
    let mut sources = SourceMap::new();
    match load_model_text(&mut sources, Path::new("t.scad"), text.as_bytes()) {
        Ok(e) => e.model,
        Err(d) => panic!("{}", d.message),
    }
}
