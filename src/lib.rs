//! `reparamc`: re-parameterize OpenSCAD models.
//!
//! The pipeline, stage by stage (see DESIGN.md): `front` parses and evaluates a model into
//! the `ir` (slots, parts, affine features); `analysis` finds the geometric relations that
//! hold on it; `back` presents and writes the results. Every stage is usable as a library;
//! `main.rs` is only the command line.

/// Evaluation and analysis allocate many small vectors (affine forms, features); mimalloc
/// handles them much faster than the system allocator.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

pub mod analysis;
pub mod back;
pub mod compile;
pub mod fit;
pub mod front;
pub mod geom;
pub mod ir;
pub mod render;
pub mod variation;

use front::diag::DResult;
use front::eval::Evaluated;
use front::source::SourceMap;
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
        let loaded = front::load::load_file(sources, path)?;
        front::eval::evaluate(sources, &loaded)
    })
}

/// Like [`load_model`], also returning what was parsed (for matching variant files).
pub fn load_model_parsed(
    sources: &mut SourceMap,
    path: &Path,
) -> DResult<(front::load::Loaded, Evaluated)> {
    with_large_stack(|| {
        let loaded = front::load::load_file(sources, path)?;
        let evaluated = front::eval::evaluate(sources, &loaded)?;
        Ok((loaded, evaluated))
    })
}

/// Parses and evaluates model text as if it were the file `path`.
pub fn load_model_text(sources: &mut SourceMap, path: &Path, text: &[u8]) -> DResult<Evaluated> {
    with_large_stack(|| {
        let loaded = front::load::load_bytes(sources, path, text.to_vec())?;
        front::eval::evaluate(sources, &loaded)
    })
}
