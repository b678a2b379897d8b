//! What a fit may be told ([`FitOptions`], the user's settings) and what it is built with
//! (the algorithm's constants, below them).
//!
//! [`FitOptions::default`] is the paper's loss and schedule (SGD, learning rate 0.05, ten
//! rounds of 30 steps, σ from 2 to 0.25 pixels), opened by our proportions search, with
//! an albedo per item, and finished on area coverage (`coverage`). The command's default,
//! `--schedule far` (`command::fit::Settings::far`), is the recipe for far pictures on top.
//! The fields are plain data, grouped by what they set: the schedule, what the loss
//! compares, how far a step may go, the finishing passes and the pictures. Lengths are in
//! units of the model's size (the longest side of its bounding box) unless a field says
//! pixels.
//!
//! Invariant: every field is a setting someone may want to change; numbers that only the
//! algorithm's design fixes are constants here, not fields.

use super::loss::LossSpec;
use super::optimize::Optimizer;

/// Settings of a fit; [`FitOptions::default`] is the paper's loss and schedule, opened by our
/// proportions search and with an albedo per item (both can be turned off).
#[derive(Debug, Clone, PartialEq)]
pub struct FitOptions {
    // ---- the schedule: rounds of optimiser steps ----------------------------------------
    /// Learning rate (slots in units of the model's size per unit gradient).
    pub lr: f64,
    /// Optimiser steps per round.
    pub iterations: usize,
    /// Rounds; the shading is refitted and the edges sharpened between rounds.
    pub rounds: usize,
    pub optimizer: Optimizer,
    /// In the last round of each stage the learning rate falls linearly by this fraction
    /// of `lr` over the round (see [`super::optimize::round_rate`]), so the stage ends
    /// almost at rest rather than wherever constant steps left it (Adam's steps stay near
    /// `lr` however close it is; on a 2.5 mm desk top that is a visible error). 0: the
    /// paper's constant rate.
    pub settle: f64,
    /// With Adam: every stage runs a second time from the same start with Adam's `floor`
    /// at this value, and the run with the lower final loss goes on to the next stage.
    /// Plain Adam gives a slot whose gradient is noise (a hollow seen only at a hard crease
    /// inside its box) full-size steps and can walk it out of the model, where nothing
    /// brings it back; damped Adam keeps such a slot still but moves small parts slowly.
    /// `None`: one run per stage.
    pub damped_rerun: Option<f64>,

    // ---- what the loss compares ---------------------------------------------------------
    /// Silhouette softness in pixels: first round, last round (geometric in between).
    pub sigma: (f64, f64),
    /// The last round, the finishing passes and the judge of the best point compare area
    /// coverage ([`crate::render::scene::BOX_FILTER`]: the exact share of each pixel a
    /// silhouette covers) instead of sigmoid edges: what antialiased pictures show, so the
    /// true numbers are its optimum to a fraction of a pixel. Pictures drawn with hard
    /// edges (every one point-sampled, as OpenSCAD draws: `Target::hard_edges`) are
    /// compared with hard edges instead, whose optimum they are.
    pub coverage: bool,
    /// How the rounds before the last soften edges ([`SoftEdges`]).
    pub soft_edges: SoftEdges,
    pub loss: LossSpec,
    /// Weight of `‖x − x₀‖²` (slots in units of the model's size).
    pub lambda: f64,
    /// Weight of the size prior `Σ ln²(s(x)/s(x₀))` over the parts' sizes `s`
    /// ([`super::parametric::Parametric::sizes`]): a size is as likely to halve as to
    /// double, so where the pictures barely tell (a back panel behind the boards in front
    /// of it) a thin part stays thin rather than growing into the hollow. 0: none.
    pub size_prior: f64,
    /// Weight of the tie prior `Σ ln(1 + (r/p)²)` over the residuals `r` of the model's
    /// structural relations ([`super::parametric::Parametric::ties`]; `p` the finest
    /// pixel): a contact or a repeat holds unless the pictures pull it apart by more than
    /// this resists, so numbers the pictures barely see keep their ties. 0: none.
    pub tie_prior: f64,
    /// Match each view's shading to its target at the start of every round.
    pub fit_shading: bool,
    /// With `fit_shading`: fit an albedo per item too, so parts of other colours in the
    /// targets (black tyres, two woods) do not read as shading (see [`super::albedo`]).
    pub per_item_albedo: bool,
    /// Coarse-to-fine: the first rounds render at `1/2^levels` of the targets' size and
    /// compare with pooled targets, one level finer every `rounds / (2·levels)` rounds, so
    /// parts far from their place in the target still feel it (and early rounds are cheap).
    /// 0: the paper's single resolution.
    pub levels: u32,
    /// Coarse levels render at full size and pool the difference (slower, but thin parts
    /// keep their true weight) instead of rendering small images.
    pub pooled: bool,

    // ---- how far a step may go ----------------------------------------------------------
    /// Largest change of one variable in one step (units of the model's size).
    pub max_step: f64,
    /// Steps as a trust region in pixels: a stage's first step moves no face further than
    /// this many of the round's edge softnesses (pixels of the finest camera, the last
    /// round's softness at least), and the bound grows by [`REACH_GROW`] after a step that
    /// lowered the loss and shrinks by [`REACH_SHRINK`] after one that raised it. A
    /// softened edge's gradient says little about where it should be beyond its softness,
    /// and Adam's steps are about the rate whatever the gradient (the first step of a
    /// stage moves every variable by the full rate), so unbounded runs can end pixels from
    /// an optimum they keep jumping over; but the same long steps also carry parts across
    /// flat stretches of the loss, and neither wins everywhere (README), so the default is
    /// 0: no bound.
    pub reach: f64,
    /// Step each slot in units of its own magnitude (at least [`RELATIVE_FLOOR`] of the
    /// model's size) instead of the model's size.
    pub relative_steps: bool,
    /// Smallest world extent of a part, in units of the model's size.
    pub min_extent: f64,

    // ---- passes before and after the gradient rounds ------------------------------------
    /// Open with a search over the model's stretch along each axis (see
    /// [`super::proportions`]).
    pub proportions: bool,
    /// Sweeps of face moves after the gradient rounds (see [`super::polish`]); 0: none.
    pub polish: usize,
    /// Sweeps of slot and face moves on hard edges after the face moves (see
    /// [`super::polish::refine`]); 0: none.
    pub refine: usize,

    // ---- the pictures -------------------------------------------------------------------
    /// The pictures show the whole object: the fit sees each picture inside a frame of
    /// background this fraction of its height wide, so that parts reaching out of the
    /// pictures are drawn back in rather than left unseen. 0: only the pictures.
    pub border: f64,
}

impl Default for FitOptions {
    fn default() -> Self {
        FitOptions {
            lr: 0.05,
            iterations: 30,
            rounds: 10,
            lambda: 0.001,
            size_prior: 0.0,
            tie_prior: 0.0,
            optimizer: Optimizer::sgd(),
            sigma: (2.0, 0.25),
            coverage: true,
            soft_edges: SoftEdges::Sigmoid,
            loss: LossSpec::default(),
            max_step: 0.02,
            reach: 0.0,
            fit_shading: true,
            per_item_albedo: true,
            min_extent: 0.002,
            relative_steps: false,
            polish: 0,
            refine: 0,
            border: 0.0,
            settle: 0.0,
            damped_rerun: Some(DAMPED_FLOOR),
            proportions: true,
            levels: 0,
            pooled: true,
        }
    }
}

/// How a round of softness `σ` softens the silhouettes it compares.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SoftEdges {
    /// The paper's (SoftRas): each silhouette's edges are sigmoids of width `σ`, the target
    /// as it is. Across a thin part that is the sharp silhouette blurred (the logistic
    /// kernel), but the target is not blurred, so the loss is least where a thin part is
    /// thicker than the truth: with `σ` = 2 px a board 2 px thick at 2.8 px, one of 1 px at
    /// 1.45 (sharpening aside).
    Sigmoid,
    /// Exact area coverage, both the render and the target blurred by a Gaussian of the
    /// sigmoid's standard deviation (`σ·π/√3`): the loss is then least at the truth in
    /// every round, for parts of any width.
    Blurred,
}

impl SoftEdges {
    /// The standard deviation of a sigmoid edge of softness `sigma` (the logistic
    /// distribution's): the width of the blur that stands in for it.
    pub fn blur_of(sigma: f64) -> f64 {
        sigma * std::f64::consts::PI / 3f64.sqrt()
    }
}

// ---- the algorithm's constants ----------------------------------------------------------

/// A part counts as lost in a stage ([`super::revive`]) when the stage started it at least
/// this many pixels across on every axis and left it under one on some axis.
pub const LOST_FROM_PIXELS: f64 = 2.0;

/// The step's reach grows by this factor after a step that lowered the loss
/// ([`FitOptions::reach`]).
pub const REACH_GROW: f64 = 1.25;

/// And shrinks by this one after a step that raised it.
pub const REACH_SHRINK: f64 = 0.5;

/// Adam's `floor` in the damped rerun of every stage ([`FitOptions::damped_rerun`]).
pub const DAMPED_FLOOR: f64 = 0.05;

/// Silhouette softness of [`super::polish::refine`]'s loss, in pixels: hard but for a
/// sliver.
pub const HARD_SIGMA: f64 = 0.02;

/// Floor of relative step scales, in units of the model's size.
pub const RELATIVE_FLOOR: f64 = 0.05;

/// Pools of the targets (each 2×2) under which the proportions search compares, so that
/// edges far from their place still count.
pub const PROPORTIONS_POOLING: u32 = 2;

/// Sweeps of half-space projections that move a step back inside the size guards.
pub const GUARD_SWEEPS: usize = 8;

/// Halvings of a step, at most, before a step that would make a part degenerate is given
/// up (the optimiser then stays where it is for that iteration).
pub const STEP_HALVINGS: usize = 10;

/// Smallest side, in pixels, of a coarse level's images.
pub const MIN_LEVEL_SIDE: u32 = 16;

/// The size prior's weight in the default schedule ([`FitOptions::size_prior`]), in units
/// of the image loss (per view a mean over its pixels): a part ten times its size in the
/// model costs `1.6e-4`, in a 256-pixel view about what moving a 50-pixel edge of the
/// silhouette by a third of a pixel costs; a doubling costs `1.4e-5`. It must outweigh
/// what OpenSCAD's pictures and the renderer disagree by along a direction the pictures
/// barely see (a back panel grown into the hollow of its carcass: `1e-5` did not, `7e-5`
/// over a 19-unit move), and not hold back a size the pictures do show (`1e-4` kept a
/// carcass's boards thick); chosen on generated families (README, the size prior).
pub const SIZE_PRIOR: f64 = 0.000_03;

/// The tie prior's weight in the default schedule ([`FitOptions::tie_prior`]), in units of
/// the image loss: a tie pulled a pixel apart costs `0.69` of it, ten pixels `4.6`; it
/// resists most (`1/p` per world unit) at one pixel, far less than a visible edge of a
/// dozen pixels pulls.
pub const TIE_PRIOR: f64 = 0.000_01;
