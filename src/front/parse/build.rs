//! From pest's parse tree to the AST: the builder, statements and lists (expressions and
//! vector elements are in [`expr`]).
//!
//! The builder recurses over the pairs; `parse::check_depth` has already bounded their
//! nesting, and flat chains (`a+b+c`, `--x`, `a^b^c`, `f(x)[i].y`) are checked here against
//! [`MAX_DEPTH`] before the tree they fold into is built. The functions on the recursive
//! paths dispatch through one call site, keep few locals and use plain loops rather than
//! iterator adapters, so that a nesting level costs little stack even unoptimised.
//!
//! Spans are tight: pest lets a rule that ends in an optional part swallow the blanks and
//! comments after it, so every span is trimmed back to its last token ([`Builder::span`]).

mod expr;

use super::{MAX_DEPTH, Rule, SYNTAX_ERROR, too_deep};
use crate::front::ast::{
    Arg, Binding, Comment, Ident, Instance, InstanceKind, Modifiers, Param, Stmt, StmtKind,
};
use crate::front::diag::{DResult, Diagnostic};
use crate::span::{FileId, Span};
use pest::iterators::{Pair, Pairs};

type P<'i> = Pair<'i, Rule>;

/// One step of the recursive descent, chosen before it is called (see the module docs).
type Step<'a, T> = for<'b, 'i> fn(&'b Builder<'a>, P<'i>, usize) -> DResult<T>;

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
            return Err(self.too_deep(pair));
        }
        Ok(())
    }

    #[cold]
    #[inline(never)]
    fn too_deep(&self, pair: &P<'_>) -> Box<Diagnostic> {
        too_deep(self.file, self.text, pair.as_span().start())
    }

    /// A grammar/builder mismatch: a bug, reported instead of panicking.
    #[cold]
    #[inline(never)]
    fn unexpected(&self, pair: &P<'_>) -> Box<Diagnostic> {
        self.internal(&format!("unexpected {:?}", pair.as_rule()), self.span(pair))
    }

    #[cold]
    #[inline(never)]
    fn internal(&self, what: &str, span: Span) -> Box<Diagnostic> {
        Box::new(
            Diagnostic::error(SYNTAX_ERROR, format!("internal parser error: {what}"))
                .at(span, "while reading this"),
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
        let span = self.span(&pair);
        <[P<'i>; N]>::try_from(self.parts(pair))
            .map_err(|_| self.internal(&format!("expected {N} parts"), span))
    }

    // ------------------------------------------------------------ statements

    fn stmt(&self, pair: P<'_>, depth: usize) -> DResult<Stmt> {
        self.check(depth, &pair)?;
        let step: Step<'a, Stmt> = match pair.as_rule() {
            Rule::empty_stmt => Self::empty,
            Rule::block | Rule::child_block => Self::block,
            Rule::include_stmt => Self::include,
            Rule::module_def => Self::module_def,
            Rule::function_def => Self::function_def,
            Rule::assignment => Self::assignment,
            Rule::instance => Self::instance,
            _ => return Err(self.unexpected(&pair)),
        };
        step(self, pair, depth)
    }

    fn empty(&self, pair: P<'_>, _depth: usize) -> DResult<Stmt> {
        Ok(Stmt {
            kind: StmtKind::Empty,
            span: self.span(&pair),
        })
    }

    fn block(&self, pair: P<'_>, depth: usize) -> DResult<Stmt> {
        let span = self.span(&pair);
        let stmts = self.stmts(pair, depth + 1)?;
        Ok(Stmt {
            kind: StmtKind::Block(stmts),
            span,
        })
    }

    /// The statements directly inside a block pair.
    fn stmts(&self, block: P<'_>, depth: usize) -> DResult<Vec<Stmt>> {
        let mut stmts = Vec::new();
        for pair in block.into_inner() {
            stmts.push(self.stmt(pair, depth)?);
        }
        Ok(stmts)
    }

    /// A body or child statement as a list: `{ a; b; }` gives its statements, `;` none.
    fn body(&self, pair: P<'_>, depth: usize) -> DResult<Vec<Stmt>> {
        match pair.as_rule() {
            Rule::block | Rule::child_block => self.stmts(pair, depth),
            Rule::empty_stmt => Ok(Vec::new()),
            _ => self.stmt(pair, depth).map(|stmt| vec![stmt]),
        }
    }

    fn include(&self, pair: P<'_>, _depth: usize) -> DResult<Stmt> {
        let span = self.span(&pair);
        let [kind, path] = self.exactly(pair)?;
        let raw = path.as_span();
        let kind = StmtKind::Include {
            path: path.as_str().to_string(),
            path_span: Span::new(self.file, raw.start(), raw.end()),
            use_: kind.as_str() == "use",
        };
        Ok(Stmt { kind, span })
    }

    fn module_def(&self, pair: P<'_>, depth: usize) -> DResult<Stmt> {
        let span = self.span(&pair);
        let [name, params, body] = self.exactly(pair)?;
        let params = self.params(params, depth + 1)?;
        let body = self.body(body, depth + 1)?;
        let name = self.ident(&name);
        Ok(Stmt {
            kind: StmtKind::ModuleDef { name, params, body },
            span,
        })
    }

    fn function_def(&self, pair: P<'_>, depth: usize) -> DResult<Stmt> {
        let span = self.span(&pair);
        let [name, params, body] = self.exactly(pair)?;
        let params = self.params(params, depth + 1)?;
        let body = self.expr(body, depth + 1)?;
        let name = self.ident(&name);
        Ok(Stmt {
            kind: StmtKind::FunctionDef { name, params, body },
            span,
        })
    }

    fn assignment(&self, pair: P<'_>, depth: usize) -> DResult<Stmt> {
        let span = self.span(&pair);
        let [name, value] = self.exactly(pair)?;
        let value = self.expr(value, depth + 1)?;
        let name = self.ident(&name);
        Ok(Stmt {
            kind: StmtKind::Assign { name, value },
            span,
        })
    }

    fn instance(&self, pair: P<'_>, depth: usize) -> DResult<Stmt> {
        let span = self.span(&pair);
        let mut modifiers = Modifiers::default();
        let mut body = None;
        for part in pair.into_inner() {
            match (part.as_rule(), part.as_str()) {
                (Rule::modifier, "!") => modifiers.root = true,
                (Rule::modifier, "#") => modifiers.highlight = true,
                (Rule::modifier, "%") => modifiers.background = true,
                (Rule::modifier, _) => modifiers.disable = true,
                _ => body = Some(part),
            }
        }
        let Some(body) = body else {
            return Err(self.internal("instantiation without a body", span));
        };
        let step: Step<'a, InstanceKind> = match body.as_rule() {
            Rule::if_stmt => Self::if_stmt,
            _ => Self::call_stmt,
        };
        let kind = step(self, body, depth)?;
        Ok(Stmt {
            kind: StmtKind::Instance(Instance { modifiers, kind }),
            span,
        })
    }

    fn if_stmt(&self, pair: P<'_>, depth: usize) -> DResult<InstanceKind> {
        let span = self.span(&pair);
        let mut parts = self.parts(pair).into_iter();
        let (Some(cond), Some(then)) = (parts.next(), parts.next()) else {
            return Err(self.internal("`if` without a condition or body", span));
        };
        let cond = self.expr(cond, depth + 1)?;
        let then = self.body(then, depth + 1)?;
        let otherwise = match parts.next() {
            Some(otherwise) => Some(self.body(otherwise, depth + 1)?),
            None => None,
        };
        Ok(InstanceKind::If {
            cond,
            then,
            otherwise,
        })
    }

    /// `name(args) child`, including `for`, `let` and `intersection_for`, which take
    /// `name = value` bindings instead of arguments.
    fn call_stmt(&self, pair: P<'_>, depth: usize) -> DResult<InstanceKind> {
        let [name, args, child] = self.exactly(pair)?;
        let args = self.args(args, depth + 1)?;
        let body = self.body(child, depth + 1)?;
        self.call_kind(self.ident(&name), args, body)
    }

    fn call_kind(&self, name: Ident, args: Vec<Arg>, body: Vec<Stmt>) -> DResult<InstanceKind> {
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
        let mut bindings = Vec::with_capacity(args.len());
        for arg in args {
            let Some(name) = arg.name else {
                return Err(Box::new(
                    Diagnostic::error(
                        SYNTAX_ERROR,
                        format!("`{}` takes `name = value` bindings", what.name),
                    )
                    .at(arg.span, "expected `name = value` here")
                    .with_secondary(what.span, format!("in this `{}`", what.name)),
                ));
            };
            bindings.push(Binding {
                name,
                value: arg.value,
            });
        }
        Ok(bindings)
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
            let default = match parts.next() {
                Some(default) => Some(self.expr(default, depth)?),
                None => None,
            };
            let name = self.ident(&name);
            params.push(Param { name, default });
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
                    name = part.into_inner().next();
                    continue;
                }
                let value = self.expr(part, depth)?;
                let name = name.take().map(|n| self.ident(&n));
                args.push(Arg { name, value, span });
            }
        }
        Ok(args)
    }

    fn bindings(&self, pair: P<'_>, depth: usize) -> DResult<Vec<Binding>> {
        let mut bindings = Vec::new();
        for binding in pair.into_inner() {
            let [name, value] = self.exactly(binding)?;
            let value = self.expr(value, depth)?;
            let name = self.ident(&name);
            bindings.push(Binding { name, value });
        }
        Ok(bindings)
    }
}

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
