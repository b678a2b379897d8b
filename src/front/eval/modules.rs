//! OpenSCAD's built-in modules: primitives, transforms and booleans.
//!
//! Primitives become IR parts with their arguments normalised as OpenSCAD does (a cylinder
//! always gets `h`, `r1`, `r2`; `d` wins over `r`); transforms compose the context's world
//! matrix. Rotation and mirror arguments decide structure, so their literals are frozen; a
//! rotation that is not a multiple of 90° marks the parts below it as off the axes.

use super::scope::Scope;
use super::stmt::group;
use super::value::Value;
use super::{Ctx, Eval};
use crate::front::ast::{Arg, Stmt};
use crate::front::diag::{DResult, Diagnostic};
use crate::ir::part::Misalignment;
use crate::ir::{CsgNode, Num, Part, Primitive, Transform};
use crate::span::Span;
use crate::tolerance::ROTATION_SNAP;
use std::collections::HashMap;
use std::rc::Rc;

use super::builtins::{cos_degrees, sin_degrees};
use super::format_number;

/// How OpenSCAD 2021.01 converts a vector argument of a built-in module.
#[derive(Clone, Copy)]
struct Shape {
    /// A single number stands for all three entries.
    scalar: bool,
    /// The vector lengths accepted (shorter ones are padded with `pad`).
    lengths: &'static [usize],
    pad: f64,
    /// An entry that is not a number stops the conversion, keeping the entries before it
    /// (`cube([1, 2, "a"])` is `cube([1, 2, 1])`).
    partial: bool,
    /// An entry that is not a number counts as 0 (`rotate([1, "b", 0])`).
    zero_bad: bool,
    /// What a failed conversion leaves, in words.
    instead: &'static str,
}

impl Shape {
    const CUBE: Shape = Shape {
        scalar: true,
        lengths: &[3],
        pad: 1.0,
        partial: true,
        zero_bad: false,
        instead: "1 for each size it cannot read",
    };
    const TRANSLATE: Shape = Shape {
        scalar: false,
        lengths: &[2, 3],
        pad: 0.0,
        partial: false,
        zero_bad: false,
        instead: "no translation",
    };
    const SCALE: Shape = Shape {
        scalar: true,
        lengths: &[2, 3],
        pad: 1.0,
        instead: "no scaling",
        ..Shape::TRANSLATE
    };
    const MIRROR: Shape = Shape {
        instead: "the normal [1, 0, 0]",
        ..Shape::TRANSLATE
    };
    const ANGLES: Shape = Shape {
        scalar: false,
        lengths: &[1, 2, 3],
        pad: 0.0,
        partial: false,
        zero_bad: true,
        instead: "0 for each angle it cannot read",
    };
    const AXIS: Shape = Shape {
        instead: "the z axis",
        ..Shape::TRANSLATE
    };

    fn wanted(&self) -> &'static str {
        if self.scalar {
            "a number or a vector of numbers"
        } else {
            "a vector of numbers"
        }
    }
}

/// Arguments of a built-in call, by parameter name, with the argument's span.
struct BuiltinArgs {
    named: HashMap<String, (Value, Span)>,
    /// A scope holding `$fn`-style arguments for what is below the call.
    scope: Rc<Scope>,
}

impl BuiltinArgs {
    fn get(&self, name: &str) -> Option<&(Value, Span)> {
        self.named.get(name).filter(|(v, _)| !v.is_undef())
    }
}

/// Snaps rotation entries that are within rounding of 0 or ±1 to exactly that.
fn snap(v: f64) -> f64 {
    for t in [0.0, 1.0, -1.0] {
        if (v - t).abs() < ROTATION_SNAP {
            return t;
        }
    }
    v
}

fn linear(m: [[f64; 3]; 3]) -> Transform {
    Transform::from_values(std::array::from_fn(|i| {
        [snap(m[i][0]), snap(m[i][1]), snap(m[i][2]), 0.0]
    }))
}

/// OpenSCAD 2021's `rotate([x, y, z])`: about x, then y, then z.
fn rotate_xyz(a: [f64; 3]) -> Transform {
    let (sx, cx) = (sin_degrees(a[0]), cos_degrees(a[0]));
    let (sy, cy) = (sin_degrees(a[1]), cos_degrees(a[1]));
    let (sz, cz) = (sin_degrees(a[2]), cos_degrees(a[2]));
    linear([
        [cy * cz, cz * sx * sy - cx * sz, cx * cz * sy + sx * sz],
        [cy * sz, cx * cz + sx * sy * sz, -cz * sx + cx * sy * sz],
        [-sy, cy * sx, cx * cy],
    ])
}

/// `rotate(a, v)`: `a` degrees about the axis `v`.
fn rotate_axis(a: f64, v: [f64; 3]) -> Transform {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    let [x, y, z] = if n > 0.0 {
        v.map(|c| c / n)
    } else {
        [0.0, 0.0, 1.0]
    };
    let (s, c) = (sin_degrees(a), cos_degrees(a));
    let k = 1.0 - c;
    linear([
        [x * x * k + c, x * y * k - z * s, x * z * k + y * s],
        [y * x * k + z * s, y * y * k + c, y * z * k - x * s],
        [z * x * k - y * s, z * y * k + x * s, z * z * k + c],
    ])
}

/// `mirror(v)`: reflection through the plane through the origin normal to `v`.
fn mirror(v: [f64; 3]) -> Transform {
    let n2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    if n2 == 0.0 {
        return Transform::identity();
    }
    let n = n2.sqrt();
    let u = v.map(|c| c / n);
    linear(std::array::from_fn(|i| {
        std::array::from_fn(|j| (if i == j { 1.0 } else { 0.0 }) - 2.0 * u[i] * u[j])
    }))
}

impl<'a> Eval<'a> {
    /// Evaluates a built-in module; `Ok(None)` if `name` is not one.
    #[allow(clippy::too_many_arguments)]
    pub fn builtin_module(
        &mut self,
        name: &str,
        args: &'a [Arg],
        children: &'a [Stmt],
        span: Span,
        scope: &Rc<Scope>,
        ctx: &Ctx<'a>,
    ) -> DResult<Option<Option<CsgNode>>> {
        let params: &[&str] = match name {
            "cube" => &["size", "center"],
            "cylinder" => &["h", "r1", "r2", "center"],
            "sphere" => &["r"],
            "translate" | "scale" | "mirror" => &["v"],
            "rotate" => &["a", "v"],
            "multmatrix" => &["m"],
            "color" => &["c", "alpha"],
            "union" | "group" | "render" | "difference" | "intersection" => &[],
            "children" => return self.children(args, scope, ctx).map(Some),
            "echo" | "assert" => {
                return self
                    .echo_assert(name, args, children, span, scope, ctx)
                    .map(Some);
            }
            _ => return Ok(None),
        };
        let bargs = self.builtin_args(params, args, scope)?;
        let node = match name {
            "cube" | "cylinder" | "sphere" => {
                if let Some(first) = children.first() {
                    self.warnings.push(
                        Diagnostic::warning(
                            "W0001",
                            format!("`{name}` takes no children; they are ignored"),
                        )
                        .at(first.span, "this is not drawn"),
                    );
                }
                self.primitive(name, &bargs, span, ctx)?
            }
            "union" | "group" | "render" | "color" => {
                self.children_block(children, &bargs.scope, ctx)?
            }
            "difference" => {
                let nodes = self.children_nodes(children, &bargs.scope, ctx)?;
                (!nodes.is_empty()).then_some(CsgNode::Difference(nodes))
            }
            "intersection" => {
                let nodes = self.children_nodes(children, &bargs.scope, ctx)?;
                (!nodes.is_empty()).then_some(CsgNode::Intersection(nodes))
            }
            _ => {
                let (local, misaligned) = self.transform(name, &bargs, span)?;
                let mut inner = ctx.clone();
                inner.transform = Rc::new(ctx.transform.compose(&local));
                if inner.misaligned.is_none() {
                    inner.misaligned = misaligned;
                }
                self.children_block(children, &bargs.scope, &inner)?
            }
        };
        Ok(Some(node))
    }

    fn children_nodes(
        &mut self,
        children: &'a [Stmt],
        scope: &Rc<Scope>,
        ctx: &Ctx<'a>,
    ) -> DResult<Vec<CsgNode>> {
        let s = Scope::child(scope);
        self.block(children, &s, ctx)
    }

    fn children_block(
        &mut self,
        children: &'a [Stmt],
        scope: &Rc<Scope>,
        ctx: &Ctx<'a>,
    ) -> DResult<Option<CsgNode>> {
        Ok(group(self.children_nodes(children, scope, ctx)?))
    }

    fn builtin_args(
        &mut self,
        params: &[&str],
        args: &[Arg],
        scope: &Rc<Scope>,
    ) -> DResult<BuiltinArgs> {
        let mut named = HashMap::new();
        let inner = Scope::child(scope);
        let mut positional = 0usize;
        for a in args {
            let v = self.expr(&a.value, scope)?;
            match &a.name {
                Some(n) if n.name.starts_with('$') => inner.set(&n.name, v),
                Some(n) => {
                    named.insert(n.name.clone(), (v, a.value.span));
                }
                None => {
                    if let Some(p) = params.get(positional) {
                        named.entry(p.to_string()).or_insert((v, a.value.span));
                    }
                    positional += 1;
                }
            }
        }
        Ok(BuiltinArgs {
            named,
            scope: inner,
        })
    }

    /// A number argument. Anything else is what OpenSCAD does with it: a warning, and the
    /// default in its place.
    fn num_arg(
        &mut self,
        bargs: &BuiltinArgs,
        name: &str,
        module: &str,
        default: f64,
    ) -> DResult<Num> {
        match bargs.get(name) {
            None => Ok(Num::constant(default)),
            Some((Value::Num(n), span)) => {
                self.finite(n, *span, &format!("`{name}` of `{module}`"))?;
                Ok(n.clone())
            }
            Some((other, span)) => {
                let text = format!("`{module}` needs a number for `{name}`");
                self.ignored_argument(text, *span, other, &format_number(default));
                Ok(Num::constant(default))
            }
        }
    }

    /// Warns that an argument OpenSCAD cannot convert is replaced by its default.
    fn ignored_argument(&mut self, message: String, span: Span, given: &Value, instead: &str) {
        self.warnings.push(
            Diagnostic::warning("W0108", message)
                .at(span, format!("this is {}", given.type_name()))
                .with_note(format!(
                    "OpenSCAD warns and uses {instead} instead; so does reparamc"
                )),
        );
    }

    /// A vector of numbers as OpenSCAD converts one: `shape` says how many entries it
    /// takes and what a failed conversion leaves. `None` when the argument is absent or
    /// cannot be converted (with a warning); the caller's default applies.
    fn vec3_arg(
        &mut self,
        bargs: &BuiltinArgs,
        name: &str,
        module: &str,
        shape: Shape,
    ) -> DResult<Option<[Num; 3]>> {
        let Some((v, span)) = bargs.get(name).cloned() else {
            return Ok(None);
        };
        let what = format!("`{name}` of `{module}`");
        let message = || format!("`{module}` needs {} for `{name}`", shape.wanted());
        match &v {
            Value::Num(n) if shape.scalar => {
                self.finite(n, span, &what)?;
                Ok(Some([n.clone(), n.clone(), n.clone()]))
            }
            Value::Vector(items) if shape.lengths.contains(&items.len()) => {
                let mut out: [Num; 3] = std::array::from_fn(|_| Num::constant(shape.pad));
                for (i, item) in items.iter().take(3).enumerate() {
                    match item {
                        Value::Num(n) => {
                            self.finite(n, span, &what)?;
                            out[i] = n.clone();
                        }
                        _ if shape.zero_bad => out[i] = Num::constant(0.0),
                        _ if shape.partial => {
                            self.ignored_argument(message(), span, &v, shape.instead);
                            return Ok(Some(out));
                        }
                        _ => {
                            self.ignored_argument(message(), span, &v, shape.instead);
                            return Ok(None);
                        }
                    }
                }
                if shape.zero_bad && items.iter().any(|x| x.as_num().is_none()) {
                    self.ignored_argument(message(), span, &v, shape.instead);
                }
                Ok(Some(out))
            }
            _ => {
                self.ignored_argument(message(), span, &v, shape.instead);
                Ok(None)
            }
        }
    }

    fn center_arg(&self, bargs: &BuiltinArgs) -> bool {
        matches!(bargs.get("center"), Some((Value::Bool(true), _)))
    }

    fn fragments(&mut self, scope: &Rc<Scope>) -> [f64; 3] {
        ["$fn", "$fa", "$fs"].map(|n| {
            let v = scope.lookup(n).unwrap_or(Value::Undef);
            self.freeze_value(&v, "a fragment count (`$fn`, `$fa`, `$fs`)");
            match (n, v) {
                (_, Value::Num(x)) => x.value,
                ("$fa", _) => 12.0,
                ("$fs", _) => 2.0,
                _ => 0.0,
            }
        })
    }

    fn primitive(
        &mut self,
        name: &str,
        bargs: &BuiltinArgs,
        span: Span,
        ctx: &Ctx<'a>,
    ) -> DResult<Option<CsgNode>> {
        let center = self.center_arg(bargs);
        let primitive = match name {
            "cube" => {
                let size = self
                    .vec3_arg(bargs, "size", "cube", Shape::CUBE)?
                    .unwrap_or_else(|| std::array::from_fn(|_| Num::constant(1.0)));
                Primitive::Cube { size, center }
            }
            "cylinder" => {
                let h = self.num_arg(bargs, "h", "cylinder", 1.0)?;
                let r = self.radius(bargs, "cylinder", "d", "r")?;
                let r1 = self
                    .radius(bargs, "cylinder", "d1", "r1")?
                    .or_else(|| r.clone())
                    .unwrap_or(Num::constant(1.0));
                let r2 = self
                    .radius(bargs, "cylinder", "d2", "r2")?
                    .or(r)
                    .unwrap_or(Num::constant(1.0));
                Primitive::Cylinder { h, r1, r2, center }
            }
            _ => {
                let r = self
                    .radius(bargs, "sphere", "d", "r")?
                    .unwrap_or(Num::constant(1.0));
                Primitive::Sphere { r }
            }
        };
        let fragments = self.fragments(&bargs.scope);
        let part = Part {
            name: ctx.part_name(),
            primitive,
            world: ctx.transform.as_ref().clone(),
            span,
            misaligned: ctx.misaligned.clone(),
            fragments,
            highlighted: ctx.highlight,
            statements: self.chain.clone(),
        };
        self.finite_part(&part)?;
        self.name_primitive_slots(&part, ctx);
        if ctx.background {
            self.background.push(part);
            return Ok(None);
        }
        self.parts.push(part);
        Ok(Some(CsgNode::Part(self.parts.len() - 1)))
    }

    /// OpenSCAD's radius lookup: a diameter wins over a radius; one that is not a number
    /// is warned about and left out, so the default radius (1) applies, as in OpenSCAD.
    fn radius(
        &mut self,
        bargs: &BuiltinArgs,
        module: &str,
        d: &str,
        r: &str,
    ) -> DResult<Option<Num>> {
        for (name, factor) in [(d, Some(0.5)), (r, None)] {
            let Some((v, span)) = bargs.get(name).cloned() else {
                continue;
            };
            let Value::Num(n) = v else {
                let text = format!("`{module}` needs a number for `{name}`");
                self.ignored_argument(text, span, &v, "its default radius");
                return Ok(None);
            };
            self.finite(&n, span, &format!("`{name}` of `{module}`"))?;
            return Ok(Some(match factor {
                Some(f) => n.mul(&Num::constant(f), crate::ir::num::FreezeSide::Right),
                None => n,
            }));
        }
        Ok(None)
    }

    /// The local matrix of a transform module and, if it turns things off the axes, why.
    fn transform(
        &mut self,
        name: &str,
        bargs: &BuiltinArgs,
        span: Span,
    ) -> DResult<(Transform, Option<Misalignment>)> {
        let local = match name {
            "translate" => {
                let v = self.vec3_arg(bargs, "v", "translate", Shape::TRANSLATE)?;
                let mut t = Transform::identity();
                if let Some(v) = v {
                    for (i, n) in v.into_iter().enumerate() {
                        self.name_slots(&n, ["x", "y", "z"][i], None);
                        t.m[i][3] = n;
                    }
                }
                t
            }
            "scale" => {
                let v = self.vec3_arg(bargs, "v", "scale", Shape::SCALE)?;
                let mut t = Transform::identity();
                if let Some(v) = v {
                    for (i, n) in v.into_iter().enumerate() {
                        self.name_slots(&n, ["width", "depth", "height"][i], None);
                        t.m[i][i] = n;
                    }
                }
                t
            }
            "rotate" => self.rotation(bargs)?,
            "mirror" => {
                let v = self.vec3_arg(bargs, "v", "mirror", Shape::MIRROR)?;
                let v = v.map_or([1.0, 0.0, 0.0], |v| {
                    v.map(|n| {
                        self.freeze_num(&n, "a mirror normal");
                        n.value
                    })
                });
                mirror(v)
            }
            _ => self.multmatrix(bargs)?,
        };
        let misaligned = local.axis_permutation().is_none().then(|| Misalignment {
            span,
            reason: format!("`{name}` here turns it off the x, y and z axes"),
        });
        Ok((local, misaligned))
    }

    fn rotation(&mut self, bargs: &BuiltinArgs) -> DResult<Transform> {
        let why = "a rotation angle";
        match bargs.get("a") {
            Some((Value::Num(a), span)) => {
                self.finite(a, *span, "the angle of `rotate`")?;
                let a = a.clone();
                self.freeze_num(&a, why);
                let axis = self.vec3_arg(bargs, "v", "rotate", Shape::AXIS)?;
                Ok(match axis {
                    Some(v) => rotate_axis(
                        a.value,
                        v.map(|n| {
                            self.freeze_num(&n, "a rotation axis");
                            n.value
                        }),
                    ),
                    None => rotate_xyz([0.0, 0.0, a.value]),
                })
            }
            Some((Value::Vector(_), _)) => {
                let v = self
                    .vec3_arg(bargs, "a", "rotate", Shape::ANGLES)?
                    .unwrap_or_else(|| std::array::from_fn(|_| Num::constant(0.0)));
                Ok(rotate_xyz(v.map(|n| {
                    self.freeze_num(&n, why);
                    n.value
                })))
            }
            None => Ok(Transform::identity()),
            Some((other, span)) => {
                let (other, span) = (other.clone(), *span);
                let text = "`rotate` needs a number or a vector of angles for `a`".to_string();
                self.ignored_argument(text, span, &other, "no rotation");
                Ok(Transform::identity())
            }
        }
    }

    fn multmatrix(&mut self, bargs: &BuiltinArgs) -> DResult<Transform> {
        let mut t = Transform::identity();
        let Some((v, span)) = bargs.get("m").cloned() else {
            return Ok(t);
        };
        let rows: Option<Vec<Vec<Num>>> = v.as_vec().and_then(|rows| {
            rows.iter()
                .take(3)
                .map(|row| {
                    let row = row.as_vec()?;
                    row.iter().take(4).map(|x| x.as_num().cloned()).collect()
                })
                .collect()
        });
        let Some(rows) = rows else {
            let text = "`multmatrix` needs a 3×4 or 4×4 matrix of numbers".to_string();
            self.ignored_argument(text, span, &v, "the identity");
            return Ok(t);
        };
        for (i, row) in rows.into_iter().enumerate() {
            for (j, n) in row.into_iter().enumerate() {
                self.finite(&n, span, "an entry of `multmatrix`")?;
                if j < 3 {
                    self.freeze_num(&n, "a `multmatrix` coefficient");
                    t.m[i][j] = Num::constant(n.value);
                } else {
                    self.name_slots(&n, ["x", "y", "z"][i], None);
                    t.m[i][j] = n;
                }
            }
        }
        Ok(t)
    }

    /// Names the slots of a primitive's size arguments after the world axis they set.
    fn name_primitive_slots(&mut self, part: &Part, ctx: &Ctx<'a>) {
        let perm = part.world.axis_permutation();
        let world_axis = |local: usize| perm.and_then(|p| p.iter().position(|&j| j == local));
        let extent = |local: usize| match world_axis(local) {
            Some(a) => ["width", "depth", "height"][a],
            None => ["size_x", "size_y", "size_z"][local],
        };
        let owner = Some(ctx.part_name());
        match &part.primitive {
            Primitive::Cube { size, .. } => {
                for (i, n) in size.iter().enumerate() {
                    self.name_slots(n, extent(i), owner.clone());
                }
            }
            Primitive::Cylinder { h, r1, r2, .. } => {
                let same = r1 == r2;
                self.name_slots(h, "length", owner.clone());
                self.name_slots(
                    r1,
                    if same { "radius" } else { "bottom_radius" },
                    owner.clone(),
                );
                self.name_slots(r2, "top_radius", owner);
            }
            Primitive::Sphere { r } => self.name_slots(r, "radius", owner),
        }
    }
}
