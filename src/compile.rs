//! The main job: a model and its variations in, a re-parameterized model out.
//!
//! Composes the stages: candidates → optional parts → discovery and cutoff (or, without
//! variations, the structural prior) → Gauss–Jordan solve with anchors → names and ranges →
//! projected variations as presets → the emitted file. Every decision is recorded in the
//! [`Report`].

use crate::analysis::candidates::{Candidate, Candidates};
use crate::analysis::cutoff::{Cutoff, cutoff};
use crate::analysis::discover::{Sample, Similarity, discover};
use crate::analysis::names::name_free_variables;
use crate::analysis::noise::{NoiseGate, noise_gate};
use crate::analysis::optional::{Toggle, optional_parts, toggles};
use crate::analysis::project::{Faces, project_onto};
use crate::analysis::ranges::{Range, ranges};
use crate::analysis::reparam::{Expression, Solution, anchor_rows_at, solve};
use crate::analysis::tiers::{TIER_NAMES, discovery_tiers, plausible_steps};
use crate::analysis::{find_candidates_for, prior};
use crate::back::emit::{Blend, EmitPlan, Slider, Switch, emit, number};
use crate::front::ast::{ExprKind, StmtKind};
use crate::front::load::Loaded;
use crate::front::source::SourceMap;
use crate::front::walk::{Visitor, visit_stmts};
use crate::ir::{Affine, CsgNode, Model};
use crate::span::Span;
use crate::tolerance::Tolerance;
use crate::variation::Variation;
use serde::Serialize;
use std::collections::{BTreeSet, HashMap, HashSet};

/// Distortion the variations' own noise explains; a curve below it keeps every constraint.
pub const DISTORTION_TOLERANCE: f64 = 0.01;

/// What the main command can be told.
#[derive(Debug, Clone, Default)]
pub struct Options {
    /// Without variations, keep every base constraint (the paper's symbolic baseline).
    pub all_constraints: bool,
    /// The file name the parameter sets will have (for the comment that points to them).
    pub presets_name: Option<String>,
}

/// The model's IoU between two settings of its slots, by exact ray-interval volumes.
pub struct VolumeSimilarity<'m> {
    model: &'m Model,
    /// For each slot, the parts whose geometry depends on it.
    slot_parts: Vec<Vec<usize>>,
    /// Each part's own volume in the input.
    part_volumes: Vec<f64>,
}

impl<'m> VolumeSimilarity<'m> {
    pub fn new(model: &'m Model) -> VolumeSimilarity<'m> {
        let part_volumes = model
            .parts_at(&model.slot_values())
            .unwrap_or_default()
            .into_iter()
            .map(|p| crate::geom::volume(&[p], &CsgNode::Part(0)))
            .collect();
        VolumeSimilarity {
            model,
            slot_parts: slot_parts(model),
            part_volumes,
        }
    }

    /// The parts (outside `skip`) that depend on a `changed` slot, at `a`; `None` when one
    /// does not evaluate.
    fn edits(&self, a: &[f64], changed: &[u32], skip: &[usize]) -> Option<Vec<crate::geom::Edit>> {
        let mut touched: Vec<usize> = changed
            .iter()
            .flat_map(|&s| self.slot_parts[s as usize].iter().copied())
            .filter(|p| !skip.contains(p))
            .collect();
        touched.sort_unstable();
        touched.dedup();
        touched
            .into_iter()
            .map(|p| Some((p, Some(self.model.parts[p].at(a)?))))
            .collect()
    }
}

/// The CSG tree without the `skip` parts (`None` when nothing is left).
pub fn csg_without(node: &CsgNode, skip: &[usize]) -> Option<CsgNode> {
    match node {
        CsgNode::Part(i) => (!skip.contains(i)).then_some(CsgNode::Part(*i)),
        CsgNode::Union(c) => {
            let kept: Vec<CsgNode> = c.iter().filter_map(|n| csg_without(n, skip)).collect();
            (!kept.is_empty()).then_some(CsgNode::Union(kept))
        }
        CsgNode::Difference(c) => {
            let first = csg_without(c.first()?, skip)?;
            let mut kept = vec![first];
            kept.extend(c[1..].iter().filter_map(|n| csg_without(n, skip)));
            Some(CsgNode::Difference(kept))
        }
        CsgNode::Intersection(c) => {
            let kept: Option<Vec<CsgNode>> = c.iter().map(|n| csg_without(n, skip)).collect();
            Some(CsgNode::Intersection(kept?))
        }
    }
}

/// A setting of the model made into geometry once, with its volume.
pub struct VolumeReference {
    solid: crate::geom::Prepared,
    skip: Vec<usize>,
}

impl Similarity for VolumeSimilarity<'_> {
    type Reference = VolumeReference;

    fn reference(&self, b: &[f64], skip: &[usize]) -> VolumeReference {
        let parts = self.model.parts_at(b).unwrap_or_default();
        let csg = csg_without(&self.model.csg, skip).unwrap_or(CsgNode::Union(Vec::new()));
        VolumeReference {
            solid: crate::geom::Prepared::new(parts, csg),
            skip: skip.to_vec(),
        }
    }

    /// IoU, integrating only around the parts that differ from the reference.
    fn similarity_to(&self, a: &[f64], r: &VolumeReference) -> f64 {
        match self.model.parts_at(a) {
            Some(parts) if parts.len() == r.solid.parts().len() => {
                let edits: Vec<crate::geom::Edit> =
                    parts.into_iter().map(Some).enumerate().collect();
                r.solid.iou_edited(&edits)
            }
            _ => 0.0,
        }
    }

    /// IoU, evaluating only the parts that depend on a changed slot.
    fn similarity_changed(&self, a: &[f64], changed: &[u32], r: &VolumeReference) -> f64 {
        if r.solid.parts().len() != self.model.parts.len() {
            return 0.0;
        }
        match self.edits(a, changed, &r.skip) {
            Some(edits) => r.solid.iou_edited(&edits),
            None => 0.0,
        }
    }

    fn update_reference(&self, r: &mut VolumeReference, a: &[f64], changed: &[u32]) {
        match self.edits(a, changed, &r.skip) {
            Some(edits) if r.solid.parts().len() == self.model.parts.len() => r.solid.apply(&edits),
            _ => *r = self.reference(a, &r.skip.clone()),
        }
    }

    fn removal_loss(&self, r: &VolumeReference, part: usize) -> f64 {
        let changed = r.solid.changed_volume(&[(part, None)]);
        let own = self.part_volumes.get(part).copied().unwrap_or(0.0);
        if changed <= 0.0 {
            0.0
        } else if own > 0.0 {
            changed / own
        } else {
            f64::INFINITY
        }
    }
}

#[derive(Debug, Clone, Serialize)]
pub struct FreeVariableReport {
    pub name: String,
    pub slot: String,
    pub description: String,
    pub value: f64,
    pub range: Range,
}

#[derive(Debug, Clone, Serialize)]
pub struct VariationReport {
    pub name: String,
    pub optional_parts: Vec<String>,
    /// IoU between the variation and its projection onto the kept constraints.
    pub projection_iou: f64,
}

/// One chosen relation and the evidence for it.
#[derive(Debug, Clone, Serialize)]
pub struct ChosenRelation {
    pub relation: String,
    /// "structural" (the prior's kind), "other", or "beyond noise" (some variation breaks it).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tier: Option<&'static str>,
    /// Its largest residual over the variations (world units).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub residual: Option<f64>,
    /// The largest loss of IoU its step caused in one variation.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub worst_loss: Option<f64>,
}

#[derive(Debug, Clone, Serialize)]
pub struct Report {
    pub model: String,
    pub parameter_count: usize,
    pub base_constraint_count: usize,
    /// How the kept constraints were chosen.
    pub method: String,
    /// Chosen constraints in order (all greedy steps, with variations).
    pub chosen: Vec<ChosenRelation>,
    /// The variations' estimated noise (world units) and the gate it sets.
    pub noise: Option<NoiseGate>,
    pub kept_count: usize,
    pub cutoff: Option<Cutoff>,
    pub distortion_curve: Vec<f64>,
    pub dimension: usize,
    pub free_variables: Vec<FreeVariableReport>,
    pub variations: Vec<VariationReport>,
    pub toggles: Vec<Vec<String>>,
}

/// The results of the main job.
#[derive(Debug, Clone)]
pub struct Compiled {
    pub scad: String,
    /// OpenSCAD parameter sets (`<name>.json`), when there are variations.
    pub presets: Option<String>,
    pub report: Report,
    /// Every candidate of the model, and the kept ones, for tests and tools.
    pub candidates: Candidates,
    pub kept: Vec<Candidate>,
    pub solution: Solution,
    /// Slot values of each variation projected onto the kept constraints and anchors.
    pub projected: Vec<Vec<f64>>,
}

/// Every identifier the program uses (variables, parameters, functions, modules).
fn identifiers(loaded: &Loaded) -> HashSet<String> {
    struct Names(HashSet<String>);
    impl<'a> Visitor<'a> for Names {
        fn enter(&mut self, s: &'a crate::front::ast::Stmt) {
            match &s.kind {
                StmtKind::Assign { name, .. } => {
                    self.0.insert(name.name.clone());
                }
                StmtKind::ModuleDef { name, params, .. }
                | StmtKind::FunctionDef { name, params, .. } => {
                    self.0.insert(name.name.clone());
                    self.0.extend(params.iter().map(|p| p.name.name.clone()));
                }
                StmtKind::Instance(i) => {
                    if let crate::front::ast::InstanceKind::Call { name, .. } = &i.kind {
                        self.0.insert(name.name.clone());
                    }
                }
                _ => {}
            }
        }
        fn expr(&mut self, e: &'a crate::front::ast::Expr) {
            if let ExprKind::Ident(n) = &e.kind {
                self.0.insert(n.clone());
            }
        }
    }
    let mut n = Names(HashSet::new());
    for p in loaded.programs.values() {
        visit_stmts(&p.stmts, &mut n);
    }
    n.0
}

/// An expression as readable OpenSCAD: `seat_width / 2 - leg_size + 7.5`.
pub fn format_expression(e: &Expression, names: &[String]) -> String {
    use crate::analysis::reparam::Frac;
    let mut out = String::new();
    for &(i, a) in &e.terms {
        let name = &names[i];
        let neg = a < 0.0;
        let m = a.abs();
        let term = match Frac::near(m) {
            Some(f) if f.den == 1 && f.num == 1 => name.clone(),
            Some(f) if f.den == 1 => format!("{} * {name}", f.num),
            Some(f) if f.num == 1 => format!("{name} / {}", f.den),
            Some(f) => format!("{name} * {} / {}", f.num, f.den),
            None => format!("{} * {name}", number(m)),
        };
        if out.is_empty() {
            out = if neg { format!("-{term}") } else { term };
        } else {
            out.push_str(if neg { " - " } else { " + " });
            out.push_str(&term);
        }
    }
    let c = e.constant;
    if out.is_empty() {
        return number(c);
    }
    if number(c) != "0" {
        out.push_str(if c < 0.0 { " - " } else { " + " });
        out.push_str(&number(c.abs()));
    }
    out
}

/// `x` moved rigidly (in slot space) so the model's anchors — centre in x and y, floor in
/// z — are where the input has them: the smallest slot change that shifts every face by
/// the same amount along its axis. Sliders are read in the input's frame; where no slot
/// change translates the whole model, `x` is returned as it is.
fn moved_to_input_anchor(model: &Model, x: &[f64]) -> Vec<f64> {
    let at_input = anchor_rows_at(model, &model.slot_values());
    let here = anchor_rows_at(model, x);
    // anchor(x) − anchor(x0) per axis (x and y centres, z floor).
    let shift: Vec<f64> = here
        .iter()
        .zip(&at_input)
        .map(|(h, i)| h.constant - i.constant)
        .collect();
    if shift.len() != 3 || shift.iter().all(|s| *s == 0.0) {
        return x.to_vec();
    }
    let mut rows: Vec<(Vec<(crate::ir::SlotId, f64)>, f64)> = Vec::new();
    for p in model.parts.iter().filter(|p| p.misaligned.is_none()) {
        let Some(iv) = crate::ir::feature::world_intervals(p) else {
            continue;
        };
        for (a, (lo, hi)) in iv.iter().enumerate() {
            for n in [lo, hi] {
                if let Some(f) = n.affine() {
                    rows.push((f.terms.clone(), shift[a]));
                }
            }
        }
    }
    let (delta, residual) = crate::analysis::linalg::least_norm_solve(&rows, model.slots.len());
    if residual > 1e-6 * model.size().max(1.0) {
        return x.to_vec();
    }
    x.iter().zip(delta.iter()).map(|(a, b)| a + b).collect()
}

/// For each slot, the parts whose geometry depends on it.
fn slot_parts(model: &Model) -> Vec<Vec<usize>> {
    let mut out = vec![Vec::new(); model.slots.len()];
    for (i, p) in model.parts.iter().enumerate() {
        let nums = p.world.m.iter().flatten().chain(match &p.primitive {
            crate::ir::Primitive::Cube { size, .. } => size.iter().collect::<Vec<_>>(),
            crate::ir::Primitive::Cylinder { h, r1, r2, .. } => vec![h, r1, r2],
            crate::ir::Primitive::Sphere { r } => vec![r],
        });
        for n in nums {
            for s in n.deps() {
                if !out[s as usize].contains(&i) {
                    out[s as usize].push(i);
                }
            }
        }
    }
    out
}

/// The previous non-space character before byte `at`, and its offset.
fn prev_char(text: &str, at: usize) -> Option<(usize, char)> {
    text[..at]
        .char_indices()
        .rev()
        .find(|(_, c)| !c.is_whitespace())
}

fn next_char(text: &str, at: usize) -> Option<char> {
    text[at..].chars().find(|c| !c.is_whitespace())
}

/// The text replacing a slot's literal: its expression, taking in a unary minus written in
/// front of the literal, and parenthesised unless the literal stands alone (a vector
/// element, an argument, an assignment's value).
fn replacement(text: &str, span: Span, e: &Expression, names: &[String]) -> (Span, String) {
    let (start, end) = (span.start as usize, span.end as usize);
    let opens = |c: Option<(usize, char)>| {
        c.is_none_or(|(_, c)| matches!(c, '[' | '(' | ',' | '=' | '?' | ':' | '{' | ';'))
    };
    let (from, expr) = match prev_char(text, start) {
        Some((p, '-')) if opens(prev_char(text, p)) => {
            let neg = Expression {
                constant: -e.constant,
                terms: e.terms.iter().map(|&(i, a)| (i, -a)).collect(),
            };
            (p, format_expression(&neg, names))
        }
        _ => (start, format_expression(e, names)),
    };
    let alone = matches!(prev_char(text, from), Some((_, '[' | '(' | ',' | '=')))
        && matches!(next_char(text, end), Some(',' | ']' | ')' | ';'));
    let simple = expr
        .chars()
        .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '.');
    let body = if alone || simple {
        expr
    } else {
        format!("({expr})")
    };
    (Span::new(span.file, from, end), body)
}

/// `a`, `a and b`, `a, b and c`.
fn english_list(items: &[String]) -> String {
    match items {
        [] => String::new(),
        [one] => one.clone(),
        [rest @ .., last] => format!("{} and {last}", rest.join(", ")),
    }
}

/// The outermost statements (in the main file) that make only parts of `group`.
fn guard_statements(model: &Model, group: &[usize], main: usize) -> Option<Vec<Span>> {
    let mut makers: HashMap<Span, BTreeSet<usize>> = HashMap::new();
    for (i, p) in model.parts.iter().enumerate() {
        for s in &p.statements {
            makers.entry(*s).or_default().insert(i);
        }
    }
    let mut out = BTreeSet::new();
    for &p in group {
        let s = model.parts[p]
            .statements
            .iter()
            .find(|s| s.file == main && makers[*s].iter().all(|q| group.contains(q)))?;
        out.insert(*s);
    }
    Some(out.into_iter().collect())
}

fn toggle_name(model: &Model, t: &Toggle, taken: &HashSet<String>) -> (String, String) {
    let names: Vec<&str> = t
        .parts
        .iter()
        .map(|&p| model.parts[p].name.as_str())
        .collect();
    let common: Vec<String> = {
        let first: Vec<&str> = names[0].split('_').collect();
        first
            .into_iter()
            .filter(|w| names.iter().all(|n| n.split('_').any(|x| x == *w)))
            .filter(|w| !w.chars().all(|c| c.is_ascii_digit()))
            .map(str::to_string)
            .collect()
    };
    let base = if common.is_empty() {
        names[0].to_string()
    } else {
        common.join("_")
    };
    let mut name = format!("show_{base}");
    let mut k = 2;
    while taken.contains(&name) {
        name = format!("show_{base}_{k}");
        k += 1;
    }
    let words: Vec<String> = names.iter().map(|n| n.replace('_', " ")).collect();
    let mut description = english_list(&words);
    if let Some(c) = description.get(0..1) {
        description.replace_range(0..1, &c.to_uppercase());
    }
    (name, description)
}

/// Runs the main job on a loaded model.
pub fn reparameterize(
    sources: &SourceMap,
    loaded: &Loaded,
    model: &Model,
    variations: &[Variation],
    options: &Options,
) -> Compiled {
    let d = model.slots.len();
    let raw: Vec<Vec<f64>> = variations.iter().map(|v| v.values.clone()).collect();
    let candidates = find_candidates_for(model, &raw);
    let faces = Faces::of(model);
    let sim = VolumeSimilarity::new(model);
    let optional = optional_parts(model.parts.len(), &raw, &sim);
    // A part a variation does without keeps the model's own shape there, so presets and
    // blends never shrink it to nothing (its switch hides it instead).
    let x0 = model.slot_values();
    let owners = slot_parts(model);
    let values: Vec<Vec<f64>> = raw
        .iter()
        .zip(&optional)
        .map(|(v, skip)| {
            v.iter()
                .enumerate()
                .map(|(s, &val)| {
                    let only_skipped =
                        !owners[s].is_empty() && owners[s].iter().all(|p| skip.contains(p));
                    if only_skipped { x0[s] } else { val }
                })
                .collect()
        })
        .collect();
    let toggle_groups = toggles(model.parts.len(), &optional);
    let (kept_idx, method, chosen_text, cut, curve, noise) = if variations.is_empty() {
        let kept: Vec<usize> = if options.all_constraints {
            (0..candidates.list.len()).collect()
        } else {
            prior::structural_prior(model, &candidates)
        };
        let method = if options.all_constraints {
            "all base constraints (the paper's symbolic baseline)".to_string()
        } else {
            "structural prior: contacts, coaxiality and equal sizes of repeated parts".to_string()
        };
        let text = kept
            .iter()
            .map(|&i| ChosenRelation {
                relation: candidates.describe(&candidates.list[i]),
                tier: None,
                residual: None,
                worst_loss: None,
            })
            .collect();
        (kept, method, text, None, Vec::new(), None)
    } else {
        let samples: Vec<Sample> = values
            .iter()
            .zip(&optional)
            .map(|(v, o)| Sample {
                values: v.clone(),
                optional: o.clone(),
            })
            .collect();
        let tolerance = Tolerance::for_size(model.size());
        let gate = noise_gate(&candidates, &samples, tolerance);
        let tiers = discovery_tiers(model, &candidates, &gate, tolerance);
        let disc = discover(&faces, &candidates, &samples, d, &sim, &tiers);
        let plausible = plausible_steps(&disc.tiers);
        let c = cutoff(&disc.curve, DISTORTION_TOLERANCE, plausible);
        let text = disc
            .order
            .iter()
            .zip(disc.tiers.iter().zip(&disc.worst))
            .map(|(&i, (&t, &w))| ChosenRelation {
                relation: candidates.describe(&candidates.list[i]),
                tier: Some(TIER_NAMES[t as usize]),
                residual: Some(gate.residual[i]),
                worst_loss: Some(w),
            })
            .collect();
        let kept = disc.order[..c.keep].to_vec();
        (
            kept,
            "greedy discovery from variations".to_string(),
            text,
            Some(c),
            disc.curve,
            Some(gate),
        )
    };
    let kept: Vec<Candidate> = kept_idx
        .iter()
        .map(|&i| candidates.list[i].clone())
        .collect();
    let rows: Vec<Affine> = kept.iter().flat_map(|c| c.rows.iter().cloned()).collect();
    let solution = solve(model, &rows);
    // Each variation keeps its own place (anchors at its own centre and floor): rigid moves
    // are not what the sliders express, and the free sizes do not depend on them.
    let projected: Vec<Vec<f64>> = values
        .iter()
        .zip(&optional)
        .map(|(v, o)| {
            let anchors = anchor_rows_at(model, v);
            let all_rows: Vec<&Affine> = rows.iter().chain(anchors.iter()).collect();
            let p = project_onto(&faces, v, &all_rows, o);
            moved_to_input_anchor(model, &p)
        })
        .collect();
    let free_at =
        |x: &[f64]| -> Vec<f64> { solution.free.iter().map(|&f| x[f as usize]).collect() };
    let input_free = free_at(&x0);
    // Projections are exact to round-off; show them to a millionth of the model's size.
    let quantum = 10f64.powf((model.size().max(1e-9)).log10().floor() - 6.0);
    let tidy = |v: f64| (v / quantum).round() * quantum;
    let var_free: Vec<Vec<f64>> = projected
        .iter()
        .map(|p| free_at(p).into_iter().map(tidy).collect())
        .collect();
    let mut taken = identifiers(loaded);
    let names = name_free_variables(model, &solution, &taken);
    taken.extend(names.iter().map(|n| n.name.clone()));
    let slider_ranges = ranges(model, &solution, &input_free, &var_free);
    let name_list: Vec<String> = names.iter().map(|n| n.name.clone()).collect();
    let mut blends = Vec::new();
    for (v, f) in variations.iter().zip(&var_free) {
        let mut name = crate::analysis::names::sanitize(&v.name);
        while taken.contains(&name) {
            name.push_str("_blend");
        }
        taken.insert(name.clone());
        blends.push(Blend {
            name,
            values: f.clone(),
        });
    }
    let mut switches = Vec::new();
    let mut switched: Vec<Toggle> = Vec::new();
    let mut toggle_report = Vec::new();
    for t in &toggle_groups {
        let Some(statements) = guard_statements(model, &t.parts, loaded.main) else {
            continue;
        };
        let (name, parts) = toggle_name(model, t, &taken);
        taken.insert(name.clone());
        let without: Vec<String> = t
            .off_in
            .iter()
            .map(|&j| format!("the {}", variations[j].name.replace('_', " ")))
            .collect();
        let verb = if without.len() == 1 { "does" } else { "do" };
        switches.push(Switch {
            name,
            description: format!("{parts} ({} {verb} without)", english_list(&without)),
            statements,
        });
        toggle_report.push(
            t.parts
                .iter()
                .map(|&p| model.parts[p].name.clone())
                .collect(),
        );
        switched.push(t.clone());
    }
    let text = sources.text(loaded.main);
    let replacements: Vec<(Span, String)> = model
        .slots
        .iter()
        .filter(|s| s.span.file == loaded.main)
        .map(|s| replacement(text, s.span, &solution.exprs[s.id as usize], &name_list))
        .collect();
    let model_name = {
        let stem = sources
            .path(loaded.main)
            .file_stem()
            .map_or("model".into(), |s| s.to_string_lossy().into_owned());
        let mut n = crate::analysis::names::sanitize(&stem);
        while taken.contains(&n) {
            n.push_str("_model");
        }
        n
    };
    let file_name = sources
        .path(loaded.main)
        .file_name()
        .map_or(String::new(), |s| s.to_string_lossy().into_owned());
    let mut summary = vec![format!(
        "Reparameterized by reparamc from {file_name}{}:",
        if variations.is_empty() {
            String::new()
        } else {
            format!(
                " with the variations {}",
                variations
                    .iter()
                    .map(|v| v.name.as_str())
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        }
    )];
    summary.push(format!(
        "{} sliders{} drive all {} numbers and keep {} relations.",
        names.len(),
        if switches.is_empty() {
            String::new()
        } else {
            format!(" and {} part switches", switches.len())
        },
        d,
        kept.len()
    ));
    if !variations.is_empty() {
        summary.push(match &options.presets_name {
            Some(n) => format!("Presets for each variation are in {n}."),
            None => {
                "Presets for each variation are in the parameter-set file beside this one.".into()
            }
        });
    }
    let sliders: Vec<Slider> = names
        .iter()
        .zip(&input_free)
        .zip(&slider_ranges)
        .map(|((n, &v), r)| Slider {
            name: n.name.clone(),
            description: n.description.clone(),
            value: v,
            range: *r,
        })
        .collect();
    let plan = EmitPlan {
        module_name: model_name,
        summary,
        sliders,
        blends,
        switches,
        replacements,
    };
    let scad = emit(sources.text(loaded.main), &plan);
    let presets =
        (!variations.is_empty()).then(|| presets_json(&plan, variations, &var_free, &switched));
    let report = Report {
        model: sources.path(loaded.main).display().to_string(),
        parameter_count: d,
        base_constraint_count: candidates.total(),
        method,
        chosen: chosen_text,
        noise,
        kept_count: kept.len(),
        cutoff: cut,
        distortion_curve: curve,
        dimension: solution.free.len(),
        free_variables: names
            .iter()
            .zip(&solution.free)
            .zip(&input_free)
            .zip(&slider_ranges)
            .map(|(((n, &s), &v), r)| FreeVariableReport {
                name: n.name.clone(),
                slot: model.slots[s as usize].name.clone(),
                description: n.description.clone(),
                value: v,
                range: *r,
            })
            .collect(),
        variations: variations
            .iter()
            .zip(&projected)
            .zip(&optional)
            .map(|((v, p), o)| VariationReport {
                name: v.name.clone(),
                optional_parts: o.iter().map(|&i| model.parts[i].name.clone()).collect(),
                projection_iou: sim.similarity(p, &v.values, o),
            })
            .collect(),
        toggles: toggle_report,
    };
    Compiled {
        scad,
        presets,
        report,
        candidates,
        kept,
        solution,
        projected,
    }
}

/// OpenSCAD's parameter-set file: one set per variation (values as strings).
fn presets_json(
    plan: &EmitPlan,
    variations: &[Variation],
    free: &[Vec<f64>],
    toggles: &[Toggle],
) -> String {
    let mut sets = serde_json::Map::new();
    for (j, v) in variations.iter().enumerate() {
        let mut set = serde_json::Map::new();
        for (i, s) in plan.sliders.iter().enumerate() {
            set.insert(s.name.clone(), number(free[j][i]).into());
        }
        for b in &plan.blends {
            set.insert(b.name.clone(), "0".into());
        }
        for (s, t) in plan.switches.iter().zip(toggles) {
            set.insert(
                s.name.clone(),
                (if t.off_in.contains(&j) {
                    "false"
                } else {
                    "true"
                })
                .into(),
            );
        }
        let key = plan
            .blends
            .get(j)
            .map_or_else(|| v.name.clone(), |b| b.name.clone());
        sets.insert(key, serde_json::Value::Object(set));
    }
    let doc = serde_json::json!({ "fileFormatVersion": "1", "parameterSets": sets });
    serde_json::to_string_pretty(&doc).unwrap_or_default() + "\n"
}
