//! Generic traversal of the AST.
//!
//! One place knows the shape of every node: [`visit_stmts`] calls back on every statement
//! (with the statements nested in it visited after it) and every expression, so passes that
//! index definitions or name literals do not each repeat the recursion.

use super::ast::{Arg, Binding, Expr, ExprKind, InstanceKind, Param, Stmt, StmtKind, VecElem};

/// Callbacks for [`visit_stmts`]. `enter`/`leave` bracket a statement and what it contains.
pub trait Visitor<'a> {
    fn enter(&mut self, _stmt: &'a Stmt) {}
    fn leave(&mut self, _stmt: &'a Stmt) {}
    fn expr(&mut self, _expr: &'a Expr) {}
}

pub fn visit_stmts<'a>(stmts: &'a [Stmt], v: &mut dyn Visitor<'a>) {
    for s in stmts {
        visit_stmt(s, v);
    }
}

fn visit_stmt<'a>(s: &'a Stmt, v: &mut dyn Visitor<'a>) {
    v.enter(s);
    match &s.kind {
        StmtKind::Empty | StmtKind::Include { .. } => {}
        StmtKind::Block(b) => visit_stmts(b, v),
        StmtKind::Assign { value, .. } => visit_expr(value, v),
        StmtKind::ModuleDef { params, body, .. } => {
            visit_params(params, v);
            visit_stmts(body, v);
        }
        StmtKind::FunctionDef { params, body, .. } => {
            visit_params(params, v);
            visit_expr(body, v);
        }
        StmtKind::Instance(inst) => match &inst.kind {
            InstanceKind::Call { args, children, .. } => {
                visit_args(args, v);
                visit_stmts(children, v);
            }
            InstanceKind::If {
                cond,
                then,
                otherwise,
            } => {
                visit_expr(cond, v);
                visit_stmts(then, v);
                if let Some(o) = otherwise {
                    visit_stmts(o, v);
                }
            }
            InstanceKind::For { bindings, body }
            | InstanceKind::IntersectionFor { bindings, body }
            | InstanceKind::Let { bindings, body } => {
                visit_bindings(bindings, v);
                visit_stmts(body, v);
            }
        },
    }
    v.leave(s);
}

fn visit_params<'a>(params: &'a [Param], v: &mut dyn Visitor<'a>) {
    for p in params {
        if let Some(d) = &p.default {
            visit_expr(d, v);
        }
    }
}

fn visit_args<'a>(args: &'a [Arg], v: &mut dyn Visitor<'a>) {
    for a in args {
        visit_expr(&a.value, v);
    }
}

fn visit_bindings<'a>(bindings: &'a [Binding], v: &mut dyn Visitor<'a>) {
    for b in bindings {
        visit_expr(&b.value, v);
    }
}

pub fn visit_expr<'a>(e: &'a Expr, v: &mut dyn Visitor<'a>) {
    v.expr(e);
    match &e.kind {
        ExprKind::Number { .. }
        | ExprKind::Bool(_)
        | ExprKind::Str(_)
        | ExprKind::Undef
        | ExprKind::Ident(_) => {}
        ExprKind::Vector(elems) => elems.iter().for_each(|el| visit_elem(el, v)),
        ExprKind::Range { start, step, end } => {
            visit_expr(start, v);
            if let Some(s) = step {
                visit_expr(s, v);
            }
            visit_expr(end, v);
        }
        ExprKind::Unary(_, x) | ExprKind::Member(x, _) => visit_expr(x, v),
        ExprKind::Binary(_, a, b) | ExprKind::Index(a, b) => {
            visit_expr(a, v);
            visit_expr(b, v);
        }
        ExprKind::Ternary(c, a, b) => {
            visit_expr(c, v);
            visit_expr(a, v);
            visit_expr(b, v);
        }
        ExprKind::Call { callee, args } => {
            visit_expr(callee, v);
            visit_args(args, v);
        }
        ExprKind::Let { bindings, body } => {
            visit_bindings(bindings, v);
            visit_expr(body, v);
        }
        ExprKind::Assert { args, body } | ExprKind::Echo { args, body } => {
            visit_args(args, v);
            if let Some(b) = body {
                visit_expr(b, v);
            }
        }
        ExprKind::FunctionLiteral { params, body } => {
            visit_params(params, v);
            visit_expr(body, v);
        }
    }
}

fn visit_elem<'a>(el: &'a VecElem, v: &mut dyn Visitor<'a>) {
    match el {
        VecElem::Expr(e) => visit_expr(e, v),
        VecElem::For { bindings, body, .. } | VecElem::Let { bindings, body, .. } => {
            visit_bindings(bindings, v);
            visit_elem(body, v);
        }
        VecElem::ForC {
            init,
            cond,
            update,
            body,
            ..
        } => {
            visit_bindings(init, v);
            visit_expr(cond, v);
            visit_bindings(update, v);
            visit_elem(body, v);
        }
        VecElem::If {
            cond,
            then,
            otherwise,
            ..
        } => {
            visit_expr(cond, v);
            visit_elem(then, v);
            if let Some(o) = otherwise {
                visit_elem(o, v);
            }
        }
        VecElem::Each(x, _) => visit_elem(x, v),
    }
}
