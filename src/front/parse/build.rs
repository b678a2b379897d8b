//! From pest's parse tree to the AST.
//!
//! The builder recurses over the pairs; `parse::check_depth` has already bounded their
//! nesting, and flat chains (`a+b+c`, `--x`, `a^b^c`, `f(x)[i].y`) are checked here against
//! [`MAX_DEPTH`] before the tree they fold into is built. Spans are tight: pest lets a rule
//! that ends in an optional part swallow the blanks and comments after it, so every span
//! is trimmed back to the last token (see [`Builder::span`]).

use super::{MAX_DEPTH, Rule, SYNTAX_ERROR, too_deep};
use crate::front::ast::{
    Arg, BinaryOp, Binding, Comment, Expr, ExprKind, Ident, Instance, InstanceKind, Modifiers,
    Param, Stmt, StmtKind, UnaryOp, VecElem,
};
use crate::front::diag::{DResult, Diagnostic};
use crate::front::source::{FileId, Span};
use pest::iterators::{Pair, Pairs};

type P<'i> = Pair<'i, Rule>;

/// Turns pairs of one file into AST nodes.
pub(super) struct Builder<'a> {
    file: FileId,
    text: &'a str,
    /// The file's comments in source order, to trim them off span ends.
    comments: &'a [Comment],
}

impl<'a> Builder<'a> {
    pub(super) fn new(file: FileId, text: &'a str, comments: &'a [Comment]) -> Self {
        Builder {
            file,
            text,
            comments,
        }
    }

    /// The statements of a successful `program` parse.
    pub(super) fn program(&self, pairs: Pairs<'_, Rule>) -> DResult<Vec<Stmt>> {
        let mut stmts = Vec::new();
        for program in pairs {
            for pair in program.into_inner() {
                if pair.as_rule() != Rule::EOI {
                    stmts.push(self.stmt(pair, 0)?);
                }
            }
        }
        Ok(stmts)
    }

    // ------------------------------------------------------------ spans and errors

    /// The pair's span, its end moved back over blanks and comments.
    fn span(&self, pair: &P<'_>) -> Span {
        let span = pair.as_span();
        Span::new(
            self.file,
            span.start(),
            self.trim_end(span.start(), span.end()),
        )
    }

    fn trim_end(&self, start: usize, mut end: usize) -> usize {
        loop {
            end = start + self.text[start..end].trim_end().len();
            match self.comment_ending_at(end) {
                Some(comment_start) if comment_start >= start && comment_start < end => {
                    end = comment_start;
                }
                _ => return end,
            }
        }
    }

    fn comment_ending_at(&self, end: usize) -> Option<usize> {
        let i = self
            .comments
            .partition_point(|c| (c.span.end as usize) < end);
        self.comments
            .get(i)
            .filter(|c| c.span.end as usize == end)
            .map(|c| c.span.start as usize)
    }

    /// Fails when a node at `depth` would be nested deeper than [`MAX_DEPTH`].
    fn check(&self, depth: usize, pair: &P<'_>) -> DResult<()> {
        if depth > MAX_DEPTH {
            return Err(too_deep(self.file, self.text, pair.as_span().start()));
        }
        Ok(())
    }

    /// A grammar/builder mismatch: a bug, reported instead of panicking.
    fn unexpected(&self, pair: &P<'_>) -> Box<Diagnostic> {
        Box::new(
            Diagnostic::error(
                SYNTAX_ERROR,
                format!("internal parser error: unexpected {:?}", pair.as_rule()),
            )
            .at(self.span(pair), "the parser did not expect this"),
        )
    }

    fn lc_outside_vector(&self, pair: &P<'_>) -> Box<Diagnostic> {
        let keyword = pair.as_str().split(|c: char| !c.is_alphanumeric()).next();
        let keyword = keyword.unwrap_or_default();
        let start = pair.as_span().start();
        Box::new(
            Diagnostic::error(
                SYNTAX_ERROR,
                format!("list comprehension `{keyword}` outside of a vector"),
            )
            .at(
                Span::new(self.file, start, start + keyword.len()),
                "only allowed as an element of `[ ]`",
            )
            .with_note(format!(
                "write `[{keyword} (...) ...]` to build a list from this element"
            )),
        )
    }

    /// The pair's children, without keyword tokens.
    fn parts<'i>(&self, pair: P<'i>) -> Vec<P<'i>> {
        pair.into_inner()
            .filter(|p| !is_keyword(p.as_rule()))
            .collect()
    }

    /// Exactly `N` children (keywords excluded), or an internal error.
    fn exactly<'i, const N: usize>(&self, pair: P<'i>) -> DResult<[P<'i>; N]> {
        let whole = pair.clone();
        <[P<'i>; N]>::try_from(self.parts(pair)).map_err(|_| self.unexpected(&whole))
    }

    // ------------------------------------------------------------ statements

    fn stmt(&self, pair: P<'_>, depth: usize) -> DResult<Stmt> {
        self.check(depth, &pair)?;
        let span = self.span(&pair);
        let kind = match pair.as_rule() {
            Rule::empty_stmt => StmtKind::Empty,
            Rule::block | Rule::child_block => StmtKind::Block(self.stmts(pair, depth + 1)?),
            Rule::include_stmt => self.include(pair)?,
            Rule::module_def => self.module_def(pair, depth)?,
            Rule::function_def => self.function_def(pair, depth)?,
            Rule::assignment => {
                let [name, value] = self.exactly(pair)?;
                StmtKind::Assign {
                    name: self.ident(&name),
                    value: self.expr(value, depth + 1)?,
                }
            }
            Rule::instance => StmtKind::Instance(self.instance(pair, depth)?),
            _ => return Err(self.unexpected(&pair)),
        };
        Ok(Stmt { kind, span })
    }

    /// The statements directly inside a block pair.
    fn stmts(&self, block: P<'_>, depth: usize) -> DResult<Vec<Stmt>> {
        block
            .into_inner()
            .map(|pair| self.stmt(pair, depth))
            .collect()
    }

    /// A body or child statement as a list: `{ a; b; }` gives its statements, `;` none.
    fn body(&self, pair: P<'_>, depth: usize) -> DResult<Vec<Stmt>> {
        match pair.as_rule() {
            Rule::block | Rule::child_block => self.stmts(pair, depth),
            Rule::empty_stmt => Ok(Vec::new()),
            _ => Ok(vec![self.stmt(pair, depth)?]),
        }
    }

    fn include(&self, pair: P<'_>) -> DResult<StmtKind> {
        let [kind, path] = self.exactly(pair)?;
        let raw = path.as_span();
        Ok(StmtKind::Include {
            path: path.as_str().to_string(),
            path_span: Span::new(self.file, raw.start(), raw.end()),
            use_: kind.as_str() == "use",
        })
    }

    fn module_def(&self, pair: P<'_>, depth: usize) -> DResult<StmtKind> {
        let [name, params, body] = self.exactly(pair)?;
        Ok(StmtKind::ModuleDef {
            name: self.ident(&name),
            params: self.params(params, depth + 1)?,
            body: self.body(body, depth + 1)?,
        })
    }

    fn function_def(&self, pair: P<'_>, depth: usize) -> DResult<StmtKind> {
        let [name, params, body] = self.exactly(pair)?;
        Ok(StmtKind::FunctionDef {
            name: self.ident(&name),
            params: self.params(params, depth + 1)?,
            body: self.expr(body, depth + 1)?,
        })
    }

    fn instance(&self, pair: P<'_>, depth: usize) -> DResult<Instance> {
        let whole = pair.clone();
        let mut modifiers = Modifiers::default();
        for part in pair.into_inner() {
            let kind = match part.as_rule() {
                Rule::modifier => {
                    match part.as_str() {
                        "!" => modifiers.root = true,
                        "#" => modifiers.highlight = true,
                        "%" => modifiers.background = true,
                        _ => modifiers.disable = true,
                    }
                    continue;
                }
                Rule::if_stmt => self.if_stmt(part, depth)?,
                Rule::call_stmt => self.call_stmt(part, depth)?,
                _ => return Err(self.unexpected(&part)),
            };
            return Ok(Instance { modifiers, kind });
        }
        Err(self.unexpected(&whole))
    }

    fn if_stmt(&self, pair: P<'_>, depth: usize) -> DResult<InstanceKind> {
        let whole = pair.clone();
        let mut parts = self.parts(pair).into_iter();
        let (Some(cond), Some(then)) = (parts.next(), parts.next()) else {
            return Err(self.unexpected(&whole));
        };
        Ok(InstanceKind::If {
            cond: self.expr(cond, depth + 1)?,
            then: self.body(then, depth + 1)?,
            otherwise: parts.next().map(|p| self.body(p, depth + 1)).transpose()?,
        })
    }

    /// `name(args) child`, including `for`, `let` and `intersection_for`, which take
    /// `name = value` bindings instead of arguments.
    fn call_stmt(&self, pair: P<'_>, depth: usize) -> DResult<InstanceKind> {
        let [name, args, child] = self.exactly(pair)?;
        let name = self.ident(&name);
        let args = self.args(args, depth + 1)?;
        let body = self.body(child, depth + 1)?;
        Ok(match name.name.as_str() {
            "for" => InstanceKind::For {
                bindings: self.named_only(&name, args)?,
                body,
            },
            "intersection_for" => InstanceKind::IntersectionFor {
                bindings: self.named_only(&name, args)?,
                body,
            },
            "let" => InstanceKind::Let {
                bindings: self.named_only(&name, args)?,
                body,
            },
            _ => InstanceKind::Call {
                name,
                args,
                children: body,
            },
        })
    }

    /// The arguments of `for`/`let`/`intersection_for`, all of which must be named.
    fn named_only(&self, what: &Ident, args: Vec<Arg>) -> DResult<Vec<Binding>> {
        args.into_iter()
            .map(|arg| match arg.name {
                Some(name) => Ok(Binding {
                    name,
                    value: arg.value,
                }),
                None => Err(Box::new(
                    Diagnostic::error(
                        SYNTAX_ERROR,
                        format!("`{}` takes `name = value` bindings", what.name),
                    )
                    .at(arg.span, "expected `name = value` here")
                    .with_secondary(what.span, format!("in this `{}`", what.name)),
                )),
            })
            .collect()
    }

    // ------------------------------------------------------------ lists

    fn ident(&self, pair: &P<'_>) -> Ident {
        Ident {
            name: pair.as_str().to_string(),
            span: self.span(pair),
        }
    }

    fn params(&self, pair: P<'_>, depth: usize) -> DResult<Vec<Param>> {
        let mut params = Vec::new();
        for param in pair.into_inner() {
            let mut parts = param.into_inner();
            let Some(name) = parts.next() else { continue };
            params.push(Param {
                name: self.ident(&name),
                default: parts.next().map(|d| self.expr(d, depth)).transpose()?,
            });
        }
        Ok(params)
    }

    fn args(&self, pair: P<'_>, depth: usize) -> DResult<Vec<Arg>> {
        let mut args = Vec::new();
        for arg in pair.into_inner() {
            let span = self.span(&arg);
            let mut name = None;
            for part in arg.into_inner() {
                if part.as_rule() == Rule::arg_name {
                    name = part.into_inner().next().map(|n| self.ident(&n));
                } else {
                    let value = self.expr(part, depth)?;
                    args.push(Arg {
                        name: name.take(),
                        value,
                        span,
                    });
                }
            }
        }
        Ok(args)
    }

    fn bindings(&self, pair: P<'_>, depth: usize) -> DResult<Vec<Binding>> {
        pair.into_inner()
            .map(|binding| {
                let [name, value] = self.exactly(binding)?;
                Ok(Binding {
                    name: self.ident(&name),
                    value: self.expr(value, depth)?,
                })
            })
            .collect()
    }

    // ------------------------------------------------------------ expressions

    fn expr(&self, pair: P<'_>, depth: usize) -> DResult<Expr> {
        self.check(depth, &pair)?;
        let pair = peel(pair);
        let span = self.span(&pair);
        let kind = match pair.as_rule() {
            Rule::ternary => self.ternary(pair, depth)?,
            Rule::or_expr
            | Rule::and_expr
            | Rule::eq_expr
            | Rule::rel_expr
            | Rule::add_expr
            | Rule::mul_expr => return self.binary_chain(pair, depth),
            Rule::unary => return self.unary(pair, depth),
            Rule::postfix => return self.postfix(pair, depth),
            Rule::paren => return self.paren(pair, depth),
            Rule::fn_literal => {
                let [params, body] = self.exactly(pair)?;
                ExprKind::FunctionLiteral {
                    params: self.params(params, depth + 1)?,
                    body: Box::new(self.expr(body, depth + 1)?),
                }
            }
            Rule::let_expr => {
                let [bindings, body] = self.exactly(pair)?;
                ExprKind::Let {
                    bindings: self.bindings(bindings, depth + 1)?,
                    body: Box::new(self.expr(body, depth + 1)?),
                }
            }
            Rule::assert_expr | Rule::echo_expr => self.assert_or_echo(pair, depth)?,
            Rule::bracket => self.bracket(pair, depth)?,
            Rule::lc_for | Rule::lc_if | Rule::lc_each => {
                return Err(self.lc_outside_vector(&pair));
            }
            _ => self.leaf(&pair)?,
        };
        Ok(Expr { kind, span })
    }

    fn leaf(&self, pair: &P<'_>) -> DResult<ExprKind> {
        Ok(match pair.as_rule() {
            Rule::lit_true => ExprKind::Bool(true),
            Rule::lit_false => ExprKind::Bool(false),
            Rule::lit_undef => ExprKind::Undef,
            Rule::ident => ExprKind::Ident(pair.as_str().to_string()),
            Rule::string => ExprKind::Str(decode_string(pair.as_str())),
            Rule::number => {
                let text = pair.as_str();
                let value = text.parse::<f64>().map_err(|_| {
                    Box::new(
                        Diagnostic::error(SYNTAX_ERROR, format!("invalid number `{text}`"))
                            .at(self.span(pair), "not a number"),
                    )
                })?;
                ExprKind::Number {
                    value,
                    text: text.to_string(),
                }
            }
            _ => return Err(self.unexpected(pair)),
        })
    }

    /// `( e )` is `e` itself; its span stays that of `e`.
    fn paren(&self, pair: P<'_>, depth: usize) -> DResult<Expr> {
        let [inner] = self.exactly(pair)?;
        self.expr(inner, depth)
    }

    fn ternary(&self, pair: P<'_>, depth: usize) -> DResult<ExprKind> {
        let [cond, then, otherwise] = self.exactly(pair)?;
        Ok(ExprKind::Ternary(
            Box::new(self.expr(cond, depth + 1)?),
            Box::new(self.expr(then, depth + 1)?),
            Box::new(self.expr(otherwise, depth + 1)?),
        ))
    }

    fn assert_or_echo(&self, pair: P<'_>, depth: usize) -> DResult<ExprKind> {
        let is_assert = pair.as_rule() == Rule::assert_expr;
        let whole = pair.clone();
        let mut parts = self.parts(pair).into_iter();
        let Some(args) = parts.next() else {
            return Err(self.unexpected(&whole));
        };
        let args = self.args(args, depth + 1)?;
        let body = match parts.next() {
            Some(body) => Some(Box::new(self.expr(body, depth + 1)?)),
            None => None,
        };
        Ok(if is_assert {
            ExprKind::Assert { args, body }
        } else {
            ExprKind::Echo { args, body }
        })
    }

    /// `a op b op c ...`, folded to the left.
    fn binary_chain(&self, pair: P<'_>, depth: usize) -> DResult<Expr> {
        let whole = pair.clone();
        let parts: Vec<P<'_>> = pair.into_inner().collect();
        let operand_depth = depth + parts.len() / 2;
        let mut parts = parts.into_iter();
        let Some(first) = parts.next() else {
            return Err(self.unexpected(&whole));
        };
        let mut span = self.span(&first);
        let mut acc = self.expr(first, operand_depth)?;
        while let (Some(op), Some(rhs)) = (parts.next(), parts.next()) {
            let op = binary_op(op.as_rule()).ok_or_else(|| self.unexpected(&op))?;
            span = span.to(self.span(&rhs));
            let rhs = self.expr(rhs, operand_depth)?;
            acc = Expr {
                kind: ExprKind::Binary(op, Box::new(acc), Box::new(rhs)),
                span,
            };
        }
        Ok(acc)
    }

    /// `prefix* postfix (^ prefix* postfix)*`: `^` is right associative, and the prefix
    /// operators in front of an operand apply to the whole power that starts there.
    fn unary(&self, pair: P<'_>, depth: usize) -> DResult<Expr> {
        let mut segments: Vec<(Vec<P<'_>>, P<'_>)> = Vec::new();
        let mut prefixes = Vec::new();
        let mut levels = 0;
        for part in pair.into_inner() {
            match part.as_rule() {
                Rule::prefix_op => {
                    prefixes.push(part);
                    levels += 1;
                }
                Rule::op_pow => levels += 1,
                _ => segments.push((std::mem::take(&mut prefixes), part)),
            }
        }
        let operand_depth = depth + levels;
        let mut acc: Option<Expr> = None;
        for (prefixes, operand) in segments.into_iter().rev() {
            let base_span = self.span(&operand);
            let base = self.expr(operand, operand_depth)?;
            let mut expr = match acc {
                None => base,
                Some(exponent) => Expr {
                    span: base_span.to(exponent.span),
                    kind: ExprKind::Binary(BinaryOp::Pow, Box::new(base), Box::new(exponent)),
                },
            };
            for op in prefixes.iter().rev() {
                expr = Expr {
                    span: self.span(op).to(expr.span),
                    kind: ExprKind::Unary(unary_op(op.as_str()), Box::new(expr)),
                };
            }
            acc = Some(expr);
        }
        acc.ok_or_else(|| {
            Box::new(Diagnostic::error(
                SYNTAX_ERROR,
                "internal parser error: empty operand",
            ))
        })
    }

    /// `primary (call | index | member)*`, folded to the left.
    fn postfix(&self, pair: P<'_>, depth: usize) -> DResult<Expr> {
        let whole = pair.clone();
        let mut parts = pair.into_inner();
        let inner_depth = depth + parts.len().saturating_sub(1);
        let Some(first) = parts.next() else {
            return Err(self.unexpected(&whole));
        };
        let mut span = self.span(&first);
        let mut acc = self.expr(first, inner_depth)?;
        for op in parts {
            span = span.to(self.span(&op));
            let rule = op.as_rule();
            let inner = op.clone().into_inner().next();
            let Some(inner) = inner else {
                return Err(self.unexpected(&op));
            };
            let kind = match rule {
                Rule::call_args => ExprKind::Call {
                    callee: Box::new(acc),
                    args: self.args(inner, inner_depth)?,
                },
                Rule::index => {
                    ExprKind::Index(Box::new(acc), Box::new(self.expr(inner, inner_depth)?))
                }
                Rule::member => ExprKind::Member(Box::new(acc), self.ident(&inner)),
                _ => return Err(self.unexpected(&op)),
            };
            acc = Expr { kind, span };
        }
        Ok(acc)
    }

    /// `[]`, `[a, b, ...]`, `[a : b]` or `[a : s : b]`.
    fn bracket(&self, pair: P<'_>, depth: usize) -> DResult<ExprKind> {
        let items: Vec<P<'_>> = pair.into_inner().collect();
        if let [start, rest] = items.as_slice()
            && rest.as_rule() == Rule::range_rest
        {
            return self.range(start.clone(), rest.clone(), depth);
        }
        let elems = items
            .into_iter()
            .map(|item| self.elem(item, depth + 1))
            .collect::<DResult<_>>()?;
        Ok(ExprKind::Vector(elems))
    }

    fn range(&self, start: P<'_>, rest: P<'_>, depth: usize) -> DResult<ExprKind> {
        let start = Box::new(self.expr(start, depth + 1)?);
        let mut bounds = rest
            .into_inner()
            .map(|b| self.expr(b, depth + 1).map(Box::new))
            .collect::<DResult<Vec<_>>>()?;
        let end = bounds.pop();
        let step = bounds.pop();
        match end {
            Some(end) => Ok(ExprKind::Range { start, step, end }),
            None => Err(Box::new(Diagnostic::error(
                SYNTAX_ERROR,
                "internal parser error: range without end",
            ))),
        }
    }

    // ------------------------------------------------------------ vector elements

    /// One element of a vector literal: an expression or a list comprehension.
    fn elem(&self, pair: P<'_>, depth: usize) -> DResult<VecElem> {
        self.check(depth, &pair)?;
        let pair = peel(pair);
        let span = self.span(&pair);
        match pair.as_rule() {
            Rule::lc_for => self.lc_for(pair, span, depth),
            Rule::lc_if => {
                let whole = pair.clone();
                let mut parts = self.parts(pair).into_iter();
                let (Some(cond), Some(then)) = (parts.next(), parts.next()) else {
                    return Err(self.unexpected(&whole));
                };
                Ok(VecElem::If {
                    cond: self.expr(cond, depth + 1)?,
                    then: Box::new(self.elem(then, depth + 1)?),
                    otherwise: match parts.next() {
                        Some(p) => Some(Box::new(self.elem(p, depth + 1)?)),
                        None => None,
                    },
                    span,
                })
            }
            Rule::lc_each => {
                let [body] = self.exactly(pair)?;
                Ok(VecElem::Each(Box::new(self.elem(body, depth + 1)?), span))
            }
            Rule::let_expr => self.let_elem(pair, span, depth),
            Rule::paren => {
                let [inner] = self.exactly(pair)?;
                self.elem(inner, depth)
            }
            _ => Ok(VecElem::Expr(self.expr(pair, depth)?)),
        }
    }

    /// `let (...) x` inside `[ ]`: a comprehension `let` when `x` is one, else an
    /// ordinary `let` expression.
    fn let_elem(&self, pair: P<'_>, span: Span, depth: usize) -> DResult<VecElem> {
        let [bindings, body] = self.exactly(pair)?;
        let bindings = self.bindings(bindings, depth + 1)?;
        Ok(match self.elem(body, depth + 1)? {
            VecElem::Expr(body) => VecElem::Expr(Expr {
                kind: ExprKind::Let {
                    bindings,
                    body: Box::new(body),
                },
                span,
            }),
            body => VecElem::Let {
                bindings,
                body: Box::new(body),
                span,
            },
        })
    }

    fn lc_for(&self, pair: P<'_>, span: Span, depth: usize) -> DResult<VecElem> {
        let whole = pair.clone();
        let parts = self.parts(pair);
        match <[P<'_>; 2]>::try_from(parts) {
            Ok([bindings, body]) => Ok(VecElem::For {
                bindings: self.bindings(bindings, depth + 1)?,
                body: Box::new(self.elem(body, depth + 1)?),
                span,
            }),
            Err(parts) => {
                let Ok([init, tail, body]) = <[P<'_>; 3]>::try_from(parts) else {
                    return Err(self.unexpected(&whole));
                };
                let [cond, update] = self.exactly(tail)?;
                Ok(VecElem::ForC {
                    init: self.bindings(init, depth + 1)?,
                    cond: self.expr(cond, depth + 1)?,
                    update: self.bindings(update, depth + 1)?,
                    body: Box::new(self.elem(body, depth + 1)?),
                    span,
                })
            }
        }
    }
}

// ---------------------------------------------------------------- helpers

fn is_keyword(rule: Rule) -> bool {
    matches!(
        rule,
        Rule::kw_module
            | Rule::kw_function
            | Rule::kw_if
            | Rule::kw_else
            | Rule::kw_let
            | Rule::kw_assert
            | Rule::kw_echo
            | Rule::kw_for
            | Rule::kw_each
    )
}

/// Skips the precedence levels that hold a single child (`1` is an `expr` holding a
/// `ternary` holding an `or_expr` ... holding a `number`), without recursion.
fn peel(mut pair: P<'_>) -> P<'_> {
    while matches!(
        pair.as_rule(),
        Rule::expr
            | Rule::ternary
            | Rule::or_expr
            | Rule::and_expr
            | Rule::eq_expr
            | Rule::rel_expr
            | Rule::add_expr
            | Rule::mul_expr
            | Rule::unary
            | Rule::postfix
    ) {
        let mut inner = pair.clone().into_inner();
        match (inner.next(), inner.next()) {
            (Some(only), None) => pair = only,
            _ => break,
        }
    }
    pair
}

fn binary_op(rule: Rule) -> Option<BinaryOp> {
    Some(match rule {
        Rule::op_or => BinaryOp::Or,
        Rule::op_and => BinaryOp::And,
        Rule::op_eq => BinaryOp::Eq,
        Rule::op_ne => BinaryOp::Ne,
        Rule::op_le => BinaryOp::Le,
        Rule::op_ge => BinaryOp::Ge,
        Rule::op_lt => BinaryOp::Lt,
        Rule::op_gt => BinaryOp::Gt,
        Rule::op_add => BinaryOp::Add,
        Rule::op_sub => BinaryOp::Sub,
        Rule::op_mul => BinaryOp::Mul,
        Rule::op_div => BinaryOp::Div,
        Rule::op_mod => BinaryOp::Mod,
        _ => return None,
    })
}

fn unary_op(text: &str) -> UnaryOp {
    match text {
        "-" => UnaryOp::Neg,
        "+" => UnaryOp::Plus,
        _ => UnaryOp::Not,
    }
}

/// The value of a string literal (quotes included in `raw`), with OpenSCAD's escapes:
/// `\n \t \r \\ \"`, `\xHH` (ASCII; `\x00` reads as a space), `\uHHHH`, `\UHHHHHH` and
/// also `\u{H...}` (an invalid or zero code point reads as a space). A backslash before
/// any other character is dropped, and raw line breaks are dropped, as OpenSCAD does.
pub(super) fn decode_string(raw: &str) -> String {
    let inner = raw
        .strip_prefix('"')
        .and_then(|s| s.strip_suffix('"'))
        .unwrap_or(raw);
    let mut out = String::with_capacity(inner.len());
    let mut rest = inner;
    while let Some(c) = rest.chars().next() {
        rest = &rest[c.len_utf8()..];
        match c {
            '\\' => rest = escape(rest, &mut out),
            '\n' | '\r' => {}
            _ => out.push(c),
        }
    }
    out
}

/// Decodes the escape after a backslash; returns the text after it.
fn escape<'s>(rest: &'s str, out: &mut String) -> &'s str {
    let Some(c) = rest.chars().next() else {
        return rest;
    };
    let after = &rest[c.len_utf8()..];
    let simple = match c {
        'n' => Some('\n'),
        't' => Some('\t'),
        'r' => Some('\r'),
        _ => None,
    };
    if let Some(s) = simple {
        out.push(s);
        return after;
    }
    let coded = match c {
        'x' => hex_escape(after, 2).filter(|&(v, _)| v <= 0x7f),
        'u' if after.starts_with('{') => braced_escape(after),
        'u' => hex_escape(after, 4),
        'U' => hex_escape(after, 6),
        _ => None,
    };
    match coded {
        Some((value, used)) => {
            out.push(
                char::from_u32(value)
                    .filter(|&ch| ch != '\0')
                    .unwrap_or(' '),
            );
            &after[used..]
        }
        // `\\`, `\"` and unknown escapes: the backslash goes, the character stays.
        None => {
            out.push(c);
            after
        }
    }
}

/// `digits` hex digits at the start of `s`: their value and length.
fn hex_escape(s: &str, digits: usize) -> Option<(u32, usize)> {
    let hex = s.get(..digits)?;
    if !hex.bytes().all(|b| b.is_ascii_hexdigit()) {
        return None;
    }
    u32::from_str_radix(hex, 16).ok().map(|v| (v, digits))
}

/// `{H...}` (1 to 6 hex digits) at the start of `s`: its value and length.
fn braced_escape(s: &str) -> Option<(u32, usize)> {
    let close = s.bytes().take(8).position(|b| b == b'}')?;
    let hex = &s[1..close];
    if hex.is_empty() || !hex.bytes().all(|b| b.is_ascii_hexdigit()) {
        return None;
    }
    u32::from_str_radix(hex, 16).ok().map(|v| (v, close + 1))
}
