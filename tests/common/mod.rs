//! Shared test support: running the real `openscad` and reading its `.csg` export.
//!
//! OpenSCAD is the oracle. Its `.csg` export is a flat program of `multmatrix`, booleans and
//! primitives with every argument written out; [`csg_parts`] walks it (with our parser, but
//! none of our evaluator) into primitives with world matrices, in OpenSCAD's order.

#![allow(dead_code)]

pub mod browser;

use reparamc::front::ast::{Expr, ExprKind, InstanceKind, Stmt, StmtKind, UnaryOp, VecElem};
use reparamc::front::parse::parse_program;
use reparamc::ir::{Num, Part, Primitive, Transform};
use std::path::{Path, PathBuf};
use std::process::Command;

pub fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Every `.scad` file directly in `dir` (relative to the repository), hidden ones aside, sorted.
pub fn scad_files(dir: &str) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(repo().join(dir))
        .unwrap_or_else(|e| panic!("cannot list {dir}: {e}"))
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "scad"))
        // Hidden files are other tests' scratch copies (a perturbed model written beside
        // its includes), which come and go while this lists the folder.
        .filter(|p| {
            !p.file_name()
                .is_some_and(|n| n.to_string_lossy().starts_with('.'))
        })
        .collect();
    v.sort();
    v
}

/// Runs `openscad -o <tmp>.<ext> model`: what it printed and exited with, and the file it
/// wrote, if any.
pub fn openscad_export(model: &Path, ext: &str) -> (std::process::Output, Option<String>) {
    openscad_export_with(model, ext, &[])
}

/// [`openscad_export`] of the parameter set `set` of the parameter file beside `model`
/// (`model.json`, as `reparamc` writes its presets): the preset as OpenSCAD evaluates it.
pub fn openscad_preset(model: &Path, set: &str) -> (std::process::Output, Option<String>) {
    let json = model.with_extension("json");
    let args = ["-p".as_ref(), json.as_os_str(), "-P".as_ref(), set.as_ref()];
    openscad_export_with(model, "csg", &args)
}

/// [`openscad_export`] with further arguments.
fn openscad_export_with(
    model: &Path,
    ext: &str,
    extra: &[&std::ffi::OsStr],
) -> (std::process::Output, Option<String>) {
    let out = tempfile(model, ext);
    let run = Command::new("openscad")
        .arg("-o")
        .arg(&out)
        .arg(model)
        .args(extra)
        .output()
        .expect("the `openscad` binary must be installed (see .ci/run)");
    let text = std::fs::read_to_string(&out).ok();
    let _ = std::fs::remove_file(&out);
    (run, text)
}

/// Runs `openscad -o <tmp>.csg model` and returns the export.
pub fn openscad_csg(model: &Path) -> String {
    let (run, text) = openscad_export(model, "csg");
    assert!(
        run.status.success(),
        "openscad failed on {}: {}",
        model.display(),
        String::from_utf8_lossy(&run.stderr)
    );
    text.expect("openscad wrote no .csg")
}

/// Asserts `rendered` against the snapshot `snapshots/<name>.snap` (insta).
pub fn snapshot(name: &str, input: &Path, rendered: &str) {
    let mut settings = insta::Settings::clone_current();
    settings.set_snapshot_path("../../snapshots");
    settings.set_prepend_module_to_snapshot(false);
    settings.set_input_file(input);
    settings.bind(|| insta::assert_snapshot!(name, rendered));
}

/// A unique temporary path for an artefact of `model`.
pub fn tempfile(model: &Path, ext: &str) -> PathBuf {
    use std::sync::atomic::{AtomicUsize, Ordering};
    static N: AtomicUsize = AtomicUsize::new(0);
    let stem = model
        .file_stem()
        .map_or("model".into(), |s| s.to_string_lossy().into_owned());
    std::env::temp_dir().join(format!(
        "reparamc-test-{}-{}-{stem}.{ext}",
        std::process::id(),
        N.fetch_add(1, Ordering::Relaxed)
    ))
}

/// One primitive of a `.csg` export.
#[derive(Debug, Clone)]
pub struct CsgPart {
    pub kind: &'static str,
    /// cube: `[x, y, z, center]`; cylinder: `[h, r1, r2, center]`; sphere: `[r]`.
    pub args: Vec<f64>,
    pub matrix: [[f64; 4]; 4],
}

fn mat_mul(a: &[[f64; 4]; 4], b: &[[f64; 4]; 4]) -> [[f64; 4]; 4] {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..4).map(|k| a[i][k] * b[k][j]).sum()))
}

const IDENTITY: [[f64; 4]; 4] = [
    [1.0, 0.0, 0.0, 0.0],
    [0.0, 1.0, 0.0, 0.0],
    [0.0, 0.0, 1.0, 0.0],
    [0.0, 0.0, 0.0, 1.0],
];

/// A constant expression of a `.csg` file: numbers, booleans, vectors, negation.
fn constant(e: &Expr) -> Vec<f64> {
    match &e.kind {
        ExprKind::Number { value, .. } => vec![*value],
        ExprKind::Bool(b) => vec![f64::from(u8::from(*b))],
        ExprKind::Unary(UnaryOp::Neg, x) => constant(x).into_iter().map(|v| -v).collect(),
        ExprKind::Vector(items) => items
            .iter()
            .flat_map(|el| match el {
                VecElem::Expr(x) => constant(x),
                _ => panic!("unexpected list comprehension in .csg"),
            })
            .collect(),
        ExprKind::Ident(name) if name == "inf" => vec![f64::INFINITY],
        other => panic!("unexpected expression in .csg: {other:?}"),
    }
}

/// The primitives of a `.csg` export with their world matrices, in order.
pub fn csg_parts(csg: &str) -> Vec<CsgPart> {
    let program =
        parse_program(0, csg).unwrap_or_else(|d| panic!("cannot parse .csg: {}", d.message));
    let mut out = Vec::new();
    walk(&program.stmts, &IDENTITY, &mut out);
    out
}

fn walk(stmts: &[Stmt], world: &[[f64; 4]; 4], out: &mut Vec<CsgPart>) {
    for s in stmts {
        let StmtKind::Instance(inst) = &s.kind else {
            continue;
        };
        if inst.modifiers.background || inst.modifiers.disable {
            continue;
        }
        let InstanceKind::Call {
            name,
            args,
            children,
        } = &inst.kind
        else {
            panic!("unexpected control statement in .csg")
        };
        let arg = |n: &str| -> Vec<f64> {
            args.iter()
                .find(|a| a.name.as_ref().is_some_and(|x| x.name == n))
                .map_or_else(Vec::new, |a| constant(&a.value))
        };
        match name.name.as_str() {
            "multmatrix" => {
                let v = arg("m");
                let v = if v.is_empty() {
                    constant(&args[0].value)
                } else {
                    v
                };
                let m: [[f64; 4]; 4] =
                    std::array::from_fn(|i| std::array::from_fn(|j| v[i * 4 + j]));
                walk(children, &mat_mul(world, &m), out);
            }
            "cube" => {
                let mut a = arg("size");
                a.extend(arg("center"));
                out.push(CsgPart {
                    kind: "cube",
                    args: a,
                    matrix: *world,
                });
            }
            "cylinder" => {
                let a = ["h", "r1", "r2", "center"]
                    .iter()
                    .flat_map(|n| arg(n))
                    .collect();
                out.push(CsgPart {
                    kind: "cylinder",
                    args: a,
                    matrix: *world,
                });
            }
            "sphere" => out.push(CsgPart {
                kind: "sphere",
                args: arg("r"),
                matrix: *world,
            }),
            _ => walk(children, world, out),
        }
    }
}

/// A part as our evaluator describes it, in the `.csg` vocabulary.
pub fn our_part(p: &Part) -> CsgPart {
    let (kind, args) = match &p.primitive {
        Primitive::Cube { size, center } => (
            "cube",
            vec![
                size[0].value,
                size[1].value,
                size[2].value,
                f64::from(u8::from(*center)),
            ],
        ),
        Primitive::Cylinder { h, r1, r2, center } => (
            "cylinder",
            vec![h.value, r1.value, r2.value, f64::from(u8::from(*center))],
        ),
        Primitive::Sphere { r } => ("sphere", vec![r.value]),
    };
    CsgPart {
        kind,
        args,
        matrix: p.world.values(),
    }
}

/// An IR part (constants only) from a `.csg` primitive, to compute its features.
pub fn part_from_csg(c: &CsgPart) -> Part {
    let k = |v: f64| Num::constant(v);
    let primitive = match c.kind {
        "cube" => Primitive::Cube {
            size: [k(c.args[0]), k(c.args[1]), k(c.args[2])],
            center: c.args[3] != 0.0,
        },
        "cylinder" => Primitive::Cylinder {
            h: k(c.args[0]),
            r1: k(c.args[1]),
            r2: k(c.args[2]),
            center: c.args[3] != 0.0,
        },
        _ => Primitive::Sphere { r: k(c.args[0]) },
    };
    let m = c.matrix;
    Part {
        name: String::new(),
        primitive,
        world: Transform::from_values([m[0], m[1], m[2]]),
        span: Default::default(),
        misaligned: None,
        fragments: [0.0, 12.0, 2.0],
        highlighted: false,
        statements: Vec::new(),
    }
}

/// `ours` agrees with OpenSCAD's printed `theirs`: within 1e-9 relative, where OpenSCAD
/// printed the number exactly, or equal after rounding to the 6 significant digits its
/// `.csg` export prints.
pub fn agrees(ours: f64, theirs: f64) -> bool {
    let scale = theirs.abs().max(1.0);
    if (ours - theirs).abs() <= 1e-9 * scale {
        return true;
    }
    let rounded: f64 = format!("{ours:.5e}").parse().unwrap_or(f64::NAN);
    (rounded - theirs).abs() <= 1e-12 * scale || (ours.abs() < 5e-7 && theirs == 0.0)
}

/// Differences between our parts and OpenSCAD's, as readable lines (empty when they agree).
pub fn compare_parts(ours: &[CsgPart], theirs: &[CsgPart]) -> Vec<String> {
    let mut errs = Vec::new();
    if ours.len() != theirs.len() {
        errs.push(format!(
            "{} parts, OpenSCAD has {}",
            ours.len(),
            theirs.len()
        ));
    }
    for (i, (a, b)) in ours.iter().zip(theirs).enumerate() {
        if a.kind != b.kind {
            errs.push(format!("part {i}: {} vs OpenSCAD's {}", a.kind, b.kind));
            continue;
        }
        let args_ok =
            a.args.len() == b.args.len() && a.args.iter().zip(&b.args).all(|(x, y)| agrees(*x, *y));
        if !args_ok {
            errs.push(format!(
                "part {i} ({}): args {:?} vs OpenSCAD's {:?}",
                a.kind, a.args, b.args
            ));
        }
        let m_ok = (0..4).all(|r| (0..4).all(|c| agrees(a.matrix[r][c], b.matrix[r][c])));
        if !m_ok {
            errs.push(format!(
                "part {i} ({}): matrix {:?} vs OpenSCAD's {:?}",
                a.kind, a.matrix, b.matrix
            ));
        }
    }
    errs
}

/// A tiny deterministic generator (xorshift), so settings and drawn models are the same on
/// every run.
pub struct Rng(pub u64);

impl Rng {
    pub fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Parts moved rigidly so their bounding box has its centre (x, y) and floor (z) at 0.
pub fn anchored(parts: &[Part]) -> Vec<Part> {
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for p in parts {
        let (l, h) = p.world_bounds();
        for a in 0..3 {
            lo[a] = lo[a].min(l[a]);
            hi[a] = hi[a].max(h[a]);
        }
    }
    let shift = [-(lo[0] + hi[0]) / 2.0, -(lo[1] + hi[1]) / 2.0, -lo[2]];
    parts
        .iter()
        .map(|p| {
            let mut q = p.clone();
            for (a, d) in shift.iter().enumerate() {
                q.world.m[a][3] = reparamc::ir::Num::constant(p.world.m[a][3].value + d);
            }
            q
        })
        .collect()
}
