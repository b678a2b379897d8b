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
//! Invariant: every form returned is at least `−slack` at the input (it is a contact there).

use crate::ir::feature::world_intervals;
use crate::ir::{Affine, Model};

/// One side of a contact: `form ≥ 0` keeps it.
#[derive(Debug, Clone)]
pub struct ContactSide {
    pub parts: [usize; 2],
    pub axis: u8,
    pub form: Affine,
}

/// Every side of every contact present in the input and in each variation that keeps both
/// parts (`skipped[v]` lists the parts variation `v` does without). In a variation a gap up
/// to `slack` (world units, what its noise explains) counts as touching; the input is
/// exact, so there only a gap within the model's tolerance does.
pub fn common_contacts(
    model: &Model,
    variations: &[Vec<f64>],
    skipped: &[Vec<usize>],
    slack: f64,
) -> Vec<ContactSide> {
    let x0 = model.slot_values();
    let exact = crate::tolerance::Tolerance::for_size(model.size()).epsilon;
    let boxes: Vec<Option<[(Affine, Affine); 3]>> = model
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
        .collect();
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
            let meets = |x: &[f64], gap: f64| sides.iter().all(|(_, f)| f.eval(x) >= -gap);
            let kept = meets(&x0, exact)
                && variations
                    .iter()
                    .zip(skipped)
                    .filter(|(_, skip)| !skip.contains(&a) && !skip.contains(&b))
                    .all(|(v, _)| meets(v, slack));
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
