//! The re-parameterized OpenSCAD file.
//!
//! The output is the input's own text: its leading comment block, then a block of new
//! top-level variables in Customizer tabs (`/* [Shape] */` sliders, `/* [Variations] */`
//! blend weights, `/* [Parts] */` checkboxes, `/* [Hidden] */` the blend), then the body
//! wrapped in one module whose parameters are the (blended) free variables. In the body only
//! literals change — each becomes its expression — and statements of optional parts are
//! prefixed with `if (show_…)`. Order, modules and comments survive.

use super::rewrite::round_for_source;
use crate::analysis::optional::Toggle;
use crate::analysis::ranges::Range;
use crate::front::eval::format_number;
use crate::span::Span;
use std::fmt::Write;

/// One free variable as a slider.
#[derive(Debug, Clone)]
pub struct Slider {
    pub name: String,
    pub description: String,
    pub value: f64,
    pub range: Range,
}

/// One variation as a blend weight, with each slider's value in that variation.
#[derive(Debug, Clone)]
pub struct Blend {
    pub name: String,
    pub values: Vec<f64>,
}

/// One part toggle: a checkbox and the statements it guards.
#[derive(Debug, Clone)]
pub struct Switch {
    pub name: String,
    pub description: String,
    pub statements: Vec<Span>,
    /// The parts it switches and the variations that do without them (for the presets).
    pub toggle: Toggle,
}

/// Everything the emitter writes, decided by the pipeline.
#[derive(Debug, Clone)]
pub struct EmitPlan {
    pub module_name: String,
    /// Lines of the summary comment (without `// `).
    pub summary: Vec<String>,
    pub sliders: Vec<Slider>,
    pub blends: Vec<Blend>,
    pub switches: Vec<Switch>,
    /// Literal spans of the main file and the expression text replacing each.
    pub replacements: Vec<(Span, String)>,
}

/// A number as OpenSCAD source (rounded to 10 significant digits).
pub fn number(v: f64) -> String {
    format_number(round_for_source(v))
}

/// Where the file's leading comment block ends: the comments before the first blank line
/// that precedes any code (a comment directly above the first statement names that statement
/// and stays with it).
fn header_end(text: &str) -> usize {
    let mut at = 0;
    let mut end = 0;
    let mut in_block = false;
    for line in text.split_inclusive('\n') {
        let t = line.trim();
        if in_block {
            in_block = !t.contains("*/");
        } else if t.is_empty() {
            end = at;
        } else if t.starts_with("/*") && !t.starts_with("/* [") {
            in_block = !t.contains("*/");
        } else if !t.starts_with("//") {
            break;
        }
        at += line.len();
    }
    text[..end].trim_end().len()
}

fn variables_block(plan: &EmitPlan, out: &mut String) {
    let _ = writeln!(out, "/* [Shape] */");
    for s in &plan.sliders {
        let _ = writeln!(out, "// {}", s.description);
        let _ = writeln!(
            out,
            "{} = {}; // [{}:{}:{}]",
            s.name,
            number(s.value),
            number(s.range.min),
            number(s.range.step),
            number(s.range.max)
        );
    }
    if !plan.blends.is_empty() {
        let _ = writeln!(out, "\n/* [Variations] */");
        for (i, b) in plan.blends.iter().enumerate() {
            let words = b.name.replace('_', " ");
            if i == 0 {
                let _ = writeln!(
                    out,
                    "// Blend toward the {words} (0 = as set above, 1 = {words})"
                );
            } else {
                let _ = writeln!(out, "// Blend toward the {words}");
            }
            let _ = writeln!(out, "{} = 0; // [0:0.05:1]", b.name);
        }
    }
    if !plan.switches.is_empty() {
        let _ = writeln!(out, "\n/* [Parts] */");
        for s in &plan.switches {
            let _ = writeln!(out, "// {}", s.description);
            let _ = writeln!(out, "{} = true;", s.name);
        }
    }
}

fn call_block(plan: &EmitPlan, out: &mut String) {
    let args: Vec<String> = if plan.blends.is_empty() {
        plan.sliders
            .iter()
            .map(|s| format!("{0} = {0}", s.name))
            .collect()
    } else {
        let _ = writeln!(out, "\n/* [Hidden] */");
        let weights: Vec<&str> = plan.blends.iter().map(|b| b.name.as_str()).collect();
        let _ = writeln!(out, "blend_total = max(1, {});", weights.join(" + "));
        let _ = writeln!(
            out,
            "// A slider's value moved toward each variation by its blend weight."
        );
        let params: Vec<String> = plan
            .blends
            .iter()
            .map(|b| format!("at_{}", b.name))
            .collect();
        let terms: Vec<String> = plan
            .blends
            .iter()
            .map(|b| format!("{0} * (at_{0} - value)", b.name))
            .collect();
        let _ = writeln!(
            out,
            "function toward(value, {}) =\n    value + ({}) / blend_total;",
            params.join(", "),
            terms.join(" + ")
        );
        plan.sliders
            .iter()
            .enumerate()
            .map(|(i, s)| {
                let at: Vec<String> = plan.blends.iter().map(|b| number(b.values[i])).collect();
                format!("{0} = toward({0}, {1})", s.name, at.join(", "))
            })
            .collect()
    };
    let _ = writeln!(out);
    if args.is_empty() {
        let _ = writeln!(out, "{}();", plan.module_name);
    } else {
        let _ = writeln!(out, "{}(\n    {});", plan.module_name, args.join(",\n    "));
    }
}

/// Applies the literal replacements and toggle guards to `text[from..]`.
fn body(text: &str, from: usize, plan: &EmitPlan) -> String {
    let mut edits: Vec<(usize, usize, String)> = plan
        .replacements
        .iter()
        .map(|(s, t)| (s.start as usize, s.end as usize, t.clone()))
        .collect();
    for sw in &plan.switches {
        for s in &sw.statements {
            edits.push((
                s.start as usize,
                s.start as usize,
                format!("if ({}) ", sw.name),
            ));
        }
    }
    // Insertions before replacements at the same place.
    edits.sort_by_key(|(s, e, _)| (*s, *e));
    let mut out = String::with_capacity(text.len() * 2);
    let mut at = from;
    for (s, e, t) in edits {
        if s < at {
            continue;
        }
        out.push_str(&text[at..s]);
        out.push_str(&t);
        at = e;
    }
    out.push_str(&text[at..]);
    out
}

/// The whole output file.
pub fn emit(text: &str, plan: &EmitPlan) -> String {
    let head = header_end(text);
    let mut out = String::new();
    if head > 0 {
        out.push_str(&text[..head]);
        out.push('\n');
    }
    for line in &plan.summary {
        let _ = writeln!(out, "// {line}");
    }
    out.push('\n');
    variables_block(plan, &mut out);
    call_block(plan, &mut out);
    let params: Vec<&str> = plan.sliders.iter().map(|s| s.name.as_str()).collect();
    let _ = writeln!(
        out,
        "\nmodule {}({}) {{",
        plan.module_name,
        params.join(", ")
    );
    let b = body(text, head, plan);
    out.push_str(b.trim_start_matches(['\n', '\r']));
    if !out.ends_with('\n') {
        out.push('\n');
    }
    out.push_str("}\n");
    out
}

#[cfg(test)]
mod tests {
    use super::header_end;

    #[test]
    fn header_is_the_leading_comment_block() {
        let t = "// A chair.\n// by me\n\n// left leg\ncube(1);\n";
        assert_eq!(&t[..header_end(t)], "// A chair.\n// by me");
        assert_eq!(header_end("// left leg\ncube(1);\n"), 0);
    }
}
