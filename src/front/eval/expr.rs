//! Expression evaluation with OpenSCAD's semantics.
//!
//! Every number literal becomes a slot-tracking [`Num`] (or a constant once frozen);
//! arithmetic keeps affine forms where it can (see `ir::num`), and every use that decides
//! structure — a condition, a comparison, an index, a range bound — freezes the slots it
//! touches. Built-in functions live in `builtins`.

use super::scope::Scope;
use super::value::{Closure, RangeValue, Value};
use super::{Eval, MAX_CALL_DEPTH};
use crate::front::ast::{Arg, BinaryOp, Binding, Expr, ExprKind, Param, UnaryOp, VecElem};
use crate::front::diag::{DResult, Diagnostic};
use crate::ir::Num;
use crate::ir::num::FreezeSide;
use crate::span::Span;
use std::rc::Rc;

/// OpenSCAD's truthiness.
pub fn truthy(v: &Value) -> bool {
    match v {
        Value::Undef => false,
        Value::Bool(b) => *b,
        Value::Num(n) => n.value != 0.0,
        Value::Str(s) => !s.is_empty(),
        Value::Vector(v) => !v.is_empty(),
        Value::Range(_) | Value::Function(_) => true,
    }
}

/// Deep equality as OpenSCAD's `==`.
pub fn values_equal(a: &Value, b: &Value) -> bool {
    match (a, b) {
        (Value::Undef, Value::Undef) => true,
        (Value::Bool(x), Value::Bool(y)) => x == y,
        (Value::Num(x), Value::Num(y)) => x.value == y.value,
        (Value::Str(x), Value::Str(y)) => x == y,
        (Value::Vector(x), Value::Vector(y)) => {
            x.len() == y.len() && x.iter().zip(y.iter()).all(|(p, q)| values_equal(p, q))
        }
        (Value::Range(x), Value::Range(y)) => {
            x.start.value == y.start.value
                && x.step.value == y.step.value
                && x.end.value == y.end.value
        }
        _ => false,
    }
}

impl Eval<'_> {
    pub fn expr(&mut self, e: &Expr, scope: &Rc<Scope>) -> DResult<Value> {
        self.tick(e.span)?;
        let v = self.expr_kind(e, scope)?;
        self.note_nonfinite(e, &v);
        Ok(v)
    }

    fn expr_kind(&mut self, e: &Expr, scope: &Rc<Scope>) -> DResult<Value> {
        match &e.kind {
            ExprKind::Number { value, .. } => Ok(Value::Num(self.literal(e.span, *value))),
            ExprKind::Bool(b) => Ok(Value::Bool(*b)),
            ExprKind::Str(s) => Ok(Value::Str(s.as_str().into())),
            ExprKind::Undef => Ok(Value::Undef),
            ExprKind::Ident(name) => self.variable(name, e.span, scope),
            ExprKind::Vector(elems) => {
                let mut out = Vec::with_capacity(elems.len());
                for el in elems {
                    self.vec_elem(el, scope, &mut out)?;
                }
                Ok(Value::Vector(Rc::new(out)))
            }
            ExprKind::Range { start, step, end } => self.range(start, step.as_deref(), end, scope),
            ExprKind::Unary(op, x) => {
                let v = self.expr(x, scope)?;
                Ok(self.unary(*op, v, x.span))
            }
            ExprKind::Binary(op, a, b) => self.binary(*op, a, b, scope),
            ExprKind::Ternary(c, a, b) => {
                let cv = self.expr(c, scope)?;
                if self.condition(&cv, "a condition") {
                    self.expr(a, scope)
                } else {
                    self.expr(b, scope)
                }
            }
            ExprKind::Index(v, i) => {
                let vv = self.expr(v, scope)?;
                let iv = self.expr(i, scope)?;
                Ok(self.index(&vv, &iv))
            }
            ExprKind::Member(v, m) => {
                let vv = self.expr(v, scope)?;
                let i = match m.name.as_str() {
                    "x" => 0.0,
                    "y" => 1.0,
                    "z" => 2.0,
                    _ => return Ok(Value::Undef),
                };
                Ok(self.index(&vv, &Value::constant(i)))
            }
            ExprKind::Call { callee, args } => self.call(callee, args, e.span, scope),
            ExprKind::Let { bindings, body } => {
                let inner = self.let_scope(bindings, scope)?;
                self.expr(body, &inner)
            }
            ExprKind::Assert { args, body } => {
                self.assert(args, e.span, scope)?;
                match body {
                    Some(b) => self.expr(b, scope),
                    None => Ok(Value::Undef),
                }
            }
            ExprKind::Echo { args, body } => {
                for a in args {
                    self.expr(&a.value, scope)?;
                }
                match body {
                    Some(b) => self.expr(b, scope),
                    None => Ok(Value::Undef),
                }
            }
            ExprKind::FunctionLiteral { .. } => {
                let def = self.defs.functions.get(&e.span).cloned().ok_or_else(|| {
                    Box::new(
                        Diagnostic::error("E0900", "internal: function literal not indexed")
                            .at(e.span, ""),
                    )
                })?;
                Ok(Value::Function(Rc::new(Closure {
                    name: def.name.clone(),
                    params: def.params.clone(),
                    body: def.body.clone(),
                    scope: scope.clone(),
                })))
            }
        }
    }

    /// Counts one step of work; a model past [`super::MAX_STEPS`] is too large.
    pub fn tick(&mut self, span: Span) -> DResult<()> {
        self.steps += 1;
        if self.steps > super::MAX_STEPS || self.parts.len() > super::MAX_PARTS {
            return Err(Box::new(
                Diagnostic::error("E0304", "the model is too large to evaluate")
                    .at(span, "evaluation stopped here")
                    .with_note(format!(
                        "reparamc evaluates at most {} expressions and {} parts; check loop bounds and recursion",
                        super::MAX_STEPS,
                        super::MAX_PARTS
                    )),
            ));
        }
        Ok(())
    }

    fn variable(&mut self, name: &str, span: Span, scope: &Rc<Scope>) -> DResult<Value> {
        if let Some(v) = scope.lookup(name) {
            return Ok(v);
        }
        if let Some(v) = special_default(name) {
            return Ok(v);
        }
        // A function name used as a value is a function reference in OpenSCAD 2021.
        if let Some((def, home)) = scope.lookup_function(name) {
            return Ok(Value::Function(Rc::new(Closure {
                name: def.name.clone(),
                params: def.params.clone(),
                body: def.body.clone(),
                scope: home,
            })));
        }
        let mut d = Diagnostic::warning("W0102", format!("unknown variable `{name}`"))
            .at(span, "not defined in this scope: it is `undef`");
        if let Some(s) = super::suggest(name, &scope.visible_names()) {
            d = d.with_note(format!(
                "help: a variable with a similar name exists: `{s}`"
            ));
        }
        self.warnings.push(d.with_note(super::AS_OPENSCAD));
        Ok(Value::Undef)
    }

    /// Decides a condition; a number used as a condition freezes its slots.
    pub fn condition(&mut self, v: &Value, why: &str) -> bool {
        self.freeze_value(v, why);
        truthy(v)
    }

    fn vec_elem(&mut self, el: &VecElem, scope: &Rc<Scope>, out: &mut Vec<Value>) -> DResult<()> {
        match el {
            VecElem::Expr(e) => out.push(self.expr(e, scope)?),
            VecElem::For { bindings, body, .. } => {
                self.for_each_binding(bindings, scope, &mut |ev, inner| {
                    ev.vec_elem(body, inner, out)
                })?;
            }
            VecElem::ForC {
                init,
                cond,
                update,
                body,
                span,
            } => {
                let mut inner = self.let_scope(init, scope)?;
                let mut count = 0usize;
                loop {
                    let c = self.expr(cond, &inner)?;
                    if !self.condition(&c, "a loop condition") {
                        break;
                    }
                    count += 1;
                    if count > 1_000_000 {
                        return Err(Box::new(
                            Diagnostic::error("E0302", "list comprehension loop does not end")
                                .at(*span, "still running after 1,000,000 iterations"),
                        ));
                    }
                    self.vec_elem(body, &inner, out)?;
                    let next = Scope::child(scope);
                    for b in update {
                        let v = self.expr(&b.value, &inner)?;
                        next.set(&b.name.name, v);
                    }
                    inner = next;
                }
            }
            VecElem::If {
                cond,
                then,
                otherwise,
                ..
            } => {
                let c = self.expr(cond, scope)?;
                if self.condition(&c, "a condition") {
                    self.vec_elem(then, scope, out)?;
                } else if let Some(o) = otherwise {
                    self.vec_elem(o, scope, out)?;
                }
            }
            VecElem::Let { bindings, body, .. } => {
                let inner = self.let_scope(bindings, scope)?;
                self.vec_elem(body, &inner, out)?;
            }
            VecElem::Each(inner, _) => {
                let mut tmp = Vec::new();
                self.vec_elem(inner, scope, &mut tmp)?;
                for v in tmp {
                    out.extend(self.iteration_values(&v));
                }
            }
        }
        Ok(())
    }

    /// The values `for` visits for one binding value.
    pub fn iteration_values(&mut self, v: &Value) -> Vec<Value> {
        match v {
            Value::Vector(items) => items.as_ref().clone(),
            Value::Range(r) => {
                self.freeze_num(&r.start, "a range bound");
                self.freeze_num(&r.step, "a range step");
                self.freeze_num(&r.end, "a range bound");
                (0..r.count())
                    .map(|k| Value::constant(r.start.value + r.step.value * k as f64))
                    .collect()
            }
            Value::Str(s) => s
                .chars()
                .map(|c| Value::Str(c.to_string().into()))
                .collect(),
            Value::Undef => Vec::new(),
            other => vec![other.clone()],
        }
    }

    /// Runs `f` once per combination of the bindings (first binding outermost).
    pub fn for_each_binding(
        &mut self,
        bindings: &[Binding],
        scope: &Rc<Scope>,
        f: &mut dyn FnMut(&mut Self, &Rc<Scope>) -> DResult<()>,
    ) -> DResult<()> {
        let Some((first, rest)) = bindings.split_first() else {
            return f(self, scope);
        };
        let v = self.expr(&first.value, scope)?;
        if let Value::Range(r) = &v {
            // Ranges are walked lazily: a long one must not be materialised.
            self.freeze_value(&v, "a range bound");
            for k in 0..r.count() {
                self.tick(first.value.span)?;
                let inner = Scope::child(scope);
                inner.set(
                    &first.name.name,
                    Value::constant(r.start.value + r.step.value * k as f64),
                );
                self.for_each_binding(rest, &inner, f)?;
            }
            return Ok(());
        }
        for item in self.iteration_values(&v) {
            let inner = Scope::child(scope);
            inner.set(&first.name.name, item);
            self.for_each_binding(rest, &inner, f)?;
        }
        Ok(())
    }

    /// A scope with `let`-style sequential bindings; a repeated name keeps its first value.
    pub fn let_scope(&mut self, bindings: &[Binding], scope: &Rc<Scope>) -> DResult<Rc<Scope>> {
        let inner = Scope::child(scope);
        for b in bindings {
            if inner.has_local(&b.name.name) {
                continue;
            }
            let v = self.expr(&b.value, &inner)?;
            inner.set(&b.name.name, v);
        }
        Ok(inner)
    }

    fn range(
        &mut self,
        start: &Expr,
        step: Option<&Expr>,
        end: &Expr,
        scope: &Rc<Scope>,
    ) -> DResult<Value> {
        let mut s = self.number(start, scope, "a range bound")?;
        let st = match step {
            Some(x) => self.number(x, scope, "a range step")?,
            None => Num::constant(1.0),
        };
        let mut e = self.number(end, scope, "a range bound")?;
        if step.is_none() && s.value > e.value {
            // OpenSCAD 2021 swaps a descending two-part range (deprecated but still done).
            std::mem::swap(&mut s, &mut e);
        }
        Ok(Value::Range(Rc::new(RangeValue {
            start: s,
            step: st,
            end: e,
        })))
    }

    /// Evaluates `e` and requires a number.
    pub fn number(&mut self, e: &Expr, scope: &Rc<Scope>, what: &str) -> DResult<Num> {
        match self.expr(e, scope)? {
            Value::Num(n) => Ok(n),
            other => Err(Box::new(
                Diagnostic::error("E0103", format!("{what} must be a number"))
                    .at(e.span, format!("this is {}", other.type_name())),
            )),
        }
    }

    fn unary(&mut self, op: UnaryOp, v: Value, _span: Span) -> Value {
        match op {
            UnaryOp::Not => Value::Bool(!self.condition(&v, "a negated condition")),
            UnaryOp::Plus => v,
            UnaryOp::Neg => negate(&v),
        }
    }

    fn binary(&mut self, op: BinaryOp, a: &Expr, b: &Expr, scope: &Rc<Scope>) -> DResult<Value> {
        if matches!(op, BinaryOp::And | BinaryOp::Or) {
            // Short-circuit: `b` is evaluated only when `a` does not decide.
            let av = self.expr(a, scope)?;
            if let Some(decided) = self.decided_by_left(op, &av) {
                return Ok(decided);
            }
            let bv = self.expr(b, scope)?;
            return Ok(Value::Bool(self.condition(&bv, "a condition")));
        }
        let av = self.expr(a, scope)?;
        let bv = self.expr(b, scope)?;
        Ok(self.apply_binary(op, &av, &bv))
    }

    pub fn apply_binary(&mut self, op: BinaryOp, a: &Value, b: &Value) -> Value {
        use BinaryOp::*;
        match op {
            Add | Sub => self.add_sub(op == Sub, a, b),
            Mul => self.multiply(a, b),
            Div => match (a, b) {
                (Value::Num(x), Value::Num(y)) => Value::Num(x.div(y)),
                (Value::Vector(v), Value::Num(_)) => Value::Vector(Rc::new(
                    v.iter().map(|x| self.apply_binary(Div, x, b)).collect(),
                )),
                (Value::Num(_), Value::Vector(v)) => Value::Vector(Rc::new(
                    v.iter().map(|y| self.apply_binary(Div, a, y)).collect(),
                )),
                _ => Value::Undef,
            },
            Mod => match (a, b) {
                (Value::Num(x), Value::Num(y)) => {
                    Value::Num(Num::opaque_of(&[x, y], x.value % y.value))
                }
                _ => Value::Undef,
            },
            Pow => match (a, b) {
                (Value::Num(x), Value::Num(y)) => {
                    Value::Num(Num::opaque_of(&[x, y], x.value.powf(y.value)))
                }
                _ => Value::Undef,
            },
            Eq | Ne => {
                self.freeze_value(a, "a comparison");
                self.freeze_value(b, "a comparison");
                Value::Bool(values_equal(a, b) == (op == Eq))
            }
            Lt | Le | Gt | Ge => self.compare(op, a, b),
            // Both operands are values already (`binary` short-circuits before evaluating
            // the right one): the same result.
            And | Or => match self.decided_by_left(op, a) {
                Some(decided) => decided,
                None => Value::Bool(self.condition(b, "a condition")),
            },
        }
    }

    /// For `&&` and `||`: the result when the left operand `a` decides it.
    fn decided_by_left(&mut self, op: BinaryOp, a: &Value) -> Option<Value> {
        let at = self.condition(a, "a condition");
        ((op == BinaryOp::And) != at).then_some(Value::Bool(at))
    }

    fn compare(&mut self, op: BinaryOp, a: &Value, b: &Value) -> Value {
        self.freeze_value(a, "a comparison");
        self.freeze_value(b, "a comparison");
        let ord = match (a, b) {
            (Value::Num(x), Value::Num(y)) => x.value.partial_cmp(&y.value),
            (Value::Str(x), Value::Str(y)) => Some(x.cmp(y)),
            (Value::Bool(x), Value::Bool(y)) => Some(x.cmp(y)),
            _ => None,
        };
        let Some(ord) = ord else { return Value::Undef };
        use std::cmp::Ordering::*;
        Value::Bool(match op {
            BinaryOp::Lt => ord == Less,
            BinaryOp::Le => ord != Greater,
            BinaryOp::Gt => ord == Greater,
            _ => ord != Less,
        })
    }

    fn add_sub(&mut self, sub: bool, a: &Value, b: &Value) -> Value {
        match (a, b) {
            (Value::Num(x), Value::Num(y)) => Value::Num(if sub { x.sub(y) } else { x.add(y) }),
            (Value::Vector(x), Value::Vector(y)) => Value::Vector(Rc::new(
                x.iter()
                    .zip(y.iter())
                    .map(|(p, q)| self.add_sub(sub, p, q))
                    .collect(),
            )),
            _ => Value::Undef,
        }
    }

    /// Which factor of `a * b` to freeze: the one without named (variable) slots, else `b`.
    fn freeze_side(&self, a: &Num, b: &Num) -> FreezeSide {
        let named = |n: &Num| n.deps().iter().any(|s| self.lits.is_named(*s));
        if named(b) && !named(a) {
            FreezeSide::Left
        } else {
            FreezeSide::Right
        }
    }

    pub fn mul_nums(&self, a: &Num, b: &Num) -> Num {
        a.mul(b, self.freeze_side(a, b))
    }

    fn multiply(&mut self, a: &Value, b: &Value) -> Value {
        match (a, b) {
            (Value::Num(x), Value::Num(y)) => Value::Num(self.mul_nums(x, y)),
            (Value::Num(_), Value::Vector(v)) => {
                Value::Vector(Rc::new(v.iter().map(|y| self.multiply(a, y)).collect()))
            }
            (Value::Vector(v), Value::Num(_)) => {
                Value::Vector(Rc::new(v.iter().map(|x| self.multiply(x, b)).collect()))
            }
            (Value::Vector(x), Value::Vector(y)) => self.vector_product(x, y),
            _ => Value::Undef,
        }
    }

    /// Dot product, matrix·vector, vector·matrix or matrix·matrix.
    fn vector_product(&mut self, x: &[Value], y: &[Value]) -> Value {
        let is_row = |v: &[Value]| !v.is_empty() && v.iter().all(|e| matches!(e, Value::Num(_)));
        let dot = |ev: &mut Self, p: &[Value], q: &[Value]| -> Value {
            if p.len() != q.len() || !is_row(p) || !is_row(q) {
                return Value::Undef;
            }
            let mut acc = Num::constant(0.0);
            for (u, v) in p.iter().zip(q) {
                if let (Value::Num(u), Value::Num(v)) = (u, v) {
                    acc = acc.add(&ev.mul_nums(u, v));
                }
            }
            Value::Num(acc)
        };
        if is_row(x) && is_row(y) {
            return dot(self, x, y);
        }
        let column = |m: &[Value], j: usize| -> Vec<Value> {
            m.iter()
                .map(|r| {
                    r.as_vec()
                        .and_then(|r| r.get(j))
                        .cloned()
                        .unwrap_or(Value::Undef)
                })
                .collect()
        };
        if is_row(y) {
            // matrix · vector
            let rows: Vec<Value> = x
                .iter()
                .map(|r| r.as_vec().map_or(Value::Undef, |r| dot(self, r, y)))
                .collect();
            return Value::Vector(Rc::new(rows));
        }
        let ncols = y.first().and_then(|r| r.as_vec()).map_or(0, |r| r.len());
        if is_row(x) {
            // vector · matrix
            let out: Vec<Value> = (0..ncols).map(|j| dot(self, x, &column(y, j))).collect();
            return Value::Vector(Rc::new(out));
        }
        let rows: Vec<Value> = x
            .iter()
            .map(|r| {
                let r = r.as_vec().unwrap_or(&[]).to_vec();
                Value::Vector(Rc::new(
                    (0..ncols).map(|j| dot(self, &r, &column(y, j))).collect(),
                ))
            })
            .collect();
        Value::Vector(Rc::new(rows))
    }

    pub fn index(&mut self, v: &Value, i: &Value) -> Value {
        let Value::Num(n) = i else {
            return Value::Undef;
        };
        self.freeze_num(n, "an index");
        let k = n.value;
        if k.is_nan() || k < 0.0 || !k.is_finite() {
            return Value::Undef;
        }
        let k = k as usize;
        match v {
            Value::Vector(items) => items.get(k).cloned().unwrap_or(Value::Undef),
            Value::Str(s) => s
                .chars()
                .nth(k)
                .map_or(Value::Undef, |c| Value::Str(c.to_string().into())),
            Value::Range(r) => {
                if k == 0 {
                    Value::Num(r.start.clone())
                } else if k == 1 {
                    Value::Num(r.step.clone())
                } else if k == 2 {
                    Value::Num(r.end.clone())
                } else {
                    Value::Undef
                }
            }
            _ => Value::Undef,
        }
    }

    fn call(
        &mut self,
        callee: &Expr,
        args: &[Arg],
        span: Span,
        scope: &Rc<Scope>,
    ) -> DResult<Value> {
        if let ExprKind::Ident(name) = &callee.kind {
            if let Some((def, home)) = scope.lookup_function(name) {
                return self.call_user(&def.params, &def.body, &def.name, &home, args, span, scope);
            }
            if let Some(Value::Function(c)) = scope.lookup(name) {
                return self.call_user(&c.params, &c.body, &c.name, &c.scope, args, span, scope);
            }
            if let Some(v) = self.builtin_function(name, args, span, scope)? {
                return Ok(v);
            }
            let mut d = Diagnostic::warning("W0104", format!("unknown function `{name}`")).at(
                callee.span,
                "no function of this name is defined: the call is `undef`",
            );
            if let Some(s) = super::suggest(name, &scope.visible_functions()) {
                d = d.with_note(format!(
                    "help: a function with a similar name exists: `{s}`"
                ));
            }
            self.warnings.push(d.with_note(super::AS_OPENSCAD));
            return Ok(Value::Undef);
        }
        match self.expr(callee, scope)? {
            Value::Function(c) => {
                self.call_user(&c.params, &c.body, &c.name, &c.scope, args, span, scope)
            }
            other => Err(Box::new(
                Diagnostic::error("E0105", "this value cannot be called").at(
                    callee.span,
                    format!("this is {}, not a function", other.type_name()),
                ),
            )),
        }
    }

    #[allow(clippy::too_many_arguments)]
    fn call_user(
        &mut self,
        params: &[Param],
        body: &Expr,
        name: &str,
        home: &Rc<Scope>,
        args: &[Arg],
        span: Span,
        caller: &Rc<Scope>,
    ) -> DResult<Value> {
        let inner = self.bind_params(params, args, name, "function", home, caller)?;
        self.depth += 1;
        if self.depth > MAX_CALL_DEPTH {
            self.depth -= 1;
            return Err(Box::new(
                Diagnostic::error("E0301", format!("recursion without end in function `{name}`"))
                    .at(span, format!("more than {MAX_CALL_DEPTH} nested calls"))
                    .with_note("help: make sure every recursive call moves toward a case that does not recurse"),
            ));
        }
        let r = self.expr(body, &inner);
        self.depth -= 1;
        r
    }

    /// Binds call arguments to parameters in a new call scope; defaults are evaluated in
    /// the definition's scope, as OpenSCAD does.
    pub fn bind_params(
        &mut self,
        params: &[Param],
        args: &[Arg],
        name: &str,
        what: &str,
        home: &Rc<Scope>,
        caller: &Rc<Scope>,
    ) -> DResult<Rc<Scope>> {
        let inner = Scope::call(home, caller);
        let mut positional = 0usize;
        for a in args {
            let v = self.expr(&a.value, caller)?;
            match &a.name {
                Some(n) if n.name.starts_with('$') => inner.set(&n.name, v),
                Some(n) => {
                    if !params.iter().any(|p| p.name.name == n.name) {
                        let names: Vec<String> =
                            params.iter().map(|p| p.name.name.clone()).collect();
                        let d = Diagnostic::warning(
                            "W0106",
                            format!("{what} `{name}` has no parameter `{}`", n.name),
                        )
                        .at(n.span, "unknown parameter")
                        .with_note(if names.is_empty() {
                            format!("`{name}` takes no parameters")
                        } else {
                            format!("`{name}` takes: {}", names.join(", "))
                        })
                        .with_note(format!(
                            "OpenSCAD warns and sets `{}` inside `{name}` all the same; so does reparamc",
                            n.name
                        ));
                        self.warnings.push(d);
                    }
                    inner.set(&n.name, v);
                }
                None => {
                    let Some(p) = params.get(positional) else {
                        self.warnings.push(
                            Diagnostic::warning(
                                "W0107",
                                format!("too many arguments to {what} `{name}`"),
                            )
                            .at(
                                a.span,
                                format!("`{name}` takes {} argument(s)", params.len()),
                            )
                            .with_note(
                                "OpenSCAD warns and ignores the extra ones; so does reparamc",
                            ),
                        );
                        continue;
                    };
                    positional += 1;
                    inner.set(&p.name.name, v);
                }
            }
        }
        for p in params {
            if inner.has_local(&p.name.name) {
                continue;
            }
            let v = match &p.default {
                Some(d) => self.expr(d, home)?,
                None => Value::Undef,
            };
            inner.set(&p.name.name, v);
        }
        Ok(inner)
    }

    pub fn assert(&mut self, args: &[Arg], span: Span, scope: &Rc<Scope>) -> DResult<()> {
        let Some(first) = args.first() else {
            return Ok(());
        };
        let c = self.expr(&first.value, scope)?;
        if self.condition(&c, "an assertion") {
            return Ok(());
        }
        let msg = match args.get(1) {
            Some(a) => format!(": {}", self.expr(&a.value, scope)?),
            None => String::new(),
        };
        Err(Box::new(
            Diagnostic::error("E0303", format!("assertion failed{msg}"))
                .at(first.value.span, "this is false")
                .with_secondary(span, "in this assert"),
        ))
    }
}

/// Unary minus, elementwise on vectors.
pub fn negate(v: &Value) -> Value {
    match v {
        Value::Num(n) => Value::Num(n.neg()),
        Value::Vector(items) => Value::Vector(Rc::new(items.iter().map(negate).collect())),
        _ => Value::Undef,
    }
}

/// Values of special variables nobody set.
fn special_default(name: &str) -> Option<Value> {
    Some(match name {
        "$fn" => Value::constant(0.0),
        "$fa" => Value::constant(12.0),
        "$fs" => Value::constant(2.0),
        "$t" => Value::constant(0.0),
        "$preview" => Value::Bool(false),
        "$children" => Value::constant(0.0),
        "$vpr" | "$vpt" => Value::Vector(Rc::new(vec![Value::constant(0.0); 3])),
        "$vpd" => Value::constant(500.0),
        "$vpf" => Value::constant(22.5),
        "PI" => Value::constant(std::f64::consts::PI),
        _ if name.starts_with('$') => Value::Undef,
        _ => return None,
    })
}
