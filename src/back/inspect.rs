//! `reparamc inspect`: what the compiler sees in a model, as tables or JSON.
//!
//! Builds one serialisable [`Inspection`] from a model and its candidates; the text form
//! prints the same data as aligned tables. Nothing here computes analysis results: it only
//! presents them.

use crate::analysis::{Candidates, RelationKind};
use crate::front::source::SourceMap;
use crate::ir::feature::AXIS_NAMES;
use crate::ir::{FreezeReason, Model, Primitive};
use crate::span::Span;
use serde::Serialize;
use std::fmt::Write;

#[derive(Debug, Serialize)]
pub struct Location {
    pub file: String,
    pub line: usize,
    pub column: usize,
}

impl Location {
    fn of(sources: &SourceMap, span: Span) -> Self {
        let (line, column) = sources.line_col(span.file, span.start as usize);
        Location {
            file: sources.path(span.file).display().to_string(),
            line,
            column,
        }
    }
}

impl std::fmt::Display for Location {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}:{}:{}", self.file, self.line, self.column)
    }
}

#[derive(Debug, Serialize)]
pub struct SlotRow {
    pub id: u32,
    pub name: String,
    pub value: f64,
    pub text: String,
    pub location: Location,
}

#[derive(Debug, Serialize)]
pub struct PartRow {
    pub index: usize,
    pub name: String,
    pub kind: String,
    /// The axis of a cylinder or cone (`x`, `y`, `z`), if it lies on one.
    pub axis: Option<String>,
    pub min: [f64; 3],
    pub max: [f64; 3],
    pub location: Location,
    /// Why the part offers no relations, if it does not.
    pub no_relations_because: Option<String>,
}

#[derive(Debug, Serialize)]
pub struct FrozenRow {
    pub text: String,
    pub value: f64,
    pub location: Location,
    pub reason: String,
}

#[derive(Debug, Serialize)]
pub struct RelationRow {
    pub kind: RelationKind,
    pub a: String,
    pub b: String,
    pub text: String,
}

#[derive(Debug, Serialize)]
pub struct Inspection {
    pub file: String,
    pub parameter_count: usize,
    pub base_constraint_count: usize,
    pub constraint_counts: std::collections::BTreeMap<RelationKind, usize>,
    /// Tangencies of round parts' sides: beyond the paper's kinds, not in its count.
    #[serde(skip_serializing_if = "is_zero")]
    pub tangent_count: usize,
    /// Mirror symmetries, equal spacings and equal insets of placements: beyond the paper's
    /// kinds too.
    #[serde(skip_serializing_if = "is_zero")]
    pub placement_count: usize,
    /// Extents twice another (`proportion`): beyond the paper's kinds too.
    #[serde(skip_serializing_if = "is_zero")]
    pub proportion_count: usize,
    /// Pairs of features driven by the very same numbers (instances of one module or loop
    /// body): counted above, but they hold for every setting and are not listed.
    pub identical_by_construction: usize,
    pub tolerance: f64,
    pub slots: Vec<SlotRow>,
    pub parts: Vec<PartRow>,
    pub frozen: Vec<FrozenRow>,
    pub constraints: Vec<RelationRow>,
}

fn cylinder_axis(model: &Model, i: usize) -> Option<String> {
    let p = &model.parts[i];
    if !matches!(p.primitive, Primitive::Cylinder { .. }) {
        return None;
    }
    let perm = p.world.axis_permutation()?;
    perm.iter()
        .position(|&j| j == 2)
        .map(|a| AXIS_NAMES[a].to_string())
}

pub fn inspect(sources: &SourceMap, model: &Model, candidates: &Candidates) -> Inspection {
    let slots = model
        .slots
        .iter()
        .map(|s| SlotRow {
            id: s.id,
            name: s.name.clone(),
            value: s.value,
            text: s.text.clone(),
            location: Location::of(sources, s.span),
        })
        .collect();
    let parts = model
        .parts
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let (min, max) = p.world_bounds();
            let reason = match &p.misaligned {
                Some(m) => Some(format!("{} ({})", m.reason, sources.location(m.span))),
                None if p.world.axis_permutation().is_none() => {
                    Some("its transform is not axis-aligned".to_string())
                }
                None => None,
            };
            PartRow {
                index: i,
                name: p.name.clone(),
                kind: p.primitive.kind_name().to_string(),
                axis: cylinder_axis(model, i),
                min,
                max,
                location: Location::of(sources, p.span),
                no_relations_because: reason,
            }
        })
        .collect();
    let frozen = model
        .frozen
        .iter()
        .map(|f| FrozenRow {
            text: f.text.clone(),
            value: f.value,
            location: Location::of(sources, f.span),
            reason: match &f.reason {
                FreezeReason::Structural(w) => format!("decides structure: {w}"),
                FreezeReason::Product(w) => w.clone(),
            },
        })
        .collect();
    let constraints = candidates
        .list
        .iter()
        .map(|c| RelationRow {
            kind: c.kind,
            a: candidates.features[c.a].label.clone(),
            b: candidates.features[c.b].label.clone(),
            text: candidates.describe(c),
        })
        .collect();
    Inspection {
        file: sources.path(0).display().to_string(),
        parameter_count: model.slots.len(),
        base_constraint_count: candidates.total(),
        tangent_count: candidates.count(RelationKind::Tangent),
        placement_count: candidates.count(RelationKind::Symmetric)
            + candidates.count(RelationKind::Spaced)
            + candidates.count(RelationKind::Inset),
        proportion_count: candidates.count(RelationKind::Proportional),
        constraint_counts: RelationKind::PAPER
            .iter()
            .map(|&k| (k, candidates.count(k)))
            .collect(),
        identical_by_construction: candidates.identical.values().sum(),
        tolerance: candidates.tolerance.epsilon,
        slots,
        parts,
        frozen,
        constraints,
    }
}

/// Left-aligned columns separated by two spaces.
fn table(header: &[&str], rows: &[Vec<String>]) -> String {
    let mut widths: Vec<usize> = header.iter().map(|h| h.chars().count()).collect();
    for r in rows {
        for (w, c) in widths.iter_mut().zip(r) {
            *w = (*w).max(c.chars().count());
        }
    }
    let mut out = String::new();
    let line = |cells: &[String], out: &mut String| {
        let mut s = String::new();
        for (i, (c, w)) in cells.iter().zip(&widths).enumerate() {
            if i + 1 == cells.len() {
                s.push_str(c);
            } else {
                let _ = write!(s, "{c:<w$}  ");
            }
        }
        out.push_str(s.trim_end());
        out.push('\n');
    };
    line(
        &header.iter().map(|h| h.to_string()).collect::<Vec<_>>(),
        &mut out,
    );
    line(
        &widths.iter().map(|&w| "-".repeat(w)).collect::<Vec<_>>(),
        &mut out,
    );
    for r in rows {
        line(r, &mut out);
    }
    out
}

fn num(v: f64) -> String {
    crate::front::eval::format_number(v)
}

fn vec3(v: [f64; 3]) -> String {
    format!("[{}, {}, {}]", num(v[0]), num(v[1]), num(v[2]))
}

impl Inspection {
    /// The machine-readable form: pretty JSON ending in a newline.
    pub fn to_json(&self) -> serde_json::Result<String> {
        serde_json::to_string_pretty(self).map(|s| s + "\n")
    }

    /// The human-readable form: a summary line, then one table per section.
    pub fn to_text(&self) -> String {
        let mut out = String::new();
        let counts: Vec<String> = self
            .constraint_counts
            .iter()
            .map(|(k, n)| format!("{n} {}", k.name()))
            .collect();
        let _ = writeln!(
            out,
            "{}: {} parameters, {} parts, {} base constraints ({})\n",
            self.file,
            self.parameter_count,
            self.parts.len(),
            self.base_constraint_count,
            counts.join(", ")
        );
        let _ = writeln!(out, "Parameters");
        let rows: Vec<Vec<String>> = self
            .slots
            .iter()
            .map(|s| {
                vec![
                    s.id.to_string(),
                    s.name.clone(),
                    num(s.value),
                    s.location.to_string(),
                ]
            })
            .collect();
        out.push_str(&table(&["#", "name", "value", "at"], &rows));
        let _ = writeln!(out, "\nParts");
        let rows: Vec<Vec<String>> = self
            .parts
            .iter()
            .map(|p| {
                vec![
                    p.index.to_string(),
                    p.name.clone(),
                    match &p.axis {
                        Some(a) => format!("{} along {a}", p.kind),
                        None => p.kind.clone(),
                    },
                    vec3(p.min),
                    vec3(p.max),
                    p.location.to_string(),
                ]
            })
            .collect();
        out.push_str(&table(&["#", "name", "kind", "min", "max", "at"], &rows));
        let off: Vec<&PartRow> = self
            .parts
            .iter()
            .filter(|p| p.no_relations_because.is_some())
            .collect();
        if !off.is_empty() {
            let _ = writeln!(out, "\nParts with exact geometry but no relations");
            for p in off {
                let _ = writeln!(
                    out,
                    "  {}: {}",
                    p.name,
                    p.no_relations_because.as_deref().unwrap_or("")
                );
            }
        }
        if !self.frozen.is_empty() {
            let _ = writeln!(out, "\nFrozen numbers (not parameters)");
            let rows: Vec<Vec<String>> = self
                .frozen
                .iter()
                .map(|f| vec![f.text.clone(), f.location.to_string(), f.reason.clone()])
                .collect();
            out.push_str(&table(&["literal", "at", "why"], &rows));
        }
        let _ = writeln!(
            out,
            "\nRelations that hold ({})",
            self.base_constraint_count
                + self.tangent_count
                + self.placement_count
                + self.proportion_count
        );
        if self.identical_by_construction > 0 {
            let _ = writeln!(
                out,
                "  ({} of them pair features driven by the very same numbers, such as instances of one\n  module or loop body; they hold for every setting and are not listed)",
                self.identical_by_construction
            );
        }
        for kind in RelationKind::ALL {
            let of_kind: Vec<&RelationRow> =
                self.constraints.iter().filter(|c| c.kind == kind).collect();
            if of_kind.is_empty() {
                continue;
            }
            let _ = writeln!(out, "  {} ({})", kind.name(), of_kind.len());
            for c in of_kind {
                let _ = writeln!(out, "    {}", c.text);
            }
        }
        out
    }
}

fn is_zero(n: &usize) -> bool {
    *n == 0
}
