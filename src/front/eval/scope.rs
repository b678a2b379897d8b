//! Scopes: where names are looked up.
//!
//! OpenSCAD has three namespaces (variables, functions, modules) and two kinds of lookup:
//! ordinary names are lexical (the defining scope's chain), `$`-names are dynamic (the
//! caller's chain). A [`Scope`] therefore has a lexical `parent` and, for the scope of a
//! module or function call, a dynamic `caller`. Definitions are shared `Rc`s made once per
//! run (see [`Defs`]), so scopes are cheap to create.

use super::value::Value;
use crate::front::ast::{Expr, Param, Stmt};
use crate::span::Span;
use std::cell::RefCell;
use std::collections::HashMap;
use std::rc::Rc;

/// A user module definition.
#[derive(Debug)]
pub struct ModuleDefn {
    /// The defining statement's span: the key into [`Defs`].
    pub span: Span,
    pub name: String,
    pub name_span: Span,
    pub params: Vec<Param>,
    pub body: Vec<Stmt>,
}

/// A user function definition or function literal.
#[derive(Debug)]
pub struct FunctionDefn {
    pub name: String,
    pub params: Vec<Param>,
    pub body: Expr,
}

/// Definitions keyed by the span of their defining statement or literal, made once.
#[derive(Debug, Default)]
pub struct Defs {
    pub modules: HashMap<Span, Rc<ModuleDefn>>,
    pub functions: HashMap<Span, Rc<FunctionDefn>>,
}

/// A definition and, for one imported with `use`, the scope its body resolves names in.
type Defined<T> = (Rc<T>, Option<Rc<Scope>>);

#[derive(Debug, Default)]
pub struct Scope {
    vars: RefCell<HashMap<String, Value>>,
    /// Functions by name, with the scope they resolve in when it is not this one (`use`).
    functions: RefCell<HashMap<String, Defined<FunctionDefn>>>,
    modules: RefCell<HashMap<String, Defined<ModuleDefn>>>,
    parent: Option<Rc<Scope>>,
    caller: Option<Rc<Scope>>,
}

impl Scope {
    pub fn root() -> Rc<Scope> {
        Rc::new(Scope::default())
    }

    /// A nested block: lexical and dynamic parent are both `parent`.
    pub fn child(parent: &Rc<Scope>) -> Rc<Scope> {
        Rc::new(Scope {
            parent: Some(parent.clone()),
            ..Scope::default()
        })
    }

    /// The scope of a call: names resolve in `definition`, `$`-names in `caller`.
    pub fn call(definition: &Rc<Scope>, caller: &Rc<Scope>) -> Rc<Scope> {
        Rc::new(Scope {
            parent: Some(definition.clone()),
            caller: Some(caller.clone()),
            ..Scope::default()
        })
    }

    pub fn set(&self, name: &str, value: Value) {
        self.vars.borrow_mut().insert(name.to_string(), value);
    }

    /// Defines a function here; `home` is the scope its body sees when that is not this one
    /// (a function imported with `use` sees its own file's top level).
    pub fn define_function(&self, def: Rc<FunctionDefn>, home: Option<Rc<Scope>>) {
        self.functions
            .borrow_mut()
            .insert(def.name.clone(), (def, home));
    }

    pub fn define_module(&self, def: Rc<ModuleDefn>, home: Option<Rc<Scope>>) {
        self.modules
            .borrow_mut()
            .insert(def.name.clone(), (def, home));
    }

    pub fn has_local(&self, name: &str) -> bool {
        self.vars.borrow().contains_key(name)
    }

    /// Looks a variable up: `$`-names along the dynamic chain, others lexically.
    pub fn lookup(&self, name: &str) -> Option<Value> {
        if let Some(v) = self.vars.borrow().get(name) {
            return Some(v.clone());
        }
        let next = if name.starts_with('$') {
            self.caller.as_ref().or(self.parent.as_ref())
        } else {
            self.parent.as_ref()
        };
        next.and_then(|s| s.lookup(name))
    }

    /// A function and the scope it was defined in.
    pub fn lookup_function(self: &Rc<Self>, name: &str) -> Option<(Rc<FunctionDefn>, Rc<Scope>)> {
        if let Some((f, home)) = self.functions.borrow().get(name) {
            return Some((f.clone(), home.clone().unwrap_or_else(|| self.clone())));
        }
        self.parent.as_ref()?.lookup_function(name)
    }

    /// A module and the scope it was defined in.
    pub fn lookup_module(self: &Rc<Self>, name: &str) -> Option<(Rc<ModuleDefn>, Rc<Scope>)> {
        if let Some((m, home)) = self.modules.borrow().get(name) {
            return Some((m.clone(), home.clone().unwrap_or_else(|| self.clone())));
        }
        self.parent.as_ref()?.lookup_module(name)
    }

    /// Every variable name visible from here (for "did you mean" suggestions).
    pub fn visible_names(&self) -> Vec<String> {
        let mut names: Vec<String> = self.vars.borrow().keys().cloned().collect();
        if let Some(p) = &self.parent {
            names.extend(p.visible_names());
        }
        names
    }

    pub fn visible_modules(&self) -> Vec<String> {
        let mut names: Vec<String> = self.modules.borrow().keys().cloned().collect();
        if let Some(p) = &self.parent {
            names.extend(p.visible_modules());
        }
        names
    }

    pub fn visible_functions(&self) -> Vec<String> {
        let mut names: Vec<String> = self.functions.borrow().keys().cloned().collect();
        if let Some(p) = &self.parent {
            names.extend(p.visible_functions());
        }
        names
    }
}
