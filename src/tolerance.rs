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

// ---- geometry (geom: exact volumes, ray intervals, quadrature) --------------------------

// ---- analysis (candidates, rank, projection, discovery) ---------------------------------

// ---- rendering (cameras, soft silhouettes, GPU) -----------------------------------------

// ---- fitting (losses, optimisers, schedules) ---------------------------------------------
