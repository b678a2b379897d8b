//! Parts: primitive instances after evaluation, with their world transforms.
//!
//! A [`Part`] is one `cube`, `cylinder` or `sphere` call as OpenSCAD instantiates it: the
//! primitive's own size arguments (normalised: a cylinder always has `h`, `r1`, `r2`) and the
//! 3×4 world matrix above it. Every entry is a [`Num`], so geometry is exact in value and
//! affine in slots where it can be. The CSG tree ([`CsgNode`]) keeps unions, differences and
//! intersections so volumes and images can be exact.

use super::affine::SlotId;
use super::num::{FreezeSide, Num};
use crate::span::Span;

/// A primitive solid with its arguments as OpenSCAD normalises them.
#[derive(Debug, Clone, PartialEq)]
pub enum Primitive {
    Cube {
        size: [Num; 3],
        center: bool,
    },
    /// A frustum along local z from 0 to `h` (or `-h/2..h/2` when centred).
    Cylinder {
        h: Num,
        r1: Num,
        r2: Num,
        center: bool,
    },
    Sphere {
        r: Num,
    },
}

impl Primitive {
    pub fn kind_name(&self) -> &'static str {
        match self {
            Primitive::Cube { .. } => "cube",
            Primitive::Cylinder { r1, r2, .. } if r1.value != r2.value => "cone",
            Primitive::Cylinder { .. } => "cylinder",
            Primitive::Sphere { .. } => "sphere",
        }
    }

    /// Local bounding box `(min, max)` at the current values.
    pub fn local_bounds(&self) -> ([f64; 3], [f64; 3]) {
        match self {
            Primitive::Cube { size, center } => {
                let s = size.each_ref().map(|n| n.value);
                if *center {
                    (s.map(|v| -v / 2.0), s.map(|v| v / 2.0))
                } else {
                    ([0.0; 3], s)
                }
            }
            Primitive::Cylinder { h, r1, r2, center } => {
                let r = r1.value.max(r2.value);
                let (z0, z1) = if *center {
                    (-h.value / 2.0, h.value / 2.0)
                } else {
                    (0.0, h.value)
                };
                ([-r, -r, z0], [r, r, z1])
            }
            Primitive::Sphere { r } => ([-r.value; 3], [r.value; 3]),
        }
    }
}

/// An affine map `x ↦ L·x + t` as a 3×4 matrix `[L | t]` of numbers.
#[derive(Debug, Clone, PartialEq)]
pub struct Transform {
    pub m: [[Num; 4]; 3],
}

impl Transform {
    pub fn identity() -> Self {
        Transform {
            m: std::array::from_fn(|i| {
                std::array::from_fn(|j| Num::constant(if i == j { 1.0 } else { 0.0 }))
            }),
        }
    }

    pub fn from_values(m: [[f64; 4]; 3]) -> Self {
        Transform {
            m: m.map(|row| row.map(Num::constant)),
        }
    }

    /// `self · inner`. Products of two slot-dependent entries freeze the inner factor.
    pub fn compose(&self, inner: &Transform) -> Transform {
        Transform {
            m: std::array::from_fn(|i| {
                std::array::from_fn(|k| {
                    let mut acc = if k == 3 {
                        self.m[i][3].clone()
                    } else {
                        Num::constant(0.0)
                    };
                    for j in 0..3 {
                        let a = &self.m[i][j];
                        let b = &inner.m[j][k];
                        if a.value == 0.0 && a.is_constant() || b.value == 0.0 && b.is_constant() {
                            continue;
                        }
                        acc = acc.add(&a.mul(b, FreezeSide::Right));
                    }
                    acc
                })
            }),
        }
    }

    /// The numeric 4×4 matrix (last row `0 0 0 1`).
    pub fn values(&self) -> [[f64; 4]; 4] {
        let mut out = [[0.0; 4]; 4];
        for (i, row) in self.m.iter().enumerate() {
            for (j, n) in row.iter().enumerate() {
                out[i][j] = n.value;
            }
        }
        out[3][3] = 1.0;
        out
    }

    /// Applies the numeric transform to a point.
    pub fn apply(&self, p: [f64; 3]) -> [f64; 3] {
        std::array::from_fn(|i| {
            self.m[i][3].value + (0..3).map(|j| self.m[i][j].value * p[j]).sum::<f64>()
        })
    }

    /// For an axis-aligned linear part, the local axis each world axis comes from; `None`
    /// when some row or column does not have exactly one non-zero entry.
    pub fn axis_permutation(&self) -> Option<[usize; 3]> {
        let mut perm = [0usize; 3];
        let mut used = [false; 3];
        for (i, row) in self.m.iter().enumerate() {
            let nonzero: Vec<usize> = (0..3).filter(|&j| row[j].value != 0.0).collect();
            let [j] = nonzero[..] else { return None };
            if used[j] {
                return None;
            }
            used[j] = true;
            perm[i] = j;
        }
        Some(perm)
    }
}

/// Why a part offers no candidates although its geometry is exact.
#[derive(Debug, Clone, PartialEq)]
pub struct Misalignment {
    /// The transform that turned it off the axes.
    pub span: Span,
    pub reason: String,
}

/// One evaluated primitive instance.
#[derive(Debug, Clone, PartialEq)]
pub struct Part {
    pub name: String,
    pub primitive: Primitive,
    pub world: Transform,
    /// The primitive's call in the source.
    pub span: Span,
    pub misaligned: Option<Misalignment>,
    /// `$fn`, `$fa`, `$fs` in effect at the call.
    pub fragments: [f64; 3],
    /// `#` highlight (still geometry).
    pub highlighted: bool,
    /// The statements whose execution made this part, outermost first (a module body's
    /// statements follow the call that ran them).
    pub statements: Vec<Span>,
}

impl Part {
    /// This part with every number evaluated at `values` (constants, no slot forms), or
    /// `None` if some number is not affine in the slots.
    pub fn at(&self, values: &[f64]) -> Option<Part> {
        let eval = |n: &Num| -> Option<Num> { Some(Num::constant(n.affine()?.eval(values))) };
        let mut m = self.world.m.clone();
        for row in m.iter_mut() {
            for n in row.iter_mut() {
                *n = eval(n)?;
            }
        }
        let primitive = match &self.primitive {
            Primitive::Cube { size, center } => Primitive::Cube {
                size: [eval(&size[0])?, eval(&size[1])?, eval(&size[2])?],
                center: *center,
            },
            Primitive::Cylinder { h, r1, r2, center } => Primitive::Cylinder {
                h: eval(h)?,
                r1: eval(r1)?,
                r2: eval(r2)?,
                center: *center,
            },
            Primitive::Sphere { r } => Primitive::Sphere { r: eval(r)? },
        };
        Some(Part {
            primitive,
            world: Transform { m },
            ..self.clone()
        })
    }

    /// Every number that shapes this part: the world matrix's entries, then the
    /// primitive's size arguments.
    pub fn numbers(&self) -> impl Iterator<Item = &Num> {
        let own: Vec<&Num> = match &self.primitive {
            Primitive::Cube { size, .. } => size.iter().collect(),
            Primitive::Cylinder { h, r1, r2, .. } => vec![h, r1, r2],
            Primitive::Sphere { r } => vec![r],
        };
        self.world.m.iter().flatten().chain(own)
    }

    /// The slots this part's geometry depends on, in the order of [`Part::numbers`] (a
    /// slot appears once for each number that depends on it).
    pub fn slot_deps(&self) -> impl Iterator<Item = SlotId> + '_ {
        self.numbers().flat_map(Num::deps)
    }

    /// World-space axis-aligned bounding box at the current values.
    pub fn world_bounds(&self) -> ([f64; 3], [f64; 3]) {
        let (lo, hi) = self.primitive.local_bounds();
        let mut min = [f64::INFINITY; 3];
        let mut max = [f64::NEG_INFINITY; 3];
        for c in 0..8 {
            let p = std::array::from_fn(|a| if c >> a & 1 == 0 { lo[a] } else { hi[a] });
            let w = self.world.apply(p);
            for a in 0..3 {
                min[a] = min[a].min(w[a]);
                max[a] = max[a].max(w[a]);
            }
        }
        (min, max)
    }
}

/// The boolean structure above the parts.
#[derive(Debug, Clone, PartialEq)]
pub enum CsgNode {
    Part(usize),
    Union(Vec<CsgNode>),
    /// The first child minus all the others.
    Difference(Vec<CsgNode>),
    Intersection(Vec<CsgNode>),
}

impl CsgNode {
    /// Every part index below this node, in order.
    pub fn parts(&self) -> Vec<usize> {
        let mut out = Vec::new();
        self.collect_parts(&mut out);
        out
    }

    /// This tree without the `skip` parts (`None` when nothing is left). A difference
    /// whose first child goes is gone; an intersection with a child gone is gone.
    pub fn without(&self, skip: &[usize]) -> Option<CsgNode> {
        match self {
            CsgNode::Part(i) => (!skip.contains(i)).then_some(CsgNode::Part(*i)),
            CsgNode::Union(c) => {
                let kept: Vec<CsgNode> = c.iter().filter_map(|n| n.without(skip)).collect();
                (!kept.is_empty()).then_some(CsgNode::Union(kept))
            }
            CsgNode::Difference(c) => {
                let first = c.first()?.without(skip)?;
                let mut kept = vec![first];
                kept.extend(c[1..].iter().filter_map(|n| n.without(skip)));
                Some(CsgNode::Difference(kept))
            }
            CsgNode::Intersection(c) => {
                let kept: Option<Vec<CsgNode>> = c.iter().map(|n| n.without(skip)).collect();
                Some(CsgNode::Intersection(kept?))
            }
        }
    }

    fn collect_parts(&self, out: &mut Vec<usize>) {
        match self {
            CsgNode::Part(i) => out.push(*i),
            CsgNode::Union(c) | CsgNode::Difference(c) | CsgNode::Intersection(c) => {
                c.iter().for_each(|n| n.collect_parts(out))
            }
        }
    }
}
