//! The model's similarity between two settings of its slots: the IoU of exact volumes.
//!
//! [`VolumeSimilarity`] is the [`Similarity`] discovery and the optional-part test use: it
//! makes a setting into `geom`'s prepared geometry once ([`VolumeReference`]) and then
//! integrates only around the parts a change touches. Invariant: a reference made without
//! some parts compares only settings without the same parts; a setting whose parts do not
//! all evaluate (a number not affine in the slots) has similarity 0.

use super::discover::Similarity;
use crate::geom::{Edit, Prepared};
use crate::ir::{CsgNode, Model};

/// The model's IoU between two settings of its slots, by exact ray-interval volumes.
pub struct VolumeSimilarity<'m> {
    model: &'m Model,
    /// For each slot, the parts whose geometry depends on it.
    slot_parts: Vec<Vec<usize>>,
    /// Each part's own volume in the input.
    part_volumes: Vec<f64>,
}

impl<'m> VolumeSimilarity<'m> {
    pub fn new(model: &'m Model) -> VolumeSimilarity<'m> {
        let part_volumes = model
            .parts_at(&model.slot_values())
            .unwrap_or_default()
            .into_iter()
            .map(|p| crate::geom::volume(&[p], &CsgNode::Part(0)))
            .collect();
        VolumeSimilarity {
            model,
            slot_parts: model.parts_by_slot(),
            part_volumes,
        }
    }

    /// A changed volume relative to `part`'s own volume in the input.
    fn relative(&self, part: usize, changed: f64) -> f64 {
        let own = self.part_volumes.get(part).copied().unwrap_or(0.0);
        if changed <= 0.0 {
            0.0
        } else if own > 0.0 {
            changed / own
        } else {
            f64::INFINITY
        }
    }

    /// The parts (outside `skip`) that depend on a `changed` slot, at `a`; `None` when one
    /// does not evaluate.
    fn edits(&self, a: &[f64], changed: &[u32], skip: &[usize]) -> Option<Vec<Edit>> {
        let mut touched: Vec<usize> = changed
            .iter()
            .flat_map(|&s| self.slot_parts[s as usize].iter().copied())
            .filter(|p| !skip.contains(p))
            .collect();
        touched.sort_unstable();
        touched.dedup();
        touched
            .into_iter()
            .map(|p| Some((p, Some(self.model.parts[p].at(a)?))))
            .collect()
    }
}

/// A setting of the model made into geometry once, with its volume.
pub struct VolumeReference {
    solid: Prepared,
    skip: Vec<usize>,
}

impl Similarity for VolumeSimilarity<'_> {
    type Reference = VolumeReference;

    fn reference(&self, b: &[f64], skip: &[usize]) -> VolumeReference {
        let parts = self.model.parts_at(b).unwrap_or_default();
        let csg = self
            .model
            .csg
            .without(skip)
            .unwrap_or(CsgNode::Union(Vec::new()));
        VolumeReference {
            solid: Prepared::new(parts, csg),
            skip: skip.to_vec(),
        }
    }

    /// IoU, integrating only around the parts that differ from the reference.
    fn similarity_to(&self, a: &[f64], r: &VolumeReference) -> f64 {
        match self.model.parts_at(a) {
            Some(parts) if parts.len() == r.solid.parts().len() => {
                let edits: Vec<Edit> = parts.into_iter().map(Some).enumerate().collect();
                r.solid.iou_edited(&edits)
            }
            _ => 0.0,
        }
    }

    /// IoU, evaluating only the parts that depend on a changed slot.
    fn similarity_changed(&self, a: &[f64], changed: &[u32], r: &VolumeReference) -> f64 {
        if r.solid.parts().len() != self.model.parts.len() {
            return 0.0;
        }
        match self.edits(a, changed, &r.skip) {
            Some(edits) => r.solid.iou_edited(&edits),
            None => 0.0,
        }
    }

    fn update_reference(&self, r: &mut VolumeReference, a: &[f64], changed: &[u32]) {
        match self.edits(a, changed, &r.skip) {
            Some(edits) if r.solid.parts().len() == self.model.parts.len() => r.solid.apply(&edits),
            _ => *r = self.reference(a, &r.skip.clone()),
        }
    }

    fn removal_loss(&self, r: &VolumeReference, part: usize) -> f64 {
        self.relative(part, r.solid.changed_volume(&[(part, None)]))
    }

    fn removal_loss_lower_bound(&self, r: &VolumeReference, part: usize) -> f64 {
        self.relative(part, r.solid.removal_lower_bound(part))
    }
}
