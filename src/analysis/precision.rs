//! How much each face of a fitted variation counts as evidence: the fit's uncertainty
//! carried into the noise model.
//!
//! The noise model (`noise`) says every face a variation keeps is displaced by Gaussian
//! noise of one `σ`, estimated from all the variations. A variation fitted to pictures
//! knows better: a face seen edge-on in every view is pinned to a fraction of a pixel, a
//! leg the cameras barely show is loose, and a part no camera sees is not measured at all
//! (the fit leaves its numbers where they started, which is no evidence about them).
//!
//! Each face's standard deviation `u_f` comes from the variation's uncertainty (the
//! variance of the face's affine form, [`crate::variation::Uncertainty::variance`]); a part's
//! along an axis is its worse face's. The fit's deviations are trusted as relative
//! measures (its pixels are not independent, so their scale is not; see
//! `fit::uncertainty`): the variation's median face (the lower one of an even count) is the noise model's
//! typical face,
//! weight 1, and a face `k` times looser weighs `1/k²` — its displacement counts as `k`
//! times the noise. Faces better determined than the median weigh 1, never more, so one
//! sharp face cannot outvote the noise estimate. A face the pictures do not determine
//! weighs 0: one whose deviation is infinite, or above the noise model's ceiling
//! (`tolerance::NOISE_MAX_SHARE` of the model's size, farther than variations of one design
//! are apart), where the pictures cannot tell its place among the designs. A part none of
//! whose faces is determined is *unseen*: relations on it get no evidence, and no degrees
//! of freedom, from that variation.

use super::project::Faces;
use crate::tolerance::noise_ceiling;
use crate::variation::Uncertainty;

/// What a fitted variation's uncertainty makes of its faces.
#[derive(Debug, Clone, PartialEq)]
pub struct Precision {
    /// Per entry of the faces' parts, per axis: the weight of its faces, in `[0, 1]`.
    pub weights: Vec<[f64; 3]>,
    /// The model's parts none of whose faces the variation determines.
    pub unseen: Vec<usize>,
}

impl Precision {
    /// The weights of `faces` under the uncertainty `u`, for a model of size `size`.
    pub fn of(faces: &Faces, u: &Uncertainty, size: f64) -> Precision {
        let ceiling = noise_ceiling(size);
        let n = faces.entries();
        let mut worst = vec![[0.0f64; 3]; n];
        let mut part_of = vec![0usize; n];
        for (k, part, axis, form) in faces.face_forms() {
            let terms: Vec<(usize, f64)> =
                form.terms.iter().map(|&(s, c)| (s as usize, c)).collect();
            let sd = u.variance(&terms).max(0.0).sqrt();
            let sd = if sd > ceiling { f64::INFINITY } else { sd };
            worst[k][axis] = worst[k][axis].max(sd);
            part_of[k] = part;
        }
        let mut finite: Vec<f64> = worst
            .iter()
            .flatten()
            .copied()
            .filter(|v| v.is_finite())
            .collect();
        finite.sort_by(f64::total_cmp);
        let reference = finite
            .get(finite.len().saturating_sub(1) / 2)
            .copied()
            .unwrap_or(0.0);
        let weights: Vec<[f64; 3]> = worst
            .iter()
            .map(|w| w.map(|sd| weight(sd, reference)))
            .collect();
        let unseen = weights
            .iter()
            .zip(&part_of)
            .filter(|(w, _)| w.iter().all(|v| *v == 0.0))
            .map(|(_, p)| *p)
            .collect();
        Precision { weights, unseen }
    }
}

/// The weight of a face of standard deviation `sd` against the typical face's `reference`.
fn weight(sd: f64, reference: f64) -> f64 {
    if !sd.is_finite() {
        0.0
    } else if sd <= reference {
        1.0
    } else {
        (reference / sd).powi(2)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::DMatrix;

    #[test]
    fn a_part_the_pictures_do_not_show_is_unseen_and_a_loose_one_weighs_less() {
        // Three boxes; the fit reports on the first two boxes' numbers only, the second's
        // size three times looser than the rest.
        let m = crate::front::test_model(
            "cube([10, 10, 10]);\n\
             translate([20, 0, 0]) cube([10, 10, 10]);\n\
             translate([40, 0, 0]) cube([10, 10, 10]);\n",
        );
        let faces = Faces::of(&m);
        let listed: Vec<(usize, String, f64)> = (0..9)
            .map(|s| (s, m.slots[s].name.clone(), m.slots[s].value))
            .collect();
        let mut info = DMatrix::identity(9, 9) * 100.0;
        for s in 6..9 {
            info[(s, s)] = 100.0 / 9.0;
        }
        let u = Uncertainty::new(m.slots.len(), &listed, info);
        let p = Precision::of(&faces, &u, m.size());
        assert_eq!(p.unseen, vec![2]);
        assert_eq!(p.weights[0], [1.0; 3]);
        assert!(
            p.weights[1].iter().all(|w| *w > 0.0 && *w < 1.0),
            "{:?}",
            p.weights[1]
        );
        assert_eq!(p.weights[2], [0.0; 3]);
    }
}
