//! Names and descriptions for the free variables.
//!
//! A free variable is named after what it moves, in the order the source is trusted: a
//! kept variable of the author keeps its own name; otherwise the slot's role (`height`,
//! `width`, `radius`, `x`, or the author's argument name) is prefixed with the words shared
//! by what its slots belong to — the author's identifiers and comments
//! (`front::naming`), or, where the source names nothing but the whole model, the part's
//! role in the arrangement ([`roles`]): `left_front_leg.height`, `right_back_leg.height`,
//! … → `leg_height`. Names that would be the same are told apart by the side and order
//! words of their parts (`front_left_wheel_radius`), then by order words alone; never by a
//! counter. Names never collide with an identifier of the program ([`identifiers`]), a
//! keyword, or each other. Part switches are named alike ([`toggle_name`]): `show_` and
//! the words their parts share.

pub mod roles;

use super::optional::Toggle;
use super::prior::BAR_ELONGATION;
use super::reparam::{ContactVariable, Solution};
use crate::front::ast::{Expr, ExprKind, InstanceKind, Stmt, StmtKind};
use crate::front::load::Loaded;
use crate::front::walk::{Visitor, visit_stmts};
use crate::ir::Model;
use crate::tolerance::Tolerance;
use roles::{Label, ordinal, part_labels};
use std::collections::{HashMap, HashSet};

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

/// `name` as an OpenSCAD identifier: transliterated to ASCII (`спинка` → `spinka`), other
/// characters become `_` (runs of them one), and it always has a letter and never starts
/// with a digit.
pub fn sanitize(name: &str) -> String {
    let ascii = deunicode::deunicode(name);
    let mut s = String::with_capacity(ascii.len());
    for c in ascii.chars() {
        let c = if c.is_ascii_alphanumeric() { c } else { '_' };
        if !(c == '_' && s.ends_with('_')) {
            s.push(c);
        }
    }
    let s = s.trim_matches('_');
    if !s.chars().any(|c| c.is_ascii_alphabetic()) {
        return if s.is_empty() {
            "value".into()
        } else {
            format!("value_{s}")
        };
    }
    if s.starts_with(|c: char| c.is_ascii_digit()) {
        format!("p_{s}")
    } else {
        s.to_string()
    }
}

/// `name` without trailing repeat numbers (`height_2` → `height`, `Bed_01_2` → `Bed`,
/// `part7` → `part`).
fn without_counter(name: &str) -> &str {
    let mut t = name;
    loop {
        let u = t
            .trim_end_matches(|c: char| c.is_ascii_digit())
            .trim_end_matches('_');
        if u.len() == t.len() || u.is_empty() {
            return t;
        }
        t = u;
    }
}

/// Whether a part's name says nothing of the part: none, a position (`part7`), or a name
/// every part of the model has (the model's own module).
fn says_nothing(name: &str, whole: Option<&str>) -> bool {
    let base = without_counter(name);
    base.is_empty() || base == "part" || Some(base) == whole
}

/// The name every part has, when there are several parts and they all have it.
fn whole_model_name(model: &Model) -> Option<String> {
    let mut names = model.parts.iter().map(|p| without_counter(&p.name));
    let first = names.next()?;
    (model.parts.len() > 1 && names.all(|n| n == first)).then(|| first.to_string())
}

/// What each slot belongs to, as words: the owner its name gives, or the role and place of
/// its first part where that owner says nothing.
fn slot_owners(model: &Model, labels: &[Label], by_slot: &[Vec<usize>]) -> Vec<String> {
    let whole = whole_model_name(model);
    model
        .slots
        .iter()
        .map(|slot| {
            let (owner, _) = split_name(&slot.name);
            let parts = &by_slot[slot.id as usize];
            let own_part = parts
                .iter()
                .any(|&p| without_counter(&model.parts[p].name) == without_counter(owner));
            let silent = says_nothing(owner, whole.as_deref());
            // Where all its parts are (a literal a loop shares is no one part's).
            let place = common_place(labels, parts);
            match parts.first() {
                Some(&p)
                    if silent
                        || (own_part && says_nothing(&model.parts[p].name, whole.as_deref())) =>
                {
                    // A literal parts of different roles share is named by none of them.
                    let mut w = place.clone();
                    if parts.iter().all(|&q| labels[q].role == labels[p].role) {
                        w.push(labels[p].role.to_string());
                    }
                    w.join("_")
                }
                Some(&p) if own_part => {
                    // The part's own name; where parts elsewhere share it, with the role
                    // (if theirs differ) and the place of its parts.
                    let base = without_counter(owner);
                    let namesakes: Vec<usize> = (0..model.parts.len())
                        .filter(|&q| without_counter(&model.parts[q].name) == base)
                        .collect();
                    let own: Vec<String> = words(owner).iter().map(|s| s.to_string()).collect();
                    let mut w: Vec<String> = Vec::new();
                    if namesakes.len() > 1 {
                        w.extend(place.iter().filter(|x| !own.contains(x)).cloned());
                    }
                    w.extend(own.iter().cloned());
                    let role = labels[p].role.to_string();
                    if namesakes.iter().any(|&q| labels[q].role != labels[p].role)
                        && !own.contains(&role)
                    {
                        w.push(role);
                    }
                    w.join("_")
                }
                _ => words(owner).join("_"),
            }
        })
        .collect()
}

/// The place words every part in `parts` has (in the first part's order).
fn common_place(labels: &[Label], parts: &[usize]) -> Vec<String> {
    let Some(&first) = parts.first() else {
        return Vec::new();
    };
    labels[first]
        .place
        .iter()
        .filter(|w| parts.iter().all(|&p| labels[p].place.contains(w)))
        .cloned()
        .collect()
}

/// `prefix_role`, with a role that repeats the prefix's last word merged (`wheel` and
/// `wheel_radius` → `wheel_radius`).
fn join_name(prefix: &[String], role: &str) -> String {
    let role_words: Vec<&str> = role.split('_').filter(|w| !w.is_empty()).collect();
    let mut p: Vec<&str> = prefix
        .iter()
        .flat_map(|w| w.split('_'))
        .filter(|w| !w.is_empty())
        .collect();
    while let (Some(l), Some(r)) = (p.last(), role_words.first()) {
        if l.eq_ignore_ascii_case(r) {
            p.pop();
        } else {
            break;
        }
    }
    p.extend(role_words);
    p.join("_")
}

/// One free variable before names are made unique.
struct Draft {
    /// The author's variable, kept by name.
    variable: Option<String>,
    prefix: Vec<String>,
    role: String,
    /// Side and order words all the parts it moves share.
    place: Vec<String>,
    /// The words of the owner its slot's name gives (the module, for an argument), to
    /// try before order words.
    source: Vec<String>,
    owners: Vec<String>,
    /// A description that says what the variable is in other words than its role's.
    said: Option<String>,
}

impl Draft {
    fn name(&self, with_place: bool, order: Option<usize>) -> String {
        let mut prefix: Vec<String> = Vec::new();
        if let Some(k) = order {
            prefix.push(ordinal(k));
        }
        if with_place {
            let have: Vec<&str> = self.prefix.iter().flat_map(|p| p.split('_')).collect();
            prefix.extend(
                self.place
                    .iter()
                    .filter(|w| !have.contains(&w.as_str()))
                    .cloned(),
            );
        }
        prefix.extend(self.prefix.iter().cloned());
        sanitize(&join_name(&prefix, &self.role))
    }

    fn description(&self, name: &str) -> String {
        if let Some(said) = &self.said {
            return said.clone();
        }
        let role = role_words(&self.role);
        if let Some(v) = &self.variable {
            return format!("{role} ({v} in the model)");
        }
        let what = name
            .strip_suffix(&self.role)
            .unwrap_or(name)
            .trim_end_matches('_')
            .replace('_', " ");
        let n = self.owners.len();
        if n > 1
            && !common_words(&self.owners.iter().map(String::as_str).collect::<Vec<_>>()).is_empty()
        {
            format!("{role} of every {what} ({n} numbers)")
        } else if n > 1 {
            // Owners without words (a literal parts of different roles share, in no one
            // place) are not named; the description says only that there are others.
            let mut distinct: Vec<String> = Vec::new();
            for o in self.owners.iter().filter(|o| !o.is_empty()) {
                let o = o.replace('_', " ");
                if !distinct.contains(&o) {
                    distinct.push(o);
                }
            }
            if distinct.is_empty() {
                format!("{role} ({n} numbers)")
            } else {
                if self.owners.iter().any(String::is_empty) {
                    distinct.truncate(3);
                    distinct.push("others".into());
                }
                format!("{role} of the {} ({n} numbers)", list_words(&distinct))
            }
        } else if what.is_empty() {
            role
        } else {
            format!("{role} of the {what}")
        }
    }
}

/// The first naming of each free variable: its kept variable, or owner words and role.
fn drafts(model: &Model, sol: &Solution) -> Vec<Draft> {
    let labels = part_labels(model);
    let by_slot = model.parts_by_slot();
    let owners_of = slot_owners(model, &labels, &by_slot);
    sol.free
        .iter()
        .enumerate()
        .map(|(i, &f)| {
            if let Some(c) = sol.contact(i) {
                return contact_draft(model, &labels, c);
            }
            let slot = &model.slots[f as usize];
            let (_, role) = split_name(&slot.name);
            let role = without_counter(role);
            // Slots this variable sets unchanged.
            let group: Vec<usize> = model
                .slots
                .iter()
                .filter(|s| {
                    let e = &sol.exprs[s.id as usize];
                    e.constant == 0.0 && e.terms == [(i, 1.0)]
                })
                .map(|s| s.id as usize)
                .collect();
            // A size that also places parts (a leg's height is the seat's z) is named for
            // the sizes it sets: the places follow from them.
            let sizes: Vec<usize> = group
                .iter()
                .copied()
                .filter(|&s| whole_size(model, s, &by_slot[s]))
                .collect();
            let named = if sizes.is_empty() { group } else { sizes };
            let owners: Vec<String> = named.iter().map(|&s| owners_of[s].clone()).collect();
            let parts: Vec<usize> = named.iter().flat_map(|&s| by_slot[s].clone()).collect();
            let role = group_role(model, &by_slot, &named, role);
            let owner_refs: Vec<&str> = owners.iter().map(String::as_str).collect();
            let own = owners_of[f as usize].as_str();
            let prefix = naming_words(&owner_refs, own);
            Draft {
                variable: slot.variable.clone(),
                prefix: if prefix.is_empty() {
                    Vec::new()
                } else {
                    vec![prefix]
                },
                role,
                place: common_place(&labels, &parts),
                source: words(split_name(&slot.name).0)
                    .iter()
                    .map(|w| w.to_string())
                    .collect(),
                owners,
                said: None,
            }
        })
        .collect()
}

/// A slot's role without a repeat number: `height`, `radius`, `x`, an argument's name.
fn slot_role(model: &Model, slot: usize) -> &str {
    without_counter(split_name(&model.slots[slot].name).1)
}

/// The role of a variable that sets `slots` unchanged (`by_slot`: each slot's parts):
/// theirs when they share one, or the first slot's position axis (`own`) when they are all
/// positions; a part's `thickness` when every slot is the thin side of a board (a seat's
/// height, a shelf's) or the two short sides of a square bar (a leg's width and depth);
/// else `size`.
fn group_role(model: &Model, by_slot: &[Vec<usize>], slots: &[usize], own: &str) -> String {
    let mut roles: Vec<&str> = slots.iter().map(|&s| slot_role(model, s)).collect();
    roles.sort_unstable();
    roles.dedup();
    let sides = roles
        .iter()
        .all(|r| matches!(*r, "width" | "depth" | "height"));
    if sides && roles.len() <= 2 && slots.iter().all(|&s| thin_side(model, s, &by_slot[s])) {
        return "thickness".into();
    }
    match roles.as_slice() {
        [one] => one.to_string(),
        _ if slots.iter().all(|&s| model.slots[s].position) => own.to_string(),
        _ => "size".into(),
    }
}

/// Whether `slot` is a size of each of its parts by itself (a side, or a radius: half a
/// side), not a place nor a term of a longer sum.
fn whole_size(model: &Model, slot: usize, parts: &[usize]) -> bool {
    let tol = Tolerance::for_size(model.size());
    let value = model.slots[slot].value;
    !model.slots[slot].position
        && !parts.is_empty()
        && parts.iter().all(|&p| {
            let (lo, hi) = model.parts[p].world_bounds();
            (0..3).any(|k| {
                let e = hi[k] - lo[k];
                tol.equal(value, e) || tol.equal(2.0 * value, e)
            })
        })
}

/// Whether `slot` is the thickness of each of its parts: its thinnest side, with the next
/// side at least [`BAR_ELONGATION`] times it (a board), or one of two equal short sides
/// with the long one that many times it (a square bar, as the prior's profile).
fn thin_side(model: &Model, slot: usize, parts: &[usize]) -> bool {
    let tol = Tolerance::for_size(model.size());
    let value = model.slots[slot].value;
    !parts.is_empty()
        && parts.iter().all(|&p| {
            let (lo, hi) = model.parts[p].world_bounds();
            let mut e: Vec<f64> = (0..3).map(|k| hi[k] - lo[k]).collect();
            e.sort_by(f64::total_cmp);
            let next = if tol.equal(e[0], e[1]) { e[2] } else { e[1] };
            tol.equal(value, e[0]) && BAR_ELONGATION * e[0] <= next
        })
}

/// A part's words: its own name where it says something, else its role and place.
fn part_words(model: &Model, labels: &[Label], p: usize) -> String {
    let name = &model.parts[p].name;
    if says_nothing(name, whole_model_name(model).as_deref()) {
        labels[p].words().join("_")
    } else {
        words(without_counter(name)).join("_")
    }
}

/// A contact variable: how far the part it places overlaps the other, along an axis.
fn contact_draft(model: &Model, labels: &[Label], c: &ContactVariable) -> Draft {
    let [moved, other] = c.parts.map(|p| part_words(model, labels, p));
    let axis = ["x", "y", "z"][c.axis as usize];
    Draft {
        variable: None,
        prefix: vec![moved.clone(), other.clone()],
        role: format!("overlap_{axis}"),
        place: common_place(labels, &[c.parts[0]]),
        source: Vec::new(),
        owners: vec![moved.clone()],
        said: Some(format!(
            "How far the {} and the {} overlap along {axis} (0 = just touching)",
            moved.replace('_', " "),
            other.replace('_', " ")
        )),
    }
}

/// Names for `sol.free`, avoiding every name in `taken`.
pub fn name_free_variables(
    model: &Model,
    sol: &Solution,
    taken: &HashSet<String>,
) -> Vec<VariableName> {
    let mut used: HashSet<String> = taken.clone();
    used.extend(KEYWORDS.iter().map(|s| s.to_string()));
    let drafts = drafts(model, sol);
    // Kept variables first: they are the author's own names.
    let mut names: Vec<Option<String>> = drafts.iter().map(|d| d.variable.clone()).collect();
    let kept: HashSet<String> = names.iter().flatten().cloned().collect();
    used.extend(kept.iter().cloned());
    // Then plain names, places where two would be the same, the owner's words where a
    // name is the program's, order words last.
    for stage in 0..4 {
        let wanted: Vec<Option<String>> = drafts
            .iter()
            .zip(&names)
            .map(|(d, n)| {
                n.is_none().then(|| match stage {
                    0 => d.name(false, None),
                    1 => d.name(true, None),
                    2 => sanitize(&join_name(&d.source, &d.name(true, None))),
                    _ => String::new(),
                })
            })
            .collect();
        let mut count: HashMap<&str, usize> = HashMap::new();
        for w in wanted.iter().flatten() {
            *count.entry(w.as_str()).or_default() += 1;
        }
        let mut rank: HashMap<String, usize> = HashMap::new();
        for (i, w) in wanted.iter().enumerate() {
            let Some(w) = w else { continue };
            if stage == 3 {
                let base = drafts[i].name(true, None);
                let k = rank.entry(base).or_default();
                let mut name = drafts[i].name(true, Some(*k));
                while used.contains(&name) {
                    *k += 1;
                    name = drafts[i].name(true, Some(*k));
                }
                *k += 1;
                used.insert(name.clone());
                names[i] = Some(name);
            } else if count[w.as_str()] == 1 && !used.contains(w) {
                used.insert(w.clone());
                names[i] = Some(w.clone());
            }
        }
    }
    drafts
        .iter()
        .zip(names)
        .map(|(d, n)| {
            let name = n.unwrap_or_default();
            VariableName {
                description: d.description(&name),
                name,
            }
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

/// A part switch's name (`show_` and the words its parts' names share, with order words
/// past `taken`: `show_second_leg`) and its description (the parts' names in words).
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
        without_counter(first).to_string()
    } else {
        common.join("_")
    };
    let mut name = sanitize(&format!("show_{base}"));
    let mut k = 1;
    while taken.contains(&name) {
        name = sanitize(&format!("show_{}_{base}", ordinal(k)));
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

    fn draft(owners: &[&str]) -> Draft {
        Draft {
            variable: None,
            prefix: Vec::new(),
            role: "carcass_width".into(),
            place: Vec::new(),
            source: Vec::new(),
            owners: owners.iter().map(|o| o.to_string()).collect(),
            said: None,
        }
    }

    #[test]
    fn a_description_names_no_owner_that_has_no_words() {
        // Two module arguments whose parts share neither a role nor a place (a generated
        // family's two bookcase units) had been described "Carcass width of the  (2
        // numbers)".
        let d = draft(&["", ""]).description("unit0_carcass_width");
        assert_eq!(d, "Carcass width (2 numbers)");
        let d = draft(&["side_board", ""]).description("unit0_carcass_width");
        assert_eq!(d, "Carcass width of the side board and others (2 numbers)");
        let d = draft(&["seat", "", "back"]).description("unit0_carcass_width");
        assert_eq!(d, "Carcass width of the seat, back and others (3 numbers)");
        let d = draft(&["seat", "back"]).description("unit0_carcass_width");
        assert_eq!(d, "Carcass width of the seat and back (2 numbers)");
    }
}
