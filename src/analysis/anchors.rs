//! Anchors: where a re-parameterized model is pinned, and variations read in its frame.
//!
//! A model's sliders say nothing about where it stands, so anchor rows pin it: the centre
//! of its extreme faces in x and y and its floor in z ([`Anchors::rows`]), on each axis along
//! which some slot change translates the whole model ([`translations`]). A variation
//! is projected keeping its own place (anchors at its own centre and floor), then moved
//! rigidly so its anchors are where the input has them ([`Anchors::moved_to_input`]):
//! sliders are read in the input's frame. [`Anchors`] holds all of it with the gauge,
//! worked out once per model. Invariant: an axis is pinned or moved only when some slot
//! change translates every face alike along it (to the tolerance), so an anchor never pins
//! a size.

use super::contacts::ContactSide;
use super::linalg::least_norm_solve;
use super::project::{Faces, project_onto};
use crate::ir::feature::world_intervals;
use crate::ir::{Affine, Model, SlotId};
use crate::tolerance::RELATIVE_EPSILON;

/// What pins a model in place, worked out once per model: none of it depends on a
/// variation, so discovery, the solve, the projections and the scores share one value.
#[derive(Debug, Clone)]
pub struct Anchors {
    /// Each axis's anchor form: the centre of the input's extreme faces in x and y, the
    /// lowest face in z (`None` where those faces are not affine).
    pub forms: [Option<Affine>; 3],
    /// Each axis's unit translation in slot space (see [`translations`]).
    pub translations: [Option<Vec<f64>>; 3],
    /// The gauge rows (`gauge::gauge_rows`): slots held at the input.
    pub gauge: Vec<Affine>,
    /// The model's slot values at the input.
    pub input: Vec<f64>,
}

impl Anchors {
    /// The anchors of `model`: its gauge, anchor forms and translations.
    pub fn of(model: &Model) -> Anchors {
        let gauge = super::gauge::gauge_rows(model);
        Anchors {
            forms: anchor_forms(model),
            translations: translations(model, &gauge),
            gauge,
            input: model.slot_values(),
        }
    }

    /// Rows that pin the model in place: its centre in x and y and its floor in z, at the
    /// input, on each axis along which some slot change moves the whole model. The faces
    /// used are the input's extremes.
    pub fn rows(&self) -> Vec<Affine> {
        self.rows_at(&self.input)
    }

    /// The anchor rows with their constants taken at `at` instead of the input: the same
    /// faces, held where `at` has them (a variation keeps its own place while projected).
    ///
    /// An axis gets a row only when the model can translate along it (see [`translations`]):
    /// where no slot change moves every face alike, the model's place on that axis is
    /// already fixed by its shape, and pinning its centre would pin a size instead.
    pub fn rows_at(&self, at: &[f64]) -> Vec<Affine> {
        self.forms
            .iter()
            .zip(&self.translations)
            .filter(|(_, t)| t.is_some())
            .filter_map(|(f, _)| f.as_ref())
            .map(|f| f.sub(&Affine::constant(f.eval(at))))
            .collect()
    }

    /// `x` moved rigidly (in slot space) so the model's anchors — centre in x and y, floor
    /// in z — are where the input has them, along each axis the model can translate on: the
    /// smallest slot change that shifts every face by the same amount along its axis.
    /// Sliders are read in the input's frame.
    pub fn moved_to_input(&self, x: &[f64]) -> Vec<f64> {
        let mut out = x.to_vec();
        for (form, step) in self.forms.iter().zip(&self.translations) {
            if let (Some(f), Some(step)) = (form, step) {
                let shift = f.eval(&self.input) - f.eval(x);
                out.iter_mut().zip(step).for_each(|(o, d)| *o += shift * d);
            }
        }
        out
    }
}

/// Each axis's anchor form: the centre of the input's extreme faces in x and y, the lowest
/// face in z (`None` where those faces are not affine).
fn anchor_forms(model: &Model) -> [Option<Affine>; 3] {
    let values = model.slot_values();
    let mut lo: [Option<(f64, Affine)>; 3] = Default::default();
    let mut hi: [Option<(f64, Affine)>; 3] = Default::default();
    for p in model.parts.iter().filter(|p| p.misaligned.is_none()) {
        let Some(iv) = world_intervals(p) else {
            continue;
        };
        for a in 0..3 {
            if let (Some(l), Some(h)) = (iv[a].0.affine(), iv[a].1.affine()) {
                let (lv, hv) = (l.eval(&values), h.eval(&values));
                if lo[a].as_ref().is_none_or(|(v, _)| lv < *v) {
                    lo[a] = Some((lv, l.clone()));
                }
                if hi[a].as_ref().is_none_or(|(v, _)| hv > *v) {
                    hi[a] = Some((hv, h.clone()));
                }
            }
        }
    }
    std::array::from_fn(|a| match (&lo[a], &hi[a]) {
        (Some((_, l)), Some((_, h))) if a < 2 => Some(l.add(h).scale(0.5)),
        (Some((_, l)), _) if a == 2 => Some(l.clone()),
        _ => None,
    })
}

/// For each axis, the smallest slot change that moves every face along that axis by one
/// unit and no face along the others (`None`: the model cannot translate that way; a face
/// no slot moves, or faces tied to sizes, prevent it). Slots the `gauge` holds stay held.
pub fn translations(model: &Model, gauge: &[Affine]) -> [Option<Vec<f64>>; 3] {
    let mut faces: Vec<(usize, &Affine)> = Vec::new();
    let mut fixed = [false; 3];
    let intervals: Vec<_> = model
        .parts
        .iter()
        .filter(|p| p.misaligned.is_none())
        .filter_map(world_intervals)
        .collect();
    for iv in &intervals {
        for (a, (lo, hi)) in iv.iter().enumerate() {
            for n in [lo, hi] {
                match n.affine() {
                    Some(f) => faces.push((a, f)),
                    None => fixed[a] = true,
                }
            }
        }
    }
    let tolerance = RELATIVE_EPSILON * model.size().max(1.0);
    std::array::from_fn(|axis| {
        if fixed[axis] {
            return None;
        }
        // Slots the gauge holds stay held: a translation never needs them.
        let rows: Vec<(Vec<(SlotId, f64)>, f64)> = faces
            .iter()
            .map(|(a, f)| (f.terms.clone(), if *a == axis { 1.0 } else { 0.0 }))
            .chain(gauge.iter().map(|g| (g.terms.clone(), 0.0)))
            .collect();
        let (delta, residual) = least_norm_solve(&rows, model.slots.len());
        (residual <= tolerance).then_some(delta)
    })
}

/// Each variation (slot values, with the parts it does without) projected onto `rows` and
/// its own anchors, then moved into the input's frame. Rigid moves are not what the sliders
/// express, and the free sizes do not depend on them.
pub fn project_variations(
    anchors: &Anchors,
    faces: &Faces,
    rows: &[Affine],
    values: &[Vec<f64>],
    optional: &[Vec<usize>],
) -> Vec<Vec<f64>> {
    let keeping = Keeping {
        contacts: &[],
        floors: &[],
        tolerance: 0.0,
    };
    project_variations_keeping(anchors, faces, rows, values, optional, &keeping)
}

/// What a projection keeps besides the rows: forms that must stay at or above a bound.
pub struct Keeping<'a> {
    /// Contact sides the variations keep within their noise.
    pub contacts: &'a [ContactSide],
    /// Sizes less their floor (`ranges::size_floors`): each must stay `≥ 0`.
    pub floors: &'a [Affine],
    /// How far a side may be broken before it is held.
    pub tolerance: f64,
}

/// As [`project_variations`], and each projection keeps the `keeping.contacts`: a contact
/// the variations keep within their noise is a constraint like the rows, and a gap the noise
/// left in a variation is noise, not a preset to reproduce (a preset with a gap widens the
/// sliders' box to settings that part the two). A part a variation does without keeps its
/// contacts too: nobody saw its numbers there, and the preset's values for it are where
/// its switch puts it back (the ranges hold them, so a gap there would part it from the
/// rest at settings inside them). Every size stays above its floor (`keeping.floors`) the
/// same way: a preset is a point the sliders can stand on, and a fit that squashed a part
/// flat (a leg hidden behind a panel) must not leave it at a negative size, which the
/// ranges would clamp away by moving other sliders. A side the projection breaks by more
/// than `keeping.tolerance` is made to hold at its bound (touching, or the input's own
/// gap; the floor), the most broken first, and the variation projected again until none
/// is broken: a point that keeps every side, near the nearest one (an active set that only
/// grows; a side that cannot hold with the rows is left broken).
pub fn project_variations_keeping(
    anchors: &Anchors,
    faces: &Faces,
    rows: &[Affine],
    values: &[Vec<f64>],
    optional: &[Vec<usize>],
    keeping: &Keeping,
) -> Vec<Vec<f64>> {
    // Each side less its bound (`form − bound ≥ 0` keeps it; `= 0` holds it there).
    let at_bound: Vec<Affine> = keeping
        .contacts
        .iter()
        .map(|c| {
            let bound = c.form.eval(&anchors.input).min(0.0);
            c.form.add(&Affine::constant(-bound))
        })
        .chain(keeping.floors.iter().cloned())
        .collect();
    values
        .iter()
        .zip(optional)
        .map(|(v, o)| {
            let own = anchors.rows_at(v);
            let mut held: Vec<usize> = Vec::new();
            loop {
                let all_rows: Vec<&Affine> = rows
                    .iter()
                    .chain(&anchors.gauge)
                    .chain(&own)
                    .chain(held.iter().map(|&k| &at_bound[k]))
                    .collect();
                let p = project_onto(faces, v, &all_rows, o);
                let worst = (0..at_bound.len())
                    .filter(|k| !held.contains(k))
                    .map(|k| (k, -at_bound[k].eval(&p)))
                    .filter(|&(_, deficit)| deficit > keeping.tolerance)
                    .max_by(|a, b| a.1.total_cmp(&b.1));
                match worst {
                    Some((k, _)) => held.push(k),
                    None => return anchors.moved_to_input(&p),
                }
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::contacts::{Slack, common_contacts};
    use crate::ir::feature::world_intervals;

    /// A top resting on a leg, no relation kept between them, and a variation whose noise
    /// left a 2-unit gap where the two meet (within the 3 units its noise explains). The
    /// contact is the variations'; the preset keeps it, where the plain projection keeps
    /// the gap, and keeps it in a variation without the top too.
    #[test]
    fn a_preset_closes_the_gap_noise_left_in_a_contact() {
        let model = crate::front::test_model(
            "cube([10, 10, 50]);\ntranslate([0, 0, 50]) cube([40, 40, 2]);\n",
        );
        let x0 = model.slot_values();
        // Leg and top 10 higher, the leg (the first 50) 2 short of the top.
        let mut noisy: Vec<f64> = x0
            .iter()
            .map(|&v| if v == 50.0 { v + 10.0 } else { v })
            .collect();
        let leg_height = x0.iter().position(|&v| v == 50.0).unwrap();
        noisy[leg_height] -= 2.0;
        let anchors = Anchors::of(&model);
        let faces = Faces::of(&model);
        let contacts = common_contacts(
            &model,
            std::slice::from_ref(&noisy),
            &[vec![]],
            &mut Slack(3.0),
        );
        assert!(
            !contacts.is_empty(),
            "the contact is seen through the noise"
        );
        let gap = |p: &[f64]| {
            contacts
                .iter()
                .map(|c| c.form.eval(p))
                .fold(f64::MAX, f64::min)
        };
        let optional = [vec![]];
        let values = std::slice::from_ref(&noisy);
        let plain = project_variations(&anchors, &faces, &[], values, &optional);
        let keeping = Keeping {
            contacts: &contacts,
            floors: &[],
            tolerance: 1e-9,
        };
        let kept = project_variations_keeping(&anchors, &faces, &[], values, &optional, &keeping);
        assert!(
            gap(&plain[0]) < -1.0,
            "plain projection: {}",
            gap(&plain[0])
        );
        assert!(gap(&kept[0]) > -1e-6, "kept: {}", gap(&kept[0]));
        // A variation without the top: its numbers there are where its switch puts it back.
        let without_top = [vec![1]];
        let kept =
            project_variations_keeping(&anchors, &faces, &[], values, &without_top, &keeping);
        assert!(gap(&kept[0]) > -1e-6, "without the top: {}", gap(&kept[0]));
    }

    /// A top over two short thin legs and a panel between them, kept flush: the legs and
    /// the panel add up to the top. A variation narrowed the top by 40 and left the rest:
    /// the legs' faces are the smallest, so the plain projection takes the 40 from them and
    /// leaves them at negative widths; kept above their floor, the top and the panel give.
    #[test]
    fn a_preset_keeps_every_size_above_its_floor() {
        let model = crate::front::test_model(
            "translate([0, 0, 50]) cube([100, 20, 10]);\n\
             cube([10, 2, 5]);\n\
             translate([90, 0, 0]) cube([10, 2, 5]);\n\
             translate([10, 0, 0]) cube([80, 20, 50]);\n",
        );
        let x_faces = |p: usize| {
            let [(lo, hi), _, _] = world_intervals(&model.parts[p]).unwrap();
            (lo.affine().unwrap().clone(), hi.affine().unwrap().clone())
        };
        let [top, left, right, panel] = [0, 1, 2, 3].map(x_faces);
        let rows = vec![
            left.0.sub(&top.0),
            right.1.sub(&top.1),
            panel.0.sub(&left.1),
            panel.1.sub(&right.0),
        ];
        let top_width = top.1.sub(&top.0);
        let mut narrow = model.slot_values();
        let slot = top_width.terms[0].0 as usize;
        narrow[slot] -= 40.0;
        let anchors = Anchors::of(&model);
        let faces = Faces::of(&model);
        let values = std::slice::from_ref(&narrow);
        let optional = [vec![]];
        let leg_width = |x: &[f64]| {
            left.1
                .sub(&left.0)
                .eval(x)
                .min(right.1.sub(&right.0).eval(x))
        };
        let plain = project_variations(&anchors, &faces, &rows, values, &optional);
        assert!(
            leg_width(&plain[0]) < 0.0,
            "plain: {}",
            leg_width(&plain[0])
        );
        let floors = crate::analysis::ranges::size_floors(&model);
        let keeping = Keeping {
            contacts: &[],
            floors: &floors,
            tolerance: 1e-9,
        };
        let kept = project_variations_keeping(&anchors, &faces, &rows, values, &optional, &keeping);
        for f in &floors {
            assert!(f.eval(&kept[0]) > -1e-6, "a size under its floor: {kept:?}");
        }
        for r in &rows {
            assert!(r.eval(&kept[0]).abs() < 1e-6, "a row broken: {kept:?}");
        }
    }
}
