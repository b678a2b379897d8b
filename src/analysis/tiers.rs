//! Discovery's order of preference among candidates, and which tiers the cutoff may keep.
//!
//! Under noise, IoU alone cannot tell an accidental equality of two sizes from a real one,
//! and a residual cannot either when the variations change the relation by less than their
//! noise. The tiers break the tie the way a designer would, asking more evidence of the
//! relations a design rarely means:
//!
//! 0. *structural*: what holds a design together (the structural prior: contacts,
//!    coaxiality, repeated parts' sizes);
//! 1. *other*: every other relation the variations keep within their noise;
//! 2. *coincidence*: an equality of sizes a designer seldom intends, kept only on strong
//!    evidence:
//!    - a size measured upright equal to one measured level (a seat's thickness and an arm's
//!      width, a bottle neck's height and its diameter): gravity makes the vertical special
//!      in furniture, vehicles and containers, so this needs every variation to keep it
//!      exactly. One part's two sizes across its own axis (a horizontal bar's square
//!      section, a wheel's diameter) are not coincidences;
//!    - equal sizes of two unrelated parts (different, not repeats of each other): their
//!      residual may not exceed the noise level itself (the typical relation's residual)
//!      rather than the gate's threshold;
//! 3. *beyond noise*: relations some variation breaks beyond its noise (the noise gate).
//!
//! Invariant: discovery takes every candidate of a lower tier before any of a higher one,
//! and the cutoff keeps only steps of the plausible tiers (below [`COINCIDENCE`]). Leaving
//! a doubtful relation out costs a slider; keeping a wrong one makes a variation
//! unreachable.

use super::candidates::{Candidates, RelationKind};
use super::noise::NoiseGate;
use super::prior::{repeated, structural_prior};
use crate::ir::feature::axial_axis;
use crate::ir::{FeatureKind, Model};
use crate::tolerance::Tolerance;

pub const STRUCTURAL: u8 = 0;
pub const OTHER: u8 = 1;
pub const COINCIDENCE: u8 = 2;
pub const BEYOND_NOISE: u8 = 3;
pub const TIER_NAMES: [&str; 4] = ["structural", "other", "coincidence", "beyond noise"];

/// The world axis that points up.
const VERTICAL: usize = 2;

/// Whether candidate `i` is an equality of sizes that needs more than the noise gate's
/// evidence (see the module doc), given its largest residual over the variations.
fn is_coincidence(
    model: &Model,
    candidates: &Candidates,
    i: usize,
    gate: &NoiseGate,
    tolerance: Tolerance,
) -> bool {
    let c = &candidates.list[i];
    let (fa, fb) = (&candidates.features[c.a], &candidates.features[c.b]);
    let (FeatureKind::Extent { axis: a }, FeatureKind::Extent { axis: b }) = (fa.kind, fb.kind)
    else {
        return false;
    };
    if c.kind != RelationKind::Equal {
        return false;
    }
    let (a, b) = (a as usize, b as usize);
    let residual = gate.residual[i];
    let same_part = fa.part == fb.part;
    let across_own_axis = same_part && {
        let axial = axial_axis(&model.parts[fa.part]);
        axial != Some(a) && axial != Some(b)
    };
    if (a == VERTICAL) != (b == VERTICAL) && !across_own_axis {
        return residual > tolerance.epsilon;
    }
    let unrelated = !same_part && !repeated(model, fa.part, fb.part, &tolerance);
    unrelated && residual > gate.level
}

/// The tier of every candidate (see the module doc).
pub fn discovery_tiers(
    model: &Model,
    candidates: &Candidates,
    gate: &NoiseGate,
    tolerance: Tolerance,
) -> Vec<u8> {
    let mut tiers = vec![OTHER; candidates.list.len()];
    for i in structural_prior(model, candidates) {
        tiers[i] = STRUCTURAL;
    }
    for (i, t) in tiers.iter_mut().enumerate() {
        if gate.deferred[i] {
            *t = BEYOND_NOISE;
        } else if *t == OTHER && is_coincidence(model, candidates, i, gate, tolerance) {
            *t = COINCIDENCE;
        }
    }
    tiers
}

/// How many of discovery's steps (their tiers in order) the cutoff may keep.
pub fn plausible_steps(step_tiers: &[u8]) -> usize {
    step_tiers.iter().take_while(|&&t| t < COINCIDENCE).count()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::find_candidates;
    use crate::front::source::SourceMap;

    /// A seat 40 thick on a table top, an arm 40 wide, and a wheel lying along y whose
    /// width and height are two numbers of one part (its diameter across its own axis).
    const MODEL: &str = "
// seat
translate([0, 0, 100]) cube([200, 150, 40]);
// arm
translate([0, 200, 0]) cube([40, 150, 90]);
// top
translate([0, 400, 0]) cube([200, 100, 10]);
// wheel
translate([500, 0, 50]) rotate([90, 0, 0]) scale([60, 60, 10]) cylinder(h = 1, r = 0.5, center = true);
";

    fn setup() -> (Model, Candidates) {
        let mut sources = SourceMap::new();
        let model =
            crate::front::load_model_text(&mut sources, "t.scad".as_ref(), MODEL.as_bytes())
                .expect("model loads")
                .model;
        let candidates = find_candidates(&model);
        (model, candidates)
    }

    fn index(c: &Candidates, text: &str) -> usize {
        (0..c.list.len())
            .find(|&i| c.describe(&c.list[i]) == text)
            .unwrap_or_else(|| panic!("no candidate {text:?}"))
    }

    /// The tiers when every candidate has `residual` in the variations, noise level 1.
    fn tiers_at(model: &Model, c: &Candidates, residual: f64) -> Vec<u8> {
        let gate = NoiseGate {
            level: 1.0,
            threshold: 3.0,
            residual: vec![residual; c.list.len()],
            deferred: vec![residual > 3.0; c.list.len()],
        };
        discovery_tiers(model, c, &gate, Tolerance::for_size(model.size()))
    }

    #[test]
    fn an_upright_size_equal_to_a_level_one_needs_exact_variations() {
        let (model, c) = setup();
        let i = index(&c, "seat.height equals arm.width");
        assert_eq!(tiers_at(&model, &c, 0.0)[i], OTHER);
        assert_eq!(tiers_at(&model, &c, 0.5)[i], COINCIDENCE);
        assert_eq!(tiers_at(&model, &c, 4.0)[i], BEYOND_NOISE);
    }

    #[test]
    fn a_wheels_diameter_across_its_own_axis_is_no_coincidence() {
        let (model, c) = setup();
        let i = index(&c, "wheel.width equals wheel.height");
        assert_eq!(tiers_at(&model, &c, 0.5)[i], OTHER);
        assert_eq!(tiers_at(&model, &c, 2.0)[i], OTHER);
    }

    #[test]
    fn unrelated_parts_sizes_must_stay_within_the_noise_level() {
        let (model, c) = setup();
        let i = index(&c, "seat.width equals top.width");
        assert_eq!(tiers_at(&model, &c, 0.5)[i], OTHER);
        assert_eq!(tiers_at(&model, &c, 2.0)[i], COINCIDENCE);
        let tiers = tiers_at(&model, &c, 2.0);
        let steps: Vec<u8> = vec![STRUCTURAL, OTHER, tiers[i], OTHER];
        assert_eq!(plausible_steps(&steps), 2);
    }
}
