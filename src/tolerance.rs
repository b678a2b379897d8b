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

/// Floor of a model's size when it is the fit's unit of length (slots are stepped and
/// regularised in units of it): a model of size 0 still gets a positive unit. Far below any
/// real model's size, so it changes nothing else.
pub const FIT_SIZE_FLOOR: f64 = 1e-9;

/// Smallest divisor of the fit's divisions by a norm, a singular value or an eigenvalue
/// that may be 0: far below any number a model produces, it only keeps `0 / 0` and `x / 0`
/// out of the arithmetic.
pub const FIT_DIVISOR_FLOOR: f64 = 1e-300;

/// Relative rank cut-off of the fit's subspace bases: a singular value (or eigenvalue, per
/// dimension) below this fraction of the largest is a direction the matrix does not have.
/// Well above `f64` round-off of a product of two unit-scale matrices (~1e-15 × d), well
/// below a real constraint's weight.
pub const FIT_RANK_RELATIVE: f64 = 1e-10;

/// Adam's `ε` (Kingma & Ba's default): keeps a coordinate whose gradient has always been 0
/// from dividing by 0, relative to gradients of unit scale.
pub const ADAM_EPSILON: f64 = 1e-8;

/// The shading/albedo alternation has settled when no albedo changes by more than this
/// fraction of itself between two alternations (albedos are near 1).
pub const ALBEDO_SETTLED: f64 = 1e-9;

/// Weight per pixel of the pulls towards the prior shading and towards albedo 1 in the
/// albedo fit. They settle what the pixels leave open (orientations a view does not show,
/// items never seen) and must not bias the rest: at 1e-3 a bookcase's albedo ratios were 1%
/// off.
pub const ALBEDO_PULL: f64 = 1e-5;

/// A step projected back onto a violated size guard aims this factor past the bound, so
/// that rounding does not leave it violated (a relative margin of 1e-6).
pub const GUARD_MARGIN: f64 = 1.000001;
