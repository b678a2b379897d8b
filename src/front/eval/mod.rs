//! Evaluation: a parsed program in, an IR [`Model`] out.
//!
//! The program is run as OpenSCAD runs it; every number literal is a candidate slot. A run
//! records which literals must be frozen — those deciding structure (conditions, loop
//! bounds, rotation angles, `$fn`) and those multiplying another slot-dependent factor in a
//! feature a relation needs — and the program is run again with them as constants until
//! nothing new is frozen. Then the literals that reach geometry become the model's slots.

mod builtins;
mod expr;
mod finite;
mod modules;
mod scope;
mod stmt;
mod value;

pub use self::value::format_number;

use self::scope::{Defs, FunctionDefn, ModuleDefn, Scope};
use self::stmt::Children;
use self::value::Value;
use super::ast::{ExprKind, StmtKind};
use super::diag::{DResult, Diagnostic};
use super::load::Loaded;
use super::naming::Naming;
use super::source::SourceMap;
use super::walk::{Visitor, visit_stmts};
use crate::ir::part::Misalignment;
use crate::ir::{CsgNode, FreezeReason, FrozenLiteral, Model, Num, Part, Slot, SlotId, Transform};
use crate::span::{FileId, Span};
use std::collections::{BTreeMap, HashMap};
use std::rc::Rc;

/// How deep module and function calls may nest before we call it endless recursion.
pub const MAX_CALL_DEPTH: usize = 1000;

/// How many expressions one pass may evaluate before the model counts as too large (a
/// mistyped loop bound, or exponential recursion, would otherwise run for hours).
pub const MAX_STEPS: u64 = 5_000_000;

/// How many parts a model may have.
pub const MAX_PARTS: usize = 100_000;

/// The note on a warning where reparamc goes on as OpenSCAD does.
const AS_OPENSCAD: &str = "OpenSCAD 2021.01 warns and goes on; so does reparamc";

/// How many freeze-and-rerun rounds evaluation may take.
const MAX_PASSES: usize = 64;

/// What evaluation produced: the model and any warnings.
#[derive(Debug)]
pub struct Evaluated {
    pub model: Model,
    pub warnings: Vec<Diagnostic>,
}

/// The geometric context of a statement: where it is, what names it, what `children()` is.
#[derive(Clone)]
pub struct Ctx<'a> {
    pub transform: Rc<Transform>,
    pub misaligned: Option<Misalignment>,
    pub highlight: bool,
    pub background: bool,
    /// The innermost comment naming a statement around here.
    pub name: Option<String>,
    /// The innermost user module being instantiated.
    pub module: Option<String>,
    /// The innermost `color("name")` around here.
    pub color: Option<String>,
    pub children: Option<Rc<Children<'a>>>,
}

impl Ctx<'_> {
    fn root() -> Self {
        Ctx {
            transform: Rc::new(Transform::identity()),
            misaligned: None,
            highlight: false,
            background: false,
            name: None,
            module: None,
            color: None,
            children: None,
        }
    }

    /// The name a part made here gets, in the order the source is trusted: the comment
    /// naming a statement around it, the module making it, its colour (empty: named by
    /// position later).
    pub fn part_name(&self) -> String {
        self.name
            .clone()
            .or_else(|| self.module.clone())
            .or_else(|| self.color.clone())
            .unwrap_or_default()
    }
}

/// Every literal seen, across passes: its id, and which are frozen.
#[derive(Default)]
pub struct Literals {
    by_span: HashMap<Span, SlotId>,
    spans: Vec<Span>,
    values: Vec<f64>,
    named: Vec<bool>,
    /// Named by any of the author's identifiers (see `Slot::authored`).
    authored: Vec<bool>,
    frozen: BTreeMap<SlotId, FreezeReason>,
}

impl Literals {
    pub fn is_named(&self, id: SlotId) -> bool {
        self.named.get(id as usize).copied().unwrap_or(false)
    }

    fn is_authored(&self, id: SlotId) -> bool {
        self.authored.get(id as usize).copied().unwrap_or(false)
    }
}

/// What names a slot: the owner (if known yet), the role in its name, and the geometric
/// role (`x`, `width`, `radius`, …) of its first use.
#[derive(Debug, Clone)]
pub struct SlotRole {
    pub owner: Option<String>,
    pub name: String,
    pub geometric: String,
}

/// The state of one evaluation pass.
pub struct Eval<'a> {
    sources: &'a SourceMap,
    loaded: &'a Loaded,
    defs: &'a Defs,
    naming: &'a Naming,
    lits: &'a mut Literals,
    new_freezes: Vec<(SlotId, FreezeReason)>,
    parts: Vec<Part>,
    background: Vec<Part>,
    root: Option<CsgNode>,
    depth: usize,
    /// The statements being executed, outermost first (recorded on each part).
    chain: Vec<Span>,
    /// Expressions evaluated in this pass (see [`MAX_STEPS`]).
    steps: u64,
    used_scopes: HashMap<FileId, Rc<Scope>>,
    /// Per slot: what names it and what it sets.
    slot_roles: HashMap<SlotId, SlotRole>,
    warnings: Vec<Diagnostic>,
    /// Where the latest non-finite number was made (a literal like `1e999`, or an
    /// operation on finite numbers like `0/0`), for the diagnostic when one reaches geometry.
    nonfinite_origin: Option<Span>,
}

impl Eval<'_> {
    /// The number a literal evaluates to: a slot, or a constant once frozen.
    fn literal(&mut self, span: Span, value: f64) -> Num {
        let next = self.lits.spans.len() as SlotId;
        let id = *self.lits.by_span.entry(span).or_insert(next);
        if id == next {
            self.lits.spans.push(span);
            self.lits.values.push(value);
            self.lits.named.push(self.naming.variable(span).is_some());
            self.lits.authored.push(
                self.naming.variable(span).is_some() || self.naming.source_name(span).is_some(),
            );
        }
        if self.lits.frozen.contains_key(&id) {
            Num::constant(value)
        } else {
            Num::slot(id, value)
        }
    }

    /// Freezes every slot `n` depends on: its value decides structure.
    fn freeze_num(&mut self, n: &Num, why: &str) {
        for s in n.deps() {
            if !self.lits.frozen.contains_key(&s) {
                self.new_freezes
                    .push((s, FreezeReason::Structural(why.to_string())));
            }
        }
    }

    fn freeze_value(&mut self, v: &Value, why: &str) {
        match v {
            Value::Num(n) => self.freeze_num(n, why),
            Value::Vector(items) => items.iter().for_each(|x| self.freeze_value(x, why)),
            Value::Range(r) => {
                for n in [&r.start, &r.step, &r.end] {
                    self.freeze_num(n, why);
                }
            }
            _ => {}
        }
    }

    /// Records what the slots of `n` set, for naming them (first use wins): the author's
    /// identifiers for the literal if it has them, else the context naming it and `role`.
    fn name_slots(&mut self, n: &Num, role: &str, owner: Option<String>) {
        if let Some(a) = n.affine() {
            for s in a.slots() {
                let span = self.lits.spans[s as usize];
                let (context, name) = match self.naming.source_name(span) {
                    Some(src) => (
                        Some(src.owner.clone()).filter(|o| !o.is_empty()),
                        src.role.clone().unwrap_or_else(|| role.to_string()),
                    ),
                    None => (
                        self.naming
                            .literal_context(span)
                            .map(str::to_string)
                            .or_else(|| owner.clone().filter(|o| !o.is_empty())),
                        role.to_string(),
                    ),
                };
                self.slot_roles.entry(s).or_insert(SlotRole {
                    owner: context,
                    name,
                    geometric: role.to_string(),
                });
            }
        }
    }
}

/// The closest name within a small edit distance, for "did you mean" notes.
pub fn suggest(name: &str, candidates: &[String]) -> Option<String> {
    let limit = (name.chars().count() / 3).max(1);
    candidates
        .iter()
        .filter(|c| c.as_str() != name)
        .map(|c| (edit_distance(name, c), c))
        .filter(|(d, _)| *d <= limit)
        .min_by_key(|(d, c)| (*d, (*c).clone()))
        .map(|(_, c)| c.clone())
}

fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut cur = vec![i + 1; b.len() + 1];
        for (j, &cb) in b.iter().enumerate() {
            cur[j + 1] = (prev[j] + usize::from(ca != cb))
                .min(prev[j + 1] + 1)
                .min(cur[j] + 1);
        }
        prev = cur;
    }
    prev[b.len()]
}

/// Indexes every module, function and function literal of every file, once.
fn build_defs(loaded: &Loaded) -> Defs {
    struct Indexer(Defs);
    impl<'a> Visitor<'a> for Indexer {
        fn enter(&mut self, s: &'a super::ast::Stmt) {
            match &s.kind {
                StmtKind::ModuleDef { name, params, body } => {
                    self.0.modules.insert(
                        s.span,
                        Rc::new(ModuleDefn {
                            span: s.span,
                            name: name.name.clone(),
                            name_span: name.span,
                            params: params.clone(),
                            body: body.clone(),
                        }),
                    );
                }
                StmtKind::FunctionDef { name, params, body } => {
                    self.0.functions.insert(
                        s.span,
                        Rc::new(FunctionDefn {
                            name: name.name.clone(),
                            params: params.clone(),
                            body: body.clone(),
                        }),
                    );
                }
                _ => {}
            }
        }
        fn expr(&mut self, e: &'a super::ast::Expr) {
            if let ExprKind::FunctionLiteral { params, body } = &e.kind {
                self.0.functions.insert(
                    e.span,
                    Rc::new(FunctionDefn {
                        name: "function literal".into(),
                        params: params.clone(),
                        body: (**body).clone(),
                    }),
                );
            }
        }
    }
    let mut ix = Indexer(Defs::default());
    for program in loaded.programs.values() {
        visit_stmts(&program.stmts, &mut ix);
    }
    ix.0
}

/// Runs the program to a fixed point of frozen literals and builds the model.
pub fn evaluate(sources: &SourceMap, loaded: &Loaded) -> DResult<Evaluated> {
    let defs = build_defs(loaded);
    let naming = Naming::new(sources, &loaded.programs, loaded.main);
    let mut lits = Literals::default();
    let mut pass = 0;
    loop {
        pass += 1;
        let mut ev = Eval {
            sources,
            loaded,
            defs: &defs,
            naming: &naming,
            lits: &mut lits,
            new_freezes: Vec::new(),
            parts: Vec::new(),
            background: Vec::new(),
            root: None,
            depth: 0,
            steps: 0,
            chain: Vec::new(),
            used_scopes: HashMap::new(),
            slot_roles: HashMap::new(),
            warnings: Vec::new(),
            nonfinite_origin: None,
        };
        let program = &loaded.programs[&loaded.main];
        let nodes = ev.block(&program.stmts, &Scope::root(), &Ctx::root())?;
        if let Some(root) = ev.root.take() {
            // `!`: only that subtree is the model.
            let (parts, csg) = keep_only(std::mem::take(&mut ev.parts), &root);
            ev.parts = parts;
            ev.root = Some(csg);
        }
        let csg = ev.root.take().unwrap_or(CsgNode::Union(nodes));
        ev.freeze_products();
        let Eval {
            new_freezes,
            parts,
            background,
            slot_roles,
            warnings,
            ..
        } = ev;
        let warnings = all_warnings(loaded, warnings);
        if parts.is_empty() {
            return Err(Box::new(draws_nothing(sources, loaded, &warnings)));
        }
        if new_freezes.is_empty() || pass >= MAX_PASSES {
            let model = build_model(sources, &lits, parts, background, csg, slot_roles);
            return Ok(Evaluated { model, warnings });
        }
        for (s, why) in new_freezes {
            lits.frozen.entry(s).or_insert(why);
        }
    }
}

/// The loader's warnings, then evaluation's, each (code and place) once: a loop body
/// warns on every turn.
fn all_warnings(loaded: &Loaded, evaluated: Vec<Diagnostic>) -> Vec<Diagnostic> {
    let mut seen = std::collections::HashSet::new();
    loaded
        .warnings
        .iter()
        .cloned()
        .chain(evaluated)
        .filter(|d| seen.insert((d.code, d.primary.as_ref().map(|(s, _)| *s))))
        .collect()
}

/// The error for a model without a part: the warnings that may say why are shown in it.
fn draws_nothing(sources: &SourceMap, loaded: &Loaded, warnings: &[Diagnostic]) -> Diagnostic {
    let main = Span::new(loaded.main, 0, 0);
    let mut d = Diagnostic::error("E0500", "the model draws nothing")
        .at(main, "no cube, cylinder or sphere is made by this file");
    for w in warnings.iter().take(8) {
        if let Some((span, _)) = &w.primary {
            d = d.with_secondary(*span, format!("warning: {}", w.message));
        }
    }
    match crate::front::call::module_only_help(sources, loaded) {
        Some(help) => d.with_note(help),
        None => d.with_note("reparamc re-parameterizes solids; a model needs at least one primitive that is not `%` or `*`"),
    }
}

impl Eval<'_> {
    /// Asks to freeze the inner factor of every product inside a relation's feature or a
    /// part's own numbers.
    fn freeze_products(&mut self) {
        let mut asks = Vec::new();
        for (i, part) in self.parts.iter().enumerate() {
            if part.misaligned.is_some() {
                continue;
            }
            for f in crate::ir::feature::part_features(part, i).unwrap_or_default() {
                for n in &f.nums {
                    asks.extend(n.freeze_to_make_affine().iter().copied());
                }
            }
            // The numbers a part is made of (its matrix and its primitive's sizes) must be
            // affine too, or the part cannot be evaluated at another setting of the slots.
            for n in part.numbers() {
                asks.extend(n.freeze_to_make_affine().iter().copied());
            }
        }
        asks.sort_unstable();
        asks.dedup();
        for s in asks {
            if !self.lits.frozen.contains_key(&s) {
                let why = "it multiplies another parameter (a size under a `scale`, or a product in an expression)";
                self.new_freezes
                    .push((s, FreezeReason::Product(why.into())));
            }
        }
    }
}

/// The parts below `root`, renumbered in order, and `root` with the new numbers.
fn keep_only(parts: Vec<Part>, root: &CsgNode) -> (Vec<Part>, CsgNode) {
    let kept = root.parts();
    let new_index: HashMap<usize, usize> = kept.iter().enumerate().map(|(n, &o)| (o, n)).collect();
    fn renumber(node: &CsgNode, map: &HashMap<usize, usize>) -> CsgNode {
        match node {
            CsgNode::Part(i) => CsgNode::Part(map[i]),
            CsgNode::Union(c) => CsgNode::Union(c.iter().map(|n| renumber(n, map)).collect()),
            CsgNode::Difference(c) => {
                CsgNode::Difference(c.iter().map(|n| renumber(n, map)).collect())
            }
            CsgNode::Intersection(c) => {
                CsgNode::Intersection(c.iter().map(|n| renumber(n, map)).collect())
            }
        }
    }
    let csg = renumber(root, &new_index);
    let mut parts: Vec<Option<Part>> = parts.into_iter().map(Some).collect();
    let kept_parts = kept
        .iter()
        .filter_map(|&i| parts.get_mut(i).and_then(Option::take))
        .collect();
    (kept_parts, csg)
}

fn part_nums(p: &Part) -> Vec<&Num> {
    let mut v: Vec<&Num> = p.world.m.iter().flatten().collect();
    match &p.primitive {
        crate::ir::Primitive::Cube { size, .. } => v.extend(size.iter()),
        crate::ir::Primitive::Cylinder { h, r1, r2, .. } => v.extend([h, r1, r2]),
        crate::ir::Primitive::Sphere { r } => v.push(r),
    }
    v
}

fn remap_part(p: &Part, map: &dyn Fn(SlotId) -> Option<SlotId>) -> Part {
    let mut q = p.clone();
    for row in q.world.m.iter_mut() {
        for n in row.iter_mut() {
            *n = n.remap(map);
        }
    }
    q.primitive = match &p.primitive {
        crate::ir::Primitive::Cube { size, center } => crate::ir::Primitive::Cube {
            size: size.each_ref().map(|n| n.remap(map)),
            center: *center,
        },
        crate::ir::Primitive::Cylinder { h, r1, r2, center } => crate::ir::Primitive::Cylinder {
            h: h.remap(map),
            r1: r1.remap(map),
            r2: r2.remap(map),
            center: *center,
        },
        crate::ir::Primitive::Sphere { r } => crate::ir::Primitive::Sphere { r: r.remap(map) },
    };
    q
}

/// Makes names unique by numbering repeats: `leg`, `leg_2`, `leg_3`.
fn dedupe(names: &mut [String]) {
    let mut seen: std::collections::HashSet<String> = names.iter().cloned().collect();
    let mut first: std::collections::HashSet<String> = std::collections::HashSet::new();
    let mut next: HashMap<String, usize> = HashMap::new();
    for n in names.iter_mut() {
        if first.insert(n.clone()) {
            continue;
        }
        let k = next.entry(n.clone()).or_insert(2);
        while seen.contains(&format!("{n}_{k}")) {
            *k += 1;
        }
        let fresh = format!("{n}_{k}");
        *k += 1;
        seen.insert(fresh.clone());
        *n = fresh;
    }
}

fn build_model(
    sources: &SourceMap,
    lits: &Literals,
    mut parts: Vec<Part>,
    background: Vec<Part>,
    csg: CsgNode,
    roles: HashMap<SlotId, SlotRole>,
) -> Model {
    let mut part_names: Vec<String> = parts
        .iter()
        .enumerate()
        .map(|(i, p)| {
            if p.name.is_empty() {
                format!("part{}", i + 1)
            } else {
                p.name.clone()
            }
        })
        .collect();
    dedupe(&mut part_names);
    for (p, n) in parts.iter_mut().zip(&part_names) {
        p.name = n.clone();
    }
    // Live slots: literals that reach geometry and are not frozen, in source order.
    let mut first_part: BTreeMap<SlotId, usize> = BTreeMap::new();
    for (i, p) in parts.iter().enumerate() {
        for n in part_nums(p) {
            for s in n.deps() {
                first_part.entry(s).or_insert(i);
            }
        }
    }
    let mut live: Vec<SlotId> = first_part
        .keys()
        .copied()
        .filter(|s| !lits.frozen.contains_key(s))
        .collect();
    live.sort_by_key(|&s| lits.spans[s as usize]);
    let dense: HashMap<SlotId, SlotId> = live
        .iter()
        .enumerate()
        .map(|(i, &s)| (s, i as SlotId))
        .collect();
    let map = |s: SlotId| dense.get(&s).copied();
    let mut names: Vec<String> = live
        .iter()
        .map(|&s| {
            let span = lits.spans[s as usize];
            if let Some(v) = naming_variable(lits, s, sources, span) {
                return v;
            }
            let (owner, role) = roles.get(&s).map_or((None, "value".into()), |r| {
                (r.owner.clone(), r.name.clone())
            });
            let owner = owner.unwrap_or_else(|| part_names[first_part[&s]].clone());
            format!("{owner}.{role}")
        })
        .collect();
    dedupe(&mut names);
    let slots = live
        .iter()
        .zip(names)
        .enumerate()
        .map(|(i, (&s, name))| {
            let span = lits.spans[s as usize];
            let role = roles.get(&s).map_or("value", |r| r.geometric.as_str());
            Slot {
                id: i as SlotId,
                position: matches!(role, "x" | "y" | "z"),
                variable: lits.is_named(s).then(|| name.clone()),
                authored: lits.is_authored(s),
                name,
                value: lits.values[s as usize],
                span,
                text: sources.snippet(span).to_string(),
            }
        })
        .collect();
    let frozen = lits
        .frozen
        .iter()
        .map(|(&s, why)| {
            let span = lits.spans[s as usize];
            FrozenLiteral {
                span,
                text: sources.snippet(span).to_string(),
                value: lits.values[s as usize],
                reason: why.clone(),
            }
        })
        .collect::<Vec<_>>();
    let mut frozen = frozen;
    frozen.sort_by_key(|f| f.span);
    Model {
        slots,
        parts: parts.iter().map(|p| remap_part(p, &map)).collect(),
        csg,
        frozen,
        background: background.iter().map(|p| remap_part(p, &map)).collect(),
    }
}

/// The variable a literal is the whole value of, read back from the source.
fn naming_variable(lits: &Literals, s: SlotId, sources: &SourceMap, span: Span) -> Option<String> {
    if !lits.is_named(s) {
        return None;
    }
    // The assignment is `name = [-]literal`: the name is the identifier before `=`.
    let text = sources.text(span.file);
    let before = text.get(..span.start as usize)?;
    let eq = before.rfind('=')?;
    let name = before[..eq].trim_end();
    let start = name
        .rfind(|c: char| !(c.is_alphanumeric() || c == '_' || c == '$'))
        .map_or(0, |i| i + 1);
    Some(name[start..].to_string())
}
