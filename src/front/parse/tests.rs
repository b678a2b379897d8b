//! Parser tests: every construct, precedence, spans and comments ([`syntax`]), every
//! error kind ([`errors`]), and robustness: garbage, truncations, deep nesting on a
//! 2 MiB stack ([`robustness`]). This file holds the shared helpers.

mod errors;
mod robustness;
mod syntax;
mod tokens;

use super::*;
use crate::front::ast::{
    Arg, Binding, Expr, ExprKind, Instance, InstanceKind, Param, Stmt, StmtKind, UnaryOp, VecElem,
};
use crate::front::diag::Diagnostic;
use crate::front::source::SourceMap;

// ---------------------------------------------------------------- helpers

fn parse(src: &str) -> Program {
    match parse_program(0, src) {
        Ok(program) => program,
        Err(err) => panic!("{src:?} should parse: {}", render(src, &err)),
    }
}

fn parse_err(src: &str) -> Box<Diagnostic> {
    match parse_program(0, src) {
        Ok(program) => panic!("{src:?} should not parse: {:?}", program.stmts),
        Err(err) => err,
    }
}

fn render(src: &str, err: &Diagnostic) -> String {
    let mut sources = SourceMap::new();
    sources.add("test.scad", src.to_string());
    err.render_plain(&sources)
}

/// The value assigned by `x = <src>;`.
fn expr(src: &str) -> Expr {
    let text = format!("x = {src};");
    match parse(&text).stmts.into_iter().next().map(|s| s.kind) {
        Some(StmtKind::Assign { value, .. }) => value,
        other => panic!("not an assignment: {other:?}"),
    }
}

/// The value of `x = <src>;` as an S-expression.
fn sx(src: &str) -> String {
    sexp(&expr(src))
}

fn sexp(e: &Expr) -> String {
    match &e.kind {
        ExprKind::Number { text, .. } => text.clone(),
        ExprKind::Bool(b) => b.to_string(),
        ExprKind::Str(s) => format!("{s:?}"),
        ExprKind::Undef => "undef".into(),
        ExprKind::Ident(name) => name.clone(),
        ExprKind::Vector(elems) => format!("[{}]", list(elems.iter().map(elem_sexp))),
        ExprKind::Range { start, step, end } => match step {
            Some(step) => format!("[{} : {} : {}]", sexp(start), sexp(step), sexp(end)),
            None => format!("[{} : {}]", sexp(start), sexp(end)),
        },
        ExprKind::Unary(op, x) => format!("({op:?} {})", sexp(x)),
        ExprKind::Binary(op, a, b) => format!("({op:?} {} {})", sexp(a), sexp(b)),
        ExprKind::Ternary(c, a, b) => format!("(? {} {} {})", sexp(c), sexp(a), sexp(b)),
        ExprKind::Index(a, i) => format!("(index {} {})", sexp(a), sexp(i)),
        ExprKind::Member(a, m) => format!("(. {} {})", sexp(a), m.name),
        ExprKind::Call { callee, args } => format!("(call {} {})", sexp(callee), args_sexp(args)),
        ExprKind::Let { bindings, body } => {
            format!("(let {} {})", bindings_sexp(bindings), sexp(body))
        }
        ExprKind::Assert { args, body } => format!("(assert {}{})", args_sexp(args), opt(body)),
        ExprKind::Echo { args, body } => format!("(echo {}{})", args_sexp(args), opt(body)),
        ExprKind::FunctionLiteral { params, body } => {
            format!("(fn {} {})", params_sexp(params), sexp(body))
        }
    }
}

fn elem_sexp(e: &VecElem) -> String {
    match e {
        VecElem::Expr(e) => sexp(e),
        VecElem::For { bindings, body, .. } => {
            format!("(for {} {})", bindings_sexp(bindings), elem_sexp(body))
        }
        VecElem::ForC {
            init,
            cond,
            update,
            body,
            ..
        } => format!(
            "(forc {} {} {} {})",
            bindings_sexp(init),
            sexp(cond),
            bindings_sexp(update),
            elem_sexp(body)
        ),
        VecElem::If {
            cond,
            then,
            otherwise,
            ..
        } => match otherwise {
            Some(o) => format!("(if {} {} {})", sexp(cond), elem_sexp(then), elem_sexp(o)),
            None => format!("(if {} {})", sexp(cond), elem_sexp(then)),
        },
        VecElem::Let { bindings, body, .. } => {
            format!("(lclet {} {})", bindings_sexp(bindings), elem_sexp(body))
        }
        VecElem::Each(body, _) => format!("(each {})", elem_sexp(body)),
    }
}

fn list(items: impl Iterator<Item = String>) -> String {
    items.collect::<Vec<_>>().join(" ")
}

fn opt(body: &Option<Box<Expr>>) -> String {
    body.as_ref()
        .map_or(String::new(), |b| format!(" {}", sexp(b)))
}

fn args_sexp(args: &[Arg]) -> String {
    let items = args.iter().map(|a| match &a.name {
        Some(name) => format!("{}={}", name.name, sexp(&a.value)),
        None => sexp(&a.value),
    });
    format!("({})", list(items))
}

fn bindings_sexp(bindings: &[Binding]) -> String {
    let items = bindings
        .iter()
        .map(|b| format!("{}={}", b.name.name, sexp(&b.value)));
    format!("({})", list(items))
}

fn params_sexp(params: &[Param]) -> String {
    let items = params.iter().map(|p| match &p.default {
        Some(d) => format!("{}={}", p.name.name, sexp(d)),
        None => p.name.name.clone(),
    });
    format!("({})", list(items))
}

/// A statement tree in one line: `call name (args) {children}` and so on.
fn stmt_sexp(s: &Stmt) -> String {
    match &s.kind {
        StmtKind::Empty => ";".into(),
        StmtKind::Block(stmts) => format!("{{{}}}", stmts_sexp(stmts)),
        StmtKind::Assign { name, value } => format!("{} = {}", name.name, sexp(value)),
        StmtKind::ModuleDef { name, params, body } => {
            format!(
                "module {} {} {{{}}}",
                name.name,
                params_sexp(params),
                stmts_sexp(body)
            )
        }
        StmtKind::FunctionDef { name, params, body } => {
            format!(
                "function {} {} {}",
                name.name,
                params_sexp(params),
                sexp(body)
            )
        }
        StmtKind::Include { path, use_, .. } => {
            format!("{} <{path}>", if *use_ { "use" } else { "include" })
        }
        StmtKind::Instance(Instance { modifiers, kind }) => {
            let mut out = String::new();
            for (on, c) in [
                (modifiers.root, '!'),
                (modifiers.highlight, '#'),
                (modifiers.background, '%'),
                (modifiers.disable, '*'),
            ] {
                if on {
                    out.push(c);
                }
            }
            out + &instance_sexp(kind)
        }
    }
}

fn instance_sexp(kind: &InstanceKind) -> String {
    match kind {
        InstanceKind::Call {
            name,
            args,
            children,
        } => format!(
            "{}{} {{{}}}",
            name.name,
            args_sexp(args),
            stmts_sexp(children)
        ),
        InstanceKind::If {
            cond,
            then,
            otherwise,
        } => match otherwise {
            Some(o) => format!(
                "if {} {{{}}} else {{{}}}",
                sexp(cond),
                stmts_sexp(then),
                stmts_sexp(o)
            ),
            None => format!("if {} {{{}}}", sexp(cond), stmts_sexp(then)),
        },
        InstanceKind::For { bindings, body } => {
            format!("for {} {{{}}}", bindings_sexp(bindings), stmts_sexp(body))
        }
        InstanceKind::IntersectionFor { bindings, body } => {
            format!(
                "intersection_for {} {{{}}}",
                bindings_sexp(bindings),
                stmts_sexp(body)
            )
        }
        InstanceKind::Let { bindings, body } => {
            format!("let {} {{{}}}", bindings_sexp(bindings), stmts_sexp(body))
        }
    }
}

fn stmts_sexp(stmts: &[Stmt]) -> String {
    list(stmts.iter().map(stmt_sexp))
}

fn program_sexp(src: &str) -> String {
    stmts_sexp(&parse(src).stmts)
}

fn snippet(src: &str, span: Span) -> &str {
    &src[span.range()]
}

/// Runs `f` on a thread with a 2 MiB stack, the default for spawned threads.
fn on_small_stack(f: impl FnOnce() + Send + 'static) {
    let handle = std::thread::Builder::new()
        .stack_size(2 << 20)
        .spawn(f)
        .expect("spawn test thread");
    handle.join().expect("the test thread panicked");
}

fn primary(err: &Diagnostic) -> (Span, &str) {
    let (span, label) = err.primary.as_ref().expect("a primary label");
    (*span, label.as_str())
}
