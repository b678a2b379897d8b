//! What the emitted file says: the [`EmitPlan`] made from the pipeline's results.
//!
//! Names every new identifier (sliders, blend weights, part switches, the module) so none
//! collides with the program's own identifiers or another new one, writes the descriptions
//! and the summary comment, and turns every slot's literal of the main file into its
//! expression. Invariant: names are taken in one order — sliders, blends, switches, the
//! module — so a program's output never depends on anything but its input.

use super::emit::{Blend, EmitPlan, Slider, Switch};
use super::rewrite::{guard_statements, replacement};
use crate::analysis::names::{
    VariableName, english_list, identifiers, name_free_variables, sanitize, toggle_name,
};
use crate::analysis::optional::Toggle;
use crate::analysis::ranges::Range;
use crate::analysis::reparam::Solution;
use crate::front::load::Loaded;
use crate::front::source::SourceMap;
use crate::ir::Model;
use crate::variation::Variation;
use std::collections::HashSet;

/// Everything the plan is made from.
pub struct PlanInputs<'a> {
    pub sources: &'a SourceMap,
    pub loaded: &'a Loaded,
    pub model: &'a Model,
    pub solution: &'a Solution,
    pub variations: &'a [Variation],
    /// The free variables' values at the input, and in each (projected) variation.
    pub input_free: &'a [f64],
    pub variation_free: &'a [Vec<f64>],
    /// Each free variable's slider range.
    pub ranges: &'a [Range],
    /// The part groups that some variation does without.
    pub toggles: &'a [Toggle],
    /// How many relations were kept.
    pub kept: usize,
    /// The parameter-set file's name, for the summary comment.
    pub presets_name: Option<&'a str>,
}

/// The plan of the output file.
pub fn plan(i: &PlanInputs) -> EmitPlan {
    let mut taken = identifiers(i.loaded);
    let names = name_free_variables(i.model, i.solution, &taken);
    taken.extend(names.iter().map(|n| n.name.clone()));
    let name_list: Vec<String> = names.iter().map(|n| n.name.clone()).collect();
    let blends = blends(i, &mut taken);
    let switches = switches(i, &mut taken);
    let text = i.sources.text(i.loaded.main);
    let replacements = i
        .model
        .slots
        .iter()
        .filter(|s| s.span.file == i.loaded.main)
        .map(|s| replacement(text, s.span, &i.solution.exprs[s.id as usize], &name_list))
        .collect();
    let module_name = module_name(i, &taken);
    let summary = summary(i, names.len(), switches.len());
    EmitPlan {
        module_name,
        summary,
        sliders: sliders(&names, i.input_free, i.ranges),
        blends,
        switches,
        replacements,
    }
}

fn sliders(names: &[VariableName], values: &[f64], ranges: &[Range]) -> Vec<Slider> {
    names
        .iter()
        .zip(values)
        .zip(ranges)
        .map(|((n, &v), r)| Slider {
            name: n.name.clone(),
            description: n.description.clone(),
            value: v,
            range: *r,
        })
        .collect()
}

/// One blend weight per variation, named after it.
fn blends(i: &PlanInputs, taken: &mut HashSet<String>) -> Vec<Blend> {
    let mut blends = Vec::new();
    for (v, f) in i.variations.iter().zip(i.variation_free) {
        let mut name = sanitize(&v.name);
        while taken.contains(&name) {
            name.push_str("_blend");
        }
        taken.insert(name.clone());
        blends.push(Blend {
            name,
            values: f.clone(),
        });
    }
    blends
}

/// One switch per toggle whose parts some statements of the main file make alone.
fn switches(i: &PlanInputs, taken: &mut HashSet<String>) -> Vec<Switch> {
    let mut switches = Vec::new();
    for t in i.toggles {
        let Some(statements) = guard_statements(i.model, &t.parts, i.loaded.main) else {
            continue;
        };
        let (name, parts) = toggle_name(i.model, t, taken);
        taken.insert(name.clone());
        let without: Vec<String> = t
            .off_in
            .iter()
            .map(|&j| format!("the {}", i.variations[j].name.replace('_', " ")))
            .collect();
        let verb = if without.len() == 1 { "does" } else { "do" };
        switches.push(Switch {
            name,
            description: format!("{parts} ({} {verb} without)", english_list(&without)),
            statements,
            toggle: t.clone(),
        });
    }
    switches
}

/// The module the body is wrapped in: the model file's stem.
fn module_name(i: &PlanInputs, taken: &HashSet<String>) -> String {
    let stem = i
        .sources
        .path(i.loaded.main)
        .file_stem()
        .map_or("model".into(), |s| s.to_string_lossy().into_owned());
    let mut n = sanitize(&stem);
    while taken.contains(&n) {
        n.push_str("_model");
    }
    n
}

/// The summary comment's lines.
fn summary(i: &PlanInputs, sliders: usize, switches: usize) -> Vec<String> {
    let file_name = i
        .sources
        .path(i.loaded.main)
        .file_name()
        .map_or(String::new(), |s| s.to_string_lossy().into_owned());
    let mut summary = vec![format!(
        "Reparameterized by reparamc from {file_name}{}:",
        if i.variations.is_empty() {
            String::new()
        } else {
            format!(
                " with the variations {}",
                i.variations
                    .iter()
                    .map(|v| v.name.as_str())
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        }
    )];
    summary.push(format!(
        "{} sliders{} drive all {} numbers and keep {} relations.",
        sliders,
        if switches == 0 {
            String::new()
        } else {
            format!(" and {switches} part switches")
        },
        i.model.slots.len(),
        i.kept
    ));
    if !i.variations.is_empty() {
        summary.push(match i.presets_name {
            Some(n) => format!("Presets for each variation are in {n}."),
            None => {
                "Presets for each variation are in the parameter-set file beside this one.".into()
            }
        });
    }
    summary
}
