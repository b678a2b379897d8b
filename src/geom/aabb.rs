//! Axis-aligned boxes in world space.
//!
//! [`Aabb`] is the region type of the geometry module: part bounds, the domain of an
//! integration, and the "changed region" of an incremental IoU. Invariant: a box is *empty*
//! when some `min[a] >= max[a]` or a coordinate is NaN; empty boxes contain nothing, and
//! [`Aabb::union`] ignores them. Boxes are closed sets for [`Aabb::contains_point`].

use crate::ir::Part;

/// A closed axis-aligned box `min ..= max`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aabb {
    pub min: [f64; 3],
    pub max: [f64; 3],
}

impl Aabb {
    pub fn new(min: [f64; 3], max: [f64; 3]) -> Self {
        Aabb { min, max }
    }

    /// The box that contains nothing (the identity of [`Aabb::union`]).
    pub fn empty() -> Self {
        Aabb {
            min: [f64::INFINITY; 3],
            max: [f64::NEG_INFINITY; 3],
        }
    }

    /// The tight world bounds of a part (a rotated sphere's true ellipsoid extent, a
    /// frustum's cap ellipses); empty for a degenerate part.
    pub fn of_part(part: &Part) -> Self {
        match super::shape::Shape::new(part) {
            Some(s) => Aabb::new(s.lo, s.hi),
            None => Aabb::empty(),
        }
    }

    /// True when the box has no interior (a flat box counts as empty: it holds no volume).
    pub fn is_empty(&self) -> bool {
        (0..3).any(|a| !(self.min[a] < self.max[a]))
    }

    /// The smallest box containing both; empty operands are ignored.
    pub fn union(&self, other: &Aabb) -> Aabb {
        match (self.is_empty(), other.is_empty()) {
            (true, _) => *other,
            (_, true) => *self,
            _ => Aabb {
                min: std::array::from_fn(|a| self.min[a].min(other.min[a])),
                max: std::array::from_fn(|a| self.max[a].max(other.max[a])),
            },
        }
    }

    /// The common part (possibly empty).
    pub fn intersection(&self, other: &Aabb) -> Aabb {
        Aabb {
            min: std::array::from_fn(|a| self.min[a].max(other.min[a])),
            max: std::array::from_fn(|a| self.max[a].min(other.max[a])),
        }
    }

    /// True when the interiors overlap.
    pub fn intersects(&self, other: &Aabb) -> bool {
        !self.intersection(other).is_empty()
    }

    /// True when `other` lies inside `self` (an empty `other` is inside everything).
    pub fn contains(&self, other: &Aabb) -> bool {
        other.is_empty()
            || (0..3).all(|a| self.min[a] <= other.min[a] && other.max[a] <= self.max[a])
    }

    pub fn contains_point(&self, p: [f64; 3]) -> bool {
        (0..3).all(|a| self.min[a] <= p[a] && p[a] <= self.max[a])
    }

    pub fn volume(&self) -> f64 {
        if self.is_empty() {
            return 0.0;
        }
        (0..3).map(|a| self.max[a] - self.min[a]).product()
    }

    /// The longest side (0 when empty).
    pub fn size(&self) -> f64 {
        if self.is_empty() {
            return 0.0;
        }
        (0..3)
            .map(|a| self.max[a] - self.min[a])
            .fold(0.0, f64::max)
    }
}

impl Default for Aabb {
    fn default() -> Self {
        Aabb::empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn union_ignores_empty_and_contains_works() {
        let a = Aabb::new([0.0; 3], [1.0; 3]);
        let b = Aabb::new([2.0, 0.0, 0.0], [3.0, 1.0, 1.0]);
        let u = a.union(&Aabb::empty()).union(&b);
        assert_eq!(u, Aabb::new([0.0; 3], [3.0, 1.0, 1.0]));
        assert!(u.contains(&a) && u.contains(&b) && !a.contains(&b));
        assert!(a.contains(&Aabb::empty()));
        assert!(!a.intersects(&b));
        assert!(Aabb::new([0.0; 3], [1.0, 0.0, 1.0]).is_empty());
        assert!(Aabb::new([f64::NAN; 3], [1.0; 3]).is_empty());
        assert_eq!(u.volume(), 3.0);
        assert!(u.contains_point([3.0, 1.0, 0.5]));
    }
}
