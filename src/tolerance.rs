//! The one tolerance policy: every threshold at which a float counts as zero, equal or
//! settled, for every layer.
//!
//! Lives at the crate root and imports nothing, so `geom`, `render`, `fit`, `analysis` and
//! the front end all read their thresholds here; no other file writes a bare tolerance
//! exponent (a test greps for them). Every "does this relation hold" question is answered
//! against a tolerance relative to the model's size (the longest side of its bounding box),
//! so the answer is the same at any scale. `algorithms.md` §1: ε = 1e-6 × size. Thresholds
//! that are not relative to a model's size (round-off of unit-scale arithmetic, guards
//! against division by zero) say what they are relative to.

/// Relative tolerance for relations holding on the input.
pub const RELATIVE_EPSILON: f64 = 1e-6;

/// Relative round-off of a model's numbers: a move or a residual below this fraction of the
/// largest number is arithmetic noise, not a change (far below [`RELATIVE_EPSILON`]).
pub const RELATIVE_ROUNDOFF: f64 = 1e-9;

/// An absolute tolerance derived from a model's size.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Tolerance {
    pub epsilon: f64,
}

impl Tolerance {
    /// ε for a model whose bounding box's longest side is `size` (a model of size 0 still
    /// gets a positive tolerance, so exact equality is always enough).
    pub fn for_size(size: f64) -> Self {
        let size = if size.is_finite() && size > 0.0 {
            size
        } else {
            1.0
        };
        Tolerance {
            epsilon: RELATIVE_EPSILON * size,
        }
    }

    pub fn equal(&self, a: f64, b: f64) -> bool {
        (a - b).abs() <= self.epsilon
    }
}

// ---- front end (parse, evaluate) -------------------------------------------------------

/// Rotation matrix entries (sines and cosines, so of unit scale) within this of 0 or ±1
/// are snapped to exactly that: `cos 90°` is 6e-17, not 0, and a few ulps of round-off
/// would otherwise make an axis-aligned part look rotated.
pub const ROTATION_SNAP: f64 = 1e-12;

/// A range `[s : st : e]` reaches `e` when `(e − s) / st` is this short of a whole number
/// of steps (relative to one step): the round-off of the division, not a real shortfall.
pub const RANGE_STEP_SLACK: f64 = 1e-9;

// ---- geometry (geom: exact volumes, ray intervals, quadrature) --------------------------

/// Interval ends along a ray or a line closer than this fraction of the solid's size (its
/// longest side, or the distance of the ray's origin when that is larger) are one point:
/// round-off of the intersection arithmetic, far below any real feature.
pub const GEOM_COINCIDENT: f64 = 1e-12;

/// Relative round-off of a value a few floating operations produced (~50 ulps): strip
/// breaks closer than this fraction of the domain's size are one (a `cos 90°` of 6e-17
/// would only make slivers), ends of two solids tie within it of their coordinate, and a
/// 3×3 matrix whose determinant is below it times the product of its row norms is
/// singular.
pub const GEOM_ROUNDOFF: f64 = 1e-14;

/// Ends of two solids along a line tie within this fraction of [`GEOM_COINCIDENT`]'s
/// absolute distance (plus [`GEOM_ROUNDOFF`] of the coordinate): touching surfaces then
/// cost no split, while ends merely closer than that keep their true order.
pub const GEOM_TIE_OF_COINCIDENT: f64 = 1e-2;

/// An entry of a transform (or of its inverse) below this fraction of the largest entry
/// of its row (or matrix) is zero: the part is axis-aligned or a prism along that axis.
pub const GEOM_NEGLIGIBLE_ENTRY: f64 = 1e-12;

/// Bounds (a shape's box, a frustum's slab between its caps) are grown by this fraction
/// of their extent, so that a line grazing a face is not turned away by round-off.
pub const GEOM_BOUNDS_PAD: f64 = 1e-9;

/// A change of structure along an interval is located by bisection to this fraction of
/// the interval searched: close enough that a kink left inside a piece costs ~its square.
pub const GEOM_BISECTION: f64 = 1e-9;

/// A piece narrower than this fraction of the interval it is cut from is a sliver: a
/// change of structure there is left to the error estimate, a cut that close to an end
/// is dropped, and two cuts that close are one.
pub const GEOM_SLIVER: f64 = 1e-7;

/// The scan for crossings of break curves starts and ends this fraction of the strip
/// inside its ends, so that the breaks at the ends themselves are not found again.
pub const GEOM_SCAN_INSET: f64 = 1e-6;

/// A quadrature piece narrower than this fraction of the domain's size (or of the whole
/// integral's width) is never split: below it, round-off is all the error estimate sees.
pub const QUAD_MIN_WIDTH: f64 = 1e-9;

/// Error allowed for the integral along one line, relative to its first estimate.
pub const QUAD_LINE_RTOL: f64 = 1e-10;

/// Absolute error allowed for the integral along one line, per unit length, as a fraction
/// of the domain's size (the integrand is a length).
pub const QUAD_LINE_ATOL: f64 = 1e-11;

/// Error allowed for the integral over a strip, relative to its first estimate (looser
/// than a line's: the lines' own errors are below it).
pub const QUAD_AREA_RTOL: f64 = 1e-9;

/// Absolute error allowed for the integral over a strip, per unit length, as a fraction
/// of the domain's size squared (the integrand is an area).
pub const QUAD_AREA_ATOL: f64 = 1e-10;

// ---- analysis (candidates, rank, projection, discovery) ---------------------------------

// ---- rendering (cameras, soft silhouettes, GPU) -----------------------------------------

// ---- fitting (losses, optimisers, schedules) ---------------------------------------------
