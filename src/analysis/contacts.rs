//! Contacts the sliders must keep: parts that touch or overlap in the input and in every
//! variation that has both.
//!
//! Two axis-aligned parts are in contact when their world boxes meet along all three axes:
//! for each axis, `hi_a − lo_b ≥ 0` and `hi_b − lo_a ≥ 0`. Each of those six sides is an
//! affine form over the slots. A contact the variations keep is kept as those inequalities
//! (`ranges` shrinks the sliders until no in-range setting breaks one), the way sizes are
//! kept positive, so a slider cannot pull a leg out of a top it sinks into, whether the
//! relations kept say it touches or not.
//!
//! In a noisy variation a side that is slightly negative may still be a contact: the test
//! is the noise model's ([`NoiseGaps`]). Closing the gap is a projection onto `side = 0`;
//! its cost in the variation's metric (`gap² / nKnᵀ`, what the relations' test weighs) is
//! what the noise explains when it is within `(z σ)²`. A side made of many noisy numbers
//! (a part placed in nested frames) may open further than one made of two. Where no
//! relation tells the noise, any noise up to the ceiling may have opened a gap, and a gap
//! within the ceiling counts as touching ([`NoiseGaps::new`]).
//!
//! Invariant: every form returned is at least `−slack` at the input (it is a contact there).

use super::chosen::Chosen;
use super::discover::Sample;
use super::noise::NoiseModel;
use super::project::{Faces, Projector};
use crate::ir::feature::world_intervals;
use crate::ir::{Affine, Model};

/// One side of a contact: `form ≥ 0` keeps it.
#[derive(Debug, Clone)]
pub struct ContactSide {
    pub parts: [usize; 2],
    pub axis: u8,
    pub form: Affine,
}

/// Whether variation `v`'s side `form` at `gap < 0` still counts as touching.
pub trait Touching {
    fn touches(&mut self, v: usize, form: &Affine, gap: f64) -> bool;
}

/// A gap up to a fixed width counts as touching (world units).
pub struct Slack(pub f64);

impl Touching for Slack {
    fn touches(&mut self, _: usize, _: &Affine, gap: f64) -> bool {
        gap >= -self.0
    }
}

/// The noise model's test: a gap counts as touching when closing it costs no more than the
/// noise explains in one degree of freedom, `(z σ)²`, in the variation's own metric (the
/// numbers' for typed variations, the faces' weighed by how well the pictures show them for
/// fitted ones).
pub struct NoiseGaps<'a> {
    faces: &'a Faces,
    samples: &'a [Sample],
    /// `(z σ)²`, world units².
    explained: f64,
    projectors: Vec<Option<Projector>>,
    /// No relation chosen: each gap is weighed on its own.
    none: Chosen,
}

impl<'a> NoiseGaps<'a> {
    /// The test for `noise`. Where no relation tells the noise (`NoiseModel::told`), it may
    /// be anything up to the `ceiling` (`tolerance::NOISE_MAX_SHARE` of the model): a gap
    /// is then as likely under a noise somewhere in that range as under a change of design
    /// of any scale up to about the ceiling itself, so a gap within it counts as touching.
    /// The floor `σ` sits at in that case is the relations' conservative choice (a relation
    /// kept wrongly costs a slider's reach), not the contacts' (a contact let go parts the
    /// model at in-range settings).
    pub fn new(
        faces: &'a Faces,
        samples: &'a [Sample],
        noise: &NoiseModel,
        ceiling: f64,
    ) -> NoiseGaps<'a> {
        let explained = if noise.told {
            (noise.critical_z * noise.sigma).powi(2)
        } else {
            ceiling * ceiling
        };
        NoiseGaps {
            faces,
            samples,
            explained,
            projectors: samples.iter().map(|_| None).collect(),
            none: Chosen::new(faces),
        }
    }
}

impl Touching for NoiseGaps<'_> {
    fn touches(&mut self, v: usize, form: &Affine, gap: f64) -> bool {
        let (faces, sample) = (self.faces, &self.samples[v]);
        let projector =
            self.projectors[v].get_or_insert_with(|| Projector::new(sample.metric(faces)));
        let costs = self.none.costs(projector, faces, &[form]);
        costs.cost(&[gap]) <= self.explained
    }
}

/// Every side of every contact present in the input and in each variation that keeps both
/// parts (`skipped[v]` lists the parts variation `v` does without), a variation's gap
/// judged by `touching`; the input is exact, so there only a gap within the model's
/// tolerance counts.
pub fn common_contacts(
    model: &Model,
    variations: &[Vec<f64>],
    skipped: &[Vec<usize>],
    touching: &mut dyn Touching,
) -> Vec<ContactSide> {
    let x0 = model.slot_values();
    let exact = crate::tolerance::Tolerance::for_size(model.size()).epsilon;
    let boxes = boxes(model);
    let mut out = Vec::new();
    for a in 0..boxes.len() {
        let Some(ba) = &boxes[a] else { continue };
        for (b, bb) in boxes.iter().enumerate().skip(a + 1) {
            let Some(bb) = bb else { continue };
            let sides: Vec<(u8, Affine)> = (0..3u8)
                .flat_map(|k| {
                    let k_ = k as usize;
                    [(k, ba[k_].1.sub(&bb[k_].0)), (k, bb[k_].1.sub(&ba[k_].0))]
                })
                .collect();
            if !sides.iter().all(|(_, f)| f.eval(&x0) >= -exact) {
                continue;
            }
            let kept = variations
                .iter()
                .zip(skipped)
                .enumerate()
                .filter(|(_, (_, skip))| !skip.contains(&a) && !skip.contains(&b))
                .all(|(v, (x, _))| {
                    sides.iter().all(|(_, f)| {
                        let gap = f.eval(x);
                        gap >= 0.0 || touching.touches(v, f, gap)
                    })
                });
            if kept {
                out.extend(sides.into_iter().filter(|(_, f)| !f.is_constant()).map(
                    |(axis, form)| ContactSide {
                        parts: [a, b],
                        axis,
                        form,
                    },
                ));
            }
        }
    }
    out
}

/// Each part's world box as affine forms (`None` for a part without one).
fn boxes(model: &Model) -> Vec<Option<[(Affine, Affine); 3]>> {
    model
        .parts
        .iter()
        .map(|p| {
            let iv = world_intervals(p)?;
            let f = |n: &crate::ir::Num| n.affine().cloned();
            Some([
                (f(&iv[0].0)?, f(&iv[0].1)?),
                (f(&iv[1].0)?, f(&iv[1].1)?),
                (f(&iv[2].0)?, f(&iv[2].1)?),
            ])
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::noise::INTENT_Z;

    /// How many contact sides survive a variation that shortens the leg (the first 30 of
    /// the source) by `gap`, judged by the noise model at σ = 1.
    fn sides_kept(source: &str, gap: f64) -> usize {
        sides_kept_under(source, gap, true, f64::INFINITY)
    }

    /// [`sides_kept`] where the noise is told (`σ = 1`) or not (`σ` at the floor), with
    /// the noise's `ceiling`.
    fn sides_kept_under(source: &str, gap: f64, told: bool, ceiling: f64) -> usize {
        let model = crate::front::test_model(source);
        let mut x1 = model.slot_values();
        let leg = x1.iter().position(|&v| v == 30.0).unwrap_or(0);
        x1[leg] -= gap;
        let faces = Faces::of(&model);
        let samples = [Sample::new(x1.clone(), Vec::new())];
        let noise = NoiseModel {
            sigma: if told { 1.0 } else { 1e-9 },
            floor: 1e-9,
            pooled: usize::from(told),
            critical_z: INTENT_Z,
            told,
        };
        let mut gaps = NoiseGaps::new(&faces, &samples, &noise, ceiling);
        common_contacts(&model, &[x1], &[Vec::new()], &mut gaps).len()
    }

    /// Where no relation tells the noise, it may be anything up to the ceiling: a top
    /// lifted off its leg by less than the ceiling still rests on it, one lifted further
    /// does not, and a told noise keeps its own test whatever the ceiling.
    #[test]
    fn an_untold_noise_keeps_the_contacts_any_noise_under_the_ceiling_explains() {
        let flat = "cube([10, 10, 30]);\ntranslate([1, 1, 30]) cube([40, 40, 2]);\n";
        assert!(sides_kept_under(flat, 3.0, false, 10.0) > 0);
        assert_eq!(sides_kept_under(flat, 30.0, false, 10.0), 0);
        assert_eq!(sides_kept_under(flat, 8.0, true, 100.0), 0);
    }

    /// A top resting on a leg, placed by one number or by three nested frames. Closing a
    /// gap spreads over every number the side has, so the nested top's noise explains a
    /// wider gap (√4·zσ ≈ 6.2 against √2·zσ ≈ 4.4): at 3 both touch, at 5 only the nested
    /// one, at 8 neither.
    #[test]
    fn a_side_of_more_noisy_numbers_may_open_further() {
        let flat = "cube([10, 10, 30]);\ntranslate([1, 1, 30]) cube([40, 40, 2]);\n";
        let nested = "cube([10, 10, 30]);\ntranslate([1, 1, 10]) translate([0, 0, 12]) \
                      translate([0, 0, 8]) cube([40, 40, 2]);\n";
        for (gap, flat_kept, nested_kept) in
            [(3.0, true, true), (5.0, false, true), (8.0, false, false)]
        {
            assert_eq!(sides_kept(flat, gap) > 0, flat_kept, "flat top, gap {gap}");
            assert_eq!(
                sides_kept(nested, gap) > 0,
                nested_kept,
                "nested top, gap {gap}"
            );
        }
    }
}
