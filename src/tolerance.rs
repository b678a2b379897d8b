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

// ---- names (analysis::names::roles) ------------------------------------------------------

/// Two faces closer than this fraction of the model's size touch, and two centres this
/// close are on one line, when parts' roles are read from their arrangement (a leg's top
/// and the underside of the seat, a wheel's centre and its axle's axis). Coarse on
/// purpose: models are drawn by hand with small gaps and overlaps.
pub const ROLE_CONTACT: f64 = 0.02;

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
// Besides these, the analysis uses [`RELATIVE_EPSILON`] (does a relation hold, did a rigid
// move succeed) and [`RELATIVE_ROUNDOFF`] (rank of constraint rows relative to their largest
// entry, round-off dropped from sparse rows, pivots of unit-scale coefficients, a fraction
// read back from a float, a step that divides a value).

/// The pseudo-inverse's cutoff, relative to the largest singular value (times the matrix's
/// larger dimension): singular values below it are round-off. A decade below
/// [`RELATIVE_ROUNDOFF`] so a least-squares solve keeps every direction a rank test keeps.
pub const PSEUDO_INVERSE_CUTOFF: f64 = 1e-10;

/// A coefficient of a solved slot's expression below this (absolute; the coefficients are
/// unit-scale fractions such as ±1, ±½) is round-off of the elimination and is dropped.
pub const COEFFICIENT_ZERO: f64 = 1e-12;

/// The continued fraction that reads a coefficient back as a fraction stops when the
/// remainder is below this (absolute, of a number below 1): the expansion is exact.
pub const FRACTION_REMAINDER_ZERO: f64 = 1e-15;

/// When a new row updates the stored rows of a row basis, entries below this fraction of
/// the [`RELATIVE_ROUNDOFF`] threshold are dropped: updates cancel exactly more often than a
/// reduction does, so only far smaller leftovers are round-off.
pub const BASIS_UPDATE_ZERO: f64 = 1e-3;

/// The projection metric's ridge, relative to its largest diagonal entry: enough to make the
/// normal equations positive definite, far below any face's weight.
pub const PROJECTION_RIDGE: f64 = RELATIVE_ROUNDOFF;

/// The first extra ridge tried when a Cholesky factorisation fails on round-off, relative
/// to the matrix's largest diagonal entry (grown a hundredfold per try).
pub const CHOLESKY_RETRY_RIDGE: f64 = 1e-12;

/// The smallest scale a matrix's diagonal is taken to have (absolute), so a zero matrix
/// still gets a positive ridge: far below any weight a model's faces give.
pub const SCALE_FLOOR: f64 = 1e-300;

/// The share of intent relations the noise test may reject by chance (`analysis::noise`):
/// each one costs a slider. Also sets which relations pool into the noise estimate.
pub const NOISE_FALSE_REJECTION: f64 = 1e-3;

/// The largest noise the noise model admits, as a share of the model's size: variations
/// are the same design give or take a few percent, not a different one. Where the only
/// relations the variations move are broken ones, their residuals would otherwise pass for
/// the noise.
pub const NOISE_MAX_SHARE: f64 = 0.05;

/// The largest noise the noise model admits for a model of size `size` (world units).
pub fn noise_ceiling(size: f64) -> f64 {
    NOISE_MAX_SHARE * size
}

/// The most of its numbers' own changes a relation may keep as residual and still show
/// that the variations have an intent relation to tell their noise by (`analysis::intent`):
/// an intent relation's residual is the noise while its numbers move by the design's
/// changes, so it cancels most of them; a broken one cancels nothing in particular (for two
/// independent changes the residual's square is, on average, as large as their squares'
/// sum). A quarter of the squares is a residual at most half the numbers' typical change.
pub const NOISE_CANCELLATION_SHARE: f64 = 0.25;

/// How near 0 or 1 the intent share of the noise estimate's mixture may come
/// (`analysis::noise`): at exactly 0 or 1 one hypothesis would be impossible, and its
/// log-likelihood would stop the share from moving.
pub const NOISE_MIXTURE_SHARE_MARGIN: f64 = 1e-6;

/// Volume lost by removing a part, as a fraction of the part's own volume in the input,
/// below which removing it changes nothing (hidden inside others or sized to nothing; a
/// variation does without it only when one of its extents is zero: `analysis::optional`).
/// Relative to the part, not the model, so a small part of a large model counts.
pub const OPTIONAL_PART_LOSS: f64 = 1e-3;

/// The smallest slider step (absolute, world units), so a range of zero width still gets
/// a step: far below any size a printed model distinguishes.
pub const MIN_SLIDER_STEP: f64 = 1e-6;

/// The smallest model size (absolute) the shown values' precision is derived from, so a
/// flat or empty model still gets a finite quantum.
pub const MIN_DISPLAY_SIZE: f64 = 1e-9;

// ---- back end (what is written for people) ----------------------------------------------

/// The distortion plot's smallest vertical scale (IoU loss), so a flat curve of zeros is
/// still drawn.
pub const MIN_PLOT_SCALE: f64 = 1e-6;

// ---- rendering (cameras, soft silhouettes, GPU) -----------------------------------------

/// Floor of a length, radius or squared length the renderer divides by (a point on a
/// frustum's axis, a ray through a sphere's center, a degenerate row of a part's map):
/// far below any length a model has, so it only keeps a zero from dividing.
pub const LENGTH_FLOOR: f64 = 1e-300;

/// Relative round-off of the renderer's unit-scale arithmetic: a determinant below this
/// times the cube of its matrix's largest entry (singular map), a turn below this times the
/// squared span of a polygon's points (collinear), a quadratic coefficient below this times
/// its scale (a cone's linear case), a cosine below this (a ray grazing a plane, a camera in
/// gimbal lock) count as zero. Far below what a picture shows, well above `f64` round-off.
pub const RENDER_ROUNDOFF: f64 = 1e-12;

/// The sine (a cross product of unit vectors, or of a vector relative to its length) below
/// which two directions count as parallel: a camera's up along its view, an eye on a
/// sphere's surface (relative to its radius).
pub const PARALLEL_SINE: f64 = 1e-9;

/// The square of [`PARALLEL_SINE`] as written (`1e-18`): a local ray whose squared sideways
/// component is below this fraction of its squared length runs along a frustum's axis.
pub const PARALLEL_SINE_SQUARED: f64 = 1e-18;

/// Depth along the view (world units) at or below which a point is behind, or too near,
/// the eye to project.
pub const NEAR_DEPTH: f64 = 1e-9;

/// World units of a distance per pixel, at least (a plane seen edge-on has no footprint):
/// keeps a soft cut edge's width finite.
pub const PIXEL_SCALE_FLOOR: f64 = 1e-12;

/// Relative slack of a depth bound the renderer's shortcuts compare (an item's near depth,
/// a surface's deepest point over a tile) and the least relative lead of a box's entry
/// face over its other faces for a tile to count as showing that face alone: far above
/// the rounding of a depth computed through a part's local frame, far below any gap
/// between parts or a pixel's worth of depth.
pub const SHORTCUT_DEPTH_SLACK: f64 = 1e-9;

/// Slack (pixels) on a signed-distance bound the renderer's tiles are classified by: far
/// above the rounding of a distance across an image, far below any coverage that matters.
pub const SHORTCUT_PIXEL_SLACK: f64 = 1e-6;

/// Overlap (pixels) a source pixel keeps in a box-filter resample at least, and the floor
/// of a resampled pixel's total weight: only keeps an empty overlap from dividing by zero.
pub const RESAMPLE_OVERLAP_FLOOR: f64 = 1e-6;
/// See [`RESAMPLE_OVERLAP_FLOOR`].
pub const RESAMPLE_WEIGHT_FLOOR: f64 = 1e-12;

/// Half the diagonal (world units) default views frame at least, so a model of zero size
/// still gets cameras at a positive distance.
pub const MIN_FRAMED_RADIUS: f64 = 1e-6;

/// Coverage of a soft image's pixel below which its grey level (premultiplied shade over
/// coverage) is undefined and taken as 0.
pub const COVERAGE_FLOOR: f32 = 1e-6;

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

/// The step of the differences that measure a fit's information (`fit::uncertainty`), a
/// share of the model's size: a small fraction of a pixel at the sizes pictures come in.
pub const UNCERTAINTY_STEP: f64 = 1e-3;

/// One level of an 8-bit channel as a standard deviation of rounding, `1 / (255 √12)`:
/// the floor of a fit's residual noise (`fit::uncertainty`).
pub const PIXEL_QUANTISATION: f64 = 1.132_0e-3;

/// Eigenvalues of a fit's information below this share of the largest count as zero: the
/// pictures say nothing along them (`variation::uncertainty`).
pub const INFORMATION_NULL_SHARE: f64 = 1e-12;

/// A combination of numbers counts as inside the information's range when its component
/// in the null space is below this share of its length (`variation::uncertainty`).
pub const INFORMATION_RANGE_SHARE: f64 = 1e-6;

/// How far (relative) a sidecar's record of a number may differ from the variant's own and
/// still describe it: the variant's numbers are written to ten significant figures.
pub const SIDECAR_VALUE_MATCH: f64 = 1e-9;

/// How far, in pixels, a fit started at the truth may leave it: fitted to its own renders,
/// every face of a model comes back within this of where it was (issue 15).
pub const FIXED_POINT_PIXELS: f64 = 0.1;
