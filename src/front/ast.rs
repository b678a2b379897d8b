//! The OpenSCAD abstract syntax tree.
//!
//! Owns the plain data the parser produces and the evaluator walks. Invariants:
//! every node carries a [`Span`] into the [`SourceMap`](super::source::SourceMap) file it came
//! from; number literals keep their exact source text (the emitter rewrites that text, and a
//! literal's span is its identity as a constructive parameter); comments are kept beside the
//! tree, in source order, so the lowering can name parts and slots after them.

use crate::span::Span;

/// One parsed file: its statements and every comment in it.
#[derive(Debug, Clone, PartialEq)]
pub struct Program {
    pub stmts: Vec<Stmt>,
    pub comments: Vec<Comment>,
}

/// A `//` or `/* */` comment. `text` is the content without the comment markers, trimmed.
#[derive(Debug, Clone, PartialEq)]
pub struct Comment {
    pub span: Span,
    pub text: String,
    pub block: bool,
}

/// A name as written, with where it was written.
#[derive(Debug, Clone, PartialEq)]
pub struct Ident {
    pub name: String,
    pub span: Span,
}

/// The modifier characters in front of an instantiation.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Modifiers {
    /// `!`: only this subtree is rendered.
    pub root: bool,
    /// `#`: highlighted, still geometry.
    pub highlight: bool,
    /// `%`: background, not geometry.
    pub background: bool,
    /// `*`: disabled, not geometry.
    pub disable: bool,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Stmt {
    pub kind: StmtKind,
    /// The whole statement, including modifiers and children.
    pub span: Span,
}

#[derive(Debug, Clone, PartialEq)]
pub enum StmtKind {
    /// `;` on its own.
    Empty,
    /// `{ ... }` at statement level.
    Block(Vec<Stmt>),
    /// `name = value;`
    Assign { name: Ident, value: Expr },
    /// `module name(params) body`
    ModuleDef {
        name: Ident,
        params: Vec<Param>,
        body: Vec<Stmt>,
    },
    /// `function name(params) = body;`
    FunctionDef {
        name: Ident,
        params: Vec<Param>,
        body: Expr,
    },
    /// `include <path>` (`use == false`) or `use <path>` (`use == true`).
    Include {
        path: String,
        path_span: Span,
        use_: bool,
    },
    /// A module instantiation, including the control statements OpenSCAD parses as
    /// instantiations (`if`, `for`, `let`, `intersection_for`, `echo`, `assert`).
    Instance(Instance),
}

#[derive(Debug, Clone, PartialEq)]
pub struct Instance {
    pub modifiers: Modifiers,
    pub kind: InstanceKind,
}

#[derive(Debug, Clone, PartialEq)]
pub enum InstanceKind {
    /// `name(args) child` / `name(args) { children }` / `name(args);`
    Call {
        name: Ident,
        args: Vec<Arg>,
        children: Vec<Stmt>,
    },
    /// `if (cond) then else otherwise`
    If {
        cond: Expr,
        then: Vec<Stmt>,
        otherwise: Option<Vec<Stmt>>,
    },
    /// `for (a = ..., b = ...) body`: nested loops, first binding outermost.
    For {
        bindings: Vec<Binding>,
        body: Vec<Stmt>,
    },
    /// `intersection_for (...) body`
    IntersectionFor {
        bindings: Vec<Binding>,
        body: Vec<Stmt>,
    },
    /// `let (a = ...) body`
    Let {
        bindings: Vec<Binding>,
        body: Vec<Stmt>,
    },
}

/// An argument in a call: positional (`name == None`) or named.
#[derive(Debug, Clone, PartialEq)]
pub struct Arg {
    pub name: Option<Ident>,
    pub value: Expr,
    pub span: Span,
}

/// A parameter in a module or function definition.
#[derive(Debug, Clone, PartialEq)]
pub struct Param {
    pub name: Ident,
    pub default: Option<Expr>,
}

/// `name = value` in `for`, `let` and list comprehensions.
#[derive(Debug, Clone, PartialEq)]
pub struct Binding {
    pub name: Ident,
    pub value: Expr,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Expr {
    pub kind: ExprKind,
    pub span: Span,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum UnaryOp {
    Neg,
    Plus,
    Not,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BinaryOp {
    Add,
    Sub,
    Mul,
    Div,
    Mod,
    Pow,
    Lt,
    Le,
    Gt,
    Ge,
    Eq,
    Ne,
    And,
    Or,
}

#[derive(Debug, Clone, PartialEq)]
pub enum ExprKind {
    /// A number literal; `text` is exactly what the source says (`15`, `0.5`, `1e3`).
    Number {
        value: f64,
        text: String,
    },
    Bool(bool),
    Str(String),
    Undef,
    Ident(String),
    /// `[a, b, for (...) ...]`
    Vector(Vec<VecElem>),
    /// `[start : end]` or `[start : step : end]`
    Range {
        start: Box<Expr>,
        step: Option<Box<Expr>>,
        end: Box<Expr>,
    },
    Unary(UnaryOp, Box<Expr>),
    Binary(BinaryOp, Box<Expr>, Box<Expr>),
    Ternary(Box<Expr>, Box<Expr>, Box<Expr>),
    /// `v[i]`
    Index(Box<Expr>, Box<Expr>),
    /// `v.x`, `v.y`, `v.z`
    Member(Box<Expr>, Ident),
    /// `f(args)`; the callee is usually an identifier.
    Call {
        callee: Box<Expr>,
        args: Vec<Arg>,
    },
    /// `let (bindings) body`
    Let {
        bindings: Vec<Binding>,
        body: Box<Expr>,
    },
    /// `assert(args) body` (body may be absent)
    Assert {
        args: Vec<Arg>,
        body: Option<Box<Expr>>,
    },
    /// `echo(args) body` (body may be absent)
    Echo {
        args: Vec<Arg>,
        body: Option<Box<Expr>>,
    },
    /// `function (params) body`
    FunctionLiteral {
        params: Vec<Param>,
        body: Box<Expr>,
    },
}

/// An element of a vector literal, which may be a list comprehension.
#[derive(Debug, Clone, PartialEq)]
pub enum VecElem {
    Expr(Expr),
    /// `for (bindings) elem`
    For {
        bindings: Vec<Binding>,
        body: Box<VecElem>,
        span: Span,
    },
    /// `for (init; cond; update) elem` (C-style)
    ForC {
        init: Vec<Binding>,
        cond: Expr,
        update: Vec<Binding>,
        body: Box<VecElem>,
        span: Span,
    },
    /// `if (cond) elem [else elem]`
    If {
        cond: Expr,
        then: Box<VecElem>,
        otherwise: Option<Box<VecElem>>,
        span: Span,
    },
    /// `let (bindings) elem`
    Let {
        bindings: Vec<Binding>,
        body: Box<VecElem>,
        span: Span,
    },
    /// `each elem`
    Each(Box<VecElem>, Span),
}
