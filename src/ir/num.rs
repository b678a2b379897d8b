//! Numbers that remember how they depend on slots.
//!
//! A [`Num`] is the exact `f64` OpenSCAD would compute plus a [`Form`]: either an exact
//! affine form over slots, or, once two slot-dependent factors were multiplied (or a
//! slot-dependent value went through a non-linear function), `NonAffine` with the slots it
//! depends on and the slots to freeze if an affine form is needed. The evaluator freezes
//! those slots (treats their literals as constants) and runs again; see `front::eval`.
//!
//! The rule for which factor to freeze: the divisor of a division; the inner factor of a
//! geometric composition (a primitive's own sizes under a `scale`, a `translate` under a
//! `scale`); in plain arithmetic, the factor without named (top-level variable) slots, else
//! the right-hand one.

use super::affine::{Affine, SlotId};

#[derive(Debug, Clone, PartialEq)]
pub enum Form {
    Affine(Affine),
    NonAffine(Box<NonAffine>),
}

/// What a non-affine value depends on and what freezing would make it affine.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct NonAffine {
    /// Every slot the value depends on (sorted, unique).
    pub deps: Vec<SlotId>,
    /// The slots to freeze so that this value becomes affine (sorted, unique).
    pub freeze: Vec<SlotId>,
}

/// A number with its dependence on slots.
#[derive(Debug, Clone, PartialEq)]
pub struct Num {
    pub value: f64,
    pub form: Form,
}

/// Which factor of a product of two slot-dependent numbers gets frozen.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FreezeSide {
    Left,
    Right,
}

fn union(a: &[SlotId], b: &[SlotId]) -> Vec<SlotId> {
    let mut v: Vec<SlotId> = a.iter().chain(b).copied().collect();
    v.sort_unstable();
    v.dedup();
    v
}

impl Num {
    pub fn constant(value: f64) -> Self {
        Num {
            value,
            form: Form::Affine(Affine::constant(value)),
        }
    }

    pub fn slot(id: SlotId, value: f64) -> Self {
        Num {
            value,
            form: Form::Affine(Affine::slot(id)),
        }
    }

    /// A value computed non-linearly from `self`: it depends on the same slots, and only
    /// freezing all of them makes it affine (used for `sqrt`, `sin`, `abs`, ...).
    pub fn opaque(&self, value: f64) -> Self {
        if self.is_constant() {
            return Num::constant(value);
        }
        let deps = self.deps();
        Num {
            value,
            form: Form::NonAffine(Box::new(NonAffine {
                freeze: deps.clone(),
                deps,
            })),
        }
    }

    /// A value computed non-linearly from several numbers (e.g. `max(a, b)`).
    pub fn opaque_of(nums: &[&Num], value: f64) -> Self {
        let deps = nums
            .iter()
            .fold(Vec::new(), |acc, n| union(&acc, &n.deps()));
        if deps.is_empty() {
            return Num::constant(value);
        }
        Num {
            value,
            form: Form::NonAffine(Box::new(NonAffine {
                freeze: deps.clone(),
                deps,
            })),
        }
    }

    pub fn is_constant(&self) -> bool {
        matches!(&self.form, Form::Affine(a) if a.is_constant())
    }

    pub fn affine(&self) -> Option<&Affine> {
        match &self.form {
            Form::Affine(a) => Some(a),
            Form::NonAffine(_) => None,
        }
    }

    /// Every slot the value depends on.
    pub fn deps(&self) -> Vec<SlotId> {
        match &self.form {
            Form::Affine(a) => a.slots().collect(),
            Form::NonAffine(n) => n.deps.clone(),
        }
    }

    /// The slots whose freezing would make this value affine (empty if it already is).
    pub fn freeze_to_make_affine(&self) -> &[SlotId] {
        match &self.form {
            Form::Affine(_) => &[],
            Form::NonAffine(n) => &n.freeze,
        }
    }

    fn non_affine(value: f64, deps: Vec<SlotId>, freeze: Vec<SlotId>) -> Self {
        Num {
            value,
            form: Form::NonAffine(Box::new(NonAffine { deps, freeze })),
        }
    }

    fn combine_linear(&self, other: &Num, k: f64, value: f64) -> Num {
        match (&self.form, &other.form) {
            (Form::Affine(a), Form::Affine(b)) => Num {
                value,
                form: Form::Affine(a.add_scaled(b, k)),
            },
            _ => {
                let deps = union(&self.deps(), &other.deps());
                let freeze = union(self.freeze_to_make_affine(), other.freeze_to_make_affine());
                Num::non_affine(value, deps, freeze)
            }
        }
    }

    pub fn add(&self, other: &Num) -> Num {
        self.combine_linear(other, 1.0, self.value + other.value)
    }

    pub fn sub(&self, other: &Num) -> Num {
        self.combine_linear(other, -1.0, self.value - other.value)
    }

    pub fn neg(&self) -> Num {
        self.scale(-1.0, -self.value)
    }

    /// Multiplies the form by the constant `k`; `value` is the exact product OpenSCAD computes.
    fn scale(&self, k: f64, value: f64) -> Num {
        match &self.form {
            Form::Affine(a) => Num {
                value,
                form: Form::Affine(a.scale(k)),
            },
            Form::NonAffine(_) if k == 0.0 => Num::constant(value),
            Form::NonAffine(n) => Num::non_affine(value, n.deps.clone(), n.freeze.clone()),
        }
    }

    /// `self * other`; when both depend on slots, `side` says which factor to freeze.
    pub fn mul(&self, other: &Num, side: FreezeSide) -> Num {
        let value = self.value * other.value;
        if other.is_constant() {
            return self.scale(other.value, value);
        }
        if self.is_constant() {
            return other.scale(self.value, value);
        }
        let frozen_factor = match side {
            FreezeSide::Left => self,
            FreezeSide::Right => other,
        };
        let freeze = union(
            &union(self.freeze_to_make_affine(), other.freeze_to_make_affine()),
            &frozen_factor.deps(),
        );
        Num::non_affine(value, union(&self.deps(), &other.deps()), freeze)
    }

    /// `self / other`; a slot-dependent divisor is the factor to freeze.
    pub fn div(&self, other: &Num) -> Num {
        let value = self.value / other.value;
        if other.is_constant() {
            return self.scale(1.0 / other.value, value);
        }
        let freeze = union(
            &union(self.freeze_to_make_affine(), other.freeze_to_make_affine()),
            &other.deps(),
        );
        Num::non_affine(value, union(&self.deps(), &other.deps()), freeze)
    }

    /// Renames slots (for the dense numbering of the finished IR).
    pub fn remap(&self, map: &dyn Fn(SlotId) -> Option<SlotId>) -> Num {
        let remap_list = |v: &[SlotId]| {
            let mut out: Vec<SlotId> = v.iter().filter_map(|&s| map(s)).collect();
            out.sort_unstable();
            out
        };
        let form = match &self.form {
            Form::Affine(a) => Form::Affine(a.remap(map)),
            Form::NonAffine(n) => Form::NonAffine(Box::new(NonAffine {
                deps: remap_list(&n.deps),
                freeze: remap_list(&n.freeze),
            })),
        };
        Num {
            value: self.value,
            form,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn product_with_constant_stays_affine() {
        let x = Num::slot(0, 3.0);
        let y = x.mul(&Num::constant(2.0), FreezeSide::Right);
        assert_eq!(y.value, 6.0);
        assert_eq!(y.affine().unwrap().terms, vec![(0, 2.0)]);
    }

    #[test]
    fn product_of_slots_asks_to_freeze_chosen_side() {
        let x = Num::slot(0, 3.0);
        let y = Num::slot(1, 4.0);
        let p = x.mul(&y, FreezeSide::Right);
        assert_eq!(p.value, 12.0);
        assert_eq!(p.freeze_to_make_affine(), &[1]);
        assert_eq!(p.deps(), vec![0, 1]);
        let q = x.div(&y);
        assert_eq!(q.freeze_to_make_affine(), &[1]);
    }

    #[test]
    fn zero_times_anything_is_constant() {
        let p = Num::constant(0.0).mul(&Num::slot(3, 5.0), FreezeSide::Right);
        assert!(p.is_constant());
    }
}
