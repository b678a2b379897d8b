//! OpenSCAD's leniency, as 2021.01 has it: what it accepts with a warning, reparamc
//! accepts with a located warning and reads as OpenSCAD reads it (the same parts as its
//! `.csg` export); what it rejects stays an error.
//!
//! The inputs are `tests/lenient/` (one kind of leniency each: extra arguments, an unknown
//! named argument, a missing include, unknown variables, functions and modules, arguments
//! OpenSCAD cannot convert) and every bad input of `tests/bad/`, judged by what the real
//! `openscad` does with them.

mod common;

use common::*;
use reparamc::front::diag::Severity;
use reparamc::front::source::SourceMap;
use std::path::{Path, PathBuf};

/// What `openscad -o x.csg` did: its exit status, its `WARNING:` and `ERROR:` lines, and the
/// export when it wrote one.
struct Run {
    warned: bool,
    failed: bool,
    csg: Option<String>,
}

fn openscad(model: &Path) -> Run {
    let (run, csg) = openscad_export(model, "csg");
    let stderr = String::from_utf8_lossy(&run.stderr);
    Run {
        warned: stderr.lines().any(|l| l.starts_with("WARNING:")),
        failed: !run.status.success() || stderr.lines().any(|l| l.starts_with("ERROR:")),
        csg,
    }
}

/// `dir/x.scad` relative to the crate root, so rendered paths are the same everywhere.
fn relative(dir: &str) -> Vec<PathBuf> {
    scad_files(dir)
        .into_iter()
        .filter_map(|p| p.file_name().map(|n| Path::new(dir).join(n)))
        .collect()
}

#[test]
fn what_openscad_accepts_with_a_warning_is_read_as_openscad_reads_it() {
    let mut files = relative("tests/lenient");
    files.extend(relative("tests/bad"));
    // Runaway programs: reparamc stops them (`tests/bounds.rs`); OpenSCAD runs them for
    // hours.
    let runaway = ["ten_million_parts.scad", "exponential_recursion.scad"];
    files.retain(|p| {
        !p.file_name()
            .is_some_and(|n| runaway.iter().any(|r| n == *r))
    });
    let mut problems = Vec::new();
    let (mut lenient, mut rejected) = (0, 0);
    for path in &files {
        let shown = path.display();
        let theirs = openscad(path);
        let mut sources = SourceMap::new();
        let ours = reparamc::load_model(&mut sources, path);
        if theirs.failed {
            rejected += 1;
            if let Ok(e) = &ours {
                problems.push(format!(
                    "{shown}: OpenSCAD rejects it, reparamc accepts it with {} warning(s)",
                    e.warnings.len()
                ));
            }
            continue;
        }
        let their_parts = theirs.csg.as_deref().map(csg_parts).unwrap_or_default();
        if !theirs.warned {
            continue;
        }
        lenient += 1;
        match ours {
            Err(d) if their_parts.is_empty() && d.code == "E0500" => {}
            // A non-finite number in geometry is an error by design: OpenSCAD warns about
            // a NaN translation and drops it, but a model whose numbers are not numbers
            // has nothing to re-parameterize.
            Err(d) if d.code == "E0109" => {}
            Err(d) => problems.push(format!(
                "{shown}: OpenSCAD only warns, reparamc fails:\n{}",
                d.render_plain(&sources)
            )),
            Ok(e) => {
                if !e.warnings.iter().any(|w| w.severity == Severity::Warning) {
                    problems.push(format!("{shown}: OpenSCAD warns, reparamc does not"));
                }
                let our_parts: Vec<CsgPart> = e.model.parts.iter().map(our_part).collect();
                let errs = compare_parts(&our_parts, &their_parts);
                if !errs.is_empty() {
                    problems.push(format!("{shown}:\n  {}", errs.join("\n  ")));
                }
            }
        }
    }
    assert!(lenient >= 15, "only {lenient} inputs OpenSCAD warns about");
    assert!(rejected >= 8, "only {rejected} inputs OpenSCAD rejects");
    assert!(problems.is_empty(), "{}", problems.join("\n\n"));
}

/// Each lenient input's warnings, as the user reads them: located, with a caret and a code.
#[test]
fn lenient_inputs_warn_with_a_place() {
    let files = relative("tests/lenient");
    assert!(files.len() >= 7);
    for path in &files {
        let mut sources = SourceMap::new();
        let evaluated = match reparamc::load_model(&mut sources, path) {
            Ok(e) => e,
            Err(d) => panic!("{}", d.render_plain(&sources)),
        };
        let rendered: String = evaluated
            .warnings
            .iter()
            .map(|w| w.render_plain(&sources))
            .collect();
        let stem = path.file_stem().map(|s| s.to_string_lossy().into_owned());
        snapshot(&stem.unwrap_or_default(), path, &rendered);
        assert!(rendered.starts_with("warning[W"), "{rendered}");
        assert!(
            rendered.contains(&format!("{}:", path.display())),
            "{rendered}"
        );
        assert!(rendered.contains('^'), "{rendered}");
    }
}
