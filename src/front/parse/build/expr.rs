//! Expressions and vector elements (list comprehensions).

use super::{Builder, P, Step};
use crate::front::ast::{BinaryOp, Expr, ExprKind, UnaryOp, VecElem};
use crate::front::diag::{DResult, Diagnostic};
use crate::front::parse::strings::decode_string;
use crate::front::parse::{Rule, SYNTAX_ERROR, precedence};
use crate::span::Span;

impl<'a> Builder<'a> {
    pub(super) fn expr(&self, pair: P<'_>, depth: usize) -> DResult<Expr> {
        self.check(depth, &pair)?;
        let pair = peel(pair);
        let step: Step<'a, Expr> = match pair.as_rule() {
            Rule::ternary => Self::ternary,
            Rule::or_expr
            | Rule::and_expr
            | Rule::eq_expr
            | Rule::rel_expr
            | Rule::add_expr
            | Rule::mul_expr => Self::binary_chain,
            Rule::unary => Self::unary,
            Rule::postfix => Self::postfix,
            Rule::paren => Self::paren,
            Rule::fn_literal => Self::fn_literal,
            Rule::let_expr => Self::let_expr,
            Rule::assert_expr | Rule::echo_expr => Self::assert_or_echo,
            Rule::bracket => Self::bracket,
            Rule::lc_for | Rule::lc_if | Rule::lc_each => Self::lc_outside_vector,
            _ => Self::leaf,
        };
        step(self, pair, depth)
    }

    fn leaf(&self, pair: P<'_>, _depth: usize) -> DResult<Expr> {
        let span = self.span(&pair);
        let kind = match pair.as_rule() {
            Rule::lit_true => ExprKind::Bool(true),
            Rule::lit_false => ExprKind::Bool(false),
            Rule::lit_undef => ExprKind::Undef,
            Rule::ident => ExprKind::Ident(pair.as_str().to_string()),
            Rule::string => ExprKind::Str(decode_string(pair.as_str())),
            Rule::number => {
                let text = pair.as_str();
                let Ok(value) = text.parse::<f64>() else {
                    return Err(self.internal(&format!("invalid number `{text}`"), span));
                };
                let text = text.to_string();
                ExprKind::Number { value, text }
            }
            _ => return Err(self.unexpected(&pair)),
        };
        Ok(Expr { kind, span })
    }

    #[cold]
    #[inline(never)]
    fn lc_outside_vector(&self, pair: P<'_>, _depth: usize) -> DResult<Expr> {
        let text = pair.as_str();
        let keyword = &text[..text
            .find(|c: char| !c.is_alphanumeric())
            .unwrap_or(text.len())];
        let start = pair.as_span().start();
        Err(Box::new(
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
        ))
    }

    /// `( e )` is `e` itself; its span stays that of `e`.
    fn paren(&self, pair: P<'_>, depth: usize) -> DResult<Expr> {
        let [inner] = self.exactly(pair)?;
        self.expr(inner, depth)
    }

    fn ternary(&self, pair: P<'_>, depth: usize) -> DResult<Expr> {
        let span = self.span(&pair);
        let [cond, then, otherwise] = self.exactly(pair)?;
        let cond = Box::new(self.expr(cond, depth + 1)?);
        let then = Box::new(self.expr(then, depth + 1)?);
        let otherwise = Box::new(self.expr(otherwise, depth + 1)?);
        let kind = ExprKind::Ternary(cond, then, otherwise);
        Ok(Expr { kind, span })
    }

    fn fn_literal(&self, pair: P<'_>, depth: usize) -> DResult<Expr> {
        let span = self.span(&pair);
        let [params, body] = self.exactly(pair)?;
        let params = self.params(params, depth + 1)?;
        let body = Box::new(self.expr(body, depth + 1)?);
        let kind = ExprKind::FunctionLiteral { params, body };
        Ok(Expr { kind, span })
    }

    fn let_expr(&self, pair: P<'_>, depth: usize) -> DResult<Expr> {
        let span = self.span(&pair);
        let [bindings, body] = self.exactly(pair)?;
        let bindings = self.bindings(bindings, depth + 1)?;
        let body = Box::new(self.expr(body, depth + 1)?);
        let kind = ExprKind::Let { bindings, body };
        Ok(Expr { kind, span })
    }

    /// `assert(args) body` / `echo(args) body`, the body optional.
    fn assert_or_echo(&self, pair: P<'_>, depth: usize) -> DResult<Expr> {
        let span = self.span(&pair);
        let is_assert = pair.as_rule() == Rule::assert_expr;
        let mut parts = self.parts(pair).into_iter();
        let Some(args) = parts.next() else {
            return Err(self.internal("`assert`/`echo` without arguments", span));
        };
        let args = self.args(args, depth + 1)?;
        let body = match parts.next() {
            Some(body) => Some(Box::new(self.expr(body, depth + 1)?)),
            None => None,
        };
        let kind = if is_assert {
            ExprKind::Assert { args, body }
        } else {
            ExprKind::Echo { args, body }
        };
        Ok(Expr { kind, span })
    }

    /// `a op b op c ...`, folded to the left.
    fn binary_chain(&self, pair: P<'_>, depth: usize) -> DResult<Expr> {
        let whole = self.span(&pair);
        let parts: Vec<P<'_>> = pair.into_inner().collect();
        // Each operator nests its left operand one level deeper.
        let operand_depth = depth + parts.len() / 2;
        let mut parts = parts.into_iter();
        let Some(first) = parts.next() else {
            return Err(self.internal("empty operator chain", whole));
        };
        let mut span = self.span(&first);
        let mut acc = self.expr(first, operand_depth)?;
        while let (Some(op), Some(rhs)) = (parts.next(), parts.next()) {
            let Some(op) = precedence::binary_op(op.as_rule()) else {
                return Err(self.unexpected(&op));
            };
            span = span.to(self.span(&rhs));
            let rhs = self.expr(rhs, operand_depth)?;
            let kind = ExprKind::Binary(op, Box::new(acc), Box::new(rhs));
            acc = Expr { kind, span };
        }
        Ok(acc)
    }

    /// `prefix* postfix (^ prefix* postfix)*`: `^` is right associative, and the prefix
    /// operators in front of an operand apply to the whole power that starts there, so
    /// `-2^2` is `-(2^2)` and `2^-1^2` is `2^(-(1^2))`, as in OpenSCAD.
    fn unary(&self, pair: P<'_>, depth: usize) -> DResult<Expr> {
        let whole = self.span(&pair);
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
        while let Some((prefixes, operand)) = segments.pop() {
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
        acc.ok_or_else(|| self.internal("empty operand", whole))
    }

    /// `primary (call | index | member)*`, folded to the left.
    fn postfix(&self, pair: P<'_>, depth: usize) -> DResult<Expr> {
        let whole = self.span(&pair);
        let mut parts = pair.into_inner();
        let inner_depth = depth + parts.len().saturating_sub(1);
        let Some(first) = parts.next() else {
            return Err(self.internal("empty postfix expression", whole));
        };
        let mut span = self.span(&first);
        let mut acc = self.expr(first, inner_depth)?;
        for op in parts {
            span = span.to(self.span(&op));
            acc = self.postfix_op(acc, op, span, inner_depth)?;
        }
        Ok(acc)
    }

    fn postfix_op(&self, target: Expr, op: P<'_>, span: Span, depth: usize) -> DResult<Expr> {
        let rule = op.as_rule();
        let [inner] = self.exactly(op)?;
        let target = Box::new(target);
        let kind = match rule {
            Rule::call_args => ExprKind::Call {
                callee: target,
                args: self.args(inner, depth)?,
            },
            Rule::index => ExprKind::Index(target, Box::new(self.expr(inner, depth)?)),
            _ => ExprKind::Member(target, self.ident(&inner)),
        };
        Ok(Expr { kind, span })
    }

    /// `[]`, `[a, b, ...]`, `[a : b]` or `[a : s : b]`.
    fn bracket(&self, pair: P<'_>, depth: usize) -> DResult<Expr> {
        let span = self.span(&pair);
        let items: Vec<P<'_>> = pair.into_inner().collect();
        let kind = match <[P<'_>; 2]>::try_from(items) {
            Ok([start, rest]) if rest.as_rule() == Rule::range_rest => {
                self.range(start, rest, depth)?
            }
            Ok(two) => self.vector(Vec::from(two), depth)?,
            Err(items) => self.vector(items, depth)?,
        };
        Ok(Expr { kind, span })
    }

    fn vector(&self, items: Vec<P<'_>>, depth: usize) -> DResult<ExprKind> {
        let mut elems = Vec::with_capacity(items.len());
        for item in items {
            elems.push(self.elem(item, depth + 1)?);
        }
        Ok(ExprKind::Vector(elems))
    }

    fn range(&self, start: P<'_>, rest: P<'_>, depth: usize) -> DResult<ExprKind> {
        let whole = self.span(&rest);
        let start = Box::new(self.expr(start, depth + 1)?);
        let mut bounds = Vec::with_capacity(2);
        for bound in rest.into_inner() {
            bounds.push(Box::new(self.expr(bound, depth + 1)?));
        }
        let end = bounds.pop();
        let step = bounds.pop();
        match end {
            Some(end) => Ok(ExprKind::Range { start, step, end }),
            None => Err(self.internal("range without an end", whole)),
        }
    }

    // ------------------------------------------------------------ vector elements

    /// One element of a vector literal: an expression or a list comprehension.
    fn elem(&self, pair: P<'_>, depth: usize) -> DResult<VecElem> {
        self.check(depth, &pair)?;
        let pair = peel(pair);
        let step: Step<'a, VecElem> = match pair.as_rule() {
            Rule::lc_for => Self::lc_for,
            Rule::lc_if => Self::lc_if,
            Rule::lc_each => Self::lc_each,
            Rule::let_expr => Self::let_elem,
            Rule::paren => Self::paren_elem,
            _ => Self::expr_elem,
        };
        step(self, pair, depth)
    }

    fn expr_elem(&self, pair: P<'_>, depth: usize) -> DResult<VecElem> {
        self.expr(pair, depth).map(VecElem::Expr)
    }

    /// `(e)` in a vector: the element `e`, which may be a comprehension.
    fn paren_elem(&self, pair: P<'_>, depth: usize) -> DResult<VecElem> {
        let [inner] = self.exactly(pair)?;
        self.elem(inner, depth)
    }

    fn lc_if(&self, pair: P<'_>, depth: usize) -> DResult<VecElem> {
        let span = self.span(&pair);
        let mut parts = self.parts(pair).into_iter();
        let (Some(cond), Some(then)) = (parts.next(), parts.next()) else {
            return Err(self.internal("`if` without a condition or body", span));
        };
        let cond = self.expr(cond, depth + 1)?;
        let then = Box::new(self.elem(then, depth + 1)?);
        let otherwise = match parts.next() {
            Some(otherwise) => Some(Box::new(self.elem(otherwise, depth + 1)?)),
            None => None,
        };
        Ok(VecElem::If {
            cond,
            then,
            otherwise,
            span,
        })
    }

    fn lc_each(&self, pair: P<'_>, depth: usize) -> DResult<VecElem> {
        let span = self.span(&pair);
        let [body] = self.exactly(pair)?;
        let body = self.elem(body, depth + 1)?;
        Ok(VecElem::Each(Box::new(body), span))
    }

    /// `let (...) x` inside `[ ]`: a comprehension `let` when `x` is one, else an
    /// ordinary `let` expression.
    fn let_elem(&self, pair: P<'_>, depth: usize) -> DResult<VecElem> {
        let span = self.span(&pair);
        let [bindings, body] = self.exactly(pair)?;
        let bindings = self.bindings(bindings, depth + 1)?;
        let body = self.elem(body, depth + 1)?;
        Ok(match body {
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

    /// `for (a = ...) x` or C-style `for (init; cond; update) x`.
    fn lc_for(&self, pair: P<'_>, depth: usize) -> DResult<VecElem> {
        let span = self.span(&pair);
        let mut parts = self.parts(pair);
        let Some(body) = parts.pop() else {
            return Err(self.internal("`for` without a body", span));
        };
        let mut parts = parts.into_iter();
        let (Some(init), tail) = (parts.next(), parts.next()) else {
            return Err(self.internal("`for` without bindings", span));
        };
        let init = self.bindings(init, depth + 1)?;
        let Some(tail) = tail else {
            let body = Box::new(self.elem(body, depth + 1)?);
            return Ok(VecElem::For {
                bindings: init,
                body,
                span,
            });
        };
        let [cond, update] = self.exactly(tail)?;
        let cond = self.expr(cond, depth + 1)?;
        let update = self.bindings(update, depth + 1)?;
        let body = Box::new(self.elem(body, depth + 1)?);
        Ok(VecElem::ForC {
            init,
            cond,
            update,
            body,
            span,
        })
    }
}

/// Skips the precedence levels that hold a single child (`1` is an `expr` holding a
/// `ternary` holding an `or_expr` ... holding a `number`), without recursion.
fn peel(mut pair: P<'_>) -> P<'_> {
    while precedence::is_level(pair.as_rule()) {
        let mut inner = pair.clone().into_inner();
        match (inner.next(), inner.next()) {
            (Some(only), None) => pair = only,
            _ => break,
        }
    }
    pair
}

fn unary_op(text: &str) -> UnaryOp {
    match text {
        "-" => UnaryOp::Neg,
        "+" => UnaryOp::Plus,
        _ => UnaryOp::Not,
    }
}
