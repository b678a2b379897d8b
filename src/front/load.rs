//! Reading a model and the files it includes.
//!
//! Owns file I/O: the model is read and parsed, then every `include <...>` / `use <...>` is
//! resolved next to the file that names it, read once and parsed; one that cannot be read
//! is skipped with a warning, as OpenSCAD skips it. The result maps each
//! include's path span to the file it names, so the evaluator never touches the disk.

use super::ast::{Program, StmtKind};
use super::diag::{DResult, Diagnostic};
use super::parse::parse_program;
use super::source::SourceMap;
use super::walk::{Visitor, visit_stmts};
use crate::span::{FileId, Span};
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// A model and everything it includes, parsed.
#[derive(Debug)]
pub struct Loaded {
    pub main: FileId,
    pub programs: HashMap<FileId, Program>,
    /// `include`/`use` path span → the file it names.
    pub includes: HashMap<Span, FileId>,
    /// What reading gave warnings for: an `include`/`use` of a file that cannot be read is
    /// skipped, as OpenSCAD skips it.
    pub warnings: Vec<Diagnostic>,
}

/// Reads and parses `path` and its includes into `sources`.
pub fn load_file(sources: &mut SourceMap, path: &Path) -> DResult<Loaded> {
    let bytes = read_model(path)?;
    load_bytes(sources, path, bytes)
}

fn read_model(path: &Path) -> DResult<Vec<u8>> {
    std::fs::read(path).map_err(|e| {
        Box::new(Diagnostic::error(
            "E0400",
            format!("cannot read `{}`: {}", path.display(), io_reason(&e)),
        ))
    })
}

/// Like [`load_file`], with the module call `call` appended to the model's text (see
/// [`super::call`]).
pub fn load_file_calling(
    sources: &mut SourceMap,
    path: &Path,
    call: Option<&str>,
) -> DResult<Loaded> {
    let Some(call) = call else {
        return load_file(sources, path);
    };
    super::call::check_call(sources, call)?;
    let mut bytes = read_model(path)?;
    bytes.extend_from_slice(super::call::appended(call).as_bytes());
    load_bytes(sources, path, bytes)
}

/// Parses `bytes` as the model at `path` (the path is for messages and includes).
pub fn load_bytes(sources: &mut SourceMap, path: &Path, bytes: Vec<u8>) -> DResult<Loaded> {
    let mut loaded = Loaded {
        main: 0,
        programs: HashMap::new(),
        includes: HashMap::new(),
        warnings: Vec::new(),
    };
    let mut by_path: HashMap<PathBuf, FileId> = HashMap::new();
    loaded.main = add_file(sources, &mut loaded, &mut by_path, path, bytes)?;
    Ok(loaded)
}

fn io_reason(e: &std::io::Error) -> String {
    match e.kind() {
        std::io::ErrorKind::NotFound => "no such file".into(),
        std::io::ErrorKind::PermissionDenied => "permission denied".into(),
        _ => e.to_string(),
    }
}

fn add_file(
    sources: &mut SourceMap,
    loaded: &mut Loaded,
    by_path: &mut HashMap<PathBuf, FileId>,
    path: &Path,
    bytes: Vec<u8>,
) -> DResult<FileId> {
    let (text, bad_utf8) = match String::from_utf8(bytes) {
        Ok(t) => (t, None),
        Err(e) => {
            let at = e.utf8_error().valid_up_to();
            (String::from_utf8_lossy(e.as_bytes()).into_owned(), Some(at))
        }
    };
    let file = sources.add(path, text);
    by_path.insert(canonical(path), file);
    if let Some(at) = bad_utf8 {
        return Err(Box::new(
            Diagnostic::error("E0003", "the file is not valid UTF-8 text")
                .at(Span::new(file, at, at + 1), "this byte is not UTF-8")
                .with_note("OpenSCAD models are text files; save this one as UTF-8"),
        ));
    }
    let program = parse_program(file, sources.text(file))?;
    let wanted = includes_of(&program);
    loaded.programs.insert(file, program);
    let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
    for (path_span, rel) in wanted {
        let target = dir.join(&rel);
        let id = match by_path.get(&canonical(&target)) {
            Some(&id) => id,
            None => {
                let bytes = match std::fs::read(&target) {
                    Ok(bytes) => bytes,
                    Err(e) => {
                        loaded.warnings.push(
                            Diagnostic::warning(
                                "W0401",
                                format!("cannot read included file `{rel}`: it is skipped"),
                            )
                            .at(path_span, io_reason(&e))
                            .with_note(format!("looked for `{}`", target.display()))
                            .with_note(
                                "OpenSCAD 2021.01 warns and goes on without it; so does reparamc",
                            ),
                        );
                        continue;
                    }
                };
                add_file(sources, loaded, by_path, &target, bytes)?
            }
        };
        loaded.includes.insert(path_span, id);
    }
    Ok(file)
}

fn canonical(p: &Path) -> PathBuf {
    p.canonicalize().unwrap_or_else(|_| p.to_path_buf())
}

/// Every include/use in a program (at any depth), with its path span.
fn includes_of(program: &Program) -> Vec<(Span, String)> {
    struct Finder(Vec<(Span, String)>);
    impl<'a> Visitor<'a> for Finder {
        fn enter(&mut self, s: &'a super::ast::Stmt) {
            if let StmtKind::Include {
                path, path_span, ..
            } = &s.kind
            {
                self.0.push((*path_span, path.clone()));
            }
        }
    }
    let mut f = Finder(Vec::new());
    visit_stmts(&program.stmts, &mut f);
    f.0
}
