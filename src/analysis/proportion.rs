//! Proportional sizes: an extent twice another (a hole half its block, a block stacked on
//! one twice its size, a cone's top half its base).
//!
//! Not one of the paper's kinds, so not in its base constraint count. A designer who typed
//! `87.5` beside `175` meant "half" as often as one who typed `175` twice meant "the same";
//! where the program says so itself (`w / 2`) the two forms are proportional already and
//! no candidate is needed. A relation `a = k·b` is one row `a − k·b`, exact and affine like
//! every other. Only halves: with thirds and quarters too, on seeds 200..400 (1% noise)
//! reach fell from 82 to 77% for half a point of dimension — a quarter of a thin board
//! under noise as large is within the noise of anything four times it, so accidental
//! ratios multiply and the variations cannot tell them.
//!
//! Invariants: `a` is the larger feature (`a = factor · b`), `factor ∈ RATIOS`, both are
//! extents of positive value, and the row is not constant (forms already proportional
//! constrain nothing). Like a large run of equal features, a feature with more partners
//! than [`RUN_NEIGHBOURS`] at one ratio is paired with the nearest in the variations (or
//! the first, without variations); the rest are counted as unlisted.

use super::candidates::{AffineFeature, Candidate, RUN_NEIGHBOURS, RelationKind};
use crate::ir::FeatureKind;
use crate::tolerance::Tolerance;

/// The ratios a size may be of another: half (see the module doc).
pub const RATIOS: [f64; 1] = [2.0];

/// Every proportional pair of extents that holds on the input, and how many holding
/// pairs were left out (see the module doc).
pub fn proportion_candidates(
    features: &[AffineFeature],
    class_sizes: &[usize],
    tol: &Tolerance,
    variations: &[Vec<f64>],
) -> (Vec<Candidate>, usize) {
    let mut extents: Vec<usize> = (0..features.len())
        .filter(|&i| matches!(features[i].kind, FeatureKind::Extent { .. }))
        .filter(|&i| features[i].values[0] > tol.epsilon)
        .collect();
    extents.sort_by(|&x, &y| features[x].values[0].total_cmp(&features[y].values[0]));
    let value = |i: usize| features[i].values[0];
    let mut out = Vec::new();
    let mut unlisted = 0;
    for &small in &extents {
        for factor in RATIOS {
            let target = factor * value(small);
            let from = extents.partition_point(|&x| value(x) < target - tol.epsilon);
            let to = extents.partition_point(|&x| value(x) <= target + tol.epsilon);
            let mut partners: Vec<(f64, usize, Candidate)> = extents[from..to]
                .iter()
                .filter_map(|&large| {
                    let row =
                        features[large].forms[0].add_scaled(&features[small].forms[0], -factor);
                    (!row.is_constant()).then(|| {
                        let spread = spread(&row, variations);
                        let candidate = Candidate {
                            kind: RelationKind::Proportional,
                            a: large,
                            b: small,
                            rows: vec![row],
                            multiplicity: class_sizes[large] * class_sizes[small],
                            more: Vec::new(),
                            factor,
                        };
                        (spread, large, candidate)
                    })
                })
                .collect();
            partners.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
            for (rank, (_, _, c)) in partners.into_iter().enumerate() {
                if rank < RUN_NEIGHBOURS {
                    out.push(c);
                } else {
                    unlisted += c.multiplicity;
                }
            }
        }
    }
    (out, unlisted)
}

/// How far the variations move a row from zero (0 without variations): partners that
/// stay proportional in every variation come first.
fn spread(row: &crate::ir::Affine, variations: &[Vec<f64>]) -> f64 {
    variations.iter().map(|v| row.eval(v).abs()).sum()
}

#[cfg(test)]
mod tests {
    use crate::analysis::{RelationKind, find_candidates};
    use crate::front::test_model as model;

    fn proportional(text: &str) -> Vec<(String, String, f64)> {
        let c = find_candidates(&model(text));
        c.list
            .iter()
            .filter(|x| x.kind == RelationKind::Proportional)
            .map(|x| {
                let label = |i: usize| c.features[i].label.clone();
                (label(x.a), label(x.b), x.factor)
            })
            .collect()
    }

    #[test]
    fn a_typed_half_is_a_candidate_and_a_written_half_needs_none() {
        let typed = proportional("cube([40, 30, 7]);\ntranslate([50, 0, 0]) cube([20, 11, 9]);\n");
        assert_eq!(typed.len(), 1, "{typed:?}");
        assert_eq!(typed[0].2, 2.0);
        let written = proportional(
            "w = 40;\ncube([w, 30, 7]);\ntranslate([50, 0, 0]) cube([w / 2, 11, 9]);\n",
        );
        assert!(written.is_empty(), "{written:?}");
    }

    #[test]
    fn only_halves_within_the_tolerance_are_candidates() {
        // 36 = 2·18 is; 12 = 4·3 (a quarter), 36 = 3·12 (a third) and 7 ≈ 2·3.49 (off by
        // more than the tolerance) are not.
        let found =
            proportional("cube([36, 12, 7]);\ntranslate([50, 0, 0]) cube([18, 3, 3.49]);\n");
        assert_eq!(found.len(), 1, "{found:?}");
        assert_eq!(
            (found[0].0.as_str(), found[0].1.as_str()),
            ("part1.width", "part2.width")
        );
    }
}
