//! Names and descriptions for the free variables.
//!
//! A free variable is named after what it moves. A top-level variable keeps its own name;
//! otherwise the slot's role (`height`, `width`, `radius`, `x`) is prefixed with the words
//! shared by the parts whose slot it drives unchanged (`left_front_leg.height`,
//! `right_back_leg.height`, … → `leg_height`). Names never collide with an identifier of
//! the program ([`identifiers`]), a keyword, or each other. Part switches are named alike
//! ([`toggle_name`]): `show_` and the words their parts share.

use super::optional::Toggle;
use super::reparam::Solution;
use crate::front::ast::{Expr, ExprKind, InstanceKind, Stmt, StmtKind};
use crate::front::load::Loaded;
use crate::front::walk::{Visitor, visit_stmts};
use crate::ir::Model;
use std::collections::HashSet;

/// A free variable's name and a one-line description for the Customizer.
#[derive(Debug, Clone, PartialEq)]
pub struct VariableName {
    pub name: String,
    pub description: String,
}

const KEYWORDS: &[&str] = &[
    "module",
    "function",
    "if",
    "else",
    "for",
    "let",
    "each",
    "true",
    "false",
    "undef",
    "include",
    "use",
    "intersection_for",
    "assert",
    "echo",
    "PI",
];

fn split_name(slot_name: &str) -> (&str, &str) {
    slot_name.rsplit_once('.').unwrap_or(("", slot_name))
}

/// Words of a part name without a trailing repeat number (`leg_2` → `leg`).
fn words(owner: &str) -> Vec<&str> {
    let mut w: Vec<&str> = owner.split('_').filter(|s| !s.is_empty()).collect();
    if w.len() > 1
        && w.last()
            .is_some_and(|s| s.chars().all(|c| c.is_ascii_digit()))
    {
        w.pop();
    }
    w
}

/// The words every owner has, in the first owner's order.
fn common_words(owners: &[&str]) -> Vec<String> {
    let Some(first) = owners.first() else {
        return Vec::new();
    };
    words(first)
        .into_iter()
        .filter(|w| owners.iter().all(|o| words(o).contains(w)))
        .map(str::to_string)
        .collect()
}

/// The words naming a group of owners: those all share, else the word most of them have,
/// else the variable's own part.
fn naming_words(owners: &[&str], own: &str) -> String {
    let common = common_words(owners);
    if !common.is_empty() {
        return common.join("_");
    }
    let mut counts: Vec<(&str, usize)> = Vec::new();
    for o in owners {
        let mut ws = words(o);
        ws.dedup();
        for w in ws {
            match counts.iter_mut().find(|(x, _)| *x == w) {
                Some(c) => c.1 += 1,
                None => counts.push((w, 1)),
            }
        }
    }
    match counts.iter().max_by_key(|(_, n)| *n) {
        Some((w, n)) if 2 * n > owners.len() => w.to_string(),
        _ => words(own).join("_"),
    }
}

/// At most four names in words: `seat, back and 3 more`.
fn list_words(items: &[String]) -> String {
    let mut unique: Vec<&String> = Vec::new();
    for i in items {
        if !unique.contains(&i) {
            unique.push(i);
        }
    }
    match unique.len() {
        0 => String::new(),
        1 => unique[0].clone(),
        n if n <= 4 => format!(
            "{} and {}",
            unique[..n - 1]
                .iter()
                .map(|s| s.as_str())
                .collect::<Vec<_>>()
                .join(", "),
            unique[n - 1]
        ),
        n => format!(
            "{} and {} more",
            unique[..3]
                .iter()
                .map(|s| s.as_str())
                .collect::<Vec<_>>()
                .join(", "),
            n - 3
        ),
    }
}

fn role_words(role: &str) -> String {
    match role {
        "width" => "Width (x)".into(),
        "depth" => "Depth (y)".into(),
        "height" => "Height (z)".into(),
        "x" | "y" | "z" => format!("Position in {role}"),
        "size" => "Size".into(),
        other => capitalized(other.replace('_', " ")),
    }
}

/// `text` with its first letter upper-case.
fn capitalized(mut text: String) -> String {
    if let Some(c) = text.get(0..1) {
        text.replace_range(0..1, &c.to_uppercase());
    }
    text
}

/// `name` as an OpenSCAD identifier (other characters become `_`).
pub fn sanitize(name: &str) -> String {
    let mut s: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect();
    if s.is_empty() || s.starts_with(|c: char| c.is_ascii_digit()) {
        s.insert_str(0, "p_");
    }
    s
}

/// Names for `sol.free`, avoiding every name in `taken`.
pub fn name_free_variables(
    model: &Model,
    sol: &Solution,
    taken: &HashSet<String>,
) -> Vec<VariableName> {
    let mut used: HashSet<String> = taken.clone();
    used.extend(KEYWORDS.iter().map(|s| s.to_string()));
    sol.free
        .iter()
        .enumerate()
        .map(|(i, &f)| {
            let slot = &model.slots[f as usize];
            let (owner, role) = split_name(&slot.name);
            // Slots this variable sets unchanged.
            let group: Vec<(&str, &str)> = model
                .slots
                .iter()
                .filter(|s| {
                    let e = &sol.exprs[s.id as usize];
                    e.constant == 0.0 && e.terms == [(i, 1.0)]
                })
                .map(|s| split_name(&s.name))
                .collect();
            let owners: Vec<&str> = group.iter().map(|g| g.0).collect();
            let same_role = group.iter().all(|g| g.1 == role);
            let role = if same_role || matches!(role, "x" | "y" | "z") {
                role
            } else {
                "size"
            };
            let (base, description) = match &slot.variable {
                Some(v) => (
                    v.clone(),
                    format!("{} ({v} in the model)", role_words(role)),
                ),
                None => {
                    let prefix = naming_words(&owners, owner);
                    let what = if owners.len() > 1 && !common_words(&owners).is_empty() {
                        format!(
                            "of every {} ({} numbers)",
                            prefix.replace('_', " "),
                            owners.len()
                        )
                    } else if owners.len() > 1 {
                        let mut distinct: Vec<String> =
                            owners.iter().map(|o| words(o).join(" ")).collect();
                        distinct.dedup();
                        format!(
                            "of the {} ({} numbers)",
                            list_words(&distinct),
                            owners.len()
                        )
                    } else {
                        format!("of the {}", prefix.replace('_', " "))
                    };
                    let base = if prefix.is_empty() {
                        role.to_string()
                    } else {
                        format!("{prefix}_{role}")
                    };
                    (base, format!("{} {what}", role_words(role)))
                }
            };
            let mut name = sanitize(&base);
            if used.contains(&name) && slot.variable.as_deref() != Some(name.as_str()) {
                let mut k = 2;
                while used.contains(&format!("{name}_{k}")) {
                    k += 1;
                }
                name = format!("{name}_{k}");
            }
            used.insert(name.clone());
            VariableName { name, description }
        })
        .collect()
}

/// Every identifier the program uses (variables, parameters, functions, modules): the
/// names a new variable must not take.
pub fn identifiers(loaded: &Loaded) -> HashSet<String> {
    struct Names(HashSet<String>);
    impl<'a> Visitor<'a> for Names {
        fn enter(&mut self, s: &'a Stmt) {
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
                    if let InstanceKind::Call { name, .. } = &i.kind {
                        self.0.insert(name.name.clone());
                    }
                }
                _ => {}
            }
        }
        fn expr(&mut self, e: &'a Expr) {
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

/// `a`, `a and b`, `a, b and c`.
pub fn english_list(items: &[String]) -> String {
    match items {
        [] => String::new(),
        [one] => one.clone(),
        [rest @ .., last] => format!("{} and {last}", rest.join(", ")),
    }
}

/// A part switch's name (`show_` and the words its parts' names share, numbered past
/// `taken`) and its description (the parts' names in words).
pub fn toggle_name(model: &Model, t: &Toggle, taken: &HashSet<String>) -> (String, String) {
    let names: Vec<&str> = t
        .parts
        .iter()
        .map(|&p| model.parts[p].name.as_str())
        .collect();
    let first = names.first().copied().unwrap_or_default();
    let common: Vec<String> = first
        .split('_')
        .filter(|w| names.iter().all(|n| n.split('_').any(|x| x == *w)))
        .filter(|w| !w.chars().all(|c| c.is_ascii_digit()))
        .map(str::to_string)
        .collect();
    let base = if common.is_empty() {
        first.to_string()
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
    (name, capitalized(english_list(&words)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shared_words_name_a_group() {
        let owners = [
            "left_front_leg",
            "right_front_leg",
            "left_back_leg",
            "right_back_leg",
        ];
        assert_eq!(common_words(&owners), vec!["leg"]);
        assert_eq!(common_words(&["leg", "leg_2", "leg_3"]), vec!["leg"]);
    }
}
