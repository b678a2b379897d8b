//! The intermediate representation: slots, parts and their features.
//!
//! A [`Model`] is what the front end makes of a program: the constructive parameters
//! ([`Slot`]s, densely numbered), the evaluated [`Part`]s in OpenSCAD's order, the CSG tree
//! above them, and what was frozen and why. Every form in a finished model refers to dense
//! slot ids `0..slots.len()`.

pub mod affine;
pub mod feature;
pub mod num;
pub mod part;

pub use affine::{Affine, SlotId};
pub use feature::{Feature, FeatureKind};
pub use num::{Form, Num};
pub use part::{CsgNode, Part, Primitive, Transform};

use crate::span::Span;
use serde::Serialize;

/// One constructive parameter: a numeric literal of the source that shapes geometry.
#[derive(Debug, Clone, PartialEq)]
pub struct Slot {
    pub id: SlotId,
    /// A readable name from the source: `seat.width`, `leg_height`, `part7.x`.
    pub name: String,
    /// Whether it sets a position (a `translate` offset) rather than a size.
    pub position: bool,
    /// The top-level variable this literal is the value of, if any.
    pub variable: Option<String>,
    /// Whether the author's identifiers name this literal: a variable's whole value or an
    /// element of a vector a variable holds, a module parameter's default, an argument
    /// of a module call. What the author named is the design's; the rest are details.
    pub authored: bool,
    pub value: f64,
    /// The literal's exact characters in the source.
    pub span: Span,
    pub text: String,
}

/// Why a literal that reaches geometry is not a slot.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum FreezeReason {
    /// It decides structure: a loop bound, a condition, an index, `$fn`, a rotation angle.
    Structural(String),
    /// It multiplies (or divides) another slot-dependent factor that a relation needs.
    Product(String),
}

/// A literal that shapes geometry but was frozen to a constant.
#[derive(Debug, Clone, PartialEq)]
pub struct FrozenLiteral {
    pub span: Span,
    pub text: String,
    pub value: f64,
    pub reason: FreezeReason,
}

/// An evaluated program.
#[derive(Debug, Clone, PartialEq)]
pub struct Model {
    pub slots: Vec<Slot>,
    pub parts: Vec<Part>,
    pub csg: CsgNode,
    pub frozen: Vec<FrozenLiteral>,
    /// `%` parts: shown by OpenSCAD in the preview, not geometry.
    pub background: Vec<Part>,
}

impl Model {
    /// Current slot values, indexed by slot id.
    pub fn slot_values(&self) -> Vec<f64> {
        self.slots.iter().map(|s| s.value).collect()
    }

    /// World bounding box of all parts at the current values (`None` if there are none).
    pub fn bounds(&self) -> Option<([f64; 3], [f64; 3])> {
        let mut it = self.parts.iter().map(Part::world_bounds);
        let first = it.next()?;
        Some(it.fold(first, |(lo, hi), (l, h)| {
            (
                std::array::from_fn(|a| lo[a].min(l[a])),
                std::array::from_fn(|a| hi[a].max(h[a])),
            )
        }))
    }

    /// The longest side of the bounding box: the scale tolerances are relative to.
    pub fn size(&self) -> f64 {
        self.bounds()
            .map(|(lo, hi)| (0..3).map(|a| hi[a] - lo[a]).fold(0.0, f64::max))
            .unwrap_or(0.0)
    }

    /// The parts with every number evaluated at `values` (slot values by id), or `None` if
    /// some number is not affine in the slots (then the program must be run again).
    pub fn parts_at(&self, values: &[f64]) -> Option<Vec<Part>> {
        self.parts.iter().map(|p| p.at(values)).collect()
    }

    /// For each slot (by id), the parts whose geometry depends on it, in part order.
    pub fn parts_by_slot(&self) -> Vec<Vec<usize>> {
        let mut out = vec![Vec::new(); self.slots.len()];
        for (i, p) in self.parts.iter().enumerate() {
            for s in p.slot_deps() {
                let owners: &mut Vec<usize> = &mut out[s as usize];
                if !owners.contains(&i) {
                    owners.push(i);
                }
            }
        }
        out
    }

    /// Every feature of every axis-aligned part.
    pub fn features(&self) -> Vec<Feature> {
        self.parts
            .iter()
            .enumerate()
            .filter(|(_, p)| p.misaligned.is_none())
            .filter_map(|(i, p)| feature::part_features(p, i))
            .flatten()
            .collect()
    }
}
