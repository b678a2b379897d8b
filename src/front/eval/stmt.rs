//! Statements: scopes, assignments, module instantiation and control flow.
//!
//! A statement list is evaluated as OpenSCAD does: `include`d files are spliced in, module
//! and function definitions are visible in the whole list, assignments run first and in
//! order (a name assigned twice keeps its first position and its last value), then the
//! instantiations run in order, each yielding at most one [`CsgNode`].

use super::scope::Scope;
use super::value::Value;
use super::{Ctx, Eval, MAX_CALL_DEPTH};
use crate::front::ast::{Arg, Expr, Instance, InstanceKind, Stmt, StmtKind};
use crate::front::diag::{DResult, Diagnostic};
use crate::ir::CsgNode;
use crate::span::Span;
use std::rc::Rc;

/// The children of a module instance, evaluated where `children()` is called.
pub struct Children<'a> {
    pub stmts: &'a [Stmt],
    pub scope: Rc<Scope>,
    pub ctx: Ctx<'a>,
}

/// Modules OpenSCAD has that reparamc does not evaluate, with the reason shown to users.
fn unsupported_module(name: &str) -> Option<&'static str> {
    Some(match name {
        "hull" | "minkowski" => {
            "its result is not a union of boxes and cylinders, so its features cannot be tracked exactly"
        }
        "linear_extrude" | "rotate_extrude" => "extrusions of 2-D shapes are not supported yet",
        "polyhedron" => "polyhedra have no box or cylinder features to relate",
        "import" | "surface" => "geometry read from other files has no parameters to track",
        "text" => "text has no box or cylinder features to relate",
        "square" | "circle" | "polygon" | "projection" | "offset" => {
            "2-D shapes are not supported yet"
        }
        "resize" => "`resize` depends on the bounding box of its children; use `scale` instead",
        "render" | "group" => return None,
        _ => return None,
    })
}

impl<'a> Eval<'a> {
    /// Evaluates a statement list in `scope` (which the caller created for it).
    pub fn block(
        &mut self,
        stmts: &'a [Stmt],
        scope: &Rc<Scope>,
        ctx: &Ctx<'a>,
    ) -> DResult<Vec<CsgNode>> {
        let mut flat: Vec<&'a Stmt> = Vec::new();
        self.flatten(stmts, scope, &mut flat, 0)?;
        self.hoist_definitions(&flat, scope);
        self.run_assignments(&flat, scope)?;
        let mut nodes = Vec::new();
        for stmt in flat {
            if let Some(node) = self.statement(stmt, scope, ctx)? {
                nodes.push(node);
            }
        }
        Ok(nodes)
    }

    /// Splices `include`d files in and imports `use`d files' definitions.
    fn flatten(
        &mut self,
        stmts: &'a [Stmt],
        scope: &Rc<Scope>,
        out: &mut Vec<&'a Stmt>,
        depth: usize,
    ) -> DResult<()> {
        for s in stmts {
            match &s.kind {
                StmtKind::Include {
                    path_span, use_, ..
                } => {
                    let Some(file) = self.loaded.includes.get(path_span).copied() else {
                        continue;
                    };
                    let program = &self.loaded.programs[&file];
                    if *use_ {
                        let home = self.file_scope(file)?;
                        self.hoist_into(&program.stmts, scope, Some(home));
                    } else {
                        if depth > 64 {
                            return Err(Box::new(
                                Diagnostic::error("E0402", "files include each other without end")
                                    .at(*path_span, "this include is more than 64 levels deep"),
                            ));
                        }
                        self.flatten(&program.stmts, scope, out, depth + 1)?;
                    }
                }
                _ => out.push(s),
            }
        }
        Ok(())
    }

    /// The top-level scope of a `use`d file (its own variables and definitions), made once.
    fn file_scope(&mut self, file: usize) -> DResult<Rc<Scope>> {
        if let Some(s) = self.used_scopes.get(&file) {
            return Ok(s.clone());
        }
        let program = &self.loaded.programs[&file];
        let scope = Scope::root();
        self.used_scopes.insert(file, scope.clone());
        let mut flat = Vec::new();
        self.flatten(&program.stmts, &scope, &mut flat, 0)?;
        self.hoist_definitions(&flat, &scope);
        self.run_assignments(&flat, &scope)?;
        Ok(scope)
    }

    fn hoist_definitions(&mut self, stmts: &[&'a Stmt], scope: &Rc<Scope>) {
        for s in stmts {
            self.hoist_one(s, scope, None);
        }
    }

    fn hoist_into(&mut self, stmts: &'a [Stmt], scope: &Rc<Scope>, home: Option<Rc<Scope>>) {
        for s in stmts {
            self.hoist_one(s, scope, home.clone());
        }
    }

    fn hoist_one(&mut self, s: &Stmt, scope: &Rc<Scope>, home: Option<Rc<Scope>>) {
        match &s.kind {
            StmtKind::ModuleDef { .. } => {
                if let Some(d) = self.defs.modules.get(&s.span) {
                    scope.define_module(d.clone(), home);
                }
            }
            StmtKind::FunctionDef { .. } => {
                if let Some(d) = self.defs.functions.get(&s.span) {
                    scope.define_function(d.clone(), home);
                }
            }
            _ => {}
        }
    }

    /// Runs the assignments of a statement list: first position, last value.
    fn run_assignments(&mut self, stmts: &[&'a Stmt], scope: &Rc<Scope>) -> DResult<()> {
        let mut order: Vec<(&'a str, &'a Expr)> = Vec::new();
        for s in stmts {
            if let StmtKind::Assign { name, value } = &s.kind {
                match order.iter_mut().find(|(n, _)| *n == name.name) {
                    Some(slot) => slot.1 = value,
                    None => order.push((&name.name, value)),
                }
            }
        }
        for (name, value) in order {
            let v = self.expr(value, scope)?;
            scope.set(name, v);
        }
        Ok(())
    }

    fn statement(
        &mut self,
        stmt: &'a Stmt,
        scope: &Rc<Scope>,
        ctx: &Ctx<'a>,
    ) -> DResult<Option<CsgNode>> {
        self.chain.push(stmt.span);
        let r = match &stmt.kind {
            StmtKind::Block(inner) => {
                let s = Scope::child(scope);
                let ctx = self.named_ctx(stmt, ctx);
                self.block(inner, &s, &ctx).map(group)
            }
            StmtKind::Instance(inst) => {
                let ctx = self.named_ctx(stmt, ctx);
                self.instance(stmt, inst, scope, &ctx)
            }
            _ => Ok(None),
        };
        self.chain.pop();
        r
    }

    /// The context with the statement's comment as the part name and its `color()` name,
    /// if it has them.
    fn named_ctx(&self, stmt: &Stmt, ctx: &Ctx<'a>) -> Ctx<'a> {
        let mut ctx = ctx.clone();
        if let Some(name) = self.naming.statement_name(stmt.span) {
            ctx.name = Some(name);
        }
        if let Some(color) = self.naming.color_name(stmt.span) {
            ctx.color = Some(color);
        }
        ctx
    }

    fn instance(
        &mut self,
        stmt: &'a Stmt,
        inst: &'a Instance,
        scope: &Rc<Scope>,
        ctx: &Ctx<'a>,
    ) -> DResult<Option<CsgNode>> {
        let m = inst.modifiers;
        if m.disable {
            return Ok(None);
        }
        let mut ctx = ctx.clone();
        ctx.highlight |= m.highlight;
        ctx.background |= m.background;
        let node = self.instance_kind(stmt, &inst.kind, scope, &ctx)?;
        if m.root && self.root.is_none() {
            self.root = Some(node.clone().unwrap_or(CsgNode::Union(Vec::new())));
        }
        if m.background {
            return Ok(None);
        }
        Ok(node)
    }

    fn instance_kind(
        &mut self,
        stmt: &'a Stmt,
        kind: &'a InstanceKind,
        scope: &Rc<Scope>,
        ctx: &Ctx<'a>,
    ) -> DResult<Option<CsgNode>> {
        match kind {
            InstanceKind::Call {
                name,
                args,
                children,
            } => self.call_module(&name.name, name.span, args, children, stmt.span, scope, ctx),
            InstanceKind::If {
                cond,
                then,
                otherwise,
            } => {
                let c = self.expr(cond, scope)?;
                let body = if self.condition(&c, "an `if` condition") {
                    Some(then)
                } else {
                    otherwise.as_ref()
                };
                match body {
                    Some(b) => {
                        let s = Scope::child(scope);
                        Ok(group(self.block(b, &s, ctx)?))
                    }
                    None => Ok(None),
                }
            }
            InstanceKind::For { bindings, body }
            | InstanceKind::IntersectionFor { bindings, body } => {
                let mut nodes = Vec::new();
                self.for_each_binding(bindings, scope, &mut |ev, inner| {
                    let s = Scope::child(inner);
                    if let Some(n) = group(ev.block(body, &s, ctx)?) {
                        nodes.push(n);
                    }
                    Ok(())
                })?;
                if matches!(kind, InstanceKind::IntersectionFor { .. }) {
                    return Ok((!nodes.is_empty()).then_some(CsgNode::Intersection(nodes)));
                }
                Ok((!nodes.is_empty()).then_some(CsgNode::Union(nodes)))
            }
            InstanceKind::Let { bindings, body } => {
                let inner = self.let_scope(bindings, scope)?;
                let s = Scope::child(&inner);
                Ok(group(self.block(body, &s, ctx)?))
            }
        }
    }

    #[allow(clippy::too_many_arguments)]
    fn call_module(
        &mut self,
        name: &str,
        name_span: Span,
        args: &'a [Arg],
        children: &'a [Stmt],
        span: Span,
        scope: &Rc<Scope>,
        ctx: &Ctx<'a>,
    ) -> DResult<Option<CsgNode>> {
        if let Some((def, home)) = scope.lookup_module(name) {
            return self.call_user_module(&def, &home, args, children, span, scope, ctx);
        }
        if let Some(node) = self.builtin_module(name, args, children, span, scope, ctx)? {
            return Ok(node);
        }
        if let Some(why) = unsupported_module(name) {
            return Err(Box::new(
                Diagnostic::error("E0201", format!("`{name}` is not supported yet"))
                    .at(name_span, "unsupported module")
                    .with_note(format!(
                        "reparamc models boxes, cylinders and spheres; {why}"
                    )),
            ));
        }
        let mut d = Diagnostic::warning("W0202", format!("unknown module `{name}`")).at(
            name_span,
            "no module of this name is defined: nothing is drawn here",
        );
        if let Some(s) = super::suggest(name, &scope.visible_modules()) {
            d = d.with_note(format!("help: a module with a similar name exists: `{s}`"));
        }
        self.warnings.push(d.with_note(super::AS_OPENSCAD));
        Ok(None)
    }

    #[allow(clippy::too_many_arguments)]
    fn call_user_module(
        &mut self,
        def: &Rc<super::scope::ModuleDefn>,
        home: &Rc<Scope>,
        args: &'a [Arg],
        children: &'a [Stmt],
        span: Span,
        scope: &Rc<Scope>,
        ctx: &Ctx<'a>,
    ) -> DResult<Option<CsgNode>> {
        let inner = self.bind_params(&def.params, args, &def.name, "module", home, scope)?;
        inner.set("$children", Value::constant(children.len() as f64));
        self.depth += 1;
        if self.depth > MAX_CALL_DEPTH {
            self.depth -= 1;
            return Err(Box::new(
                Diagnostic::error("E0301", format!("recursion without end in module `{}`", def.name))
                    .at(span, format!("more than {MAX_CALL_DEPTH} nested module calls"))
                    .with_secondary(def.name_span, "module defined here")
                    .with_note("help: make sure every recursive call moves toward a case that does not recurse"),
            ));
        }
        // The body lives as long as the definitions table, which outlives this run.
        let defs: &'a super::scope::Defs = self.defs;
        let body: &'a [Stmt] = defs
            .modules
            .get(&def.span)
            .map_or(&[], |d| d.body.as_slice());
        let mut body_ctx = ctx.clone();
        body_ctx.module = Some(def.name.clone());
        body_ctx.children = Some(Rc::new(Children {
            stmts: children,
            scope: scope.clone(),
            ctx: ctx.clone(),
        }));
        let r = self.block(body, &inner, &body_ctx);
        self.depth -= 1;
        Ok(group(r?))
    }

    /// `children()`, `children(i)`, `children([i, j])`, `children([a:b])`.
    pub fn children(
        &mut self,
        args: &'a [Arg],
        scope: &Rc<Scope>,
        ctx: &Ctx<'a>,
    ) -> DResult<Option<CsgNode>> {
        let Some(ch) = ctx.children.clone() else {
            return Ok(None);
        };
        let selected: Vec<usize> = match args.first() {
            None => (0..ch.stmts.len()).collect(),
            Some(a) => {
                let v = self.expr(&a.value, scope)?;
                let items = match &v {
                    Value::Num(_) => vec![v.clone()],
                    other => self.iteration_values(other),
                };
                items
                    .iter()
                    .filter_map(|i| i.as_num().map(|n| n.value))
                    .filter(|i| *i >= 0.0)
                    .map(|i| i as usize)
                    .filter(|&i| i < ch.stmts.len())
                    .collect()
            }
        };
        let mut child_ctx = ch.ctx.clone();
        child_ctx.transform = ctx.transform.clone();
        child_ctx.misaligned = ctx.misaligned.clone();
        child_ctx.highlight = ctx.highlight;
        child_ctx.background = ctx.background;
        let mut nodes = Vec::new();
        for i in selected {
            let s = Scope::child(&ch.scope);
            nodes.extend(self.block(std::slice::from_ref(&ch.stmts[i]), &s, &child_ctx)?);
        }
        Ok(group(nodes))
    }

    /// `echo(...)` and `assert(...)` as statements, with their children.
    pub fn echo_assert(
        &mut self,
        name: &str,
        args: &'a [Arg],
        children: &'a [Stmt],
        span: Span,
        scope: &Rc<Scope>,
        ctx: &Ctx<'a>,
    ) -> DResult<Option<CsgNode>> {
        if name == "assert" {
            self.assert(args, span, scope)?;
        } else {
            for a in args {
                self.expr(&a.value, scope)?;
            }
        }
        let s = Scope::child(scope);
        Ok(group(self.block(children, &s, ctx)?))
    }
}

/// One node for a list of nodes: nothing, the node itself, or their union.
pub fn group(mut nodes: Vec<CsgNode>) -> Option<CsgNode> {
    match nodes.len() {
        0 => None,
        1 => nodes.pop(),
        _ => Some(CsgNode::Union(nodes)),
    }
}
