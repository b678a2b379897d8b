//! Mirror symmetry and equal spacing as relations the sliders keep, checked through
//! OpenSCAD: random flat tables (a top on four inset legs, no comments, every number typed
//! as a literal) and random rows of evenly spaced shelves are re-parameterized without
//! variations; at random in-range slider settings, OpenSCAD's own export must still show
//! the legs mirrored about the top's centre and the shelves at equal gaps, and a table
//! needs at most eight sliders (issue 14's target for a plain four-legged table).

mod common;

use common::*;
use reparamc::command::compile::{Compiled, Options, reparameterize};
use reparamc::front::source::SourceMap;
use std::path::{Path, PathBuf};
use std::process::Command;

/// A number in `[lo, hi]` rounded to a tenth, as people type them.
fn typed(rng: &mut Rng, lo: f64, hi: f64) -> f64 {
    ((lo + rng.next() * (hi - lo)) * 10.0).round() / 10.0
}

/// `x` as OpenSCAD text, without float noise.
fn num(x: f64) -> String {
    let s = format!("{:.3}", x);
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// A top on four legs set in from its corners, at a random place; legs are boxes or
/// cylinders. Part 0 is the top, parts 1–4 the legs (front left, front right, back left,
/// back right).
fn table(rng: &mut Rng) -> String {
    let (w, d, t) = (
        typed(rng, 40.0, 120.0),
        typed(rng, 30.0, 80.0),
        typed(rng, 2.0, 6.0),
    );
    let (l, h) = (typed(rng, 3.0, 8.0), typed(rng, 30.0, 80.0));
    let inset = [typed(rng, 1.0, 10.0), typed(rng, 1.0, 10.0)];
    let at = [typed(rng, -50.0, 50.0), typed(rng, -50.0, 50.0)];
    let round = rng.next() < 0.4;
    top_on_legs([w, d, t], [l, h], inset, at, round)
}

/// A chair as people type one: a seat on four legs, flush with its corners or set in
/// equally from both sides, and a back panel standing on the seat's rear edge. Parts 0–4
/// as in [`table`], part 5 the back.
fn chair(rng: &mut Rng) -> String {
    let (w, d, t) = (
        typed(rng, 36.0, 56.0),
        typed(rng, 34.0, 52.0),
        typed(rng, 2.0, 5.0),
    );
    let (l, h) = (typed(rng, 3.0, 6.0), typed(rng, 38.0, 50.0));
    let i = if rng.next() < 0.4 {
        0.0
    } else {
        typed(rng, 1.0, 6.0)
    };
    let at = [typed(rng, -50.0, 50.0), typed(rng, -50.0, 50.0)];
    let round = rng.next() < 0.4;
    let (bt, bh) = (typed(rng, 2.0, 5.0), typed(rng, 30.0, 50.0));
    let mut s = top_on_legs([w, d, t], [l, h], [i, i], at, round);
    s += &format!(
        "translate([{}, {}, {}]) cube([{}, {}, {}]);\n",
        num(at[0]),
        num(at[1] + d - bt),
        num(h + t),
        num(w),
        num(bt),
        num(bh)
    );
    s
}

/// A top of `[w, d, t]` at `at` and height `h`, on four legs `l` thick set in by `inset`
/// on x and y: boxes or (`round`) cylinders.
fn top_on_legs(
    top: [f64; 3],
    [l, h]: [f64; 2],
    inset: [f64; 2],
    at: [f64; 2],
    round: bool,
) -> String {
    let [w, d, t] = top;
    let [ox, oy] = at;
    let [ix, iy] = inset;
    let mut s = format!(
        "translate([{}, {}, {}]) cube([{}, {}, {}]);\n",
        num(ox),
        num(oy),
        num(h),
        num(w),
        num(d),
        num(t)
    );
    for y in [oy + iy, oy + d - iy - l] {
        for x in [ox + ix, ox + w - ix - l] {
            if round {
                s += &format!(
                    "translate([{}, {}, 0]) cylinder(h = {}, r = {});\n",
                    num(x + l / 2.0),
                    num(y + l / 2.0),
                    num(h),
                    num(l / 2.0)
                );
            } else {
                s += &format!(
                    "translate([{}, {}, 0]) cube([{}, {}, {}]);\n",
                    num(x),
                    num(y),
                    num(l),
                    num(l),
                    num(h)
                );
            }
        }
    }
    s
}

/// Two sides and a bottom with three to five evenly spaced shelves between the sides.
/// Parts 0–2 are the carcass; the shelves follow, lowest first.
fn shelves(rng: &mut Rng) -> (String, usize) {
    let (w, d, gap, t) = (
        typed(rng, 40.0, 90.0),
        typed(rng, 20.0, 40.0),
        typed(rng, 15.0, 40.0),
        typed(rng, 1.5, 3.0),
    );
    let n = 3 + (rng.next() * 3.0) as usize;
    let h = gap * (n as f64 + 1.0) + t;
    let mut s = format!("cube([{}, {}, {}]);\n", num(t), num(d), num(h));
    s += &format!(
        "translate([{}, 0, 0]) cube([{}, {}, {}]);\n",
        num(w - t),
        num(t),
        num(d),
        num(h)
    );
    s += &format!(
        "translate([{}, 0, 0]) cube([{}, {}, {}]);\n",
        num(t),
        num(w - 2.0 * t),
        num(d),
        num(t)
    );
    for k in 1..=n {
        s += &format!(
            "translate([{}, 0, {}]) cube([{}, {}, {}]);\n",
            num(t),
            num(k as f64 * gap),
            num(w - 2.0 * t),
            num(d),
            num(t)
        );
    }
    (s, n)
}

/// Writes `text` to a scratch file and compiles it without variations.
fn compile(name: &str, text: &str) -> (PathBuf, Compiled) {
    let dir = tempfile(&repo().join(format!("tests/{name}.scad")), "symmetry");
    std::fs::create_dir_all(&dir).unwrap();
    let input = dir.join(format!("{name}.scad"));
    std::fs::write(&input, text).unwrap();
    let mut sources = SourceMap::new();
    let (loaded, evaluated) = match reparamc::load_model_parsed(&mut sources, &input) {
        Ok(x) => x,
        Err(d) => panic!("{}", d.render_plain(&sources)),
    };
    let options = Options {
        all_constraints: false,
        presets_name: None,
        measure: false,
    };
    let compiled = reparameterize(&sources, &loaded, &evaluated.model, &[], &options);
    let out = dir.join(format!("{name}_param.scad"));
    std::fs::write(&out, &compiled.scad).unwrap();
    (out, compiled)
}

/// The world centre of every part OpenSCAD exports for `model` at `defs`.
fn centres(model: &Path, defs: &[String]) -> Vec<[f64; 3]> {
    boxes(model, defs)
        .iter()
        .map(|[lo, hi]| std::array::from_fn(|k| 0.5 * (lo[k] + hi[k])))
        .collect()
}

/// The world bounding box of every part OpenSCAD exports for `model` at `defs`.
fn boxes(model: &Path, defs: &[String]) -> Vec<[[f64; 3]; 2]> {
    let csg = tempfile(model, "csg");
    let args = defs.iter().flat_map(|d| ["-D".to_string(), d.clone()]);
    let run = Command::new("openscad")
        .args(args)
        .arg("-o")
        .arg(&csg)
        .arg(model)
        .output()
        .expect("the `openscad` binary must be installed (see scripts/setup)");
    assert!(
        run.status.success(),
        "openscad failed on {}: {}",
        model.display(),
        String::from_utf8_lossy(&run.stderr)
    );
    let text = std::fs::read_to_string(&csg).unwrap();
    let _ = std::fs::remove_file(&csg);
    csg_parts(&text)
        .iter()
        .map(|p| {
            let (lo, hi) = part_from_csg(p).world_bounds();
            [lo, hi]
        })
        .collect()
}

/// `count` random in-range settings of the output's sliders, as `-D` definitions.
fn settings(compiled: &Compiled, rng: &mut Rng, count: usize) -> Vec<Vec<String>> {
    (0..count)
        .map(|_| {
            compiled
                .report
                .free_variables
                .iter()
                .map(|f| {
                    let v = f.range.min + rng.next() * (f.range.max - f.range.min);
                    format!("{}={v}", f.name)
                })
                .collect()
        })
        .collect()
}

/// Checks `count` random settings of `out`: the legs (parts 1–4) mirrored about the top's
/// centre (part 0) on x and y, and, with `equal_insets`, each leg as far from the top's
/// nearer side on x as on y.
fn check_legs(
    what: &str,
    out: &Path,
    compiled: &Compiled,
    rng: &mut Rng,
    equal_insets: bool,
    failures: &mut Vec<String>,
) {
    for defs in settings(compiled, rng, 5) {
        let b = boxes(out, &defs);
        let c: Vec<[f64; 3]> = b
            .iter()
            .map(|[lo, hi]| std::array::from_fn(|k| 0.5 * (lo[k] + hi[k])))
            .collect();
        let at = defs.join(" ");
        // OpenSCAD's export prints six significant digits.
        let tol = 1e-4 * 200.0;
        // Mirror pairs across x (same row) and across y (same column).
        for (axis, pairs) in [(0, [(1, 2), (3, 4)]), (1, [(1, 3), (2, 4)])] {
            for (a, b) in pairs {
                let off = c[a][axis] + c[b][axis] - 2.0 * c[0][axis];
                if off.abs() > tol {
                    failures.push(format!(
                        "{what}, legs {a} and {b} off by {off} on axis {axis} at {at}"
                    ));
                }
            }
        }
        if equal_insets {
            // The front left leg is as far in from the top's left side as from its front;
            // with the mirror pairs, so is every leg from its own corner.
            let (leg, top) = (b[1][0], b[0][0]);
            let off = (leg[0] - top[0]) - (leg[1] - top[1]);
            if off.abs() > tol {
                failures.push(format!("{what}: insets differ by {off} at {at}"));
            }
        }
    }
}

/// Draws six models with `draw`, re-parameterizes each without variations and checks that
/// it has at most eight sliders and that its legs keep their placement ([`check_legs`]).
fn legs_hold_with_at_most_eight_sliders(
    what: &str,
    seed: u64,
    draw: fn(&mut Rng) -> String,
    equal_insets: bool,
) {
    let mut rng = Rng(seed);
    let mut failures = Vec::new();
    for k in 0..6 {
        let text = draw(&mut rng);
        let (out, compiled) = compile(&format!("{what}{k}"), &text);
        let names: Vec<&str> = compiled
            .report
            .free_variables
            .iter()
            .map(|v| v.name.as_str())
            .collect();
        if names.len() > 8 {
            failures.push(format!(
                "{what} {k}: {} sliders (at most 8): {names:?}\n{text}",
                names.len()
            ));
        }
        let mut found = Vec::new();
        let label = format!("{what} {k}");
        check_legs(&label, &out, &compiled, &mut rng, equal_insets, &mut found);
        failures.extend(found.into_iter().map(|f| format!("{f}\n{text}")));
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn table_legs_stay_mirrored_about_the_top_at_random_settings() {
    legs_hold_with_at_most_eight_sliders("table", 0x5eed_7ab1e, table, false);
}

/// Issue 14's target for a plain chair: a flat chair with a back and no comments gets at
/// most eight sliders, and its legs stay mirrored and equally inset at random settings.
#[test]
fn chair_legs_stay_mirrored_and_inset_with_at_most_eight_sliders() {
    legs_hold_with_at_most_eight_sliders("chair", 0xc4a1_5eed, chair, true);
}

#[test]
fn shelves_stay_evenly_spaced_at_random_settings() {
    let mut rng = Rng(0x5e1f);
    let mut failures = Vec::new();
    for k in 0..4 {
        let (text, n) = shelves(&mut rng);
        let (out, compiled) = compile(&format!("shelves{k}"), &text);
        for defs in settings(&compiled, &mut rng, 4) {
            let c = centres(&out, &defs);
            let z: Vec<f64> = (3..3 + n).map(|i| c[i][2]).collect();
            for w in z.windows(3) {
                let off = (w[1] - w[0]) - (w[2] - w[1]);
                if off.abs() > 1e-4 * 400.0 {
                    failures.push(format!(
                        "shelves {k}: gaps differ by {off} at {}\n{text}",
                        defs.join(" ")
                    ));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
