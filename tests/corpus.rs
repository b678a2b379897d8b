//! Models from the wild (`tests/corpus/`, sources and licences in `tests/corpus/SOURCES.md`),
//! run as a new user would: `reparamc model.scad -o out.scad`, no variations. Each output
//! must render in OpenSCAD equal to its input at default values (their `.csg` exports), have
//! sliders when the model has numbers, and carry no machine-made name: no counter suffix,
//! no name without a letter, no description like "Width 2 of the chair"; and where the
//! author named some of the numbers (variables, module parameters), at most three sliders
//! more than those. The repository's examples are held to the same. The test prints the slider counts
//! and where the names came from.

mod common;

use common::*;
use reparamc::command::compile::{Compiled, Options, reparameterize};
use reparamc::front::source::SourceMap;
use std::collections::HashSet;
use std::path::{Path, PathBuf};

/// Words the geometric roles use (`analysis::names::roles`), for the rates printed.
const ROLE_WORDS: &[&str] = &[
    "leg", "top", "seat", "back", "post", "wheel", "axle", "side", "front", "bottom", "shelf",
    "divider", "hole", "cutout", "bar", "board", "block", "rod", "disc", "cylinder", "ball",
];

/// Order words, the last resort for telling names apart.
const ORDER_WORDS: &[&str] = &[
    "first", "second", "third", "fourth", "fifth", "sixth", "seventh", "eighth", "ninth", "tenth",
];

struct Outcome {
    model: PathBuf,
    problems: Vec<String>,
    sliders: Vec<(String, String)>,
    numbers: usize,
    /// How many of the numbers that drive parts the author named (variables, vectors a
    /// variable holds, module parameters and arguments).
    author_variables: usize,
    /// Every identifier of the input: the author's own names.
    identifiers: HashSet<String>,
}

/// Identifier-like words of a source text.
fn source_identifiers(text: &str) -> HashSet<String> {
    text.split(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .filter(|w| w.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_'))
        .map(str::to_string)
        .collect()
}

/// Why `name` (with `description`) reads as machine-made, if it does.
fn machine_made(name: &str, description: &str, author: &HashSet<String>) -> Option<String> {
    if !name.chars().any(|c| c.is_ascii_alphabetic()) {
        return Some(format!("`{name}` has no letter"));
    }
    // The author's own identifiers may hold digits (`rear_axle_1_offset`).
    if !author.contains(name)
        && name
            .split('_')
            .any(|w| w.chars().all(|c| c.is_ascii_digit()))
    {
        return Some(format!("`{name}` has a counter"));
    }
    let words: Vec<&str> = description.split_whitespace().collect();
    if words.len() >= 3 && words[1].chars().all(|c| c.is_ascii_digit()) && words[2] == "of" {
        return Some(format!("`{name}` is described as \"{description}\""));
    }
    None
}

/// The main job on `model` with no variations: its results, the model's own text, how
/// many numbers it has and how many of them the author named.
fn compile(model: &Path) -> (Compiled, String, usize, usize) {
    let mut sources = SourceMap::new();
    let (loaded, evaluated) = match reparamc::load_model_parsed(&mut sources, model) {
        Ok(x) => x,
        Err(d) => panic!("{}", d.render_plain(&sources)),
    };
    let compiled = reparameterize(
        &sources,
        &loaded,
        &evaluated.model,
        &[],
        &Options::default(),
    );
    let text = sources.text(loaded.main).to_string();
    let slots = &evaluated.model.slots;
    let named = slots.iter().filter(|s| s.authored).count();
    (compiled, text, slots.len(), named)
}

fn run(model: &Path) -> Outcome {
    let (compiled, text, numbers, author_variables) = compile(model);
    let out = tempfile(model, "scad");
    std::fs::write(&out, &compiled.scad).unwrap();
    let mut problems = compare_parts(
        &csg_parts(&openscad_csg(&out)),
        &csg_parts(&openscad_csg(model)),
    );
    let _ = std::fs::remove_file(&out);
    let identifiers = source_identifiers(&text);
    let sliders: Vec<(String, String)> = compiled
        .report
        .free_variables
        .iter()
        .map(|v| (v.name.clone(), v.description.clone()))
        .collect();
    for (n, d) in &sliders {
        problems.extend(machine_made(n, d, &identifiers));
    }
    if numbers > 0 && sliders.is_empty() {
        problems.push(format!("{numbers} numbers and no slider"));
    }
    // Issue 14: the author's named numbers come first, and at most three sliders more.
    if author_variables > 0 && sliders.len() > author_variables + 3 {
        problems.push(format!(
            "{} sliders for {author_variables} numbers the author named (at most 3 more)",
            sliders.len()
        ));
    }
    Outcome {
        model: model.to_path_buf(),
        problems,
        sliders,
        numbers,
        author_variables,
        identifiers,
    }
}

/// Runs `f` on every item on a few threads, in order.
fn parallel<T: Sync, R: Send>(items: &[T], f: impl Fn(&T) -> R + Sync) -> Vec<R> {
    let next = std::sync::atomic::AtomicUsize::new(0);
    let results: std::sync::Mutex<Vec<(usize, R)>> = std::sync::Mutex::new(Vec::new());
    std::thread::scope(|s| {
        for _ in 0..2 {
            s.spawn(|| {
                loop {
                    let i = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                    let Some(item) = items.get(i) else { break };
                    let r = f(item);
                    results.lock().unwrap().push((i, r));
                }
            });
        }
    });
    let mut r = results.into_inner().unwrap();
    r.sort_by_key(|(i, _)| *i);
    r.into_iter().map(|(_, r)| r).collect()
}

#[test]
fn every_corpus_model_has_its_source_and_licence() {
    let sources = std::fs::read_to_string(repo().join("tests/corpus/SOURCES.md")).unwrap();
    let models = scad_files("tests/corpus");
    assert!(models.len() >= 20, "the corpus has {} models", models.len());
    for m in models {
        let name = m.file_name().unwrap().to_string_lossy().into_owned();
        let line = sources
            .lines()
            .find(|l| l.contains(&format!("`{name}`")))
            .unwrap_or_else(|| panic!("{name} is not in SOURCES.md"));
        assert!(line.contains("https://"), "{name}: no source address");
        assert!(
            ["MIT", "GPL", "CC BY", "CC0"]
                .iter()
                .any(|l| line.contains(l)),
            "{name}: no licence"
        );
    }
}

#[test]
fn corpus_models_come_back_equal_with_names_a_person_wrote() {
    check_names_and_counts(&scad_files("tests/corpus"));
}

/// The repository's examples are held to the same: no machine-made name, the author's
/// variables first.
#[test]
fn examples_come_back_equal_with_names_a_person_wrote() {
    let mut models = scad_files("examples");
    models.extend(scad_files("examples/paper"));
    check_names_and_counts(&models);
}

fn check_names_and_counts(models: &[PathBuf]) {
    let outcomes = parallel(models, |m| run(m));
    let mut failures = Vec::new();
    let (mut total, mut author, mut roles, mut order) = (0, 0, 0, 0);
    println!(
        "{:<40} {:>7} {:>7} {:>7}",
        "model", "numbers", "named", "sliders"
    );
    for o in &outcomes {
        let stem = o.model.file_name().unwrap().to_string_lossy().into_owned();
        println!(
            "{stem:<40} {:>7} {:>7} {:>7}",
            o.numbers,
            o.author_variables,
            o.sliders.len()
        );
        for (n, d) in &o.sliders {
            println!("    {n:<36} {d}");
            total += 1;
            let words: Vec<&str> = n.split('_').collect();
            if o.identifiers.contains(n) {
                author += 1;
            } else if words.iter().any(|w| ORDER_WORDS.contains(w)) {
                order += 1;
            } else if words.iter().any(|w| ROLE_WORDS.contains(w)) {
                roles += 1;
            }
        }
        if !o.problems.is_empty() {
            failures.push(format!("{stem}: {}", o.problems.join("; ")));
        }
    }
    let pct = |n: usize| 100.0 * n as f64 / total.max(1) as f64;
    println!(
        "{total} sliders on {} models: {:.0}% the author's variables, {:.0}% with a role from \
         geometry, {:.0}% told apart by order words, {:.0}% other source words",
        outcomes.len(),
        pct(author),
        pct(roles),
        pct(order),
        pct(total - author - roles - order)
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn machine_made_names_are_recognised() {
    let none = HashSet::new();
    assert!(machine_made("Chair_size_8", "Size of the chair", &none).is_some());
    assert!(machine_made("_______x", "Position in x", &none).is_some());
    assert!(machine_made("chair_width", "Width 2 of the chair", &none).is_some());
    assert!(machine_made("leg_height", "Height (z) of every leg (4 numbers)", &none).is_none());
    let author: HashSet<String> = ["rear_axle_1_offset".to_string()].into();
    assert!(machine_made("rear_axle_1_offset", "X", &author).is_none());
}

/// The sliders of a model given as text: `(name, description, min, max)`.
fn sliders_of(text: &str) -> Vec<(String, String, f64, f64)> {
    let path = tempfile(Path::new("inline.scad"), "scad");
    std::fs::write(&path, text).unwrap();
    let (compiled, ..) = compile(&path);
    let _ = std::fs::remove_file(&path);
    compiled
        .report
        .free_variables
        .iter()
        .map(|v| {
            (
                v.name.clone(),
                v.description.clone(),
                v.range.min,
                v.range.max,
            )
        })
        .collect()
}

#[test]
fn cyrillic_comments_give_transliterated_names() {
    let s = sliders_of(
        "// сиденье\ncube([40, 40, 4]);\n// спинка\ntranslate([0, 36, 4]) cube([40, 4, 40]);\n",
    );
    let names: Vec<&str> = s.iter().map(|x| x.0.as_str()).collect();
    assert!(names.iter().any(|n| n.starts_with("spinka")), "{names:?}");
    assert!(names.iter().any(|n| n.starts_with("siden")), "{names:?}");
}

#[test]
fn a_module_called_with_named_arguments_exposes_them() {
    let s = sliders_of(
        "module bench(width, depth, height, board) {\n\
         for (x = [0, width - board]) translate([x, 0, 0]) cube([board, depth, height]);\n\
         translate([0, 0, height]) cube([width, depth, board]);\n}\n\
         bench(width = 120, depth = 40, height = 45, board = 3);\n",
    );
    let names: Vec<&str> = s.iter().map(|x| x.0.as_str()).collect();
    assert!(!s.is_empty());
    for n in &names {
        let arg = n.strip_prefix("bench_").unwrap_or(n);
        assert!(
            ["width", "depth", "height", "board"].contains(&arg),
            "`{n}` is not named after the argument it sets: {names:?}"
        );
    }
}

#[test]
fn legs_under_a_top_are_named_legs_and_positions_span_the_model() {
    let s = sliders_of(
        "translate([0, 0, 0]) cube([5, 5, 70]);\ntranslate([95, 0, 0]) cube([5, 5, 70]);\n\
         translate([0, 55, 0]) cube([5, 5, 70]);\ntranslate([95, 55, 0]) cube([5, 5, 70]);\n\
         translate([0, 0, 70]) cube([100, 60, 4]);\n",
    );
    let names: Vec<&str> = s.iter().map(|x| x.0.as_str()).collect();
    assert!(names.iter().any(|n| n.contains("leg")), "{names:?}");
    assert!(names.iter().any(|n| n.contains("top")), "{names:?}");
    for (n, _, lo, hi) in &s {
        assert!(hi - lo > 1.0, "`{n}` moves only within [{lo}, {hi}]");
    }
}
